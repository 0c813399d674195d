#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# bar / true error of the hp loop, level by level, against tests/data/truths.csv: every
# eigen scene (lowest positive mu, tolerance 1e-11) and every threshold scene (lambda+-
# or the collision onsets, tolerance 1e-10) of scripts/lib/truth_scenes.sh, from 2 x 2
# squares per unit length (rectangles) or a Gmsh Delaunay P1 mesh of size 1/2 (other
# shapes). Levels from the third on whose true error is at least 100 times the truth's
# uncertainty count (the others cannot be judged). Prints one line per scene and
# quantity (level:ratio), then min, median, max and the share in [1, 10].
# Usage: scripts/dev/hp_bar_quality.sh [NCEIG [SIGMA]] (default build/nceig and &adapt
# sigma's default, 0.15); needs gmsh. Some 3 minutes on 2 cores. A side that stalls
# (hp_run_bar) has no bar and no ratio: the plus side of half-contact-threshold, whose
# onset moves with the mesh.
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=$(realpath "${1:-$root/build/nceig}")
sigma=${2:+, sigma = $2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$root/scripts/lib/truth_scenes.sh"
for name in "${truth_scenes[@]}"; do

    scene_info "$name"
    tol=1e-11
    [[ $kind == threshold ]] && tol=1e-10
    if [[ -n $W ]]; then
        mesh=$(scene_rect_nml 2 p1)
    else
        scene_gmsh "$work/$name.msh" 1 -setnumber graded 0 -clmax 0.5 || continue
        mesh=$(scene_mesh_nml "$work/$name.msh")
    fi
    {
        echo "$mesh"
        scene_physics_nml
        echo "&adapt tolerance = $tol, strategy = 'hp'$sigma /"
        echo "&output directory = '$work/$name', vtk = .false., plot = .false., progress = .false. /"
    } >"$work/$name.nml"
    "$nceig" "$work/$name.nml" >/dev/null 2>&1
    [[ -f $work/$name/adapt.csv ]] || { echo "$name: no adapt.csv"; continue; }
    # each truth of the scene: its adapt.csv value and bar columns
    awk -F, -v s="$name" '$1 == s { print $2, $3, $4 }' "$root/tests/data/truths.csv" |
        while read -r quantity value uncertainty; do
            case $quantity in
                lowest_positive_mu) col=mu bar=error_bar ;;
                lambda_critical_plus) col=lambda_plus bar=error_bar_plus ;;
                lambda_critical_minus) col=lambda_minus bar=error_bar_minus ;;
                lambda_onset_plus) col=collision_plus bar=error_bar_collision_plus ;;
                lambda_onset_minus) col=collision_minus bar=error_bar_collision_minus ;;
                *) continue ;;
            esac
            awk -F, -v c="$col" -v b="$bar" -v t="$value" -v u="$uncertainty" \
                -v label="$name $quantity" '
                NR == 1 { for (i = 1; i <= NF; i++) { if ($i == c) ci = i; if ($i == b) bi = i }; next }
                NR >= 4 && $ci != "" && $bi != "" {
                    e = ($ci - t) / t; if (e < 0) e = -e
                    if (e >= 100 * u) { r = $bi / e; line = line sprintf(" %d:%.1f", NR - 1, r); print r > "/dev/stderr" }
                }
                END { print label ":" line }' "$work/$name/adapt.csv" 2>>"$work/ratios"
        done
done
sort -g "$work/ratios" | awk '{ r[NR] = $1; if ($1 >= 1 && $1 <= 10) inside++ }
    END { if (NR == 0) exit; m = (NR % 2) ? r[(NR + 1) / 2] : (r[NR / 2] + r[NR / 2 + 1]) / 2
          printf "n = %d, min %.2f, median %.1f, max %.1f, in [1, 10]: %d\n", NR, r[1], m, r[NR], inside }'
