#!/usr/bin/env bash
# Runs every test twice: a normal build with warnings as errors, then an
# AddressSanitizer + UndefinedBehaviorSanitizer build. Installs what is missing first.
#   scripts/test.sh            both builds
#   scripts/test.sh --quick    the normal build only
# The real-data tests need the public datasets (CMake's MINENAV_DATASETS_DIR, by default
# ../shared/datasets); without them they are not built and the last line says so. With
# MINENAV_REQUIRE_DATASETS=1 in the environment (CI) missing datasets fail the configure.
source "$(dirname "$0")/common.sh"
minenav_install_deps

quick=0
[ "${1:-}" = "--quick" ] && quick=1

require=OFF
[ "${MINENAV_REQUIRE_DATASETS:-}" = "1" ] && require=ON

run_suite() {
  local name="$1" dir="$2"; shift 2
  echo "== [$name] configure and build in $dir"
  minenav_build "$dir" -DMINENAV_WERROR=ON -DMINENAV_REQUIRE_DATASETS=$require "$@"
  echo "== [$name] tests"
  (cd "$dir" && ctest --output-on-failure -j "$MINENAV_JOBS" --timeout 600)
}

run_suite release "$MINENAV_ROOT/build/release"
if [ $quick -eq 0 ]; then
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  # Benchmarks are compiled (warnings checked) in the normal build; the sanitizer build
  # runs the tests only.
  run_suite sanitize "$MINENAV_ROOT/build/sanitize" -DMINENAV_SANITIZE=ON -DMINENAV_BUILD_BENCH=OFF
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
