#!/usr/bin/env bash
# Runs a command inside a private network namespace whose only interface is loopback,
# with multicast routed on it, so LCM traffic can never leave this machine
# (DESIGN.md, "The bus"). Fails loudly when the namespace cannot be made.
#
#   tests/bus/private_net.sh [--port N] -- COMMAND [ARGS...]
#
# --port N sets LCM_DEFAULT_URL to udpm://239.255.76.67:N?ttl=0&recv_buf_size=4194304 so
# that tests running in parallel never share a bus.
set -euo pipefail

port=""
if [ "${1:-}" = "--port" ]; then port="$2"; shift 2; fi
[ "${1:-}" = "--" ] && shift
[ $# -ge 1 ] || { echo "usage: $0 [--port N] -- COMMAND [ARGS...]" >&2; exit 2; }

if [ -z "${MINENAV_IN_PRIVATE_NET:-}" ]; then
  if ! command -v unshare >/dev/null || ! command -v ip >/dev/null; then
    echo "private_net: FAILED: unshare and ip (util-linux, iproute2) are needed for bus tests" >&2
    exit 1
  fi
  unshare_flags=(--net)
  [ "$(id -u)" -eq 0 ] || unshare_flags=(--net --map-root-user)
  export MINENAV_IN_PRIVATE_NET=1
  args=()
  [ -n "$port" ] && args=(--port "$port")
  if ! unshare "${unshare_flags[@]}" true 2>/dev/null; then
    echo "private_net: FAILED: cannot create a network namespace (unshare ${unshare_flags[*]}); bus tests need it" >&2
    exit 1
  fi
  exec unshare "${unshare_flags[@]}" "$0" "${args[@]}" -- "$@"
fi

ip link set lo up
ip link set lo multicast on
ip route add 239.0.0.0/8 dev lo 2>/dev/null || true
if ! ip route show | grep -q '^239.0.0.0/8 dev lo'; then
  echo "private_net: FAILED: could not route multicast on loopback" >&2
  exit 1
fi
if [ -n "$port" ]; then
  export LCM_DEFAULT_URL="udpm://239.255.76.67:${port}?ttl=0&recv_buf_size=4194304"
fi
exec "$@"
