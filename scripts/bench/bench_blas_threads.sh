#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# nceig's own choice of BLAS threads (docs/performance.md, "BLAS threads") against forced
# OPENBLAS_NUM_THREADS = 1 and 2, on the cores as found ("as found") and on cores this
# script loads itself ("loaded": one busy loop per core at nice 0, started 30 s before the
# runs so that the load average has risen, stopped at the end), for three runs, each alone:
#   c_n_1e-12  the reference scene's hp c_n to 1e-12 (input/square.nml, &adapt hp, 1e-12)
#   threshold  an hp threshold run (input/threshold_adapt.nml, &adapt hp)
#   uniform    the reference scene on a uniform P2 mesh of N x N squares (default 128:
#              131584 dofs), a factor large enough for threads to pay
# Usage: scripts/bench/bench_blas_threads.sh [--uniform N] [--loads 'found loaded'] [REPEATS]
#        scripts/bench/bench_blas_threads.sh --crossover [REPEATS] [N ...]
# The first prints per (load, run, threads) the count the run had (summary.json
# blas_threads), the factor's order (n_dofs of the last level), the medians over REPEATS
# (default 3) of wall and CPU (user + system) seconds of GNU time, and /proc/loadavg before
# and after. --crossover prints, for uniform P2 meshes of N x N squares (default 16 24 32 48
# 64 96 128), the medians of the factorization's seconds (summary.json time_factor_s) and of
# the wall seconds on 1 and on 2 threads: where 2 threads start to pay is the policy's
# crossover (blas_threads.f90, THREAD_DOFS). Timings of a loaded machine say what a loaded
# machine does: each row carries its load average.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
uniform_n=128
loads=(found loaded)
crossover=false
while (($# > 0)); do
    case $1 in
        --uniform) uniform_n=$2; shift 2 ;;
        --loads) read -ra loads <<<"$2"; shift 2 ;;
        --crossover) crossover=true; shift ;;
        *) break ;;
    esac
done
if $crossover; then
    (($# > 1)) || set -- "${1:-3}" 16 24 32 48 64 96 128
else
    set -- "${1:-3}" 0   # no sizes: bench_begin's default list is not used
fi
source "$root/scripts/lib/bench_common.sh"
bench_begin bench_blas_threads "$@"
command -v jq >/dev/null 2>&1 || { echo "bench_blas_threads: needs jq" >&2; exit 1; }

busy=()   # the busy loops' process ids
stop_load() {
    local pid
    for pid in "${busy[@]}"; do kill "$pid" 2>/dev/null || true; done
    for pid in "${busy[@]}"; do wait "$pid" 2>/dev/null || true; done
    busy=()
}
trap 'stop_load; rm -rf "$work"' EXIT
start_load() {
    local core
    for ((core = 0; core < $(nproc); core++)); do
        nice -n 0 bash -c 'while :; do :; done' &
        busy+=($!)
    done
    sleep 30
}

no_files=(--set output%vtk=.false. --set output%plot=.false. --set output%modes=1)
run_args() {   # run_args NAME [N]: the input and --set options of run NAME into args
    case $1 in
        c_n_1e-12) args=("$root/input/square.nml" --set adapt%strategy=hp
                         --set adapt%tolerance=1e-12) ;;
        threshold) args=("$root/input/threshold_adapt.nml" --set adapt%strategy=hp) ;;
        uniform) args=("$root/input/square.nml" --set mesh%element=p2
                       --set mesh%nx="$2" --set mesh%ny="$2") ;;
    esac
    args+=("${no_files[@]}")
}

# measure MODE: one run of $args on MODE threads ('policy': no variable set, nceig
# chooses); appends to walls, cpus, factors; checks the summary's thread count and source
measure() {
    local mode=$1 wall user system want_source=environment
    local -a environment=(env -u OPENBLAS_NUM_THREADS -u GOTO_NUM_THREADS -u OMP_NUM_THREADS)
    if [[ $mode == policy ]]; then
        want_source=nceig
    else
        environment+=(OPENBLAS_NUM_THREADS="$mode")
    fi
    rm -rf "$work/out"
    "${environment[@]}" /usr/bin/time -f '%e %U %S' -o "$work/time" "$nceig" "${args[@]}" \
        --set "output%directory=$work/out" >"$work/log" 2>&1 ||
        { echo "bench_blas_threads: ${args[*]} failed: $(tail -n 2 "$work/log")" >&2; exit 1; }
    [[ $(key "$work/out/summary.json" blas_threads_source) == "$want_source" ]] ||
        { echo "bench_blas_threads: threads not chosen by $want_source" >&2; exit 1; }
    [[ $mode == policy || $(key "$work/out/summary.json" blas_threads) == "$mode" ]] ||
        { echo "bench_blas_threads: nceig did not run on $mode threads" >&2; exit 1; }
    read -r wall user system < <(tail -n 1 "$work/time")
    walls+=("$wall")
    cpus+=("$(awk -v u="$user" -v s="$system" 'BEGIN { printf "%.2f", u + s }')")
    factors+=("$(key "$work/out/summary.json" time_factor_s)")
    chosen+=("$(key "$work/out/summary.json" blas_threads)")
}

load_now() { cut -d' ' -f1 /proc/loadavg; }
echo "# nceig $("$nceig" --version | cut -d' ' -f2), $(nproc) cores, medians of $repeats" \
    "runs, each alone; load at start: $(cut -d' ' -f1-3 /proc/loadavg)"

if $crossover; then
    printf '%5s | %7s | %-19s | %-19s | %s\n' N dofs 'factor s: 1 / 2 thr' \
        'wall s: 1 / 2 thr' 'load before -> after'
    for n in "${sizes[@]}"; do
        run_args uniform "$n"
        before=$(load_now)
        declare -A factor_med wall_med
        for threads in 1 2; do
            walls=() cpus=() factors=() chosen=()
            for ((r = 1; r <= repeats; r++)); do measure "$threads"; done
            factor_med[$threads]=$(printf '%.3f' "$(echo "${factors[*]}" | median)")
            wall_med[$threads]=$(echo "${walls[*]}" | median)
        done
        printf '%5s | %7s | %8s / %8s | %8s / %8s | %s -> %s\n' "$n" \
            "$(key "$work/out/summary.json" n_dofs)" "${factor_med[1]}" "${factor_med[2]}" \
            "${wall_med[1]}" "${wall_med[2]}" "$before" "$(load_now)"
    done
    exit 0
fi

printf '%-6s | %-10s | %-7s | %6s | %6s | %8s | %8s | %s\n' load run threads chosen dofs \
    'wall med' 'cpu med' 'load before -> after'
for load in "${loads[@]}"; do
    if [[ $load == loaded ]]; then start_load; fi
    for name in c_n_1e-12 threshold uniform; do
        run_args "$name" "$uniform_n"
        for mode in policy 1 2; do
            walls=() cpus=() factors=() chosen=()
            before=$(load_now)
            for ((r = 1; r <= repeats; r++)); do measure "$mode"; done
            printf '%-6s | %-10s | %-7s | %6s | %6s | %8s | %8s | %s -> %s\n' "$load" \
                "$name" "$mode" "$(printf '%s\n' "${chosen[@]}" | sort -u | paste -sd/)" \
                "$(key "$work/out/summary.json" n_dofs)" "$(echo "${walls[*]}" | median)" \
                "$(echo "${cpus[*]}" | median)" "$before" "$(load_now)"
        done
    done
    if [[ $load == loaded ]]; then stop_load; fi
done
echo "# load at end: $(cut -d' ' -f1-3 /proc/loadavg)"
