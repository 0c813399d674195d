#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Delaunay mesh with element size h = 1/N (in the geometry's length unit) of a Gmsh geometry,
# by default the reference scene (input/meshes/square.geo):
#   scripts/make_mesh.sh N ORDER OUTFILE [FORMAT [GEOMETRY.geo]]
# ORDER is 1 (3-node triangles), 2 (6-node), 3 (10-node) or 4 (15-node triangles); FORMAT is
# msh41 (default) or msh22, both ASCII, as nceig reads them. Exit status non-zero, with a message, on any error.
set -euo pipefail
usage='usage: make_mesh.sh N ORDER OUTFILE [msh41|msh22 [GEOMETRY.geo]]'
if [[ $# -lt 3 || $# -gt 5 ]]; then echo "$usage" >&2; exit 2; fi
root=$(cd "$(dirname "$0")/.." && pwd)
n=$1 order=$2 out=$3 format=${4:-msh41} geometry=${5:-$root/input/meshes/square.geo}
[[ $n =~ ^[1-9][0-9]*$ ]] || { echo "make_mesh.sh: N must be a positive integer, got '$n'" >&2; exit 2; }
[[ $order =~ ^[1-4]$ ]] || { echo "make_mesh.sh: ORDER must be 1, 2, 3 or 4, got '$order'" >&2; exit 2; }
[[ $format == msh41 || $format == msh22 ]] || { echo "make_mesh.sh: FORMAT must be msh41 or msh22, got '$format'" >&2; exit 2; }
[[ -f $geometry ]] || { echo "make_mesh.sh: $geometry: no such geometry file" >&2; exit 2; }
command -v gmsh >/dev/null || { echo "make_mesh.sh: gmsh not found (apt-get install gmsh)" >&2; exit 3; }
h=$(awk -v n="$n" 'BEGIN { printf "%.17g", 1 / n }')
log=$(mktemp)
trap 'rm -f "$log"' EXIT
if ! gmsh "$geometry" -2 -order "$order" -clmax "$h" -format "$format" \
        -o "$out" >"$log" 2>&1; then
    cat "$log" >&2
    echo "make_mesh.sh: gmsh failed for N=$n ORDER=$order" >&2
    exit 1
fi
