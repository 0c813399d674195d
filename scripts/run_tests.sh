#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Quick start 2: install what is missing, then build and run the whole test suite in Release
# and in Debug (-fcheck=all, floating-point traps).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install_deps.sh"
status=0
for type in Release Debug; do
    bash "$root/scripts/build.sh" "$type"
    folder="$root/build"
    [[ $type == Release ]] || folder="$root/build-debug"
    echo "== ctest ($type)"
    ctest --test-dir "$folder" --output-on-failure -j "$(nproc)" || status=1
done
exit $status
