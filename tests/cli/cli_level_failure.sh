#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# An adaptive run whose level after the first fails (a numerical library's failure) writes
# the results of its last complete level: the same values as a run stopped there by
# max_levels, adapt_converged false, a warning naming the level and the failure, and exit 5
# (README, "Exit statuses"). Before, such a run exited 5 and wrote nothing: an h-adapted
# threshold run of a random body failed at its level 32 after ten minutes. The failure is the
# test hook NCEIG_TEST_FAIL_LEVEL (docs/testing.md): h levels fail before their solve, hp
# levels at their factor, after the goal began to take the level in, so that the goal's
# last complete level must be made again (threshold_goal: restore_hp_level).
# Usage: cli_level_failure.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source_dir=$2
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_level_failure
cd "$work"
input="$source_dir/input/threshold_adapt.nml"

# run NAME ARGS...: input/threshold_adapt.nml with ARGS into NAME/; sets rc.
run() {
    local name=$1
    shift
    timeout 300 "$nceig" "$input" --set output%directory="$name" --set output%plot=.false. \
        --set output%progress=.false. "$@" >"$name.out" 2>"$name.err"
    rc=$?
}

# The values a run reports, without the bars the hp check gives the level a loop ends at
# (a run at max_levels checks it, a failed one does not) and the times: the adapt.csv
# columns up to the first time_s or error_bar one, and the summary's values.
values() {
    awk -F, 'NR == 1 { for (n = 1; n <= NF && $n != "time_s" && $n !~ /^error_bar/; n++); }
             { line = $1; for (i = 2; i < n; i++) line = line "," $i; print line }' \
        "$1/adapt.csv"
    for key in lowest_positive_mu lambda_critical_plus lambda_critical_minus \
        lambda_onset_plus lambda_onset_minus adapt_levels; do
        echo "$key $(json "$1/summary.json" "$key")"
    done
}

# Level 3 fails: h levels are 0, 1, 2 before it, hp levels 1, 2; max_levels = 2 stops both
# at the same last level.
for kind in eigen threshold; do
    for strategy in h hp; do
        name=${kind}_$strategy
        NCEIG_TEST_FAIL_LEVEL=3 run "$name" --set analysis%kind=$kind \
            --set adapt%strategy=$strategy
        failed_rc=$rc
        run "${name}_limit" --set analysis%kind=$kind --set adapt%strategy=$strategy \
            --set adapt%max_levels=2
        echo "      $(head -c 300 "$name.err")"
        check "$kind, $strategy: level 3 fails: exit 5, one line naming the level and the failure" \
            "[[ $failed_rc -eq 5 && \$(wc -l <$name.err) -eq 1 ]] && grep -q 'level 3: the failure NCEIG_TEST_FAIL_LEVEL asks for (level 3 failed): the results of the last complete level are written' $name.err"
        check "$kind, $strategy: the last complete level written, adapt_converged false" \
            "[[ -s $name/summary.json && -s $name/adapt.csv ]] && [[ \$(json $name/summary.json adapt_converged) == false ]]"
        check "$kind, $strategy: a warning names the failed level" \
            "grep -q 'not met: level 3 failed (level 3: the failure NCEIG_TEST_FAIL_LEVEL' $name/summary.json"
        check "$kind, $strategy: the values of a run stopped by max_levels = 2 (exit 8)" \
            "[[ $rc -eq 8 ]] && diff <(values $name) <(values ${name}_limit)"
    done
done

# Nothing but the last complete level's rows: none of the failed level.
check 'h: adapt.csv has levels 0 to 2' \
    "[[ \$(tail -n 1 threshold_h/adapt.csv | cut -d, -f1) == 2 ]]"

# Sweeps. hp: one climb for every lambda, which fails at level 3: each point as level 2 had
# it, the set flagged partial, exit 5. h: each point its own loop; the first fails at its
# level 3: the points complete before it (none) as a partial set, exit 5 (as before).
for strategy in hp h; do
    NCEIG_TEST_FAIL_LEVEL=3 run sweep_$strategy --set analysis%kind=lambda_sweep \
        --set adapt%strategy=$strategy --set sweep%n_lambda=5
    echo "      $(head -c 300 sweep_$strategy.err)"
    check "$strategy sweep: level 3 fails: exit 5, a partial set written" \
        "[[ \$rc -eq 5 && \$(json sweep_$strategy/summary.json sweep_partial) == true ]] && grep -q 'level 3 failed' sweep_$strategy.err"
done
check 'hp sweep: its 5 points as level 2 had them' \
    "[[ \$(json sweep_hp/summary.json sweep_n_complete) == 5 ]]"
cli_end
