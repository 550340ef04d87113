#!/usr/bin/env bash
# Runs the tests twice: a normal build with warnings as errors (every test; its mission test
# in the background, beside the next build: mission_start, below), then an
# AddressSanitizer + UndefinedBehaviorSanitizer build (all but sanitize_exclude's five, below);
# then the fuzz stage: a clang-14 build of the libFuzzer targets alone (fuzz/README.md), each
# its committed corpus and then 3 s of mutation (MINENAV_FUZZ_SECONDS=N in the environment:
# N seconds; 0: every input once, no mutation).
# Installs what is missing first.
#   scripts/test.sh            both builds and the fuzz stage
#   scripts/test.sh --quick    the normal build only
#   scripts/test.sh --fuzz     the fuzz stage only
# The real-data tests need the public datasets (CMake's MINENAV_DATASETS_DIR, by default
# ../shared/datasets); without them they are not built and the last line says so. With
# MINENAV_REQUIRE_DATASETS=1 in the environment (CI) missing datasets fail the configure.
source "$(dirname "$0")/common.sh"
minenav_install_deps

quick=0
[ "${1:-}" = "--quick" ] && quick=1
fuzz_only=0
[ "${1:-}" = "--fuzz" ] && fuzz_only=1

require=OFF
[ "${MINENAV_REQUIRE_DATASETS:-}" = "1" ] && require=ON

# Each stage says how long it took: CI stops at 90 minutes, and the build and test times of
# every stage are what to look at first when it comes near (docs/DESIGN.md, "Tests and CI").
stage_started=$SECONDS
stage_done() { echo "== [$1] took $((SECONDS - stage_started)) s (${SECONDS} s since the start)"; stage_started=$SECONDS; }

# build_stage NAME DIR [cmake args...]: configure and build DIR, warnings as errors.
build_stage() {
  local name="$1" dir="$2"; shift 2
  echo "== [$name] configure and build in $dir"
  minenav_build "$dir" -DMINENAV_WERROR=ON -DMINENAV_REQUIRE_DATASETS=$require "$@"
  stage_done "$name build"
}

# test_stage NAME DIR [ctest args...]: the tests of DIR (all but those the arguments leave out).
test_stage() {
  local name="$1" dir="$2"; shift 2
  echo "== [$name] tests"
  (cd "$dir" && ctest --output-on-failure -j "$MINENAV_JOBS" --timeout 600 "$@")
  stage_done "$name tests"
}

# The mission test (label `mission`: ~10 minutes of the whole fleet in real time, scans at
# 10 Hz) needs the machine's time when the fleet asks for it, and nothing beside it that keeps
# time itself (another test's timing bound would pay for the fleet's bursts). A compile keeps
# no time: the mission runs beside the sanitizer build, which runs at nice 19 and so takes only
# what the fleet leaves (on the 2 cores, 0.6 of one on average). Alone after the normal
# build's other tests it added its ~540 s to the run. Its output is printed when it ends.
mission_start() {
  local dir="$MINENAV_ROOT/build/release"
  mission_out="$dir/mission_test.txt"
  echo "== [mission] bus.mission_two_hosts_with_a_fault starts in the background (output: $mission_out)"
  # In a process group of its own (setsid), so that a failed build or a Ctrl-C stops the whole
  # fleet with it (the EXIT trap).
  (cd "$dir" && exec setsid ctest --output-on-failure -L mission --timeout 1200 >"$mission_out" 2>&1) &
  mission_pid=$!
  trap 'exit 130' INT TERM
  trap '[ -n "${mission_pid:-}" ] && kill -- "-$mission_pid" 2>/dev/null' EXIT
}
mission_wait() {
  local status=0 waiting=$SECONDS
  wait "$mission_pid" || status=$?
  mission_pid=""
  cat "$mission_out"
  echo "== [mission] ended: the run waited $((SECONDS - waiting)) s for it after the build beside it" \
       "(its own time: ctest's line above; ${SECONDS} s since the start)"
  [ $status -eq 0 ] || { echo "== [mission] FAILED (exit $status)"; exit 1; }
}

# Under the sanitizers, all tests but five accuracy runs of long closed loops and real data (1000 s
# of the stage's 3400 s of test CPU on the development machine: the cutter's box and slab cut
# 565 s, the tracker on the live mapper's pose 2 x 143 s, the Intel slice and the mapper process
# on a survey 79 s each). Their code runs under the sanitizers in shorter tests (the cutter and
# the planner on the live map on the bus, the mapper's process, stop and restart tests, the
# CARMEN readers); the normal build runs them for their figures.
sanitize_exclude='^(CutterSimTest\.ABoxCutThenASlabCutBesideIt|Maneuvers/ClosedLoopLiveMapperTest\.TracksWithinTheTargetsOnTheMappersPose/(box_cut_10dHz|slab_cut_2dHz) |CarmenRegressionTest\.|ContourMapperProcessTest\.MapsASurveyLogToTruth$)'

# The fuzz stage: the fuzz targets and what they link only (target fuzz_targets), unoptimised
# (-O0: the build is most of the stage's time; -O1 made it ~4 times dearer, 1250 s of CPU
# against ~330 s), with line tables for the sanitizers' stack traces and Eigen's and the
# standard library's templates not traced for coverage (fuzz/coverage_ignorelist.txt: what made
# the slow node targets slow); then the `fuzz` label (fuzz/CMakeLists.txt): each target 3 s of
# mutation after its corpus. fuzz/README.md, "CI", has the stage's measured time.
run_fuzz() {
  local dir="$MINENAV_ROOT/build/fuzz"
  echo "== [fuzz] configure and build the fuzz targets in $dir (clang-14)"
  CC=clang-14 CXX=clang++-14 minenav_build "$dir" -DMINENAV_WERROR=ON -DMINENAV_FUZZ=ON -DMINENAV_BUILD_BENCH=OFF \
    -DMINENAV_FUZZ_SECONDS="${MINENAV_FUZZ_SECONDS:-3}" \
    -DCMAKE_BUILD_TYPE=FuzzSmoke "-DCMAKE_CXX_FLAGS_FUZZSMOKE=-O0 -gline-tables-only" \
    "-DCMAKE_C_FLAGS_FUZZSMOKE=-O0 -gline-tables-only" -- fuzz_targets
  stage_done "fuzz build"
  echo "== [fuzz] each target over its corpus"
  # The same sanitizer options whether or not the sanitizer suite ran before (libFuzzer handles
  # the crash itself: no abort_on_error).
  (cd "$dir" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --output-on-failure -j "$MINENAV_JOBS" -L fuzz)
  stage_done "fuzz tests"
}

if [ $fuzz_only -eq 1 ]; then
  run_fuzz
  echo "== fuzz stage passed"
  exit 0
fi

release="$MINENAV_ROOT/build/release"
build_stage release "$release"
if [ $quick -eq 1 ]; then
  test_stage release "$release"
else
  test_stage release "$release" -LE mission
  mission_start
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  # Benchmarks are compiled (warnings checked) in the normal build; the sanitizer build
  # runs the tests only.
  MINENAV_NICE=19 build_stage sanitize "$MINENAV_ROOT/build/sanitize" -DMINENAV_SANITIZE=ON -DMINENAV_BUILD_BENCH=OFF
  mission_wait
  echo "== [sanitize] left to the normal build: ${sanitize_exclude}"
  test_stage sanitize "$MINENAV_ROOT/build/sanitize" -E "$sanitize_exclude"
  run_fuzz
fi
echo "== all tests passed"

# What CMake found (build/release/CMakeCache.txt): did the real-data tests run?
cache="$MINENAV_ROOT/build/release/CMakeCache.txt"
datasets="$(sed -n 's/^MINENAV_DATASETS_DIR:PATH=//p' "$cache")"
datasets="$(realpath -m "$datasets")"
if grep -qx 'MINENAV_HAVE_DATASETS:INTERNAL=ON' "$cache"; then
  echo "real-data tests: ran, datasets at $datasets"
else
  echo "real-data tests: NOT built: no datasets at $datasets (see docs/DESIGN.md, Scenarios)"
fi
