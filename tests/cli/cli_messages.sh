#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Messages that said less than they should: an empty --set value got a syntax message about
# something else; a generated mesh's degenerate cell (width = 1e16) did not name the input
# file; a tolerance of 0.999999 was printed 1.00E+00; an hp run called its mesh p1 and its
# level change an "estimate" larger than its bar; a c_n whose bar exceeds it was quoted
# plainly, and ARPACK (unlike the dense solver) did not say that lambda was near a critical
# value. (The boundary lines' "1 points" and "(0 -> 0)" are checked in test_threshold_run.)
# Usage: cli_messages.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source_dir=$2
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_messages
cd "$work"
square="$source_dir/input/square.nml"

"$nceig" "$square" --set mesh%dirichlet= >out 2>err
rc=$?
echo "      $(cat err)"
check 'an empty --set value: exit 2, one line naming &mesh, dirichlet and the missing value' \
    "[[ \$rc -eq 2 && \$(wc -l <err) -eq 1 ]] && grep -q '&mesh: dirichlet: no value after' err"

"$nceig" "$square" --set mesh%width=1e16 --set output%directory=runs >out 2>err
rc=$?
echo "      $(cat err)"
check 'a degenerate generated cell (width = 1e16): exit 3, one line naming the input' \
    "[[ \$rc -eq 3 && \$(wc -l <err) -eq 1 ]] && grep -q '^nceig: $square: mesh: cell 1 is' err"

"$nceig" "$source_dir/input/adapt.nml" --set adapt%tolerance=0.999999 \
    --set output%directory=runs --set output%plot=.false. >out 2>err
check 'a tolerance of 0.999999 is printed as given, not rounded to 1.00E+00' \
    "grep -q 'tolerance 9.99999E-01 met' out && ! grep -q 'tolerance 1.00E+00' out"

"$nceig" "$source_dir/input/adapt.nml" --set adapt%strategy=hp --set adapt%tolerance=1e-6 \
    --set output%directory=hp --set output%plot=.false. >out 2>err
grep -E '^  (mesh|relative)' out | sed 's/^/      /'
check 'an hp run: its mesh is hp, not p1 (stdout and summary.json)' \
    "grep -q '^  mesh        rectangle, hp, ' out && grep -q '\"element\": \"hp\"' hp/summary.json"
check 'an hp run: the level change is called what it is, beside the bar' \
    "grep -q '^  relative change of mu to the previous hp level: .* (the error of that level); error bar ' out && ! grep -q 'relative error estimate of mu' out"

# Near a critical lambda, on every solver path. At lambda = 1.94 the 32 x 32 mesh has
# lambda+ = 1.9334 and a positive mu of 517, with a bar of 7.5e3 (the continuum's lambda+ is
# 1.9447: it has no positive mu there): 'no certain digit', with a warning. At 1.93337, 5e-6
# relative from this mesh's lambda+, ARPACK (the default) now warns as the dense solver
# did, with the same sensitivity of mu to lambda (computed from its left vector).
for solver in arpack dense; do
    "$nceig" "$square" --set analysis%lambda=1.94 --set eigen%solver=$solver \
        --set output%directory=near_$solver --set output%plot=.false. >out 2>err
    check "lambda = 1.94 ($solver): c_n with no certain digit, and a warning saying why" \
        "grep -q 'critical c_n = .* +- .* (no certain digit)' out && grep -q '^warning: no digit of the lowest positive mu is certain' out && grep -q 'no digit of the lowest positive mu' near_$solver/summary.json"
    "$nceig" "$square" --set analysis%lambda=1.93337 --set eigen%solver=$solver \
        --set output%directory=near_$solver --set output%plot=.false. >out_$solver 2>err
done
sensitivity() { sed -n 's/.*changes \([^ ]*\) times faster than lambda.*/\1/p' "$1"; }
echo "      sensitivity of mu to lambda at 1.93337: arpack $(sensitivity out_arpack), dense $(sensitivity out_dense)"
check 'lambda = 1.93337: ARPACK warns that lambda is near a critical value, as dense does' \
    "grep -q '^warning: lambda is near a critical value' out_arpack && grep -q '^warning: lambda is near a critical value' out_dense"
check 'lambda = 1.93337: the same sensitivity from both solvers (3 digits)' \
    '[[ -n $(sensitivity out_arpack) && $(sensitivity out_arpack) == $(sensitivity out_dense) ]]'

cli_end
