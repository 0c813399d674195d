#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# &eigen operator = 'full' and cn_max from the command line: summary.json names the operator
# and lists the critical c_n, eigenvalues.csv and the mode files carry each of them, and
# the full and the reduced operator print the same numbers.
# Tolerance 1e-10 relative between the operators: both converge to backward errors ~1e-16
# on eigenvalues with condition numbers below 1e4, so each is within ~1e-12 of the exact
# discrete mu (tests/eigen/test_full_operator.f90 has the detail); a wrong eigenvalue is 10x away.
# Usage: cli_full_operator.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_full_operator

# run NAME OPERATOR 'eigen extras' 'output extras': P1 16 x 16, lambda = 20 (four positive
# eigenvalues: 0.126, 5.53, 20.7, 47.2), output in $work/NAME
run() {
    cat >"$work/$1.nml" <<NML
&mesh nx = 16, ny = 16, element = 'p1' /
&analysis kind = 'eigen', lambda = 20.0 /
&eigen solver = 'arpack', operator = '$2', estimate = 'off' $3 /
&output directory = '$work/$1', plot = .false. $4 /
NML
    "$nceig" "$work/$1.nml" >"$work/$1.out" 2>"$work/$1.err"
    echo $? >"$work/$1.rc"
}

run full full ', cn_max = 25' ', modes = 3'
run reduced reduced ', cn_max = 25' ', modes = 3'
run lowest full '' ''
s=$work/full/summary.json
check 'full: exit 0' '[[ $(cat "$work/full.rc") == 0 ]]'
check 'full: summary.json names the operator' '[[ $(json "$s" operator) == full ]]'
check 'reduced: summary.json names the operator' \
    '[[ $(json "$work/reduced/summary.json" operator) == reduced ]]'
check 'full: cn_max as given' 'close "$(json "$s" cn_max)" 25 0'
list=$(json "$s" critical_cn | tr -d '[] ')
check 'full: critical_cn holds the three positive mu up to 25' \
    '[[ $(echo "$list" | tr "," "\n" | grep -c .) == 3 ]]'
reduced_list=$(json "$work/reduced/summary.json" critical_cn | tr -d '[] ')
for i in 1 2 3; do
    a=$(echo "$list" | cut -d, -f$i)
    b=$(echo "$reduced_list" | cut -d, -f$i)
    check "critical c_n $i: full and reduced within 1e-10 ($a)" 'close "$a" "$b" 1e-10'
    row=$(sed -n "$((i + 1))p" "$work/full/eigenvalues.csv")
    check "critical c_n $i: row $i of eigenvalues.csv, kind positive" \
        '[[ $(echo "$row" | cut -d, -f4) == positive ]] && close "$(echo "$row" | cut -d, -f2)" "$a" 0'
    check "critical c_n $i: its mode file" '[[ -s "$work/full/mode_00$i.vtu" ]]'
done
check 'full: the first is critical_c_n' 'close "$(json "$s" critical_c_n)" "$(echo "$list" | cut -d, -f1)" 0'
check 'full without cn_max: critical_cn is the lowest alone' \
    '[[ $(json "$work/lowest/summary.json" critical_cn) == "[$(json "$work/lowest/summary.json" critical_c_n)]" ]]'
check 'full without cn_max: certified by ARPACK, not densely' \
    '[[ $(json "$work/lowest/summary.json" dense_decision) == false ]]'
# Its factor: CHOLMOD's own ordering (the progress line says so), no contact-last block;
# near the threshold lambda+ = 1.917 of 16 x 16 (mu ~ 1e5) ARPACK is undecided and the
# dense decision factors again with the contact dofs last, then decides like 'reduced'.
check 'full: K factored in CHOLMOD'"'"'s own ordering, once' \
    '[[ $(grep -c "factor .*CHOLMOD, its own ordering" "$work/lowest.out") == 1 &&
        $(grep -c "contact nodes last" "$work/lowest.out") == 0 ]]'
for op in full reduced; do
    cat >"$work/near_$op.nml" <<NML
&mesh nx = 16, ny = 16, element = 'p1' /
&analysis kind = 'eigen', lambda = 1.918 /
&eigen solver = 'arpack', operator = '$op', estimate = 'off' /
&output directory = '$work/near_$op', plot = .false., vtk = .false. /
NML
    "$nceig" "$work/near_$op.nml" >"$work/near_$op.out" 2>&1
done
n=$work/near_full/summary.json
check 'full near the threshold: the dense decision, after a contact-last factor' \
    '[[ $(json "$n" dense_decision) == true ]] && grep -q "contact nodes last" "$work/near_full.out"'
check 'full near the threshold: the same lowest mu as reduced (1e-10)' \
    'close "$(json "$n" lowest_positive_mu)" "$(json "$work/near_reduced/summary.json" lowest_positive_mu)" 1e-10'
check 'full: --help documents operator and cn_max' \
    '"$nceig" --help | grep -q "operator = " && "$nceig" --help | grep -q "cn_max = "'
cli_end
