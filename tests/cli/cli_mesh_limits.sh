#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Meshes nceig must refuse with one line naming the input (or mesh file and line), fast and
# without a backtrace: a grid whose dof count overflows default integers (nx = ny = 46341);
# thin strips whose dense contact blocks exceed the machine's memory (nx = 200000 and
# 1000000, ny = 1: refused before allocating, with the estimate); a Gmsh mesh cut in two by a crack
# (duplicated nodes along x = 0.5), which used to end in an internal Cholesky message; and,
# under ulimit -v, an allocation that fails after the estimate passed (exit 5, one line),
# and a limit too small for the BLAS's buffers, which hung (exit 5 at once).
# Usage: cli_mesh_limits.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_mesh_limits
cd "$work"
# No wall-clock bound is asserted (a loaded machine exceeds any): the refusals come from
# estimates made before any large allocation, which the messages show. `timeout` only stops
# a run that hangs, so that CI cannot stall; the seconds are printed for the reader.
HANG=600
sanitized=0
if ldd "$nceig" 2>/dev/null | grep -q libasan; then sanitized=1; fi

# refused NAME STATUS WORD...: the last run ($rc, err) ended with STATUS, one stderr line
# containing every WORD, and no output directory.
refused() {
    local name=$1 status=$2 ok=1
    shift 2
    [[ $rc -eq $status ]] || ok=0
    [[ $(wc -l <err) -eq 1 ]] || ok=0
    for word in "$@"; do grep -q -F -- "$word" err || ok=0; done
    [[ ! -e out ]] || ok=0
    check "$name" '[[ $ok -eq 1 ]]'
    echo "      rc=$rc ${seconds}s: $(head -c 400 err)"
}

# run TEXT: the &mesh body TEXT, run nceig on it; sets rc and seconds.
run() {
    printf '&mesh %s /\n&output directory = "out" /\n' "$1" >in.nml
    rm -rf out
    SECONDS=0
    timeout $HANG "$nceig" in.nml >stdout 2>err
    rc=$?
    seconds=$SECONDS
}

run "nx = 46341, ny = 46341"
refused 'nx = ny = 46341: the input file, &mesh, nx and ny and the limit' 2 \
    'in.nml: &mesh: nx = 46341, ny = 46341' '(nx + 1) (ny + 1) <= 1073741823'

run "nx = 200000, ny = 1"
refused 'thin strip nx = 200000: refused with the memory estimate' 2 \
    'in.nml: &mesh: nx = 200000, ny = 1' 'p = 200001' '(8 p x p doubles) need an estimated 2560.0 GB' 'MemAvailable'

run "nx = 1000000, ny = 1"
refused 'nx = 1000000, ny = 1 (the largest documented): refused before allocating' 2 \
    'in.nml: &mesh: nx = 1000000, ny = 1' 'estimated 64000.1 GB'

# msh_header: the start of an MSH 2.2 file with the four sides as physical groups
msh_header() {
    cat <<'MSH'
$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
4
1 1 "bottom"
1 2 "right"
1 3 "top"
1 4 "left"
$EndPhysicalNames
MSH
}

# Two unit-height quadrangles side by side whose common side is two pairs of nodes (3, 7 at
# x = 0.5): each half is held by the top, but the body is two pieces.
{ msh_header; cat <<'MSH'; } >crack.msh
$Nodes
8
1 0 0 0
2 0.5 0 0
3 0.5 1 0
4 0 1 0
5 0.5 0 0
6 1 0 0
7 0.5 1 0
8 1 1 0
$EndNodes
$Elements
8
1 1 2 1 1 1 2
2 1 2 1 1 5 6
3 1 2 2 2 6 8
4 1 2 3 3 8 7
5 1 2 3 3 3 4
6 1 2 4 4 4 1
7 3 2 5 1 1 2 3 4
8 3 2 5 1 5 6 8 7
$EndElements
MSH
run "source = 'gmsh', file = 'crack.msh'"
refused 'a crack (duplicated nodes): the mesh file, the line, not connected' 3 \
    'crack.msh:31: the mesh is not connected: it falls into 2 pieces'

# A sliver: node 5 lies 1e-13 off the diagonal 1-3, so cell 1 5 3 has an area of 5e-14 (above
# the degenerate bound, 64 eps x diameter^2) but makes K numerically singular. The message
# blamed a missing Dirichlet boundary; it names the cell.
{ msh_header; cat <<'MSH'; } >sliver.msh
$Nodes
5
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0.5 0.4999999999999 0
$EndNodes
$Elements
8
1 1 2 1 1 1 2
2 1 2 2 2 2 3
3 1 2 3 3 3 4
4 1 2 4 4 4 1
5 2 2 5 1 1 2 5
6 2 2 5 1 2 3 5
7 2 2 5 1 1 5 3
8 2 2 5 1 1 3 4
$EndElements
MSH
run "source = 'gmsh', file = 'sliver.msh'"
refused 'a sliver cell: K singular, the cell named, not the Dirichlet boundary' 6 \
    'in.nml: &mesh: the stiffness matrix K is singular, likely from a sliver' \
    'the cell at sliver.msh:27 has |det J| = 5.00E-14'

# An allocation failure after the estimate passed (here: a 700 MB address space) is one
# line and exit status 5, not a backtrace.
# AddressSanitizer reserves terabytes of address space at start: under ulimit -v a sanitized
# nceig cannot even start, so that build skips this one case.
if [[ $sanitized -eq 1 ]]; then
    echo "SKIP  out of memory under ulimit -v: a sanitizer build cannot run under ulimit -v"
else
    printf '&mesh nx = 5000, ny = 1 /\n&output directory = "out" /\n' >in.nml
    rm -rf out
    SECONDS=0
    (ulimit -v 700000 && exec timeout $HANG "$nceig" in.nml) >stdout 2>err
    rc=$?
    seconds=$SECONDS
    refused 'out of memory under ulimit -v: one line, exit status 5' 5 'out of memory'

    # An address space too small for OpenBLAS's 128 MiB buffer: OpenBLAS retried its mmap
    # for ever inside CHOLMOD (and its shutdown then joined a thread stuck so). timeout: a
    # regression must fail this check, not hang the suite.
    printf '&mesh nx = 64, ny = 64 /\n&output directory = "out" /\n' >in.nml
    rm -rf out
    SECONDS=0
    (ulimit -v 100000 && exec timeout 60 "$nceig" in.nml) >stdout 2>err
    rc=$?
    seconds=$SECONDS
    refused 'ulimit -v 100000: refused before OpenBLAS, exit status 5' 5 'ulimit -v' \
        'in.nml'
fi

cli_end
