#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# nceig starts gnuplot with an argument vector, through no shell, and writes paths into
# gnuplot text as quoted strings: an output directory holding quotes, `;` or gnuplot's
# system() runs nothing, and "Bob's results" gets its pictures (mode_001.png,
# lambda_sweep.png, adapt.png). Under a low
# descriptor limit the note says why gnuplot did not start, not that it is missing. A reader
# that closes stdout early (`| head`) neither kills the run (SIGPIPE) nor loses its set.
# Usage: cli_no_shell.sh NCEIG SOURCE_DIR
set -u
# absolute: the runs start in the scratch folder, where relative output paths land
nceig=$(realpath "$1")
source_dir=$(realpath "$2")
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_no_shell
cd "$work" || exit 1

have_gnuplot=0
command -v gnuplot >/dev/null 2>&1 && have_gnuplot=1
[[ $have_gnuplot -eq 1 ]] || echo "      gnuplot is not installed: the pictures are not checked"

# eigen DIRECTORY [how]: a small eigen run into DIRECTORY, named in the input file (or, with
# `set`, by --set); its exit status in $rc, stdout in $work/stdout
eigen() {
    if [[ ${2:-file} == set ]]; then
        printf '&mesh nx = 6, ny = 6 /\n' >"$work/eigen.nml"
        "$nceig" "$work/eigen.nml" --set "output%directory=$1" >"$work/stdout" 2>"$work/stderr"
    else
        # the namelist string in double quotes: a single quote in it is plain text
        printf '&mesh nx = 6, ny = 6 /\n&output directory = "%s" /\n' "$1" >"$work/eigen.nml"
        "$nceig" "$work/eigen.nml" >"$work/stdout" 2>"$work/stderr"
    fi
    rc=$?
}

# picture DIRECTORY FILE: FILE was drawn there (or gnuplot is missing)
picture() { [[ $have_gnuplot -eq 0 || -s "$1/$2" ]]; }

for how in file set; do
    dir="res';touch INJECTED;'"
    eigen "$dir" "$how"
    check "&output directory with ';touch INJECTED;' ($how): exit 0, the set committed" \
        '[[ $rc -eq 0 && -s "$dir/summary.json" ]]'
    check "... ($how): no command ran (no INJECTED file)" '[[ ! -e INJECTED ]]'
    check "... ($how): mode_001.png drawn" 'picture "$dir" mode_001.png'
    rm -rf "$dir" INJECTED
done

# A name that is harmless to a shell but a command to gnuplot if pasted unquoted
dir="g'.system('touch INJECTED').'"
eigen "$dir" set
check "a directory with gnuplot's system(): exit 0, nothing ran, mode_001.png drawn" \
    '[[ $rc -eq 0 && ! -e INJECTED ]] && picture "$dir" mode_001.png'
rm -rf INJECTED

eigen "Bob's results" set
echo "      $(grep 'mode plot' "$work/stdout")"
check "\"Bob's results\": exit 0, mode_001.png drawn" \
    '[[ $rc -eq 0 ]] && picture "Bob'\''s results" mode_001.png'

eigen "-dash" set
check 'a relative directory starting with "-": mode_001.png drawn' \
    '[[ $rc -eq 0 ]] && picture -dash mode_001.png'

# The other pictures, whose gnuplot text holds data and titles besides the path:
# lambda_sweep.png and adapt.png
cat >"$work/sweep.nml" <<'NML'
&mesh nx = 6, ny = 6 /
&analysis kind = 'lambda_sweep' /
&sweep lambda_min = -20.0, lambda_max = 20.0, n_lambda = 21 /
&output vtk = .false. /
NML
cat >"$work/adapt.nml" <<'NML'
&mesh nx = 2, ny = 2, element = 'p2' /
&adapt tolerance = 1e-3 /
&output vtk = .false. /
NML
for dir in "Bob's sweep" "s'.system('touch INJECTED').'"; do
    "$nceig" "$work/sweep.nml" --set "output%directory=$dir" >"$work/stdout" 2>&1
    rc=$?
    echo "      $(grep '  plot ' "$work/stdout")"
    check "lambda_sweep into \"$dir\": exit 0, nothing ran" '[[ $rc -eq 0 && ! -e INJECTED ]]'
    check "lambda_sweep into \"$dir\": lambda_sweep.png drawn" 'picture "$dir" lambda_sweep.png'
    rm -rf INJECTED "$dir"
    "$nceig" "$work/adapt.nml" --set "output%directory=$dir" >"$work/stdout" 2>&1
    rc=$?
    echo "      $(grep 'adapt plot' "$work/stdout")"
    check "adaptive eigen into \"$dir\": exit 0, nothing ran, adapt.png drawn" \
        '[[ $rc -eq 0 && ! -e INJECTED ]] && picture "$dir" adapt.png'
    rm -rf INJECTED
done

# Few descriptors: the spawn itself may fail (EMFILE). gnuplot is installed, so no limit
# may make the note say it is not; at the lowest limits that let a run through, the note
# names the reason.
if [[ $have_gnuplot -eq 1 ]]; then
    n_reason=0 n_wrong=0
    for n in 4 5 6 7 8; do
        (ulimit -n "$n" && exec "$nceig" "$work/eigen.nml" --set output%directory=fd) \
            >"$work/stdout" 2>&1
        rc=$?
        note=$(grep 'mode plot' "$work/stdout")
        echo "      ulimit -n $n: exit $rc $note"
        [[ $rc -ne 0 ]] && continue
        [[ $note == *'not installed'* ]] && n_wrong=$((n_wrong + 1))
        [[ $note == *'gnuplot could not be started: Too many open files'* ]] &&
            n_reason=$((n_reason + 1))
    done
    check 'ulimit -n 4..8: never "gnuplot is not installed"' '[[ $n_wrong -eq 0 ]]'
    check 'ulimit -n 4..8: the lowest limit says "could not be started: Too many open files"' \
        '[[ $n_reason -ge 1 ]]'
fi

# stdout closed early: with progress lines (the reader leaves after the first) and without
for progress in .true. .false.; do
    rm -rf pipe
    "$nceig" "$source_dir/input/square.nml" --set output%directory=pipe \
        --set "output%progress=$progress" 2>"$work/stderr" | head -c 10 >/dev/null
    rc=${PIPESTATUS[0]}
    check "| head -c 10, progress = $progress: exit 0 (not 141), no error, summary.json" \
        '[[ $rc -eq 0 && ! -s "$work/stderr" && -s pipe/summary.json ]]'
done
# A failed run keeps its own status when stdout is closed
"$nceig" "$work/no-such-input.nml" 2>/dev/null | head -c 1 >/dev/null
rc=${PIPESTATUS[0]}
check '| head, a missing input file: exit 2 as ever' '[[ $rc -eq 2 ]]'

cli_end
