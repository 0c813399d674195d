#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Cost of mode_001.vtu in each &output vtk_format on the reference scene (model.md section 10:
# unit square, P1 'right' N x N, lambda = 5, one mode): the output phase (time_output_s of
# summary.json: eigenvalues.csv + mode_001.vtu + summary.json) and the .vtu file size.
# A run with vtk = .false. gives the output phase without the .vtu.
# Usage: scripts/bench/bench_vtu.sh [REPEATS] [N ...]   (defaults: 3, and 256 512 1024)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
repeats=${1:-3}
shift || true
sizes=("$@")
((${#sizes[@]} > 0)) || sizes=(256 512 1024)
[[ -x $nceig ]] || { echo "bench_vtu: build first (scripts/dev/build.sh Release)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

key() { jq -r --arg key "$2" '.[$key] // empty' "$1"; }   # a summary.json value
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# run N FORMAT VTK: one run, prints "time_output_s file_bytes time_total_s"
run() {
    cat >"$work/bench.nml" <<NML
&mesh nx = $1, ny = $1, element = 'p1', diagonal = 'right' /
&analysis lambda = 5.0 /
&output directory = '$work/out', vtk = $3, vtk_format = '$2' /
NML
    "$nceig" "$work/bench.nml" >"$work/stdout" 2>"$work/stderr" || { cat "$work/stderr" >&2; exit 1; }
    local bytes=0
    [[ -e $work/out/mode_001.vtu ]] && bytes=$(stat -c %s "$work/out/mode_001.vtu")
    echo "$(key "$work/out/summary.json" time_output_s) $bytes $(key "$work/out/summary.json" time_total_s)"
}

echo "# nceig $("$nceig" --version | cut -d' ' -f2), $(nproc) cores, load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%5s %8s | %8s %8s %8s %6s | %9s %9s %6s | %7s\n' N nodes none_s ascii_s binary_s ratio \
    ascii_MB binary_MB ratio total_s
for n in "${sizes[@]}"; do
    declare -A t=() total=()
    for ((r = 1; r <= repeats; r++)); do
        # Interleaved, so that a change of machine load hits both formats alike.
        for f in ascii binary none; do
            if [[ $f == none ]]; then
                ((r == 1)) || continue   # a baseline: one run is enough
                read -r out bytes tot < <(run "$n" binary .false.)
            else
                read -r out bytes tot < <(run "$n" "$f" .true.)
                eval "bytes_$f=$bytes"
            fi
            t[$f]="${t[$f]:-} $out"
            total[$f]="${total[$f]:-} $tot"
        done
    done
    nodes=$(( (n + 1) * (n + 1) ))
    ta=$(echo "${t[ascii]}" | median) tb=$(echo "${t[binary]}" | median)
    printf '%5d %8d | %8.3f %8.3f %8.3f %6.1f | %9.1f %9.1f %6.2f | %7.2f\n' "$n" "$nodes" \
        "$(echo "${t[none]}" | median)" "$ta" "$tb" "$(awk -v a="$ta" -v b="$tb" 'BEGIN { print a / b }')" \
        "$(awk -v b="$bytes_ascii" 'BEGIN { print b / 1e6 }')" \
        "$(awk -v b="$bytes_binary" 'BEGIN { print b / 1e6 }')" \
        "$(awk -v a="$bytes_ascii" -v b="$bytes_binary" 'BEGIN { print a / b }')" \
        "$(echo "${total[binary]}" | median)"
done
echo "# output phase in s, medians of $repeats runs (none: vtk = .false., one run); ratio = ascii / binary"
echo "# total_s: whole run with the binary .vtu (median); load at end: $(cut -d' ' -f1-3 /proc/loadavg)"
