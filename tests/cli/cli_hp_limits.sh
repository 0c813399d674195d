#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# hp runs that hung before their first level, or at a level the mesh builder could not make:
# &adapt sigma = 0.999999, 1e-20 or 1e-300 (refused now: exit 2, one line with the range);
# sigma = 0.01 to 1e-14, whose 7th level asks cells below binary64's resolution (exit 8, the
# last level written); a Gmsh mesh with one edge 1e-6 long beside the end of the contact
# (the grading asked for ever smaller cells beside it; max_levels and max_dofs did not stop
# it). `timeout` turns a hang into a failure.
# Usage: cli_hp_limits.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source_dir=$2
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_hp_limits
cd "$work"
HANG=120
adapt="$source_dir/input/adapt.nml"

# hp NAME ARGS...: an hp run of input/adapt.nml with ARGS under timeout; sets rc.
hp() {
    local name=$1
    shift
    timeout $HANG "$nceig" "$adapt" --set adapt%strategy=hp --set output%plot=.false. \
        --set output%directory="$name" "$@" >"$name.out" 2>"$name.err"
    rc=$?
}

for sigma in 0.999999 1e-20 1e-300; do
    hp refused --set adapt%sigma=$sigma
    check "sigma = $sigma: exit 2, one line naming &adapt sigma and the range" \
        "[[ \$rc -eq 2 && \$(wc -l <refused.err) -eq 1 ]] && grep -q '&adapt: sigma = .*: expected a grading factor with 0.01 <= sigma <= 0.5' refused.err"
done
echo "      $(cat refused.err)"

hp floor --set adapt%sigma=0.01 --set adapt%tolerance=1e-14
echo "      $(head -c 300 floor.err)"
check 'sigma = 0.01 to 1e-14: exit 8 at the resolution of binary64, the last level written' \
    "[[ \$rc -eq 8 ]] && grep -q 'below what binary64 resolves of the coordinates' floor.err && [[ -s floor/summary.json ]]"

if ! command -v gmsh >/dev/null 2>&1; then
    echo "SKIP  a Gmsh mesh with a 1e-6 edge: gmsh is not installed"
    cli_end
fi
# The unit square, contact on [0, 0.5] of the bottom, a free part from 0.5 to 0.500001
# (the short edge) and on to 1.
cat >short.geo <<'GEO'
Point(1) = {0, 0, 0, 0.25}; Point(2) = {0.5, 0, 0, 0.25}; Point(3) = {0.500001, 0, 0, 0.25};
Point(4) = {1, 0, 0, 0.25}; Point(5) = {1, 1, 0, 0.25}; Point(6) = {0, 1, 0, 0.25};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Plane Surface(1) = {1};
Physical Curve("bottom") = {1}; Physical Curve("gap") = {2, 3}; Physical Curve("right") = {4};
Physical Curve("top") = {5}; Physical Curve("left") = {6}; Physical Surface("body") = {1};
GEO
gmsh -2 -format msh22 short.geo -o short.msh >/dev/null 2>&1
mesh="--set mesh%source=gmsh --set mesh%file=$work/short.msh --set mesh%dirichlet=top"
# shellcheck disable=SC2086
hp short --set adapt%max_levels=2 $mesh --set "mesh%neumann=left right gap"
echo "      $(head -c 300 short.err)"
check 'a 1e-6 edge, max_levels = 2: ends (exit 8 at the limit), the last level written' \
    "[[ \$rc -eq 8 ]] && grep -q 'max_levels = 2 reached' short.err && [[ -s short/summary.json ]]"
# shellcheck disable=SC2086
hp short_dofs --set adapt%max_dofs=20 $mesh --set "mesh%neumann=left right gap"
echo "      $(head -c 300 short_dofs.err)"
check 'a 1e-6 edge, max_dofs = 20: refused before the first level (exit 2, one line)' \
    "[[ \$rc -eq 2 && \$(wc -l <short_dofs.err) -eq 1 ]] && grep -q 'max_dofs = 20' short_dofs.err"

cli_end
