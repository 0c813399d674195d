#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# hp on the reference scene (scripts/bench/bench_hp.f90): compiled here against the Release library
# of build/ (no CMake target), then run on a sequence of geometric meshes.
# Usage: scripts/bench/bench_hp.sh [--scene NAME] [SIGMA SLOPE P_MIN N_START LAYERS P_MAX ...]
# --scene: a scene of tests/data/truths.csv (scripts/lib/truth_scenes.sh) other than the
# square: starts from a plain Gmsh mesh of it (size 0.3; needs gmsh) instead of the square.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${NCEIG_BUILD:-$root/build}
source "$root/scripts/lib/bench_common.sh"
scene=
if [[ ${1:-} == --scene ]]; then
    scene=$2
    shift 2
fi
bench_program bench_hp
if [[ -n $scene ]]; then
    source "$root/scripts/lib/truth_scenes.sh"
    scene_info "$scene"
    [[ $kind == eigen ]] || { echo "bench_hp: scene $scene is not an eigen scene" >&2; exit 1; }
    gmsh "$geo" "${gset[@]}" -setnumber graded 0 -clmax 0.3 -2 -format msh41 \
        -o "$work/scene.msh" >"$work/gmsh.log" 2>&1 ||
        { cat "$work/gmsh.log" >&2; echo "bench_hp: gmsh failed" >&2; exit 1; }
    export HP_MESH=$work/scene.msh HP_CONTACT=$contact HP_POISSON=$nu HP_LAMBDA=$lam
    HP_TRUTH=$(awk -F, -v s="$scene" '$1 == s && $2 == "lowest_positive_mu" { print $3 }' \
               "$root/tests/data/truths.csv")
    export HP_TRUTH
fi
if (($# == 0)); then
    set -- 0.15 1.0 1 2 3 4 4 5 5 6 6 7 7 8 8 9 10 10 16 11
fi
OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} "$work/bench_hp" "$@"
