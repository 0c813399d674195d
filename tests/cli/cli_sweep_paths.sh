#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# nceig-sweep runs no text of a path: installed into a prefix holding quotes, $(...),
# backquotes, spaces and a newline, run from working folders and with -o names holding the
# same (and ;, &, |, globs, %), the local sweep (GNU parallel) and its SLURM scripts (run as
# SLURM runs them: each array task in the output folder with the arguments slurm_submit.sh
# passes, then the collection) make their tables, and no canary file (PWN*) appears. The
# submission script, run against a stand-in sbatch that records its arguments (the real one
# is cli_slurm.sh's), passes each path as one exact argument. Templates named -n.nml,
# --help.nml or a=b.nml are templates, not options or awk assignments; a newline in a
# template's or the output folder's name is refused up front (exit 2, one line).
# Usage: cli_sweep_paths.sh NCEIG SOURCE_DIR
set -u
nceig=$(realpath "$1")
source_dir=$(realpath "$2")
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_sweep_paths
unset NCEIG

prefix="$work/p'\$(touch PWN1)' \"\`touch PWN2\`\""$'\n'"x"
cmake --install "$(dirname "$nceig")" --prefix "$prefix" >"$work/install.log" 2>&1
rc=$?
check 'cmake --install into a prefix with quotes, $(...), a space and a newline' \
    '[[ $rc -eq 0 && -x $prefix/bin/nceig-sweep ]]'
sweep=("$prefix/bin/nceig-sweep" -e q1 -n 4,8,16)
printf '&mesh nx = 2, ny = 2 /\n&analysis lambda = 5.0 /\n&output vtk = .false., plot = .false. /\n' \
    >"$work/template.nml"
canaries() { find "$work" -name 'PWN*'; }

# A stand-in sbatch for slurm_submit.sh: records each call's arguments (NUL-separated) and
# answers a job id, as sbatch --parsable does.
mkdir "$work/bin"
cat >"$work/bin/sbatch" <<'STANDIN'
#!/bin/bash
n=$(ls "$SBATCH_RECORD" | wc -l)
printf '%s\0' "$@" >"$SBATCH_RECORD/call_$((n + 1))"
echo $((100 + n))
STANDIN
chmod +x "$work/bin/sbatch"

# sweep_in DIR OUT: the sweep from working folder DIR into -o OUT, locally and with -s; the
# SLURM scripts run as SLURM would, and slurm_submit.sh against the stand-in.
sweep_in() {
    local dir=$1 out=$2 label=$3 rc k
    mkdir -p "$dir"
    cp "$work/template.nml" "$dir/t.nml"
    (cd "$dir" && "${sweep[@]}" -j 2 -o "$out" t.nml) >"$work/local.log" 2>&1
    rc=$?
    check "$label: the local sweep succeeds" \
        '[[ $rc -eq 0 && $(grep -c ",ok," "$dir/$out/results.csv") -eq 3 && -s $dir/$out/extrapolation.csv ]]'
    (cd "$dir" && "${sweep[@]}" -s -o "$out.slurm" t.nml) >"$work/write.log" 2>&1
    rc=$?
    check "$label: -s writes the scripts, none holds a path" \
        '[[ $rc -eq 0 ]] && ! grep -qF "$work" "$dir/$out.slurm"/slurm_*.sh'
    (
        cd "$dir/$out.slurm" || exit 1
        for k in 1 2 3; do
            SLURM_ARRAY_TASK_ID=$k bash slurm_sweep.sh "$PWD/slurm/tasks" "$PWD/slurm/task.argv" 1
        done
        bash slurm_collect.sh "$PWD/slurm/collect.argv"
    ) >"$work/tasks.log" 2>&1
    rc=$?
    check "$label: its array tasks and collection make the tables" \
        '[[ $rc -eq 0 && $(grep -c ",ok," "$dir/$out.slurm/results.csv") -eq 3 ]]'
    rm -rf "$work/record"
    mkdir "$work/record"
    (cd "$dir" && SBATCH_RECORD="$work/record" PATH="$work/bin:$PATH" \
        bash "./$out.slurm/slurm_submit.sh" --time=00:10:00) >"$work/submit.log" 2>&1
    rc=$?
    local folder
    folder=$(cd "$dir/$out.slurm" && pwd)
    check "$label: slurm_submit.sh passes the folder and files as exact arguments" \
        '[[ $rc -eq 0 && $(tr "\0" "|" <"$work/record/call_1") == "--parsable|--chdir=$folder|--time=00:10:00|slurm_sweep.sh|$folder/slurm/tasks|$folder/slurm/task.argv|1|" && $(tr "\0" "|" <"$work/record/call_2") == "--parsable|--chdir=$folder|--dependency=afterany:100|--time=00:10:00|slurm_collect.sh|$folder/slurm/collect.argv|" ]]'
    check "$label: no canary file" '[[ -z $(canaries) ]]'
}

sweep_in "$work/d'\$(touch PWN3)'e" out "the issue's folder d'\$(touch PWN3)'e"
sweep_in "$work/s p;touch PWN5;&|<>*?[x] \"\$(touch PWN6)\" \`touch PWN7\` %j \\" \
    "-o\"\$(touch PWN8)\" %a" 'shell and sbatch specials in the folder and -o'
sweep_in "$work/Bob's runs" "Bob's sweep o'\$(touch PWN4)'x" 'apostrophes in the folder and -o'

# A newline: refused up front in the working folder (nceig takes none in a --set value) or
# in -o; one line, exit 2, nothing run.
one_line_exit_2() { [[ $1 -eq 2 && $(wc -l <"$work/err") -eq 1 && ! -e $2 ]] && grep -q newline "$work/err"; }
nl_dir="$work/nl"$'\n'"x"
mkdir -p "$nl_dir"
cp "$work/template.nml" "$nl_dir/t.nml"
(cd "$nl_dir" && "${sweep[@]}" -o out t.nml) >/dev/null 2>"$work/err"
rc=$?
check 'a newline in the working folder: exit 2, one line, nothing run' \
    'one_line_exit_2 $rc "$nl_dir/out/runs/q1_n0004"'
nl_out="o"$'\n'"x"
(cd "$work" && "${sweep[@]}" -o "$nl_out" template.nml) >/dev/null 2>"$work/err"
rc=$?
check 'a newline in -o: exit 2, one line, nothing run' 'one_line_exit_2 $rc "$work/$nl_out/runs/q1_n0004"'

# Templates whose names look like options or awk assignments: after --, or as ./NAME.
mkdir -p "$work/names"
for name in -n.nml --help.nml a=b.nml; do cp "$work/template.nml" "$work/names/$name"; done
# named NAME ARGS...: the sweep in names/ with ARGS; true when it made 3 ok rows in names/NAME
named() {
    local out=$1
    shift
    (cd "$work/names" && "${sweep[@]}" -o "$out" "$@") >>"$work/names.log" 2>&1 &&
        [[ $(grep -c ",ok," "$work/names/$out/results.csv") -eq 3 ]]
}
check 'template -n.nml after --: a sweep' 'named dash_n -- -n.nml'
check 'template --help.nml after --: a sweep' 'named help -- --help.nml'
check 'template ./--help.nml: a sweep' 'named help2 ./--help.nml'
check 'template a=b.nml (an awk assignment if passed as is): a sweep' 'named assign a=b.nml'
check 'the default output folder of -n.nml is output/sweep_-n' \
    '(cd "$work/names" && "${sweep[@]}" -s -- -n.nml >/dev/null 2>&1) && [[ -x $work/names/output/sweep_-n/slurm_submit.sh ]]'
nl_name="new"$'\n'"line"
cp "$work/template.nml" "$work/names/$nl_name.nml"
(cd "$work/names" && "${sweep[@]}" "$nl_name.nml") >"$work/out" 2>"$work/err"
rc=$?
check 'a newline in the template name: exit 2, one line, before anything ran' \
    'one_line_exit_2 $rc "$work/names/output/sweep_$nl_name" && [[ ! -s $work/out ]]'
check 'no canary file at the end' '[[ -z $(canaries) ]]'
cli_end
