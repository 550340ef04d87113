#!/usr/bin/env bash
# Opens the operator's view of the running demo (scripts/run_demo.sh) in a browser:
#
#   viewer/view_demo.sh [--port 8765] [--allow-commands] [--pid PID] [--build-dir DIR]
#
# The demo runs its fleet in a private network namespace; this starts viewer_bridge with its
# page on http://127.0.0.1:PORT/ here and its LCM socket in the demo's namespace (the
# namespace of PID, by default the newest vehicle_sim's; --net-namespace, needs root). Open
# the address in a browser (or Foxglove: ws://127.0.0.1:PORT). Ctrl-C ends the bridge, not the demo.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
port=8765 pid="" build="$root/build/release" extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --port) port="$2"; shift 2 ;;
    --pid) pid="$2"; shift 2 ;;
    --build-dir) build="$2"; shift 2 ;;
    --allow-commands) extra+=(--allow-commands); shift ;;
    -h|--help) awk 'NR > 1 && /^#/ { print; next } NR > 1 { exit }' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "view_demo.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
if [ -z "$pid" ]; then
  pid="$(pgrep -n -x vehicle_sim || true)"
  [ -n "$pid" ] || { echo "view_demo.sh: no vehicle_sim is running: start scripts/run_demo.sh first (or give --pid)" >&2; exit 2; }
fi
[ -x "$build/bin/viewer_bridge" ] || {
  source "$root/scripts/common.sh"
  minenav_install_deps
  minenav_build "$build" -DMINENAV_WERROR=ON -- viewer_bridge
}
# The demo's fleet signs its command channels: the bridge verifies what it shows of them and
# signs the operator's commands with the same key file, read from vehicle_sim's command line.
key_file="$(tr '\0' '\n' < "/proc/$pid/cmdline" | awk 'prev == "--auth.key-file" { print; exit } { prev = $0 }')"
[ -n "$key_file" ] && extra+=(--auth.key-file "$key_file")
echo "== the operator's view of the demo (pid $pid): http://127.0.0.1:$port/"
exec "$build/bin/viewer_bridge" --port "$port" --net-namespace "/proc/$pid/ns/net" \
  "${extra[@]}"
