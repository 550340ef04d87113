#!/usr/bin/env bash
# Runs every test twice: a normal build with warnings as errors, then an
# AddressSanitizer + UndefinedBehaviorSanitizer build. Installs what is missing first.
#   scripts/test.sh            both builds
#   scripts/test.sh --quick    the normal build only
source "$(dirname "$0")/common.sh"
minenav_install_deps

quick=0
[ "${1:-}" = "--quick" ] && quick=1

run_suite() {
  local name="$1" dir="$2"; shift 2
  echo "== [$name] configure and build in $dir"
  minenav_build "$dir" -DMINENAV_WERROR=ON "$@"
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
