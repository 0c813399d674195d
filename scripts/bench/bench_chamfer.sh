#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The chamfered block of issue 34 (tests/data/bodies/chamfer.geo: 2 x 1, its bottom-right
# corner cut 0.3 x 0.3, contact on (0,0)-(1.7,0), top clamped) as an hp threshold run to
# 1e-8 from a P1 Delaunay mesh of size 1 and of size 1/4, at each Poisson ratio: the wall
# time of one run, its exit status and levels, and per side the value, its relative bar
# and the run's word on it (the side's clause of summary.json's adapt_outcome: met, none,
# or why it does not converge). The target: each run within a minute, each side with a bar
# or named as not converging with the reason.
# Usage: scripts/bench/bench_chamfer.sh [NU ...]   (default: 0.1 0.2 0.3 0.4 0.45)
# Environment: NCEIG (executable, default build/nceig), SIZES (default "1 4": 1/size).
# Needs gmsh, jq and GNU time.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
source "$root/scripts/lib/bench_common.sh"
bench_begin bench_chamfer 1
nus=("$@")
((${#nus[@]} > 0)) || nus=(0.1 0.2 0.3 0.4 0.45)
command -v jq >/dev/null || { echo "bench_chamfer: needs jq" >&2; exit 1; }

# side JSON SIGN LABEL: "value (bar): clause" of one side from summary.json, the clause
# being the side's part of adapt_outcome (met, none, or why it does not converge)
side() {
    local value bar why
    IFS=$'\t' read -r value bar why < <(jq -r --arg s "$2" --arg l "$3" '
        [(.["lambda_critical_" + $s] // "none" | tostring),
         (.["lambda_critical_" + $s + "_error_bar"] // "none" | tostring),
         (.adapt_outcome // "" | split("; ") | map(select(startswith($l + ":")))
             | map(.[($l | length) + 2:]) | join("; ") | if . == "" then "-" else . end)]
        | @tsv' "$1")
    [[ $value == none ]] || value=$(printf '%.10f' "$value")
    [[ $bar == none ]] && bar='no bar' || bar=$(printf 'bar %.1e' "$bar")
    echo "$value ($bar): $why"
}

echo "chamfered block, hp thresholds to 1e-8, P1 start meshes (wall and CPU seconds)"
echo
echo '| size | nu | wall s | CPU s | exit | levels |' \
    'lambda- (bar): the run says | lambda+ (bar): the run says |'
echo '|---|---|---|---|---|---|---|---|'
for n in ${SIZES:-1 4}; do
    bash "$root/scripts/make_mesh.sh" "$n" 1 "$work/chamfer_$n.msh" msh41 \
        "$root/tests/data/bodies/chamfer.geo"
    for nu in "${nus[@]}"; do
        out=$work/out_${n}_$nu
        cat >"$work/in.nml" <<EOF
&mesh source = 'gmsh', file = '$work/chamfer_$n.msh', dirichlet = 'top',
      neumann = 'left right chamfer', contact = 'contact' /
&material poisson = $nu /
&analysis kind = 'threshold', lambda = 5.0 /
&adapt tolerance = 1e-8, strategy = 'hp' /
&eigen estimate = 'off' /
&output directory = '$out', vtk = .false., plot = .false., progress = .false. /
EOF
        set +e
        /usr/bin/time -f '%e %U %S' -o "$work/time" "$nceig" "$work/in.nml" >"$work/log" 2>&1
        rc=$?
        set -e
        read -r seconds user system < <(tail -n 1 "$work/time")
        cpu=$(awk -v u="$user" -v s="$system" 'BEGIN { printf "%.2f", u + s }')
        if [[ -f $out/summary.json ]]; then
            levels=$(jq -r '.adapt_levels // "?"' "$out/summary.json")
            minus=$(side "$out/summary.json" minus 'lambda-')
            plus=$(side "$out/summary.json" plus 'lambda+')
        else
            levels='?' minus="nothing written: $(tail -n 1 "$work/log" | cut -c1-120)" plus='-'
        fi
        echo "| 1/$n | $nu | $seconds | $cpu | $rc | $levels | $minus | $plus |"
    done
done
