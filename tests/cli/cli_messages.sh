#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Messages that said less than they should: an empty --set value got a syntax message about
# something else; a generated mesh's degenerate cell (width = 1e16) did not name the input
# file; a tolerance of 0.999999 was printed 1.00E+00; an hp run called its mesh p1 and its
# level change an "estimate" larger than its bar. (The boundary lines' "1 points" and
# "(0 -> 0)" are checked in test_threshold_run.)
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

cli_end
