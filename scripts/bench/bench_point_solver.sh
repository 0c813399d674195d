#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Where an adapted sweep's points should go dense (docs/studies.md, "Cost"): a table, not a test.
#   bash scripts/bench/bench_point_solver.sh [REPEATS]
# One adapted lambda_sweep (the 2 x 1 rectangle, nu = 0.3, 41 lambdas from -20 to 20, hp to
# 1e-8, c_n alone), run on one BLAS thread with &eigen dense_max_contact = N for each N of
# LIMITS: every level (and the check one degree higher) with at most N contact functions
# solves its points densely (all eigenvalues of the p x p matrix, one certificate), the others
# with the certified ARPACK search. Consecutive rows differ by the levels of the 'dense p'
# column that changed solver, so the change of CPU between two rows is what those levels'
# points cost densely against ARPACK. REPEATS (default 3) runs per N, the median quoted.
# NCEIG (default build/nceig) is the program; GNU time is needed (/usr/bin/time).
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
repeats=${1:-3}
limits=${LIMITS:-1 24 40 60 80 115 155 190 240}
[[ -x /usr/bin/time ]] || { echo "bench_point_solver: GNU time (/usr/bin/time) is needed" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/sweep.nml" <<EOF
&mesh source = 'rectangle', width = 2.0, height = 1.0, nx = 2, ny = 2, element = 'p1' /
&material young = 1.0, poisson = 0.3 /
&analysis kind = 'lambda_sweep' /
&adapt tolerance = 1e-8, strategy = 'hp' /
&output directory = 'out', vtk = .false., plot = .false., progress = .false. /
&sweep lambda_min = -20.0, lambda_max = 20.0, n_lambda = 41, adapt_thresholds = .false. /
EOF
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# The contact functions of the climb's levels: the same climb with its thresholds adapted
# writes them (adapt.csv, n_contact); the check one degree higher is not listed.
(cd "$work" && OPENBLAS_NUM_THREADS=1 "$nceig" sweep.nml --set sweep%adapt_thresholds=.true. \
    --set output%directory=levels >/dev/null 2>&1)
levels=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "n_contact") c = i; next }
    c && !seen[$c]++ { print $c }' "$work/levels/adapt.csv" 2>/dev/null)
echo "adapted sweep, 2 x 1 rectangle, nu 0.3, 41 lambdas, hp to 1e-8; medians of $repeats; load $(cut -d' ' -f1-3 /proc/loadavg)"
printf '| %17s | %-34s | %9s | %11s |\n' dense_max_contact "dense p (levels)" "CPU" "exit status"
printf '|%s|%s|%s|%s|\n' "-------------------" "------------------------------------" "-----------" "-------------"
for n in $limits; do
    cpus=()
    for ((r = 1; r <= repeats; r++)); do
        rm -rf "$work/out"
        (cd "$work" && OPENBLAS_NUM_THREADS=1 /usr/bin/time -f '%U %S' -o "$work/cpu" "$nceig" \
            sweep.nml --set "eigen%dense_max_contact=$n" >/dev/null 2>&1)
        status=$?
        cpus+=("$(awk '/^[0-9.]+ [0-9.]+$/ { printf "%.2f", $1 + $2 }' "$work/cpu")")
    done
    dense=$(awk -v n="$n" '$1 <= n { printf "%s%s", sep, $1; sep = " " }' <<<"$levels")
    printf '| %17s | %-34s | %7s s | %11s |\n' "$n" "${dense:--}" \
        "$(printf '%s\n' "${cpus[@]}" | median)" "$status"
done
