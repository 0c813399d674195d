#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Every example in input/ runs and still gives the numbers its comments quote. Each input
# file carries lines `! headline: KEY = VALUE` (KEY a key of summary.json); this script runs
# the file in a scratch copy of input/ (meshes are referenced relatively) and compares.
# Tolerances, from what can legitimately differ between two runs:
#   - eigenvalues, thresholds, compliances, delta_max: 1e-10 relative. The runs are
#     deterministic; what may change between machines is the BLAS kernel and so the
#     rounding of the factor of K, which forming the contact blocks of K^-1 amplifies by
#     about cond(K): E = 2 instead of 1 (the same problem up to an exact factor 2, but a
#     factor rounded differently) moves mu by 2.5e-13 on 32 x 32 and 3.4e-12 on 128 x 128
#     (docs/model.md). 1e-10 keeps a margin of 30 over that and is far below any change
#     of model or mesh (1e-4 and more).
#   - integers, booleans and strings: exactly.
#   - branch_delta (solve at a critical point) is never a headline: there the solution is
#     not isolated, so the member reached is chosen by the iteration from its start and by
#     the rounding of every step (it moved in the 7th digit between BLAS kernels and thread
#     counts), not by the equations; only its distance from the branch line is fixed (zero
#     up to round-off, checked below 1e-10 separately).
# Further checks: the single element against its closed form in awk (1e-12: a 2 x 2 problem
# solved by Cholesky and a 1 x 1 eigenvalue, a few eps), ARPACK against the dense solver
# (1e-9: two different algorithms, each converged to round-off), and the scaling of mu with
# E and with the size of the body that docs/model.md states.
# Usage: cli_examples.sh NCEIG SOURCE_DIR
set -u
nceig=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
source_dir=$(cd "$2" && pwd)
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_examples

cp -r "$source_dir/input" "$work/input"
rm -rf "$work/input/output"
cd "$work/input" || exit 1

# run NML: run one example here; output/<stem>/ and <stem>.out, <stem>.err, <stem>.rc
run() {
    local stem=${1%.nml}
    "$nceig" "$1" >"$stem.out" 2>"$stem.err"
    echo $? >"$stem.rc"
}

# tolerance KEY: the relative tolerance for a numeric headline key, or 'exact'
tolerance() {
    case $1 in
        n_* | iterations | slip_sign | sweep_n_*) echo exact ;;
        *) echo 1e-10 ;;
    esac
}

examples=$(ls ./*.nml)
for nml in $examples; do
    nml=${nml#./}
    stem=${nml%.nml}
    run "$nml"
    summary=output/$stem/summary.json
    check "$nml runs (exit 0, nothing on stderr)" \
        '[[ $(cat "$stem.rc") -eq 0 && ! -s "$stem.err" ]]'
    check "$nml writes summary.json" '[[ -s "$summary" ]]'
    check "$nml quotes at least one headline" 'grep -q "^! headline: " "$nml"'
    while read -r key value; do
        got=$(json "$summary" "$key")
        tol=$(tolerance "$key")
        # 'VALUE within TOL': the example's own relative tolerance (an adaptive run's mu
        # is known to its requested accuracy, not to round-off)
        if [[ $value == *' within '* ]]; then
            tol=${value##* within }
            value=${value%% within *}
        fi
        if [[ $tol == exact || ! $value =~ ^[-+0-9.eE]+$ ]]; then
            check "$nml: $key = $value (got $got)" '[[ "$got" == "$value" ]]'
        else
            check "$nml: $key = $value within $tol (got $got)" 'close "$got" "$value" "$tol"'
        fi
    done < <(sed -n 's/^! headline: *\([A-Za-z_0-9]*\) *= *\(.*\)$/\1 \2/p' "$nml")
done

# The single element (docs/model.md): mu = -6 G (L + 2G) / ((L (lambda + 1) + G (lambda + 3)) l)
# and the one threshold lambda- = -(L + 3G) / (L + G), with E, nu, lambda read from the file
# and l = 2 from the mesh.
se=single_element.nml
young=$(sed -n 's/^ *young *= *\([-0-9.eE]*\).*/\1/p' $se)
poisson=$(sed -n 's/^ *poisson *= *\([-0-9.eE]*\).*/\1/p' $se)
lambda=$(sed -n 's/^ *lambda *= *\([-0-9.eE]*\).*/\1/p' $se)
closed_mu=$(awk -v e="$young" -v nu="$poisson" -v lam="$lambda" -v l=2 'BEGIN {
    L = e * nu / ((1 + nu) * (1 - 2 * nu)); G = e / (2 * (1 + nu))
    printf "%.17g", -6 * G * (L + 2 * G) / ((L * (lam + 1) + G * (lam + 3)) * l) }')
closed_threshold=$(awk -v e="$young" -v nu="$poisson" 'BEGIN {
    L = e * nu / ((1 + nu) * (1 - 2 * nu)); G = e / (2 * (1 + nu))
    printf "%.17g", -(L + 3 * G) / (L + G) }')
mu=$(json output/single_element/summary.json lowest_positive_mu)
check "single element: mu = $mu, closed form $closed_mu (1e-12)" 'close "$mu" "$closed_mu" 1e-12'
sed "s/kind = 'eigen'/kind = 'threshold'/" $se >single_element_threshold.nml
run single_element_threshold.nml
summary=output/single_element_threshold/summary.json
check "single element: lambda- = $(json $summary lambda_critical_minus), closed form $closed_threshold (1e-12)" \
    'close "$(json $summary lambda_critical_minus)" "$closed_threshold" 1e-12'
check 'single element: no lambda+ (mu > 0 only for lambda < lambda-)' \
    '[[ $(json $summary lambda_critical_plus) == null ]]'

# ARPACK against the dense solver on the same pencils (p = 65 and p = 33).
sed "s/solver = 'auto'/solver = 'dense'/" eigen_p2.nml >eigen_p2_dense.nml
sed "s/solver = 'dense'/solver = 'arpack'/" eigen_p1_left.nml >eigen_p1_left_arpack.nml
run eigen_p2_dense.nml
run eigen_p1_left_arpack.nml
for pair in eigen_p2:eigen_p2_dense eigen_p1_left_arpack:eigen_p1_left; do
    a=output/${pair%%:*}/summary.json b=output/${pair##*:}/summary.json
    check "arpack and dense agree to 1e-9: ${pair/:/ and }" \
        '[[ $(json $a solver) == arpack && $(json $b solver) == dense ]] &&
         close "$(json $a lowest_positive_mu)" "$(json $b lowest_positive_mu)" 1e-9'
done

# Scaling (docs/model.md): mu ~ E and mu ~ 1/size; lambda is dimensionless, so the
# thresholds do not move. Powers of two scale K and the boundary mass exactly.
mu_ref=$(json output/square/summary.json lowest_positive_mu)
sed 's/young = 1.0/young = 2.0/' square.nml >square_e2.nml
sed 's/width = 1.0, height = 1.0/width = 2.0, height = 2.0/' square.nml >square_size2.nml
run square_e2.nml
run square_size2.nml
check "E = 2 doubles mu ($mu_ref -> $(json output/square_e2/summary.json lowest_positive_mu))" \
    'close "$(json output/square_e2/summary.json lowest_positive_mu)" "$(awk -v m=$mu_ref "BEGIN { printf \"%.17g\", 2 * m }")" 1e-10'
check "a 2 x larger square halves mu ($mu_ref -> $(json output/square_size2/summary.json lowest_positive_mu))" \
    'close "$(json output/square_size2/summary.json lowest_positive_mu)" "$(awk -v m=$mu_ref "BEGIN { printf \"%.17g\", m / 2 }")" 1e-10'
sed '/^&mesh/a\    width = 2.0, height = 2.0' threshold.nml | sed '/^&analysis/i\&material young = 2.0 /' >threshold_scaled.nml
run threshold_scaled.nml
check 'E = 2 and a 2 x larger square leave lambda+ and lambda- unchanged' \
    'close "$(json output/threshold_scaled/summary.json lambda_critical_plus)" "$(json output/threshold/summary.json lambda_critical_plus)" 1e-10 &&
     close "$(json output/threshold_scaled/summary.json lambda_critical_minus)" "$(json output/threshold/summary.json lambda_critical_minus)" 1e-10'

# Numbers quoted in comments that are not summary keys.
check 'lambda_sweep_fine: c_n(-5) = 0.7537534622070868 (lambda_sweep.csv)' \
    'close "$(awk -F, "\$1 == \"-5.0\" { print \$2 }" output/lambda_sweep_fine/lambda_sweep.csv)" 0.7537534622070868 1e-10'
check 'solve: u_n = 0.03444625495361595 at x = 0.5 (contact_states.csv)' \
    'close "$(awk -F, "\$2 == \"0.5\" { print \$4 }" output/solve/contact_states.csv)" 0.03444625495361595 1e-10'
check 'solve_branch: the solution lies on the branch line (distance below 1e-10)' \
    'awk -v d="$(json output/solve_branch/summary.json branch_distance)" "BEGIN { exit !(d < 1e-10) }"'
# Round-off on U + delta phi: a few hundred eps relative to the load.
check 'branch: every member solves the problem to round-off (below 1e-12)' \
    'awk -v r="$(json output/branch/summary.json branch_max_residual)" "BEGIN { exit !(r < 1e-12) }"'
check 'eigen_q1 writes K.mtx and B.mtx in Matrix Market format' \
    'for m in K B; do head -1 output/eigen_q1/$m.mtx | grep -q "^%%MatrixMarket matrix coordinate real general" || exit 1; done'
check 'eigen_q2 writes its mode as text' 'grep -q "format=\"ascii\"" output/eigen_q2/mode_001.vtu'

cli_end
