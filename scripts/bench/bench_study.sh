#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The cost of a study (docs/studies.md, "Cost"): a table, not a test.
#   bash scripts/bench/bench_study.sh [REPEATS]
# The study: the rectangle at widths 1 and 2 and input/meshes/trapezoid.geo, NU (default five
# Poisson ratios), N_LAMBDA lambdas from -20 to 20 (default 41), c_n and both thresholds, hp
# to TOL (default 1e-8); every size can be made smaller through the environment:
#   NU='0.1 0.3' N_LAMBDA=11 TOL=1e-6 bash scripts/bench/bench_study.sh 1
# It measures, REPEATS times (default 3; medians quoted):
#   study CPU     user + system CPU of `nceig-study -j 1` and everything it started
#   tasks CPU     the sum of its nceig runs' CPU (the hp climbs and their dense solves)
#   per point     one nceig run per point instead: kind 'eigen' per (geometry, nu, lambda),
#                 plus one 'threshold' run per (geometry, nu) (the task's input, its kind
#                 changed, the sweep's lambdas as the boundary search), CPU summed; each
#                 on one thread in the environment of a study's task
#   wall -j1, -j2 the study's wall time on one and on two jobs (fresh folders each)
# NCEIG (default build/nceig) is the program; GNU time is needed (/usr/bin/time).
# NCEIG_BEFORE, another nceig (say the program before a change, with its nceig-study-plan
# beside it): its study is run too, right before NCEIG's in every repeat, and its column
# printed beside (the per-point runs are NCEIG's alone).
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
export NCEIG=${NCEIG:-$root/build/nceig}
repeats=${1:-3}
nu_list=${NU:-0.1 0.2 0.3 0.4 0.45}
n_lambda=${N_LAMBDA:-41}
tol=${TOL:-1e-8}
[[ -x /usr/bin/time ]] || { echo "bench_study: GNU time (/usr/bin/time) is needed" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$root/input/meshes/trapezoid.geo" "$work/"
cat >"$work/bench.nml" <<EOF
&study
    geometry = 'rectangle', 'trapezoid.geo'
    widths = 1.0, 2.0
    poisson = $(echo "$nu_list" | sed 's/ /, /g')
    lambda_min = -20.0, lambda_max = 20.0, n_lambda = $n_lambda
/
&mesh nx = 2, ny = 2, element = 'p1' /
&adapt tolerance = $tol, strategy = 'hp' /
&output progress = .false. /
EOF
study=$root/scripts/nceig-study

# cpu_of FILE: user + system seconds from a GNU time output '%e %U %S'
cpu_of() { awk '!/^Command/ { printf "%.2f", $2 + $3 }' "$1"; }
wall_of() { awk '!/^Command/ { printf "%.2f", $1 }' "$1"; }
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

declare -a study_cpu tasks_cpu point_cpu wall1 wall2 before_study before_tasks before_wall1 \
    before_wall2
# study_runs NCEIG: the study on one job then two (fresh folders), its CPU and wall times
study_runs() {
    rm -rf "$work/j1" "$work/j2"
    NCEIG=$1 /usr/bin/time -f '%e %U %S' -o "$work/t1" bash "$study" -j 1 -o "$work/j1" \
        "$work/bench.nml" >/dev/null 2>"$work/j1.err"
    NCEIG=$1 /usr/bin/time -f '%e %U %S' -o "$work/t2" bash "$study" -j 2 -o "$work/j2" \
        "$work/bench.nml" >/dev/null 2>"$work/j2.err"
    run_cpu=$(cpu_of "$work/t1")
    run_wall1=$(wall_of "$work/t1")
    run_wall2=$(wall_of "$work/t2")
    run_tasks=$(cat "$work"/j1/tasks/*/result | sed -n 's/^[a-z]*_cpu=//p' | awk '{ s += $1 } END { printf "%.2f", s }')
}
for ((r = 1; r <= repeats; r++)); do
    if [[ -n ${NCEIG_BEFORE:-} ]]; then
        study_runs "$NCEIG_BEFORE"
        before_study+=("$run_cpu")
        before_tasks+=("$run_tasks")
        before_wall1+=("$run_wall1")
        before_wall2+=("$run_wall2")
    fi
    rm -rf "$work/points"
    study_runs "$NCEIG"
    study_cpu+=("$run_cpu")
    tasks_cpu+=("$run_tasks")
    wall1+=("$run_wall1")
    wall2+=("$run_wall2")
    # One nceig run per point, from the study's own task inputs, on one thread as a task's
    # runs are (the same environment: like with like).
    one_thread=(env OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1)
    : >"$work/points.cpu"
    for task in "$work"/j1/tasks/*/; do
        while read -r lambda; do
            (cd "$task" && "${one_thread[@]}" /usr/bin/time -f '%e %U %S' -a \
                -o "$work/points.cpu" "$NCEIG" cn.nml --set analysis%kind=eigen \
                --set "analysis%lambda=$lambda" --set sweep%adapt_thresholds=.false. \
                --set output%directory=point --set output%vtk=.false. >/dev/null 2>&1)
        done <"$work/j1/plan/lambdas"
        (cd "$task" && "${one_thread[@]}" /usr/bin/time -f '%e %U %S' -a \
            -o "$work/points.cpu" "$NCEIG" cn.nml --set analysis%kind=threshold \
            --set sweep%adapt_thresholds=.false. --set output%directory=point_thr >/dev/null 2>&1)
    done
    point_cpu+=("$(grep -v '^Command' "$work/points.cpu" | awk '{ s += $2 + $3 } END { printf "%.2f", s }')")
done
n_tasks=$(wc -l <"$work/j1/plan/tasks")
n_points=$((n_tasks * $(wc -l <"$work/j1/plan/lambdas")))
sc=$(printf '%s\n' "${study_cpu[@]}" | median)
tc=$(printf '%s\n' "${tasks_cpu[@]}" | median)
pc=$(printf '%s\n' "${point_cpu[@]}" | median)
w1=$(printf '%s\n' "${wall1[@]}" | median)
w2=$(printf '%s\n' "${wall2[@]}" | median)
echo "study: 3 geometries x $(wc -w <<<"$nu_list") nu x $n_lambda lambdas ($n_tasks tasks, $n_points c_n points), hp to $tol; medians of $repeats; load $(cut -d' ' -f1-3 /proc/loadavg)"
ratio() { awk -v a="$1" -v b="$2" -v f="$3" 'BEGIN { printf f, a / b }'; }
# row NAME VALUE [BEFORE]: a line of the table, the before column when NCEIG_BEFORE is set
row() {
    if [[ -n ${NCEIG_BEFORE:-} ]]; then
        printf '| %-34s | %12s | %12s |\n' "$1" "$3" "$2"
    else
        printf '| %-34s | %12s |\n' "$1" "$2"
    fi
}
if [[ -n ${NCEIG_BEFORE:-} ]]; then
    bsc=$(printf '%s\n' "${before_study[@]}" | median)
    btc=$(printf '%s\n' "${before_tasks[@]}" | median)
    bw1=$(printf '%s\n' "${before_wall1[@]}" | median)
    bw2=$(printf '%s\n' "${before_wall2[@]}" | median)
    printf '| %-34s | %12s | %12s |\n' quantity "NCEIG_BEFORE" NCEIG
    printf '|%s|%s|%s|\n' "------------------------------------" "--------------" "--------------"
else
    bsc=1 btc=1 bw1=1 bw2=1
    printf '| %-34s | %12s |\n' quantity value
    printf '|%s|%s|\n' "------------------------------------" "--------------"
fi
row "study CPU (-j 1, all processes)" "$sc s" "$bsc s"
row "sum of its nceig runs' CPU" "$tc s" "$btc s"
row "study / its runs" "$(ratio "$sc" "$tc" %.2f)" "$(ratio "$bsc" "$btc" %.2f)"
row "one nceig run per point, CPU" "$pc s" "$pc s"
row "per point / study" "$(ratio "$pc" "$sc" %.1f)" "$(ratio "$pc" "$bsc" %.1f)"
row "wall -j 1" "$w1 s" "$bw1 s"
row "wall -j 2" "$w2 s" "$bw2 s"
row "speed-up -j 2 / -j 1" "$(ratio "$w1" "$w2" %.2f)" "$(ratio "$bw1" "$bw2" %.2f)"
