#!/usr/bin/env bash
# Runs scripts/quickstart.lua under valgrind's memcheck with full leak
# checking, then prints valgrind's heap, leak and error summaries. Exits with
# status 1 on any invalid read or write, use of an uninitialised value, or
# memory definitely or possibly lost; "still reachable" memory (libraries'
# static state) is reported but allowed.
#   scripts/valgrind_quickstart.sh [build folder] [output folder]
# The build folder (default build/, the Release build of ./run.sh) holds
# bin/ashlar; a RelWithDebInfo build gives file:line in reports. The output
# folder receives the quickstart's files (default: a temporary folder,
# removed afterwards).
# It runs as ctest valgrind.quickstart in builds without the sanitizers.
set -euo pipefail

root=$(dirname "$(dirname "$(readlink -f "${BASH_SOURCE[0]}")")")
build=$(readlink -f "${1:-$root/build}")
ashlar=$build/bin/ashlar

command -v valgrind >/dev/null || { echo "valgrind_quickstart: valgrind is not installed (Debian: valgrind)" >&2; exit 2; }
[[ -x $ashlar ]] || { echo "valgrind_quickstart: no $ashlar: build first (./run.sh build)" >&2; exit 2; }
log=$(mktemp)
temporary=()
if (($# >= 2)); then
  out=$2
  mkdir -p "$out"
else
  out=$(mktemp -d)
  temporary=("$out")
fi
trap 'rm -rf "$log" "${temporary[@]}"' EXIT

status=0
valgrind --leak-check=full --error-exitcode=1 --num-callers=30 --log-file="$log" \
  "$ashlar" "$root/scripts/quickstart.lua" "$out" || status=$?

if ((status != 0)); then
  cat "$log"  # every error and lost block with its stack
else
  sed -n '/HEAP SUMMARY:/,$p' "$log" | sed 's/^==[0-9]*== \{0,1\}//'
fi
exit "$status"
