#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# solver = 'arpack' through the command line: the summary keys it adds, K.mtx and B.mtx
# identical to those of the dense solver (the same problem, for any other solver), and the
# same lowest positive mu as the dense solver. Usage: cli_arpack.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_arpack

for solver in arpack dense; do
    cat >"$work/$solver.nml" <<NML
&mesh nx = 24, ny = 24, diagonal = 'left' /
&analysis lambda = -4.0 /
&eigen solver = '$solver' /
&output directory = '$work/$solver', modes = 2, matrices = .true. /
NML
    "$nceig" "$work/$solver.nml" >"$work/$solver.out" 2>"$work/$solver.err"; rc=$?
    check "$solver runs" '[[ $rc -eq 0 && ! -s "$work/$solver.err" ]]'
done
check 'summary names the solver arpack' '[[ $(json "$work/arpack/summary.json" solver) == arpack ]]'
check 'certified: the warnings array is empty' '[[ $(json "$work/arpack/summary.json" warnings) == "[]" ]]'
check 'stdout has no warning: line' '! grep -q "^warning:" "$work/arpack.out"'
check 'summary has time_ordering_s and operator_applications > 0' \
    '[[ -n $(json "$work/arpack/summary.json" time_ordering_s) && $(json "$work/arpack/summary.json" operator_applications) -gt 0 ]]'
for f in K.mtx B.mtx mode_001.vtu mode_002.vtu eigenvalues.csv; do
    check "arpack writes $f" '[[ -s "$work/arpack/$f" ]]'
done
check 'K.mtx identical to the dense run' 'cmp -s "$work/arpack/K.mtx" "$work/dense/K.mtx"'
check 'B.mtx identical to the dense run' 'cmp -s "$work/arpack/B.mtx" "$work/dense/B.mtx"'
# Both solvers are backward stable and this eigenvalue is well conditioned (dgeevx: ~10):
# 1e-9 relative is far above their rounding and far below the gap to the next eigenvalue.
a=$(json "$work/arpack/summary.json" lowest_positive_mu) d=$(json "$work/dense/summary.json" lowest_positive_mu)
check "same lowest positive mu ($a vs $d)" \
    'awk -v a="$a" -v d="$d" "BEGIN { e = a - d; if (e < 0) e = -e; exit !(d > 0 && e <= 1e-9 * d) }"'
check 'eigenvalues.csv: the first row is the positive one' \
    '[[ $(sed -n 2p "$work/arpack/eigenvalues.csv" | cut -d, -f4) == positive ]]'
cli_end
