#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Wall time of a mesh sweep (scripts/sweep_mesh.sh, through GNU parallel) at -j 1 and -j 2:
# input/square.nml without mode files, families p1:right,q1,p2,q2, N = 16, 32, 64 (12 runs),
# each sweep into a fresh folder.
# Usage: scripts/bench/bench_sweep_jobs.sh [REPEATS] [JOBS ...]   (defaults: 3, and 1 2)
# Prints per JOBS the wall seconds of every repeat, their median, and the median of -j 1
# divided by this median. Timings mean something on idle cores only: the load is printed.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
(($# > 1)) || set -- "${1:-3}" 1 2   # default JOBS: 1 2
source "$root/scripts/lib/bench_common.sh"
bench_begin bench_sweep_jobs "$@"   # repeats; the JOBS values as its "sizes"
jobs_list=("${sizes[@]}")
command -v parallel >/dev/null 2>&1 ||
    { echo "bench_sweep_jobs: needs GNU parallel (package parallel)" >&2; exit 1; }
sed 's/vtk = .true./vtk = .false., plot = .false./' "$root/input/square.nml" >"$work/square.nml"

echo "# nceig $("$nceig" --version | cut -d' ' -f2), $(nproc) cores, 12 runs" \
    "(p1:right,q1,p2,q2 x N = 16,32,64), load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%5s | %-30s | %8s | %s\n' jobs 'wall s (each repeat)' median 'speed-up'
declare -A median_of
for jobs in "${jobs_list[@]}"; do
    walls=()
    for ((r = 1; r <= repeats; r++)); do
        rm -rf "$work/sweep"
        t0=$(date +%s.%N)
        NCEIG=$nceig bash "$root/scripts/sweep_mesh.sh" -e p1:right,q1,p2,q2 -n 16,32,64 \
            -j "$jobs" -o "$work/sweep" "$work/square.nml" >"$work/sweep.log" 2>&1 ||
            { echo "bench_sweep_jobs: the sweep failed: $(tail -n 3 "$work/sweep.log")" >&2; exit 1; }
        t1=$(date +%s.%N)
        walls+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }')")
    done
    median_of[$jobs]=$(printf '%s\n' "${walls[@]}" | median)
    speedup=$(awk -v a="${median_of[${jobs_list[0]}]}" -v b="${median_of[$jobs]}" \
        'BEGIN { printf "%.2f", a / b }')
    printf '%5s | %-30s | %8s | %s\n' "$jobs" "${walls[*]}" "${median_of[$jobs]}" "$speedup"
done
echo "# load at end: $(cut -d' ' -f1-3 /proc/loadavg)"
