#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The extremes table: runs nceig over extreme cases (material, size, lambda, thresholds,
# mesh size, cell shape) and prints a markdown table of what it returns: the lowest positive
# mu, its condition number and backward error, the worst backward error of the spectrum, the
# real mu of largest modulus, and the warnings. Usage: scripts/dev/extremes_table.sh [NCEIG]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${1:-$root/build/nceig}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

value() { jq -r --arg key "$1" '.[$key] | tostring' "$work/out/summary.json"; }   # null if absent
short() { [[ $1 == null ]] && echo '-' || awk -v x="$1" 'BEGIN { printf "%.3g", x }'; }

# solve NAME MESH MATERIAL ANALYSIS: one run into $work/out
solve() {
    cat >"$work/case.nml" <<NML
&mesh $2 /
&material $3 /
&analysis $4 /
&eigen solver = 'dense' /
&output directory = '$work/out', vtk = .false. /
NML
    rm -rf "$work/out"
    "$nceig" "$work/case.nml" >"$work/stdout" 2>&1
}

row() {  # NAME MESH MATERIAL ANALYSIS
    solve "$@"
    local largest warnings
    largest=$(awk -F, 'NR > 1 && $4 != "complex" { a = $2 < 0 ? -$2 : $2; if (a > m) { m = a; v = $2 } }
                       END { printf "%.3g", v }' "$work/out/eigenvalues.csv")
    warnings=$( { grep '^warning:' "$work/stdout" || true; } | sed 's/^warning: //; s/[:(].*//' | paste -sd ';' -)
    echo "| $1 | $(short "$(value lowest_positive_mu)") | $(short "$(value lowest_positive_condition)") |" \
         "$(short "$(value lowest_positive_residual)") | $(short "$(value max_residual)") |" \
         "$largest | ${warnings:--} |"
}

has_positive() {  # LAMBDA: does the 8 x 8 P1 reference scene have a positive mu?
    solve probe "nx = 8, ny = 8" "" "lambda = $1"
    [[ $(value lowest_positive_mu) != null ]]
}

threshold() {  # INSIDE OUTSIDE: bisection between a lambda without and one with a positive mu
    local inside=$1 outside=$2 middle
    for _ in $(seq 60); do
        middle=$(awk -v a="$inside" -v b="$outside" 'BEGIN { printf "%.17g", (a + b) / 2 }')
        if has_positive "$middle"; then outside=$middle; else inside=$middle; fi
    done
    echo "$outside"
}

echo '| case | lowest positive mu | condition | backward error | max backward error | largest real mu | warnings |'
echo '|---|---|---|---|---|---|---|'
ref="nx = 8, ny = 8"
row 'reference, 8 x 8 p1' "$ref" "" ""
for young in 1e-6 1e9 1e-300 1e300; do row "E = $young" "$ref" "young = $young" ""; done
for size in 1e-3 1e3 1e-300 1e300; do row "size $size" "$ref, width = $size, height = $size" "" ""; done
for nu in 0 0.49 0.4999 0.499999; do
    for element in p1 q1 q2; do
        row "nu = $nu, $element" "$ref, element = '$element'" "poisson = $nu" ""
    done
done
for lambda in 1e4 1e8 -1e8 1e160 1e300; do row "lambda = $lambda" "$ref" "" "lambda = $lambda"; done
plus=$(threshold 0 5)
minus=$(threshold 0 -5)
for lc in "$plus" "$minus"; do
    for side in 1 -1; do
        lambda=$(awk -v c="$lc" -v s="$side" 'BEGIN { printf "%.17g", c * (1 + s * 1e-6) }')
        row "lambda_c $(short "$lc") $( [[ $side == 1 ]] && echo '+' || echo '-') 1e-6 rel." \
            "$ref" "" "lambda = $lambda"
    done
done
for cells in 1 128; do
    for element in p1 q2; do
        row "$cells x $cells $element" "nx = $cells, ny = $cells, element = '$element'" "" ""
    done
done
row 'cells 1000:1 (1000 x 1 q2)' "nx = 1000, ny = 1, element = 'q2'" "" ""
row 'cells 1000:1 (1000 x 1 p1)' "nx = 1000, ny = 1" "" ""
row 'cells 1:1000 (1 x 1000 p1)' "nx = 1, ny = 1000" "" ""
row 'cells 1:100 (10 x 1000 q1)' "nx = 10, ny = 1000, element = 'q1'" "" ""
