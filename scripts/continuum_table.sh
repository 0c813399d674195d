#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The critical c_n and c_t of the reference scene (unit square, top fixed, contact on the
# bottom, E = 1) as mesh-independent numbers: for each nu and lambda, the adaptive loop
# (P3 from 4 x 4 squares, &adapt) to a tolerance, with the final error estimate and the
# time. lambda = 1e300 stands for the limit lambda -> infinity, where c_n -> 0 and
# c_t = mu |lambda| tends to a finite value (K phi = nu B_inf phi with B(lambda) / lambda ->
# B_inf; every mu is computed in units where lambda is scaled away, so 1e300 loses nothing).
# Usage: scripts/continuum_table.sh [TOLERANCE] [NU ...]   (defaults 1e-8; 0.3 0 0.45)
# Prints a Markdown table; c_t carries the same relative error estimate as c_n.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
tolerance=${1:-1e-8}
shift || true
nus=("$@")
((${#nus[@]} > 0)) || nus=(0.3 0 0.45)
[[ -x $nceig ]] || { echo "continuum_table: build first (scripts/build.sh Release)" >&2; exit 1; }
command -v jq >/dev/null || { echo "continuum_table: needs jq" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$root/scripts/lib/bench_common.sh"   # key FILE KEY

echo "# nceig $("$nceig" --version | cut -d' ' -f2), $(nproc) cores, tolerance $tolerance," \
    "load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
echo '| nu | lambda | critical c_n | critical c_t | estimate | levels | dofs | time |'
echo '|---|---|---|---|---|---|---|---|'
for nu in "${nus[@]}"; do
    for lambda in 2 2.5 3 5 10 20 100 1e300; do
        cat >"$work/run.nml" <<NML
&mesh nx = 4, ny = 4, element = 'p3' /
&material poisson = $nu /
&analysis kind = 'eigen', lambda = $lambda /
&adapt tolerance = $tolerance, max_levels = 200 /
&output directory = '$work/out', vtk = .false., plot = .false., progress = .false. /
NML
        start=$(date +%s.%N)
        "$nceig" "$work/run.nml" >/dev/null || { echo "continuum_table: nu = $nu, lambda = $lambda failed" >&2; exit 1; }
        seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f s", b - a }')
        s=$work/out/summary.json
        shown=$lambda
        [[ $lambda != 1e300 ]] || shown='infinity'
        if [[ -z $(key "$s" lowest_positive_mu) ]]; then
            echo "| $nu | $shown | none | none | - | $(key "$s" adapt_levels) | $(key "$s" n_dofs) | $seconds |"
            continue
        fi
        c_n=$(key "$s" critical_c_n)
        [[ $lambda != 1e300 ]] || c_n='-> 0'
        estimate=$(key "$s" lowest_positive_error_estimate)
        if [[ -n $estimate ]]; then estimate=$(printf '%.1e' "$estimate"); else estimate='none'; fi
        # a loop that stopped short: the last mu is no continuum value, say why
        [[ $(key "$s" adapt_converged) == true ]] || estimate="$estimate (not met: $(key "$s" adapt_outcome | cut -d: -f2- | cut -c1-60)...)"
        printf '| %s | %s | %s | %s | %s | %s | %s | %s |\n' "$nu" "$shown" "$c_n" \
            "$(key "$s" critical_c_t)" "$estimate" "$(key "$s" adapt_levels)" \
            "$(key "$s" n_dofs)" "$seconds"
    done
done
