#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A stop signal is the user's decision, whatever library runs when it comes: SIGTERM while
# METIS orders the nodes (METIS traps SIGTERM itself and returned "METIS failed", exit 5;
# an adaptive run then committed its last level and exited 8), in an adaptive loop at random
# moments, and SIGXCPU from a CPU time limit (ulimit -t: it was a gfortran backtrace) end the
# run by that signal, exit status 128 + n, with one line on stderr, the previous set intact
# and no staging folder left.
# Usage: cli_stop_signals.sh NCEIG SOURCE_DIR [ROUNDS]
set -u
nceig=$1
rounds=${3:-6}
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_stop_signals
out="$work/out"
# A background job of a script ignores SIGINT; job control keeps the shell's own ways.
set -m

# The previous set: a small run, kept aside to compare with.
cat >"$work/previous.nml" <<NML
&mesh nx = 8, ny = 8 /
&output directory = '$out', plot = .false. /
NML
"$nceig" "$work/previous.nml" >/dev/null 2>&1
cp -a "$out" "$work/kept"
intact() { diff -r "$out" "$work/kept" >/dev/null && ! compgen -G "$work/.out.nceig-staging-*" >/dev/null; }
check 'the previous set is written' '[[ -s $out/summary.json ]]'

# Waits without starting a process (a sleep or a grep costs some ms, more under load, and
# the window of an ordering is tens of ms): `read -t` on a FIFO nobody writes to.
mkfifo "$work/idle"
exec 9<>"$work/idle"
# pause MS: wait MS milliseconds.
pause() {
    local seconds
    printf -v seconds '%d.%03d' $(($1 / 1000)) $(($1 % 1000))
    read -r -t "$seconds" -u 9 _ || :
}
# until_line FILE TEXT PID: wait until FILE holds a line with TEXT (or the run ended),
# reading its new lines as they come.
until_line() {
    local line
    : >>"$1"
    exec 8<"$1"
    while kill -0 "$3" 2>/dev/null; do
        while IFS= read -r line <&8; do
            [[ $line == *"$2"* ]] && { exec 8<&-; return; }
        done
        pause 1
    done
    exec 8<&-
}

# ordering_window INPUT AFTER K: "MS GAP", the time of the K-th ordering of a run of INPUT
# (from its progress line) and the time from the line with AFTER to that ordering's line as
# a poll every 2 ms sees it, both in ms (the run is stopped there). Where AFTER is not the
# line right before the ordering (a refinement and an assembly come between), the ordering
# is the last MS of the GAP, and a load on the machine stretches both.
ordering_window() {
    : >"$work/full.out"   # there before the loop reads it (the run's redirection may lag)
    "$nceig" "$1" --set output%directory="$work/full" >"$work/full.out" 2>&1 &
    local pid=$! ms t0 t1
    until_line "$work/full.out" "$2" "$pid"
    t0=${EPOCHREALTIME//[!0-9]/}
    while kill -0 "$pid" 2>/dev/null &&
          (($(grep -c '\.\. ordering' "$work/full.out") < $3)); do
        sleep 0.002
    done
    t1=${EPOCHREALTIME//[!0-9]/}
    kill -TERM "$pid" 2>/dev/null
    wait "$pid"
    ms=$(awk -v n="$3" '/\.\. ordering/ && ++k == n {printf "%d", $3 * 1000}' "$work/full.out")
    echo "$((ms > 1 ? ms : 1)) $(((10#$t1 - 10#$t0) / 1000))"
}

# signal_rounds INPUT AFTER K: `rounds` runs of INPUT into $out, each sent SIGTERM at a
# random moment of its K-th METIS ordering as ordering_window places it: after the progress
# line AFTER, at GAP - MS plus a random part of the first half of MS (seeing the line and
# starting sleep take some ms of their own, more under load), and earlier after each round
# whose signal came too late. Where none of them came before the ordering ended (a loaded
# machine moves the window), up to four times as many more rounds, until one does. Counts
# the signals that came before the ordering ended (n_in_metis), the runs that did not end by
# the signal (n_bad_status), without their one line (n_bad_line) or without the previous
# set intact (n_bad_set; it is put back).
signal_rounds() {
    local input=$1 after=$2 k=$3 ms gap lead i rc pid
    read -r ms gap < <(ordering_window "$input" "$after" "$k")
    lead=$((gap > ms ? gap - ms : 0))
    echo "      ordering $k of $(basename "$input") takes $ms ms, ending $gap ms after '$after'"
    n_in_metis=0 n_bad_status=0 n_bad_line=0 n_bad_set=0
    for ((i = 1; i <= rounds || (n_in_metis == 0 && i <= 5 * rounds); i++)); do
        # Emptied here, not only by the run's redirection: that happens in the child, after
        # the fork, and a wait that read the last round's file before it would find its line
        # at once and signal the child before nceig runs (exit 143 from the shell or the
        # loader, with no line).
        : >"$work/run.out"
        : >"$work/run.err"
        "$nceig" "$input" >"$work/run.out" 2>"$work/run.err" &
        pid=$!
        until_line "$work/run.out" "$after" "$pid"
        pause $((lead + RANDOM % ((ms + 1) / 2)))
        kill -TERM "$pid" 2>/dev/null
        wait "$pid"
        rc=$?
        # A signal that came after the ordering: the machine is slower than when the window
        # was measured; aim earlier (the line AFTER precedes the ordering, so a lead of 0
        # lands before it ends).
        if (($(grep -c '\.\. ordering' "$work/run.out") < k)); then
            n_in_metis=$((n_in_metis + 1))
        else
            lead=$((lead / 2))
        fi
        if [[ $rc -ne 143 ]]; then
            n_bad_status=$((n_bad_status + 1))
            echo "      round $i: exit $rc: $(head -c 300 "$work/run.err")"
        fi
        if ! { [[ $(wc -l <"$work/run.err") -eq 1 ]] &&
               grep -q "^nceig: $input: stopped by SIGTERM$" "$work/run.err"; }; then
            n_bad_line=$((n_bad_line + 1))
            echo "      round $i: stderr $(wc -l <"$work/run.err") lines: $(head -c 300 "$work/run.err")"
        fi
        intact || { n_bad_set=$((n_bad_set + 1)); rm -rf "$out"; cp -a "$work/kept" "$out"; }
    done
    echo "      $n_in_metis of $((i - 1)) signals came before ordering $k ended"
}
RANDOM=2718

# 1. SIGTERM during METIS's nested dissection of 40000 nodes ('B for lambda' precedes it).
cat >"$work/order.nml" <<NML
&mesh nx = 200, ny = 200 /
&output directory = '$out', plot = .false. /
NML
signal_rounds "$work/order.nml" 'B for lambda' 1
check 'some signals came while METIS ordered' '[[ $n_in_metis -ge 1 ]]'
check 'SIGTERM during the ordering: exit 143 every time' '[[ $n_bad_status -eq 0 ]]'
check 'SIGTERM during the ordering: one line naming the input and the signal' \
    '[[ $n_bad_line -eq 0 ]]'
check 'SIGTERM during the ordering: the previous set stays, no staging folder' \
    '[[ $n_bad_set -eq 0 ]]'

# 2. The same in an adaptive run, during the ordering of its second level (after the
# progress line of that level's refinement): the first level is complete, but a signal
# commits nothing (it committed the first level, exit 8, or ended with exit 5).
cat >"$work/adapt.nml" <<NML
&mesh nx = 100, ny = 100, element = 'p1' /
&adapt tolerance = 1e-12, max_levels = 1 /
&output directory = '$out', plot = .false. /
NML
signal_rounds "$work/adapt.nml" 'level 1, ' 2
check 'some signals came while METIS ordered level 1' '[[ $n_in_metis -ge 1 ]]'
check 'SIGTERM in an adaptive loop: exit 143 and one line every time' \
    '[[ $n_bad_status -eq 0 && $n_bad_line -eq 0 ]]'
check 'SIGTERM in an adaptive loop: the previous set stays, nothing committed' \
    '[[ $n_bad_set -eq 0 ]]'

# 3. SIGXCPU: a soft CPU time limit of 1 s on a run that needs more.
(
    ulimit -S -t 1
    exec "$nceig" "$work/order.nml" --set mesh%nx=400 --set mesh%ny=400 >/dev/null 2>"$work/xcpu.err"
)
rc=$?
echo "      exit $rc; stderr: $(head -c 300 "$work/xcpu.err")"
check 'SIGXCPU (ulimit -t): exit 152 = 128 + 24' '[[ $rc -eq 152 ]]'
check 'SIGXCPU: one line naming the input and the limit' \
    '[[ $(wc -l <"$work/xcpu.err") -eq 1 ]] && grep -q "order.nml: stopped by SIGXCPU: the CPU time limit (ulimit -t)" "$work/xcpu.err"'
check 'SIGXCPU: the previous set stays, no staging folder, no core file' \
    'intact && ! compgen -G "core*" >/dev/null'

cli_end
