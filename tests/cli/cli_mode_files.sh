#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Mode files say what they are the mode of: mu (and its imaginary part), lambda and nu as
# VTK field data of each mode_NNN.vtu (eigen, threshold, hp); threshold and sweep runs
# write the modes of positive mu only, so none (and no mode_001.png) at a lambda without
# one: they wrote the mode of a negative or complex mu there.
# Usage: cli_mode_files.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source_dir=$2
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_mode_files
cd "$work"
square="$source_dir/input/square.nml"

# field FILE NAME: the value of the field data array NAME of a .vtu file
field() { sed -n "s/.*Name=\"$2\" NumberOfTuples=\"1\" format=\"ascii\"> *\([^ <]*\) *<.*/\1/p" "$1"; }
# csv_mu DIR ROW: re of row ROW of DIR/eigenvalues.csv
csv_mu() { awk -F, -v row="$2" 'NR == row + 1 { print $2 }' "$1/eigenvalues.csv"; }

"$nceig" "$square" --set mesh%nx=8 --set mesh%ny=8 --set output%modes=3 \
    --set output%directory=eigen --set output%plot=.false. >/dev/null 2>&1
ok=1
for k in 1 2 3; do
    file=eigen/mode_00$k.vtu
    close "$(field "$file" mu)" "$(csv_mu eigen $k)" 1e-15 || ok=0
    [[ -n $(field "$file" mu_imag) ]] || ok=0
done
check 'eigen: each mode file carries its mu (the row of eigenvalues.csv) and mu_imag' '[[ $ok -eq 1 ]]'
check 'eigen: lambda = 5 and nu = 0.3 in the field data' \
    'close "$(field eigen/mode_001.vtu lambda)" 5 0 && close "$(field eigen/mode_001.vtu nu)" 0.3 1e-15'
"$nceig" "$square" --set mesh%nx=8 --set mesh%ny=8 --set output%vtk_format=ascii \
    --set output%directory=ascii --set output%plot=.false. >/dev/null 2>&1
check 'eigen, ascii: the same field data' \
    '[[ $(field ascii/mode_001.vtu mu) == $(field eigen/mode_001.vtu mu) ]]'

# threshold at lambda = 1, between lambda- and lambda+: no positive mu, no mode
"$nceig" "$square" --set mesh%nx=8 --set mesh%ny=8 --set analysis%kind=threshold \
    --set analysis%lambda=1.0 --set output%modes=3 --set output%directory=inside >out 2>err
rc=$?
check 'threshold at lambda = 1 (no positive mu): no mode file, no mode_001.png' \
    '[[ $rc -eq 0 ]] && ! compgen -G "inside/mode_*" >/dev/null && ! grep -q mode_ inside/summary.json'
check 'threshold at lambda = 1: the summary says why' 'grep -q "no positive mu at lambda = 1.0" out'

# threshold at lambda = 5 with modes = 40: the positive mu only (their rows come first)
"$nceig" "$square" --set mesh%nx=8 --set mesh%ny=8 --set analysis%kind=threshold \
    --set output%modes=40 --set output%directory=outside --set output%plot=.false. >/dev/null 2>&1
positive=$(grep -c ',positive,' outside/eigenvalues.csv)
check "threshold at lambda = 5: as many mode files as positive mu ($positive), each positive" \
    '[[ $positive -ge 1 && $(ls outside/mode_*.vtu | wc -l) -eq $positive ]] && awk "BEGIN { exit !($(field outside/mode_001.vtu mu) > 0) }"'

# hp: the sampled mode file carries them too
"$nceig" "$source_dir/input/adapt.nml" --set adapt%strategy=hp --set adapt%tolerance=1e-4 \
    --set output%directory=hp --set output%plot=.false. >/dev/null 2>&1
check 'hp: mu, lambda and nu in the sampled mode file' \
    'close "$(field hp/mode_001.vtu mu)" "$(csv_mu hp 1)" 1e-15 && close "$(field hp/mode_001.vtu lambda)" 5 0 && close "$(field hp/mode_001.vtu nu)" 0.3 1e-15'

cli_end
