#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# What an hp threshold run costs against an hp c_n run at the same tolerance, on the same
# start mesh (issue 34: the thresholds should cost at most twice c_n). Scenes:
#   half_contact  input/half_contact.nml's body (contact on half the bottom; both
#                 mechanisms of the boundary of the positive set) from a P1 Delaunay mesh
#                 of size 1/4 (meshes/half_contact.geo)
#   reference     the unit square (top clamped, contact on the bottom, nu = 0.3) from 2 x 2
#                 P1 squares
#   slanted       tests/data/bodies/slanted.geo (nu = 0.1) from a P1 Delaunay mesh of size 1/8
# Each run: &adapt strategy = 'hp', the tolerance, &eigen estimate off, no pictures, no VTK;
# c_n at &analysis lambda, the thresholds with the boundary searched over [-20, 20] (401
# points, the &sweep default of half_contact.nml). Wall and CPU (user + system) time from
# /usr/bin/time, medians of REPEATS runs; the exit status and the levels of the last run.
# On a machine shared with other jobs the wall times follow the load; the CPU times and
# their ratio much less.
# Usage: scripts/bench/bench_thresholds.sh [REPEATS] [TOLERANCE]   (defaults: 3, 1e-8)
# Environment: NCEIG (executable, default build/nceig). Needs gmsh, jq and GNU time.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
source "$root/scripts/lib/bench_common.sh"
bench_begin bench_thresholds "${1:-3}"
tolerance=${2:-1e-8}
command -v jq >/dev/null || { echo "bench_thresholds: needs jq" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "bench_thresholds: needs gmsh" >&2; exit 1; }

gmsh "$root/input/meshes/half_contact.geo" -2 -order 1 -clmax 0.25 -format msh41 \
    -o "$work/half.msh" >/dev/null
gmsh "$root/tests/data/bodies/slanted.geo" -2 -order 1 -clmax 0.125 -format msh41 \
    -o "$work/slanted.msh" >/dev/null

# scene NAME: the &mesh and &material groups of the scene
scene() {
    case $1 in
        half_contact) echo "&mesh source = 'gmsh', file = '$work/half.msh', dirichlet = 'top',
      neumann = 'left right bottom_free', contact = 'contact' /" ;;
        reference) echo "&mesh nx = 2, ny = 2, element = 'p1' /" ;;
        slanted) echo "&mesh source = 'gmsh', file = '$work/slanted.msh', dirichlet = 'top',
      neumann = 'left right', contact = 'contact' /
&material poisson = 0.1 /" ;;
    esac
}

# timed SCENE KIND: "median wall seconds (exit, levels)" of REPEATS runs, exit and levels
# of the last one; the median CPU seconds in $cpu
timed() {
    local times=() cpus=() i
    {
        scene "$1"
        echo "&analysis kind = '$2', lambda = 5.0 /"
        echo "&sweep lambda_min = -20.0, lambda_max = 20.0, n_lambda = 401 /"
        echo "&adapt strategy = 'hp', tolerance = $tolerance /"
        echo "&eigen estimate = 'off' /"
        echo "&output directory = '$work/out', vtk = .false., plot = .false., progress = .false. /"
    } >"$work/in.nml"
    for ((i = 0; i < repeats; i++)); do
        rm -rf "$work/out"
        set +e
        /usr/bin/time -f '%e %U %S' -o "$work/time" "$nceig" "$work/in.nml" >/dev/null 2>&1
        rc=$?
        set -e
        read -r wall user system < <(tail -n 1 "$work/time")
        times+=("$wall")
        cpus+=("$(awk -v u="$user" -v s="$system" 'BEGIN { print u + s }')")
    done
    levels=$(jq -r '.adapt_levels // empty' "$work/out/summary.json" 2>/dev/null || true)
    cpu=$(echo "${cpus[*]}" | median)
    echo "$(echo "${times[*]}" | median) ($rc, ${levels:-?})"
}

echo "hp threshold run against hp c_n run, tolerance $tolerance, median of $repeats (s)"
echo
echo '| scene | c_n: wall s (exit, levels) | thresholds: wall s (exit, levels) | ratio |' \
    'c_n: CPU s | thresholds: CPU s | CPU ratio |'
echo '|---|---|---|---|---|---|---|'
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
for s in half_contact reference slanted; do
    timed "$s" eigen >"$work/row"
    cn=$(cat "$work/row") cn_cpu=$cpu
    timed "$s" threshold >"$work/row"
    thr=$(cat "$work/row") thr_cpu=$cpu
    echo "| $s | $cn | $thr | $(ratio "${thr%% *}" "${cn%% *}") | $cn_cpu | $thr_cpu |" \
        "$(ratio "$thr_cpu" "$cn_cpu") |"
done
