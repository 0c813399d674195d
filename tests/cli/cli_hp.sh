#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# &adapt strategy = 'hp' end to end: on the reference scene the loop meets 1e-10 and its
# value is within its bar of the independent truth (tests/data/truths.csv); the files
# (adapt.csv per level, mode_001.vtu with the degree field, mesh.msh and degrees.csv, and
# with gnuplot mode_001.png and adapt.png; without it notes and exit 0);
# the dense solver's whole spectrum;
# the same from a Gmsh mesh of the trapezoid scene; hp within the h loop's bar on a
# second scene; the floating-point floor and a level limit end in exit 8 with a warning;
# bad input is one stderr line naming &adapt and the variable, exit 2. kind = 'threshold':
# both critical lambdas of the reference scene and the collision onsets of the trapezoid and
# half-contact scenes within their bars of the truths, the floor; kind = 'lambda_sweep': every
# point within its bar of the truth (mirror symmetry gives the truths at -lambda); hp refused
# for the others.
# Usage: cli_hp.sh NCEIG SOURCE_DIR
set -u
nceig=$1
root=$2
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_hp
truth() { awk -F, -v s="$1" '$1 == s && $2 == "lowest_positive_mu" { print $3 }' \
    "$root/tests/data/truths.csv"; }
# within MU BAR TRUTH: |MU - TRUTH| <= BAR |MU| (the bar is relative)
within() { awk -v m="$1" -v b="$2" -v t="$3" 'BEGIN { d = m - t; if (d < 0) d = -d
    exit !(b > 0 && d <= b * m) }'; }

# The reference scene (the rectangle's defaults) from 2 x 2 squares.
cat >"$work/hp.nml" <<NML
&mesh nx = 2, ny = 2, element = 'p1' /
&analysis kind = 'eigen', lambda = 5.0 /
&adapt tolerance = 1e-10, strategy = 'hp' /
&output directory = '$work/out' /
NML
"$nceig" "$work/hp.nml" >"$work/stdout" 2>"$work/err"; rc=$?
s=$work/out/summary.json
check 'runs: exit 0, nothing on stderr' '[[ $rc -eq 0 && ! -s "$work/err" ]]'
check 'summary: converged, strategy hp' \
    '[[ $(json "$s" adapt_converged) == true && $(json "$s" adapt_strategy) == hp ]]'
check 'summary: the bar meets the tolerance' \
    'awk -v e="$(json "$s" lowest_positive_error_bar)" "BEGIN { exit !(e > 0 && e <= 1e-10) }"'
check 'the value is within its bar of the truth' \
    'within "$(json "$s" lowest_positive_mu)" "$(json "$s" lowest_positive_error_bar)" "$(truth ref)"'
check 'stdout: the headline with its bar, the tolerance met' \
    'grep -q "critical c_n = 0.75284361.* +- " "$work/stdout" &&
     grep -q "tolerance 1.00E-10 met at level" "$work/stdout"'
csv=$work/out/adapt.csv
check 'adapt.csv: header' \
    '[[ $(head -n 1 "$csv") == level,layers,p_min,p_max,n_dofs,n_contact,n_cells,mu,error_bar,roundoff,time_s ]]'
check 'adapt.csv: one row per level, the last the summary'\''s' \
    '[[ $(($(wc -l <"$csv") - 1)) -eq $(json "$s" adapt_levels) &&
        $(tail -n 1 "$csv" | cut -d, -f5) == $(json "$s" n_dofs) ]]'
check 'adapt.csv: level k has k layers, degrees 1 to k + 1, growing dofs' \
    'awk -F, "NR > 1 && (\$2 != NR - 1 || \$3 != 1 || \$4 != NR || \$5 <= d) { bad = 1 }
              NR > 1 { d = \$5 } END { exit bad }" "$csv"'
check 'adapt.csv: no bar at the first level, one at every other' \
    'awk -F, "NR == 2 && \$9 != \"\" { bad = 1 } NR > 2 && \$9 == \"\" { bad = 1 } END { exit bad }" "$csv"'
check 'mode_001.vtu carries the degree field' \
    'grep -q "Name=\"degree\"" "$work/out/mode_001.vtu"'
check 'degrees.csv: one row per cell of mesh.msh' \
    '[[ $(($(wc -l <"$work/out/degrees.csv") - 1)) -eq $(json "$s" n_cells) ]]'
check 'summary lists mesh.msh, degrees.csv and adapt.csv' \
    'grep -q "\"mesh.msh\"" "$s" && grep -q "\"degrees.csv\"" "$s" && grep -q "\"adapt.csv\"" "$s"'
if command -v gnuplot >/dev/null 2>&1; then
    check 'mode_001.png and adapt.png drawn and listed, stdout names them' \
        'drawn "$work/out" mode_001.png && drawn "$work/out" adapt.png &&
         grep -q "mode plot   $work/out/mode_001.png" "$work/stdout" &&
         grep -q "adapt plot  $work/out/adapt.png" "$work/stdout"'
fi
PATH=/nonexistent "$nceig" "$work/hp.nml" --set adapt%tolerance=1e-4 \
    --set "output%directory='$work/no_gnuplot'" >"$work/stdout" 2>"$work/err"; rc=$?
check 'no gnuplot: exit 0, a note for each picture, no png' \
    '[[ $rc -eq 0 && ! -s "$work/err" && -s "$work/no_gnuplot/adapt.csv" ]] &&
     grep -q "mode plot   not drawn: gnuplot is not installed" "$work/stdout" &&
     grep -q "adapt plot  not drawn: gnuplot is not installed" "$work/stdout" &&
     [[ -z $(ls "$work/no_gnuplot" | grep "png$") ]]'

# The dense solver on every level: the whole spectrum of the last one (one eigenvalue per
# contact function), its lowest positive mu the same within the round-off bound.
"$nceig" "$work/hp.nml" --set "eigen%solver='dense'" --set "output%directory='$work/dense'" \
    >/dev/null 2>"$work/err"; rc=$?
d=$work/dense/summary.json
check 'dense: every eigenvalue of the last level' '[[ $rc -eq 0 && ! -s "$work/err" &&
    $(json "$d" n_eigenvalues) -eq $(json "$d" n_contact) &&
    $(($(wc -l <"$work/dense/eigenvalues.csv") - 1)) -eq $(json "$d" n_contact) ]]'
check 'dense: the same mu within the round-off bound' \
    'within "$(json "$d" lowest_positive_mu)" "$(json "$s" lowest_positive_roundoff)" "$(json "$s" lowest_positive_mu)"'

# A Gmsh mesh: the trapezoid scene (its slanted side adds corners of other angles).
if command -v gmsh >/dev/null 2>&1; then
    source "$root/scripts/lib/truth_scenes.sh"
    scene_info trapezoid
    scene_gmsh "$work/trapezoid.msh" 1 -setnumber graded 0 -clmax 0.3
    { scene_mesh_nml "$work/trapezoid.msh"; scene_physics_nml
      echo "&adapt tolerance = 1e-8, strategy = 'hp' /"
      echo "&output directory = '$work/gmsh', vtk = .false. /"; } >"$work/gmsh.nml"
    "$nceig" "$work/gmsh.nml" >/dev/null 2>"$work/err"; rc=$?
    g=$work/gmsh/summary.json
    check 'Gmsh mesh: meets 1e-8' '[[ $rc -eq 0 && ! -s "$work/err" &&
        $(json "$g" adapt_converged) == true ]]'
    check 'Gmsh mesh: within its bar of the truth' \
        'within "$(json "$g" lowest_positive_mu)" "$(json "$g" lowest_positive_error_bar)" "$(truth trapezoid)"'
else
    echo 'SKIP: gmsh is not installed: the Gmsh mesh checks did not run'
fi

# hp against the h loop (P3) on the 2 x 1 rectangle, nu = 0.25, lambda = -4.
cat >"$work/rect.nml" <<NML
&mesh width = 2.0, nx = 4, ny = 2, element = 'p3' /
&material poisson = 0.25 /
&analysis kind = 'eigen', lambda = -4.0 /
&adapt tolerance = 1e-7 /
&output directory = '$work/h', vtk = .false., plot = .false. /
NML
"$nceig" "$work/rect.nml" >/dev/null 2>"$work/err"; rc_h=$?
"$nceig" "$work/rect.nml" --set "adapt%strategy='hp'" --set "mesh%element='p1'" \
    --set "output%directory='$work/hp_rect'" >/dev/null 2>>"$work/err"; rc_hp=$?
h=$work/h/summary.json
p=$work/hp_rect/summary.json
check '2 x 1: both loops meet 1e-7' '[[ $rc_h -eq 0 && $rc_hp -eq 0 && ! -s "$work/err" &&
    $(json "$h" adapt_converged) == true && $(json "$p" adapt_converged) == true ]]'
check '2 x 1: hp within the h loop'\''s bar' \
    'within "$(json "$p" lowest_positive_mu)" "$(json "$h" lowest_positive_error_bar)" "$(json "$h" lowest_positive_mu)"'
check '2 x 1: hp within its own bar of the truth' \
    'within "$(json "$p" lowest_positive_mu)" "$(json "$p" lowest_positive_error_bar)" "$(truth rect2x1-nu0.25-lambda-4)"'

# Below the round-off bound: the loop stops at the floor instead of refining in vain.
"$nceig" "$work/hp.nml" --set adapt%tolerance=1e-14 --set "output%directory='$work/floor'" \
    >"$work/stdout" 2>"$work/err"; rc=$?
f=$work/floor/summary.json
check 'floor: exit 8, one stderr line, the set written' '[[ $rc -eq 8 && $(wc -l <"$work/err") -eq 1 &&
    $(json "$f" adapt_converged) == false && $(json "$f" adapt_floor_reached) == true ]]'
check 'floor: said on stdout and in the warnings' \
    'grep -q "the floating-point floor is reached" "$work/stdout" &&
     grep "\"warnings\"" "$f" | grep -q "the floating-point floor is reached"'
# The floor's bar is the check's (one degree higher), whose round-off part is mu's bound plus
# the check's own (6.1e-14 each here: Rayleigh quotients of similar systems); summary.json
# has mu's, so the round-off part at least half the bar makes mu's at least a quarter.
check 'floor: the round-off part is at least half the bar' \
    'awk -v b="$(json "$f" lowest_positive_error_bar)" -v r="$(json "$f" lowest_positive_roundoff)" \
        "BEGIN { exit !(r > 0 && 4 * r >= b) }"'

# A level limit: exit 8 with the limit named.
"$nceig" "$work/hp.nml" --set adapt%max_levels=3 --set "output%directory='$work/limit'" \
    >"$work/stdout" 2>"$work/err"; rc=$?
check 'max_levels: exit 8, three levels, the limit named' '[[ $rc -eq 8 &&
    $(json "$work/limit/summary.json" adapt_levels) -eq 3 ]] && grep -q "max_levels = 3" "$work/err"'

# Bad input: one line on stderr naming &adapt and the variable, exit 2, no output.
bad() {
    local name=$1 pattern=$2
    shift 2
    "$nceig" "$work/hp.nml" --set "output%directory='$work/bad_$name'" "$@" \
        >/dev/null 2>"$work/bad.err"; rc=$?
    check "bad input ($name): exit 2, one line naming it, no output" \
        '[[ $rc -eq 2 && $(wc -l <"$work/bad.err") -eq 1 && ! -e "$work/bad_$name" ]] &&
         grep -q -- "$pattern" "$work/bad.err"'
}
bad strategy "&adapt: strategy = 'p': expected one of 'h', 'hp'" --set "adapt%strategy='p'"
bad quads "&adapt: strategy = 'hp': expected 'h' for &mesh element = 'q1'" --set "mesh%element='q1'"
bad degree "&adapt: p_max = 21: expected a degree from 1 to 20" --set adapt%p_max=21
bad sigma "&adapt: sigma = 1.0: expected a grading factor" --set adapt%sigma=1.0
bad max_dofs "&adapt: max_dofs = 100: expected at least the 220 free dofs of the first hp level" \
    --set adapt%max_dofs=100
bad branch "&adapt: strategy = 'hp': expected 'h' for &analysis kind = 'branch'" \
    --set "analysis%kind='branch'"
bad solve "&adapt: strategy = 'hp': expected 'h' for &analysis kind = 'solve'" \
    --set "analysis%kind='solve'"

# kind = 'lambda_sweep': every point climbs the hp levels to 1e-9. The square is its own
# mirror image (x -> 1 - x turns t into -t and lambda into -lambda), so c_n at -5 and +5
# are the truth of lambda = 5, at -3 and +3 that of lambda = -3: each within its bar.
cat >"$work/sweep.nml" <<NML
&mesh nx = 2, ny = 2, element = 'p1' /
&analysis kind = 'lambda_sweep', lambda = 5.0 /
&sweep lambdas = -5.0, -3.0, 3.0, 5.0 /
&adapt tolerance = 1e-9, strategy = 'hp' /
&output directory = '$work/sweep', vtk = .false. /
NML
"$nceig" "$work/sweep.nml" >"$work/stdout" 2>"$work/err"; rc=$?
s=$work/sweep/summary.json
csv=$work/sweep/lambda_sweep.csv
check 'sweep: exit 0, nothing on stderr, every point met 1e-9' '[[ $rc -eq 0 && ! -s "$work/err" &&
    $(json "$s" sweep_n_not_met) -eq 0 ]] &&
    awk -v e="$(json "$s" sweep_max_error_bar)" "BEGIN { exit !(e > 0 && e <= 1e-9) }"'
sweep_point() { awk -F, -v l="$1" 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    $1 + 0 == l { print $c["critical_c_n"], $c["error_bar"] }' "$csv"; }
for pair in "-5 ref" "5 ref" "-3 lambda-3" "3 lambda-3"; do
    read -r lam scene <<<"$pair"
    check "sweep: c_n at lambda = $lam within its bar of the truth" \
        'within $(sweep_point $lam) "$(truth $scene)"'
done

# kind = 'threshold': both critical lambdas of the reference scene to 1e-10, each within its
# bar (relative) plus the truth's own uncertainty of the truth.
tvalue() { awk -F, -v s="$1" -v q="$2" '$1 == s && $2 == q { print $3 }' "$root/tests/data/truths.csv"; }
tuncertainty() { awk -F, -v s="$1" -v q="$2" '$1 == s && $2 == q { print $4 }' "$root/tests/data/truths.csv"; }
# near VALUE BAR TRUTH UNCERTAINTY: |VALUE - TRUTH| <= BAR |VALUE| + UNCERTAINTY, BAR > 0
near() { awk -v v="$1" -v b="$2" -v t="$3" -v u="$4" 'BEGIN { d = v - t; if (d < 0) d = -d
    m = v < 0 ? -v : v; exit !(b > 0 && d <= b * m + u) }'; }
# onset_bar SUMMARY KEY: the boundary_error_bar of the boundary point at the onset KEY
onset_bar() { awk -v want="$(json "$1" "$2")" '
    /"boundary_lambda":/ { gsub(/.*\[|\].*/, ""); n = split($0, l, ", ") }
    /"boundary_error_bar":/ { gsub(/.*\[|\].*/, ""); split($0, b, ", ") }
    END { for (i = 1; i <= n; i++) if (l[i] == want) print b[i] }' "$1"; }
cat >"$work/thr.nml" <<NML
&mesh nx = 2, ny = 2, element = 'p1' /
&analysis kind = 'threshold', lambda = 5.0 /
&adapt tolerance = 1e-10, strategy = 'hp' /
&output directory = '$work/thr', vtk = .false. /
NML
"$nceig" "$work/thr.nml" >"$work/stdout" 2>"$work/err"; rc=$?
s=$work/thr/summary.json
check 'threshold: exit 0, nothing on stderr, converged by hp' '[[ $rc -eq 0 && ! -s "$work/err" &&
    $(json "$s" adapt_converged) == true && $(json "$s" adapt_strategy) == hp &&
    $(json "$s" adapt_floor_reached) == false ]]'
for side in plus minus; do
    check "threshold: lambda_$side's bar meets 1e-10" \
        'awk -v e="$(json "$s" lambda_critical_${side}_error_bar)" "BEGIN { exit !(e > 0 && e <= 1e-10) }"'
    check "threshold: lambda_$side within its bar of the truth" \
        'near "$(json "$s" lambda_critical_$side)" "$(json "$s" lambda_critical_${side}_error_bar)" \
            "$(tvalue ref-threshold lambda_critical_$side)" "$(tuncertainty ref-threshold lambda_critical_$side)"'
done
check 'threshold: the headline lambda+ X +- B, the tolerance met' \
    'grep -q "lambda+     1.94471144.* +- " "$work/stdout" &&
     grep -q "tolerance 1.00E-10 met at level" "$work/stdout"'
csv=$work/thr/adapt.csv
check 'threshold: adapt.csv has the h loop'\''s columns, then layers, p_min, p_max' \
    '[[ $(head -n 1 "$csv") == level,n_dofs,n_contact,n_cells,lambda_plus,*,error_bar_collision_minus,layers,p_min,p_max &&
        $(($(wc -l <"$csv") - 1)) -eq $(json "$s" adapt_levels) ]]'
check 'threshold: degrees.csv and mesh.msh of the last level' \
    '[[ $(($(wc -l <"$work/thr/degrees.csv") - 1)) -eq $(json "$s" n_cells) && -s "$work/thr/mesh.msh" ]]'

# Below the round-off bound of the thresholds: the floor, exit 8.
"$nceig" "$work/thr.nml" --set adapt%tolerance=1e-13 --set "output%directory='$work/thr_floor'" \
    >"$work/stdout" 2>"$work/err"; rc=$?
check 'threshold floor: exit 8, one stderr line, the floor named' '[[ $rc -eq 8 && $(wc -l <"$work/err") -eq 1 &&
    $(json "$work/thr_floor/summary.json" adapt_floor_reached) == true ]] &&
    grep -q "the floating-point floor is reached" "$work/err"'

# Collision onsets (complex_pair) as the goals: the trapezoid's (both sides, to 1e-8) and
# the half-contact scene's (minus), each within its bar of the truth; the boundary search
# over [-3, 3] only (the onsets are inside). The half-contact scene's lambda+ (a pencil
# eigenvalue at the free end of the contact part) converges slowly: its run stops at
# max_levels = 5 (exit 8), which leaves the onset's bar to check.
if command -v gmsh >/dev/null 2>&1; then
    for scene in trapezoid-threshold half-contact-threshold; do
        scene_info $scene
        levels=0 want=0
        [[ $scene == half-contact-threshold ]] && levels=5 want=8
        scene_gmsh "$work/$scene.msh" 1 -setnumber graded 0 -clmax 0.3
        { scene_mesh_nml "$work/$scene.msh"; scene_physics_nml
          echo "&adapt tolerance = 1e-8, strategy = 'hp', max_levels = $levels /"
          echo "&sweep lambda_min = -3.0, lambda_max = 3.0 /"
          echo "&output directory = '$work/$scene', vtk = .false. /"; } >"$work/$scene.nml"
        "$nceig" "$work/$scene.nml" >/dev/null 2>"$work/err"; rc=$?
        g=$work/$scene/summary.json
        check "$scene: exit $want" '[[ $rc -eq $want && -s "$g" ]]'
        for key in $onsets; do
            check "$scene: $key a collision within its bar of the truth" \
                '[[ $(json "$g" ${key}_mechanism) == complex_pair ]] &&
                 near "$(json "$g" $key)" "$(onset_bar "$g" $key)" "$(tvalue $scene $key)" "$(tuncertainty $scene $key)"'
        done
    done
else
    echo 'SKIP: gmsh is not installed: the collision onset checks did not run'
fi

# A side settled to round-off stops refining (error_bar: settled_floor): the slanted body
# (nu = 0.1) at 1e-8, whose thresholds sit at corners where the round-off bound passes the
# tolerance while the values still change by less than it. The loop must end at the first
# level where every side has been met, is at the floor or has its last two changes (relative,
# from the progress lines' 12 digits) within those levels' round-off bounds, at least 1e-8
# (11: lambda- met at level 7, lambda+ settled at 11); before the rule the check one degree
# higher reopened lambda- and the loop went on to level 14, each value further off.
if command -v gmsh >/dev/null 2>&1; then
    gmsh "$root/tests/data/bodies/slanted.geo" -2 -order 1 -clmax 0.125 -format msh41 \
        -o "$work/slanted.msh" >/dev/null
    cat >"$work/slanted.nml" <<NML
&mesh source = 'gmsh', file = '$work/slanted.msh', dirichlet = 'top', neumann = 'left right',
      contact = 'contact' /
&material poisson = 0.1 /
&analysis kind = 'threshold', lambda = 5.0 /
&sweep lambda_min = -20.0, lambda_max = 20.0, n_lambda = 401 /
&adapt strategy = 'hp', tolerance = 1e-8 /
&eigen estimate = 'off' /
&output directory = '$work/slanted', vtk = .false., plot = .false., progress = .true. /
NML
    "$nceig" "$work/slanted.nml" >"$work/stdout" 2>&1; rc=$?
    # the first level at which each side has been met (bar <= 1e-8), is at the floor (its
    # round-off at least half its bar) or has settled (0: never)
    settled=$(grep -E '^  \.\. hp level [0-9]+: [0-9]+ dofs' "$work/stdout" | awk '
        function side_value(s, re,    t) {
            if (!match(s, re)) return ""
            t = substr(s, RSTART, RLENGTH); sub(/.*= /, "", t)
            rest = substr(s, RSTART + RLENGTH)
            return t
        }
        { sub(/^  \.\. hp level /, ""); level = $1 + 0; done = 1
          for (side = 1; side <= 2; side++) {
              v = side_value($0, side == 1 ? "lambda[+] = [-0-9.E+]+" : "lambda- = [-0-9.E+]+")
              if (v == "") { done = 0; n[side] = 0; continue }
              r = -1
              if (index(rest, ", lambda")) rest = substr(rest, 1, index(rest, ", lambda"))
              if (match(rest, /\[roundoff [0-9.E+-]+\]/)) {
                  t = substr(rest, RSTART, RLENGTH); sub(/.*\[roundoff /, "", t); r = t + 0 }
              b = 1
              if (match(rest, /bar [0-9.E+-]+\)/)) {
                  t = substr(rest, RSTART + 4, RLENGTH - 5); b = t + 0 }
              c = (n[side] > 0) ? (v - last[side]) / v : 1; if (c < 0) c = -c
              within[side] = (c <= r) ? within[side] + 1 : 0
              last[side] = v + 0; n[side]++
              if (b <= 1e-8) met[side] = 1
              if (!(met[side] || 2 * r >= b || (within[side] >= 2 && r >= 1e-8))) done = 0
          }
          if (done && !first) first = level }
        END { print first + 0 }')
    # At that level the check one degree higher may still reopen a side met earlier whose
    # round-off bound is just below the tolerance (lambda- here: 8.2e-9 with the Prescott
    # kernels, which moved it above 1e-8): one level more, then both are at the floor. Which
    # of the two happens turns on digits at the round-off level, so either is right.
    levels=$(json "$work/slanted/summary.json" adapt_levels)
    check 'settled: the floor, exit 8, at the first level where both sides settled (or one more)' \
        '[[ $rc -eq 8 && $(json "$work/slanted/summary.json" adapt_floor_reached) == true &&
            $settled -gt 0 && $levels -ge $settled && $levels -le $((settled + 1)) ]]'
else
    echo 'SKIP: gmsh is not installed: the settled-side check did not run'
fi
cli_end
