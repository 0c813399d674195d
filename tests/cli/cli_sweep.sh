#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# scripts/sweep_mesh.sh on tiny meshes: the tables and plots of a sweep, the per-run inputs
# (the template copied unchanged, the mesh and output folder as --set overrides, the
# command recorded), resuming without redoing, a failing family
# reported while the others are kept, the template's own body refined (never another one),
# and the SLURM scripts of -s.
# Usage: cli_sweep.sh NCEIG SOURCE_DIR
set -u
nceig=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
source_dir=$(realpath "$2")
sweep="$source_dir/scripts/sweep_mesh.sh"
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_sweep
column_of() { awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == name) print i }' "$1"; }
export NCEIG=$nceig

# A template with traps for any namelist editing: a '/' inside a quoted value and in
# comments, a group on one line, and a variable (poisson) the sweep must keep.
cat >"$work/template.nml" <<'NML'
! reference-like scene / small
&mesh nx = 3, ny = 3, element = 'q2', file = 'not/used.msh' ! a / in a comment
      dirichlet = 'top', neumann = 'left right', contact = 'bottom' /
&material young = 1.0, poisson = 0.25 /
&analysis lambda = 5.0 /
&output directory = 'elsewhere/out', vtk = .false. /
NML

out="$work/sweep"
bash "$sweep" -e p1:right,q1 -n 2,4,8 -j 2 -o "$out" "$work/template.nml" >"$work/first.log" 2>&1
rc=$?
check 'sweep of two families on N = 2,4,8 succeeds' '[[ $rc -eq 0 ]]'
check 'results.csv: header then 6 rows' '[[ $(wc -l <"$out/results.csv") -eq 7 ]]'
for key in element mesh n h n_dofs n_contact lowest_positive_mu time_total_s peak_rss_mb; do
    check "results.csv has column $key" '[[ -n $(column_of "$out/results.csv" $key) ]]'
done
check 'every run ok with a positive mu' \
    '[[ $(awk -F, -v s="$(column_of "$out/results.csv" status)" -v m="$(column_of "$out/results.csv" lowest_positive_mu)" "NR > 1 && \$s == \"ok\" && \$m > 0" "$out/results.csv" | wc -l) -eq 6 ]]'
# The mesh counts follow from N: P1 on N x N has 2 (N + 1) N free dofs (top row fixed) and
# N + 1 contact nodes; Q1 the same nodes.
check 'n_dofs and n_contact match the structured N x N meshes' \
    '[[ $(awk -F, -v n="$(column_of "$out/results.csv" n)" -v d="$(column_of "$out/results.csv" n_dofs)" -v c="$(column_of "$out/results.csv" n_contact)" "NR > 1 && (\$d != 2 * (\$n + 1) * \$n || \$c != \$n + 1)" "$out/results.csv" | wc -l) -eq 0 ]]'
check 'runs beside each other (-j 2) had one BLAS thread each' \
    'for s in "$out"/runs/*/output/summary.json; do [[ $(jq .blas_threads "$s") == 1 ]] || exit 1; done'
check 'GNU parallel ran them, its job log lists the 6 runs, each exit 0' \
    '[[ $(awk "NR > 1 && \$7 == 0" "$out"/log/*.joblog | wc -l) -eq 6 ]] && grep -q "(parallel)" "$work/first.log"'
check 'peak RSS measured' \
    '[[ $(awk -F, -v r="$(column_of "$out/results.csv" peak_rss_mb)" "NR > 1 && \$r > 0" "$out/results.csv" | wc -l) -eq 6 ]]'
run="$out/runs/p1-right_n0004"
check 'run input: the template, unchanged' 'cmp -s "$work/template.nml" "$run/input.nml"'
check 'run command: the mesh as --set overrides (nx, ny, element, diagonal)' \
    'for setting in mesh%nx=4 mesh%ny=4 mesh%element=p1 mesh%diagonal=right; do
         grep -qF -- "--set $setting" "$run/command" || exit 1; done'
check 'run used the template values it did not override (poisson)' \
    '[[ $(jq -r .poisson "$run/output/summary.json") == 0.25 ]]'
check 'run output directory set per run' '[[ -s $run/output/summary.json && ! -e $work/elsewhere ]]'
check 'summary.json says p1 on 4 x 4, diagonal right' \
    '[[ $(jq -r "[.nx, .ny, .element, .diagonal] | join(\" \")" "$run/output/summary.json") == "4 4 p1 right" ]]'
check 'q1 run is a quad mesh' 'grep -q "\"element\": \"q1\"" "$out/runs/q1_n0008/output/summary.json"'
check 'extrapolation.csv: a row per family' '[[ $(wc -l <"$out/extrapolation.csv") -eq 3 ]]'
for key in limit order error_estimate; do
    check "extrapolation.csv has column $key" '[[ -n $(column_of "$out/extrapolation.csv" $key) ]]'
done
# Each run's own bar beside the extrapolation: results.csv and tradeoff.csv carry every run's
# lowest_positive_error_bar, extrapolation.csv the finest run's, copied from summary.json
# (the same text, so compared exactly; the tiny meshes are under estimate = 'auto''s size).
bar_of() { jq -r '.lowest_positive_error_bar // empty' "$out/runs/$1/output/summary.json"; }
for table in results tradeoff; do
    check "$table.csv has column error_bar, each run's summary.json bar" \
        '[[ -n $(column_of "$out/$table.csv" error_bar) ]] &&
         awk -F, -v f="$(column_of "$out/$table.csv" family)" -v n="$(column_of "$out/$table.csv" n)" \
             -v b="$(column_of "$out/$table.csv" error_bar)" \
             "NR > 1 { gsub(\":\", \"-\", \$f); printf \"%s_n%04d %s\\n\", \$f, \$n, \$b }" \
             "$out/$table.csv" >"$work/bars" && [[ $(wc -l <"$work/bars") -eq 6 ]] &&
         while read -r run bar; do
             [[ -n $bar && $bar == "$(bar_of "$run")" ]] || exit 1
         done <"$work/bars"'
done
check 'extrapolation.csv: finest_error_bar is the N = 8 run'"'"'s summary.json bar' \
    '[[ -n $(column_of "$out/extrapolation.csv" finest_error_bar) ]] &&
     for family in p1:right q1; do
         [[ $(awk -F, -v f="$family" -v b="$(column_of "$out/extrapolation.csv" finest_error_bar)" \
                  "\$1 == f { print \$b }" "$out/extrapolation.csv") == \
            "$(bar_of "${family//:/-}_n0008")" && -n $(bar_of "${family//:/-}_n0008") ]] || exit 1
     done'
check 'tradeoff.csv: a row per run with a value' '[[ $(wc -l <"$out/tradeoff.csv") -eq 7 ]]'
check 'tradeoff.csv has relative_error and time_s' \
    '[[ -n $(column_of "$out/tradeoff.csv" relative_error) && -n $(column_of "$out/tradeoff.csv" time_s) ]]'
if command -v gnuplot >/dev/null 2>&1; then
    for png in convergence.png tradeoff.png; do
        check "$png is a PNG" '[[ $(head -c 4 "$out/$png" | tail -c 3) == PNG ]]'
    done
fi

# Resuming: nothing is redone, the summaries stay as they were.
stamp=$(stat -c %Y.%s "$out"/runs/*/output/summary.json | md5sum)
bash "$sweep" -e p1:right,q1 -n 2,4,8 -j 2 -o "$out" "$work/template.nml" >"$work/second.log" 2>&1
rc=$?
check 'second call succeeds' '[[ $rc -eq 0 ]]'
check 'second call redoes nothing (6 reused, 0 done)' 'grep -q "6 runs: 0 done, 6 reused, 0 failed" "$work/second.log"'
check 'second call leaves the summaries untouched' '[[ $(stat -c %Y.%s "$out"/runs/*/output/summary.json | md5sum) == "$stamp" ]]'
check 'another template is refused in the same folder' \
    '! bash "$sweep" -e q1 -n 2 -o "$out" "$source_dir/input/square.nml" >/dev/null 2>&1'

# A failing family: this nceig fails on every Q2 input; P1 runs go on and are kept.
cat >"$work/flaky_nceig" <<WRAPPER
#!/usr/bin/env bash
if [[ "\$*" == *mesh%element=q2* ]]; then echo "flaky: no Q2 today" >&2; exit 5; fi
exec "$nceig" "\$@"
WRAPPER
chmod +x "$work/flaky_nceig"
# The sweep looks for nceig-extrapolate next to nceig: put the one under test there.
cp "$(dirname "$nceig")/nceig-extrapolate" "$work/"
out2="$work/failing"
NCEIG="$work/flaky_nceig" bash "$sweep" -e q2,p1:left -n 2,4,8 -j 2 -o "$out2" "$work/template.nml" \
    >"$work/third.log" 2>&1
rc=$?
check 'a failing family makes the sweep exit non-zero' '[[ $rc -ne 0 ]]'
check 'the failures are reported with their message' '[[ $(grep -c "q2 N=.*no Q2 today" "$work/third.log") -ge 3 ]]'
check 'results.csv keeps the good runs and lists the failed ones' \
    '[[ $(grep -c ",ok," "$out2/results.csv") -eq 3 && $(grep -c ",failed," "$out2/results.csv") -eq 3 ]]'
check 'the good family is extrapolated all the same' 'grep -q "^p1:left," "$out2/extrapolation.csv"'
NCEIG="$nceig" bash "$sweep" -e q2,p1:left -n 2,4,8 -o "$out2" "$work/template.nml" >"$work/fourth.log" 2>&1
check 'running again retries only the failed runs' 'grep -q "6 runs: 3 done, 3 reused, 0 failed" "$work/fourth.log"'

# Without GNU parallel (a PATH of everything else): one line says so, and the built-in
# runner does the same runs.
mkdir "$work/no_parallel"
IFS=: read -r -a path_dirs <<<"$PATH"
for dir in "${path_dirs[@]}"; do
    for program in "$dir"/*; do
        name=${program##*/}
        [[ $name == parallel || -e $work/no_parallel/$name ]] || ln -s "$program" "$work/no_parallel/$name"
    done
done
out5="$work/no_parallel_sweep"
PATH="$work/no_parallel" bash "$sweep" -e p1:right,q1 -n 2,4,8 -j 2 -o "$out5" "$work/template.nml" \
    >"$work/fallback.log" 2>"$work/fallback.err"
rc=$?
check 'without GNU parallel: one line on stderr, the sweep succeeds with the built-in runner' \
    '[[ $rc -eq 0 && $(wc -l <"$work/fallback.err") -eq 1 ]] && grep -q "GNU parallel not found" "$work/fallback.err" && grep -q "(built-in)" "$work/fallback.log"'
check '... and gives the same results.csv values as GNU parallel did' \
    '[[ $(cut -d, -f1-9 "$out5/results.csv") == $(cut -d, -f1-9 "$out/results.csv") ]]'

# Bad arguments: one line naming the problem, exit 2.
bash "$sweep" -e p1:diagonal -n 2 -o "$work/bad" "$work/template.nml" >/dev/null 2>"$work/err"
rc=$?
check 'malformed family: exit 2, message names it' '[[ $rc -eq 2 ]] && grep -q "p1:diagonal" "$work/err"'
bash "$sweep" -e q1 -n 0 -o "$work/bad" "$work/template.nml" >/dev/null 2>"$work/err"
rc=$?
check 'N = 0 refused' '[[ $rc -eq 2 ]] && grep -q -- "-n" "$work/err"'

# The body is the template's own. A trapezoid given as a Gmsh mesh: refused without its
# geometry, refused for the structured families (they mesh a rectangle), and with -g every
# run solves a Delaunay mesh of the trapezoid: run N = 4 equals nceig on make_mesh.sh's mesh
# of the same geometry (the same Gmsh call, so the same mesh), and a unit-square run differs.
cat >"$work/trapezoid.geo" <<'GEO'
Point(1) = {0, 0, 0, 1e22}; Point(2) = {2, 0, 0, 1e22};
Point(3) = {1.5, 1, 0, 1e22}; Point(4) = {0.5, 1, 0, 1e22};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("bottom") = {1}; Physical Curve("right") = {2};
Physical Curve("top") = {3}; Physical Curve("left") = {4};
Physical Surface("body") = {1};
Mesh.Algorithm = 5;
GEO
bash "$source_dir/scripts/make_mesh.sh" 4 1 "$work/trapezoid_4.msh" msh41 "$work/trapezoid.geo"
cat >"$work/trapezoid.nml" <<'NML'
&mesh source = 'gmsh', file = 'trapezoid_4.msh', contact = 'bottom' /
&analysis lambda = 5.0 / &output vtk = .false. /
NML
bash "$sweep" -e p1:delaunay -n 4 -o "$work/trap_bad" "$work/trapezoid.nml" >/dev/null 2>"$work/err"
rc=$?
check 'Gmsh template without -g: exit 2, asks for the geometry' \
    '[[ $rc -eq 2 && $(wc -l <"$work/err") -eq 1 ]] && grep -q "source = .gmsh.*-g FILE.geo" "$work/err"'
bash "$sweep" -e q1,p1:delaunay -n 4 -g "$work/trapezoid.geo" -o "$work/trap_bad" "$work/trapezoid.nml" >/dev/null 2>"$work/err"
rc=$?
check 'Gmsh template with a structured family: exit 2 naming it' \
    '[[ $rc -eq 2 ]] && grep -q "family .q1. would solve a rectangle" "$work/err"'
check 'refused sweeps ran nothing' '[[ -z $(ls -A "$work/trap_bad/runs" 2>/dev/null) ]]'
bash "$sweep" -g "$work/trapezoid.geo" -e p1:right -n 4 -o "$work/trap_bad2" "$work/template.nml" >/dev/null 2>"$work/err"
rc=$?
check '-g with a rectangle template: exit 2' '[[ $rc -eq 2 ]] && grep -q "source = .rectangle." "$work/err"'
bash "$sweep" -e p1:delaunay -n 4,8,16 -g "$work/trapezoid.geo" -o "$work/trap" "$work/trapezoid.nml" >"$work/trap.log" 2>&1
"$nceig" "$work/trapezoid.nml" --set "output%directory=$work/trap_direct" >/dev/null 2>&1
direct=$(json "$work/trap_direct/summary.json" lowest_positive_mu)
swept=$(json "$work/trap/runs/p1-delaunay_n0004/output/summary.json" lowest_positive_mu)
square=$(json "$work/sweep/runs/p1-right_n0004/output/summary.json" lowest_positive_mu)
check "Gmsh sweep: N = 4 solves the trapezoid (mu $swept, direct $direct)" \
    '[[ -n $direct ]] && close "$swept" "$direct" 1e-12'
check "Gmsh sweep: not the square (mu $swept against $square)" '! close "$swept" "$square" 1e-2'
# A 2 x 1 rectangle template: its delaunay meshes are 2 x 1 too: edges of at most h = 1/4
# along a contact side of length 2 are at least 8, so at least 9 contact nodes (the unit
# square has about 5).
sed 's/&mesh nx = 3, ny = 3, element = .q2.,/\&mesh width = 2.0, height = 1.0,/' "$work/template.nml" >"$work/wide.nml"
bash "$sweep" -e delaunay -n 4 -o "$work/wide" "$work/wide.nml" >"$work/wide.log" 2>&1
check 'rectangle template 2 x 1: its delaunay mesh has at least 9 contact nodes at h = 1/4' \
    '[[ $(json "$work/wide/runs/delaunay_n0004/output/summary.json" n_contact) -ge 9 ]]'

# SLURM: scripts written, nothing run; no path in their text (the paths are in files of
# NUL-separated words that the scripts read), and a task runs as SLURM would start it.
out3="$work/slurm"
bash "$sweep" -s -e p1:right,q1,delaunay -n 4,8 -j 3 -o "$out3" "$work/template.nml" >"$work/slurm.log" 2>&1
rc=$?
array="$out3/slurm_sweep.sh"
check '-s succeeds and writes the array script' '[[ $rc -eq 0 && -x $array ]]'
check '-s runs nothing' '[[ -z $(ls -A "$out3/runs") ]]'
check 'array of 6 tasks, at most 3 at a time' 'grep -q "^#SBATCH --array=1-6%3$" "$array"'
check 'one task per (family, N), in order' \
    '[[ $(tr "\t" " " <"$out3/slurm/tasks" | paste -sd,) == "p1:right 4,p1:right 8,q1 4,q1 8,delaunay 4,delaunay 8" ]]'
check 'a task runs sweep_mesh.sh --run OUTDIR with this nceig' \
    '[[ $(tr "\0" "|" <"$out3/slurm/task.argv") == "env|NCEIG=$nceig|bash|$sweep|--run|$out3|" ]]'
check 'the collection step calls --collect OUTDIR' \
    '[[ $(tr "\0" "|" <"$out3/slurm/collect.argv") == "env|NCEIG=$nceig|bash|$sweep|--collect|$out3|" ]]'
check 'submission chains the collection after the array' \
    'grep -q "sbatch --parsable" "$out3/slurm_submit.sh" && grep -q "dependency=afterany" "$out3/slurm_submit.sh"'
check 'the scripts are valid bash' 'bash -n "$array" && bash -n "$out3/slurm_collect.sh" && bash -n "$out3/slurm_submit.sh"'
check 'no path in the scripts (the output folder, the source tree, nceig)' \
    '! grep -qF -e "$work" -e "$source_dir" -e "$(dirname "$nceig")" "$array" "$out3/slurm_collect.sh" "$out3/slurm_submit.sh"'
# A task as SLURM would start it (slurm_submit.sh passes these arguments): task 3 is q1 on N = 4.
(cd "$out3" && SLURM_ARRAY_TASK_ID=3 bash slurm_sweep.sh "$out3/slurm/tasks" "$out3/slurm/task.argv" 1) \
    >"$work/task.log" 2>&1
check 'array task 3 runs q1 N=4 alone' '[[ -s $out3/runs/q1_n0004/output/summary.json && $(ls "$out3/runs" | wc -l) -eq 1 ]]'
check 'the array task ran nceig on one BLAS thread' \
    '[[ $(jq -r .blas_threads "$out3/runs/q1_n0004/output/summary.json") == 1 ]]'

cli_end
