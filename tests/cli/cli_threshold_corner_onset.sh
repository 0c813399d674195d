#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# An hp threshold run whose lambda+ side is a collision onset next to a corner
# (tests/data/bodies/corner_onset.geo, body 28 of random_bodies.sh -s 35 -n 29): the mode of
# lambda+ gathers at the 86.3-degree free end of Gamma_C, just past that corner's crossing,
# where uniform P4 meshes up to L/64 settle on a wrong onset (1.582031; L/128 gives
# 1.5818325). The independent values: Lagrange P4 on Gmsh meshes graded to every corner (size
# 0.15 r, at least 1e-4 and 1e-6: onsets 1.5818069841 and 1.5818071667, pencil values
# 1.5820956885 and 1.5820957596), the finer one taken as the truth within 1e-8 (the grading
# from 1e-4 to 1e-6 moved it by 1.8e-7; hp from start meshes of size L/2, L/4, L/8 lies within
# 2.6e-9 of it). The run's bars must cover them. Usage: cli_threshold_corner_onset.sh NCEIG
# SOURCE_DIR. Without gmsh: one SKIP line, pass.
set -u
nceig=$1
source_dir=$2
source "$(dirname "$0")/lib/cli_common.sh"
if ! command -v gmsh >/dev/null 2>&1; then
    cli_skip cli_threshold_corner_onset 'gmsh is not installed: the corner onset did not run'
fi
cli_begin cli_threshold_corner_onset
cd "$work"

# the start mesh of the validation's hp runs: P1, size L/2 (L = 1.97772, the largest extent)
gmsh "$source_dir/tests/data/bodies/corner_onset.geo" -2 -order 1 -clmax 0.98886 \
    -format msh41 -o start.msh >gmsh.log 2>&1
check 'gmsh meshes corner_onset.geo at size L/2, P1' '[[ -s start.msh ]]'
cat >body.nml <<NML
&mesh source = 'gmsh', file = 'start.msh', dirichlet = 'clamped', neumann = 'free',
      contact = 'contact' /
&material poisson = 0.414 /
&analysis kind = 'threshold', lambda = -3.0633 /
&eigen estimate = 'off' /
&adapt strategy = 'hp', tolerance = 1e-5, max_levels = 10 /
&output directory = 'hp', vtk = .false., plot = .false. /
NML
"$nceig" body.nml >hp.log 2>hp.err
rc=$?
s=hp/summary.json
check 'hp threshold run: tolerance met (exit 0)' '[[ $rc -eq 0 && ! -s hp.err ]]'
check 'lambda+ side: its onset is a collision of two real mu' \
    '[[ $(json $s lambda_onset_plus_mechanism) == complex_pair ]]'
onset=$(json $s lambda_onset_plus)
# the boundary point's bar (relative) of the onset
bar=$(jq -r '.lambda_onset_plus as $v | [.boundary_lambda, .boundary_error_bar] | transpose
    | map(select(.[0] == $v)) | .[0][1] // "null"' "$s")
check "the onset $onset has a bar ($bar) of at most the tolerance" \
    'awk -v b="$bar" "BEGIN { exit !(b != \"null\" && b > 0 && b <= 1e-5) }"'
check 'its bar covers the graded P4 onset 1.5818071667 (+- 1e-8)' \
    'awk -v v="$onset" -v b="$bar" "BEGIN { d = v - 1.5818071667; if (d < 0) d = -d
        exit !(d <= b * v + 1e-8) }"'
pencil=$(json $s lambda_critical_plus)
pbar=$(json $s lambda_critical_plus_error_bar)
check "the pencil value $pencil (bar $pbar) covers the graded P4 value 1.5820957596" \
    'awk -v v="$pencil" -v b="$pbar" "BEGIN { d = v - 1.5820957596; if (d < 0) d = -d
        exit !(b != \"null\" && d <= b * v + 1e-8) }"'
cli_end
