#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SIGTERM and SIGINT at random moments of runs (most in the output phase) end the run by that
# signal, leave the previous complete set (or the new one, when the signal came after the
# commit) and no staging folder; nor do the parent directories a run created survive it.
# Usage: cli_signals.sh NCEIG SOURCE_DIR [TRIES]
set -u
nceig=$1
source "$2/tests/cli/lib/output_sets.bash"
tries=${3:-12}
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_signals
out="$work/out"
# Job control: a background job of a script otherwise ignores SIGINT, and nceig keeps an
# ignored signal ignored.
set -m

make_reference_sets "$nceig" "$work" "$out"
# The judge of the sets: a file of the other set makes a mix; a changed digit does not.
cp -a "$work/ref_4" "$work/judge"
cp "$work/ref_5/mode_007.vtu" "$work/judge/"
check 'a set holding a file of the other run is a mix' \
    '[[ $(set_state "$work/judge" "$work/ref_4" "$work/ref_5") == "broken: a mix"* ]]'
cp "$work/ref_4/mode_007.vtu" "$work/judge/"
sed -i '2s/[0-9],/0,/' "$work/judge/eigenvalues.csv"
check 'a set whose digits differ is its run'"'"'s' \
    '! cmp -s "$work/judge/eigenvalues.csv" "$work/ref_4/eigenvalues.csv" && [[ $(set_state "$work/judge" "$work/ref_4" "$work/ref_5" 2>/dev/null) == "ref 0" ]]'
rm -rf "$work/judge"
"$nceig" "$work/run_5.nml" >/dev/null 2>&1
duration=999999999
for i in 1 2 3; do
    t0=$(date +%s%N)
    "$nceig" "$work/run_5.nml" >/dev/null 2>&1
    t=$((($(date +%s%N) - t0) / 1000))
    ((t < duration)) && duration=$t
done
echo "      a run takes $duration us"

RANDOM=4321
state=$(set_state "$out" "$work/ref_4" "$work/ref_5")
for signal in TERM INT; do
    n_signalled=0 n_bad=0 n_left=0 n_status=0
    for ((i = 1; i <= tries; i++)); do
        k=4
        [[ $state == "ref 0" ]] && k=5
        delay=$((duration * 3 / 10 + RANDOM * duration * 8 / 10 / 32768))
        "$nceig" "$work/run_$k.nml" >/dev/null 2>&1 &
        pid=$!
        sleep "$(printf '0.%06d' "$delay")"
        kill -"$signal" "$pid" 2>/dev/null && n_signalled=$((n_signalled + 1))
        wait "$pid"
        rc=$?
        # 128 + signal number: ended by the signal; 0: it had finished
        [[ $rc -eq 0 || $rc -eq $((128 + $(kill -l "$signal"))) ]] || n_status=$((n_status + 1))
        state=$(set_state "$out" "$work/ref_4" "$work/ref_5")
        if [[ $state == broken* ]]; then
            n_bad=$((n_bad + 1))
            echo "      SIG$signal try $i (after $delay us, exit $rc): ${state:0:400}"
            rm -rf "$out"
            "$nceig" "$work/run_4.nml" >/dev/null 2>&1
            state=$(set_state "$out" "$work/ref_4" "$work/ref_5")
        fi
        if [[ -n $(ls -A "$work" | grep nceig-staging) ]]; then
            n_left=$((n_left + 1))
            echo "      SIG$signal try $i (after $delay us): left $(ls -A "$work" | grep nceig-staging)"
            rm -rf "$work"/.out.nceig-staging-*
        fi
    done
    echo "      SIG$signal: $n_signalled of $tries runs signalled while running"
    check "SIG$signal: every run ends by the signal or completes" '[[ $n_status -eq 0 ]]'
    check "SIG$signal: the directory always holds a complete set" '[[ $n_bad -eq 0 ]]'
    check "SIG$signal: no staging folder is left" '[[ $n_left -eq 0 ]]'
done

# A run into a new directory under new parents, signalled in its output phase: the
# parents it created go too (unless the signal came during the commit: it waits for it).
cat >"$work/deep.nml" <<NML
&mesh nx = 60, ny = 6 /
&eigen solver = 'dense' /
&output directory = '$work/new1/new2/out', modes = 61 /
NML
n_left=0 n_hit=0
for ((i = 1; i <= 4; i++)); do
    "$nceig" "$work/deep.nml" >/dev/null 2>&1 &
    pid=$!
    while kill -0 "$pid" 2>/dev/null; do
        if compgen -G "$work/new1/new2/.out.nceig-staging-$pid/mode_010.vtu" >/dev/null; then
            kill -TERM "$pid"
            break
        fi
    done
    wait "$pid"
    if [[ $? -eq 143 ]]; then   # ended by the signal (not finished before it)
        n_hit=$((n_hit + 1))
        # nothing, or (the signal came during the commit, which finished first) a whole set
        deep_out="$work/new1/new2/out"
        if [[ -e $work/new1 && $(set_state "$deep_out" "$deep_out") != "ref 0" ]]; then
            n_left=$((n_left + 1))
            ls -AR "$work/new1" | head -5
        fi
    fi
    rm -rf "$work/new1"
done
echo "      $n_hit of 4 runs into new parents ended by SIGTERM while writing"
check 'SIGTERM while writing into new parents leaves no directory' '[[ $n_left -eq 0 ]]'

cli_end
