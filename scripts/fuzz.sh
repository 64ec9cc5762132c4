#!/usr/bin/env bash
# Fuzzes the mesh importer, the structure JSON reader and the Lua API's
# argument checking with libFuzzer, one target after another.
#   scripts/fuzz.sh [seconds-per-target [target...]]
# Targets: mesh_import structure_json lua_api (default: all, 600 s each).
# Installs clang-14 and libclang-rt-14-dev when missing (the other build
# dependencies come with ./run.sh build), builds build-fuzz/ (clang,
# AddressSanitizer, UBSan, libFuzzer), fuzzes each target from its corpus
# tests/fuzz/corpus/<target>/ and merges the fewest new inputs that add
# coverage back into it. Crashes, timeouts and leaks go to ASHLAR_FUZZ_ARTIFACTS
# (default /tmp/ashlar-fuzz)/<target>/, outside the tree. Exits non-zero when
# a target found one.
set -euo pipefail

cd "$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")/.."

readonly BUILD_DIR=build-fuzz
readonly CLANG_PACKAGES=(clang-14 libclang-rt-14-dev)
readonly ALL_TARGETS=(mesh_import structure_json lua_api)
ARTIFACTS=$(realpath -m "${ASHLAR_FUZZ_ARTIFACTS:-/tmp/ashlar-fuzz}")
readonly ARTIFACTS
# Longest input per target: enough for a small mesh or structure file or a
# couple of dozen API calls, and small enough to keep the corpus small.
declare -rA MAX_LENGTH=([mesh_import]=4096 [structure_json]=4096 [lua_api]=512)
# An input of the Lua target is a program of up to 24 calls: at full length
# from the start (not grown slowly from a few bytes), each input makes many
# calls and the corpus needs fewer inputs.
declare -rA LENGTH_CONTROL=([mesh_import]=100 [structure_json]=100 [lua_api]=0)
# Seconds one input may take before it counts as a hang.
readonly INPUT_TIMEOUT=20

say() { printf 'fuzz.sh: %s\n' "$*"; }

# run.sh knows how to install Debian packages (as root or through sudo).
install_clang() { ./run.sh install "${CLANG_PACKAGES[@]}"; }

build() {
  if [[ ! -f $BUILD_DIR/build.ninja ]]; then
    say "configuring $BUILD_DIR/"
    CC=clang-14 CXX=clang++-14 cmake -S . -B "$BUILD_DIR" -G Ninja \
      -DCMAKE_BUILD_TYPE=RelWithDebInfo -DASHLAR_FUZZ=ON
  fi
  say "building"
  local targets=()
  for target in "$@"; do targets+=(--target "fuzz_$target"); done
  cmake --build "$BUILD_DIR" -j "${ASHLAR_JOBS:-$(nproc)}" "${targets[@]}"
}

# Fuzzes one target for $1 seconds; new inputs collect in a scratch folder
# first, so that only the ones that add coverage reach the corpus.
fuzz() {
  local seconds=$1 target=$2
  local program=$BUILD_DIR/tests/fuzz/fuzz_$target
  local corpus=tests/fuzz/corpus/$target
  local artifacts=$ARTIFACTS/$target
  local new_inputs log
  new_inputs=$(mktemp -d "/tmp/ashlar-fuzz-$target-new-XXXXXX")
  log=$artifacts/fuzz.log
  mkdir -p "$corpus" "$artifacts"
  say "$target: fuzzing for $seconds s (log: $log)"
  local found_before started=$SECONDS
  found_before=$(find "$artifacts" -type f ! -name fuzz.log | wc -l)
  # One worker process that is restarted after a crash, so that a run finds
  # every problem it can in its time instead of stopping at the first.
  "$program" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -max_total_time="$seconds" -timeout="$INPUT_TIMEOUT" -max_len="${MAX_LENGTH[$target]}" \
    -len_control="${LENGTH_CONTROL[$target]}" \
    -artifact_prefix="$artifacts/" "$new_inputs" "$corpus" >"$log" 2>&1 || true
  local elapsed=$((SECONDS - started)) before after found
  before=$(find "$corpus" -type f | wc -l)
  # The fewest new inputs that reach every branch the run reached (counting
  # branches taken, not how often), added to the corpus.
  "$program" -set_cover_merge=1 -use_counters=0 -max_len="${MAX_LENGTH[$target]}" \
    -artifact_prefix="$artifacts/merge-" \
    "$corpus" "$new_inputs" >>"$log" 2>&1 || true
  after=$(find "$corpus" -type f | wc -l)
  rm -rf "$new_inputs"
  local runs
  runs=$(sed -n 's/^#\([0-9]*\): cov:.*/\1/p' "$log" | tail -1)
  say "$target: ${runs:-?} executions in $elapsed s; corpus $before -> $after files"
  found=$(($(find "$artifacts" -type f ! -name fuzz.log | wc -l) - found_before))
  if ((found > 0)); then
    say "$target: FOUND $found PROBLEM INPUT(S) in $artifacts/:" >&2
    grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error|.*CHECK failed)' "$log" | sort | uniq -c | head -10 >&2 || true
    return 1
  fi
}

main() {
  local seconds=${1:-600}
  [[ $seconds =~ ^[0-9]+$ ]] || { sed -n '3,4s/^# //p' "${BASH_SOURCE[0]}" >&2; exit 1; }
  shift || true
  local targets=("$@") target
  ((${#targets[@]} > 0)) || targets=("${ALL_TARGETS[@]}")
  for target in "${targets[@]}"; do
    [[ -v MAX_LENGTH[$target] ]] || { say "unknown target '$target' (known: ${ALL_TARGETS[*]})" >&2; exit 1; }
  done
  install_clang
  build "${targets[@]}"
  local failed=0
  for target in "${targets[@]}"; do
    fuzz "$seconds" "$target" || failed=1
  done
  return "$failed"
}

main "$@"
