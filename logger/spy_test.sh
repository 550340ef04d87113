#!/usr/bin/env bash
# log_tool spy as a person uses it: in a terminal (tmux), on a live bus (a private network
# namespace), while the operator's view's known log (viewer_test_log) and one undecodable
# POSE are played into it; the screen (capture-pane) must list the channels with their
# types, counts and the bad message, and the decoded fields of the latest messages; Ctrl-C
# (send-keys) must end it. Installs tmux when missing, then runs itself in the namespace.
#   logger/spy_test.sh BIN_DIR WORK_DIR
set -euo pipefail
bin="$1"; work="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
if [ -z "${MINENAV_IN_PRIVATE_NET:-}" ]; then
  source "$root/scripts/common.sh"
  minenav_install_missing tmux liblcm-bin python3
  command -v tmux >/dev/null || { echo "spy_test: FAILED: tmux is missing" >&2; exit 1; }
  exec "$root/tests/bus/private_net.sh" --port "${MINENAV_SPY_TEST_PORT:-7851}" -- "$0" "$@"
fi

rm -rf "$work"; mkdir -p "$work"; cd "$work"
export TMUX_TMPDIR="$work"  # a tmux server of our own
session=spy
cleanup() { tmux kill-server 2>/dev/null || true; }
trap cleanup EXIT

"$root/viewer/testing/make_known_log.sh" "$bin"
python3 - bad.lcm <<'PY'
import struct, sys
open(sys.argv[1], "wb").write(struct.pack(">IqqII", 0xEDA1DA01, 0, 1000000000000000, 4, 3) + b"POSE" + b"\x01\x02\x03")
PY

tmux new-session -d -s $session -x 200 -y 60 "LCM_DEFAULT_URL='$LCM_DEFAULT_URL' $bin/log_tool spy --period 0.2 --window 60; echo SPY-EXITED \$?; sleep 30"
sleep 1
lcm-logplayer known.lcm >/dev/null
lcm-logplayer bad.lcm >/dev/null
sleep 1
tmux capture-pane -p -t $session > screen.txt
cat screen.txt
fail=0
expect() { grep -Eq -- "$1" screen.txt || { echo "spy_test: FAILED: the screen has no match for: $1" >&2; fail=1; }; }
expect '^log_tool spy .* messages'
expect '^LADAR_SCAN +minenav\.ladar_scan_t +[0-9.]+ +6 '
expect '^POSE +minenav\.pose_estimate_t +[0-9.]+ +7 .* 1$'                 # 6 good + 1 bad
expect 'last bad: payload of 3 bytes is shorter than an 8-byte fingerprint'
expect '^CONTOUR_MAP +minenav\.contour_map_t +[0-9.]+ +2 '
expect '^MISSION_STATUS +minenav\.mission_status_t '
expect '"sensor_id":"typhoon"'                                              # decoded fields
expect '"mission_id":"survey-test"'
expect '"message":"driving to station 5"'
tmux send-keys -t $session C-c
sleep 1
tmux capture-pane -p -t $session > after.txt
grep -q "SPY-EXITED 0" after.txt || { echo "spy_test: FAILED: Ctrl-C did not end log_tool spy with exit 0" >&2; cat after.txt; fail=1; }
[ $fail -eq 0 ] && echo "spy_test: passed"
exit $fail
