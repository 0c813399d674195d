#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# hp on the reference scene (scripts/bench_hp.f90): compiled here against the Release library
# of build/ (no CMake target), then run on a sequence of geometric meshes.
# Usage: scripts/bench_hp.sh [SIGMA SLOPE P_MIN N_START LAYERS P_MAX [LAYERS P_MAX ...]]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${NCEIG_BUILD:-$root/build}
source "$root/scripts/lib/bench_common.sh"
bench_program bench_hp
if (($# == 0)); then
    set -- 0.15 1.0 1 2 3 4 4 5 5 6 6 7 7 8 8 9 10 10 16 11
fi
OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} "$work/bench_hp" "$@"
