#!/usr/bin/env bash
# Test of record.sh on a live bus. Run inside tests/bus/private_net.sh (CTest does):
#   record_test.sh VEHICLE_SIM LOG_TOOL
# vehicle_sim publishes SIM_TRUTH/ODOMETRY at 20 Hz; record.sh must log the selected
# channels completely, name logs by date, split, and refuse to overwrite or bad flags.
set -euo pipefail
vehicle_sim="$1" log_tool="$2"
here="$(cd "$(dirname "$0")" && pwd)"
record="$here/record.sh"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
fail() { echo "record_test: FAIL: $*" >&2; exit 1; }
[ -n "${LCM_DEFAULT_URL:-}" ] || fail "run me through tests/bus/private_net.sh --port N"
[ -x "$vehicle_sim" ] || fail "$vehicle_sim is not built"
[ -x "$log_tool" ] || fail "$log_tool is not built"

# Channel count, missing count and seq range of one channel from log_tool info --json.
channel_stats() {  # LOG CHANNEL -> "count missing first last" (or "none")
  "$log_tool" info --json "$1" | python3 -c '
import json, sys
s = json.load(sys.stdin)
for c in s["channels"]:
    if c["channel"] == sys.argv[1]:
        print(c["count"], c["missing"], c["first_sequence"], c["last_sequence"]); break
else:
    print("none")' "$2"
}

echo "== selected channels, named by date, nothing lost"
"$record" --dir "$dir/logs" --name run --channels 'SIM_TRUTH' --duration 3.5 --quiet >"$dir/out.txt" &
rec_pid=$!
sleep 0.7
"$vehicle_sim" --generate mine --run-for 2 --heartbeat-period 0 2>/dev/null
wait "$rec_pid"
log="$(cat "$dir/out.txt")"
[[ "$log" =~ ^$dir/logs/run-[0-9]{8}-[0-9]{6}\.lcm$ ]] || fail "log name '$log' is not DIR/run-YYYYmmdd-HHMMSS.lcm"
[ -f "$log" ] || fail "no log at $log"
read -r count missing first last <<<"$(channel_stats "$log" SIM_TRUTH)"
[ "$count" -ge 30 ] || fail "only $count SIM_TRUTH messages in 2 s at 20 Hz"
[ "$missing" -eq 0 ] || fail "$missing SIM_TRUTH messages missing"
[ "$(channel_stats "$log" ODOMETRY)" = "none" ] || fail "ODOMETRY logged although not selected"
echo "   $count SIM_TRUTH messages, seq $first..$last, none missing; ODOMETRY not logged"

echo "== refuses to overwrite"
status=0
"$record" --out "$log" --duration 1 --quiet 2>"$dir/err.txt" || status=$?
[ "$status" -eq 2 ] || fail "overwrite: exit $status, expected 2"
grep -q "refusing to overwrite" "$dir/err.txt" || fail "overwrite: message was: $(cat "$dir/err.txt")"

echo "== splits large logs into parts that are complete logs"
"$record" --out "$dir/split.lcm" --split-mb 0.002 --duration 3.5 --quiet >"$dir/parts.txt" &
rec_pid=$!
sleep 0.7
"$vehicle_sim" --generate mine --run-for 2 --heartbeat-period 0 2>/dev/null
wait "$rec_pid"
parts="$(wc -l <"$dir/parts.txt")"
[ "$parts" -ge 3 ] || fail "only $parts parts with --split-mb 0.002"
total=0 prev_last=""
while read -r part; do
  [[ "$part" =~ \.lcm\.[0-9]+$ ]] || fail "part name '$part'"
  "$log_tool" info "$part" >/dev/null || fail "part $part is not a clean log"
  read -r count missing first last <<<"$(channel_stats "$part" SIM_TRUTH)"
  [ "$count" = "none" ] && continue
  [ "$missing" -eq 0 ] || fail "$part: $missing SIM_TRUTH missing inside the part"
  if [ -n "$prev_last" ]; then [ "$first" -eq $((prev_last + 1)) ] || fail "$part starts at seq $first after $prev_last"; fi
  prev_last="$last"
  total=$((total + count))
done <"$dir/parts.txt"
[ "$total" -ge 30 ] || fail "only $total SIM_TRUTH messages over all parts"
echo "   $parts parts, $total SIM_TRUTH messages, seq continuous across parts"
status=0
"$record" --out "$dir/split.lcm" --split-mb 0.002 --duration 1 --quiet 2>/dev/null || status=$?
[ "$status" -eq 2 ] || fail "split overwrite: exit $status, expected 2"

echo "== --engine log_tool records the same way"
"$record" --engine log_tool --log-tool "$log_tool" --out "$dir/engine.lcm" --channels 'SIM_TRUTH|ODOMETRY' \
    --duration 3.5 --quiet >"$dir/engine.txt" &
rec_pid=$!
sleep 0.7
"$vehicle_sim" --generate mine --run-for 2 --heartbeat-period 0 2>/dev/null
wait "$rec_pid"
[ "$(cat "$dir/engine.txt")" = "$dir/engine.lcm" ] || fail "engine log_tool printed '$(cat "$dir/engine.txt")'"
read -r count missing first last <<<"$(channel_stats "$dir/engine.lcm" ODOMETRY)"
[ "$count" -ge 30 ] && [ "$missing" -eq 0 ] || fail "engine log_tool: $count ODOMETRY, $missing missing"
[ "$(channel_stats "$dir/engine.lcm" SIM_WORLD)" = "none" ] || fail "engine log_tool: unselected channel SIM_WORLD logged"
echo "   $count ODOMETRY messages, none missing"

echo "== log_tool record --parts: a recorder killed and restarted starts the next part; join keeps both"
"$log_tool" record --parts true --out "$dir/fleet.lcm" --channels SIM_TRUTH 2>/dev/null &
rec_pid=$!
sleep 0.7
"$vehicle_sim" --generate mine --run-for 1 --heartbeat-period 0 2>/dev/null
sleep 0.3  # past its flush interval (0.1 s)
kill -9 "$rec_pid"; wait "$rec_pid" 2>/dev/null || true
[ -f "$dir/fleet.lcm.00.partial" ] || fail "--parts: no fleet.lcm.00.partial after kill -9: $(ls "$dir")"
"$log_tool" record --parts true --out "$dir/fleet.lcm" --channels SIM_TRUTH --duration 2.5 2>/dev/null >"$dir/part.txt" &
rec_pid=$!
sleep 0.7
"$vehicle_sim" --generate mine --run-for 1 --heartbeat-period 0 2>/dev/null
wait "$rec_pid"
[ "$(cat "$dir/part.txt")" = "$dir/fleet.lcm.01" ] || fail "--parts: the restart wrote '$(cat "$dir/part.txt")', not fleet.lcm.01"
"$log_tool" join "$dir/fleet.lcm" "$dir"/fleet.lcm.[0-9][0-9]* 2>/dev/null || fail "join of the parts failed"
read -r count_a missing_a first_a last_a <<<"$(channel_stats "$dir/fleet.lcm.00.partial" SIM_TRUTH)"
read -r count_b missing_b first_b last_b <<<"$(channel_stats "$dir/fleet.lcm.01" SIM_TRUTH)"
read -r count missing first last <<<"$(channel_stats "$dir/fleet.lcm" SIM_TRUTH)"
[ "$count_a" -ge 10 ] && [ "$count_b" -ge 10 ] || fail "--parts: $count_a and $count_b SIM_TRUTH in the parts (1 s at 20 Hz each)"
[ "$count" -eq $((count_a + count_b)) ] || fail "join: $count events, the parts had $count_a + $count_b"
echo "   part 00 (killed): $count_a SIM_TRUTH, part 01: $count_b; joined: $count"

echo "== bad flags"
for bad in "--channels (" "--engine tape" "--engine log_tool --log-tool /nonexistent" "--split-mb lots" "--duration soon" "--recv-buf big" "--frobnicate" "--lcm-url http://x"; do
  status=0
  # shellcheck disable=SC2086
  "$record" --dir "$dir/bad" --duration 0.5 --quiet $bad 2>"$dir/err.txt" >/dev/null || status=$?
  [ "$status" -eq 2 ] || fail "'$bad': exit $status, expected 2"
  [ "$(wc -l <"$dir/err.txt")" -eq 1 ] || fail "'$bad': not one line: $(cat "$dir/err.txt")"
done
[ ! -e "$dir/bad" ] || [ -z "$(ls -A "$dir/bad")" ] || fail "a bad flag left a log behind"
echo "record_test: all passed"
