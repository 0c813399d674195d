#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Nothing lost: a run killed (SIGKILL, no chance to clean up) at several moments, into a
# directory holding a previous complete result, must leave that result as it was, or, if
# the kill came after the commit, the new complete result; never a visible partial file
# nor a summary.json next to files of another set. (tests/cli/cli_kill_loop.sh kills many more
# runs, at random moments and aimed at the commit.)
# Usage: cli_interrupted_run.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_interrupted_run
out="$work/out"

# A small complete result first (lambda = 5, two modes) ...
cat >"$work/first.nml" <<NML
&mesh nx = 6, ny = 6 /
&output directory = '$out', modes = 2 /
NML
"$nceig" "$work/first.nml" >/dev/null 2>&1
check 'first run completes' '[[ -s "$out/summary.json" ]]'
mkdir "$work/before"
cp -p "$out"/* "$work/before/"

# ... then a run of about 1.5 s (Release) with another lambda into the same directory.
cat >"$work/big.nml" <<NML
&mesh nx = 150, ny = 150 /
&analysis lambda = 4 /
&output directory = '$out', modes = 3 /
NML
n_killed=0
for delay in 0.1 0.4 0.8 1.2; do
    "$nceig" "$work/big.nml" >/dev/null 2>&1 &
    pid=$!
    sleep "$delay"
    if kill -KILL "$pid" 2>/dev/null; then n_killed=$((n_killed + 1)); fi
    wait "$pid" 2>/dev/null
    visible=$(cd "$out" && ls)
    if grep -q '"lambda": 4' "$out/summary.json" 2>/dev/null; then
        # killed after the commit: the new set is complete and is what summary.json lists
        check "kill after ${delay}s: new complete set" \
            'for f in $(grep -o "\"files\": \[.*\]" "$out/summary.json" | grep -o "[a-z_0-9]*\.[a-z]*"); do [[ -s "$out/$f" ]] || exit 1; done'
        cp -p "$work/before"/* "$out/"   # restore the first result for the next kill
        rm -f "$out/mode_003.vtu"
    else
        check "kill after ${delay}s: summary.json unchanged" 'cmp -s "$out/summary.json" "$work/before/summary.json"'
        check "kill after ${delay}s: every visible file is the first run's" \
            'for f in $visible; do cmp -s "$out/$f" "$work/before/$f" || exit 1; done'
        check "kill after ${delay}s: no other visible file" \
            '[[ "$visible" == "$(cd "$work/before" && ls)" ]]'
    fi
done
echo "      $n_killed of 4 runs were still running when killed"
check 'at least one run was killed mid-way' '[[ $n_killed -ge 1 ]]'
check 'the killed runs left nothing in the output directory' \
    '[[ -z $(cd "$out" && ls -A | grep -v -x -F "$(cd "$work/before" && ls)") ]]'
check 'the killed runs left only hidden staging folders next to it' \
    '[[ -z $(cd "$work" && ls -A | grep -v -x -e "out" -e "before" -e "first.nml" -e "big.nml" -e ".out.nceig-lock" -e ".out.nceig-staging-[0-9]*") ]]'


# The next run into the directory removes the staging folders of killed runs (their
# processes are gone; they sit next to the directory, <parent>/.<name>.nceig-staging-<pid>),
# but not that of a live process (this shell, as if it were a run in progress), nor what a
# stale-looking name links to (pid 999999999 exceeds any pid_max). Each run's begin already
# removes the folders of the runs killed before it, so one more killed process gets a
# staging folder as a run's would look when killed while writing.
sleep 30 &
victim=$!
mkdir "$work/.out.nceig-staging-$victim"
echo 'partial' >"$work/.out.nceig-staging-$victim/mode_001.vtu"
kill -KILL "$victim"
wait "$victim" 2>/dev/null
stale=$(cd "$work" && ls -A | grep '^\.out\.nceig-staging-' | tr '\n' ' ')
echo "      staging folders of killed processes: $stale"
mkdir "$work/.out.nceig-staging-$$"
echo 'being written' >"$work/.out.nceig-staging-$$/mode_001.vtu"
mkdir "$work/elsewhere"
echo 'not ours' >"$work/elsewhere/keep.txt"
ln -s "$work/elsewhere" "$work/.out.nceig-staging-999999999"
"$nceig" "$work/first.nml" >/dev/null 2>&1
check 'the next run completes' '[[ -s "$out/summary.json" ]]'
check 'the next run removed every staging folder of a killed run' \
    '( for f in $stale; do [[ ! -e "$work/$f" ]] || exit 1; done )'
check 'the next run kept the staging folder of a live process' \
    '[[ $(cat "$work/.out.nceig-staging-$$/mode_001.vtu") == "being written" ]]'
check 'the next run did not follow a link named like a staging folder' \
    '[[ -L "$work/.out.nceig-staging-999999999" && $(cat "$work/elsewhere/keep.txt") == "not ours" ]]'
check 'the next run left no staging folder of its own' \
    '[[ $(cd "$work" && ls -A | grep -c "^\.out\.nceig-staging-") -eq 2 ]]'

cli_end
