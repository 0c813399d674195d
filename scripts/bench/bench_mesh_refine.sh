#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Speed of mesh refinement (scripts/bench/bench_mesh_refine.f90): compiled here against the
# Release library of build/ (no CMake target, so the build files stay untouched), then run.
# Usage: scripts/bench/bench_mesh_refine.sh [TARGET_CELLS [FILE.msh]]   (default 1000000 cells)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${NCEIG_BUILD:-$root/build}
source "$root/scripts/lib/bench_common.sh"
bench_program bench_mesh_refine
"$work/bench_mesh_refine" "$@"
