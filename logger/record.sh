#!/usr/bin/env bash
# Records the bus into an LCM log with lcm-logger, named by date (logger/README.md).
#
#   logger/record.sh [--dir DIR] [--name PREFIX] [--channels REGEX] [--invert]
#                    [--split-mb N] [--duration S] [--lcm-url URL] [--recv-buf BYTES]
#                    [--out FILE] [--engine lcm-logger|log_tool] [--log-tool PATH] [--quiet]
#
# Writes DIR/PREFIX-YYYYmmdd-HHMMSS.lcm (UTC), or FILE with --out; with --split-mb the
# files are ...lcm.00, ...lcm.01, ... (lcm-logger -i). Never overwrites: exits 2 if the
# log (or any of its split parts) exists. Stops on SIGINT (Ctrl-C), SIGTERM, or after
# --duration; a script that starts it with & must stop it with SIGTERM (bash makes
# background jobs of scripts ignore SIGINT). Prints the path of each log on stdout.
#
# UDP drops what the socket buffer cannot hold (DESIGN.md "The bus"), so the URL gets
# recv_buf_size=BYTES (default 4194304) unless it already names one or --recv-buf 0. The
# kernel caps SO_RCVBUF at net.core.rmem_max, which on this kernel is a host-wide
# setting (read-only inside a network namespace): the script warns when it is too small,
# it does not change it (that needs root on the host: sysctl -w net.core.rmem_max=N).
# lcm-logger keeps LCM's default subscription queue (30 messages) and drops bursts that
# the kernel delivered; --engine log_tool records with `log_tool record` instead, which
# does not (no --split-mb or --invert there). log_tool is --log-tool, else on PATH, else
# build/release/bin/log_tool.
set -euo pipefail

usage() { sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; }
die() { echo "record.sh: error: $*" >&2; exit 2; }

dir="." name="minenav" channels=".*" invert=0 split_mb="" duration="" quiet=0 out="" engine="lcm-logger" log_tool=""
url="${LCM_DEFAULT_URL:-udpm://239.255.76.67:7667?ttl=0}"
recv_buf=4194304
while [ $# -gt 0 ]; do
  case "$1" in
    --dir) dir="${2:?--dir needs a value}"; shift 2 ;;
    --name) name="${2:?--name needs a value}"; shift 2 ;;
    --channels) channels="${2:?--channels needs a regex}"; shift 2 ;;
    --invert) invert=1; shift ;;
    --split-mb) split_mb="${2:?--split-mb needs a value}"; shift 2 ;;
    --duration) duration="${2:?--duration needs seconds}"; shift 2 ;;
    --lcm-url) url="${2:?--lcm-url needs a URL}"; shift 2 ;;
    --lcm-url=*) url="${1#--lcm-url=}"; shift ;;
    --recv-buf) recv_buf="${2:?--recv-buf needs bytes}"; shift 2 ;;
    --out) out="${2:?--out needs a file}"; shift 2 ;;
    --engine) engine="${2:?--engine needs lcm-logger or log_tool}"; shift 2 ;;
    --log-tool) log_tool="${2:?--log-tool needs a path}"; shift 2 ;;
    --quiet) quiet=1; shift ;;
    -h|--help) usage; exit 0 ;;
    *) die "unknown option '$1' (see --help)" ;;
  esac
done

case "$engine" in
  lcm-logger) command -v lcm-logger >/dev/null || die "lcm-logger not found (Debian package liblcm-bin)" ;;
  log_tool)
    if [ -z "$log_tool" ]; then
      log_tool="$(command -v log_tool || true)"
      [ -n "$log_tool" ] || log_tool="$(cd "$(dirname "$0")/.." && pwd)/build/release/bin/log_tool"
    fi
    [ -x "$log_tool" ] || die "log_tool not found at '$log_tool' (build it, or give --log-tool PATH)"
    [ -z "$split_mb" ] || die "--split-mb needs --engine lcm-logger"
    [ $invert -eq 0 ] || die "--invert needs --engine lcm-logger" ;;
  *) die "--engine '$engine' is not lcm-logger or log_tool" ;;
esac
[[ "$recv_buf" =~ ^[0-9]+$ ]] || die "--recv-buf '$recv_buf' is not a number of bytes"
[ -z "$split_mb" ] || [[ "$split_mb" =~ ^[0-9]+(\.[0-9]+)?$ ]] || die "--split-mb '$split_mb' is not a number"
[ -z "$duration" ] || [[ "$duration" =~ ^[0-9]+(\.[0-9]+)?$ ]] || die "--duration '$duration' is not a number of seconds"
[[ "$url" == udpm://* || "$url" == file://* || "$url" == memq://* ]] || die "--lcm-url '$url' is not an LCM URL"
# A bad regex would make lcm-logger log nothing at all.
regex_status=0
echo "" | grep -Eq -- "$channels" 2>/dev/null || regex_status=$?
[ "$regex_status" -le 1 ] || die "--channels '$channels' is not a valid regex"

if [ "$recv_buf" -gt 0 ] && [[ "$url" == udpm://* ]] && [[ "$url" != *recv_buf_size=* ]]; then
  if [[ "$url" == *\?* ]]; then url="${url}&recv_buf_size=${recv_buf}"; else url="${url}?recv_buf_size=${recv_buf}"; fi
fi
if [[ "$url" =~ recv_buf_size=([0-9]+) ]]; then
  want="${BASH_REMATCH[1]}"
  cap="$(cat /proc/sys/net/core/rmem_max 2>/dev/null || echo 0)"
  if [ "$cap" -gt 0 ] && [ "$cap" -lt "$want" ]; then
    echo "record.sh: warning: net.core.rmem_max = $cap caps recv_buf_size=$want; expect drops at high rates" \
         "(raise it on the host: sysctl -w net.core.rmem_max=$want)" >&2
  fi
fi

if [ -z "$out" ]; then
  mkdir -p "$dir" || die "cannot create directory '$dir'"
  out="$dir/$name-$(date -u +%Y%m%d-%H%M%S).lcm"
fi
[ -d "$(dirname "$out")" ] || die "directory '$(dirname "$out")' does not exist"
[ -e "$out" ] && die "'$out' exists; refusing to overwrite"
if [ -n "$split_mb" ] && compgen -G "$out.[0-9]*" >/dev/null; then die "'$out.NN' exists; refusing to overwrite"; fi

args=(--lcm-url="$url" --channel="$channels" -q)
[ $invert -eq 1 ] && args+=(--invert-channels)
[ -n "$split_mb" ] && args+=(-i --split-mb="$split_mb")
[ $quiet -eq 1 ] || echo "record.sh: $engine recording '$channels'$([ $invert -eq 1 ] && echo ' (inverted)') from $url to $out${split_mb:+.NN (split every $split_mb MB)}" >&2

if [ "$engine" = lcm-logger ]; then
  lcm-logger "${args[@]}" "$out" &
  stop_signal=INT
else
  "$log_tool" record --lcm-url "$url" --channels "$channels" --out "$out" >/dev/null 2>&1 &
  stop_signal=TERM
fi
logger_pid=$!
stop() { kill -"$stop_signal" "$logger_pid" 2>/dev/null || true; }
trap stop INT TERM
if [ -n "$duration" ]; then
  ( sleep "$duration"; kill -"$stop_signal" "$logger_pid" 2>/dev/null || true ) &
  timer_pid=$!
fi
status=0
wait "$logger_pid" || status=$?
# wait returns early when a trapped signal arrives: wait for the logger to flush and exit.
while kill -0 "$logger_pid" 2>/dev/null; do wait "$logger_pid" || status=$?; done
[ -n "${timer_pid:-}" ] && kill "$timer_pid" 2>/dev/null || true
# What matters is that a log was written; log_tool also fails loudly on write errors.
if [ "$engine" = log_tool ] && [ "$status" -ne 0 ]; then
  echo "record.sh: error: log_tool record failed (exit $status); what it got is in $out.partial" >&2
  exit 3
fi
if [ -n "$split_mb" ]; then
  compgen -G "$out.[0-9]*" >/dev/null || { echo "record.sh: error: no log written: nothing received on '$channels' from $url ( exit $status)" >&2; exit 3; }
  ls -1 "$out".[0-9]*
else
  [ -e "$out" ] || { echo "record.sh: error: no log written: nothing received on '$channels' from $url ( exit $status)" >&2; exit 3; }
  echo "$out"
fi
