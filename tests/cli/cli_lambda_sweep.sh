#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# kind = 'threshold' and 'lambda_sweep' from the command line: summary keys, confirmations,
# lambda_sweep.csv (header, rows, empty cells inside the thresholds, c_t = c_n |lambda|, the
# same mu as the eigen solver at lambda), the optional plot (off with &output plot too), &sweep
# input errors, an adapted sweep that misses its tolerance (a warning, adapt_converged), one
# whose point fails (a partial set) and one stopped by a signal (the previous set stays).
# Usage: cli_lambda_sweep.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_lambda_sweep

cat >"$work/thr.nml" <<NML
&mesh nx = 8, ny = 8 /
&analysis kind = 'threshold' /
&output directory = '$work/thr', vtk = .false. /
NML
"$nceig" "$work/thr.nml" >"$work/stdout" 2>"$work/stderr"; rc=$?
check 'threshold runs' '[[ $rc -eq 0 && ! -s "$work/stderr" ]]'
check 'threshold: summary has the contract keys' 'for k in analysis lambda n_contact lowest_positive_mu time_total_s lambda_critical_plus lambda_critical_minus; do grep -q "\"$k\":" "$work/thr/summary.json" || exit 1; done'
plus=$(json "$work/thr/summary.json" lambda_critical_plus)
minus=$(json "$work/thr/summary.json" lambda_critical_minus)
check "threshold: lambda+ = $plus > 0 > lambda- = $minus" 'awk -v p="$plus" -v m="$minus" "BEGIN { exit !(p > 0 && m < 0) }"'
check 'threshold: both confirmed' '[[ $(json "$work/thr/summary.json" lambda_critical_plus_confirmed) == true && $(json "$work/thr/summary.json" lambda_critical_minus_confirmed) == true ]]'
check 'threshold: no positive mu just inside' '[[ $(json "$work/thr/summary.json" mu_plus_inside) == null && $(json "$work/thr/summary.json" mu_minus_inside) == null ]]'
check 'threshold: a large positive mu just outside' 'awk -v a="$(json "$work/thr/summary.json" mu_plus_outside)" -v b="$(json "$work/thr/summary.json" mu_minus_outside)" "BEGIN { exit !(a > 1e4 && b > 1e4) }"'
check 'threshold: stdout shows lambda+ and lambda- confirmed' '[[ $(grep -c "lambda[+-] .*confirmed" "$work/stdout") -eq 2 ]]'
check 'threshold: no sweep file' '[[ ! -e "$work/thr/lambda_sweep.csv" ]]'

cat >"$work/list.nml" <<NML
&mesh nx = 8, ny = 8 /
&analysis kind = 'lambda_sweep', lambda = 5.0 /
&sweep lambdas = 5.0, -5.0, 0.5, -30.0, plot = .false. /
&output directory = '$work/list', vtk = .false. /
NML
"$nceig" "$work/list.nml" >"$work/stdout" 2>"$work/stderr"; rc=$?
csv="$work/list/lambda_sweep.csv"
check 'list sweep runs' '[[ $rc -eq 0 && ! -s "$work/stderr" ]]'
check 'sweep csv header' '[[ $(head -1 "$csv") == "lambda,critical_c_n,critical_c_t,slip_sign,n_positive,error_estimate,n_dofs,error_bar" ]]'
check 'sweep csv: one row per lambda, in the given order' '[[ $(tail -n +2 "$csv" | cut -d, -f1 | tr "\n" " ") == "5.0 -5.0 0.5 -30.0 " ]]'
check 'sweep csv: empty c_n and c_t and no positive mu inside the thresholds' '[[ $(sed -n 4p "$csv" | cut -d, -f1-6) == "0.5,,,-1,0," ]]'
check 'sweep csv: c_t = c_n |lambda|' 'tail -n +2 "$csv" | awk -F, "\$2 != \"\" { l = \$1 < 0 ? -\$1 : \$1; d = \$3 - \$2 * l; if (d < 0) d = -d; if (d > 1e-14 * \$3) exit 1 }"'
check 'sweep csv: slip sign -sgn(lambda)' '[[ $(tail -n +2 "$csv" | cut -d, -f4 | tr "\n" " ") == "-1 1 -1 1 " ]]'
# The sweep (dgeev on the reduced matrix) and the eigen solve at lambda (dgeevx) are two
# backward-stable paths to the same mu (condition ~ 10): agreement to 1e-12 relative.
check 'sweep mu at lambda = 5 equals the eigen solver'"'"'s lowest positive mu' 'awk -v a="$(sed -n 2p "$csv" | cut -d, -f2)" -v b="$(json "$work/list/summary.json" lowest_positive_mu)" "BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-12 * b) }"'
check 'sweep summary has the thresholds and sweep keys' 'for k in lambda_critical_plus lambda_critical_minus sweep_file sweep_n_lambda sweep_spacing time_sweep_s; do grep -q "\"$k\":" "$work/list/summary.json" || exit 1; done'
check 'sweep summary: spacing list, 4 lambdas, 3 with a mu' '[[ $(json "$work/list/summary.json" sweep_spacing) == list && $(json "$work/list/summary.json" sweep_n_lambda) == 4 && $(json "$work/list/summary.json" sweep_n_with_positive_mu) == 3 ]]'
check 'plot = .false.: no png, no note' '[[ ! -e "$work/list/lambda_sweep.png" ]] && ! grep -q "^  plot " "$work/stdout"'

cat >"$work/range.nml" <<NML
&mesh nx = 4, ny = 4, element = 'q1' /
&analysis kind = 'lambda_sweep' /
&sweep lambda_min = -1000.0, lambda_max = -1.0, n_lambda = 7, spacing = 'log' /
&output directory = '$work/range', vtk = .false. /
NML
"$nceig" "$work/range.nml" >"$work/stdout" 2>"$work/stderr"; rc=$?
check 'log range sweep runs' '[[ $rc -eq 0 && ! -s "$work/stderr" ]]'
check 'log range: 7 rows from -1000 to -1' '[[ $(tail -n +2 "$work/range/lambda_sweep.csv" | wc -l) -eq 7 && $(sed -n 2p "$work/range/lambda_sweep.csv" | cut -d, -f1) == -1000.0 && $(tail -1 "$work/range/lambda_sweep.csv" | cut -d, -f1) == -1.0 ]]'
if command -v gnuplot >/dev/null; then
    check 'gnuplot installed: lambda_sweep.png is a non-empty PNG, listed' 'drawn "$work/range" lambda_sweep.png'
    check 'gnuplot installed: stdout names the plot' 'grep -q "plot .*lambda_sweep.png" "$work/stdout"'
else
    check 'no gnuplot: a note, no png, success' 'grep -q "plot .*not drawn" "$work/stdout" && [[ ! -e "$work/range/lambda_sweep.png" ]]'
fi
check 'no staging folder left' '[[ -z $(ls -A "$work" | grep nceig-staging) ]]'

bad() {  # name, &sweep body, expected words in the message
    local want=$3
    printf "&analysis kind = 'lambda_sweep' /\n&sweep %s /\n&output directory = '%s' /\n" \
        "$2" "$work/badout" >"$work/bad.nml"
    rm -rf "$work/badout"
    "$nceig" "$work/bad.nml" >/dev/null 2>"$work/err"; local rc=$?
    check "bad &sweep ($1): exit 2" '[[ $rc -eq 2 ]]'
    check "bad &sweep ($1): one stderr line naming the file, &sweep and $3" '[[ $(wc -l <"$work/err") -eq 1 ]] && grep -q "bad.nml: &sweep" "$work/err" && grep -q -- "$want" "$work/err"'
    check "bad &sweep ($1): no output left" '[[ ! -e "$work/badout" ]]'
}
bad 'log across zero' "lambda_min = -1.0, lambda_max = 2.0, spacing = 'log'" 'lambda_min'
bad 'empty range' 'lambda_min = 3.0, lambda_max = 3.0' 'lambda_max'
bad 'one point' 'n_lambda = 1' 'n_lambda'
bad 'unknown spacing' "spacing = 'cubic'" 'spacing'
bad 'unknown variable' 'lambda_mni = 1.0' 'lambda_mni'
bad 'gap in the list' 'lambdas(1) = 1.0, lambdas(3) = 2.0' 'lambdas(3)'

# solver = 'arpack' (refused before): the spectrum at lambda and the sweep points by ARPACK,
# on the same factor; the curve must match the dense one (1e-9 relative: well-conditioned
# eigenvalues, backward-stable solvers, see test_threshold_analysis).
for s in dense arpack; do
    cat >"$work/$s.nml" <<NML
&mesh nx = 16, ny = 16 /
&analysis kind = 'lambda_sweep', lambda = 5.0 /
&eigen solver = '$s' /
&sweep lambda_min = -10.0, lambda_max = 10.0, n_lambda = 21, plot = .false. /
&output directory = '$work/$s', vtk = .false. /
NML
    "$nceig" "$work/$s.nml" >"$work/stdout" 2>"$work/stderr"; rc=$?
    check "sweep with solver = '$s' runs" '[[ $rc -eq 0 && ! -s "$work/stderr" ]]'
done
check 'arpack sweep: solver arpack, some points certified by ARPACK' '[[ $(json "$work/arpack/summary.json" solver) == arpack && $(json "$work/arpack/summary.json" sweep_n_arpack) -gt 0 ]]'
check 'arpack sweep: same thresholds as dense' '[[ $(json "$work/arpack/summary.json" lambda_critical_plus) == $(json "$work/dense/summary.json" lambda_critical_plus) && $(json "$work/arpack/summary.json" lambda_critical_minus) == $(json "$work/dense/summary.json" lambda_critical_minus) ]]'
# (7 columns each: the arpack row's c_n is field 9 of the pasted line)
check 'arpack sweep: same curve as dense' 'paste -d, "$work/dense/lambda_sweep.csv" "$work/arpack/lambda_sweep.csv" | tail -n +2 | awk -F, "{ if ((\$2 == \"\") != (\$10 == \"\")) exit 1; if (\$2 != \"\") { d = \$2 - \$10; if (d < 0) d = -d; if (d > 1e-9 * \$2) exit 1 } }"'

# &output plot = .false. is every picture's switch: lambda_sweep.png was drawn all the same.
cat >"$work/noplot.nml" <<NML
&mesh nx = 4, ny = 4 /
&analysis kind = 'lambda_sweep' /
&sweep lambdas = 3.0, 5.0 /
&output directory = '$work/noplot', plot = .false. /
NML
"$nceig" "$work/noplot.nml" >"$work/stdout" 2>"$work/stderr"; rc=$?
check '&output plot = .false.: no lambda_sweep.png, none listed' \
    '[[ $rc -eq 0 && ! -e "$work/noplot/lambda_sweep.png" ]] && ! grep -q lambda_sweep.png "$work/noplot/summary.json"'

# An adapted sweep that misses its tolerance (h and hp) says so where a user looks: a
# warning in summary.json and on stdout, adapt_converged false; then exit 8.
for strategy in h hp; do
    cat >"$work/miss_$strategy.nml" <<NML
&mesh nx = 4, ny = 4, element = 'p2' /
&analysis kind = 'lambda_sweep' /
&sweep lambdas = 3.0, 5.0 /
&adapt tolerance = 1e-9, max_levels = 1, strategy = '$strategy' /
&output directory = '$work/miss_$strategy', plot = .false. /
NML
    "$nceig" "$work/miss_$strategy.nml" >"$work/stdout" 2>"$work/stderr"; rc=$?
    summary="$work/miss_$strategy/summary.json"
    check "adapted sweep ($strategy) missing its tolerance: exit 8, sweep_n_not_met 2" \
        '[[ $rc -eq 8 && $(json "$summary" sweep_n_not_met) == 2 ]]'
    check "adapted sweep ($strategy) missing its tolerance: adapt_converged false" \
        '[[ $(json "$summary" adapt_converged) == false ]]'
    check "adapted sweep ($strategy) missing its tolerance: a warning in summary.json and on stdout" \
        'grep -q "\"warnings\": \[\"2 of the 2 sweep points did not meet the tolerance" "$summary" && grep -q "^warning: 2 of the 2 sweep points did not meet the tolerance" "$work/stdout"'
done

# A point's loop that fails (here: young = 1e-10 makes mu at lambda = 1e300 about 2e-310,
# which binary64 cannot hold: exit 2 at that point) leaves a partial set of the points
# complete before it, marked partial (they were lost: nothing was written); the run ends
# with that failure's status and one line.
cat >"$work/partial.nml" <<NML
&mesh nx = 4, ny = 4, element = 'p2' /
&material young = 1e-10 /
&analysis kind = 'lambda_sweep' /
&sweep lambdas = 5.0, 3.0, 1e300, 4.0 /
&adapt tolerance = 1e-4 /
&output directory = '$work/partial', plot = .false., modes = 1 /
NML
"$nceig" "$work/partial.nml" >"$work/stdout" 2>"$work/stderr"; rc=$?
summary="$work/partial/summary.json"
echo "      $(head -c 300 "$work/stderr")"
check 'a failed point: exit 2, one line saying the partial set is written' \
    '[[ $rc -eq 2 && $(wc -l <"$work/stderr") -eq 1 ]] && grep -q "a partial set of the 2 of 4 points complete is written" "$work/stderr"'
check 'a failed point: lambda_sweep.csv holds the two points before it' \
    '[[ $(tail -n +2 "$work/partial/lambda_sweep.csv" | cut -d, -f1 | tr "\n" " ") == "5.0 3.0 " ]]'
check 'a failed point: summary.json marks the set partial, with a warning' \
    '[[ $(json "$summary" sweep_partial) == true && $(json "$summary" sweep_n_complete) == 2 ]] && grep -q "\"warnings\": \[\"the sweep is partial: 2 of its 4 points" "$summary" && grep -q "^warning: the sweep is partial" "$work/stdout"'

# A signal during an adapted sweep commits nothing: the previous set stays.
sed -i "s|young = 1e-10|young = 1.0|; s|1e300|2.5|" "$work/partial.nml"
"$nceig" "$work/partial.nml" >/dev/null 2>&1
cp -a "$work/partial" "$work/partial.kept"
sed -i "s|tolerance = 1e-4|tolerance = 1e-7|" "$work/partial.nml"
"$nceig" "$work/partial.nml" >"$work/stdout" 2>&1 &
pid=$!
while kill -0 "$pid" 2>/dev/null && ! grep -q 'sweep, lambda 2/' "$work/stdout"; do sleep 0.01; done
kill -TERM "$pid" 2>/dev/null
wait "$pid"
rc=$?
check 'SIGTERM during an adapted sweep: exit 143, the previous set intact' \
    '[[ $rc -eq 143 ]] && diff -r "$work/partial" "$work/partial.kept" >/dev/null'

cli_end
