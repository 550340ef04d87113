#!/usr/bin/env bash
# The live contour_mapper on the 42-station synthetic mine of thesis 5.2 (2048-point Typhoon
# scans, initial pose noise 0.33 m / 3.33 deg): the survey log is replayed with
# lcm-logplayer inside a private network namespace (tests/bus/private_net.sh) and the
# process reports, at shutdown, the median time to handle one scan (wall and CPU of its
# worker thread), the size of CONTOUR_MAP plain and compressed, and the checkpoint's size
# and write time. Prints a table; --json-out FILE writes the figures as JSON.
#
#   bench/contour_mapper_live_bench.sh [--build-dir build/release] [--json-out FILE]
#                                      [--port 7769] [--speed 1]
set -euo pipefail
build=build/release
json=""
port=7769
speed=1
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) build=$2; shift 2 ;;
    --json-out) json=$2; shift 2 ;;
    --port) port=$2; shift 2 ;;
    --speed) speed=$2; shift 2 ;;
    *) echo "usage: $0 [--build-dir DIR] [--json-out FILE] [--port N] [--speed S]" >&2; exit 2 ;;
  esac
done
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$(cd "$build/bin" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$bin/log_tool" generate --kind mine --seed 1 --world-out "$tmp/mine.json" --stations-out "$tmp/st.csv" >/dev/null
"$bin/log_tool" survey --world "$tmp/mine.json" --stations "$tmp/st.csv" --sensor typhoon --points 2048 \
  --pose-noise 0.33,0.33,3.33deg --seed 7 --out "$tmp/survey.lcm" --truth-out "$tmp/truth.csv" >/dev/null
scans=42

# The live run: start, wait for its first heartbeat's worth of time, play, wait until every
# scan has been handled (one log line each), stop with SIGTERM (checkpoint at shutdown).
"$root/tests/bus/private_net.sh" --port "$port" -- bash -c '
  set -e
  "$1/contour_mapper" --checkpoint "$2/run.ckpt" --map-out "$2/map.json" --poses-out "$2/poses.csv" \
    > "$2/live.txt" 2>&1 &
  pid=$!
  sleep 2
  lcm-logplayer --speed="$3" "$2/survey.lcm" > /dev/null
  for _ in $(seq 1200); do
    n=$(grep -c -E ": (inserted|tracked|refused)" "$2/live.txt" || true)
    [ "$n" -ge "$4" ] && break
    sleep 0.5
  done
  kill -TERM "$pid"
  wait "$pid"
' _ "$bin" "$tmp" "$speed" "$scans"

summary=$(grep "median handling time" "$tmp/live.txt")
checkpoint=$(grep "checkpoint .*run.ckpt" "$tmp/live.txt" | tail -1)
handled=$(echo "$summary" | sed -E 's/.* ([0-9]+) inserted, ([0-9]+) tracked, ([0-9]+) refused.*/\1 \2 \3/')
wall=$(echo "$summary" | sed -E 's/.*median handling time ([0-9.e-]+) s wall.*/\1/')
cpu=$(echo "$summary" | sed -E 's/.* ([0-9.e-]+) s CPU per scan.*/\1/')
plain=$(echo "$summary" | sed -E 's/.*\(map ([0-9]+) bytes plain.*/\1/')
packed=$(echo "$summary" | sed -E 's/.*plain, ([0-9]+) compressed.*/\1/')
ck_bytes=$(echo "$checkpoint" | sed -E 's/.* ([0-9]+) bytes, .*/\1/')
ck_s=$(echo "$checkpoint" | sed -E 's/.* bytes, ([0-9.e-]+) s$/\1/')
read -r inserted tracked refused <<< "$handled"

printf '%-44s %s\n' "measure" "value"
printf '%-44s %s\n' "scans inserted / tracked / refused" "$inserted / $tracked / $refused of $scans"
printf '%-44s %s\n' "median time to handle one scan, wall (s)" "$wall"
printf '%-44s %s\n' "median time to handle one scan, CPU (s)" "$cpu"
printf '%-44s %s\n' "CONTOUR_MAP plain (bytes)" "$plain"
printf '%-44s %s\n' "CONTOUR_MAP compressed (bytes)" "$packed"
printf '%-44s %s\n' "checkpoint size (bytes)" "$ck_bytes"
printf '%-44s %s\n' "checkpoint write time (s)" "$ck_s"
if [ -n "$json" ]; then
  cat > "$json" <<JSON
{"scans": $scans, "inserted": $inserted, "tracked": $tracked, "refused": $refused,
 "median_handle_wall_s": $wall, "median_handle_cpu_s": $cpu,
 "contour_map_plain_bytes": $plain, "contour_map_compressed_bytes": $packed,
 "checkpoint_bytes": $ck_bytes, "checkpoint_write_s": $ck_s}
JSON
fi
