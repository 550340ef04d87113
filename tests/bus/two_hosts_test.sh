#!/usr/bin/env bash
# Two hosts (tests/bus/two_hosts.sh): what crosses the vehicle LAN and what does not.
#
#   two_hosts_test.sh crosses|stays|fleet FLEET_BIN LOG_TOOL PORT
#
#   crosses  ttl=1: a supervisor's HEARTBEAT published on the vehicle is heard on the base
#            (`fleet status` there lists it).
#   stays    ttl=0: the same HEARTBEAT is heard on the vehicle itself but not on the base.
#   fleet    the small real fleet (two_hosts.fleet) under two supervisors, vehicle_sim,
#            ladar_driver and contour_mapper on the vehicle, lcm-logger and path_planner on
#            the base: the base records the vehicle's POSE, CONTOUR_MAP and HEARTBEATs, and
#            each host's `fleet status` lists the other's processes.
set -euo pipefail
mode="$1" fleet="$2" log_tool="$3" port="$4"
here="$(cd "$(dirname "$0")" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
fail() { echo "two_hosts_test $mode: FAILED: $*" >&2; exit 1; }
# A table row of `fleet status`: "NAME  PID ..." at the start of a line.
has_row() { grep -qE "^$2 +[0-9]+ " "$1"; }
# Only the LAN besides loopback: nothing else is reachable from a host.
only_the_lan='test "$(ip -o link show | grep -vc ": lo:")" = 1 || { echo "more links than the LAN:"; ip -o link show; exit 1; }'

cat > "$work/idle.fleet" <<FLEET
[process idle]
command = sleep 1000
group = vehicle
heartbeat = none
FLEET
supervise_idle="$fleet run $work/idle.fleet --out $work/vehicle --run-for 4 --status-period 0 --heartbeat-period 0.2"

case "$mode" in
  crosses)
    "$here/two_hosts.sh" --port "$port" --ttl 1 -- \
      "$only_the_lan; $supervise_idle" -- \
      "$only_the_lan; sleep 0.5; $fleet status --for 2.5 > $work/base_status.txt"
    cat "$work/base_status.txt"
    grep -qE "^fleet:all +[0-9]+ .* OK .*1 running" "$work/base_status.txt" ||
      fail "the base did not hear the vehicle's supervisor"
    ;;
  stays)
    "$here/two_hosts.sh" --port "$port" --ttl 0 -- \
      "$supervise_idle & sleep 0.5; $fleet status --for 2.5 > $work/vehicle_status.txt; wait" -- \
      "sleep 0.5; if $fleet status --for 2.5 > $work/base_status.txt 2>&1; then exit 1; fi"
    cat "$work/vehicle_status.txt" "$work/base_status.txt"
    has_row "$work/vehicle_status.txt" fleet:all || fail "the vehicle did not hear its own supervisor: the check proves nothing"
    grep -q "no HEARTBEAT heard" "$work/base_status.txt" || fail "with ttl=0 something crossed to the base"
    ;;
  fleet)
    run="$fleet run $here/two_hosts.fleet --run-for 9 --status-period 0"
    "$here/two_hosts.sh" --port "$port" --ttl 1 -- \
      "$only_the_lan; $run --groups vehicle --out $work/vehicle & sleep 5; $fleet status --for 2.5 > $work/vehicle_status.txt; wait" -- \
      "$only_the_lan; $run --groups base --out $work/base & sleep 5; $fleet status --for 2.5 > $work/base_status.txt; wait"
    echo "== the base station hears:"; cat "$work/base_status.txt"
    echo "== the vehicle hears:"; cat "$work/vehicle_status.txt"
    # The supervisors' instance is the groups they run.
    for p in vehicle_sim ladar_driver contour_mapper path_planner fleet:vehicle fleet:base; do
      has_row "$work/base_status.txt" "$p" || fail "the base did not hear $p"
      has_row "$work/vehicle_status.txt" "$p" || fail "the vehicle did not hear $p"
    done
    "$log_tool" info "$work/base/base.lcm" > "$work/info.txt" || { cat "$work/info.txt"; fail "log_tool info on the base's log"; }
    cat "$work/info.txt"
    for channel in POSE CONTOUR_MAP LADAR_SCAN SIM_TRUTH HEARTBEAT; do
      grep -qE "^$channel +" "$work/info.txt" || fail "the base's log has no $channel from the vehicle"
    done
    ;;
  *) echo "usage: $0 crosses|stays|fleet FLEET_BIN LOG_TOOL PORT" >&2; exit 2 ;;
esac
echo "two_hosts_test $mode: passed"
