#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# nceig-study on the local engine (GNU parallel), end to end, on a 2 x 2 study of the
# reference scene's rectangle (widths 1 and 2, nu = 0.25 and 0.3, three lambdas, hp to 1e-6):
# the table and its values against the mathematics (the mirror symmetry lambda -> -lambda of
# the rectangle, a direct nceig run of one point, a Gmsh geometry of the same square), the
# pictures and the ParaView collection; a second call redoes nothing; a study killed while
# it runs, called again, gives the same table and redoes only the killed tasks; a changed
# point is redone and only it; a task that fails or misses its tolerance is a row with its
# exit status and reason, the study goes on and exits 8, --retry-failed runs it again; bad
# input: one stderr line, exit 2, the previous study untouched.
# Usage: cli_study.sh NCEIG SOURCE_DIR
set -u
nceig=$(realpath "$1")
source_dir=$(realpath "$2")
source "$(dirname "$0")/lib/cli_common.sh"
source "$(dirname "$0")/lib/study_common.sh"
cli_begin cli_study
export NCEIG=$nceig
study=("$source_dir/scripts/nceig-study")
for tool in parallel jq gnuplot gmsh; do
    command -v "$tool" >/dev/null || cli_skip cli_study "$tool not installed (scripts/dev/install_deps.sh)"
done
[[ -x $(dirname "$nceig")/nceig-study-plan ]] || { echo "FAIL  nceig-study-plan not built"; exit 1; }
cd "$work" || exit 1

# row JSON QUANTITY GEOMETRY NU [LAMBDA]: "value error_bar" of one row of study.json
row() {
    jq -r --arg q "$2" --arg g "$3" --argjson nu "$4" --argjson l "${5:-null}" \
        '.rows[] | select(.quantity == $q and .geometry == $g and .poisson == $nu
                          and .lambda == $l) | "\(.value) \(.error_bar)"' "$1"
}
# within A BAR_A B BAR_B: |A - B| <= BAR_A |A| + BAR_B |B| (each value within its relative
# bar of the same true value; the bars are meant to bound the true error)
within() {
    awk -v a="$1" -v ra="$2" -v b="$3" -v rb="$4" 'BEGIN {
        d = a - b; if (d < 0) d = -d; if (a < 0) a = -a; if (b < 0) b = -b
        exit !(ra != "" && rb != "" && d <= ra * a + rb * b) }'
}
# stamps DIR: the modification times of the task results
stamps() { stat -c '%n %y' "$1"/tasks/*/result 2>/dev/null | sort; }
# redone BEFORE AFTER: the tasks whose result changed between two stamps lists, sorted
redone() {
    comm -13 <(echo "$1") <(echo "$2") | cut -d' ' -f1 | xargs -r -n1 dirname |
        xargs -r -n1 basename | sort | paste -sd' '
}

study_input s.nml 1e-6
"${study[@]}" -j 2 -o out s.nml >run1.out 2>run1.err
rc=$?
check 'a 2 x 2 study runs: exit 0' '[[ $rc -eq 0 ]]'
check 'the task list names four tasks' '[[ $(grep -c "^g0[12]_nu0[12] " run1.out) -eq 4 ]]'
check 'study.csv: a header and 4 x (3 c_n + 4 threshold) rows' \
    '[[ $(head -n 1 out/study.csv) == "\"geometry\",\"poisson\",\"lambda\",\"quantity\",\"value\",\"error_bar\",\"converged\",\"exit_status\",\"reason\",\"dofs\",\"seconds\",\"input_hash\",\"nceig_version\",\"source_commit\",\"blas\",\"task\"" && $(wc -l <out/study.csv) -eq 29 ]]'
check 'study.json has the same 28 rows, every one converged with exit status 0' \
    '[[ $(jq "[.rows[] | select(.converged and .exit_status == 0)] | length" out/study.json) -eq 28 ]]'
check 'one nceig run per task: c_n and thresholds adapted in one hp climb' \
    '[[ $(ls out/tasks/*/cn.nml | wc -l) -eq 4 && -z $(ls out/tasks/*/thr.nml 2>/dev/null) ]] &&
     [[ $(grep -li "^ *adapt_thresholds *= *t" out/tasks/*/cn.nml | wc -l) -eq 4 ]] &&
     [[ $(jq "[.rows[] | select(.quantity == \"lambda_plus\" and .error_bar != null)] | length" out/study.json) -eq 4 ]]'
check 'each row carries its input hash, the nceig version and one BLAS thread' \
    '[[ $(jq -r "[.rows[] | select((.input_hash | length) == 64 and .nceig_version != null
          and (.blas | test(\"[(]1 thread[)]\")))] | length" out/study.json) -eq 28 ]]'
check 'one progress line per task on stderr, each with an ETA, the last one all done' \
    '[[ $(grep -c "tasks done" run1.err) -ge 4 && $(grep -c "tasks done, 0 failed or missed the tolerance, ETA [0-9]* s$" run1.err) -eq 3 ]] &&
     grep -q "4/4 tasks done, 0 failed.*all done" run1.err && [[ -z $(grep -v "^nceig-study: " run1.err) ]]'
# The rectangle is its own mirror image under x -> -x, which maps lambda to -lambda: c_n(5)
# and c_n(-5) are one continuum value (the hp meshes are not mirror images: each is within
# its bar of it), and lambda- = -lambda+.
# mirrored QA LA QB LB: for every geometry and nu, row (QA, LA) and row (QB, LB) of the first
# study have one absolute value within their two bars
mirrored() {
    local g nu a ra b rb
    for g in rectangle_w1 rectangle_w2; do for nu in 0.25 0.3; do
        read -r a ra <<<"$(row out/study.json "$1" $g $nu "$2")"
        read -r b rb <<<"$(row out/study.json "$3" $g $nu "$4")"
        within "${a#-}" "$ra" "${b#-}" "$rb" || return 1
    done; done
}
check 'c_n(-5) = c_n(5) within their bars, for every geometry and nu' 'mirrored c_n -5 c_n 5'
check 'lambda- = -lambda+ within their bars, for every geometry and nu' \
    'mirrored lambda_plus null lambda_minus null && [[ $(row out/study.json lambda_minus rectangle_w1 0.3) == -* ]]'
# An independent path to one point: kind 'eigen' at lambda = 2.5 on the same template.
printf '&mesh nx = 2, ny = 2, element = "p1" /\n&material poisson = 0.3 /\n&analysis lambda = 2.5 /\n&adapt tolerance = 1e-6, strategy = "hp" /\n&output vtk = .false., plot = .false., progress = .false. /\n' >direct.nml
"$nceig" direct.nml >direct.out 2>&1
check 'c_n(2.5) at nu = 0.3 equals a direct eigen run within their bars' '
    read -r a ra <<<"$(row out/study.json c_n rectangle_w1 0.3 2.5)"
    within "$a" "$ra" "$(json output/direct/summary.json critical_c_n)" \
        "$(json output/direct/summary.json lowest_positive_error_bar)"'
check 'the pictures: study_cn.png and study_thresholds.png' \
    '[[ $(head -c 4 out/study_cn.png | tail -c 3) == PNG && $(head -c 4 out/study_thresholds.png | tail -c 3) == PNG ]]'
check 'study.pvd lists the four lowest modes, each with lambda, nu and mu as field data' '
    [[ $(grep -c "<DataSet " out/study.pvd) -eq 4 ]] || exit 1
    for f in $(sed -n "s/.*file=\"\([^\"]*\)\".*/\1/p" out/study.pvd); do
        for name in lambda nu mu; do grep -q "Name=\"$name\"" "out/$f" || exit 1; done
    done'

# A second call: every task reused, the same table.
cp out/study.csv first.csv
before=$(stamps out)
"${study[@]}" -j 2 -o out s.nml >run2.out 2>run2.err
rc=$?
check 'a second call exits 0 and redoes no task' '[[ $rc -eq 0 && $(stamps out) == "$before" ]]'
check '... and writes the same table' 'same_study first.csv out/study.csv'

# Killed while it runs, then called again: the same table; the tasks that had ended are kept.
setsid "${study[@]}" -j 1 -o killed s.nml >kill.out 2>kill.err &
pid=$!
for _ in $(seq 600); do
    [[ $(ls killed/tasks/*/result 2>/dev/null | wc -l) -ge 1 ]] && break
    sleep 0.1
done
kill -TERM -- -"$pid" 2>/dev/null
wait "$pid"
kill_status=$?
# every process of the killed study gone (nceig ends on SIGTERM within a moment)
for _ in $(seq 100); do kill -0 -- -"$pid" 2>/dev/null || break; sleep 0.1; done
n_ended=$(ls killed/tasks/*/result 2>/dev/null | wc -l)
kept=$(stamps killed)
check 'the killed study exits 143 (SIGTERM), having ended 1 to 3 of its 4 tasks' \
    '[[ $kill_status -eq 143 ]] && ((n_ended >= 1 && n_ended <= 3))'
"${study[@]}" -j 2 -o killed s.nml >rerun.out 2>rerun.err
rc=$?
check 'called again, it ends (exit 0) with the table of the uninterrupted study' \
    '[[ $rc -eq 0 ]] && same_study first.csv killed/study.csv'
check '... redoing only the tasks that had not ended' \
    '[[ -z $(comm -23 <(echo "$kept") <(stamps killed)) ]]'

# A changed point: nu = 0.3 -> 0.35 changes the tasks of nu index 2 only.
before=$(stamps out)
sed 's/poisson = 0.25, 0.3/poisson = 0.25, 0.35/' s.nml >s2.nml
"${study[@]}" -j 2 -o out s2.nml >run3.out 2>run3.err
rc=$?
check 'a changed Poisson ratio: exit 0, the table holds nu = 0.35 and no 0.3' \
    '[[ $rc -eq 0 && $(jq "[.rows[] | select(.poisson == 0.35)] | length" out/study.json) -eq 14 && $(jq "[.rows[] | select(.poisson == 0.3)] | length" out/study.json) -eq 0 ]]'
check '... its two tasks are redone, the two others reused' \
    '[[ $(redone "$before" "$(stamps out)") == "g01_nu02 g02_nu02" ]]'

# A shorter list: the tasks it drops leave the table (their folders stay, out of the study).
sed 's/poisson = 0.25, 0.3/poisson = 0.25/' s.nml >s3.nml
before=$(stamps out)
"${study[@]}" -j 2 -o out s3.nml >run4.out 2>run4.err
rc=$?
check 'one Poisson ratio fewer: exit 0, nothing run, the table has its 14 rows only' \
    '[[ $rc -eq 0 && $(stamps out) == "$before" && $(wc -l <out/study.csv) -eq 15 && $(jq .tasks out/study.json) -eq 2 ]]'
"${study[@]}" -j 2 -o out s2.nml >run5.out 2>run5.err

# Bad input: one line naming the file, the group, the variable and what was expected; exit 2;
# the previous study stays as it was.
cp out/study.csv before.csv
printf '&study\n    poisson = 0.25, 0.7\n    lambda = 1.0\n/\n' >bad.nml
"${study[@]}" -o out bad.nml >bad.out 2>bad.err
rc=$?
check 'a Poisson ratio of 0.7: exit 2, one stderr line naming file, group, variable, expectation' \
    '[[ $rc -eq 2 && $(wc -l <bad.err) -eq 1 ]] && grep -q "^nceig-study: bad.nml: line [0-9]*: &study: poisson = .*: expected Poisson ratios -1 < nu < 0.5" bad.err'
printf '&study\n    poisson = 0.3\n    lambda = 1.0\n    widht = 2.0\n/\n' >bad2.nml
"${study[@]}" -o out bad2.nml >bad2.out 2>bad2.err
rc=$?
check 'an unknown &study variable: exit 2, its line and the known names' \
    '[[ $rc -eq 2 && $(wc -l <bad2.err) -eq 1 ]] && grep -q "^nceig-study: bad2.nml: line 4: &study: unknown variable widht: expected one of geometry" bad2.err'
printf '&study poisson = 0.3, lambda = 1.0 /\n&mesh\n    nx = 0\n/\n' >bad3.nml
"${study[@]}" -o out bad3.nml >bad3.out 2>bad3.err
rc=$?
check 'a bad template value: exit 2, nceig'"'"'s own message in the study file'"'"'s name' \
    '[[ $rc -eq 2 && $(wc -l <bad3.err) -eq 1 ]] && grep -q "^nceig-study: bad3.nml: &mesh: nx = 0: expected an integer" bad3.err'
printf '&study poisson = 0.3, lambda = 1.0 /\n&analysis kind = "eigen" /\n' >bad4.nml
"${study[@]}" -o out bad4.nml >bad4.out 2>bad4.err
rc=$?
check 'an &analysis group (the study sets it): exit 2, one line' \
    '[[ $rc -eq 2 && $(wc -l <bad4.err) -eq 1 ]] && grep -q "bad4.nml: line 2: &analysis: .*expected no &analysis group" bad4.err'
check 'after the bad inputs the previous study is untouched' \
    '[[ -z $(ls -a out | grep -F .stage) ]] && cmp -s before.csv out/study.csv && grep -q "0.35" out/plan/tasks'

# Failures: a broken .msh (nceig exit 3) and a tolerance the hp levels cannot reach in one
# level (exit 8) beside good points (the rectangle and the same square from its .geo).
cp "$source_dir/input/meshes/square.geo" square.geo
printf '$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\nbroken\n' >broken.msh
cat >f.nml <<'EOF'
&study
    geometry = 'rectangle', 'square.geo', 'broken.msh'
    poisson = 0.3
    lambda = 2.5
    quantities = 'c_n'
/
&mesh
    nx = 2, ny = 2, element = 'p1'
/
&adapt
    tolerance = 1e-6
/
EOF
"${study[@]}" -j 2 -o fail f.nml >fail.out 2>fail.err
rc=$?
check 'a study with a broken mesh goes on to its end and exits 8' \
    '[[ $rc -eq 8 && $(jq .tasks_done fail/study.json) -eq 3 ]]'
check '... the broken task is a row with exit status 3 and the mesh error as its reason' \
    '[[ $(jq -r ".rows[] | select(.geometry == \"broken\") | \"\(.exit_status) \(.converged) \(.value)\"" fail/study.json) == "3 false null" ]] &&
     jq -r ".rows[] | select(.geometry == \"broken\") | .reason" fail/study.json | grep -q "g03.msh"'
check '... the square from square.geo gives the rectangle'"'"'s c_n(2.5) within their bars' '
    read -r a ra <<<"$(row fail/study.json c_n rectangle 0.3 2.5)"
    read -r b rb <<<"$(row fail/study.json c_n square 0.3 2.5)"
    within "$a" "$ra" "$b" "$rb"'
before=$(stamps fail)
"${study[@]}" -j 2 -o fail f.nml >fail2.out 2>fail2.err
rc=$?
check 'called again: exit 8 still, the failed task not run again' '[[ $rc -eq 8 && $(stamps fail) == "$before" ]]'
"${study[@]}" -j 2 --retry-failed -o fail f.nml >fail3.out 2>fail3.err
rc=$?
check '--retry-failed runs the failed task again, and only it' \
    '[[ $rc -eq 8 && $(redone "$before" "$(stamps fail)") == "g03_nu01" ]]'
sed 's/tolerance = 1e-6/tolerance = 1e-10, max_levels = 1/' f.nml | sed "s/, 'broken.msh'//" >m.nml
"${study[@]}" -j 2 -o missed m.nml >missed.out 2>missed.err
rc=$?
check 'a tolerance not met: exit 8, rows with exit status 8, not converged, the reason given' \
    '[[ $rc -eq 8 && $(jq "[.rows[] | select(.exit_status == 8 and (.converged | not) and (.reason | test(\"tolerance\")))] | length" missed/study.json) -eq 2 ]]'
# A lambda without a positive mu (1, between the thresholds -1.94 and 1.94): its row is
# converged where the run confirmed the absence (three hp levels without a mu, and no point
# of the run missed its tolerance), not where a limit came first (max_levels = 2: two
# levels confirm nothing; the run exits 8 and the row says why).
cat >n.nml <<'EOF'
&study
    geometry = 'rectangle'
    poisson = 0.3
    lambda = 1.0, 5.0
    quantities = 'c_n'
/
&mesh
    nx = 2, ny = 2, element = 'p1'
/
&adapt
    tolerance = 1e-4
/
EOF
"${study[@]}" -j 2 -o none n.nml >none.out 2>none.err
rc=$?
check 'no positive mu at lambda = 1, confirmed: exit 0, its row converged' \
    '[[ $rc -eq 0 && $(jq -r ".rows[] | select(.lambda == 1) | \"\(.value) \(.converged) \(.reason)\"" none/study.json) == "null true no positive mu at this lambda" ]]'
sed 's/tolerance = 1e-4/tolerance = 1e-4, max_levels = 2/' n.nml >n2.nml
"${study[@]}" -j 2 -o none2 n2.nml >none2.out 2>none2.err
rc=$?
check '... max_levels = 2, the absence not confirmed: exit 8, the row not converged, said why' \
    '[[ $rc -eq 8 && $(jq -r ".rows[] | select(.lambda == 1) | .converged" none2/study.json) == false ]] &&
     jq -r ".rows[] | select(.lambda == 1) | .reason" none2/study.json |
         grep -q "not known to be confirmed.*its absence not confirmed"'
check '--help says how to use it' '"${study[@]}" --help | grep -q "^usage: nceig-study"'
cli_end
