# Shared by the two README commands: install what is missing, configure, build.
# Source it; do not run it.
set -euo pipefail

MINENAV_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
MINENAV_JOBS="${MINENAV_JOBS:-$(nproc)}"

# Debian packages the project needs; installed with apt-get only when missing.
# librsvg2-bin: rsvg-convert, which turns the mission's SVG picture into its PNG
# (log_tool mission-report --png-out; its test checks the PNG). libsystemd-dev: the node
# loop's notify protocol. libboost-dev: Boost.Beast/Asio (header-only) for viewer/'s HTTP and
# WebSocket server; chromium: the viewer's browser test (headless, driven by npm
# playwright-core); tmux: the terminal spy's test (send-keys, capture-pane). clang-14 and
# libclang-rt-14-dev: the fuzz targets (fuzz/README.md: libFuzzer, ASan and UBSan runtimes).
MINENAV_PACKAGES=(build-essential cmake liblcm-dev liblcm-bin libeigen3-dev libgtest-dev
                  libgmock-dev zlib1g-dev libbz2-dev nlohmann-json3-dev iproute2 util-linux python3
                  libsystemd-dev librsvg2-bin libboost-dev chromium tmux clang-14 libclang-rt-14-dev
                  libsodium-dev pkg-config)

# minenav_install_missing PACKAGE...: apt-get installs those of the Debian packages not installed.
minenav_install_missing() {
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then return 0; fi
  echo "== installing missing Debian packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# Node.js and npm run the browser test (playwright-core) and the MCAP reader test (@mcap/core).
# A machine may have them from another source than Debian (NodeSource's nodejs bundles npm and
# conflicts with Debian's npm package): they are installed from Debian only when the commands
# are missing.
minenav_install_node() {
  if command -v node >/dev/null && command -v npm >/dev/null; then return 0; fi
  minenav_install_missing nodejs npm
}

minenav_install_deps() { minenav_install_missing "${MINENAV_PACKAGES[@]}"; minenav_install_node; }

# minenav_npm_ci DIR: the npm packages of DIR's committed package.json + package-lock.json,
# installed with `npm ci` only when DIR/node_modules is missing or older than the lockfile.
minenav_npm_ci() {
  local dir="$1"
  minenav_install_node
  # Tests that run at once (ctest -j) share DIR: one installs, the others wait for it.
  (
    flock 9
    if [ -f "$dir/node_modules/.package-lock.json" ] && ! [ "$dir/package-lock.json" -nt "$dir/node_modules/.package-lock.json" ]; then
      exit 0
    fi
    echo "== installing npm packages of $dir (npm ci)"
    cd "$dir" && npm ci --no-audit --no-fund --loglevel=error
  ) 9>"$dir/.npm-ci.lock"
}

# Only for bench/planner_ompl_bench (the planner against OMPL): the build and CI do not need
# them; CMake builds that bench only when it finds OMPL. Boost's dev packages are the ones
# OMPL's headers include and its CMake config asks for.
MINENAV_BENCH_PACKAGES=(libompl-dev libboost-filesystem-dev libboost-system-dev libboost-serialization-dev)
minenav_install_bench_deps() { minenav_install_missing "${MINENAV_BENCH_PACKAGES[@]}"; }

# minenav_build DIR [cmake args...] [-- targets...]   (no targets: everything)
minenav_build() {
  local dir="$1"; shift
  local args=() targets=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do args+=("$1"); shift; done
  [ "${1:-}" = "--" ] && { shift; targets=("$@"); }
  cmake -S "$MINENAV_ROOT" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${args[@]}" >/dev/null
  # MINENAV_NICE=N in the environment: the compile at that nice level (scripts/test.sh: the
  # sanitizer build beside the mission test).
  local nice_cmd=()
  [ -n "${MINENAV_NICE:-}" ] && nice_cmd=(nice -n "$MINENAV_NICE")
  if [ ${#targets[@]} -eq 0 ]; then
    "${nice_cmd[@]}" cmake --build "$dir" -j "$MINENAV_JOBS"
  else
    "${nice_cmd[@]}" cmake --build "$dir" -j "$MINENAV_JOBS" --target "${targets[@]}"
  fi
}
