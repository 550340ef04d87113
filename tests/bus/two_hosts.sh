#!/usr/bin/env bash
# Two hosts on one machine: a vehicle and a base station, each a network namespace of its
# own whose only link is a veth pair between them (the vehicle LAN), with multicast routed
# on it. Nothing else is reachable: the pair lives inside a private namespace of its own,
# never the machine's. Runs one command on each host, with LCM_DEFAULT_URL on the LAN
# (ttl=1 by default: one hop, vehicle to base station; DESIGN.md, "The bus"), and fails
# loudly when the hosts cannot be made or a command fails.
#
#   tests/bus/two_hosts.sh [--port N] [--ttl T] -- 'VEHICLE COMMAND' -- 'BASE COMMAND'
#
# Each command is run by bash -c, with MINENAV_HOST=vehicle or base (and
# MINENAV_IN_PRIVATE_NET=1, so bus tests accept it); their output lines are prefixed with
# [vehicle] and [base]. Exit 0 when both commands exit 0, else 1 naming the one(s) that
# failed. --ttl 0 keeps every packet on its own host: nothing crosses.
set -euo pipefail

port=7667 ttl=1 stage="" host="" device="" address=""
while [ $# -gt 0 ]; do
  case "$1" in
    --port) port="$2"; shift 2 ;;
    --ttl) ttl="$2"; shift 2 ;;
    --stage) stage="$2"; host="$3"; device="$4"; address="$5"; shift 5 ;;
    --) shift; break ;;
    *) echo "usage: $0 [--port N] [--ttl T] -- 'VEHICLE COMMAND' -- 'BASE COMMAND'" >&2; exit 2 ;;
  esac
done
fail() { echo "two_hosts: FAILED: $*" >&2; exit 1; }

# Stage 3: on one host. Say where we are, wait for our end of the veth, configure, run.
# A host stays up until both commands ended: its end of the link going away would take the
# other end with it.
if [ "$stage" = "host" ]; then
  command="$1" work="$2"
  trap 'touch "$work/$host.finished"; while [ ! -e "$work/vehicle.finished" ] || [ ! -e "$work/base.finished" ]; do sleep 0.02; done' EXIT
  echo $$ > "$work/$host.pid"
  for _ in $(seq 500); do [ -e "$work/go" ] && break; sleep 0.01; done
  [ -e "$work/go" ] || fail "$host: the link was never set up"
  ip link set lo up
  ip link set "$device" up
  ip addr add "$address/24" dev "$device"
  ip link set "$device" multicast on
  ip route add 239.0.0.0/8 dev "$device"
  ip route show | grep -q "^239.0.0.0/8 dev $device" || fail "$host: could not route multicast on $device"
  export LCM_DEFAULT_URL="udpm://239.255.76.67:${port}?ttl=${ttl}&recv_buf_size=4194304"
  export MINENAV_HOST="$host" MINENAV_IN_PRIVATE_NET=1
  bash -c "$command"
  exit $?
fi

[ $# -eq 3 ] && [ "$2" = "--" ] || { echo "usage: $0 [--port N] [--ttl T] -- 'VEHICLE COMMAND' -- 'BASE COMMAND'" >&2; exit 2; }
vehicle_command="$1" base_command="$3"
[[ "$port" =~ ^[0-9]+$ && "$ttl" =~ ^[0-9]+$ ]] || { echo "two_hosts: --port and --ttl are numbers" >&2; exit 2; }

# Stage 1: into a private namespace of our own, so the veth pair never touches the machine's.
if [ "$stage" != "outer" ]; then
  command -v unshare >/dev/null && command -v ip >/dev/null ||
    fail "unshare and ip (util-linux, iproute2) are needed for two hosts"
  unshare_flags=(--net)
  [ "$(id -u)" -eq 0 ] || unshare_flags=(--net --map-root-user)
  unshare "${unshare_flags[@]}" true 2>/dev/null || fail "cannot create a network namespace (unshare ${unshare_flags[*]})"
  exec unshare "${unshare_flags[@]}" "$0" --stage outer - - - --port "$port" --ttl "$ttl" -- \
    "$vehicle_command" -- "$base_command"
fi

# Stage 2: make the two hosts, link them, let them run.
work="$(mktemp -d)"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
# Addresses on the link are link-local: the LAN is these two namespaces and nothing else.
run_host() {  # NAME DEVICE ADDRESS COMMAND
  (
    set -o pipefail
    unshare --net "$0" --stage host "$1" "$2" "$3" --port "$port" --ttl "$ttl" -- "$4" "$work" 2>&1 |
      sed -u "s/^/[$1] /"
  ) &
  pids+=($!)
}
run_host vehicle lan0 169.254.76.1 "$vehicle_command"
run_host base lan1 169.254.76.2 "$base_command"
for _ in $(seq 500); do [ -s "$work/vehicle.pid" ] && [ -s "$work/base.pid" ] && break; sleep 0.01; done
[ -s "$work/vehicle.pid" ] && [ -s "$work/base.pid" ] || fail "the hosts did not start"
ip link add lan0 type veth peer name lan1 || fail "cannot make a veth pair"
ip link set lan0 netns "$(cat "$work/vehicle.pid")" || fail "cannot move lan0 to the vehicle"
ip link set lan1 netns "$(cat "$work/base.pid")" || fail "cannot move lan1 to the base station"
touch "$work/go"

status=0
wait "${pids[0]}" || { echo "two_hosts: FAILED: the vehicle command exited $?" >&2; status=1; }
wait "${pids[1]}" || { echo "two_hosts: FAILED: the base command exited $?" >&2; status=1; }
pids=()
exit $status
