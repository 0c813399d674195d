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
# NCEIG_BEFORE (another executable, e.g. main's): each repeat runs it and NCEIG on the same
# input, in turn (each first every other repeat), so that both see the same load, and a
# second table gives, per scene, the levels, the p x p solves of the threshold run (the
# sum over its progress lines), the CPU medians of both, the ratios to c_n, and whether
# summary.json says the same but for times and solve counts ("same") or not ("differ",
# the differences on stderr).
# PHASES=1: per scene, the phase seconds of NCEIG's last c_n and threshold run step by step
# (each level, the check one degree higher, the report; scripts/bench/phase_table.awk). With
# an executable configured with -DNCEIG_CPU_TIMERS=ON these are CPU seconds, e.g.
#   cmake -S . -B build-cputime -DNCEIG_CPU_TIMERS=ON && cmake --build build-cputime -t nceig
#   NCEIG=build-cputime/nceig PHASES=1 bash scripts/bench/bench_thresholds.sh 3 1e-8
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

# input SCENE KIND OUT: the input of one run writing to OUT (progress lines on stdout)
input() {
    scene "$1"
    echo "&analysis kind = '$2', lambda = 5.0 /"
    echo "&sweep lambda_min = -20.0, lambda_max = 20.0, n_lambda = 401 /"
    echo "&adapt strategy = 'hp', tolerance = $tolerance /"
    echo "&eigen estimate = 'off' /"
    echo "&output directory = '$3', vtk = .false., plot = .false., progress = .true. /"
}

# run EXE OUT: one timed run of $work/in_OUT.nml; appends wall and CPU seconds to
# $work/OUT.times, its exit status to $work/OUT.rc, its stdout to $work/OUT.log
run() {
    local wall user system rc
    rm -rf "${work:?}/$2"
    set +e
    /usr/bin/time -f '%e %U %S' -o "$work/time" "$1" "$work/in_$2.nml" >"$work/$2.log" 2>&1
    rc=$?
    set -e
    read -r wall user system < <(tail -n 1 "$work/time")
    echo "$wall $(awk -v u="$user" -v s="$system" 'BEGIN { print u + s }')" >>"$work/$2.times"
    echo "$rc" >"$work/$2.rc"
}

# timed SCENE KIND: REPEATS runs of NCEIG (and NCEIG_BEFORE before each, where given) into
# $work/after (and $work/before); "median wall seconds (exit, levels)" of NCEIG's, exit and
# levels of the last run; the median CPU seconds in $cpu (NCEIG_BEFORE's in $cpu_before)
timed() {
    local i who
    for who in before after; do
        input "$1" "$2" "$work/$who" >"$work/in_$who.nml"
        rm -f "$work/$who.times"
    done
    for ((i = 0; i < repeats; i++)); do
        if [[ -z ${NCEIG_BEFORE:-} ]]; then
            run "$nceig" after
        elif ((i % 2 == 0)); then   # in turn, each first every other repeat
            run "$NCEIG_BEFORE" before
            run "$nceig" after
        else
            run "$nceig" after
            run "$NCEIG_BEFORE" before
        fi
    done
    cpu=$(awk '{ print $2 }' "$work/after.times" | median)
    [[ -z ${NCEIG_BEFORE:-} ]] || cpu_before=$(awk '{ print $2 }' "$work/before.times" | median)
    levels=$(jq -r '.adapt_levels // empty' "$work/after/summary.json" 2>/dev/null || true)
    echo "$(awk '{ print $1 }' "$work/after.times" | median) ($(cat "$work/after.rc"), ${levels:-?})"
}

# solves WHO: the p x p solves of the last run's progress lines
solves() {
    grep -o '([0-9]* p x p solves' "$work/$1.log" | awk '{ n += substr($1, 2) } END { print n + 0 }'
}

# same_values: summary.json of before and after alike but for times, solve counts and
# the input's name
same_values() {
    local filter='walk(if type == "object" then with_entries(select((.key | startswith("time_")
        or . == "input" or . == "boundary_n_evaluations") | not)) else . end)'
    if diff <(jq -S "$filter" "$work/before/summary.json") \
        <(jq -S "$filter" "$work/after/summary.json") >"$work/diff"; then
        echo same
    else
        echo differ
        cat "$work/diff" >&2
    fi
}

echo "hp threshold run against hp c_n run, tolerance $tolerance, median of $repeats (s)"
echo
echo '| scene | c_n: wall s (exit, levels) | thresholds: wall s (exit, levels) | ratio |' \
    'c_n: CPU s | thresholds: CPU s | CPU ratio |'
echo '|---|---|---|---|---|---|---|'
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
rows=()
for s in half_contact reference slanted; do
    timed "$s" eigen >"$work/row"
    cn=$(cat "$work/row") cn_cpu=$cpu cn_before=${cpu_before:-}
    cp "$work/after.log" "$work/phases_${s}_eigen.log"
    [[ -z ${NCEIG_BEFORE:-} ]] || cn_same=$(same_values)
    timed "$s" threshold >"$work/row"
    thr=$(cat "$work/row") thr_cpu=$cpu
    cp "$work/after.log" "$work/phases_${s}_threshold.log"
    echo "| $s | $cn | $thr | $(ratio "${thr%% *}" "${cn%% *}") | $cn_cpu | $thr_cpu |" \
        "$(ratio "$thr_cpu" "$cn_cpu") |"
    if [[ -n ${NCEIG_BEFORE:-} ]]; then
        row="| $s | $(jq -r .adapt_levels "$work/before/summary.json"), $levels |"
        row+=" $(solves before), $(solves after) | $cn_before, $cn_cpu |"
        row+=" $cpu_before, $thr_cpu | $(ratio "$cpu_before" "$cn_before"),"
        row+=" $(ratio "$thr_cpu" "$cn_cpu") | $cn_same, $(same_values) |"
        rows+=("$row")
    fi
done
if [[ -n ${NCEIG_BEFORE:-} ]]; then
    echo
    echo "NCEIG_BEFORE = $NCEIG_BEFORE against NCEIG = $nceig, run in turn (CPU s, medians)"
    echo
    echo '| scene | threshold levels: before, after | p x p solves: before, after |' \
        'c_n CPU: before, after | thresholds CPU: before, after | ratio: before, after |' \
        'summary.json c_n, thresholds |'
    echo '|---|---|---|---|---|---|---|'
    printf '%s\n' "${rows[@]}"
fi
if [[ -n ${PHASES:-} ]]; then
    for s in half_contact reference slanted; do
        for kind in eigen threshold; do
            echo
            echo "$s, kind = '$kind': seconds per step of the last run of $nceig"
            echo
            echo '| step | dofs | assembly | ordering + factor | contact blocks |' \
                'thresholds, round-off | p x p solves: n at p, s | eigen | rest | step |' \
                'so far |'
            echo '|---|---|---|---|---|---|---|---|---|---|---|'
            awk -f "$root/scripts/bench/phase_table.awk" "$work/phases_${s}_$kind.log"
        done
    done
fi
