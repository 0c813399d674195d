#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The SLURM scripts of a mesh sweep on a real single-node SLURM cluster (munged, slurmctld and
# slurmd on this machine, scripts/lib/slurm_cluster.sh; slurm-wlm and munge are installed
# from Debian when missing): nceig-sweep -s from a hostile working folder, installed into a
# hostile prefix, with a hostile -o name; slurm_submit.sh submits the array and the
# collection; every job ends COMPLETED, nothing that a path holds is run (no canary file),
# and the tables equal those of the same sweep run locally (the same nceig runs). Submitting
# again reuses every run. The job-array library itself (scripts/lib/slurm_jobs.sh) with two
# tasks per array element runs every task once, its fields intact. Needs root (to install, and slurmd is run as root: it starts each
# job as its user; other users were not tried); otherwise skipped (77) with the reason. A cluster that is installed but does not come up fails, with its logs.
# Usage: cli_slurm.sh NCEIG SOURCE_DIR
set -u
nceig=$(realpath "$1")
source_dir=$(realpath "$2")
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_slurm
source "$source_dir/scripts/lib/slurm_cluster.sh"
source "$source_dir/scripts/lib/slurm_jobs.sh"
unset NCEIG

if [[ $(id -u) -ne 0 ]]; then
    echo "SKIP  not root: the test installs slurm-wlm and munge and runs slurmd (which starts each job as its user) as root"
    exit 77
fi
if ! slurm_cluster_install; then
    echo "SKIP  $slurm_cluster_error"
    exit 77
fi
slurm_cluster_start
rc=$?
check 'the single-node cluster starts and its node is idle' '[[ $rc -eq 0 ]]'
if [[ $rc -ne 0 ]]; then
    echo "$slurm_cluster_error"
    cli_end
fi

# Hostile names: quotes, $(...), backquotes, spaces, and sbatch's file-name patterns (%j, %a)
# in the install prefix (with a newline too), the working folder and -o.
prefix="$work/p'\$(touch PWN1)' \"\`touch PWN2\`\""$'\n'"x"
cwd="$work/d'\$(touch PWN3)'e \"\$(touch PWN4)\" %j"
out="o %a \$(touch PWN5) \`touch PWN6\`"
start_dir=$PWD
cmake --install "$(dirname "$nceig")" --prefix "$prefix" >"$work/install.log" 2>&1
rc=$?
check 'cmake --install into the hostile prefix' '[[ $rc -eq 0 && -x $prefix/bin/nceig-sweep ]]'
mkdir -p "$cwd"
cd "$cwd" || exit 1
# The reference scene at small N, without the mode files and pictures (not in the tables).
sed 's/vtk = .true./vtk = .false., plot = .false./' "$source_dir/input/square.nml" >square.nml
sweep=("$prefix/bin/nceig-sweep" -e p1:right,q1 -n 4,8,16 -j 2)
# canaries: the PWN files any run of what the names hold would leave
canaries() { find "$work" "$start_dir" "$slurm_cluster_dir" -name 'PWN*' 2>/dev/null; }

"${sweep[@]}" -o local square.nml >"$work/local.log" 2>&1
rc=$?
check 'the local sweep from the hostile folder succeeds' '[[ $rc -eq 0 && -s local/results.csv ]]'

"${sweep[@]}" -s -o "$out" square.nml >"$work/write.log" 2>&1
rc=$?
check 'nceig-sweep -s writes the scripts' '[[ $rc -eq 0 && -x $out/slurm_submit.sh ]]'
t0=$SECONDS
bash "$out/slurm_submit.sh" >"$work/submit.log" 2>&1
rc=$?
check 'slurm_submit.sh submits the array and the collection' \
    '[[ $rc -eq 0 ]] && grep -q "^array=[0-9]" "$out/slurm/jobs" && grep -q "^collect=[0-9]" "$out/slurm/jobs"'
array=$(sed -n 's/^array=//p' "$out/slurm/jobs")
collect=$(sed -n 's/^collect=//p' "$out/slurm/jobs")
collect_state=$(slurm_wait "$collect" 150)
array_state=$(slurm_job_state "$array")
echo "      array $array: $array_state; collection $collect: $collect_state ($((SECONDS - t0)) s)"
check 'the six array elements end COMPLETED' \
    '[[ $(tr " " "\n" <<<"$array_state" | grep -c "^COMPLETED$") -eq 6 ]]'
check 'the collection job ends COMPLETED after them' '[[ $collect_state == COMPLETED ]]'
check 'the logs are in OUTDIR/slurm' '[[ -s $out/slurm/sweep_1.log && -s $out/slurm/collect.log ]]'
check 'each array task ran nceig on one BLAS thread' \
    'for s in "$out"/runs/*/output/summary.json; do [[ $(jq .blas_threads "$s") == 1 ]] || exit 1; done'
check 'nothing the paths hold was run (no PWN file)' '[[ -z $(canaries) ]]'

# same_table A B SKIP: the CSV files agree, column by column, but the columns named in SKIP
# (times and memory); numbers to a relative 1e-9, text exactly. The runs are the same nceig
# on the same input with one BLAS thread, so mu agrees to round-off; the extrapolation of
# three such mu can amplify a last-digit difference by about 1/(1 - ratio of differences),
# far below 1e-9 here.
same_table() {
    awk -F, -v skip="$3" '
        function num(s) { return s ~ /^[-+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][-+]?[0-9]+)?$/ }
        NR == FNR { a[FNR] = $0; n = FNR; next }
        FNR == 1 { split(skip, s, " "); for (k in s) drop[s[k]] = 1
                   for (i = 1; i <= NF; i++) name[i] = $i }
        { m = FNR; split(a[FNR], x, ",")
          for (i = 1; i <= NF; i++) {
              if (name[i] in drop) continue
              if (num(x[i]) && num($i)) {
                  d = x[i] - $i; d = d < 0 ? -d : d; r = $i < 0 ? -$i : $i
                  if (d > 1e-9 * r) { print "differ: " name[i] " row " FNR ": " x[i] " " $i; bad = 1 }
              } else if (x[i] != $i) { print "differ: " name[i] " row " FNR ": " x[i] " " $i; bad = 1 }
          } }
        END { if (m != n) { print "rows: " n " and " m; bad = 1 }; exit bad }' "$1" "$2"
}
times="time_total_s time_output_s time_mesh_s wall_s peak_rss_mb time_s"
check 'results.csv from SLURM equals the local one (but times)' \
    'same_table local/results.csv "$out/results.csv" "$times"'
check 'extrapolation.csv from SLURM equals the local one' \
    'same_table local/extrapolation.csv "$out/extrapolation.csv" ""'
check 'tradeoff.csv from SLURM equals the local one (but times)' \
    'same_table local/tradeoff.csv "$out/tradeoff.csv" "$times"'
check 'the collection drew the plots' '[[ -s $out/convergence.png && -s $out/tradeoff.png ]]'

# Submitting again: every run is reused, nothing is redone.
stamp=$(stat -c %Y "$out"/runs/*/output/summary.json | md5sum)
bash "$out/slurm_submit.sh" >"$work/submit2.log" 2>&1
collect=$(sed -n 's/^collect=//p' "$out/slurm/jobs")
collect_state=$(slurm_wait "$collect" 150)
check 'a second submission ends COMPLETED and reuses all six runs' \
    '[[ $collect_state == COMPLETED && $(cat "$out"/slurm/sweep_*.log | grep -c "^reused") -eq 6 ]]'
check '... and leaves the summaries untouched' \
    '[[ $(stat -c %Y "$out"/runs/*/output/summary.json | md5sum) == "$stamp" ]]'
check 'still no PWN file' '[[ -z $(canaries) ]]'
# The library as a future driver uses it: 5 tasks, 2 per array element (3 elements), fields
# with spaces, quotes and $(...); each task records its fields, the collection joins them.
lib="$cwd/lib's \$(touch PWN7)"
mkdir -p "$lib/slurm"
for k in 1 2 3 4 5; do slurm_task "$k" "a 'b' \$(touch PWN8) $k"; done >"$lib/slurm/tasks"
slurm_write_argv "$lib/slurm/task.argv" bash -c 'printf "%s|%s\n" "$1" "$2" >"$0/record_$1"' "$lib"
slurm_write_argv "$lib/slurm/collect.argv" bash -c 'cat "$0"/record_* >"$0/all"' "$lib"
slurm_write_jobs "$lib" study 2 2
bash "$lib/slurm_submit.sh" >"$work/lib.log" 2>&1
lib_array=$(sed -n 's/^array=//p' "$lib/slurm/jobs")
lib_state=$(slurm_wait "$(sed -n 's/^collect=//p' "$lib/slurm/jobs")" 120)
check 'slurm_write_jobs with 2 tasks per element: 3 elements, all COMPLETED' \
    '[[ $lib_state == COMPLETED && $(slurm_job_state "$lib_array") == "COMPLETED COMPLETED COMPLETED" ]]'
check '... every task ran once with its fields intact, and the collection after them' \
    '[[ $(cat "$lib/all") == "$(for k in 1 2 3 4 5; do echo "$k|a '"'b'"' \$(touch PWN8) $k"; done)" ]]'
check '... and nothing was run from the fields or the folder (no PWN file)' '[[ -z $(canaries) ]]'
cd /
cluster=$slurm_cluster_dir
# daemons DIR: a munged, slurmctld, slurmd or job step of the cluster in DIR still runs
daemons() {
    local process
    for process in /proc/[0-9]*; do
        case $(cat "$process/comm" 2>/dev/null) in
            munged | slurmctld | slurmd | slurmstepd)
                cat "$process/cmdline" "$process/environ" 2>/dev/null | tr '\0' '\n' |
                    grep -qF "$1" && return 0 ;;
        esac
    done
    return 1
}
check 'while it runs, its daemons are found' 'daemons "$cluster"'
slurm_cluster_stop
check 'the cluster stops: its folder is gone, none of its daemons runs' \
    '[[ ! -e $cluster ]] && ! daemons "$cluster"'
cli_end
