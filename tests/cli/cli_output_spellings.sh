#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Concurrent runs into one output directory spelt differently ('out', 'out/.', './out/',
# 'x/../out', a symbolic link to it): one real directory, one lock. Each round starts four
# runs (lambda 1..4, spellings rotating); after it the directory must hold one run's
# complete set and no staging folder. Before the paths were resolved, 'out/.' was committed
# in place under another lock than 'out', and a round could end without summary.json.
# Usage: cli_output_spellings.sh NCEIG SOURCE_DIR [ROUNDS]
set -u
nceig=$(realpath "$1")
source "$2/tests/cli/lib/output_sets.bash"
rounds=${3:-20}
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_output_spellings
cd "$work" || exit 1
mkdir x
spellings=(out out/. ./out/ x/../out link)

refs=()
for k in 1 2 3 4; do
    cat >"ref_$k.nml" <<NML
&mesh nx = 4, ny = 4 /
&analysis lambda = $k /
&output directory = 'ref_$k', modes = $k, plot = .false. /
NML
    "$nceig" "ref_$k.nml" >/dev/null 2>&1
    refs+=("$work/ref_$k")
done
"$nceig" ref_1.nml >/dev/null 2>&1 && cp -a ref_1 out
ln -s out link
check 'the four reference runs complete' \
    '( for k in 1 2 3 4; do [[ $(set_state "ref_$k" "ref_$k") == "ref 0" ]] || exit 1; done )'

n_bad=0 n_failed_runs=0
start=$SECONDS
for ((round = 1; round <= rounds; round++)); do
    pids=()
    for k in 1 2 3 4; do
        spelling=${spellings[$(((round + k) % ${#spellings[@]}))]}
        sed "s|'ref_$k'|'$spelling'|" "ref_$k.nml" >"run_$k.nml"
        "$nceig" "run_$k.nml" >/dev/null 2>>stderr &
        pids+=($!)
    done
    for pid in "${pids[@]}"; do wait "$pid" || n_failed_runs=$((n_failed_runs + 1)); done
    state=$(set_state out "${refs[@]}")
    if [[ $state == broken* ]]; then
        n_bad=$((n_bad + 1))
        echo "      round $round: $state"
    fi
    left=$(ls -A . out | grep -E 'nceig-(staging|partial|old)')
    if [[ -n $left ]]; then
        n_bad=$((n_bad + 1))
        echo "      round $round: staging folder left: $left"
    fi
    [[ -L link ]] || { n_bad=$((n_bad + 1)); echo "      round $round: the link was replaced"; }
done
echo "      $rounds rounds of 4 concurrent runs, 5 spellings, in $((SECONDS - start)) s:" \
    "$n_bad inconsistent, $n_failed_runs runs failed"
[[ -s stderr ]] && head -3 stderr
check 'every run succeeds' '[[ $n_failed_runs -eq 0 ]]'
check 'after every round the directory holds one run'\''s complete set' '[[ $n_bad -eq 0 ]]'

cli_end
