#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The round-off error of the critical lambdas, measured, against its bound (summary.json
# lambda_critical_{plus,minus}_roundoff): the same discrete pencil in 6 roundings, young E
# in {1, 3.7, 0.61} x the size scaled by s in {1, 1.37}; lambda is dimensionless, so the
# values themselves are compared. Rectangle meshes (contact on the bottom, top fixed).
# Usage: scripts/dev/threshold_roundoff_spread.sh NCEIG NAME 'MESH' 'MATERIAL'
#   MESH: the &mesh body without width and height (set to s).
# Prints per side: NAME, lambda, spread (max - min) / |lambda|, the largest bound, the ratio.
set -u
nceig=$1 name=$2 mesh=$3 material=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run() {  # E S: one run; prints lambda+, its bound, lambda-, its bound
    printf '%s\n' "&mesh $mesh, width = $2, height = $2 /" "&material young = $1, $material /" \
        "&analysis kind = 'threshold', lambda = 5 /" "&eigen estimate = 'off' /" \
        "&output directory = '$work/out', vtk = .false., plot = .false. /" >"$work/in.nml"
    rm -rf "$work/out"
    "$nceig" "$work/in.nml" >"$work/stdout" 2>&1
    local j=$work/out/summary.json
    get() { sed -n "s/^ *\"$1\": *\([^,]*\),*$/\1/p" "$j" | head -n 1; }
    echo "$(get lambda_critical_plus) $(get lambda_critical_plus_roundoff)" \
        "$(get lambda_critical_minus) $(get lambda_critical_minus_roundoff)"
}

for e in 1 3.7 0.61; do
    for s in 1 1.37; do run $e $s; done
done >"$work/rows"
[[ -n ${ROUNDOFF_ROWS:-} ]] && cat "$work/rows" >&2
for side in plus minus; do
    col=$([[ $side == plus ]] && echo 1 || echo 3)
    awk -v name="$name" -v side="$side" -v c="$col" '
        { v[NR] = $c + 0; if ($(c + 1) + 0 > b) b = $(c + 1) + 0 }
        END { lo = v[1]; hi = v[1]; for (i in v) { if (v[i] < lo) lo = v[i]; if (v[i] > hi) hi = v[i] }
              spread = (hi - lo) / (v[1] < 0 ? -v[1] : v[1])
              printf "%-26s %-5s lambda %.15g  spread %.2e  bound %.2e  bound/spread %.3g\n",
                     name, side, v[1], spread, b, (spread > 0 ? b / spread : 0) }' "$work/rows"
done
