#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Gmsh meshes end to end: scripts/make_mesh.sh (Delaunay, order 1 to 4, MSH 4.1 and 2.2),
# structured grids meshed by Gmsh (transfinite) against the rectangle generator for P1, Q1,
# P2, Q2, P3, P4, the shipped inputs delaunay.nml and single_element.nml, and a bad mesh file on the
# command line. Usage: cli_gmsh.sh NCEIG SOURCE_DIR. Without gmsh: one SKIP line, pass.
set -u
nceig=$1
source_dir=$2
source "$(dirname "$0")/lib/cli_common.sh"
if ! command -v gmsh >/dev/null 2>&1; then
    cli_skip cli_gmsh 'gmsh is not installed: the Gmsh end-to-end checks did not run'
fi
cli_begin cli_gmsh
cd "$work"

run() {  # name, mesh text (the &mesh body); writes out_<name>/summary.json, <name>.log
          # (stdout: progress and summary) and <name>.err (stderr: the one error line)
    # ascii VTU: the cell-type check below greps its text.
    printf '&mesh %s /\n&output directory = "out_%s", vtk = .true., vtk_format = "ascii" /\n' \
        "$2" "$1" >"$1.nml"
    "$nceig" "$1.nml" >"$1.log" 2>"$1.err"
}

# Delaunay meshes from the shipped script, both orders and both formats.
for order in 1 2 3 4; do
    for format in msh41 msh22; do
        name=d${order}_$format
        bash "$source_dir/scripts/make_mesh.sh" 8 "$order" "$name.msh" "$format"
        check "make_mesh.sh 8 $order $format writes a mesh" '[[ -s $name.msh ]]'
        run "$name" "source = 'gmsh', file = '$name.msh'"; rc=$?
        check "nceig runs on the $format order-$order Delaunay mesh" '[[ $rc -eq 0 && -s out_$name/summary.json ]]'
    done
    check "order $order: element from the file" '[[ $(json out_d${order}_msh41/summary.json element) == p$order ]]'
    check "order $order: a positive mu" '[[ $(json out_d${order}_msh41/summary.json lowest_positive_mu) != null ]]'
    # The same mesh in both formats: identical results.
    check "order $order: MSH 2.2 and 4.1 give the identical lowest mu" \
        '[[ $(json out_d${order}_msh41/summary.json lowest_positive_mu) == $(json out_d${order}_msh22/summary.json lowest_positive_mu) ]]'
    # VTK cell types: triangle 5, quadratic triangle 22, Lagrange triangle 69.
    case $order in 1) vtk_type=5 ;; 2) vtk_type=22 ;; *) vtk_type=69 ;; esac
    check "order $order: VTU cell type $vtk_type" \
        'grep -q "^ *$vtk_type\( \|$\)" out_d${order}_msh41/mode_001.vtu'
done
bash "$source_dir/scripts/make_mesh.sh" 8 5 x.msh 2>/dev/null; rc=$?
check 'make_mesh.sh rejects order 5' '[[ $rc -ne 0 ]]'
bash "$source_dir/scripts/make_mesh.sh" 2>/dev/null; rc=$?
check 'make_mesh.sh without arguments: usage error' '[[ $rc -eq 2 ]]'

# Structured 6 x 6 grids of the unit square meshed by Gmsh (transfinite; 'Right' splits each
# square from lower-left to upper-right as diagonal = 'right' does) against the generator.
# Gmsh places the inner grid nodes to ~1e-12, so the eigenvalues agree to ~1e-11; 1e-8
# still separates them from any other mesh of this size (which differ by 1e-3 or more).
for element in p1 q1 p2 q2 p3 p4; do
    case $element in p*) recombine='' ;; *) recombine='Recombine Surface{1};' ;; esac
    order=${element#?}
    cat >grid.geo <<GEO
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 7;
Transfinite Surface{1} = {1, 2, 3, 4} Right;
$recombine
Physical Curve("bottom") = {1}; Physical Curve("right") = {2};
Physical Curve("top") = {3}; Physical Curve("left") = {4}; Physical Surface("body") = {1};
GEO
    gmsh grid.geo -2 -order "$order" -format msh41 -o "grid_$element.msh" >/dev/null 2>&1
    run "g_$element" "source = 'gmsh', file = 'grid_$element.msh'"
    run "r_$element" "source = 'rectangle', nx = 6, ny = 6, element = '$element'"
    a=$(json "out_g_$element/summary.json" lowest_positive_mu)
    b=$(json "out_r_$element/summary.json" lowest_positive_mu)
    check "Gmsh transfinite $element grid = rectangle generator ($a vs $b)" 'close "$a" "$b" 1e-8'
    check "Gmsh $element grid: same node count" \
        '[[ $(json out_g_$element/summary.json n_nodes) == $(json out_r_$element/summary.json n_nodes) ]]'
done

# The shipped inputs.
mkdir -p shipped && cd shipped
"$nceig" "$source_dir/input/delaunay.nml" >log 2>&1; rc=$?
check 'input/delaunay.nml runs' '[[ $rc -eq 0 && -s output/delaunay/summary.json ]]'
"$nceig" "$source_dir/input/single_element.nml" >log 2>&1
# model.md section 8 with l = 2, lambda = -5, L = 15/26, G = 5/13: mu = 105/208.
check 'input/single_element.nml gives 105/208' \
    'close "$(json output/single_element/summary.json lowest_positive_mu)" 0.50480769230769230 1e-13'
cd "$work"

# A bad mesh file on the command line: exit status 3, one line naming the file and line.
printf '$MeshFormat\n4.1 1 8\n$EndMeshFormat\n' >binary.msh
run bad "source = 'gmsh', file = 'binary.msh'"
rc=$?
check 'binary mesh: exit status 3' '[[ $rc -eq 3 ]]'
check 'binary mesh: one line with file:line and the advice' \
    '[[ $(wc -l <bad.err) -eq 1 ]] && grep -q "binary.msh:2: binary MSH files are not supported; write ASCII with gmsh -format msh41" bad.err'
check 'binary mesh: no output folder' '[[ ! -e out_bad ]]'

cli_end
