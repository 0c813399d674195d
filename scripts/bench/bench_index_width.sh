#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The index width of the sparse factorizations on large scenes of the reference problem:
#   scripts/bench/bench_index_width.sh [--before OLD_NCEIG] [--cholmod-only] [N:ELEMENT ...]
# (default 128:p3 512:p1). Prints two Markdown tables:
# - UMFPACK's int ("di") against its long ("dl") API on the full operator's K - 0.5 B
#   (scripts/bench/bench_index_width.f90: factor and solve times, medians of 3, UMFPACK's
#   peak memory and Numeric size);
# - with --before, CHOLMOD through this build's nceig against OLD_NCEIG (e.g. a build of
#   the commit before the shim moved to cholmod_l_*): input/square.nml at each scene,
#   OPENBLAS_NUM_THREADS=1, no pictures: median factor time (time_factor_s) and median peak
#   resident memory of the run (GNU time), 3 runs each, alternating, with the ratio new/old.
# --cholmod-only leaves out the first table (UMFPACK on N = 1024 P1 takes many GB).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
before=
umfpack=1
while [[ ${1:-} == --* ]]; do
    case $1 in
    --before) before=$(realpath "$2"); shift 2 ;;
    --cholmod-only) umfpack=0; shift ;;
    *) echo "bench_index_width: unknown option $1" >&2; exit 2 ;;
    esac
done
scenes=("$@")
((${#scenes[@]} > 0)) || scenes=(128:p3 512:p1)
nceig=$root/build/nceig
bash "$root/scripts/dev/build.sh" Release
cmake --build "$root/build" --target bench_index_width >/dev/null
source "$root/scripts/lib/bench_common.sh"
bench_begin bench_index_width 3

((umfpack == 0)) || OPENBLAS_NUM_THREADS=1 "$root/build/bench_index_width" "${scenes[@]}"
[[ -n $before ]] || exit 0

# run EXE N ELEMENT: prints "factor_s max_rss_kB" of one run
run() {
    local out=$work/run
    rm -rf "$out"
    OPENBLAS_NUM_THREADS=1 /usr/bin/time -f '%M' -o "$work/rss" "$1" \
        "$root/input/square.nml" --set mesh%nx="$2" --set mesh%ny="$2" \
        --set mesh%element="$3" --set output%plot=.false. --set output%vtk=.false. \
        --set output%progress=.false. --set output%directory="$out" >/dev/null
    echo "$(key "$out/summary.json" time_factor_s) $(tail -1 "$work/rss")"
}
echo
echo '| scene | dofs | factor s old | factor s new | new/old | peak MB old | peak MB new | new/old |'
echo '|---|---:|---:|---:|---:|---:|---:|---:|'
for scene in "${scenes[@]}"; do
    n=${scene%%:*}
    element=${scene#*:}
    old_t=() new_t=() old_m=() new_m=()
    for ((r = 1; r <= repeats; r++)); do
        read -r t m < <(run "$before" "$n" "$element"); old_t+=("$t"); old_m+=("$m")
        read -r t m < <(run "$nceig" "$n" "$element"); new_t+=("$t"); new_m+=("$m")
    done
    dofs=$(key "$work/run/summary.json" n_dofs)
    ot=$(echo "${old_t[*]}" | median); nt=$(echo "${new_t[*]}" | median)
    om=$(echo "${old_m[*]}" | median); nm=$(echo "${new_m[*]}" | median)
    awk -v s="$n x $n $element" -v d="$dofs" -v ot="$ot" -v nt="$nt" -v om="$om" -v nm="$nm" \
        'BEGIN { printf "| %s | %s | %.3f | %.3f | %.2f | %.0f | %.0f | %.3f |\n",
                 s, d, ot, nt, nt / ot, om / 1024, nm / 1024, nm / om }'
done
