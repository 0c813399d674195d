#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Configure and build one configuration:
#     scripts/dev/build.sh [Release|Debug|Asan] [--target TARGET] [cmake args]
# The build folder is build/ for Release, build-debug/ for Debug and build-asan/ for Asan
# (Debug flags at -O1 plus -fsanitize=address,undefined: NCEIG_SANITIZE=ON). --target builds one
# target (nceig: the program alone, without the test programs); default: everything.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
type=${1:-Release}
shift || true
targets=()
if [[ ${1:-} == --target ]]; then
    targets=(--target "$2")
    shift 2
fi
folder="$root/build"
[[ $type == Release ]] || folder="$root/build-$(echo "$type" | tr '[:upper:]' '[:lower:]')"
if [[ $type == Asan ]]; then
    type=Debug
    set -- -DNCEIG_SANITIZE=ON "$@"
fi
cmake -S "$root" -B "$folder" -DCMAKE_BUILD_TYPE="$type" "$@" >/dev/null
# Only diagnostics (the compilers' 'Warning:', 'error:', make's '***'), not file names that
# contain the word (error_estimate.f90). gfortran gives the place on a line of its own
# ('src/x.f90:413:21:') a few lines above its 'Warning:' line: it is printed before it.
cmake --build "$folder" -j "$(nproc)" "${targets[@]}" 2>&1 | awk '
    /^[^ ].*:[0-9]+:[0-9]+:$/ { place = $0; next }
    /(^|[ :])([Ww]arning|[Ee]rror):|\*\*\*|CMake Error/ {
        if (/^(Warning|Error):/ && place != "") print place
        print; place = ""
    }'
test -x "$folder/nceig"
