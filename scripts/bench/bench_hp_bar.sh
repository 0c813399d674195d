#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The hp bar's check one degree higher: what it costs and whether the bar it makes covers the
# true error, with &adapt p_max = 1 to 6 and the default (20). Scenes of tests/data/truths.csv
# (scripts/lib/truth_scenes.sh): ref (c_n, 2 x 2 P1 squares), half-contact (c_n, Gmsh
# Delaunay P1 of size 1/2), ref-threshold (lambda+-) and half-contact-threshold (its minus
# onset, a collision), all 'hp' to TOLERANCE. Per run: the exit status, the last level's
# value and bar (adapt.csv: the bar with the check folded in) against the truth, "covers"
# when bar >= |value - truth| / |truth| - the truth's uncertainty; the loop's wall time
# (adapt.csv time_s of the last level: the loop without the check) and the check's (stdout
# "hp check of level N: ... X s"), medians of REPEATS runs, and their ratio (loop + check) /
# loop. The ratio is shown for runs with a check (exit 0, or 8 from the check).
# Usage: scripts/bench/bench_hp_bar.sh [REPEATS [TOLERANCE]]  (defaults 3, 1e-8); needs gmsh.
# Environment: NCEIG (executable), SCENES (default: the four above; half-contact-threshold
# with p_max = 3 to 5 climbs for minutes before its onset stalls).
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=$(realpath "${NCEIG:-$root/build/nceig}")
repeats=${1:-3}
tol=${2:-1e-8}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$root/scripts/lib/truth_scenes.sh"
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

printf '| scene | quantity | p_max | exit | dofs | value | bar | true error | covers | loop s | check s | ratio |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|---|\n'
for name in ${SCENES:-ref half-contact ref-threshold half-contact-threshold}; do
    scene_info "$name"
    if [[ -n $W ]]; then
        mesh=$(scene_rect_nml 2 p1)
    else
        scene_gmsh "$work/$name.msh" 1 -setnumber graded 0 -clmax 0.5 >/dev/null 2>&1 || continue
        mesh=$(scene_mesh_nml "$work/$name.msh")
    fi
    case $name in
        ref | half-contact) quantity=lowest_positive_mu col=mu bar=error_bar ;;
        ref-threshold) quantity=lambda_critical_plus col=lambda_plus bar=error_bar_plus ;;
        half-contact-threshold) quantity=lambda_onset_minus col=collision_minus
            bar=error_bar_collision_minus ;;
    esac
    read -r truth unc < <(awk -F, -v s="$name" -v q="$quantity" '$1 == s && $2 == q { print $3, $4 }' \
        "$root/tests/data/truths.csv")
    for p in 1 2 3 4 5 6 default; do
        cap=""
        [[ $p == default ]] || cap=", p_max = $p"
        loops="" checks="" status=""
        for ((r = 1; r <= repeats; r++)); do
            out=$work/$name-$p
            {
                echo "$mesh"
                scene_physics_nml
                echo "&adapt tolerance = $tol, strategy = 'hp'$cap /"
                echo "&output directory = '$out', vtk = .false., plot = .false. /"
            } >"$work/$name.nml"
            OPENBLAS_NUM_THREADS=1 "$nceig" "$work/$name.nml" >"$work/stdout" 2>&1
            status=$?
            [[ -f $out/adapt.csv ]] || continue
            loops+=" $(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "time_s") c = i; next } { t = $c } END { print t }' "$out/adapt.csv")"
            checks+=" $(grep -E 'hp check of level [0-9]+: .* s$' "$work/stdout" | tail -1 | awk '{ print $(NF - 1) }')"
        done
        [[ -f $out/adapt.csv ]] || { echo "| $name | $quantity | $p | $status | no adapt.csv |"; continue; }
        awk -F, -v c="$col" -v b="$bar" -v t="$truth" -v u="$unc" -v name="$name" -v q="$quantity" \
            -v p="$p" -v status="$status" -v loop="$(echo "$loops" | median)" \
            -v check="$(echo "$checks" | median)" '
            NR == 1 { for (i = 1; i <= NF; i++) { if ($i == c) ci = i; if ($i == b) bi = i; if ($i == "n_dofs") di = i }; next }
            { v = $ci; bb = $bi; d = $di }
            END {
                e = (v - t) / t; if (e < 0) e = -e
                cover = (bb != "" && bb + u >= e) ? "yes" : (bb == "" ? "no bar" : "NO")
                ratio = (check != "" && loop > 0) ? sprintf("%.2f", (loop + check) / loop) : "-"
                printf "| %s | %s | %s | %s | %s | %.12g | %s | %.2e | %s | %.3f | %s | %s |\n", name, q, p,
                    status, d, v, (bb == "" ? "none" : sprintf("%.2e", bb)), e, cover, loop,
                    (check == "" ? "-" : check), ratio
            }' "$out/adapt.csv"
    done
done
