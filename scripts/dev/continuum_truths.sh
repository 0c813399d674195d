#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Independent continuum values of the critical c_n (and of lambda+ and lambda-) of the
# scenes of scripts/lib/truth_scenes.sh, the truths of tests/data/truths.csv
# (docs/accuracy.md, "Independent truths").
# Method: Gmsh meshes graded geometrically toward the singular points (cell size
# min(hmax, max(hmin, alpha r)), r the distance to the nearest corner; alpha = 0.15, hmax =
# 0.075), 15-node P4 triangles, no adaptation and no error estimate, for hmin = 1e-4, 1e-5,
# 1e-6, 1e-7. The values converge geometrically in hmin (ratio about 1/20 to 1/30 per
# decade); the truth is the Aitken extrapolation of the last three, its uncertainty the
# larger of |extrapolation - finest value| and the distance between the Aitken
# extrapolations of the first three and of the last three values (or |last difference|
# when the sequence is not geometric). Cross-check: nceig's adaptive P3 loop to 1e-10
# (a different mesh family, a different element, its own stopping test).
# Usage: scripts/dev/continuum_truths.sh [--write] [SCENE...]
#   --write   also write the scenes computed into tests/data/truths.csv (their rows replaced,
#             the other scenes' rows kept)
# Prints scene, quantity, value, uncertainty, method, adaptive value, difference, time.
# Needs gmsh and jq; about 10 to 15 minutes on 2 shared cores (the threshold scene is most).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
write=0
if [[ ${1:-} == --write ]]; then write=1; shift; fi
[[ -x $nceig ]] || { echo "continuum_truths: build first (scripts/dev/build.sh Release)" >&2; exit 1; }
command -v jq >/dev/null || { echo "continuum_truths: needs jq" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "continuum_truths: needs gmsh" >&2; exit 1; }
source "$root/scripts/lib/truth_scenes.sh"
scenes=("$@")
((${#scenes[@]} > 0)) || scenes=("${truth_scenes[@]}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
alpha=0.15 hmax=0.075 hmins=(1e-4 1e-5 1e-6 1e-7)
csv=$work/truths.csv
echo "scene,quantity,value,uncertainty,method" >"$csv"

# run NAME: nceig on $work/NAME.nml (exit 8, a tolerance not met, is reported, not fatal)
run() {
    local rc=0
    "$nceig" "$work/$1.nml" >"$work/$1.log" 2>&1 || rc=$?
    if ((rc != 0 && rc != 8)); then
        echo "continuum_truths: $1 failed (exit $rc)" >&2; tail -5 "$work/$1.log" >&2; exit 1
    fi
    ((rc == 0)) || echo "continuum_truths: $1: adaptive tolerance not met (exit 8)" >&2
}
val() { jq -r --arg k "$2" '.[$k] // empty' "$work/$1/summary.json"; }
# extrapolate X1 X2 X3 X4: "value uncertainty" (see the header)
extrapolate() {
    awk -v x1="$1" -v x2="$2" -v x3="$3" -v x4="$4" 'function abs(v) { return v < 0 ? -v : v }
    function aitken(a, b, c,   d1, d2) { d1 = b - a; d2 = c - b
        if (d1 == 0 || d2 / d1 <= 0 || d2 / d1 >= 0.5) return "none"
        return c + d2 * (d2 / d1) / (1 - d2 / d1) }
    BEGIN { a1 = aitken(x1, x2, x3); a2 = aitken(x2, x3, x4)
        if (a1 == "none" || a2 == "none") { printf "%.17g %.2e\n", x4, abs(x4 - x3); exit }
        u = abs(a2 - x4); if (abs(a2 - a1) > u) u = abs(a2 - a1)
        printf "%.17g %.2e\n", a2, u }'
}

printf '%-24s %-22s %-20s %-9s %-10s | %-20s %-9s %-9s %6s\n' scene quantity value uncert. \
    method adaptive 'its est.' diff time
total_start=$(date +%s)
for name in "${scenes[@]}"; do
    scene_info "$name"
    start=$(date +%s)
    quantities=(lowest_positive_mu)
    [[ $kind == threshold ]] && quantities=(lambda_critical_plus lambda_critical_minus)
    [[ -n $onsets ]] && read -r -a quantities <<<"$onsets"
    declare -A seq=()
    for hmin in "${hmins[@]}"; do
        tag=${name}_$hmin
        scene_gmsh "$work/$tag.msh" 4 -setnumber graded 1 -setnumber alpha $alpha \
            -setnumber hmin "$hmin" -setnumber hmax $hmax
        {
            scene_mesh_nml "$work/$tag.msh"
            scene_physics_nml
            echo "&eigen estimate = 'off' /"
            echo "&output directory = '$work/$tag', vtk = .false., plot = .false., progress = .false. /"
        } >"$work/$tag.nml"
        run "$tag"
        for q in "${quantities[@]}"; do seq[$q]="${seq[$q]:-} $(val "$tag" $q)"; done
    done
    # the adaptive P3 cross-check, from 4 cells per unit length (rectangles) or a Delaunay
    # P3 mesh of size 1/4
    tag=${name}_adapt
    if [[ -n $W ]]; then
        mesh_line=$(scene_rect_nml 4 p3)
    else
        scene_gmsh "$work/$tag.msh" 3 -setnumber graded 0 -clmax 0.25
        mesh_line=$(scene_mesh_nml "$work/$tag.msh")
    fi
    {
        echo "$mesh_line"
        scene_physics_nml
        echo "&adapt tolerance = 1e-10, max_dofs = 400000, max_levels = 200 /"
        echo "&output directory = '$work/$tag', vtk = .false., plot = .false., progress = .false. /"
    } >"$work/$tag.nml"
    run "$tag"
    elapsed=$(($(date +%s) - start))
    for q in "${quantities[@]}"; do
        read -r -a x <<<"${seq[$q]}"
        read -r value unc < <(extrapolate "${x[@]}")
        case $q in
            lowest_positive_mu) ad=$(val "$tag" lowest_positive_mu) ade=$(val "$tag" lowest_positive_error_estimate) ;;
            lambda_critical_plus) ad=$(val "$tag" lambda_critical_plus) ade=$(val "$tag" lambda_critical_plus_error_estimate) ;;
            lambda_critical_minus) ad=$(val "$tag" lambda_critical_minus) ade=$(val "$tag" lambda_critical_minus_error_estimate) ;;
            # a collision onset: its bar (its estimate is no summary key)
            lambda_onset_*) ad=$(val "$tag" "$q")
                ade=$(jq -r --argjson l "$ad" '[.boundary_lambda, .boundary_error_bar] | transpose
                    | map(select(.[0] == $l))[0][1] // empty' "$work/$tag/summary.json") ;;
        esac
        method="graded-P4-hmin-1e-4..1e-7-aitken"
        awk -v s="$name" -v q="$q" -v v="$value" -v u="$unc" -v ad="$ad" -v ade="${ade:-nan}" -v t="$elapsed" \
            -v seqs="${seq[$q]}" 'BEGIN {
            ur = u / (v < 0 ? -v : v); d = (ad - v) / (v < 0 ? -v : v)
            printf "%-24s %-22s %-20.15g %-9.1e %-10s | %-20.15g %-9.1e %-9.1e %5ds\n", s, q, v, ur,
                "graded-P4", ad, ade, d, t
            n = split(seqs, x, " ")
            printf "%-24s   graded P4, hmin = 1e-4 .. 1e-7:", ""
            for (i = 1; i <= n; i++) printf " %.17g", x[i]; printf "\n" }'
        awk -v v="$value" -v u="$unc" 'BEGIN { printf "%.2e", u / (v < 0 ? -v : v) }' >"$work/ur"
        echo "$name,$q,$value,$(cat "$work/ur"),$method" >>"$csv"
    done
    unset seq
done

# (j) the single element of input/single_element.nml: P1 on ONE triangle, in closed form
# (docs/model.md, section 8): mu = 105/208 at lambda = -5, lambda- = -(L + 3G) / (L + G)
# = -9/5 for E = 1, nu = 0.3. A truth for that discrete problem, not for a continuum.
start=$(date +%s)
sed -e "s|meshes/single_element.msh|$root/input/meshes/single_element.msh|" \
    -e "s|vtk = .true.|vtk = .false., plot = .false., progress = .false., directory = '$work/single'|" \
    "$root/input/single_element.nml" >"$work/single.nml"
run single
sed -e "s|'eigen'|'threshold'|" -e "s|/single'|/single_t'|" "$work/single.nml" >"$work/single_t.nml"
run single_t
t=$(($(date +%s) - start))
for q in lowest_positive_mu lambda_critical_minus; do
    if [[ $q == lowest_positive_mu ]]; then v=0.50480769230769231 f=single; else v=-1.8 f=single_t; fi
    got=$(val $f $q)
    awk -v q=$q -v v=$v -v g="$got" -v t=$t 'BEGIN {
        printf "%-24s %-22s %-20.15g %-9s %-10s | %-20.15g %-9s %-9.1e %5ds\n", "single-element-p1", q, v,
            "exact", "closed", g, "", (g - v) / (v < 0 ? -v : v), t }'
    echo "single-element-p1,$q,$v,0,closed-form-p1-one-triangle" >>"$csv"
done
echo "total $(($(date +%s) - total_start)) s"
if ((write)); then
    old=$root/tests/data/truths.csv
    [[ -f $old ]] || echo "scene,quantity,value,uncertainty,method" >"$old"
    awk -F, 'NR == FNR { if (FNR > 1) new[$1] = 1; next }
        FNR == 1 || !($1 in new)' "$csv" "$old" >"$work/merged"
    tail -n +2 "$csv" >>"$work/merged"
    cp "$work/merged" "$old"
    echo "wrote tests/data/truths.csv"
fi
