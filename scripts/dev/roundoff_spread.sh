#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The round-off error of the lowest positive mu, measured, against its bound (summary.json
# lowest_positive_roundoff): the same discrete problem solved in different roundings, whose
# spread is the error round-off makes. Variants: young E in {1, 3.7, 0.61} and the size
# scaled by s in {1, 1.37} (mu scales exactly like E / s: the values compared are mu s / E),
# the dense and the ARPACK solver, and ARPACK on the full operator. A Gmsh mesh is written
# here scaled by s (and moved off the origin) from the generator SCENE names.
# Usage: scripts/dev/roundoff_spread.sh NCEIG NAME 'MESH' 'MATERIAL' LAMBDA
#   MESH: the &mesh body with the size left out (rectangle: width and height are set to s;
#   'sliver DELTA N': an N x N Gmsh triangle mesh of the unit square with one cell on the
#   contact side split around a node DELTA (relative) off its diagonal: a sliver;
#   'gmsh FILE': the Gmsh mesh FILE (an adaptive run's mesh.msh, parts bottom/right/top/left)
#   with its nodes scaled by s and moved by 0.37).
# ROUNDOFF_EXTRA: more namelist groups for every run (e.g. "&adapt strategy = 'hp',
# tolerance = 1e-15, max_levels = 8 /": one hp level, whose last level is compared).
# Prints: NAME, mu, spread (max - min) / |mu| over the variants, the largest bound, the
# ratio, and the median time_roundoff_s and time_eigen_s of the base run.
set -u
nceig=$1 name=$2 mesh=$3 material=$4 lambda=$5
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# sliver_mesh DELTA N S FILE: the Gmsh 2.2 mesh described above, coordinates x S + 0.37
sliver_mesh() {
    awk -v delta="$1" -v n="$2" -v s="$3" 'BEGIN {
        h = 1.0 / n; sc = int(n / 2)
        print "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n5"
        print "1 1 \"bottom\"\n1 2 \"right\"\n1 3 \"top\"\n1 4 \"left\"\n2 5 \"body\"\n$EndPhysicalNames"
        nn = (n + 1) * (n + 1) + 1
        print "$Nodes\n" nn
        for (j = 0; j <= n; j++) for (i = 0; i <= n; i++)
            printf "%d %.17g %.17g 0\n", j * (n + 1) + i + 1, i * h * s + 0.37, j * h * s + 0.37
        # the extra node in cell (sc, 0), delta h off its diagonal
        printf "%d %.17g %.17g 0\n", nn, (sc + 0.5) * h * s + 0.37, (0.5 - delta) * h * s + 0.37
        ne = 0
        for (i = 0; i < n; i++) { e[++ne] = "1 2 1 1 " (i + 1) " " (i + 2) }
        for (j = 0; j < n; j++) { e[++ne] = "1 2 2 2 " (j * (n + 1) + n + 1) " " ((j + 1) * (n + 1) + n + 1) }
        for (i = n; i > 0; i--) { e[++ne] = "1 2 3 3 " (n * (n + 1) + i + 1) " " (n * (n + 1) + i) }
        for (j = n; j > 0; j--) { e[++ne] = "1 2 4 4 " (j * (n + 1) + 1) " " ((j - 1) * (n + 1) + 1) }
        for (j = 0; j < n; j++) for (i = 0; i < n; i++) {
            a = j * (n + 1) + i + 1; b = a + 1; c = a + n + 2; d = a + n + 1
            if (i == sc && j == 0) {
                e[++ne] = "2 2 5 5 " a " " b " " nn; e[++ne] = "2 2 5 5 " b " " c " " nn
                e[++ne] = "2 2 5 5 " a " " nn " " c; e[++ne] = "2 2 5 5 " a " " c " " d
            } else {
                e[++ne] = "2 2 5 5 " a " " b " " c; e[++ne] = "2 2 5 5 " a " " c " " d
            }
        }
        print "$EndNodes\n$Elements\n" ne
        for (k = 1; k <= ne; k++) print k, e[k]
        print "$EndElements" }' >"$4"
}

# scaled_msh IN S OUT: the MSH 4.1 file IN with x, y of its nodes mapped to x S + 0.37
scaled_msh() {
    awk -v s="$2" '/^\$Nodes/ { inside = 1 } /^\$EndNodes/ { inside = 0 }
        inside && NF == 3 && $1 ~ /[.eE]/ { printf "%.17g %.17g %s\n", $1 * s + 0.37, $2 * s + 0.37, $3; next }
        { print }' "$1" >"$3"
}

run() {  # SOLVER OPERATOR E S: one run; prints mu s / E, the bound, the two times
    local body=$mesh
    if [[ $mesh == gmsh* ]]; then
        read -r _ file <<<"$mesh"
        scaled_msh "$file" "$4" "$work/m_$4.msh"
        body="source = 'gmsh', file = '$work/m_$4.msh', dirichlet = 'top', neumann = 'left right', contact = 'bottom'"
    elif [[ $mesh == sliver* ]]; then
        read -r _ delta n <<<"$mesh"
        sliver_mesh "$delta" "$n" "$4" "$work/m_$4.msh"
        body="source = 'gmsh', file = '$work/m_$4.msh', dirichlet = 'top', neumann = 'left right', contact = 'bottom'"
    else
        body="$mesh, width = $4, height = $4"
    fi
    printf '%s\n' "&mesh $body /" "&material young = $3, $material /" \
        "&analysis kind = 'eigen', lambda = $lambda /" \
        "&eigen solver = '$1', operator = '$2', estimate = 'off' /" \
        "&output directory = '$work/out', vtk = .false., plot = .false. /" \
        ${ROUNDOFF_EXTRA:+"$ROUNDOFF_EXTRA"} >"$work/in.nml"
    rm -rf "$work/out"
    "$nceig" "$work/in.nml" >"$work/stdout" 2>&1
    local j=$work/out/summary.json
    get() { sed -n "s/^ *\"$1\": *\([^,]*\),*$/\1/p" "$j" | head -n 1; }
    awk -v mu="$(get lowest_positive_mu)" -v e="$3" -v s="$4" -v b="$(get lowest_positive_roundoff)" \
        -v tr="$(get time_roundoff_s)" -v te="$(get time_eigen_s)" \
        'BEGIN { printf "%.17g %s %s %s\n", mu * s / e, b, tr, te }'
}

{
    for solver in dense arpack; do
        for e in 1 3.7 0.61; do
            for s in 1 1.37; do run $solver reduced $e $s; done
        done
    done
    run arpack full 1 1
} >"$work/rows"
[[ -n ${ROUNDOFF_ROWS:-} ]] && cat "$work/rows" >&2
awk -v name="$name" '{ v[NR] = $1; if ($2 + 0 > b) b = $2 + 0; if (NR == 1) { tr = $3; te = $4 } }
    END { lo = v[1]; hi = v[1]; for (i in v) { if (v[i] < lo) lo = v[i]; if (v[i] > hi) hi = v[i] }
          spread = (hi - lo) / (v[1] < 0 ? -v[1] : v[1])
          printf "%-28s mu %.15g  spread %.2e  bound %.2e  bound/spread %.3g  roundoff %ss of eigen %ss\n",
                 name, v[1], spread, b, (spread > 0 ? b / spread : 0), tr, te }' "$work/rows"
