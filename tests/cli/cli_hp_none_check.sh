#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# An hp side met as 'none' (no value at its last three levels) is confirmed at exit 0 only
# where the check of the last level, every degree raised by one, has no value there either:
# the levels' changes cannot bound a value they never had. Contact on the left half of the
# bottom (input/half_contact.nml) with &adapt p_max = 2: levels 1 to 3 have no real pencil
# value on the plus side, the check (degree 3 where the levels stop at 2) has one, and both
# the plain run on the input mesh and hp level 4 have one too; lambda- meets the loose
# tolerance. Before the check looked at 'none' sides this run said "tolerance met", exit 0,
# lambda+ none. Usage: cli_hp_none_check.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source_dir=$2
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_hp_none_check

nml=$source_dir/input/half_contact.nml
"$nceig" "$nml" --set output%directory="$work/plain" --set output%plot=.false. \
    >"$work/plain.out" 2>&1; rc=$?
check 'the plain run on the input mesh: a real pencil value lambda+ > 0 (exit 0)' \
    '[[ $rc -eq 0 ]] && awk -v v="$(json "$work/plain/summary.json" lambda_critical_plus)" \
        "BEGIN { exit !(v != \"null\" && v > 0) }"'

"$nceig" "$nml" --set adapt%strategy=hp --set adapt%tolerance=1e-2 --set adapt%p_max=2 \
    --set output%directory="$work/hp" --set output%plot=.false. \
    >"$work/hp.out" 2>"$work/hp.err"; rc=$?
s=$work/hp/summary.json
check 'hp, p_max = 2: lambda+ none at levels 1 to 3, the check finds one: exit 8, not converged' \
    '[[ $rc -eq 8 && $(json "$s" adapt_converged) == false && $(json "$s" adapt_levels) == 3 &&
       $(json "$s" lambda_critical_plus) == null ]]'
value=$(sed -n 's/.*none at hp levels 1 to 3, but the check of hp level 3 with every degree raised by one ([0-9]* dofs) finds lambda+ = \([^:]*\): it appears with the degree, not converged.*/\1/p' "$work/hp.err" | head -n 1)
check 'the stderr line names the side, the value the check found and why' \
    '[[ $(wc -l <"$work/hp.err") -eq 1 && -n $value ]] &&
    awk -v v="$value" "BEGIN { exit !(v + 0 > 0) }"'
check 'the same words among the warnings, and lambda- still met on its own' \
    'grep -q "finds lambda+ = .*: it appears with the degree, not converged" "$s" &&
    grep -q "lambda-: tolerance 1.00E-02 met at level 3" "$work/hp.err"'

# one level more (no cap on the levels): hp level 4 has the plus value the check found at
# level 3 (a value that appears after three levels without one: not converged either)
"$nceig" "$nml" --set adapt%strategy=hp --set adapt%tolerance=1e-6 --set adapt%p_max=2 \
    --set adapt%max_levels=4 --set output%directory="$work/hp4" --set output%plot=.false. \
    >"$work/hp4.out" 2>"$work/hp4.err"; rc=$?
check 'hp level 4 has a lambda+ the levels 1 to 3 did not have' \
    '[[ $rc -eq 8 ]] && [[ -n $(awk -F, "NR == 5 { print \$5 }" "$work/hp4/adapt.csv") ]] &&
    [[ -z $(awk -F, "NR >= 2 && NR <= 4 { printf \"%s\", \$5 }" "$work/hp4/adapt.csv") ]]'

# An eigen lambda met as 'none, confirmed' is checked the same way. lambda = -1.49 lies below
# the scene's onset -1.4858 (tests/cli/cli_adapt_no_mu.sh), where a positive mu exists: hp
# levels capped at degree 1 (p_max = 1) have none at levels 1 to 3, the check at degree 2
# has one, and so do levels capped at degree 2.
for p in 1 2; do
    "$nceig" "$nml" --set analysis%kind=eigen --set analysis%lambda=-1.49 \
        --set adapt%strategy=hp --set adapt%tolerance=1e-2 --set adapt%p_max=$p \
        --set output%directory="$work/eig$p" --set output%plot=.false. \
        >"$work/eig$p.out" 2>"$work/eig$p.err"; echo $? >"$work/eig$p.rc"
done
check 'eigen, p_max = 1: no positive mu at levels 1 to 3, the check finds one: exit 8' \
    '[[ $(cat "$work/eig1.rc") -eq 8 && $(json "$work/eig1/summary.json" adapt_converged) == false ]] &&
    grep -q "no positive mu at hp levels 1 to 3 (.* dofs), but the check of hp level 3 with every degree raised by one ([0-9]* dofs) finds mu = .*: it appears with the degree, not converged" "$work/eig1.err"'
check 'eigen, p_max = 2: the levels have that positive mu' \
    '[[ $(json "$work/eig2/summary.json" critical_c_n) != null ]]'
cli_end
