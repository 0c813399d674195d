#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Does the mode of the lowest positive mu converge, and to the same function from every
# element family? For the reference scene (unit square, top fixed, contact on the bottom,
# E = 1) at one nu and lambda, each run writes mode_001.vtu (ASCII), and the script reads
# the mode on Gamma_C at x = 1/4, 1/2 and 3/4 (y = 0; nodes of every mesh used): the
# shape ratios u_n(1/4) / u_n(1/2), u_n(3/4) / u_n(1/2) and u_t(1/2) / u_n(1/2), which do not
# depend on how a mode is scaled. Rows: uniform P1, P2, Q1, Q2 for N = 8 to 64 (h = 1/N),
# then the adaptive loop (P1 to 1e-4, P2 to 1e-7, P3 to 1e-8, from 4 x 4; 1e-9 is below
# the floating-point floor of P3 on this scene) with mu's error
# estimate. Prints a Markdown table.
# Usage: scripts/dev/mode_convergence.sh [NU] [LAMBDA]   (defaults 0.3 and 5)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
nu=${1:-0.3}
lambda=${2:-5}
[[ -x $nceig ]] || { echo "mode_convergence: build first (scripts/dev/build.sh Release)" >&2; exit 1; }
command -v jq >/dev/null || { echo "mode_convergence: needs jq" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$root/scripts/lib/bench_common.sh"   # key FILE KEY

# shape FILE: the three ratios of mode_001.vtu's displacement at the three points (the
# first DataArray is the displacement, one point per line; the Points array has the
# points in the same order). n = (0, -1) and t = (-1, 0) on the bottom: u_n = -u_y, u_t = -u_x.
shape() {
    awk '/<Points>/ { points = 1 } /<DataArray/ { array++; next } /<\/DataArray>/ { next }
        array == 1 { ux[++n] = $1; uy[n] = $2 }
        points && !done { if (/<\/Points>/) done = 1; else if (NF == 3) { x = $1; y = $2; k++
            if (y * y < 1e-18) for (j = 1; j <= 3; j++) if ((x - j / 4) ^ 2 < 1e-18) at[j] = k } }
        END {
            if (!at[1] || !at[2] || !at[3]) { print "- | - | -"; exit }
            printf "%.8f | %.8f | %.8f\n", uy[at[1]] / uy[at[2]], uy[at[3]] / uy[at[2]],
                ux[at[2]] / uy[at[2]] }' "$1"
}

# run NAME ARGS...: one nceig run with --set ARGS, then its table row.
run() {
    local name=$1
    shift
    rm -rf "$work/out"
    "$nceig" "$work/base.nml" "$@" >/dev/null || { echo "mode_convergence: $name failed" >&2; exit 1; }
    local s=$work/out/summary.json estimate
    estimate=$(key "$s" lowest_positive_error_estimate)
    [[ -z $estimate ]] || estimate=$(printf '%.1e' "$estimate")
    echo "| $name | $(key "$s" n_dofs) | $(key "$s" lowest_positive_mu) | ${estimate:--} | $(shape "$work/out/mode_001.vtu") |"
}

cat >"$work/base.nml" <<NML
&material poisson = $nu /
&analysis kind = 'eigen', lambda = $lambda /
&eigen estimate = 'off' /
&output directory = '$work/out', vtk_format = 'ascii', modes = 1, plot = .false., progress = .false. /
NML
echo "# nceig $("$nceig" --version | cut -d' ' -f2): the mode of the lowest positive mu on Gamma_C, nu = $nu, lambda = $lambda"
echo '| mesh | dofs | mu | estimate | u_n(1/4) / u_n(1/2) | u_n(3/4) / u_n(1/2) | u_t(1/2) / u_n(1/2) |'
echo '|---|---|---|---|---|---|---|'
for element in p1 p2 q1 q2; do
    for n in 8 16 32 64; do
        run "$element $n x $n" --set mesh%element=$element --set mesh%nx=$n --set mesh%ny=$n
    done
done
for pair in p1:1e-4 p2:1e-7 p3:1e-8; do
    run "adaptive ${pair%%:*} to ${pair#*:}" --set mesh%element=${pair%%:*} --set mesh%nx=4 \
        --set mesh%ny=4 --set eigen%estimate=auto --set adapt%tolerance=${pair#*:} \
        --set adapt%max_levels=200 --set adapt%max_dofs=2000000
done
