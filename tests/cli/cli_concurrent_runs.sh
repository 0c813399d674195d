#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Concurrent runs into one output directory: five runs at once (lambda 1..5, modes 1..5),
# many rounds; after each round the directory must hold exactly one run's complete set, the
# one its summary.json describes, with no file of another run and no staging folder.
# Usage: cli_concurrent_runs.sh NCEIG SOURCE_DIR [ROUNDS]
set -u
nceig=$1
source "$2/tests/cli/lib/output_sets.bash"
rounds=${3:-40}
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_concurrent_runs
out="$work/out"

refs=()
for k in 1 2 3 4 5; do
    for target in ref_$k run_$k; do
        cat >"$work/$target.nml" <<NML
&mesh nx = 8, ny = 8 /
&analysis lambda = $k /
&output directory = '$work/$target', modes = $k /
NML
    done
    sed -i "s|'$work/run_$k'|'$out'|" "$work/run_$k.nml"
    "$nceig" "$work/ref_$k.nml" >/dev/null 2>&1
    refs+=("$work/ref_$k")
done
check 'the five reference runs complete' \
    '( for k in 1 2 3 4 5; do [[ $(set_state "$work/ref_$k" "$work/ref_$k") == "ref 0" ]] || exit 1; done )'

n_bad=0 n_failed_runs=0
declare -A winners=()
start=$SECONDS
for ((round = 1; round <= rounds; round++)); do
    pids=()
    for k in 1 2 3 4 5; do
        "$nceig" "$work/run_$k.nml" >/dev/null 2>>"$work/stderr" &
        pids+=($!)
    done
    for pid in "${pids[@]}"; do wait "$pid" || n_failed_runs=$((n_failed_runs + 1)); done
    state=$(set_state "$out" "${refs[@]}")
    if [[ $state == broken* ]]; then
        n_bad=$((n_bad + 1))
        echo "      round $round: $state"
    else
        winners[$state]=1
    fi
    if [[ -n $(ls -A "$work" | grep nceig-staging) ]]; then
        n_bad=$((n_bad + 1))
        echo "      round $round: staging folder left: $(ls -A "$work" | grep nceig-staging)"
    fi
done
echo "      $rounds rounds of 5 concurrent runs in $((SECONDS - start)) s: $n_bad inconsistent," \
    "$n_failed_runs runs failed, final sets from ${#winners[@]} different runs"
[[ -s $work/stderr ]] && head -3 "$work/stderr"
check 'every run succeeds' '[[ $n_failed_runs -eq 0 ]]'
check 'after every round the directory holds one run'\''s complete set' '[[ $n_bad -eq 0 ]]'

cli_end
