# SPDX-License-Identifier: MIT
# shellcheck shell=bash
# SLURM job arrays that carry no path in their text. Sourced by scripts/sweep_mesh.sh (and
# installed with it to P/share/nceig/scripts/lib/); meant for any nceig driver that farms out
# tasks, e.g. a study over many inputs.
#
# A path written into a script that a shell reads is a command waiting to run: a folder named
# d'$(touch X)'e runs `touch X`, and an ordinary apostrophe breaks the script. So the scripts
# written here are fixed text (job names and counts only); the paths reach them as
# arguments, through files of NUL-separated words, and the submission script finds its folder
# from its own location at run time.
#
# What a caller provides, in a folder DIR (absolute, existing):
#   DIR/slurm/tasks         one task per line, its fields separated by tabs (slurm_task writes
#                           such a line; fields must be non-empty and hold no tab or newline:
#                           pass a path as an index into a file of your own, or in the command)
#   DIR/slurm/task.argv     the command every task runs, NUL-terminated words
#                           (slurm_write_argv); the task's fields are appended to it
#   DIR/slurm/collect.argv  the command run once every task has ended (ok or not)
# then calls
#   slurm_write_jobs DIR NAME MAX_RUNNING PER_ELEMENT
# which writes DIR/slurm_NAME.sh (the array), DIR/slurm_collect.sh and DIR/slurm_submit.sh.
# `bash DIR/slurm_submit.sh [sbatch options]` submits the array and the collection after it,
# prints both job ids and writes them to DIR/slurm/jobs; the logs go to DIR/slurm/.
# Every job runs in DIR (sbatch --chdir), so the nodes must see DIR and the commands' files.

# slurm_write_argv FILE WORD...: FILE holds the words, each ended by a NUL byte, so any text
# (quotes, spaces, newlines, $(...)) survives as one argument.
slurm_write_argv() {
    local file=$1
    shift
    (($# > 0)) || { echo "slurm_write_argv: no command for $file" >&2; return 2; }
    printf '%s\0' "$@" >"$file"
}

# slurm_task FIELD...: one line of a tasks file; refuses an empty field, a tab or a newline.
slurm_task() {
    local field
    for field in "$@"; do
        [[ -n $field && $field != *$'\t'* && $field != *$'\n'* ]] || {
            echo "slurm_task: a task field must be non-empty, without tab or newline" >&2
            return 2
        }
    done
    local IFS=$'\t'
    printf '%s\n' "$*"
}

# slurm_write_jobs DIR NAME MAX_RUNNING PER_ELEMENT: the three scripts described above. NAME
# ([a-z0-9_-]) names the array script and the jobs (nceig-NAME, nceig-NAME-collect);
# MAX_RUNNING array elements run at a time; each element runs PER_ELEMENT consecutive tasks
# (several when tasks are short, so that the scheduler's cost per job stays small).
slurm_write_jobs() {
    local dir=$1 name=$2 max_running=$3 per=$4 n_tasks n_elements
    [[ $name =~ ^[a-z0-9_-]+$ ]] || { echo "slurm_write_jobs: bad job name '$name'" >&2; return 2; }
    [[ $max_running =~ ^[1-9][0-9]*$ && $per =~ ^[1-9][0-9]*$ ]] ||
        { echo "slurm_write_jobs: MAX_RUNNING and PER_ELEMENT must be positive integers" >&2; return 2; }
    local file
    for file in tasks task.argv collect.argv; do
        [[ -s $dir/slurm/$file ]] || { echo "slurm_write_jobs: $dir/slurm/$file is missing" >&2; return 2; }
    done
    n_tasks=$(wc -l <"$dir/slurm/tasks")
    n_elements=$(((n_tasks + per - 1) / per))
    # Below: fixed text, the name and numbers checked above; no path.
    cat >"$dir/slurm_$name.sh" <<EOF
#!/bin/bash
# A SLURM job array written by nceig: $n_tasks tasks, $per per array element, at most
# $max_running elements at a time. Submit it with slurm_submit.sh beside it, which runs it in
# this folder with the arguments TASKS COMMAND PER: element k runs the tasks (lines of TASKS)
# (k - 1) PER + 1 to k PER, each as the words of COMMAND (NUL-separated) followed by the
# task's tab-separated fields. One BLAS thread per CPU the element was given.
#SBATCH --job-name=nceig-$name
#SBATCH --array=1-$n_elements%$max_running
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --output=/dev/null
set -uo pipefail
# The log, opened here in the job's folder: sbatch would read a % in the folder's path as
# one of its file-name patterns (%j, %a ...) and fail to open the file it names.
[[ -n \${SLURM_JOB_ID:-} ]] && exec >"slurm/${name}_\${SLURM_ARRAY_TASK_ID:-0}.log" 2>&1
if [[ \$# -ne 3 || -z \${SLURM_ARRAY_TASK_ID:-} ]]; then
    echo "usage: SLURM_ARRAY_TASK_ID=K bash slurm_$name.sh TASKS COMMAND PER" >&2
    exit 2
fi
command=()  # (read -d '', not mapfile -d '': bash 4.2 of older clusters has no mapfile -d)
while IFS= read -r -d '' word; do command+=("\$word"); done <"\$2" || exit 2
((\${#command[@]} > 0)) || { echo "slurm_$name.sh: no command in \$2" >&2; exit 2; }
export OPENBLAS_NUM_THREADS=\${SLURM_CPUS_PER_TASK:-1} OMP_NUM_THREADS=\${SLURM_CPUS_PER_TASK:-1} \\
    OMP_THREAD_LIMIT=\${SLURM_CPUS_PER_TASK:-1}
first=\$(((SLURM_ARRAY_TASK_ID - 1) * \$3 + 1))
last=\$((first + \$3 - 1))
status=0 line_number=0
while IFS= read -r line; do
    line_number=\$((line_number + 1))
    ((line_number >= first)) || continue
    ((line_number <= last)) || break
    IFS=\$'\t' read -r -a fields <<<"\$line"
    "\${command[@]}" "\${fields[@]}" </dev/null || status=1
done <"\$1"
exit \$status
EOF
    cat >"$dir/slurm_collect.sh" <<EOF
#!/bin/bash
# The collection job written by nceig: runs the command whose NUL-separated words are in the
# file given as its argument. slurm_submit.sh starts it once every array element has ended.
#SBATCH --job-name=nceig-$name-collect
#SBATCH --ntasks=1
#SBATCH --output=/dev/null
set -uo pipefail
[[ -n \${SLURM_JOB_ID:-} ]] && exec >slurm/collect.log 2>&1
[[ \$# -eq 1 ]] || { echo "usage: bash slurm_collect.sh COMMAND" >&2; exit 2; }
command=()
while IFS= read -r -d '' word; do command+=("\$word"); done <"\$1" || exit 2
((\${#command[@]} > 0)) || { echo "slurm_collect.sh: no command in \$1" >&2; exit 2; }
exec "\${command[@]}" </dev/null
EOF
    cat >"$dir/slurm_submit.sh" <<EOF
#!/bin/bash
# Submits slurm_$name.sh ($n_elements array elements, at most $max_running at a time) and then
# slurm_collect.sh once every element has ended (ok or not); its arguments go to both sbatch
# calls (--time, --mem, --partition, --account ...). Both jobs run in this script's folder,
# wherever it is called from; their logs go to slurm/ and the job ids to slurm/jobs.
set -euo pipefail
case \${BASH_SOURCE[0]} in */*) cd -- "\${BASH_SOURCE[0]%/*}" ;; esac
here=\$PWD
array=\$(sbatch --parsable --chdir="\$here" "\$@" slurm_$name.sh \\
    "\$here/slurm/tasks" "\$here/slurm/task.argv" $per)
array=\${array%%;*}
collect=\$(sbatch --parsable --chdir="\$here" --dependency=afterany:"\$array" "\$@" \\
    slurm_collect.sh "\$here/slurm/collect.argv")
collect=\${collect%%;*}
printf 'array=%s\ncollect=%s\n' "\$array" "\$collect" >slurm/jobs
echo "nceig-$name: array job \$array ($n_tasks tasks), collection job \$collect after it"
EOF
    chmod +x "$dir/slurm_$name.sh" "$dir/slurm_collect.sh" "$dir/slurm_submit.sh"
}

# slurm_job_state JOBID: the states of a job (one word per array element, e.g. "COMPLETED
# COMPLETED FAILED"); 'GONE' once the controller has forgotten it (MinJobAge). Needs only
# scontrol (no accounting database).
slurm_job_state() {
    local out
    out=$(scontrol show job -o "$1" 2>/dev/null) || { echo GONE; return 0; }
    grep -o 'JobState=[A-Z_]*' <<<"$out" | cut -d= -f2 | paste -sd' '
}

# slurm_wait JOBID SECONDS: waits until every element of JOBID has ended (or the controller
# forgot it); 1 when SECONDS pass first. Prints the final states.
slurm_wait() {
    local job=$1 deadline=$((SECONDS + $2)) states
    while :; do
        states=$(slurm_job_state "$job")
        if [[ ! $states =~ (PENDING|RUNNING|CONFIGURING|COMPLETING|REQUEUED|RESIZING|SUSPENDED) ]]; then
            echo "$states"
            return 0
        fi
        ((SECONDS < deadline)) || { echo "$states"; return 1; }
        sleep 1
    done
}
