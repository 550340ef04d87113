#!/usr/bin/env bash
# Bandwidth and smoothness of the operator's view with the fleet running (issue 17): attaches
# viewer_bridge to the running demo (scripts/run_demo.sh, in its network namespace, as
# viewer/view_demo.sh does), keeps the page open in headless chromium for --duration seconds
# (bench/viewer_bench.mjs: frames/s, redraws/s, bytes/s received by the page), and compares
# the bytes the bridge sent on its socket (its /minenav/bridge counters, read at the end)
# with the bytes on the bus over the same time (log_tool spy --json in the demo's namespace).
#
#   bench/viewer_bench.sh [--build-dir DIR] [--duration S] [--pid PID] [--json-out FILE]
#                         [--screenshot FILE]
#
# Needs root (joins the demo's namespace). Prints a table; --json-out writes it as JSON.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build/release" duration=30 pid="" json_out="" screenshot=""
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build="$2"; shift 2 ;;
    --duration) duration="$2"; shift 2 ;;
    --pid) pid="$2"; shift 2 ;;
    --json-out) json_out="$2"; shift 2 ;;
    --screenshot) screenshot="$2"; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "viewer_bench: unknown option '$1'" >&2; exit 2 ;;
  esac
done
source "$root/scripts/common.sh"
minenav_npm_ci "$root/tests/js" >/dev/null
pid="${pid:-$(pgrep -n -x vehicle_sim || true)}"
[ -n "$pid" ] || { echo "viewer_bench: no vehicle_sim running: start scripts/run_demo.sh first" >&2; exit 2; }
work="$(mktemp -d)"
port=8799
bridge_pid=""
cleanup() { [ -n "$bridge_pid" ] && kill "$bridge_pid" 2>/dev/null; wait 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT
"$build/bin/viewer_bridge" --port $port --net-namespace "/proc/$pid/ns/net" 2> "$work/bridge.log" &
bridge_pid=$!
sleep 1
nsenter --net="/proc/$pid/ns/net" "$build/bin/log_tool" spy --json --duration $((duration + 3)) > "$work/bus.json" &
spy_pid=$!
node "$root/bench/viewer_bench.mjs" --url "http://127.0.0.1:$port/" --duration "$duration" \
  ${screenshot:+--screenshot "$screenshot"} > "$work/page.json"
wait $spy_pid
python3 - "$work/page.json" "$work/bus.json" "$duration" "$json_out" <<'PY'
import json, sys
page = json.load(open(sys.argv[1])); bus = json.load(open(sys.argv[2])); duration = float(sys.argv[3])
bus_s = duration + 3
bus_bytes = sum(c["bytes"] for c in bus["channels"]) / bus_s
bridge = (page.get("bridge") or {}).get("server") or {}
rows = [
  ("page frames/s (median, min)", f'{page["fps_median"]} / {page["fps_min"]}'),
  ("page redraws/s (median)", page["redraws_median"]),
  ("page received B/s (median, max)", f'{page["page_bytes_per_s_median"]} / {page["page_bytes_per_s_max"]}'),
  ("page messages/s (median)", page["messages_per_s_median"]),
  ("bus B/s (all channels, log_tool spy)", round(bus_bytes)),
  ("bridge socket B/s (bytes_sent over the connection)", round(bridge.get("bytes_sent", 0) / (duration + 3))),
  ("bridge socket: frames dropped", bridge.get("frames_dropped")),
  ("contours shown at the end", page["contours"]),
]
for k, v in rows: print(f"{k:40s} {v}")
for c in sorted(bus["channels"], key=lambda c: -c["bytes"])[:8]:
  print(f'  bus {c["channel"]:20s} {c["bytes"] / bus_s:10.0f} B/s {c["count"] / bus_s:6.1f} msg/s')
if sys.argv[4]:
  json.dump({"duration_s": duration, "page": page, "bus_bytes_per_s": bus_bytes,
             "bus_channels": [{k: c[k] for k in ("channel", "type", "count", "bytes")} for c in bus["channels"]]},
            open(sys.argv[4], "w"), indent=1)
PY
