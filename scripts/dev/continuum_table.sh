#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The critical c_n and c_t of the reference scene (unit square, top fixed, contact on the
# bottom, E = 1) as mesh-independent numbers: for each nu and lambda, the adaptive loop
# (P3 from 4 x 4 squares, &adapt) to a tolerance, with the final error estimate and the
# time. lambda = 1e300 stands for the limit lambda -> infinity, where c_n -> 0 and
# c_t = mu |lambda| tends to a finite value (K phi = nu B_inf phi with B(lambda) / lambda ->
# B_inf; every mu is computed in units where lambda is scaled away, so 1e300 loses nothing).
# Then, per nu, the critical lambdas lambda+ and lambda- (kind = 'threshold' with &adapt, the
# same start and tolerance), their estimates and lambda+ + lambda-, which the mirror
# symmetry of the square makes 0.
# Usage: scripts/dev/continuum_table.sh [TOLERANCE] [NU ...]   (defaults 1e-8; 0.3 0 0.45)
# Prints two Markdown tables; c_t carries the same relative error estimate as c_n.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
tolerance=${1:-1e-8}
shift || true
nus=("$@")
((${#nus[@]} > 0)) || nus=(0.3 0 0.45)
[[ -x $nceig ]] || { echo "continuum_table: build first (scripts/dev/build.sh Release)" >&2; exit 1; }
command -v jq >/dev/null || { echo "continuum_table: needs jq" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$root/scripts/lib/bench_common.sh"   # key FILE KEY

echo "# nceig $("$nceig" --version | cut -d' ' -f2), $(nproc) cores, tolerance $tolerance," \
    "load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
# run KIND NU LAMBDA: the adaptive run; sets s (its summary.json) and seconds
run() {
    cat >"$work/run.nml" <<NML
&mesh nx = 4, ny = 4, element = 'p3' /
&material poisson = $2 /
&analysis kind = '$1', lambda = $3 /
&adapt tolerance = $tolerance, max_levels = 200 /
&output directory = '$work/out', vtk = .false., plot = .false., progress = .false. /
NML
    local start
    start=$(date +%s.%N)
    "$nceig" "$work/run.nml" >/dev/null || { echo "continuum_table: $1, nu = $2, lambda = $3 failed" >&2; exit 1; }
    seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f s", b - a }')
    s=$work/out/summary.json
}
# outcome: ' (not met: why...)' for a loop that stopped short, else ''
outcome() {
    [[ $(key "$s" adapt_converged) == true ]] || echo " (not met: $(key "$s" adapt_outcome | cut -d: -f2- | cut -c1-60)...)"
}
estimate_text() { if [[ -n $1 ]]; then printf '%.1e' "$1"; else echo none; fi; }

echo '| nu | lambda | critical c_n | critical c_t | estimate | levels | dofs | time |'
echo '|---|---|---|---|---|---|---|---|'
for nu in "${nus[@]}"; do
    for lambda in 2 2.5 3 5 10 20 100 1e300; do
        run eigen "$nu" "$lambda"
        shown=$lambda
        [[ $lambda != 1e300 ]] || shown='infinity'
        if [[ -z $(key "$s" lowest_positive_mu) ]]; then
            echo "| $nu | $shown | none | none | - | $(key "$s" adapt_levels) | $(key "$s" n_dofs) | $seconds |"
            continue
        fi
        c_n=$(key "$s" critical_c_n)
        [[ $lambda != 1e300 ]] || c_n='-> 0'
        # a loop that stopped short: the last mu is no continuum value, say why
        estimate="$(estimate_text "$(key "$s" lowest_positive_error_estimate)")$(outcome)"
        printf '| %s | %s | %s | %s | %s | %s | %s | %s |\n' "$nu" "$shown" "$c_n" \
            "$(key "$s" critical_c_t)" "$estimate" "$(key "$s" adapt_levels)" \
            "$(key "$s" n_dofs)" "$seconds"
    done
done

echo
echo '| nu | lambda+ | estimate | lambda- | estimate | lambda+ + lambda- | levels | dofs | time |'
echo '|---|---|---|---|---|---|---|---|---|'
for nu in "${nus[@]}"; do
    run threshold "$nu" 5
    plus=$(key "$s" lambda_critical_plus)
    minus=$(key "$s" lambda_critical_minus)
    sum=-
    [[ -z $plus || -z $minus ]] || sum=$(awk -v p="$plus" -v m="$minus" 'BEGIN { printf "%.1e", p + m }')
    printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n' "$nu" "${plus:-none}" \
        "$(estimate_text "$(key "$s" lambda_critical_plus_error_estimate)")$(outcome)" \
        "${minus:-none}" "$(estimate_text "$(key "$s" lambda_critical_minus_error_estimate)")" \
        "$sum" "$(key "$s" adapt_levels)" "$(key "$s" n_dofs)" "$seconds"
done
