#!/usr/bin/env bash
# Does recording lose messages? vehicle_sim + ladar_driver publish Typhoon scans (2048
# points) while logger/record.sh records, inside a private network namespace
# (tests/bus/private_net.sh). Published = the scans ladar_driver reports at exit
# (scan_id counts them from 0); logged = LADAR_SCAN messages in the log and the gaps in
# their scan_id (log_tool info). One run per (receive buffer, scan rate).
#
#   bench/logger_drop_bench.sh [--build-dir DIR] [--duration S] [--rates "10 100"]
#                              [--bufs "0 4194304"] [--json-out FILE]
#
# --bufs: recv_buf_size of the logger's URL in bytes; 0 = none (the kernel default,
# net.core.rmem_default). Prints a table; --json-out writes the rows as JSON.
#
# Then a burst (--burst N scans, 0 = skip): a log of N Typhoon scans made by log_tool
# survey is replayed with lcm-logplayer -s 0 (as fast as it can) while recording, the
# worst case a logger meets (replaying a run while recording it, or a map dump), once
# per recording engine (--engines "lcm-logger log_tool": record.sh --engine).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build/release" duration=60 rates="10 100" bufs="0 4194304" json_out="" burst=1000 engines="lcm-logger log_tool"
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build="$2"; shift 2 ;;
    --duration) duration="$2"; shift 2 ;;
    --rates) rates="$2"; shift 2 ;;
    --bufs) bufs="$2"; shift 2 ;;
    --json-out) json_out="$2"; shift 2 ;;
    --burst) burst="$2"; shift 2 ;;
    --engines) engines="$2"; shift 2 ;;
    -h|--help) sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "logger_drop_bench: unknown option '$1'" >&2; exit 2 ;;
  esac
done
for b in vehicle_sim ladar_driver log_tool; do
  [ -x "$build/bin/$b" ] || { echo "logger_drop_bench: $build/bin/$b missing (build first, or --build-dir)" >&2; exit 2; }
done

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
port=7745
rows=()
printf "%-8s %-10s %-10s %7s %6s %10s %8s %8s %8s %8s\n" "source" "engine" "recv_buf" "rate Hz" "s" "published" "logged" "missing" "loss %" "rmem_max"
for rate in $rates; do
  for buf in $bufs; do
    port=$((port + 1))
    run="$work/r$port"
    mkdir -p "$run"
    # One run: logger first, then the vehicle, then the ladar for $duration s; the ladar
    # stops first so every scan it published had time to reach the logger.
    "$root/tests/bus/private_net.sh" --port "$port" -- bash -c '
      set -e
      run="$1" build="$2" root="$3" buf="$4" rate="$5" duration="$6" port="$7"
      cat /proc/sys/net/core/rmem_max > "$run/rmem_max"
      "$root/logger/record.sh" --out "$run/log.lcm" --lcm-url "udpm://239.255.76.67:$port?ttl=0" \
          --recv-buf "$buf" --channels "LADAR_SCAN|SIM_TRUTH" --quiet >/dev/null 2>"$run/record.err" &
      rec=$!
      sleep 1
      "$build/bin/vehicle_sim" --generate mine --heartbeat-period 0 --log-level warn 2>"$run/vehicle.err" &
      veh=$!
      sleep 1.5
      "$build/bin/ladar_driver" --sensor typhoon --points 2048 --scan-rate "$rate" --heartbeat-period 0 \
          --run-for "$duration" 2>"$run/ladar.err"
      sleep 1
      kill -TERM $veh; wait $veh || true
      kill -TERM $rec; wait $rec || true
    ' _ "$run" "$build" "$root" "$buf" "$rate" "$duration" "$port"
    published="$(grep -o '[0-9]* scans published' "$run/ladar.err" | grep -o '^[0-9]*' || echo 0)"
    read -r logged missing <<<"$("$build/bin/log_tool" info --json "$run/log.lcm" | python3 -c '
import json, sys
s = json.load(sys.stdin)
c = [c for c in s["channels"] if c["channel"] == "LADAR_SCAN"]
print(c[0]["count"], c[0]["missing"]) if c else print(0, 0)')"
    loss="$(python3 -c "print(f'{100.0 * (1 - $logged / $published):.2f}' if $published else 'n/a')")"
    rmem="$(cat "$run/rmem_max")"
    printf "%-8s %-10s %-10s %7s %6s %10s %8s %8s %8s %8s\n" "sensor" "lcm-logger" "$([ "$buf" = 0 ] && echo default || echo "$buf")" "$rate" \
      "$duration" "$published" "$logged" "$missing" "$loss" "$rmem"
    rows+=("{\"source\": \"ladar_driver\", \"engine\": \"lcm-logger\", \"recv_buf_size\": $buf, \"scan_rate_hz\": $rate, \"duration_s\": $duration, \"published\": $published, \"logged\": $logged, \"missing_scan_ids\": $missing, \"loss_percent\": \"$loss\", \"rmem_max\": $rmem}")
  done
done
if [ "$burst" -gt 0 ]; then
  # The burst log: N stations cycling through the mine survey, 0.1 s apart.
  "$build/bin/log_tool" generate --kind mine --world-out "$work/mine.json" --stations-out "$work/st.csv" 2>/dev/null
  python3 - "$work/st.csv" "$burst" <<'PY'
import sys
path, n = sys.argv[1], int(sys.argv[2])
lines = open(path).read().split("\n")
header, rows = lines[0], [l for l in lines[1:] if l]
open(path, "w").write(header + "\n" + "\n".join(rows[i % len(rows)] for i in range(n)) + "\n")
PY
  "$build/bin/log_tool" survey --world "$work/mine.json" --stations "$work/st.csv" --points 2048 \
      --station-interval 0.1 --quiet --out "$work/burst.lcm"
  for engine in $engines; do
  for buf in $bufs; do
    port=$((port + 1))
    run="$work/b$port"
    mkdir -p "$run"
    "$root/tests/bus/private_net.sh" --port "$port" -- bash -c '
      set -e
      run="$1" root="$2" buf="$3" port="$4" log="$5" engine="$6" tool="$7"
      "$root/logger/record.sh" --engine "$engine" --log-tool "$tool" --out "$run/log.lcm" --lcm-url "udpm://239.255.76.67:$port?ttl=0" \
          --recv-buf "$buf" --channels "LADAR_SCAN" --quiet >/dev/null 2>"$run/record.err" &
      rec=$!
      sleep 1
      lcm-logplayer -s 0 --regexp=LADAR_SCAN --lcm-url="udpm://239.255.76.67:$port?ttl=0" "$log" >/dev/null 2>&1
      sleep 1
      kill -TERM $rec; wait $rec || true
    ' _ "$run" "$root" "$buf" "$port" "$work/burst.lcm" "$engine" "$build/bin/log_tool"
    read -r logged missing <<<"$("$build/bin/log_tool" info --json "$run/log.lcm" | python3 -c '
import json, sys
s = json.load(sys.stdin)
c = [c for c in s["channels"] if c["channel"] == "LADAR_SCAN"]
print(c[0]["count"], c[0]["missing"]) if c else print(0, 0)')"
    loss="$(python3 -c "print(f'{100.0 * (1 - $logged / $burst):.2f}')")"
    printf "%-8s %-10s %-10s %7s %6s %10s %8s %8s %8s %8s\n" "burst" "$engine" "$([ "$buf" = 0 ] && echo default || echo "$buf")" \
      "max" "-" "$burst" "$logged" "$missing" "$loss" "$(cat /proc/sys/net/core/rmem_max)"
    rows+=("{\"source\": \"lcm-logplayer -s 0\", \"engine\": \"$engine\", \"recv_buf_size\": $buf, \"published\": $burst, \"logged\": $logged, \"missing_scan_ids\": $missing, \"loss_percent\": \"$loss\"}")
  done
  done
fi
if [ -n "$json_out" ]; then
  { echo "{\"bench\": \"logger_drop\", \"points\": 2048, \"rows\": ["
    for i in "${!rows[@]}"; do echo "  ${rows[$i]}$([ "$i" -lt $((${#rows[@]} - 1)) ] && echo ,)"; done
    echo "]}"; } >"$json_out"
  echo "wrote $json_out"
fi
