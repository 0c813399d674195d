#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Whether a change left the results alone: run every input/*.nml with one nceig, keep the
# output folders, then compare two such runs.
#   scripts/dev/compare_outputs.sh run NCEIG FOLDER [REPEATS]
#       runs each input REPEATS times (default 3) with OPENBLAS_NUM_THREADS=1 (the factor's
#       last digits depend on the thread count) and no pictures; keeps the last run's output
#       in FOLDER/<stem>/ and appends the wall times to FOLDER/times.txt (so that runs of
#       the two programs can alternate: 'run OLD A 1; run NEW B 1', three times). FOLDER
#       should lie outside the repository (a baseline must survive a checkout).
#   scripts/dev/compare_outputs.sh diff BEFORE AFTER
#       for each input: summary.json with every key containing 'time' left out, and every
#       CSV file with its time columns left out, compared to the last digit; the other files
#       (VTU, Matrix Market, MSH) byte for byte. Prints one line per input and a table of
#       the median wall times with their ratio; exits 1 if anything differs.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)

usage() { sed -n '3,15p' "$0" >&2; exit 2; }

# run NCEIG FOLDER REPEATS
run_inputs() {
    local nceig folder repeats input stem r start end
    nceig=$(realpath "$1")
    folder=$2
    repeats=${3:-3}
    mkdir -p "$folder"
    folder=$(realpath "$folder")
    for input in "$root"/input/*.nml; do
        stem=$(basename "$input" .nml)
        for ((r = 1; r <= repeats; r++)); do
            rm -rf "${folder:?}/$stem"
            start=$(date +%s.%N)
            OPENBLAS_NUM_THREADS=1 "$nceig" "$input" --set output%plot=.false. \
                --set output%progress=.false. --set "output%directory=$folder/$stem" \
                >"$folder/$stem.stdout" 2>"$folder/$stem.stderr" || true
            end=$(date +%s.%N)
            echo "$stem $(echo "$end - $start" | bc)" >>"$folder/times.txt"
        done
    done
}

# summary.json without its timings, keys sorted
summary_values() {
    jq -S 'walk(if type == "object" then with_entries(select(.key | test("time") | not))
                else . end)' "$1"
}

# a CSV file without the columns whose header names contain 'time'
csv_values() {
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) keep[i] = ($i !~ /time/) }
             { line = ""; sep = ""
               for (i = 1; i <= NF; i++) if (keep[i]) { line = line sep $i; sep = "," }
               print line }' "$1"
}

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# diff BEFORE AFTER
diff_outputs() {
    local before=$1 after=$2 stem dir file name status=0 differs t0 t1
    for dir in "$before"/*/; do
        stem=$(basename "$dir")
        differs=()
        [[ -d $after/$stem ]] || { echo "$stem: no output after"; status=1; continue; }
        if [[ "$(cd "$before/$stem" && find . -type f | sort)" != \
              "$(cd "$after/$stem" && find . -type f | sort)" ]]; then
            differs+=("file list")
        fi
        while IFS= read -r file; do
            name=${file#./}
            [[ -f $after/$stem/$name ]] || continue
            case $name in
            summary.json)
                cmp -s <(summary_values "$before/$stem/$name") \
                    <(summary_values "$after/$stem/$name") || differs+=("$name") ;;
            *.csv)
                cmp -s <(csv_values "$before/$stem/$name") \
                    <(csv_values "$after/$stem/$name") || differs+=("$name") ;;
            *)
                cmp -s "$before/$stem/$name" "$after/$stem/$name" || differs+=("$name") ;;
            esac
        done < <(cd "$before/$stem" && find . -type f | sort)
        if ((${#differs[@]} > 0)); then
            echo "$stem: DIFFERS (${differs[*]})"
            status=1
        else
            echo "$stem: same ($(cd "$before/$stem" && find . -type f | wc -l) files)"
        fi
    done
    echo
    echo "| input | before s | after s | after/before |"
    echo "|---|---:|---:|---:|"
    for dir in "$before"/*/; do
        stem=$(basename "$dir")
        t0=$(awk -v s="$stem" '$1 == s { print $2 }' "$before/times.txt" | median)
        t1=$(awk -v s="$stem" '$1 == s { print $2 }' "$after/times.txt" | median)
        [[ -n $t0 && -n $t1 ]] || continue
        awk -v s="$stem" -v a="$t0" -v b="$t1" \
            'BEGIN { printf "| %s | %.3f | %.3f | %.2f |\n", s, a, b, (a > 0) ? b / a : 0 }'
    done
    return $status
}

case ${1:-} in
run) (($# >= 3)) || usage; run_inputs "$2" "$3" "${4:-3}" ;;
diff) (($# == 3)) || usage; diff_outputs "$2" "$3" ;;
*) usage ;;
esac
