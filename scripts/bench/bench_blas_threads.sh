#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# nceig alone on OPENBLAS_NUM_THREADS = 1 against 2 (and any other counts given), for the two
# runs whose factor is the largest in everyday use: the reference scene's hp c_n to 1e-12
# (input/square.nml, &adapt strategy = 'hp', tolerance = 1e-12) and an hp threshold run
# (input/threshold_adapt.nml with strategy = 'hp'). Each run alone, one after the other.
# Usage: scripts/bench/bench_blas_threads.sh [REPEATS] [THREADS ...]   (defaults: 3, and 1 2)
# Prints per (run, threads) the wall and CPU (user + system) seconds of GNU time, their
# medians over the repeats, the factor's size (n_dofs of the last level) and the load average
# of /proc/loadavg before and after: timings of a loaded machine say what a loaded machine
# does, and nothing about idle cores.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
(($# > 1)) || set -- "${1:-3}" 1 2   # default THREADS: 1 2
source "$root/scripts/lib/bench_common.sh"
bench_begin bench_blas_threads "$@"   # repeats; the thread counts as its "sizes"
threads_list=("${sizes[@]}")
command -v jq >/dev/null 2>&1 || { echo "bench_blas_threads: needs jq" >&2; exit 1; }

no_files=(--set output%vtk=.false. --set output%plot=.false.)
cn_run=("$root/input/square.nml" --set adapt%strategy=hp --set adapt%tolerance=1e-12
        "${no_files[@]}")
threshold_run=("$root/input/threshold_adapt.nml" --set adapt%strategy=hp "${no_files[@]}")

median() {
    sort -g | awk '{ v[NR] = $1 }
        END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'
}

echo "# nceig $("$nceig" --version | cut -d' ' -f2), $(nproc) cores," \
    "$repeats repeats, each run alone"
printf '%-12s | %7s | %6s | %-22s | %-22s | %8s | %8s | %s\n' run threads dofs \
    'wall s (each)' 'cpu s (each)' 'wall med' 'cpu med' 'load before -> after'
for name in c_n_1e-12 threshold; do
    if [[ $name == threshold ]]; then args=("${threshold_run[@]}"); else args=("${cn_run[@]}"); fi
    for threads in "${threads_list[@]}"; do
        walls=() cpus=()
        load_before=$(cut -d' ' -f1 /proc/loadavg)
        for ((r = 1; r <= repeats; r++)); do
            rm -rf "$work/out"
            OPENBLAS_NUM_THREADS=$threads OMP_NUM_THREADS=$threads /usr/bin/time \
                -f '%e %U %S' -o "$work/time" "$nceig" "${args[@]}" \
                --set "output%directory=$work/out" >"$work/log" 2>&1 ||
                { echo "bench_blas_threads: $name failed: $(tail -n 2 "$work/log")" >&2; exit 1; }
            [[ $(jq .blas_threads "$work/out/summary.json") == "$threads" ]] ||
                { echo "bench_blas_threads: nceig did not run on $threads threads" >&2; exit 1; }
            read -r wall user system < <(tail -n 1 "$work/time")
            walls+=("$wall")
            cpus+=("$(awk -v u="$user" -v s="$system" 'BEGIN { printf "%.2f", u + s }')")
        done
        printf '%-12s | %7s | %6s | %-22s | %-22s | %8s | %8s | %s -> %s\n' "$name" "$threads" \
            "$(jq .n_dofs "$work/out/summary.json")" "${walls[*]}" "${cpus[*]}" \
            "$(printf '%s\n' "${walls[@]}" | median)" "$(printf '%s\n' "${cpus[@]}" | median)" \
            "$load_before" "$(cut -d' ' -f1 /proc/loadavg)"
    done
done
