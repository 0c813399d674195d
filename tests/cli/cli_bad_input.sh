#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The bad-input catalogue of docs/outputs.md: every namelist variable out of range, unknown
# groups and variables, wrong types, unknown names, a side used twice, no Dirichlet boundary,
# a missing, unreadable, truncated or garbage input file; a missing, directory, truncated,
# garbage or binary mesh file, unknown physical groups, a bent contact group; an output
# directory that cannot be written. Each must give exactly one line on stderr naming the
# place (file, group and variable, or file and line) and what was expected, a non-zero
# exit, and leave no output.
# Usage: cli_bad_input.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source_dir=$2
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_bad_input
out="$work/out"

# run_bad NAME FILE WORD...: run on FILE; one stderr line containing every WORD (fixed
# strings), exit status non-zero, nothing written under $out.
run_bad() {
    local name=$1 file=$2
    shift 2
    rm -rf "$out"
    "$nceig" "$file" >"$work/stdout" 2>"$work/err"
    local rc=$?
    local ok=1
    [[ $rc -ne 0 ]] || ok=0
    [[ $(wc -l <"$work/err") -eq 1 ]] || ok=0
    for word in "$@"; do grep -q -F -- "$word" "$work/err" || ok=0; done
    [[ ! -e "$out" ]] || ok=0
    check "$name" '[[ $ok -eq 1 ]]'
    if [[ $ok -eq 1 ]]; then echo "PASS  $name: $(cat "$work/err")"; else
        echo "      rc=$rc stderr: $(head -c 400 "$work/err")"; fi
}

# bad NAME 'namelist text' WORD...: the text plus an &output group pointing at $out.
bad() {
    local name=$1 text=$2
    shift 2
    printf '%s\n&output directory = '"'%s'"' /\n' "$text" "$out" >"$work/bad.nml"
    run_bad "$name" "$work/bad.nml" bad.nml "$@"
}

# --- every variable out of range (the message names the group and the variable)
bad 'mesh source' "&mesh source = 'disk' /" '&mesh' source 'rectangle'
bad 'mesh gmsh without file' "&mesh source = 'gmsh' /" '&mesh' file
bad 'mesh width 0' "&mesh width = 0 /" '&mesh' width '> 0'
bad 'mesh width < 0' "&mesh width = -1 /" '&mesh' width
bad 'mesh width NaN' "&mesh width = NaN /" '&mesh' width finite
bad 'mesh height inf' "&mesh height = Inf /" '&mesh' height finite
bad 'mesh nx 0' "&mesh nx = 0 /" '&mesh' nx
bad 'mesh nx huge' "&mesh nx = 2000000 /" '&mesh' nx
bad 'mesh ny < 0' "&mesh ny = -3 /" '&mesh' ny
bad 'mesh element' "&mesh element = 'p7' /" '&mesh' element "'q2'"
bad 'mesh diagonal' "&mesh diagonal = 'up' /" '&mesh' diagonal "'left'"
bad 'mesh dirichlet unknown side' "&mesh dirichlet = 'front' /" '&mesh' dirichlet front
bad 'mesh neumann unknown side' "&mesh neumann = 'left back' /" '&mesh' neumann back
bad 'mesh contact unknown side' "&mesh contact = 'under' /" '&mesh' contact under
bad 'mesh contact two sides' "&mesh contact = 'bottom left', neumann = 'right' /" '&mesh' contact 'exactly one'
bad 'mesh contact empty' "&mesh contact = '' /" '&mesh' contact
bad 'no Dirichlet boundary' "&mesh dirichlet = '', neumann = 'left right top' /" '&mesh' dirichlet Dirichlet
bad 'side twice in one list' "&mesh dirichlet = 'top top' /" '&mesh' dirichlet twice
bad 'side in two lists' "&mesh neumann = 'left right top' /" '&mesh' neumann top
bad 'contact also fixed' "&mesh dirichlet = 'top bottom' /" '&mesh' contact bottom
bad 'material young 0' "&material young = 0 /" '&material' young
bad 'material young < 0' "&material young = -2e9 /" '&material' young
bad 'material young NaN' "&material young = NaN /" '&material' young
bad 'material poisson 0.5' "&material poisson = 0.5 /" '&material' poisson
bad 'material poisson -1' "&material poisson = -1 /" '&material' poisson
bad 'analysis kind' "&analysis kind = 'modal' /" '&analysis' kind "'eigen'"
bad 'analysis lambda inf' "&analysis lambda = -Inf /" '&analysis' lambda finite
bad 'eigen solver' "&eigen solver = 'qr' /" '&eigen' solver "'dense'"
bad 'eigen nev 0' "&eigen nev = 0 /" '&eigen' nev
bad 'eigen target NaN' "&eigen target = NaN /" '&eigen' target
bad 'eigen tol < 0' "&eigen tol = -1e-3 /" '&eigen' tol
bad 'eigen maxit 0' "&eigen maxit = 0 /" '&eigen' maxit
bad 'eigen ncv too small' "&eigen nev = 6, ncv = 7 /" '&eigen' ncv
bad 'eigen dense_max_contact 0' "&eigen dense_max_contact = 0 /" '&eigen' dense_max_contact
bad 'eigen operator unknown' "&eigen operator = 'whole' /" '&eigen' operator "'full'"
bad 'eigen operator full with dense' "&eigen operator = 'full', solver = 'dense' /" '&eigen' operator dense
bad 'eigen cn_max < 0' "&eigen cn_max = -1 /" '&eigen' cn_max '>= 0'
bad 'eigen cn_max NaN' "&eigen cn_max = NaN /" '&eigen' cn_max finite
# 'solve' works in the input's units: loads within young's range, displacements within the
# size's (u_d1 = 1e300 overflowed the Newton merit: SIGFPE in Debug)
bad 'solve u_d1 1e300' "&analysis kind = 'solve' /
&solve u_d1 = 1e300 /" '&solve' u_d1 '1e50'
bad 'solve t2 -1e101' "&analysis kind = 'solve' /
&solve t2 = -1e101 /" '&solve' t2 '1e100'
bad 'solve c_n 1e-101' "&analysis kind = 'solve' /
&solve c_n = 1e-101 /" '&solve' c_n '1e-100 to 1e100'
# the &output groups carry the directory themselves
bad_output() {
    local name=$1 text=$2
    shift 2
    printf '&output directory = '"'%s'"', %s /\n' "$out" "$text" >"$work/bad.nml"
    run_bad "$name" "$work/bad.nml" bad.nml "$@"
}
bad_output 'output modes < 0' "modes = -1" '&output' modes
bad_output 'unknown vtk_format' "vtk_format = 'xml'" '&output' vtk_format "'binary'"

# --- unknown groups and variables
bad 'unknown group' "&meshh nx = 3 /" meshh 'known groups'
bad 'group twice' "&mesh nx = 3 /
&mesh ny = 3 /" '&mesh' twice
bad_output 'unknown variable in &output' "bogus = 1" '&output' bogus 'knows'
for group in mesh material analysis eigen; do
    bad "unknown variable in &$group" "&$group bogus = 1 /" "&$group" bogus 'knows'
done

# --- wrong types
bad 'integer given a word' "&mesh nx = many /" '&mesh' nx 'expected an integer'
bad 'integer given a real' "&mesh ny = 2.5 /" '&mesh' ny 'expected an integer'
bad 'real given a word' "&material young = steel /" '&material' young 'expected a real'
bad 'real given a logical' "&analysis lambda = .true. /" '&analysis' lambda 'expected a real'
bad_output 'logical given a number' "vtk = 7" '&output' vtk 'expected .true.'
bad 'integer given a string' "&eigen nev = 'six' /" '&eigen' nev 'expected an integer'

# --- the input file itself
run_bad 'missing input file' "$work/none.nml" none.nml
mkdir -p "$work/folder.nml"
run_bad 'a directory as input file' "$work/folder.nml" folder.nml directory
printf "&mesh nx = 4, ny = 4\n&output directory = '%s'" "$out" >"$work/truncated.nml"
run_bad 'truncated namelist (no closing /)' "$work/truncated.nml" truncated.nml '&mesh'
printf "&mesh nx = 4, ny = 4, element = 'q" >"$work/cut.nml"
run_bad 'truncated inside a string' "$work/cut.nml" cut.nml '&mesh'
# 3000 pseudo-random bytes, the same every run, without '&', '$' and '/' so that no group
# can appear in them by accident
LC_ALL=C awk 'BEGIN { srand(8); for (i = 0; i < 3000; i++) printf "%c", 1 + int(rand() * 255) }' \
    | LC_ALL=C tr -d '&$/' >"$work/garbage2.nml"
run_bad 'garbage bytes' "$work/garbage2.nml" garbage2.nml 'outside any namelist group'
printf 'nx = 4\n' >"$work/nogroup.nml"
run_bad 'text outside any group' "$work/nogroup.nml" nogroup.nml 'line 1'
if [[ $(id -u) -ne 0 ]]; then
    printf '&mesh /\n' >"$work/locked.nml"
    chmod 000 "$work/locked.nml"
    run_bad 'unreadable input file' "$work/locked.nml" locked.nml
else
    echo "SKIP  unreadable input file: running as root, whom chmod 000 does not stop" \
         "(the directory case above covers an open that fails)"
fi

# --- bad mesh files (source = 'gmsh'): the message names the mesh file, and its line where
# one applies (gmsh_bad NAME MESH 'dirichlet neumann contact' WORD...)
meshes="$source_dir/input/meshes"
gmsh_bad() {
    local name=$1 mesh=$2 groups=$3
    shift 3
    read -r dirichlet neumann contact <<<"$groups"
    [[ $neumann != - ]] || neumann=''
    printf "&mesh source = 'gmsh', file = '%s', dirichlet = '%s', neumann = '%s', " \
        "$mesh" "$dirichlet" "$neumann" >"$work/mesh.nml"
    printf "contact = '%s' /\n&output directory = '%s' /\n" "$contact" "$out" >>"$work/mesh.nml"
    run_bad "$name" "$work/mesh.nml" "$@"
    # Quoted file content must not reach the terminal raw (binary bytes, escapes).
    check "$name: stderr is printable ASCII" '! LC_ALL=C grep -q "[^[:print:]]" "$work/err"'
}
groups='fixed traction contact'   # the groups of single_element.msh
cp "$meshes/single_element.msh" "$work/good.msh"
readable='expected a readable Gmsh .msh file'
gmsh_bad 'mesh file missing' "$work/none.msh" "$groups" none.msh 'cannot open' "$readable"
mkdir -p "$work/folder.msh"
gmsh_bad 'mesh file is a directory' "$work/folder.msh" "$groups" folder.msh directory "$readable"
# Cut in the middle of $Nodes: the header's count no longer fits (reported at its line).
head -n 200 "$meshes/square_16.msh" >"$work/cut.msh"
nodes_line=$(($(grep -n '^\$Nodes' "$work/cut.msh" | cut -d: -f1) + 1))
gmsh_bad 'mesh file truncated in $Nodes' "$work/cut.msh" 'top left bottom' \
    "cut.msh:$nodes_line: " truncated expected
# Cut after the last element: the end marker is missing.
grep -v '^\$EndElements' "$meshes/single_element.msh" >"$work/noend.msh"
gmsh_bad 'mesh file truncated before $EndElements' "$work/noend.msh" "$groups" \
    "noend.msh:$(wc -l <"$work/noend.msh"): unexpected end of file (truncated?)" \
    'expected $EndElements'
# 3000 pseudo-random bytes, the same every run
LC_ALL=C awk 'BEGIN { srand(9); for (i = 0; i < 3000; i++) printf "%c", int(rand() * 256) }' \
    >"$work/garbage.msh"
gmsh_bad 'garbage mesh file' "$work/garbage.msh" "$groups" 'garbage.msh:' \
    'not a Gmsh mesh file: expected $MeshFormat'
sed 's/^4\.1 0 8$/4.1 1 8/' "$meshes/single_element.msh" >"$work/binary.msh"
gmsh_bad 'binary MSH file' "$work/binary.msh" "$groups" \
    'binary.msh:2: binary MSH files are not supported' '-format msh41'
gmsh_bad 'unknown group in dirichlet' "$work/good.msh" 'fixd traction contact' \
    mesh.nml '&mesh' dirichlet \
    "good.msh has no 1D physical group 'fixd' (it has: contact, fixed, traction)"
gmsh_bad 'unknown group in neumann' "$work/good.msh" 'fixed side contact' \
    mesh.nml '&mesh' neumann \
    "no 1D physical group 'side' (it has: contact, fixed, traction)"
gmsh_bad 'unknown group in contact' "$work/good.msh" 'fixed traction gap' \
    mesh.nml '&mesh' contact \
    "no 1D physical group 'gap' (it has: contact, fixed, traction)"
# Curve 2 ([B, C], line 38) moved from group 'fixed' (2) into group 'contact' (1): a bent
# contact boundary, reported at the line of the edge that leaves the first edge's line.
sed 's/^2 0 0 0 2 2 0 1 2 2 2 -3$/2 0 0 0 2 2 0 1 1 2 2 -3/' "$meshes/single_element.msh" \
    >"$work/bent.msh"
bent_line=$(grep -n '^2 2 3$' "$work/bent.msh" | cut -d: -f1)
gmsh_bad 'contact group not straight' "$work/bent.msh" 'traction - contact' \
    "bent.msh:$bent_line: contact boundary 'contact' is not one straight segment" \
    'expected one straight segment'

# --- an output directory that cannot be written: a path under a regular file
printf 'x\n' >"$work/plain"
printf "&mesh nx = 2, ny = 2 /\n&output directory = '%s/sub' /\n" "$work/plain" >"$work/io.nml"
rm -rf "$out"
"$nceig" "$work/io.nml" >/dev/null 2>"$work/err"; rc=$?
check 'output under a regular file: non-zero exit, one line naming it' \
    '[[ $rc -ne 0 && $(wc -l <"$work/err") -eq 1 ]] && grep -q -F "$work/plain/sub" "$work/err"'
echo "      $(cat "$work/err")"
check 'output under a regular file: the file is untouched' '[[ $(cat "$work/plain") == x ]]'

cli_end
