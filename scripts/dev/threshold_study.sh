#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The measurements of docs/thresholds.md on the bodies of tests/data/bodies (the chamfered
# block, the slanted top, the triangle), each section a table on stdout:
#   uniform   lambda+ and lambda- of Gmsh meshes refined by halving, P2, P3, P4 (nceig)
#   infsup    the pencil's inf-sup constant against the mesh past a corner crossing, and the
#             rate it falls at, beside the corner exponent (pencil_probe --scan)
#   variants  the real pencil value nearest zero per side on hp levels from four start
#             meshes, with nceig's contact forces and the variants of docs/thresholds.md
#             (pencil_probe --level: default, --lower, --half, --half --degrees plus:1)
#   scripts/dev/threshold_study.sh [-b BUILD] [-o OUTDIR] [SECTION...]   (default: all three)
# Builds pencil_probe and wedge_table in BUILD (default build/) when missing; meshes and runs
# go to OUTDIR (default output/threshold_study). A few minutes on two idle cores.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$root/build out=output/threshold_study
while getopts 'b:o:' opt; do
    case $opt in
        b) build=$OPTARG ;; o) out=$OPTARG ;;
        *) echo 'usage: threshold_study.sh [-b BUILD] [-o OUTDIR] [uniform|infsup|variants]...' >&2
           exit 2 ;;
    esac
done
shift $((OPTIND - 1))
sections=${*:-uniform infsup variants}
[[ -x $build/pencil_probe ]] || cmake --build "$build" --target pencil_probe >/dev/null
mkdir -p "$out"
out=$(cd "$out" && pwd)
bodies=$root/tests/data/bodies
probe=$build/pencil_probe

# nml BODY NU MESH: the scene's input (chamfer, slanted: top clamped; triangle: its parts)
nml() {
    local body=$1 nu=$2 mesh=$3 dirichlet=top neumann='left right'
    [[ $body == chamfer ]] && neumann='left right chamfer'
    [[ $body == triangle ]] && dirichlet=clamped neumann=free
    printf "&mesh source = 'gmsh', file = '%s', dirichlet = '%s', neumann = '%s', contact = 'contact' /\n" \
        "$mesh" "$dirichlet" "$neumann"
    printf "&material poisson = %s /\n&analysis kind = 'threshold', lambda = 5.0 /\n" "$nu"
    printf "&adapt tolerance = 1e-8, strategy = 'hp' /\n&eigen estimate = 'off' /\n"
    printf "&output vtk = .false., plot = .false., progress = .false. /\n"
}

# mesh BODY N ORDER: OUT/BODY_N_pORDER.msh (size 1/N)
mesh() {
    local m=$out/${1}_${2}_p$3.msh
    [[ -f $m ]] || bash "$root/scripts/make_mesh.sh" "$2" "$3" "$m" msh41 "$bodies/$1.geo"
    echo "$m"
}

scenes='chamfer:0.1 chamfer:0.2 chamfer:0.3 chamfer:0.45 slanted:0.1 triangle:0.3'

if [[ $sections == *uniform* ]]; then
    echo '| body | nu | element | N = 4 | 8 | 16 | 32 |'
    echo '|---|---|---|---|---|---|---|'
    for scene in $scenes; do
        body=${scene%:*} nu=${scene#*:}
        for order in 2 3 4; do
            for side in plus minus; do
                row="| $body | $nu | P$order lambda_$side"
                for n in 4 8 16 32; do
                    m=$(mesh "$body" "$n" "$order")
                    d=$out/u_${body}_${nu}_${n}_$order
                    if [[ ! -f $d/summary.json ]]; then
                        nml "$body" "$nu" "$m" >"$d.nml"
                        "$build/nceig" "$d.nml" --set adapt%tolerance=0 \
                            --set output%directory="$d" >/dev/null 2>&1 || true
                    fi
                    row="$row | $(jq -r ".lambda_critical_$side // \"none\"" "$d/summary.json" \
                        | awk '$1 == "none" { print; next } { printf "%.9f", $1 }')"
                done
                echo "$row |"
            done
        done
    done
    echo
fi

if [[ $sections == *infsup* ]]; then
    # chamfer, nu = 0.2: lambda < -pi/2 is past the crossing of its 90-degree end (0, 0)
    echo '| scene | lambda | inf-sup constant by mesh | rates | exponent at the end |'
    echo '|---|---|---|---|---|'
    for lambda in -2 -3 -4; do
        values=()
        for n in 4 8 16 32; do
            m=$(mesh chamfer "$n" 2)
            nml chamfer 0.2 "$m" >"$out/infsup.nml"
            values+=("$("$probe" "$out/infsup.nml" --scan "$lambda" "$lambda" 1 | awk '/^scan/ { print $3 }')")
        done
        rates=$(printf '%s\n' "${values[@]}" | awk 'NR > 1 { printf "%.2f ", log(p / $1) / log(2) } { p = $1 }')
        echo "| chamfer nu 0.2, P2, N = 4, 8, 16, 32 | $lambda | ${values[*]} | $rates (per halving) | see wedge_table |"
    done
    # slanted, nu = 0.1: lambda > pi/2 is past the crossing of its 90-degree end (1.5, 0)
    m=$(mesh slanted 4 1)
    nml slanted 0.1 "$m" >"$out/infsup.nml"
    for lambda in 2 3; do
        values=()
        for level in 2 3 4 5 6 7; do
            values+=("$("$probe" "$out/infsup.nml" --level "$level" --scan "$lambda" "$lambda" 1 | awk '/^scan/ { print $3 }')")
        done
        rates=$(printf '%s\n' "${values[@]}" | awk 'NR > 1 { printf "%.2f ", log(p / $1) / log(1 / 0.15) } { p = $1 }')
        echo "| slanted nu 0.1, hp levels 2 to 7 from h = 1/4 | $lambda | ${values[*]} | $rates (per level, in h_min) | see wedge_table |"
    done
    echo
fi

if [[ $sections == *variants* ]]; then
    echo '| scene | variant | start h | lambda+ at levels 6, 8 | lambda- at levels 6, 8 |'
    echo '|---|---|---|---|---|'
    for scene in $scenes; do
        body=${scene%:*} nu=${scene#*:}
        for variant in '' '--lower' '--half' '--half --degrees plus:1'; do
            for n in 1 2 4 8; do
                m=$(mesh "$body" "$n" 1)
                nml "$body" "$nu" "$m" >"$out/variants.nml"
                row="| $body nu $nu | ${variant:-default} | 1/$n"
                plus='' minus=''
                for level in 6 8; do
                    # shellcheck disable=SC2086
                    lines=$("$probe" "$out/variants.nml" --level "$level" $variant --window -1000 1000 2>/dev/null || true)
                    plus="$plus $(echo "$lines" | awk '/^real/ && $2 > 0 { if (!n || $2 < b) b = $2; n = 1 } END { if (n) printf "%.7f", b; else printf "none" }')"
                    minus="$minus $(echo "$lines" | awk '/^real/ && $2 < 0 { if (!n || $2 > b) b = $2; n = 1 } END { if (n) printf "%.7f", b; else printf "none" }')"
                done
                echo "$row |$plus |$minus |"
            done
        done
    done
fi
