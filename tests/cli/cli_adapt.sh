#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# &adapt end to end: the loop meets its tolerance and writes adapt.csv, adapt.png, the final
# mode with its error indicators and mesh.msh, which nceig reads back to the same problem
# and eigenvalue and can adapt further; the same for the critical lambdas and a sweep (with
# their pictures; without gnuplot a note and exit 0); a limit reached is exit 0 with a warning in
# summary.json and on stdout; bad input is one stderr line naming &adapt and the variable,
# exit 2, no output. Usage: cli_adapt.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_adapt

# The reference scene (the rectangle's defaults) at lambda = 5, P2 from 2 x 2 squares.
cat >"$work/adapt.nml" <<NML
&mesh nx = 2, ny = 2, element = 'p2' /
&analysis kind = 'eigen', lambda = 5.0 /
&output directory = '$work/out' /
&adapt tolerance = 1e-5 /
NML
"$nceig" "$work/adapt.nml" >"$work/stdout" 2>"$work/err"; rc=$?
s=$work/out/summary.json
check 'runs: exit 0, nothing on stderr' '[[ $rc -eq 0 && ! -s "$work/err" ]]'
check 'summary: converged' '[[ $(json "$s" adapt_converged) == true ]]'
check 'summary: the final estimate meets the tolerance' \
    'awk -v e="$(json "$s" lowest_positive_error_estimate)" "BEGIN { exit !(e > 0 && e <= 1e-5) }"'
check 'summary: no warning' 'grep -q "\"warnings\": \[\]" "$s"'
check 'stdout: the tolerance met' 'grep -q "tolerance 1.00E-05 met at level" "$work/stdout"'
# below the Doerfler fractions at which the bar was measured, the run says so (exit 0)
"$nceig" "$work/adapt.nml" --set adapt%theta=0.05 --set output%directory="$work/theta" \
    >"$work/stdout_theta" 2>&1; rc=$?
check 'theta = 0.05: exit 0 and a warning that the bar was not measured there' \
    '[[ $rc -eq 0 ]] && grep -q "^warning: &adapt theta = 5.00E-02 is below 0.1" "$work/stdout_theta" &&
     grep -q "is below 0.1" "$work/theta/summary.json"'
# and a lambda sweep adapted at each lambda says it once, for the run
"$nceig" "$work/adapt.nml" --set adapt%theta=0.05 --set adapt%tolerance=1e-4 \
    --set analysis%kind=lambda_sweep --set sweep%lambdas=3.0,5.0 \
    --set output%directory="$work/theta_sweep" >"$work/stdout_theta" 2>&1; rc=$?
check 'theta = 0.05, lambda sweep: exit 0 and the warning once' \
    '[[ $rc -eq 0 && $(grep -c "^warning: &adapt theta = 5.00E-02 is below 0.1" "$work/stdout_theta") -eq 1 ]]'
check 'stdout: one progress line per level' \
    '[[ $(grep -c "adapt level" "$work/stdout") -eq $(( $(json "$s" adapt_levels) + 1 )) ]]'
csv=$work/out/adapt.csv
check 'adapt.csv: header' \
    '[[ $(head -n 1 "$csv") == level,n_dofs,n_contact,n_cells,mu,error_estimate,time_s,error_bar ]]'
check 'adapt.csv: one row per level, the last the summary'\''s' \
    '[[ $(($(wc -l <"$csv") - 1)) -eq $(( $(json "$s" adapt_levels) + 1 )) &&
        $(tail -n 1 "$csv" | cut -d, -f2) == $(json "$s" n_dofs) ]]'
check 'adapt.csv: dofs grow, times grow' \
    'awk -F, "NR > 2 && (\$2 <= d || \$7 < t) { bad = 1 } NR > 1 { d = \$2; t = \$7 } END { exit bad }" "$csv"'
check 'mode_001.vtu carries the error indicators' \
    'grep -q "Name=\"error_indicator\"" "$work/out/mode_001.vtu"'
check 'summary lists mesh.msh and adapt.csv' \
    'grep -q "\"mesh.msh\"" "$s" && grep -q "\"adapt.csv\"" "$s"'
if command -v gnuplot >/dev/null; then
    check 'adapt.png and mode_001.png drawn and listed, stdout names them' \
        'drawn "$work/out" adapt.png && drawn "$work/out" mode_001.png &&
         grep -q "adapt plot  $work/out/adapt.png" "$work/stdout"'
fi

# mesh.msh read back: the same problem and eigenvalue (another node order: round-off).
cp "$work/out/mesh.msh" "$work/adapted.msh"
cat >"$work/back.nml" <<NML
&mesh source = 'gmsh', file = '$work/adapted.msh', dirichlet = 'top',
      neumann = 'left right', contact = 'bottom' /
&analysis kind = 'eigen', lambda = 5.0 /
&eigen estimate = 'on' /
&output directory = '$work/back', vtk = .false., plot = .false. /
NML
"$nceig" "$work/back.nml" >/dev/null 2>"$work/err"; rc=$?
b=$work/back/summary.json
check 'mesh.msh reads back' '[[ $rc -eq 0 && ! -s "$work/err" ]]'
check 'read back: the same dofs and contact nodes' \
    '[[ $(json "$b" n_dofs) == $(json "$s" n_dofs) && $(json "$b" n_contact) == $(json "$s" n_contact) ]]'
check 'read back: the same mu (1e-12)' \
    'close "$(json "$b" lowest_positive_mu)" "$(json "$s" lowest_positive_mu)" 1e-12'
check 'read back: the same estimate (1e-6 of it)' \
    'close "$(json "$b" lowest_positive_error_estimate)" "$(json "$s" lowest_positive_error_estimate)" 1e-6'
"$nceig" "$work/back.nml" --set adapt%tolerance=3e-6 --set output%directory="$work/further" \
    >/dev/null 2>"$work/err"; rc=$?
check 'a Gmsh mesh adapts further' '[[ $rc -eq 0 && ! -s "$work/err" &&
    $(json "$work/further/summary.json" adapt_converged) == true &&
    $(json "$work/further/summary.json" adapt_start_dofs) == $(json "$s" n_dofs) ]]'

# The full ARPACK operator factors K in CHOLMOD's own ordering: the estimate must still be
# made at every level, so the loop meets its tolerance as with the reduced operator.
"$nceig" "$work/adapt.nml" --set eigen%operator=full --set output%directory="$work/full" \
    >/dev/null 2>"$work/err"; rc=$?
check 'full operator: the loop meets its tolerance' '[[ $rc -eq 0 && ! -s "$work/err" &&
    $(json "$work/full/summary.json" adapt_converged) == true ]]'

# A limit: the set of the last level is written, with a warning in summary.json and on
# stdout that names the limit and what was reached, and the run exits 8 (tolerance not
# met) with one line on stderr, so that no script takes it for a success.
"$nceig" "$work/adapt.nml" --set adapt%max_levels=2 --set output%directory="$work/limit" \
    >"$work/stdout" 2>"$work/err"; rc=$?
l=$work/limit/summary.json
check 'max_levels reached: exit 8, one stderr line naming &adapt and the limit' \
    '[[ $rc -eq 8 && $(wc -l <"$work/err") -eq 1 ]] && grep -q "adapt.nml: &adapt: tolerance 1.00E-05 not met: max_levels = 2 reached" "$work/err"'
check 'max_levels reached: the set is written' '[[ -s "$work/limit/adapt.csv" && -s "$work/limit/mesh.msh" ]]'
check 'max_levels reached: not converged, 2 levels' \
    '[[ $(json "$l" adapt_converged) == false && $(json "$l" adapt_levels) == 2 ]]'
check 'max_levels reached: warning in summary.json' \
    'grep -A1 "\"warnings\"" "$l" | grep -q "tolerance 1.00E-05 not met: max_levels = 2 reached"'
check 'max_levels reached: warning on stdout' \
    'grep -q "^warning: tolerance 1.00E-05 not met: max_levels = 2 reached with error bar" "$work/stdout"'

# Below the round-off bound (nu -> 1/2: R grows like the Lame ratio and with the dofs): the
# loop stops at the floating-point floor, as the hp loop does, instead of refining in vain.
"$nceig" "$work/adapt.nml" --set material%poisson=0.499999999 \
    --set output%directory="$work/floor" >"$work/stdout" 2>"$work/err"; rc=$?
f=$work/floor/summary.json
check 'floor: exit 8, one stderr line, the set written' '[[ $rc -eq 8 && $(wc -l <"$work/err") -eq 1 &&
    -s "$work/floor/mesh.msh" && $(json "$f" adapt_converged) == false &&
    $(json "$f" adapt_floor_reached) == true ]]'
check 'floor: said on stdout and in the warnings' \
    'grep -q "^warning: tolerance 1.00E-05 not met: the floating-point floor is reached" "$work/stdout" &&
     grep -A1 "\"warnings\"" "$f" | grep -q "the floating-point floor is reached"'
check 'floor: the round-off part is at least half the bar' \
    'awk -v b="$(json "$f" lowest_positive_error_bar)" -v r="$(json "$f" lowest_positive_roundoff)" \
        "BEGIN { exit !(r > 0 && 2 * r >= b) }"'
check 'not the floor when the tolerance is met' '[[ $(json "$s" adapt_floor_reached) == false ]]'

# The threshold loop stops at the same floor, each side at its own (lambda+- of the pencil,
# or a collision onset: its round-off part against its bar); a side stopped there did not
# meet the tolerance, so summary.json gives it no bar, and the last level's bar is in
# adapt.csv (error_bar_plus, column 10).
"$nceig" "$work/adapt.nml" --set analysis%kind=threshold --set material%poisson=0.499999999 \
    --set output%directory="$work/tfloor" >"$work/stdout" 2>"$work/err"; rc=$?
f=$work/tfloor/summary.json
check 'threshold floor: exit 8, one stderr line naming both sides, the set written' \
    '[[ $rc -eq 8 && $(wc -l <"$work/err") -eq 1 &&
    -s "$work/tfloor/adapt.csv" && $(json "$f" adapt_floor_reached) == true ]] &&
    grep -q "lambda+: tolerance 1.00E-05 not met: the floating-point floor is reached" "$work/err" &&
    grep -q "lambda-: tolerance 1.00E-05 not met: the floating-point floor is reached" "$work/err"'
check 'threshold floor: the round-off part is at least half the last level'\''s bar, no bar quoted' \
    'awk -v b="$(tail -n 1 "$work/tfloor/adapt.csv" | cut -d, -f10)" \
        -v r="$(json "$f" lambda_critical_plus_roundoff)" "BEGIN { exit !(r > 0 && 2 * r >= b) }" &&
     [[ $(json "$f" lambda_critical_plus_error_bar) == null ]]'

# No positive mu (lambda = 1, below the threshold 1.94): one level's absence is no answer (a
# coarse mesh can miss a mu a finer one finds; tests/cli/cli_adapt_no_mu.sh), so every cell
# is refined until three levels without a mu, over which the dofs doubled, confirm it, as a
# threshold side's 'none': exit 0, c_n null, said on stdout; the set holds exactly its
# listed files (no picture, no leftover of one).
"$nceig" "$work/adapt.nml" --set analysis%lambda=1 --set output%directory="$work/none" \
    >"$work/stdout" 2>"$work/err"; rc=$?
check 'no positive mu: exit 0, none confirmed over three uniform levels, c_n null' \
    '[[ $rc -eq 0 && ! -s "$work/err" && $(json "$work/none/summary.json" critical_c_n) == null &&
       $(json "$work/none/summary.json" adapt_converged) == true &&
       $(cut -d, -f4 "$work/none/adapt.csv" | tr "\n" " ") == "n_cells 8 16 32 " ]] &&
    grep -q "none, confirmed: no positive mu at h levels 0 to 2 (40 to 144 dofs)" "$work/stdout" &&
    ! grep -q "^warning" "$work/stdout"'
check 'no positive mu: adapt.png not drawn, said why' \
    'grep -q "adapt plot  not drawn: no level has an error estimate" "$work/stdout"'
check 'no positive mu: only the listed files' \
    '[[ $(ls -A "$work/none" | sort | tr "\n" " ") == "adapt.csv eigenvalues.csv mesh.msh mode_001.png mode_001.vtu summary.json " ]]'

# nu = 0 has no continuum c_n: the lowest positive mu grows like 1/h (a grid-scale mode) and
# is gone after a refinement. Its values had bars, none converged: exit 8, said why.
"$nceig" "$work/adapt.nml" --set material%poisson=0 --set analysis%lambda=20 \
    --set output%directory="$work/gone" >"$work/stdout" 2>"$work/err"; rc=$?
check 'mu gone on refinement (nu = 0): exit 8, one stderr line saying no converged value' \
    '[[ $rc -eq 8 && $(wc -l <"$work/err") -eq 1 ]] &&
    grep -q "positive mu of the coarser levels is gone.*no converged value" "$work/err"'
check 'mu gone on refinement: the earlier levels had a mu, the last none' \
    '[[ -n $(sed -n 2p "$work/gone/adapt.csv" | cut -d, -f5) &&
       -z $(tail -1 "$work/gone/adapt.csv" | cut -d, -f5) &&
       $(json "$work/gone/summary.json" adapt_converged) == false ]]'

# A lambda sweep to a tolerance: every row has its estimate within it (or says none), the
# meshes grow or are reused, the same mu as a single adaptive run at one of its lambdas.
cat >"$work/sweep.nml" <<NML
&mesh nx = 2, ny = 2, element = 'p2' /
&analysis kind = 'lambda_sweep', lambda = 5.0 /
&sweep lambdas = 4.0, 5.0, 6.0, 1.0 /
&adapt tolerance = 1e-5 /
&output directory = '$work/sweep', vtk = .false. /
NML
"$nceig" "$work/sweep.nml" >"$work/stdout" 2>"$work/err"; rc=$?
w=$work/sweep/lambda_sweep.csv
check 'sweep: exit 0, nothing on stderr' '[[ $rc -eq 0 && ! -s "$work/err" ]]'
check 'sweep: every row with a mu has its estimate <= 1e-5' \
    'awk -F, "NR > 1 && \$2 != \"\" && !(\$6 != \"\" && \$6 <= 1e-5) { bad = 1 } END { exit bad }" "$w"'
check 'sweep: no positive mu at lambda = 1 (below the threshold), no estimate' \
    '[[ $(sed -n 5p "$w" | cut -d, -f2,6) == "," ]]'
check 'sweep: summary counts the adapted rows and the reused meshes' \
    '[[ $(json "$work/sweep/summary.json" sweep_n_adapted) == 4 && -n $(json "$work/sweep/summary.json" sweep_n_mesh_reused) ]]'
if command -v gnuplot >/dev/null; then
    check 'sweep: lambda_sweep.png (with the bars) drawn and listed' \
        'drawn "$work/sweep" lambda_sweep.png'
fi
# lambda = 5 from the mesh of lambda = 4 against lambda = 5 alone: each within its estimate
# (1e-5), so within 2e-5 of each other plus the ratio's spread: 5e-5 relative
check 'sweep: lambda = 5 agrees with the single adaptive run (5e-5)' \
    'close "$(sed -n 3p "$w" | cut -d, -f2)" "$(json "$work/out/summary.json" lowest_positive_mu)" 5e-5'

# The critical lambdas to a tolerance: both sides' estimates in summary.json and adapt.csv
# within it, on one final mesh whose threshold, read back, is the same number; the mirror
# symmetry of the square gives lambda- = -lambda+ (the meshes are not mirror images: each
# side's own error, 1e-6, bounds the difference with the ratio's spread: 3e-6 relative).
cat >"$work/threshold.nml" <<NML
&mesh nx = 4, ny = 4, element = 'p2' /
&analysis kind = 'threshold', lambda = 5.0 /
&adapt tolerance = 1e-6 /
&output directory = '$work/threshold', vtk = .false. /
NML
"$nceig" "$work/threshold.nml" >"$work/stdout" 2>"$work/err"; rc=$?
s=$work/threshold/summary.json
check 'threshold: exit 0, nothing on stderr' '[[ $rc -eq 0 && ! -s "$work/err" ]]'
check 'threshold: converged, both estimates <= 1e-6' '[[ $(json "$s" adapt_converged) == true ]] &&
    awk -v p="$(json "$s" lambda_critical_plus_error_estimate)" \
        -v m="$(json "$s" lambda_critical_minus_error_estimate)" \
        "BEGIN { exit !(p > 0 && p <= 1e-6 && m > 0 && m <= 1e-6) }"'
check 'threshold: both confirmed' '[[ $(json "$s" lambda_critical_plus_confirmed) == true &&
    $(json "$s" lambda_critical_minus_confirmed) == true ]]'
check 'threshold: lambda- = -lambda+ (3e-6)' \
    'close "$(json "$s" lambda_critical_plus)" "$(awk -v m="$(json "$s" lambda_critical_minus)" "BEGIN { printf \"%.17g\", -m }")" 3e-6'
csv=$work/threshold/adapt.csv
check 'threshold adapt.csv: header' '[[ $(head -n 1 "$csv") == level,n_dofs,n_contact,n_cells,lambda_plus,error_estimate_plus,lambda_minus,error_estimate_minus,time_s,error_bar_plus,error_bar_minus,collision_plus,error_estimate_collision_plus,error_bar_collision_plus,collision_minus,error_estimate_collision_minus,error_bar_collision_minus ]]'
check 'threshold adapt.csv: the last row is the summary'\''s' \
    '[[ $(tail -n 1 "$csv" | cut -d, -f2) == $(json "$s" n_dofs) &&
        $(tail -n 1 "$csv" | cut -d, -f5) == $(json "$s" lambda_critical_plus) ]]'
check 'threshold: stdout gives each estimate' \
    '[[ $(grep -c "relative error estimate .* (p3 enrichment)" "$work/stdout") -eq 2 ]]'
if command -v gnuplot >/dev/null; then
    check 'threshold: adapt.png and mode_001.png drawn and listed' \
        'drawn "$work/threshold" adapt.png && drawn "$work/threshold" mode_001.png'
fi
# Pictures are optional: gnuplot off the PATH leaves a note, exit 0 and the rest of the set.
PATH=/nonexistent "$nceig" "$work/threshold.nml" --set adapt%tolerance=1e-3 \
    --set output%directory="$work/no_gnuplot" >"$work/stdout" 2>"$work/err"; rc=$?
check 'threshold without gnuplot: exit 0, notes for both pictures, no png' \
    '[[ $rc -eq 0 && ! -s "$work/err" && -s "$work/no_gnuplot/adapt.csv" ]] &&
     grep -q "adapt plot  not drawn: gnuplot is not installed" "$work/stdout" &&
     grep -q "mode plot   not drawn: gnuplot is not installed" "$work/stdout" &&
     [[ -z $(ls "$work/no_gnuplot" | grep "png$") ]]'
cp "$work/threshold/mesh.msh" "$work/threshold.msh"
cat >"$work/threshold_back.nml" <<NML
&mesh source = 'gmsh', file = '$work/threshold.msh', dirichlet = 'top',
      neumann = 'left right', contact = 'bottom' /
&analysis kind = 'threshold', lambda = 5.0 /
&output directory = '$work/threshold_back', vtk = .false., plot = .false. /
NML
"$nceig" "$work/threshold_back.nml" >/dev/null 2>"$work/err"; rc=$?
b=$work/threshold_back/summary.json
check 'threshold: mesh.msh reads back to the same lambda+ (1e-12) and estimate (1e-6 of it)' \
    '[[ $rc -eq 0 ]] && close "$(json "$b" lambda_critical_plus)" "$(json "$s" lambda_critical_plus)" 1e-12 &&
    close "$(json "$b" lambda_critical_plus_error_estimate)" "$(json "$s" lambda_critical_plus_error_estimate)" 1e-6'

# Limits reached by the other goals: exit 8 too, the set written. The thresholds stopped
# after one level; the sweep's points stopped after one level each (lambda = 1 has no
# positive mu, and two levels cannot confirm that: all 4 points are counted).
"$nceig" "$work/threshold.nml" --set adapt%max_levels=1 --set output%directory="$work/th_limit" \
    >/dev/null 2>"$work/err"; rc=$?
check 'threshold, max_levels reached: exit 8, one stderr line, the set written' \
    '[[ $rc -eq 8 && $(wc -l <"$work/err") -eq 1 && -s $work/th_limit/summary.json ]] &&
     grep -q "&adapt: lambda+: tolerance 1.00E-06 not met: max_levels = 1 reached" "$work/err" &&
     grep -q "lambda-: tolerance 1.00E-06 not met: max_levels = 1 reached" "$work/err"'
"$nceig" "$work/sweep.nml" --set adapt%max_levels=1 --set adapt%tolerance=1e-9 \
    --set output%directory="$work/sw_limit" >/dev/null 2>"$work/err"; rc=$?
check 'sweep, max_levels reached: exit 8, the points counted, the set written' \
    '[[ $rc -eq 8 && $(wc -l <"$work/err") -eq 1 && $(json "$work/sw_limit/summary.json" sweep_n_not_met) == 4 ]] &&
     grep -q "4 of the sweep.s points did not meet the tolerance" "$work/err"'

# Each side its own target on h levels: the square with its top and left sides clamped
# (P2 from 2 x 2 squares, 2e-2, at most 12 levels; tests/analysis/test_threshold_goal.f90,
# h_sides_are_independent): lambda+ meets 2e-2 and is quoted with its bar, lambda- comes and
# goes with no bar below 0.45: exit 8 for lambda- alone, its bar null, the warning naming it.
cat >"$work/sides.nml" <<NML
&mesh nx = 2, ny = 2, element = 'p2', dirichlet = 'top left', neumann = 'right' /
&analysis kind = 'threshold', lambda = 5.0 /
&sweep lambda_min = -3.0, lambda_max = 3.0, n_lambda = 7 /
&adapt tolerance = 2e-2, max_levels = 12 /
&output directory = '$work/sides', vtk = .false., plot = .false. /
NML
"$nceig" "$work/sides.nml" >"$work/stdout" 2>"$work/err"; rc=$?
s=$work/sides/summary.json
check 'h sides: exit 8, one stderr line naming lambda- as not met first' \
    '[[ $rc -eq 8 && $(wc -l <"$work/err") -eq 1 ]] &&
     grep -q "&adapt: lambda-: tolerance 2.00E-02 not met: max_levels = 12 reached" "$work/err"'
check 'h sides: lambda+ met with its bar, lambda- with none' \
    'awk -v b="$(json "$s" lambda_critical_plus_error_bar)" "BEGIN { exit !(b > 0 && b <= 2e-2) }" &&
     [[ $(json "$s" lambda_critical_minus_error_bar) == null ]] &&
     grep -q "lambda+: tolerance 2.00E-02 met at level" "$work/err"'
check 'h sides: the warning in summary.json names lambda-' \
    'grep -A1 "\"warnings\"" "$s" | grep -q "lambda-: tolerance 2.00E-02 not met"'

# bad NAME WORD... -- SETTINGS: one stderr line with every WORD, exit 2, no output.
bad() {
    local name=$1
    shift
    local words=()
    while [[ $1 != -- ]]; do words+=("$1"); shift; done
    shift
    rm -rf "$work/bad"
    "$nceig" "$work/adapt.nml" --set output%directory="$work/bad" "$@" >/dev/null \
        2>"$work/err"; local rc=$?
    local ok=1
    [[ $rc -eq 2 && $(wc -l <"$work/err") -eq 1 && ! -e "$work/bad" ]] || ok=0
    for word in "${words[@]}"; do grep -q -F -- "$word" "$work/err" || ok=0; done
    check "$name: $(cat "$work/err")" '[[ $ok -eq 1 ]]'
}
bad 'tolerance < 0' '&adapt' 'tolerance' -- --set adapt%tolerance=-1e-3
bad 'tolerance >= 1' '&adapt' 'tolerance' '0 <= tolerance < 1' -- --set adapt%tolerance=1
bad 'theta 0' '&adapt' 'theta' -- --set adapt%theta=0
bad 'max_levels < 0' '&adapt' 'max_levels' -- --set adapt%max_levels=-1
bad 'max_dofs below the start' '&adapt' 'max_dofs = 20' 'free dofs of the starting mesh' \
    -- --set adapt%max_dofs=20
bad 'another analysis' '&adapt' 'tolerance' "kind = 'branch'" 'eigen' 'threshold' \
    'lambda_sweep' -- --set analysis%kind=branch
bad 'quadrilaterals' '&adapt' 'tolerance' "element = 'q2'" -- --set mesh%element=q2
bad 'threshold on quadrilaterals' '&adapt' 'tolerance' "element = 'q1'" -- \
    --set analysis%kind=threshold --set mesh%element=q1
bad 'p4 (no enriched space)' '&adapt' "element = 'p4'" -- --set mesh%element=p4
bad 'estimate off' '&adapt' "estimate = 'off'" -- --set eigen%estimate=off
cli_end
