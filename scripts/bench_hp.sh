#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# hp on the reference scene (scripts/bench_hp.f90): compiled here against the Release library
# of build/ (no CMake target), then run on a sequence of geometric meshes.
# Usage: scripts/bench_hp.sh [SIGMA SLOPE P_MIN N_START LAYERS P_MAX [LAYERS P_MAX ...]]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${NCEIG_BUILD:-$root/build}
[[ -f $build/libnceig_lib.a ]] ||
    { echo "bench_hp: build first (scripts/build.sh Release)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The link line of a test program, minus its own object and the test library.
libs=$(sed -e 's/^.* -o [^ ]* *//' -e 's/libnceig_testing.a//' \
       -e "s#\.\./libnceig_lib.a#$build/libnceig_lib.a#" \
       "$build/tests/CMakeFiles/test_mesh_refine.dir/link.txt")
gfortran -O3 -std=f2008 -Wall -Wextra -fimplicit-none -I "$build/modules" \
    "$root/scripts/bench_hp.f90" -o "$work/bench_hp" $libs
if (($# == 0)); then
    set -- 0.15 1.0 1 2 3 4 4 5 5 6 6 7 7 8 8 9 10 10 16 11
fi
OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} "$work/bench_hp" "$@"
