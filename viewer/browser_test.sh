#!/usr/bin/env bash
# The operator's view in a real browser (issue 17), run by ctest (viewer.browser); it installs
# what it needs, then runs itself inside tests/bus/private_net.sh: the known log (viewer_test_log) played into viewer_bridge by lcm-logplayer,
# Debian's chromium driven by npm playwright-core (browser_test.mjs) loads the page, checks a
# screenshot against the true walls, follows the vehicle and presses Pause; the command must
# reach the bus (recorded by log_tool record, decoded by log_tool spy). Fails loudly when
# chromium or the npm packages cannot be had (it installs them first, as the project's scripts do).
#
#   viewer/browser_test.sh BIN_DIR WORK_DIR
set -euo pipefail
bin="$1"; work="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

# Outside the namespace (it has no network): install what is missing, then run inside it.
if [ -z "${MINENAV_IN_PRIVATE_NET:-}" ]; then
  source "$root/scripts/common.sh"
  minenav_install_missing chromium liblcm-bin python3
  minenav_npm_ci "$root/tests/js"
  [ -x /usr/bin/chromium ] || { echo "browser_test: FAILED: /usr/bin/chromium is missing" >&2; exit 1; }
  [ -d "$root/tests/js/node_modules/playwright-core" ] || { echo "browser_test: FAILED: npm playwright-core is missing" >&2; exit 1; }
  exec "$root/tests/bus/private_net.sh" --port "${MINENAV_BROWSER_TEST_PORT:-7850}" -- "$0" "$@"
fi

rm -rf "$work"; mkdir -p "$work"; cd "$work"
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT
bridges=()

"$here/testing/make_known_log.sh" "$bin"

port=8765
"$bin/viewer_bridge" --port $port --allow-commands --display.vehicle-width 1.2 --display.vehicle-length 2 \
  --display.max-scan-rate 10 --display.max-channel-rate 50 2> bridge.log &
pids+=($!); bridges+=($!)
"$bin/log_tool" record --out commands.lcm --channels COORDINATOR_COMMAND 2> record.log &
record_pid=$!
pids+=($record_pid)
for _ in $(seq 50); do
  (exec 3<>/dev/tcp/127.0.0.1/$port) 2>/dev/null && break
  sleep 0.1
done

# The same log read directly by a second bridge, with the time slider.
"$bin/viewer_bridge" --port $((port + 1)) --replay known.lcm --replay-speed 0.1 --display.vehicle-width 1.2 --display.vehicle-length 2 \
  --heartbeat-period 0 2> replay_bridge.log &
pids+=($!); bridges+=($!)
for _ in $(seq 50); do
  (exec 3<>/dev/tcp/127.0.0.1/$((port + 1))) 2>/dev/null && break
  sleep 0.1
done

node "$here/browser_test.mjs" --url "http://127.0.0.1:$port/" --world world.json --log known.lcm \
  --screenshot "$work/viewer.png" --replay-url "http://127.0.0.1:$((port + 1))/" --stations stations.csv

kill -TERM "$record_pid"; wait "$record_pid" || true
"$bin/log_tool" spy --log commands.lcm --json > commands.json
python3 - commands.json <<'PY'
import json, sys
spy = json.load(open(sys.argv[1]))
ch = {c["channel"]: c for c in spy["channels"]}
cmd = ch.get("COORDINATOR_COMMAND")
assert cmd and cmd["count"] == 1, f"expected one COORDINATOR_COMMAND on the bus, got {cmd}"
assert cmd["latest"]["command"] == 1 and cmd["latest"]["seq"] == 1, f"not PAUSE seq 1: {cmd['latest']}"
print("browser_test: PAUSE reached the bus:", json.dumps(cmd["latest"]))
PY
# The bridges end cleanly on SIGTERM (and, in the sanitizer build, without a report).
for p in "${bridges[@]}"; do kill -TERM "$p"; done
status=0
for p in "${bridges[@]}"; do wait "$p" || status=$?; done
if [ $status -ne 0 ] || grep -q "Sanitizer" bridge.log replay_bridge.log; then
  echo "browser_test: FAILED: a bridge did not end cleanly (exit $status):" >&2
  tail -20 bridge.log replay_bridge.log >&2
  exit 1
fi
echo "browser_test: passed"
