#!/usr/bin/env bash
# The main job: the whole mission on the fleet's built-in simulated mine, live on the LCM bus.
#
#   scripts/run_demo.sh [--seed S] [--fast F] [--depth D] [--out DIR] [--small] [--max-stations N]
#                       [--two-hosts] [--kill NAME@SECONDS]... [--attack S@LENGTH] [--port P]
#                       [--bin DIR] [--no-batch-map]
#
# Generates a room-and-pillar section (thesis 5.2.1; 7 m entries: the 3.3 x 10 m miner's turn
# into a crosscut needs more than 6 m, planner/README.md) and runs the mission's fleet
# (fleet/mission.fleet, under the fleet supervisor, in a private network namespace: nothing
# leaves this machine): vehicle_sim, ladar_driver, the live contour_mapper, path_planner,
# path_tracker, cutter, task_planner, the coordinator, and log_tool record recording every message.
# With nothing known in advance but the start pose, the miner explores the section (the
# contour map grows live; the task planner chooses each scan station; the vehicle is driven
# closed-loop on the mapper's estimate, never on the truth), then advances the entry whose face
# is given by the section's plan with a box cut and a slab cut, and backs out for the roof
# bolter. A progress line per change of the mission's state; Ctrl-C stops the fleet and still
# writes the report of what was done. Leaves in DIR (default out/mission-<UTC time>):
#
#   mission.lcm           the log of every message (log_tool record)
#   mine.json             the true section at the start
#   contour_map.json      the live contour map (and the mapper's checkpoint mapper.ckpt)
#   contour_map_batch.json the map rebuilt from the log by the batch mapper (same policy)
#   mission.json          the coordinator's account (subtasks, events, planning waits)
#   report.md, report.json the report: explored area and time, map accuracy against the true
#                         world, pose error along the drive, each cut's depth against the
#                         request, planning times, what was retried or refused
#   mission.svg, mission.png  the final map over the true walls, planned and driven paths
#   NAME.log              each process's log; fleet.log the supervisor's status tables
#   fleet.key             the key the command channels were signed with (mode 600)
#
# --fast F (default 6) multiplies the miner's speeds (tramming 0.076 m/s, turning 0.05 rad/s,
# the cutter's sumping and shearing) so the mission takes minutes; the report states it.
# --small: a one-pillar section and a 0.5 m cut (what CI runs). Watch it live in a browser:
# viewer/view_demo.sh (in another terminal, while it runs).
#
# --two-hosts: the fleet split as on a real machine: the `vehicle` group (vehicle_sim,
# ladar_driver, contour_mapper, path_tracker, cutter) in one network namespace, the `base`
# group (recorder, path_planner, task_planner, coordinator) in another, joined only by a veth
# pair with ttl=1 (tests/bus/two_hosts.sh); each under its own supervisor; the vehicle's stops
# when the base's mission has ended. fleet_vehicle.log and fleet_base.log hold their tables.
# --kill NAME@SECONDS (repeatable): a fault: kill -9 the process NAME that many seconds into the
# mission; its supervisor restarts it (fleet/README.md) and the mission goes on or stops with
# the reason. --attack S@LENGTH: an attacker without the key on the vehicle's network
# (tests/bus/command_attacker): it records the signed command channels from the start, then from
# S seconds into the mission for LENGTH seconds publishes replayed, forged, tampered and
# unsigned copies (5 rounds a second) on every one of them; what it sent is in
# command_attacker.txt, what each process refused in the last line of its NAME.log ("stopping:
# ... refused by authentication: CHANNEL COUNT ...", common/node/README.md "Security"); the
# report reads the log with the fleet's key and uses none of them.
# --port: the bus's UDP port (default 7667). --bin DIR: use the programs in DIR as they are
# (built elsewhere, e.g. by the tests) instead of building build/release. --no-batch-map: no
# contour_map_batch.json (the report judges the live map; the rebuild from the log takes
# minutes: tests/bus/mission_test.sh leaves it out).
source "$(dirname "$0")/common.sh"

seed=7 fast=6 depth=1.0 out="" small=0 max_stations=30 two_hosts=0 port=7667 bin="" kills=() attack="" batch_map=1
while [ $# -gt 0 ]; do
  case "$1" in
    --seed) seed="$2"; shift 2 ;;
    --fast) fast="$2"; shift 2 ;;
    --depth) depth="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --small) small=1; shift ;;
    --max-stations) max_stations="$2"; shift 2 ;;
    --two-hosts) two_hosts=1; shift ;;
    --kill) kills+=("$2"); shift 2 ;;
    --attack) attack="$2"; shift 2 ;;
    --port) port="$2"; shift 2 ;;
    --bin) bin="$2"; shift 2 ;;
    --no-batch-map) batch_map=0; shift ;;
    -h|--help) awk 'NR > 1 && /^#/ { print; next } NR > 1 { exit }' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "run_demo.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
number='^[0-9]+([.][0-9]+)?$'
[[ "$seed" =~ ^[0-9]+$ ]] || { echo "run_demo.sh: --seed must be a whole number" >&2; exit 2; }
[[ "$fast" =~ $number ]] && awk "BEGIN { exit !($fast >= 1 && $fast <= 20) }" ||
  { echo "run_demo.sh: --fast must be a number from 1 to 20" >&2; exit 2; }
[[ "$depth" =~ $number ]] && awk "BEGIN { exit !($depth >= 0.1 && $depth <= 5) }" ||
  { echo "run_demo.sh: --depth must be a number of metres from 0.1 to 5" >&2; exit 2; }
[[ "$max_stations" =~ ^[0-9]+$ && "$max_stations" -ge 1 ]] ||
  { echo "run_demo.sh: --max-stations must be a whole number >= 1" >&2; exit 2; }
[[ "$port" =~ ^[0-9]+$ && "$port" -ge 1024 && "$port" -le 65535 ]] ||
  { echo "run_demo.sh: --port must be a UDP port from 1024 to 65535" >&2; exit 2; }
programs=(vehicle_sim ladar_driver contour_mapper path_planner path_tracker cutter task_planner coordinator)
processes=("${programs[@]}" recorder)  # --kill names: the fleet file's processes
for k in "${kills[@]}"; do
  [[ "$k" =~ ^([a-z_]+)@([0-9]+([.][0-9]+)?)$ ]] && [[ " ${processes[*]} " == *" ${BASH_REMATCH[1]} "* ]] ||
    { echo "run_demo.sh: --kill takes NAME@SECONDS with NAME one of: ${processes[*]} (got '$k')" >&2; exit 2; }
done
tools=(log_tool fleet auth_keygen)
if [ -n "$attack" ]; then
  [[ "$attack" =~ ^([0-9]+([.][0-9]+)?)@([0-9]+([.][0-9]+)?)$ ]] ||
    { echo "run_demo.sh: --attack takes SECONDS@LENGTH, e.g. 60@300 (got '$attack')" >&2; exit 2; }
  tools+=(command_attacker)
fi

if [ -z "$bin" ]; then
  minenav_install_deps
  build="$MINENAV_ROOT/build/release"
  echo "== building in $build"
  minenav_build "$build" -DMINENAV_WERROR=ON -- "${programs[@]}" "${tools[@]}"
  bin="$build/bin"
else
  for p in "${programs[@]}" "${tools[@]}"; do
    [ -x "$bin/$p" ] || { echo "run_demo.sh: --bin $bin has no program $p" >&2; exit 2; }
  done
  bin="$(cd "$bin" && pwd)"
fi

out="${out:-$MINENAV_ROOT/out/mission-$(date -u +%Y%m%d-%H%M%S)}"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
# The fleet's key (fleet/mission.fleet's KEY_FILE): its command channels are signed and nothing
# unsigned is obeyed (common/node/README.md, "Security"). A fresh one per run, mode 600; on two
# hosts both supervisors read this file.
rm -f "$out/fleet.key"
"$bin/auth_keygen" "$out/fleet.key" >/dev/null
echo "== outputs in $out"

# The section: pillars 12 m square, entries 7 m wide; the panel's boundary wall one entry
# width outside the pillars (sim/mine_generator.h). The miner starts in the south entry
# facing east; the face to advance is the boundary wall at the east end of that entry.
rows=1 cols=2
[ $small -eq 1 ] && { cols=1; [ "$depth" = "1.0" ] && depth=0.5; }
room=7 pillar=12
"$bin/log_tool" generate --kind mine --rows $rows --cols $cols --room-width $room --pillar-size $pillar \
  --seed "$seed" --world-out "$out/mine.json" --stations-out "$out/plan_stations.csv" >/dev/null
width=$(awk "BEGIN { print $cols * ($pillar + $room) + $room }")
start_pose="9.5,$(awk "BEGIN { print $room / 2 }"),0"
face="$(awk "BEGIN { print $width - 4 }"),$(awk "BEGIN { print $room / 2 }"),0"

# The speed factor: the miner's speeds (fleet/mission.fleet's variables) times F.
times() { awk "BEGIN { printf \"%.4g\", $1 * $fast }"; }
shear_time=$(awk "BEGIN { printf \"%.4g\", 12 / $fast }")
speeds=(TRAM_SPEED="$(times 0.076)" TURN_RATE="$(times 0.05)" ACCELERATION="$(times 0.05)"
        DECELERATION="$(times 0.1)" YAW_ACCELERATION="$(times 0.05)" APPROACH_SPEED="$(times 0.05)"
        SUMP_SPEED="$(times 0.02)" CUSP_SPEED="$(times 0.03)" CUTTER_TURN_RATE="$(times 0.03)"
        BOOM_RATE="$(times 0.2)" SHEAR_TIME="$shear_time")
echo "== the mission: explore the ${cols}x${rows}-pillar section from $start_pose, then advance the face at $face by $depth m"
echo "   speed factor $fast: tramming $(times 0.076) m/s (the miner's 0.076 x $fast); progress below, Ctrl-C stops"

# One host's supervisor, as a script of its own (run inside the namespace): supervise.sh
# GROUPS LOG [ENDED]. The fleet's GROUPS (all, vehicle or base), its tables in LOG, the faults
# of --kill among its processes (kill -9 of its child NAME, the time given after the start).
# With ENDED, the base touches that file when its fleet has ended and the vehicle stops its
# own then (nothing on the vehicle knows the mission). Ctrl-C reaches the supervisor.
supervise="$out/.supervise.sh"
{
  echo '#!/usr/bin/env bash'
  echo 'groups="$1" log="$2" ended="${3:-}" args=()'
  echo '[ "$groups" != all ] && args=(--groups "$groups")'
  printf '%q ' "$bin/fleet" run "$MINENAV_ROOT/fleet/mission.fleet" --out "$out" --status-period 60 \
    SEED="$seed" START_POSE="$start_pose" FACE="$face" DEPTH="$depth" MAX_STATIONS="$max_stations" "${speeds[@]}"
  echo '"${args[@]}" > >(tee "$log") &'
  echo 'f=$!'
  echo "trap 'kill -INT \$f 2>/dev/null' INT TERM"
  for k in "${kills[@]}"; do
    name="${k%@*}" at="${k#*@}"
    group="$(awk -v p="[process $name]" '$0 == p { on = 1; next } /^\[/ { on = 0 } on && $1 == "group" { print $3 }' \
             "$MINENAV_ROOT/fleet/mission.fleet")"
    echo "if [ \"\$groups\" = all ] || [ \"\$groups\" = $group ]; then"
    program="$name"; [ "$name" = recorder ] && program=log_tool  # the fleet's name, the program's
    echo "  (sleep $at; pkill -9 -P \$f -x $program && echo \"== fault: kill -9 $name, $at s into the mission\") &"
    echo "fi"
  done
  if [ -n "$attack" ]; then
    # On the vehicle's network (the one host, or the vehicle of two): it listens from the start.
    echo 'if [ "$groups" = all ] || [ "$groups" = vehicle ]; then'
    # A job of this script itself (not inside a subshell), so the `kill $(jobs -p)` below
    # stops it when the fleet ends first.
    printf '  %q --capture %q --attack %q --rate 5 > %q 2> %q &\n' "$bin/command_attacker" \
      "${attack%@*}" "${attack#*@}" "$out/command_attacker.txt" "$out/command_attacker.log"
    echo 'fi'
  fi
  echo 'if [ -n "$ended" ] && [ "$groups" = vehicle ]; then'
  echo '  while kill -0 $f 2>/dev/null && [ ! -e "$ended" ]; do sleep 0.5; done'
  echo '  kill -INT $f 2>/dev/null'
  echo 'fi'
  echo 'wait $f; s=$?'
  echo 'while kill -0 $f 2>/dev/null; do wait $f; s=$?; done'
  echo 'kill $(jobs -p) 2>/dev/null'
  echo '[ -n "$ended" ] && [ "$groups" = base ] && touch "$ended"'
  echo '[ "$groups" = vehicle ] && exit 0'
  echo 'exit $s'
} > "$supervise"
chmod +x "$supervise"

status=0
if [ $two_hosts -eq 0 ]; then
  "$MINENAV_ROOT/tests/bus/private_net.sh" --port "$port" -- "$supervise" all "$out/fleet.log" || status=$?
else
  ended="$out/.base_ended"
  rm -f "$ended"
  "$MINENAV_ROOT/tests/bus/two_hosts.sh" --port "$port" --ttl 1 -- \
    "$(printf '%q ' "$supervise" vehicle "$out/fleet_vehicle.log" "$ended")" -- \
    "$(printf '%q ' "$supervise" base "$out/fleet_base.log" "$ended")" || status=$?
  rm -f "$ended"
fi
rm -f "$supervise"
case $status in
  0) echo "== the mission ended" ;;
  130) echo "== stopped by Ctrl-C: the report covers what was done" ;;
  *) echo "== the fleet ended with exit code $status (see $out/fleet.log and $out/coordinator.log)" ;;
esac

# The recorder's parts (log_tool record --parts; a killed part is left as .NN.partial, and the
# recorder restarted after a crash writes the next one) as one log, in order; a part torn by its
# writer's death keeps its whole events (log_tool join).
parts=("$out"/mission.lcm.[0-9][0-9]*)
if [ -e "${parts[0]}" ]; then
  "$bin/log_tool" join "$out/mission.lcm" "${parts[@]}" && rm -f "${parts[@]}"
fi
[ -s "$out/mission.lcm" ] || { echo "run_demo.sh: no log was recorded ($out/mission.lcm)" >&2; exit 3; }
if [ $batch_map -eq 1 ]; then
  echo "== the contour map rebuilt from the log (batch mapper, same policy)"
  # The live mapper's bounded refit too (fleet/mission.fleet): with every scan a long mission's
  # rebuild grows quadratically (120 inserts: 7 minutes); the final refinement uses every scan.
  "$bin/contour_mapper" --log "$out/mission.lcm" --insert-min-translation 1.0 --insert-min-rotation 0.3 \
    --mapper.fit-scans 20 --mapper.local-fit-radius 15 --final-refinement-rounds 2 --map-out "$out/contour_map_batch.json" --svg-out "$out/contour_map_batch.svg" \
    2> "$out/contour_mapper_batch.log" || echo "   (the batch mapper failed: $out/contour_mapper_batch.log)"
fi
echo "== the report"
report_args=(--log "$out/mission.lcm" --key-file "$out/fleet.key" --world "$out/mine.json" --report-out "$out/report.md"
             --json-out "$out/report.json" --svg-out "$out/mission.svg" --png-out "$out/mission.png"
             --note "speed factor $fast: tramming at $(times 0.076) m/s, the cutter's speeds x $fast (the real miner: x 1)")
[ -s "$out/contour_map.json" ] && report_args+=(--map "$out/contour_map.json")
[ -s "$out/mission.json" ] && report_args+=(--mission "$out/mission.json")
"$bin/log_tool" mission-report "${report_args[@]}" || { echo "run_demo.sh: the report failed" >&2; exit 3; }
cat "$out/report.md"
echo "== done: $out/report.md, $out/mission.png (and .svg)"
exit $status
