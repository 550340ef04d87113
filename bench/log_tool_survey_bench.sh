#!/usr/bin/env bash
# Wall time of `log_tool survey` on the synthetic mine of thesis 5.2.1 (42 stations):
# median of --repeats runs per sensor setting, whole process (load world, simulate,
# write log and truth CSV).
#
#   bench/log_tool_survey_bench.sh [--build-dir DIR] [--repeats N] [--json-out FILE]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build/release" repeats=5 json_out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build="$2"; shift 2 ;;
    --repeats) repeats="$2"; shift 2 ;;
    --json-out) json_out="$2"; shift 2 ;;
    -h|--help) sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "log_tool_survey_bench: unknown option '$1'" >&2; exit 2 ;;
  esac
done
tool="$build/bin/log_tool"
[ -x "$tool" ] || { echo "log_tool_survey_bench: $tool missing (build first, or --build-dir)" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$tool" generate --kind mine --seed 1 --world-out "$work/mine.json" --stations-out "$work/st.csv" 2>/dev/null

rows=()
printf "%-10s %7s %9s %12s %12s %12s\n" "sensor" "points" "stations" "median s" "min s" "log MB"
for setting in "typhoon 2048" "cyclone 2048" "cyclone 8192"; do
  read -r sensor points <<<"$setting"
  times=()
  for ((i = 0; i < repeats; i++)); do
    rm -f "$work/s.lcm" "$work/t.csv"
    t0=$(date +%s.%N)
    "$tool" survey --world "$work/mine.json" --stations "$work/st.csv" --sensor "$sensor" --points "$points" \
        --pose-noise 0.33,0.33,3.33deg --seed 7 --quiet --out "$work/s.lcm" --truth-out "$work/t.csv"
    t1=$(date +%s.%N)
    times+=("$(python3 -c "print($t1 - $t0)")")
  done
  read -r median min <<<"$(printf '%s\n' "${times[@]}" | python3 -c '
import statistics, sys
v = [float(x) for x in sys.stdin.read().split()]
print(f"{statistics.median(v):.3f} {min(v):.3f}")')"
  mb="$(python3 -c "print(f'{$(stat -c %s "$work/s.lcm") / 1e6:.2f}')")"
  printf "%-10s %7s %9s %12s %12s %12s\n" "$sensor" "$points" 42 "$median" "$min" "$mb"
  rows+=("{\"sensor\": \"$sensor\", \"points\": $points, \"stations\": 42, \"median_s\": $median, \"min_s\": $min, \"log_mb\": $mb}")
done
if [ -n "$json_out" ]; then
  { echo "{\"bench\": \"log_tool_survey\", \"repeats\": $repeats, \"rows\": ["
    for i in "${!rows[@]}"; do echo "  ${rows[$i]}$([ "$i" -lt $((${#rows[@]} - 1)) ] && echo ,)"; done
    echo "]}"; } >"$json_out"
  echo "wrote $json_out"
fi
