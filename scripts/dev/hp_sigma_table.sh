#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The continuum c_n of three scenes by hp runs on three families of graded meshes
# (&adapt sigma = 0.10, 0.15, 0.20), each to tolerance 1e-13: other cells at every level,
# the same continuum value (docs/accuracy.md, "hp levels: the Rayleigh quotient without a
# stored K"). Needs jq. Usage: scripts/dev/hp_sigma_table.sh [NCEIG]  (default build/nceig)
set -eu
nceig=${1:-build/nceig}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%-10s %-6s %-5s %-22s %-10s %-10s\n' scene sigma exit mu bar roundoff
# scene width height poisson lambda
while read -r name width height poisson lambda; do
    for sigma in 0.10 0.15 0.20; do
        out=$work/$name-$sigma
        cat >"$out.nml" <<NML
&mesh width = $width, height = $height, nx = $((${width%.*} * 2)), ny = 2, element = 'p1' /
&material poisson = $poisson /
&analysis kind = 'eigen', lambda = $lambda /
&adapt tolerance = 1e-13, strategy = 'hp', sigma = $sigma /
&output vtk = .false., plot = .false., progress = .false., directory = '$out' /
NML
        rc=0
        "$nceig" "$out.nml" >/dev/null 2>&1 || rc=$?
        jq -r --arg n "$name" --arg s "$sigma" --arg rc "$rc" \
            '"\($n) \($s) \($rc) \(.lowest_positive_mu) \(.lowest_positive_error_bar) \(.lowest_positive_roundoff)"' \
            "$out/summary.json" | awk '{ printf "%-10s %-6s %-5s %-22s %-10.2e %-10.2e\n", $1, $2, $3, $4, $5, $6 }'
    done
done <<SCENES
reference 1.0 1.0 0.3 5.0
rect2x1 2.0 1.0 0.25 -4.0
nu0.45 1.0 1.0 0.45 20.0
SCENES
