#!/usr/bin/env python3
"""SIM_TRUTH closes no loop (DESIGN.md; issue 14): no process of the fleet subscribes the
simulator's ground truth except the ladar simulation (ladar_driver) and the evaluation tools.

Processes declare their subscriptions as channel options (ConfigSchema::AddChannel with
direction "subscribes" and the message type); `<process> --print-options-table` lists them as
rows `| key | subscribes TYPE | DEFAULT | meaning |`. The check fails for any other process
with a row that subscribes vehicle_truth_t, or that subscribes anything on the channel
SIM_TRUTH by default. It also fails when an allowed process that must read the truth
(ladar_driver) shows no such row: then the parsing is broken and the check would see nothing.

Usage: fleet_truth_check.py PROCESS_BINARY [PROCESS_BINARY ...]
Exit 0 when every process passes, 1 otherwise (one line per problem).
"""

import os
import re
import subprocess
import sys

ALLOWED = {"ladar_driver"}        # the ladar simulation ray-casts from the true pose
MUST_SUBSCRIBE = {"ladar_driver"}  # proves the rows are parsed
ROW = re.compile(r"^\| `([^`]+)` \| ([^|]*) \| `([^`]*)` \|")


def truth_subscriptions(binary):
    out = subprocess.run([binary, "--print-options-table"], check=True, capture_output=True, text=True).stdout
    rows = []
    for line in out.splitlines():
        m = ROW.match(line)
        if not m:
            continue
        key, unit, default = m.group(1), m.group(2).strip(), m.group(3)
        if unit.startswith("subscribes") and ("vehicle_truth_t" in unit or default == "SIM_TRUTH"):
            rows.append(f"{key} ({unit}, default {default})")
    return rows


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    problems = []
    for binary in argv[1:]:
        process = os.path.basename(binary)
        rows = truth_subscriptions(binary)
        if rows and process not in ALLOWED:
            problems.append(f"{process} subscribes the ground truth: {', '.join(rows)}")
        if not rows and process in MUST_SUBSCRIBE:
            problems.append(f"{process} shows no truth subscription: the check cannot see the rows")
        print(f"{process}: {', '.join(rows) if rows else 'no ground truth'}")
    for p in problems:
        print("FAIL: " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
