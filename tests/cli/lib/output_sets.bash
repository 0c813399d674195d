# SPDX-License-Identifier: MIT
# Helpers of the cli tests that check output sets (sourced, not a test itself).

# listed_files DIR: the names DIR/summary.json lists in "files", one per line.
listed_files() {
    grep -o '"files": \[[^]]*\]' "$1/summary.json" 2>/dev/null | grep -o '"[^"]*"' |
        tail -n +2 | tr -d '"'
}

# set_state DIR REF...: "ref K" when DIR holds exactly the complete set of the K-th (from 0)
# reference directory: summary.json lists what is there, every listed file but summary.json
# is byte-identical to the reference's, and summary.json gives the reference's lambda.
# Otherwise "broken: WHY", WHY starting with one of: "no summary.json", "a listed file is
# missing", "a mix" (the listed files are no reference's set), "unlisted files".
# Hidden names (dot files) are not part of a set.
set_state() {
    local dir=$1 ref listed present lambda k=0 ok f match=-1 differing=''
    shift
    if [[ ! -f $dir/summary.json ]]; then echo "broken: no summary.json"; return; fi
    listed=$(listed_files "$dir" | sort)
    for f in $listed; do
        if [[ ! -f $dir/$f ]]; then echo "broken: a listed file is missing: $f"; return; fi
    done
    lambda=$(grep '"lambda":' "$dir/summary.json")
    for ref in "$@"; do
        ok=1
        [[ "$(listed_files "$ref" | sort)" == "$listed" ]] || ok=0
        [[ $ok == 1 && "$(grep '"lambda":' "$ref/summary.json")" == "$lambda" ]] || ok=0
        if [[ $ok == 1 ]]; then
            for f in $listed; do
                [[ $f == summary.json ]] && continue
                cmp -s "$dir/$f" "$ref/$f" || { ok=0; differing+=" $f"; break; }
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

# make_reference_sets NCEIG WORK OUT: two complete sets that differ in every file and in
# their number (dense solver, every eigenpair: 61 and 40 modes, about 60 files of 35 kB):
# WORK/ref_4 and WORK/ref_5 written now, and inputs WORK/run_4.nml, WORK/run_5.nml writing
# the same sets into OUT.
make_reference_sets() {
    local nceig=$1 work=$2 out=$3 k target
    for k in 4 5; do
        for target in ref_$k run_$k; do
            cat >"$work/$target.nml" <<NML
&mesh nx = 60, ny = 6 /
&analysis lambda = $k /
&eigen solver = 'dense' /
&output directory = '$work/$target', modes = $((k == 4 ? 61 : 40)) /
NML
        done
        sed -i "s|'$work/run_$k'|'$out'|" "$work/run_$k.nml"
        "$nceig" "$work/ref_$k.nml" >/dev/null 2>&1
    done
}
