#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# cmake --install into a temporary prefix: the installed nceig answers --version, its example
# inputs run from a copy, the installed
# nceig-sweep runs a sweep with the prefix's own binaries (an nceig earlier on PATH that fails
# is not used), the installed nceig draws its sweep plot (no script is installed for it: it
# needs none), and the prefix still works after being moved.
# Usage: cli_install.sh NCEIG SOURCE_DIR
set -u
nceig=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
build=$(dirname "$nceig")
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_install
unset NCEIG

prefix="$work/prefix"
cmake --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1
rc=$?
check 'cmake --install into a fresh prefix succeeds' '[[ $rc -eq 0 ]]'
for program in nceig nceig-extrapolate nceig-sweep; do
    check "bin/$program is installed and executable" "[[ -x $prefix/bin/$program ]]"
done
check 'the installed nceig --version is the built one' \
    '[[ "$("$prefix/bin/nceig" --version)" == "$("$nceig" --version)" ]]'

# The README's first run from the prefix: the examples are installed with their meshes and run
# from a copy (the Gmsh example reads its mesh relative to its own folder).
check 'the example inputs are installed' \
    '[[ -f $prefix/share/nceig/input/square.nml && -f $prefix/share/nceig/input/meshes/square_16.msh ]]'
cp -r "$prefix/share/nceig/input" "$work/examples"
(cd "$work" && "$prefix/bin/nceig" examples/square.nml && "$prefix/bin/nceig" examples/delaunay.nml) \
    >"$work/examples.log" 2>&1
rc=$?
check 'the installed examples run from a copy' \
    '[[ $rc -eq 0 && -s $work/output/square/summary.json && -s $work/output/delaunay/summary.json ]]'

# A decoy first on PATH: a sweep that used it would fail every run.
mkdir -p "$work/decoy"
printf '#!/bin/sh\nexit 99\n' >"$work/decoy/nceig"
chmod +x "$work/decoy/nceig"
cat >"$work/template.nml" <<'NML'
&mesh nx = 2, ny = 2 /
&analysis lambda = 5.0 /
&output vtk = .false. /
NML
(cd "$work" && PATH="$work/decoy:/usr/bin:/bin" "$prefix/bin/nceig-sweep" -e p1 -n 8,16,32 \
    -o "$work/sweep" template.nml) >"$work/sweep.log" 2>&1
rc=$?
check 'installed nceig-sweep succeeds with a failing nceig first on PATH' '[[ $rc -eq 0 ]]'
check 'its results.csv has a row per run' \
    '[[ -f $work/sweep/results.csv && $(wc -l <"$work/sweep/results.csv") -eq 4 ]] && grep -q "with $prefix/bin/nceig" "$work/sweep.log"'

cat >"$work/sweep.nml" <<'NML'
&mesh nx = 4, ny = 4 /
&analysis kind = 'lambda_sweep', lambda = 5.0 /
&sweep lambda_min = 2.5, lambda_max = 10.0, n_lambda = 4 /
&output directory = 'plotted', vtk = .false. /
NML
if command -v gnuplot >/dev/null 2>&1; then
    check 'no plot script is installed' \
        '[[ -z $(find "$prefix/share/nceig/scripts" -name "plot_*") ]]'
    mv "$prefix" "$work/moved"
    (cd "$work" && "$work/moved/bin/nceig" sweep.nml) >"$work/plot.log" 2>&1
    rc=$?
    check 'a moved installed nceig runs a lambda sweep' '[[ $rc -eq 0 ]]'
    check 'it draws lambda_sweep.png' \
        'drawn "$work/plotted" lambda_sweep.png && grep -q "plot .*lambda_sweep.png" "$work/plot.log"'
else
    echo "SKIP  plot from the installed prefix: gnuplot is not installed"
fi
cli_end
