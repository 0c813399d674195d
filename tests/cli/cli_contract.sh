#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The command-line contract of docs/outputs.md on a small reference scene: --help, --version,
# the output files and their headers, and bad input giving one stderr line, a non-zero exit
# and no output. Usage: cli_contract.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_contract

"$nceig" --version >"$work/version" 2>&1
check '--version prints the version' 'grep -q "^nceig [0-9]" "$work/version"'
"$nceig" --help >"$work/help" 2>&1
check '--help lists every group' 'for g in mesh material analysis eigen output; do grep -q "&$g" "$work/help" || exit 1; done'
"$nceig" >/dev/null 2>"$work/err"; rc=$?
check 'no argument: non-zero exit and one stderr line' '[[ $rc -ne 0 && $(wc -l <"$work/err") -eq 1 ]]'

cat >"$work/small.nml" <<NML
&mesh nx = 6, ny = 6 /
&output directory = '$work/out', modes = 2, matrices = .true. /
NML
"$nceig" "$work/small.nml" >"$work/stdout" 2>"$work/stderr"; rc=$?
check 'small scene runs' '[[ $rc -eq 0 && ! -s "$work/stderr" ]]'
for f in summary.json eigenvalues.csv mode_001.vtu mode_002.vtu K.mtx B.mtx; do
    check "writes $f" '[[ -s "$work/out/$f" ]]'
done
check 'no staging folder left' '[[ -z $(ls -A "$work" | grep nceig-staging) ]]'
check 'eigenvalues.csv header' '[[ $(head -1 "$work/out/eigenvalues.csv") == "index,re,im,kind,residual,condition,error_estimate,error_bar" ]]'
check 'summary.json has the contract keys' 'for k in analysis lambda element n_nodes n_dofs n_contact solver lowest_positive_mu critical_c_n critical_c_t slip_sign n_eigenvalues max_residual lowest_positive_roundoff time_assembly_s time_factor_s time_eigen_s time_total_s; do grep -q "\"$k\":" "$work/out/summary.json" || exit 1; done'
check 'stdout names the critical c_n' 'grep -q "critical c_n" "$work/stdout"'
check 'P1: summary.json has a number for lowest_positive_error_estimate' 'grep -q "\"lowest_positive_error_estimate\": [0-9]" "$work/out/summary.json"'
check 'P1: stdout has the relative error estimate of mu' 'grep -q "relative error estimate of mu: " "$work/stdout"'
check 'P1: eigenvalues.csv has the estimate in the first row only' '[[ $(sed -n 2p "$work/out/eigenvalues.csv" | cut -d, -f7) =~ ^[0-9] && -z $(sed -n 3p "$work/out/eigenvalues.csv" | cut -d, -f7) ]]'
check 'P1: mode_001.vtu has the cell data error_indicator, mode_002.vtu none' 'grep -aq "<CellData Scalars=\"error_indicator\">" "$work/out/mode_001.vtu" && ! grep -aq "<CellData" "$work/out/mode_002.vtu"'
"$nceig" "$work/small.nml" --set mesh%element=q1 --set output%directory="$work/q1" >"$work/stdout_q1" 2>&1
# Q1 has no degree above it: its estimate is the difference to Q1 on the halved mesh, a
# number, printed so, with a bar of 5 times it (error_bar's BAR_FACTOR) plus the round-off
# bound (lowest_positive_roundoff)
check 'Q1 (no enrichment): the estimate from the halved mesh, printed so' \
    'grep -q "\"lowest_positive_error_estimate\": [0-9]" "$work/q1/summary.json" && grep -q "(q1, halved mesh); error bar" "$work/stdout_q1"'
check 'Q1: the bar is 5 times the estimate plus the round-off bound' \
    'close "$(json "$work/q1/summary.json" lowest_positive_error_bar)" "$(awk -v e="$(json "$work/q1/summary.json" lowest_positive_error_estimate)" -v r="$(json "$work/q1/summary.json" lowest_positive_roundoff)" "BEGIN { printf \"%.17g\", 5 * e + r }")" 1e-14'
check 'K.mtx is Matrix Market' 'head -1 "$work/out/K.mtx" | grep -q "^%%MatrixMarket matrix coordinate real general"'

bad() {  # name, namelist text, expected words in the message
    local want=$3
    printf '%s\n' "$2" >"$work/bad.nml"
    rm -rf "$work/badout"
    "$nceig" "$work/bad.nml" >/dev/null 2>"$work/err"; local rc=$?
    check "bad input ($1): non-zero exit" '[[ $rc -ne 0 ]]'
    check "bad input ($1): one stderr line naming $3" '[[ $(wc -l <"$work/err") -eq 1 ]] && grep -q "bad.nml" "$work/err" && grep -q -- "$want" "$work/err"'
    check "bad input ($1): no output left" '[[ ! -e "$work/badout" ]]'
}
bad 'out of range' "&mesh nx = 0 / &output directory = '$work/badout' /" 'nx'
bad 'unknown variable' "&mesh nxx = 3 / &output directory = '$work/badout' /" '&mesh'
bad 'unknown element' "&mesh element = 'p7' / &output directory = '$work/badout' /" 'element'
"$nceig" "$work/missing.nml" >/dev/null 2>"$work/err"; rc=$?
check 'missing input file: non-zero exit, one line naming it' '[[ $rc -ne 0 && $(wc -l <"$work/err") -eq 1 ]] && grep -q missing.nml "$work/err"'

cli_end
