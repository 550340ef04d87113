#!/usr/bin/env bash
# Runs the benchmark programs one after another (never side by side: the machine has two
# cores and the figures are times), each printing its table and writing its JSON into OUT.
# The module READMEs quote these tables; after a change, run this and compare.
#
#   bench/run_all.sh [--bin DIR] [--out DIR] [--carmen] [--only NAME[,NAME...]]
#
#   --bin DIR    where the bench binaries are (default build/release/bin)
#   --out DIR    where tables (NAME.txt) and JSON (NAME.json) go (default bench-results)
#   --carmen     also the CARMEN logs (mapper_carmen_bench: Intel and Freiburg 079, about
#                15 minutes; needs the datasets in ../shared/datasets)
#   --only LIST  just these benches (names as in the table below)
# planner_ompl_bench (the planner against OMPL) needs Debian's libompl-dev: run_all.sh installs
# it with apt-get when missing (scripts/common.sh minenav_install_bench_deps); CMake builds that
# bench only where OMPL is found, so after a first install reconfigure and build it.
# Exit status: 0 when every bench ran, else the number of benches that failed.
# Not run here (they start processes on a bus, in a private network namespace): the scripts
# bench/logger_drop_bench.sh, bench/contour_mapper_live_bench.sh and bench/fleet_load_bench.sh
# (the whole fleet for 10 minutes: CPU, memory, messages lost, UDP margin; fleet/README.md),
# nor bench/mapper_insert_cost.sh (needs a recorded mission: mapper/README.md, "Insert cost").
set -uo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${here}/build/release/bin"
out="bench-results"
carmen=0
only=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --bin) bin="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --carmen) carmen=1; shift ;;
    --only) only="$2"; shift 2 ;;
    -h|--help) sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "run_all.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ -d "$bin" ]] || { echo "run_all.sh: no binaries in $bin (build first: scripts/build.sh)" >&2; exit 2; }
mkdir -p "$out"

# name | arguments after the JSON flag
benches=(
  "ladar_sim_bench|"
  "ipe_correspondence|"
  "ipe_accuracy|"
  "ipe_variants|"
  "fpe_mockup|"
  "fpe_comparison|"
  "mapper_synthetic_mine_bench|"
  "mapper_loop_bench|"
  "mapper_scale_bench|"
  "mapper_dynamic_bench|"
  "planner_bench|"
  "footprint_collision_bench|"
  "planner_ompl_bench|"
  "task_planner_bench|"
  "auth_bench|"
)
if [[ $carmen -eq 1 ]]; then
  benches+=("mapper_carmen_bench_intel|--only intel" "mapper_carmen_bench_fr079|--only fr079")
fi

# OMPL for planner_ompl_bench (in a subshell: common.sh sets -e).
if [[ -z "$only" || ",$only," == *",planner_ompl_bench,"* ]]; then
  ( source "$here/scripts/common.sh" && minenav_install_bench_deps ) ||
    echo "run_all.sh: could not install OMPL (scripts/common.sh minenav_install_bench_deps)" >&2
fi

stopped=0
trap 'stopped=1' INT TERM
failed=0
for entry in "${benches[@]}"; do
  name="${entry%%|*}"
  extra="${entry#*|}"
  if [[ -n "$only" && ",$only," != *",$name,"* ]]; then continue; fi
  program="$name"
  [[ "$name" == mapper_carmen_bench_* ]] && program=mapper_carmen_bench
  if [[ ! -x "$bin/$program" ]]; then
    echo "== $name: $bin/$program is missing" >&2
    [[ "$name" == planner_ompl_bench ]] &&
      echo "   (built only where CMake finds OMPL: reconfigure and build the target planner_ompl_bench)" >&2
    failed=$((failed + 1))
    continue
  fi
  echo "== $name"
  start=$(date +%s)
  # shellcheck disable=SC2086  # extra is a word list on purpose
  "$bin/$program" --json-out "$out/$name.json" $extra > "$out/$name.txt" 2>&1
  status=$?
  cat "$out/$name.txt"
  echo "-- $name: exit $status, $(( $(date +%s) - start )) s (table $out/$name.txt, JSON $out/$name.json)"
  [[ $status -eq 0 ]] || failed=$((failed + 1))
  if [[ $stopped -eq 1 ]]; then echo "run_all.sh: stopped; the finished tables are in $out" >&2; exit 130; fi
done
exit "$failed"
