#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Speed of mesh refinement (scripts/bench/bench_mesh_refine.f90): compiled here against the
# Release library of build/ (no CMake target, so the build files stay untouched), then run.
# Usage: scripts/bench/bench_mesh_refine.sh [TARGET_CELLS [FILE.msh]]   (default 1000000 cells)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${NCEIG_BUILD:-$root/build}
[[ -f $build/libnceig_lib.a ]] ||
    { echo "bench_mesh_refine: build first (scripts/dev/build.sh Release)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The link line of a test program, minus its own object and the test library.
libs=$(sed -e 's/^.* -o [^ ]* *//' -e 's/libnceig_testing.a//' \
       -e "s#\.\./libnceig_lib.a#$build/libnceig_lib.a#" \
       "$build/tests/CMakeFiles/test_mesh_refine.dir/link.txt")
gfortran -O3 -std=f2008 -Wall -Wextra -fimplicit-none -I "$build/modules" \
    "$root/scripts/bench/bench_mesh_refine.f90" -o "$work/bench_mesh_refine" $libs
"$work/bench_mesh_refine" "$@"
