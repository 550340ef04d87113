#!/usr/bin/env bash
# A real dataset replayed live: log_tool import-carmen turns MIT CSAIL (1988 scans, 424 s)
# into an LCM log, ladar_driver --replay publishes it on the bus at 100x the recorded
# rate, log_tool record records the bus; every scan must arrive, unchanged, on time.
# Run inside tests/bus/private_net.sh (CTest does):
#   carmen_replay_test.sh LADAR_DRIVER LOG_TOOL DATASETS_DIR
set -euo pipefail
ladar_driver="$1" log_tool="$2" datasets="$3"
dir="$(mktemp -d)"
rec_pid=""
cleanup() {
  if [ -n "$rec_pid" ]; then kill "$rec_pid" 2>/dev/null || true; fi
  rm -rf "$dir"
}
trap cleanup EXIT
fail() { echo "carmen_replay_test: FAIL: $*" >&2; exit 1; }
[ -n "${LCM_DEFAULT_URL:-}" ] || fail "run me through tests/bus/private_net.sh --port N"
[ -x "$ladar_driver" ] || fail "$ladar_driver is not built"
[ -x "$log_tool" ] || fail "$log_tool is not built"
[ -f "$datasets/mit-csail.clf.bz2" ] || fail "$datasets/mit-csail.clf.bz2 is missing (MINENAV_DATASETS_DIR)"

echo "== import"
"$log_tool" import-carmen "$datasets/mit-csail.clf.bz2" "$dir/mit.lcm" 2>/dev/null >/dev/null

echo "== replay at 100x while recording"
"$log_tool" record --out "$dir/rec.lcm" --channels LADAR_SCAN --duration 60 2>/dev/null >/dev/null &
rec_pid=$!
sleep 0.7
start=$(date +%s.%N)
"$ladar_driver" --replay "$dir/mit.lcm" --replay-speed 100 --heartbeat-period 0 2>"$dir/driver.txt" ||
  fail "ladar_driver --replay failed: $(cat "$dir/driver.txt")"
end=$(date +%s.%N)
sleep 0.5
kill -INT "$rec_pid"
wait "$rec_pid" || fail "log_tool record failed"
rec_pid=""
grep -q "replayed 1988 scans" "$dir/driver.txt" || fail "driver said: $(cat "$dir/driver.txt")"
# 424 s of data at 100x: about 4.24 s of wall time (never faster than the recorded rate).
elapsed=$(python3 -c "print(f'{$end - $start:.2f}')")
python3 -c "import sys; sys.exit(0 if 4.0 <= $elapsed <= 12.0 else 1)" ||
  fail "replay took $elapsed s for 4.24 s of data at 100x"
echo "   replayed in $elapsed s (4.24 s expected)"

echo "== every scan arrived unchanged"
count=$("$log_tool" info --json "$dir/rec.lcm" | python3 -c '
import json, sys
s = json.load(sys.stdin)
c = [c for c in s["channels"] if c["channel"] == "LADAR_SCAN"]
print(c[0]["count"] if c else 0)')
[ "$count" -eq 1988 ] || fail "recorded $count of 1988 scans"
"$log_tool" export "$dir/mit.lcm" --scans-out "$dir/sent.csv" >/dev/null 2>&1
"$log_tool" export "$dir/rec.lcm" --scans-out "$dir/got.csv" >/dev/null 2>&1
cmp -s "$dir/sent.csv" "$dir/got.csv" || fail "recorded scans differ from the imported ones"
echo "   1988 scans, identical to the imported log"
echo "carmen_replay_test: all passed"
