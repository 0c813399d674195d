# SPDX-License-Identifier: MIT
# Helpers of the cli tests that check output sets (sourced, not a test itself).

# listed_files DIR: the names DIR/summary.json lists in "files", one per line.
listed_files() {
    grep -o '"files": \[[^]]*\]' "$1/summary.json" 2>/dev/null | grep -o '"[^"]*"' |
        tail -n +2 | tr -d '"'
}

# fingerprint FILE: what a rounding difference cannot change: the line count of a CSV file,
# the size of any other (a VTU file's binary arrays have a fixed size).
fingerprint() {
    if [[ $1 == *.csv ]]; then echo "lines $(wc -l <"$1")"; else echo "bytes $(stat -c %s "$1")"; fi
}

# same_run FILE REF_FILE OTHER_REF_FILE...: FILE is REF_FILE as the same run writes it:
# byte-identical, or (a BLAS kernel whose last bits follow the alignment of its arrays, seen
# once under AddressSanitizer) with REF_FILE's fingerprint where no other reference's
# file has that fingerprint. The references of a test differ in their meshes, so a file
# of another run has another fingerprint.
same_run() {
    local file=$1 ref=$2 print other
    shift 2
    cmp -s "$file" "$ref" && return 0
    print=$(fingerprint "$file")
    [[ $print == "$(fingerprint "$ref")" ]] || return 1
    for other in "$@"; do
        [[ -f $other && $print == "$(fingerprint "$other")" ]] && return 1
    done
    echo "      note: $file differs from $ref in its digits only" >&2
    return 0
}

# set_state DIR REF...: "ref K" when DIR holds exactly the complete set of the K-th (from 0)
# reference directory: summary.json lists what is there, every listed file but summary.json
# is that reference's (same_run), and summary.json gives the reference's lambda.
# Otherwise "broken: WHY", WHY starting with one of: "no summary.json", "a listed file is
# missing", "a mix" (the listed files are no reference's set), "unlisted files".
# Hidden names (dot files) are not part of a set.
set_state() {
    local dir=$1 ref other listed present lambda k=0 ok f match=-1 differing=''
    shift
    if [[ ! -f $dir/summary.json ]]; then echo "broken: no summary.json"; return; fi
    listed=$(listed_files "$dir" | sort)
    for f in $listed; do
        if [[ ! -f $dir/$f ]]; then echo "broken: a listed file is missing: $f"; return; fi
    done
    lambda=$(grep '"lambda":' "$dir/summary.json")
    local refs=("$@") others
    for ref in "$@"; do
        ok=1
        [[ "$(listed_files "$ref" | sort)" == "$listed" ]] || ok=0
        [[ $ok == 1 && "$(grep '"lambda":' "$ref/summary.json")" == "$lambda" ]] || ok=0
        if [[ $ok == 1 ]]; then
            for f in $listed; do
                [[ $f == summary.json ]] && continue
                others=()
                for other in "${refs[@]}"; do
                    [[ $other == "$ref" ]] || others+=("$other/$f")
                done
                same_run "$dir/$f" "$ref/$f" "${others[@]}" || {
                    ok=0
                    # what differs, for a failure that does not repeat: fingerprints, first byte
                    differing+=" $f ($(fingerprint "$dir/$f") against $(fingerprint "$ref/$f"),"
                    differing+=" $(cmp "$dir/$f" "$ref/$f" 2>&1 | head -1 | sed 's|.*differ: ||'))"
                    break
                }
            done
        fi
        if [[ $ok == 1 ]]; then match=$k; break; fi
        k=$((k + 1))
    done
    if [[ $match -lt 0 ]]; then
        echo "broken: a mix: no reference's set ($lambda; differing from the references:$differing)"
        return
    fi
    present=$(cd "$dir" && ls | sort)
    if [[ "$listed" != "$present" ]]; then
        echo "broken: unlisted files: $(comm -13 <(echo "$listed") <(echo "$present") | head -3 | tr '\n' ' ')..."
        return
    fi
    echo "ref $match"
}

# make_reference_sets NCEIG WORK OUT: two complete sets that differ in every file, in every
# file's fingerprint and in their number (dense solver on 60 x 6 and 50 x 6 cells: 61 and
# 40 modes, about 60 files of 35 kB):
# WORK/ref_4 and WORK/ref_5 written now, and inputs WORK/run_4.nml, WORK/run_5.nml writing
# the same sets into OUT.
make_reference_sets() {
    local nceig=$1 work=$2 out=$3 k target
    for k in 4 5; do
        for target in ref_$k run_$k; do
            cat >"$work/$target.nml" <<NML
&mesh nx = $((k == 4 ? 60 : 50)), ny = 6 /
&analysis lambda = $k /
&eigen solver = 'dense' /
&output directory = '$work/$target', modes = $((k == 4 ? 61 : 40)) /
NML
        done
        sed -i "s|'$work/run_$k'|'$out'|" "$work/run_$k.nml"
        "$nceig" "$work/ref_$k.nml" >/dev/null 2>&1
    done
}
