#!/usr/bin/env python3
"""Module READMEs and the processes' options cannot drift apart (issue 12).

Each README shows its process's options, as `<process> --print-options-table` prints them,
between two markers:

    <!-- options-table: ladar_driver -->
    | key | unit | default | meaning |
    ...
    <!-- /options-table -->

Usage:
    readme_options_check.py PROCESS_BINARY README [PROCESS_BINARY README ...]
    readme_options_check.py --update PROCESS_BINARY README [...]   (rewrites the tables)

The check fails unless, for every pair, the README has the block for the process, the block
has a row for every key the process declares, and no row for a key it does not (a key that
was renamed or removed). Exit 0 when all pairs pass, 1 otherwise (one line per problem).
"""

import os
import re
import subprocess
import sys

ROW_KEY = re.compile(r"^\| `([^`]+)` \|")


def options_table(binary):
    out = subprocess.run([binary, "--print-options-table"], check=True, capture_output=True, text=True)
    return out.stdout


def keys_of(table_text):
    return [m.group(1) for line in table_text.splitlines() if (m := ROW_KEY.match(line))]


def markers(process):
    return f"<!-- options-table: {process} -->", "<!-- /options-table -->"


def find_block(readme_text, process):
    """(start, end) of the text between the markers, or None."""
    begin, end = markers(process)
    b = readme_text.find(begin)
    if b < 0:
        return None
    start = b + len(begin)
    e = readme_text.find(end, start)
    return None if e < 0 else (start, e)


def check(binary, readme):
    process = os.path.basename(binary)
    table = options_table(binary)
    text = open(readme, encoding="utf-8").read()
    block = find_block(text, process)
    regenerate = f"regenerate it: tests/readme_options_check.py --update {binary} {readme}"
    if block is None:
        begin, end = markers(process)
        return [f"{readme}: no '{begin}' ... '{end}' block with {process}'s options; {regenerate}"]
    in_readme = keys_of(text[block[0]:block[1]])
    declared = keys_of(table)
    missing = [k for k in declared if k not in in_readme]
    gone = [k for k in in_readme if k not in declared]
    problems = []
    if missing:
        problems.append(f"{readme}: no row for {len(missing)} of {process}'s options: {', '.join(missing)}; {regenerate}")
    if gone:
        problems.append(f"{readme}: rows for {', '.join(gone)}, which {process} does not have; {regenerate}")
    return problems


def update(binary, readme):
    process = os.path.basename(binary)
    text = open(readme, encoding="utf-8").read()
    block = find_block(text, process)
    if block is None:
        sys.exit(f"{readme}: add the markers {' and '.join(markers(process))} where the table goes")
    text = text[:block[0]] + "\n" + options_table(binary) + text[block[1]:]
    with open(readme, "w", encoding="utf-8") as f:
        f.write(text)


def main(argv):
    updating = bool(argv) and argv[0] == "--update"
    pairs = argv[1:] if updating else argv
    if not pairs or len(pairs) % 2:
        sys.exit(__doc__)
    problems = []
    for binary, readme in zip(pairs[0::2], pairs[1::2]):
        if updating:
            update(binary, readme)
        else:
            problems += check(binary, readme)
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
