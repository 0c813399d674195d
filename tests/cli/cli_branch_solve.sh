#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The 'branch' and 'solve' analyses from the command line: their files and summary keys, the
# branch to round-off, two starting guesses at the critical point giving two members, a
# failed Newton iteration reported with its history, and bad &branch / &solve input.
# Usage: cli_branch_solve.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_branch_solve

cat >"$work/branch.nml" <<NML
&mesh nx = 6, ny = 6, element = 'q1' /
&analysis kind = 'branch', lambda = 5.0 /
&branch alpha = 0.05, beta = 0.2, n_delta = 7, write_members = 2 /
&output directory = '$work/branch' /
NML
"$nceig" "$work/branch.nml" >"$work/stdout" 2>"$work/stderr"; rc=$?
check 'branch runs' '[[ $rc -eq 0 && ! -s "$work/stderr" ]]'
for f in summary.json eigenvalues.csv branch.csv branch_001.vtu branch_007.vtu; do
    check "branch writes $f" '[[ -s "$work/branch/$f" ]]'
done
check 'branch writes only the members asked for' '[[ ! -e "$work/branch/branch_004.vtu" ]]'
check 'branch.csv header and 7 rows' '[[ $(head -1 "$work/branch/branch.csv") == "index,delta,residual" && $(wc -l <"$work/branch/branch.csv") -eq 8 ]]'
check 'summary has delta_max and branch_max_residual' 'for k in delta_max branch_max_residual critical_c_n; do grep -q "\"$k\":" "$work/branch/summary.json" || exit 1; done'
# round-off: 100 eps times ||K|| ||x|| / ||b|| is about 1e-13 here
check 'branch_max_residual below 1e-12' 'awk -v r="$(json "$work/branch/summary.json" branch_max_residual)" "BEGIN { exit !(r < 1e-12) }"'
check 'the last member has delta = delta_max' '[[ $(tail -1 "$work/branch/branch.csv" | cut -d, -f2) == $(json "$work/branch/summary.json" delta_max) ]]'

solve() {  # name, &solve body
    cat >"$work/$1.nml" <<NML
&mesh nx = 6, ny = 6 /
&analysis kind = 'solve', lambda = 5.0 /
&solve $2 /
&output directory = '$work/$1' /
NML
    "$nceig" "$work/$1.nml" >"$work/$1.out" 2>"$work/$1.err"
}
solve given "c_n = 0.5, c_t = 0.2, u_d1 = 0.02, u_d2 = -0.05"; rc=$?
check 'solve runs' '[[ $rc -eq 0 && ! -s "$work/given.err" ]]'
for f in summary.json newton.csv contact_states.csv solution.vtu; do
    check "solve writes $f" '[[ -s "$work/given/$f" ]]'
done
check 'contact_states.csv header' '[[ $(head -1 "$work/given/contact_states.csv") == "node,x,y,u_n,u_t,normal_force,tangential_force,friction_bound,state" ]]'
check 'solve summary: converged and state counts add up to n_contact' '[[ $(json "$work/given/summary.json" converged) == true && $(( $(json "$work/given/summary.json" n_separated) + $(json "$work/given/summary.json" n_stick) + $(json "$work/given/summary.json" n_slip_plus) + $(json "$work/given/summary.json" n_slip_minus) )) -eq $(json "$work/given/summary.json" n_contact) ]]'

solve start_a "data = 'branch', start = 'branch', start_delta = 0.03, start_noise = 0.01"
solve start_b "data = 'branch', start = 'branch', start_delta = -0.03, start_noise = 0.01"
da=$(json "$work/start_a/summary.json" branch_delta); db=$(json "$work/start_b/summary.json" branch_delta)
check 'critical point: both guesses converge onto the branch line' 'for d in start_a start_b; do awk -v r="$(json "$work/$d/summary.json" branch_distance)" "BEGIN { exit !(r < 1e-8) }" || exit 1; done'
check "critical point: two guesses, two members (delta $da, $db)" 'awk -v a="$da" -v b="$db" "BEGIN { exit !(a - b > 0.02) }"'

solve failing "c_n = 0.5, c_t = 0.2, u_d2 = -0.05, max_iterations = 1"; rc=$?
check 'failed Newton: non-zero exit and one stderr line with the history' '[[ $rc -ne 0 && $(wc -l <"$work/failing.err") -eq 1 ]] && grep -q "did not converge.*history" "$work/failing.err"'
check 'failed Newton: history and summary written, no solution' '[[ -s "$work/failing/newton.csv" && $(json "$work/failing/summary.json" converged) == false && ! -e "$work/failing/solution.vtu" ]]'

bad() {  # name, namelist text, expected words in the message
    local want=$3
    printf '%s\n' "$2" >"$work/bad.nml"
    "$nceig" "$work/bad.nml" >/dev/null 2>"$work/err"; local rc=$?
    check "bad input ($1): one stderr line naming $3" '[[ $rc -ne 0 && $(wc -l <"$work/err") -eq 1 ]] && grep -q -- "$want" "$work/err"'
}
bad 'alpha' "&analysis kind = 'branch' / &branch alpha = -1.0 / &output directory = '$work/bad' /" '&branch: alpha'
bad 'start' "&analysis kind = 'solve' / &solve start = 'nowhere' / &output directory = '$work/bad' /" '&solve: start'
bad 'contact on top' "&mesh dirichlet = 'bottom', contact = 'top' / &analysis kind = 'branch' / &output directory = '$work/bad' /" 'normal (0, -1)'
check 'bad input leaves no output' '[[ ! -e "$work/bad" ]]'

cli_end
