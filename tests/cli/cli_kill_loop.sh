#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Nothing lost under kill -9: runs into a directory holding a complete set are killed at
# random moments (SIGKILL: no chance to clean up), many times, the moments spread over the
# whole run and most of them in its output phase. After each kill the directory must hold
# the previous complete set or the new one, never a mix, a partial file or nothing; the
# hidden staging folders the kills leave are removed by the next run.
# Usage: cli_kill_loop.sh NCEIG SOURCE_DIR [TRIES]
set -u
nceig=$1
source "$2/tests/cli/lib/output_sets.bash"
tries=${3:-30}
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_kill_loop
out="$work/out"

make_reference_sets "$nceig" "$work" "$out"
check 'the reference runs complete' \
    '[[ $(set_state "$work/ref_4" "$work/ref_4") == "ref 0" && $(set_state "$work/ref_5" "$work/ref_5") == "ref 0" ]]'
"$nceig" "$work/run_5.nml" >/dev/null 2>&1

# The duration of a run, in microseconds (the fastest of three).
duration=999999999
for i in 1 2 3; do
    t0=$(date +%s%N)
    "$nceig" "$work/run_5.nml" >/dev/null 2>&1
    t=$((($(date +%s%N) - t0) / 1000))
    ((t < duration)) && duration=$t
done
echo "      a run takes $duration us"

n_old=0 n_new=0 n_broken=0 n_finished=0
declare -A why=()
RANDOM=12345
state=$(set_state "$out" "$work/ref_4" "$work/ref_5")
for ((i = 1; i <= tries; i++)); do
    previous=$state
    k=4   # replace the set with the other one
    [[ $previous == "ref 0" ]] && k=5
    # Half the kills anywhere in the run, half in its last 40 % (the output phase).
    if ((i % 2)); then
        delay=$((RANDOM * duration * 12 / 10 / 32768))
    else
        delay=$((duration * 6 / 10 + RANDOM * duration * 5 / 10 / 32768))
    fi
    "$nceig" "$work/run_$k.nml" >/dev/null 2>&1 &
    pid=$!
    sleep "$(printf '0.%06d' "$delay")"
    kill -KILL "$pid" 2>/dev/null || n_finished=$((n_finished + 1))
    wait "$pid" 2>/dev/null
    state=$(set_state "$out" "$work/ref_4" "$work/ref_5")
    if [[ $state == broken* ]]; then
        n_broken=$((n_broken + 1))
        echo "      try $i (kill after ${delay} us): ${state:0:100}"
        reason=${state#broken: }
        reason=${reason%%:*}
        why[$reason]=$((${why[$reason]:-0} + 1))
        # start the next try from a complete set
        rm -rf "$out"
        "$nceig" "$work/run_4.nml" >/dev/null 2>&1
        state=$(set_state "$out" "$work/ref_4" "$work/ref_5")
    elif [[ $state == "$previous" ]]; then
        n_old=$((n_old + 1))
    else
        n_new=$((n_new + 1))
    fi
done
echo "      $tries kills: previous set kept $n_old, new set complete $n_new," \
    "lost (neither) $n_broken; $n_finished runs had finished"
for reason in "${!why[@]}"; do echo "      lost: ${why[$reason]} times $reason"; done
check 'every kill left a complete previous or new set' '[[ $n_broken -eq 0 ]]'
check 'some kills came before the commit' '[[ $n_old -ge 1 ]]'

# Kills aimed at the commit: as soon as summary.json, the last file, is in the staging
# folder (before the directory swap <out>/.nceig-partial-<pid>/, now
# <parent>/.<out>.nceig-staging-<pid>/).
n_aimed=0 n_lost=0
for ((i = 1; i <= tries / 2; i++)); do
    previous=$state
    k=4
    [[ $previous == "ref 0" ]] && k=5
    "$nceig" "$work/run_$k.nml" >/dev/null 2>&1 &
    pid=$!
    while kill -0 "$pid" 2>/dev/null; do
        if compgen -G "$work/.out.nceig-staging-$pid/summary.json" >/dev/null ||
            compgen -G "$out/.nceig-partial-$pid/summary.json" >/dev/null; then
            kill -KILL "$pid" 2>/dev/null && n_aimed=$((n_aimed + 1))
            break
        fi
    done
    wait "$pid" 2>/dev/null
    state=$(set_state "$out" "$work/ref_4" "$work/ref_5")
    if [[ $state == broken* ]]; then
        n_lost=$((n_lost + 1))
        echo "      aimed try $i: ${state:0:100}"
        rm -rf "$out"
        "$nceig" "$work/run_4.nml" >/dev/null 2>&1
        state=$(set_state "$out" "$work/ref_4" "$work/ref_5")
    fi
done
echo "      $((tries / 2)) kills aimed at the commit ($n_aimed hit a live process):" \
    "the directory held neither complete set $n_lost times"
check 'kills aimed at the commit left a complete previous or new set' '[[ $n_lost -eq 0 ]]'

"$nceig" "$work/run_4.nml" >/dev/null 2>&1
check 'the next run removes the staging folders of killed runs' \
    '[[ -z $(ls -A "$work" | grep nceig-staging) ]]'
check 'and commits its set' '[[ $(set_state "$out" "$work/ref_4") == "ref 0" ]]'

cli_end
