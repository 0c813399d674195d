#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Scaling table of the reference scene (model.md section 10: unit square, P1 'right' N x N,
# lambda = 5).
# Usage: scripts/bench/bench_scaling.sh [--solver S] [--analysis A] [REPEATS] [N ...]
#   S: 'auto' (default: ARPACK beyond dense_max_contact contact nodes), 'dense' or 'arpack';
#   A: 'eigen' (default) or 'threshold'; defaults: 3 repeats, N = 64 128 256 512 1024.
# Each N runs REPEATS times; every column is the median over the runs. Phase times come
# from summary.json (time_*_s; `reduce` = the dense p x p blocks, `thresh` = the pencil
# QZ and confirmations of 'threshold'), peak memory and wall time from /usr/bin/time -v.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
solver=auto
analysis=eigen
while [[ ${1:-} == --* ]]; do
    case $1 in
        --solver) solver=$2 ;;
        --analysis) analysis=$2 ;;
        *) echo "bench_scaling: unknown option $1" >&2; exit 2 ;;
    esac
    shift 2
done
source "$root/scripts/lib/bench_common.sh"
bench_begin bench_scaling "$@"

echo "# nceig $("$nceig" --version | cut -d' ' -f2), $(nproc) cores, solver = $solver," \
    "analysis = $analysis, load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%5s %8s %9s %5s | %6s %6s %6s %6s %6s %6s %6s %7s %7s | %5s %7s | %s\n' N dofs nnz_K \
    p assem order factor reduce eigen thresh output total wall ops peakMB lowest_mu
declare -A total_of dofs_of peak_of
for n in "${sizes[@]}"; do
    cat >"$work/bench.nml" <<NML
&mesh nx = $n, ny = $n, element = 'p1', diagonal = 'right' /
&analysis kind = '$analysis', lambda = 5.0 /
&eigen solver = '$solver' /
&output directory = '$work/out' /
NML
    declare -A col=()
    for ((r = 1; r <= repeats; r++)); do
        /usr/bin/time -v "$nceig" "$work/bench.nml" >"$work/stdout" 2>"$work/time" \
            || { cat "$work/time" >&2; exit 1; }
        s=$work/out/summary.json
        for k in time_assembly_s time_ordering_s time_factor_s time_reduction_s time_eigen_s \
                 time_threshold_s time_output_s time_total_s operator_applications; do
            v=$(key "$s" $k)
            col[$k]="${col[$k]:-} ${v:-0}"
        done
        wall=$(grep 'Elapsed (wall clock)' "$work/time" | awk -F': ' '{print $2}' \
            | awk -F: '{ if (NF == 3) print $1 * 3600 + $2 * 60 + $3; else print $1 * 60 + $2 }')
        col[wall]="${col[wall]:-} $wall"
        col[peak]="${col[peak]:-} $(grep 'Maximum resident' "$work/time" | awk '{print $NF / 1024}')"
    done
    dofs=$(key "$s" n_dofs)
    med() { echo "${col[$1]}" | median; }
    total_of[$n]=$(med time_total_s) dofs_of[$n]=$dofs peak_of[$n]=$(med peak)
    printf '%5d %8d %9d %5d | %6.3f %6.3f %6.3f %6.3f %6.3f %6.3f %6.3f %7.3f %7.2f | %5.0f %7.0f | %s\n' \
        "$n" "$dofs" "$(key "$s" nnz_k)" "$(key "$s" n_contact)" "$(med time_assembly_s)" \
        "$(med time_ordering_s)" "$(med time_factor_s)" "$(med time_reduction_s)" \
        "$(med time_eigen_s)" "$(med time_threshold_s)" \
        "$(med time_output_s)" "$(med time_total_s)" "$(med wall)" \
        "$(med operator_applications)" "$(med peak)" "$(key "$s" lowest_positive_mu)"
done
echo "# times in s (medians of $repeats runs): assem = mesh + K + B, order = METIS on the node"
echo "# graph (contact nodes last), eigen = eigen-solve + eigenvectors + backward errors; wall and"
echo "# peakMB from time -v"
echo "# load at end: $(cut -d' ' -f1-3 /proc/loadavg)"
# the targets are those of the default run (analysis 'eigen', solver 'auto')
[[ $analysis == eigen && $solver == auto ]] || exit 0
if [[ -n ${total_of[512]:-} ]]; then
    awk -v t="${total_of[512]}" 'BEGIN { printf "# target N = 512 total <= 6 s: %.2f s, %s (%+.0f%%)\n", t, (t <= 6 ? "met" : "MISSED"), 100 * (t - 6) / 6 }'
fi
if [[ -n ${total_of[1024]:-} ]]; then
    awk -v t="${total_of[1024]}" -v m="${peak_of[1024]}" 'BEGIN {
        printf "# target N = 1024 total <= 25 s: %.2f s, %s (%+.0f%%)\n", t, (t <= 25 ? "met" : "MISSED"), 100 * (t - 25) / 25
        printf "# target N = 1024 peak <= 3.5 GB: %.2f GB, %s (%+.0f%%)\n", m / 1024, (m <= 3584 ? "met" : "MISSED"), 100 * (m - 3584) / 3584 }'
fi
if [[ -n ${total_of[512]:-} && -n ${total_of[1024]:-} ]]; then
    awk -v a="${total_of[512]}" -v b="${total_of[1024]}" -v na="${dofs_of[512]}" -v nb="${dofs_of[1024]}" 'BEGIN {
        e = log(b / a) / log(nb / na)
        printf "# growth 512 -> 1024: time ~ n^%.2f (target <= n^1.3): %s\n", e, (e <= 1.3 ? "met" : "MISSED") }'
fi
