#!/usr/bin/env bash
# Sets up a Debian 12 machine for ashlar, builds it, and runs it.
#   ./run.sh build              install what is missing, build (Release) into build/
#   ./run.sh quickstart [dir]   build, then run scripts/quickstart.lua (output in dir, default build/out)
#   ./run.sh test [args]        build, run the test suite (args go to ctest), then the sanitizer suite
#   ./run.sh sanitize [args]    build with ASan+UBSan into build-sanitize/ and run the suite there
#   ./run.sh install PACKAGE... install the Debian packages that are missing (for scripts/fuzz.sh)
# Re-running is cheap: packages and the CMake configuration are only set up
# when missing, npm packages when missing or their lockfile is newer.
# ASHLAR_JOBS sets the build's parallelism.
set -euo pipefail

cd "$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")"

readonly DEBIAN_PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev liblua5.4-dev lua5.4 libsuitesparse-dev libopenblas0-pthread libcgal-dev libgmp-dev libmpfr-dev
  libassimp-dev liblbfgspp-dev libsqlite3-dev zlib1g-dev libopenmpi-dev openmpi-bin nlohmann-json3-dev coinor-libclp-dev coinor-libipopt-dev libcairo2-dev libplplot-dev plplot-driver-cairo
  libbullet-dev
  googletest libgtest-dev lua-busted valgrind libreadline-dev
  nodejs npm python3 python3-cvxopt python3-numpy python3-scipy chromium
)
# Node.js may come from outside Debian (NodeSource's nodejs bundles npm and
# conflicts with Debian's npm): for these a working command is enough.
declare -rA COMMAND_OF_PACKAGE=([nodejs]=node [npm]=npm)
readonly BUILD_DIR=build
readonly SANITIZE_DIR=build-sanitize

# Each line carries the time since run.sh started, so a CI log shows what
# each step took.
say() { printf 'run.sh [%d:%02d]: %s\n' $((SECONDS / 60)) $((SECONDS % 60)) "$*"; }

usage() {
  printf 'usage:\n' >&2
  sed -n '3,7s/^#//p' "${BASH_SOURCE[0]}" >&2
  exit 1
}

# The packages given (default: ashlar's) that are not installed.
missing_packages() {
  local package status command
  for package in "${@:-${DEBIAN_PACKAGES[@]}}"; do
    command=${COMMAND_OF_PACKAGE[$package]:-}
    [[ -n $command ]] && command -v "$command" >/dev/null && continue
    status=$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null || true)
    [[ $status == installed ]] || echo "$package"
  done
}

install_packages() {
  if ! command -v dpkg-query >/dev/null; then
    say "no dpkg-query: not a Debian system, assuming the build tools are installed"
    return
  fi
  local missing
  mapfile -t missing < <(missing_packages "$@")
  ((${#missing[@]} == 0)) && return
  say "installing ${missing[*]}"
  local as_root=()
  if ((EUID != 0)); then
    command -v sudo >/dev/null || { say "not root and no sudo: install ${missing[*]} by hand" >&2; exit 1; }
    as_root=(sudo)
  fi
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -q --no-install-recommends "${missing[@]}"
}

# npm packages, each folder at the versions its package-lock.json pins:
# web/ holds three.js, which the build embeds in the HTML viewer; tests/tools
# the glTF validator and puppeteer-core, which drives Debian's chromium in
# the viewer's tests (it never downloads a browser). A folder is installed
# again when its lockfile is newer than what npm last installed.
install_node_tools() {
  local folder
  for folder in web tests/tools; do
    [[ -f $folder/package-lock.json ]] || continue
    [[ $folder/package-lock.json -nt $folder/node_modules/.package-lock.json ]] || continue
    say "installing node packages in $folder"
    (cd "$folder" && npm ci --no-audit --no-fund)
  done
}

# build <dir> [cmake options]: configures <dir> once, then builds it.
build() {
  local dir=$1
  shift
  if [[ ! -f $dir/build.ninja ]]; then
    say "configuring $dir/"
    cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
  fi
  say "building $dir/"
  cmake --build "$dir" -j "${ASHLAR_JOBS:-$(nproc)}"
}

set_up_and_build() {
  install_packages
  install_node_tools
  build "$BUILD_DIR"
}

# The whole suite again, built with AddressSanitizer, LeakSanitizer and
# UndefinedBehaviorSanitizer: ctest sets their options (tests/CMakeLists.txt).
run_sanitized_tests() {
  build "$SANITIZE_DIR" -DASHLAR_SANITIZE=ON
  say "running the tests under the sanitizers"
  (cd "$SANITIZE_DIR" && ctest --output-on-failure -j2 "$@")
}

(($# >= 1)) || usage
mode=$1
shift
case $mode in
  build)
    set_up_and_build
    ;;
  quickstart)
    set_up_and_build
    out=${1:-$BUILD_DIR/out}
    mkdir -p "$out"
    say "running scripts/quickstart.lua (output in $out/)"
    exec "$BUILD_DIR/bin/ashlar" scripts/quickstart.lua "$out"
    ;;
  test)
    set_up_and_build
    say "running the tests"
    (cd "$BUILD_DIR" && ctest --output-on-failure -j2 "$@")
    run_sanitized_tests "$@"
    say "all tests passed"
    ;;
  install)
    install_packages "$@"
    ;;
  sanitize)
    install_packages
    install_node_tools
    run_sanitized_tests "$@"
    ;;
  *)
    usage
    ;;
esac
