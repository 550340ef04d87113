#!/usr/bin/env bash
# The main job: the fleet on its built-in simulated mine, live on the LCM bus.
#
#   scripts/run_demo.sh [--stations N] [--seed S] [--speed M/S] [--out DIR]
#
# Generates a room-and-pillar mine (thesis 5.2.1), starts vehicle_sim, ladar_driver
# (Typhoon, 2048 points, 10 Hz), the live contour_mapper (thesis ch. 4: it maps while the
# vehicle drives, inserting a scan every metre and tracking the others), the live
# path_planner, the path_tracker (on the mapper's POSE, never SIM_TRUTH) and lcm-logger inside
# a private network namespace (nothing leaves this machine); survey_client drives the survey
# route station by station (a PATH_REQUEST each, tracked until the tracker reports it done), and leaves in DIR (default out/demo-<UTC time>): the
# log, the world, the stations, the live contour map (contour_map.json, with a checkpoint of
# the mapper saved every 10 scans, so a crash loses the last few scans, not the map), a
# summary of the log, an SVG of the run and an SVG of the contour map rebuilt from the log
# by the batch mapper (same policy as live).
#
# The miner's real cruise speed is 0.076 m/s; the demo drives at --speed (default 1 m/s)
# so that a 16-station survey takes about two minutes.
source "$(dirname "$0")/common.sh"

stations=16 seed=7 speed=1.0 out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --stations) stations="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    --speed) speed="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) awk 'NR > 1 && /^#/ { print; next } NR > 1 { exit }' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "run_demo.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$stations" =~ ^[0-9]+$ && "$stations" -ge 2 && "$stations" -le 42 ]] ||
  { echo "run_demo.sh: --stations must be 2..42" >&2; exit 2; }

minenav_install_deps
build="$MINENAV_ROOT/build/release"
echo "== building in $build"
minenav_build "$build" -DMINENAV_WERROR=ON -- vehicle_sim ladar_driver log_tool contour_mapper path_planner \
  path_tracker survey_client
bin="$build/bin"

out="${out:-$MINENAV_ROOT/out/demo-$(date -u +%Y%m%d-%H%M%S)}"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
echo "== outputs in $out"

"$bin/log_tool" generate --kind mine --seed "$seed" --world-out "$out/mine.json" \
  --stations-out "$out/all_stations.csv"
head -n $((stations + 1)) "$out/all_stations.csv" > "$out/stations.csv"
start_pose="$(sed -n 2p "$out/stations.csv")"

# Everything below runs in a fresh network namespace: loopback only, multicast routed on it.
# Scans arrive at 10 Hz while the vehicle drives: insert one per metre or 0.3 rad, track the rest.
mapper_policy="--insert-min-translation 1.0 --insert-min-rotation 0.3 --final-refinement-rounds 2"
# The live mapper's checkpoint (and contour_map.json) every 10 handled scans, i.e. every 1 s
# of 10 Hz scans (inserted and tracked ones count alike): without --checkpoint-every it is
# written only at a clean shutdown and a crash loses the whole live map. A checkpoint holds
# the inserted scans, 2048 points x 16 bytes each: 1.3 MB after 40 inserts, written in
# 0.004-0.023 s (measured here; mapper/README.md), against 0.16 s of mapping per scan. This
# survey inserts one scan per metre or 0.3 rad, so a few MB and a few hundredths of a second
# per write: about 1 % of the mapper's time.
checkpoint_every=10
# The survey vehicle's footprint (W,L in m, centred on its pose): the planner plans for it and
# the tracker checks its motion with it. The stations of the generated survey point anywhere
# in the 6 m entries, so a compact ladar vehicle surveys; the 3.3 x 10 m miner is
# path_planner's default and the maneuvers' (planner/README.md).
footprint_w=1.2 footprint_l=2.0
export out bin speed seed start_pose mapper_policy checkpoint_every footprint_w footprint_l
"$MINENAV_ROOT/tests/bus/private_net.sh" --port 7667 -- bash -c '
  set -euo pipefail
  pids=()
  cleanup() { for p in "${pids[@]}"; do kill -INT "$p" 2>/dev/null || true; done; wait || true; }
  trap cleanup EXIT
  lcm-logger --lcm-url="$LCM_DEFAULT_URL" --quiet "$out/survey.lcm" & pids+=($!)
  "$bin/vehicle_sim" --world "$out/mine.json" --start-pose "$start_pose" --seed "$seed" \
    --max-forward-speed "$speed" --max-acceleration 1 --max-deceleration 2 \
    --max-turn-in-place-rate 0.6 --max-yaw-acceleration 2 --heartbeat-period 1 \
    2> "$out/vehicle_sim.log" & pids+=($!)
  "$bin/ladar_driver" --world "$out/mine.json" --sensor typhoon --seed "$seed" \
    2> "$out/ladar_driver.log" & pids+=($!)
  "$bin/contour_mapper" $mapper_policy --checkpoint "$out/mapper.ckpt" --checkpoint-every "$checkpoint_every" \
    --save-map "$out/contour_map.json" 2> "$out/contour_mapper.log" & pids+=($!)
  "$bin/path_planner" --footprint "$footprint_w,$footprint_l" --speed "$speed" --deadline 5 \
    2> "$out/path_planner.log" & pids+=($!)
  "$bin/path_tracker" --vehicle-width "$footprint_w" --vehicle-length "$footprint_l" \
    --tracker.cruise-speed "$speed" --tracker.turn-rate 0.5 --tracker.deceleration 2 \
    2> "$out/path_tracker.log" & pids+=($!)
  sleep 1
  echo "== driving the survey on the fleet'"'"'s own estimate: PATH_REQUEST per station, path_planner on the"
  echo "   live contour map, path_tracker on the mapper'"'"'s POSE (progress below; Ctrl-C stops)"
  "$bin/survey_client" --stations "$out/stations.csv" --requests.dwell 0.5 --log-level info
  sleep 0.5
'

echo "== log summary"
"$bin/log_tool" info "$out/survey.lcm" | tee "$out/survey_info.txt"
"$bin/log_tool" render "$out/survey.lcm" --world "$out/mine.json" --out "$out/survey.svg" \
  --title "MINENAV survey demo: $stations stations, seed $seed"
echo "== live mapper: $(grep -E "scans received" "$out/contour_mapper.log" | tail -1 | sed 's/.*info: //')"
echo "== contour map from the log (batch mapper, same policy)"
"$bin/contour_mapper" --log "$out/survey.lcm" $mapper_policy --map-out "$out/contour_map_batch.json" \
  --poses-out "$out/contour_poses.csv" --svg-out "$out/contour_map.svg" 2> "$out/contour_mapper_batch.log" ||
  { tail -5 "$out/contour_mapper_batch.log" >&2; exit 3; }
tail -1 "$out/contour_mapper_batch.log"
echo "== done: open $out/survey.svg and $out/contour_map.svg"
