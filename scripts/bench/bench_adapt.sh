#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The adaptive loop against uniform meshes on the reference scene (unit square, top fixed,
# contact on the bottom, E = 1, nu = 0.3, lambda = 5).
# Usage: scripts/bench/bench_adapt.sh [--element E] [--start N] [REPEATS] [TOLERANCE ...]
#   E: the adapted element (default p3), N: the starting N x N squares (default 4);
#   defaults: 3 repeats, tolerances 1e-4 1e-6 1e-8 1e-10.
# First a reference: the same loop to 1e-12 (P3; 35 s on 2 idle cores) whose own estimate
# bounds the error of the true errors below. Then each tolerance, REPEATS times: levels,
# final dofs, wall time and peak memory (median; /usr/bin/time), the estimate and the true
# error. Then uniform P1 and P2 meshes N = 8 ... 256 once each (wall time without the
# estimate, true error and, from a second run up to N = 128, their own estimate), and for
# each tolerance the most accurate uniform P1 and P2 run that took no more wall time than
# the adaptive one.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
element=p3
start=4
while [[ ${1:-} == --* ]]; do
    case $1 in
        --element) element=$2 ;;
        --start) start=$2 ;;
        *) echo "bench_adapt: unknown option $1" >&2; exit 2 ;;
    esac
    shift 2
done
tolerances=("${@:2}")
((${#tolerances[@]} > 0)) || tolerances=(1e-4 1e-6 1e-8 1e-10)
source "$root/scripts/lib/bench_common.sh"
bench_begin bench_adapt "${1:-3}"
command -v jq >/dev/null || { echo "bench_adapt: needs jq" >&2; exit 1; }

relative() { awk -v a="$1" -v b="$2" 'BEGIN { d = (a - b) / b; if (d < 0) d = -d; printf "%.2e", d }'; }

# run NAME ELEMENT N TOLERANCE [SETTINGS...]: one run; prints "wall_s peak_MB"
run() {
    local name=$1 el=$2 n=$3 tol=$4
    shift 4
    cat >"$work/$name.nml" <<NML
&mesh nx = $n, ny = $n, element = '$el' /
&analysis kind = 'eigen', lambda = 5.0 /
&eigen estimate = 'on' /
&output directory = '$work/$name', vtk = .false., plot = .false., progress = .false. /
&adapt tolerance = $tol /
NML
    /usr/bin/time -f '%e %M' -o "$work/time" "$nceig" "$work/$name.nml" "$@" >/dev/null \
        || { echo "bench_adapt: $name failed" >&2; exit 1; }
    awk '{ printf "%s %.0f\n", $1, $2 / 1024 }' "$work/time"
}

echo "# nceig $("$nceig" --version | cut -d' ' -f2), $(nproc) cores," \
    "load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
read -r ref_wall ref_peak < <(run ref p3 4 1e-12 --set adapt%max_dofs=600000 \
    --set adapt%max_levels=200)
reference=$(key "$work/ref/summary.json" lowest_positive_mu)
echo "# reference: adaptive p3 to 1e-12: mu = $reference, estimate" \
    "$(key "$work/ref/summary.json" lowest_positive_error_estimate)," \
    "$(key "$work/ref/summary.json" n_dofs) dofs, ${ref_wall} s, ${ref_peak} MB"
echo
echo "adaptive $element from ${start} x ${start} squares, theta = $(key "$work/ref/summary.json" adapt_theta) (median of $repeats)"
printf '%9s %6s %8s %8s %8s %10s %10s %5s\n' tolerance levels dofs wall_s peak_MB estimate \
    true_error met
declare -A adapt_wall
for tol in "${tolerances[@]}"; do
    walls='' peaks=''
    for ((r = 1; r <= repeats; r++)); do
        read -r wall peak < <(run adapt "$element" "$start" "$tol" --set adapt%max_levels=200)
        walls+=" $wall" peaks+=" $peak"
    done
    s=$work/adapt/summary.json
    adapt_wall[$tol]=$(echo "$walls" | median)
    printf '%9s %6s %8s %8s %8s %10s %10s %5s\n' "$tol" "$(key "$s" adapt_levels)" \
        "$(key "$s" n_dofs)" "${adapt_wall[$tol]}" "$(echo "$peaks" | median)" \
        "$(printf '%.2e' "$(key "$s" lowest_positive_error_estimate)")" \
        "$(relative "$(key "$s" lowest_positive_mu)" "$reference")" "$(key "$s" adapt_converged)"
done

echo
echo "uniform meshes (one run each)"
printf '%4s %5s %8s %8s %8s %10s %10s\n' el N dofs wall_s peak_MB estimate true_error
declare -A uniform_rows
for el in p1 p2; do
    for n in 8 16 32 64 128 256; do
        # the time without the estimate (a plain run); the estimate from a second run
        read -r wall peak < <(run uniform "$el" "$n" 0 --set eigen%estimate=off)
        s=$work/uniform/summary.json
        error=$(relative "$(key "$s" lowest_positive_mu)" "$reference")
        estimate=''
        if ((n <= 128)); then   # P2 N = 256: 526k dofs, about a minute with its estimate
            run uniform "$el" "$n" 0 >/dev/null
            estimate=$(key "$s" lowest_positive_error_estimate)
        fi
        [[ -z $estimate ]] || estimate=$(printf '%.2e' "$estimate")
        printf '%4s %5s %8s %8s %8s %10s %10s\n' "$el" "$n" "$(key "$s" n_dofs)" "$wall" \
            "$peak" "${estimate:--}" "$error"
        uniform_rows[$el]+="$wall $error $n"$'\n'
    done
done

echo
echo "the most accurate uniform run within the adaptive run's wall time"
printf '%9s %8s | %-22s | %-22s\n' tolerance wall_s 'uniform p1: N, error' 'uniform p2: N, error'
for tol in "${tolerances[@]}"; do
    best() {   # the smallest error among rows with wall <= the adaptive wall
        printf '%s' "${uniform_rows[$1]}" | awk -v limit="${adapt_wall[$tol]}" \
            '$1 != "" && $1 <= limit { if (best == "" || $2 < best) { best = $2; n = $3 } }
             END { if (best == "") print "none that fast"; else printf "N = %s, %s\n", n, best }'
    }
    printf '%9s %8s | %-22s | %-22s\n' "$tol" "${adapt_wall[$tol]}" "$(best p1)" "$(best p2)"
done
