#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# nceig-study --engine slurm on a real single-node SLURM cluster (munged, slurmctld and slurmd
# on this machine, scripts/lib/slurm_cluster.sh; slurm-wlm and munge installed from Debian
# when missing): the 2 x 2 study of cli_study.sh, installed into a prefix whose path holds
# quotes, $(...) and a %, submitted as a job array of two tasks per element and a collection
# job; every job ends COMPLETED, nothing a path holds is run, and study.csv equals the local
# engine's table of the same study (the same nceig runs on one BLAS thread). Submitting
# again reuses every task. Needs root; otherwise skipped (77) with the reason.
# Usage: cli_study_slurm.sh NCEIG SOURCE_DIR
set -u
nceig=$(realpath "$1")
source_dir=$(realpath "$2")
source "$(dirname "$0")/lib/cli_common.sh"
source "$(dirname "$0")/lib/study_common.sh"
cli_begin cli_study_slurm
source "$source_dir/scripts/lib/slurm_cluster.sh"
source "$source_dir/scripts/lib/slurm_jobs.sh"
unset NCEIG

if [[ $(id -u) -ne 0 ]]; then
    echo "SKIP  not root: the test installs slurm-wlm and munge and runs slurmd as root"
    exit 77
fi
for tool in parallel jq; do
    command -v "$tool" >/dev/null || { echo "SKIP  $tool not installed"; exit 77; }
done
if ! slurm_cluster_install; then
    echo "SKIP  $slurm_cluster_error"
    exit 77
fi
slurm_cluster_start
rc=$?
check 'the single-node cluster starts' '[[ $rc -eq 0 ]]'
if [[ $rc -ne 0 ]]; then
    echo "$slurm_cluster_error"
    cli_end
fi

prefix="$work/p'\$(touch PWN1)' %j"
cwd="$work/d \"\$(touch PWN2)\" %a"
cmake --install "$(dirname "$nceig")" --prefix "$prefix" >"$work/install.log" 2>&1
rc=$?
check 'cmake --install puts nceig-study and nceig-study-plan in the prefix' \
    '[[ $rc -eq 0 && -x $prefix/bin/nceig-study && -x $prefix/bin/nceig-study-plan ]]'
mkdir -p "$cwd"
cd "$cwd" || exit 1
canaries() { find "$work" "$slurm_cluster_dir" -name 'PWN*' 2>/dev/null; }
study_input s.nml 1e-6

"$prefix/bin/nceig-study" -j 2 -o local s.nml >local.out 2>local.err
rc=$?
check 'the local engine runs the study (exit 0)' '[[ $rc -eq 0 && $(wc -l <local/study.csv) -eq 29 ]]'

t0=$SECONDS
"$prefix/bin/nceig-study" --engine slurm -j 2 --per-element 2 -o "o \$(touch PWN3)" s.nml \
    >submit.out 2>submit.err
rc=$?
out="o \$(touch PWN3)"
check '--engine slurm writes and submits the array and the collection' \
    '[[ $rc -eq 0 ]] && grep -q "^array=[0-9]" "$out/slurm/jobs" && grep -q "^collect=[0-9]" "$out/slurm/jobs"'
array=$(sed -n 's/^array=//p' "$out/slurm/jobs")
collect=$(sed -n 's/^collect=//p' "$out/slurm/jobs")
collect_state=$(slurm_wait "$collect" 300)
array_state=$(slurm_job_state "$array")
echo "      array $array: $array_state; collection $collect: $collect_state ($((SECONDS - t0)) s)"
check 'two array elements (two tasks each) end COMPLETED' \
    '[[ $(tr " " "\n" <<<"$array_state" | grep -c "^COMPLETED$") -eq 2 ]]'
check 'the collection job ends COMPLETED' '[[ $collect_state == COMPLETED ]]'
check 'the table from SLURM equals the local engine'"'"'s (but times)' \
    'same_study local/study.csv "$out/study.csv"'
check 'each task was one nceig run on the nodes (c_n and thresholds in one hp climb)' \
    '[[ -z $(ls "$out"/tasks/*/thr.nml 2>/dev/null) && $(ls "$out"/tasks/*/cn/summary.json | wc -l) -eq 4 ]] &&
     [[ $(grep -l "^cn_status=0" "$out"/tasks/*/result | wc -l) -eq 4 ]]'
check 'the collection drew the pictures and study.pvd' \
    '[[ -s $out/study_cn.png && -s $out/study_thresholds.png && $(grep -c "<DataSet " "$out/study.pvd") -eq 4 ]]'
check 'nothing the paths hold was run (no PWN file)' '[[ -z $(canaries) ]]'

stamp=$(stat -c %y "$out"/tasks/*/result | md5sum)
"$prefix/bin/nceig-study" --engine slurm -j 2 --per-element 2 -o "$out" s.nml >submit2.out 2>&1
collect=$(sed -n 's/^collect=//p' "$out/slurm/jobs")
collect_state=$(slurm_wait "$collect" 300)
check 'a second submission ends COMPLETED and reuses all four tasks' \
    '[[ $collect_state == COMPLETED && $(stat -c %y "$out"/tasks/*/result | md5sum) == "$stamp" ]]'
cd /
slurm_cluster_stop
check 'the cluster stops' '[[ ! -e $slurm_cluster_dir ]]'
cli_end
