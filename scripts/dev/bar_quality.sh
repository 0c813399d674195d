#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# How good the error bar (or, before it exists, the error estimate) of every critical value
# is: bar / true error, against the independent truths of tests/data/truths.csv
# (docs/accuracy.md, "Independent truths" and "Quality of the error bars").
# For every scene of truths.csv (scripts/lib/truth_scenes.sh; the single-element closed
# form is a P1 value, not a continuum one, and is left out) and every family:
#   uniform P1, P2, P3 (and Q1, Q2 on rectangles) at N = 4, 8, 16, 32 cells per unit
#   length (rectangles: nceig's own meshes, 'right' diagonals; other shapes: Gmsh Delaunay
#   meshes of the scene's .geo of size 1/N, of the element's order), and
#   adaptive P1, P2, P3 to 1e-8 (from N = 4; at most 60000 dofs, so P1 stops early),
#   every adapt.csv level from the 3rd on,
# it takes the relative bar of each value (summary.json lowest_positive_error_bar,
# lambda_critical_plus/minus_error_bar, adapt.csv error_bar(_plus/_minus) when present,
# else the error estimate: lowest_positive_error_estimate, ..._error_estimate,
# error_estimate(_plus/_minus); the table says which) over its true relative error, and
# prints min, median, max and the share in [1, 10] per family and overall (and the adaptive
# values by how far their true error dipped below its trend: docs/accuracy.md). 'threshold'
# scenes give the critical lambdas (uniform threshold runs and kind = 'threshold'
# adaptive): lambda+ and lambda-, or where a scene's truths are collision onsets
# (lambda_onset_*), boundary_error_bar and the adapt.csv collision columns. Values whose
# true error is below 100 times the truth's uncertainty are skipped (counted); values with
# neither bar nor estimate are counted as 'none'.
# Usage: scripts/dev/bar_quality.sh [-j JOBS] [--adaptive] [--keep DIR] [SCENE...]
#   -j JOBS     parallel runs (default 2)
#   --adaptive  only the adaptive jobs (the uniform families then count 0 values)
#   --keep DIR  work in DIR (created; must not exist) and keep it: jobs/NAME.nml and .meta,
#               out/NAME/adapt.csv and summary.json of every run, and 'ratios', one line per
#               value (scene family quantity source ratio; adaptive values add the envelope
#               and the change parts of the level bar over the true error, the level, for
#               scripts/dev/level_factor.sh, the dip of the true error below its trend,
#               and the two parts again with the window WINDOW)
#   --analyse DIR  no runs: the table again from a folder kept by --keep
# Environment: NCEIG (the binary), TRUTHS (the truths file), ADAPT (more &adapt settings of
# the adaptive runs, e.g. ADAPT='theta = 0.5'); for 'ratios' only: WINDOW_WAS, the window
# growth of the build that made the runs (default 1.4, error_bar's WINDOW_GROWTH; 0 for a
# build before it, whose window was three levels), and WINDOW, another growth for
# scripts/dev/level_factor.sh --window (default 1.4).
# Needs gmsh and jq; 35 to over 60 minutes on 2 shared cores (the adaptive runs take most).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
jobs=2 adaptive_only= keep= analyse=
while (($# > 0)); do
    case $1 in
        -j) jobs=$2; shift 2 ;;
        --adaptive) adaptive_only=1; shift ;;
        --keep) keep=$2; shift 2 ;;
        --analyse) analyse=$2; shift 2 ;;
        -*) echo "bar_quality: unknown option $1 (-j JOBS, --adaptive, --keep DIR, --analyse DIR)" >&2
            exit 2 ;;
        *) break ;;
    esac
done
[[ -x $nceig ]] || { echo "bar_quality: build first (scripts/dev/build.sh Release)" >&2; exit 1; }
command -v jq >/dev/null || { echo "bar_quality: needs jq" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "bar_quality: needs gmsh" >&2; exit 1; }
truths=${TRUTHS:-$root/tests/data/truths.csv}
[[ -f $truths ]] || { echo "bar_quality: $truths missing (scripts/dev/continuum_truths.sh --write)" >&2; exit 1; }
source "$root/scripts/lib/truth_scenes.sh"
scenes=("$@")
if ((${#scenes[@]} == 0)); then
    mapfile -t scenes < <(awk -F, 'NR > 1 && $5 !~ /^closed/ && !seen[$1]++ { print $1 }' "$truths")
fi
if [[ -n $analyse ]]; then
    [[ -d $analyse/jobs ]] || { echo "bar_quality: --analyse $analyse: no jobs/ (a folder of --keep)" >&2; exit 2; }
    work=$(cd "$analyse" && pwd)
elif [[ -n $keep ]]; then
    [[ ! -e $keep ]] || { echo "bar_quality: --keep $keep exists already" >&2; exit 2; }
    mkdir -p "$keep"
    work=$(cd "$keep" && pwd)
else
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
fi
start=$(date +%s)
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
sizes=(4 8 16 32)

if [[ -z $analyse ]]; then
    # job NAME FAMILY MESH_LINE ADAPT_LINE: writes $work/jobs/NAME.nml and NAME.meta
    mkdir -p "$work/jobs" "$work/meshes"
    job() {
        local name=$1 family=$2 mesh_line=$3 adapt_line=$4 est=on
        [[ $family == *q1* || $family == *q2* ]] && est=auto
        {
            echo "$mesh_line"
            scene_physics_nml
            echo "&eigen estimate = '$est' /"
            echo "$adapt_line"
            echo "&output directory = '$work/out/$name', vtk = .false., plot = .false., progress = .false. /"
        } >"$work/jobs/$name.nml"
        echo "$scene $family $kind" >"$work/jobs/$name.meta"
    }

    for scene in "${scenes[@]}"; do
        scene_info "$scene"
        for el in p1 p2 p3 q1 q2; do
            [[ $el == q* && -z $W ]] && continue
            for n in "${sizes[@]}"; do
                # the Gmsh meshes of N = 4 are the adaptive runs' start too
                [[ -n $adaptive_only && -n $W ]] && break
                [[ -n $adaptive_only && $n != 4 ]] && continue
                if [[ -n $W ]]; then
                    mesh_line=$(scene_rect_nml "$n" "$el")
                else
                    m=$work/meshes/${scene}_${el}_$n.msh
                    scene_gmsh "$m" "${el#p}" -setnumber graded 0 -clmax "$(awk -v n="$n" 'BEGIN { print 1 / n }')"
                    mesh_line=$(scene_mesh_nml "$m")
                fi
                if [[ -z $adaptive_only ]]; then job "${scene}_u${el}_$n" "uniform-$el" "$mesh_line" ""; fi
            done
        done
        for el in p1 p2 p3; do
            if [[ -n $W ]]; then
                mesh_line=$(scene_rect_nml 4 "$el")
            else
                m=$work/meshes/${scene}_${el}_4.msh
                mesh_line=$(scene_mesh_nml "$m")
            fi
            job "${scene}_a$el" "adaptive-$el" "$mesh_line" \
                "&adapt tolerance = 1e-8, max_dofs = 60000, max_levels = 200${ADAPT:+, $ADAPT} /"
        done
    done

    # run the jobs, longest first (adaptive, then the finest uniform meshes)
    ls "$work/jobs"/*.nml | awk '{ k = ($0 ~ /_a[^\/]*$/) ? 0 : ($0 ~ /_32\.nml$/) ? 1 : 2; print k, $0 }' |
        sort -k1,1n | cut -d' ' -f2- |
        xargs -P "$jobs" -I{} sh -c '"$1" "$2" >"$2.log" 2>&1; echo $? >"$2.rc"' _ "$nceig" {}
fi

# ratios: one line per value: scene family quantity source ratio (or 'skip' / 'none')
ratio_lines() {
    local f name scene family kind rc out q
    for f in "$work/jobs"/*.nml; do
        name=$(basename "$f" .nml)
        read -r scene family kind <"$work/jobs/$name.meta"
        rc=$(cat "$f.rc")
        out=$work/out/$name
        if [[ $rc != 0 && $rc != 8 ]] || [[ ! -f $out/summary.json ]]; then
            echo "$scene $family - failed $rc"; continue
        fi
        for q in $(awk -F, -v s="$scene" '$1 == s { print $2 }' "$truths"); do
            read -r truth unc < <(awk -F, -v s="$scene" -v q="$q" '$1 == s && $2 == q { print $3, $4 }' "$truths")
            if [[ $family == adaptive-* ]]; then
                local vcol ecol bcol
                case $q in
                    lowest_positive_mu) vcol=mu ecol=error_estimate bcol=error_bar ;;
                    lambda_critical_plus) vcol=lambda_plus ecol=error_estimate_plus bcol=error_bar_plus ;;
                    lambda_critical_minus) vcol=lambda_minus ecol=error_estimate_minus bcol=error_bar_minus ;;
                    lambda_onset_*) vcol=collision_${q#lambda_onset_} ecol=error_estimate_collision_${q#lambda_onset_}
                        bcol=error_bar_collision_${q#lambda_onset_} ;;
                esac
                # after the ratio: level_bar's two parts over the true error (the envelope
                # of the window's estimates carried at the optimal rate, the change over the
                # window) and the level, to recompute the bar with another level factor; the
                # window as error_bar's: w levels and those before with dofs(k) / g or more
                # (g of the build that made the runs). Then the dip: the largest of the
                # window's true errors carried at the optimal rate over this level's (above
                # 1: the error fell below its trend); and the two parts again with the
                # window of growth g2, to recompute the bar with another window
                awk -F, -v v="$vcol" -v e="$ecol" -v b="$bcol" -v t="$truth" -v u="$unc" \
                    -v p="${family#adaptive-p}" -v w=3 -v g="${WINDOW_WAS:-1.4}" \
                    -v g2="${WINDOW:-1.4}" -v pre="$scene $family $q" '
                    # env, moved, trend over the window of growth gg at level k
                    function window(gg,    first, j, x) {
                        env = 0; moved = 0; trend = 0
                        first = (k - w + 1 > 1) ? k - w + 1 : 1
                        while (first > 1 && gg * dofs[first - 1] >= dofs[k]) first--
                        for (j = first; j <= k; j++) if (est[j] >= 0) {
                            x = est[j] * (dofs[j] / dofs[k]) ^ p; if (x > env) env = x
                            x = (val[k] - val[j]) / val[k]; if (x < 0) x = -x; if (x > moved) moved = x
                            x = (val[j] - t) / t; if (x < 0) x = -x
                            x *= (dofs[j] / dofs[k]) ^ p; if (x > trend) trend = x }
                    }
                    BEGIN { OFMT = "%.10g" }
                    NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
                    { k = NR - 1; dofs[k] = $c["n_dofs"]; val[k] = $c[v]
                      est[k] = (c[e] && $c[e] != "" && $c[v] != "") ? $c[e] : -1 }
                    $1 >= 2 && c[v] && $c[v] != "" {
                        src = (c[b] && $c[b] != "") ? "bar" : (c[e] && $c[e] != "") ? "estimate" : "none"
                        err = ($c[v] - t) / t; if (err < 0) err = -err
                        if (err < 100 * u) { print pre, src, "skip"; next }
                        if (src == "none") { print pre, "none", "none"; next }
                        window(g2); env2 = env; moved2 = moved
                        window(g)
                        print pre, src, (src == "bar" ? $c[b] : $c[e]) / err, env / err, moved / err, $1,
                            trend / err, env2 / err, moved2 / err }' "$out/adapt.csv"
            else
                jq -r --arg q "$q" --arg t "$truth" --arg u "$unc" --arg pre "$scene $family $q" '
                    (.[$q]) as $v
                    | (if $q == "lowest_positive_mu" then .lowest_positive_error_bar
                       elif ($q | startswith("lambda_onset_")) then ([.boundary_lambda,
                           .boundary_error_bar] | transpose | map(select(.[0] == $v)) | .[0][1])
                       else .[$q + "_error_bar"] end) as $b
                    | (if $q == "lowest_positive_mu" then .lowest_positive_error_estimate
                       else .[$q + "_error_estimate"] end) as $e
                    | if $v == null then "\($pre) none missing" else
                      ((($v - ($t | tonumber)) / ($t | tonumber)) | fabs) as $err
                      | if $err < 100 * ($u | tonumber) then "\($pre) - skip"
                        elif $b != null then "\($pre) bar \($b / $err)"
                        elif $e != null then "\($pre) estimate \($e / $err)"
                        else "\($pre) none none" end end' "$out/summary.json"
            fi
        done
    done
}
# a summary line of the ratios on stdin: label source n min median max share[1,10] skipped none
summarise() {
    awk -v label="$1" '
        $5 == "skip" { skip++; next }
        $5 == "none" || $5 == "missing" || $4 == "failed" { none++; next }
        { r[++n] = $5 + 0; src[$4] = 1 }
        END {
            s = ""; for (k in src) s = s (s == "" ? "" : "+") k; if (s == "") s = "-"
            if (n == 0) { printf "%-28s %-9s %4d %8s %8s %8s %7s %5d %5d\n", label, s, 0, "-", "-", "-", "-", skip, none; exit }
            for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (r[j] < r[i]) { t = r[i]; r[i] = r[j]; r[j] = t }
            for (i = 1; i <= n; i++) if (r[i] >= 1 && r[i] <= 10) in10++
            med = (n % 2) ? r[(n + 1) / 2] : (r[n / 2] + r[n / 2 + 1]) / 2
            printf "%-28s %-9s %4d %8.3g %8.3g %8.3g %6.0f%% %5d %5d\n", label, s, n, r[1], med, r[n], 100 * in10 / n, skip, none }'
}

ratio_lines >"$work/ratios"
echo "# nceig $("$nceig" --version | cut -d' ' -f2): bar / true error against ${truths#$root/}"
echo "# source 'bar' = *_error_bar, 'estimate' = *_error_estimate (no bar in this build)"
printf '%-28s %-9s %4s %8s %8s %8s %7s %5s %5s\n' family source n min median max '[1,10]' skip none
for group in mu lambda; do
    if [[ $group == mu ]]; then sel='$3 == "lowest_positive_mu"'; echo "critical c_n (lowest positive mu):"
    else sel='$3 != "lowest_positive_mu"'; echo "critical lambdas (lambda+ and lambda-, collision onsets):"; fi
    for fam in uniform-p1 uniform-p2 uniform-p3 uniform-q1 uniform-q2 adaptive-p1 adaptive-p2 adaptive-p3; do
        awk -v f="$fam" "\$2 == f && $sel" "$work/ratios" | summarise "  $fam"
    done
    awk "$sel" "$work/ratios" | summarise "  all"
done
awk '1' "$work/ratios" | summarise "overall"
echo
# a bar cannot follow a true error that falls by cancellation at one level (the estimates
# dip too, and a bar that believed such dips would fall below the error elsewhere): the
# adaptive values by how far their true error dipped below the window's trend
echo "adaptive values by the dip of the true error (the window's, carried, over its own):"
awk '$2 ~ /^adaptive/ && NF >= 9 && $9 < 3' "$work/ratios" | summarise "  dip below 3"
awk '$2 ~ /^adaptive/ && NF >= 9 && $9 >= 3 && $9 < 10' "$work/ratios" | summarise "  dip 3 to 10"
awk '$2 ~ /^adaptive/ && NF >= 9 && $9 >= 10' "$work/ratios" | summarise "  dip 10 or more"
echo
echo "per scene (all families):"
for scene in "${scenes[@]}"; do awk -v s="$scene" '$1 == s' "$work/ratios" | summarise "  $scene"; done
if grep -q failed "$work/ratios"; then echo "failed runs:"; grep failed "$work/ratios" | sort -u; fi
echo "time $(($(date +%s) - start)) s ($jobs parallel runs)"
