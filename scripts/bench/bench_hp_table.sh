#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Time to the critical c_n of the reference scene (unit square, E = 1, nu = 0.3, top clamped,
# sides free, contact on the bottom, lambda = 5) at a requested accuracy, one table for:
#   hp       &adapt strategy = 'hp' from 2 x 2 P1 squares (modes = 1, plot off)
#   h P3     input/adapt.nml (h-adaptive P3 from 4 x 4) with the tolerance, plot off
#   P2, P4   uniform N x N meshes ('right'), estimate off: the smallest N of the ladder whose
#            true error meets the tolerance, else the largest N ("stalls")
#   FreeFEM  scripts/bench/graded_p4.edp: P4 on a mesh graded a priori toward the four
#            corners (the clamped top corners, the ends of the contact side); the first
#            (layers, split) of the ladder whose true error meets the tolerance
# and the critical lambdas ('threshold', input/threshold_adapt.nml, plot off) to 1e-10 by the
# h loop and, where nceig accepts it, by strategy = 'hp'. Every nceig run has &output plot
# off: gnuplot's pictures are no part of the answer (hp's mode_001.png alone takes 0.5 s).
# Usage: scripts/bench/bench_hp_table.sh [REPEATS] [TOLERANCE ...]  (defaults: 3, 1e-8 1e-10 1e-12)
# Environment: NCEIG (executable), P2_LADDER, P4_LADDER (N values), FF_LADDER (layers:split),
# THR_TOLERANCE (of the critical lambdas, default 1e-10), THR_MAX_DOFS (cap of their h loop,
# default 120000).
# A run "meets" a tolerance T when |mu - truth| <= T truth + the truth's own uncertainty
# (tests/data/truths.csv), so that below that uncertainty no method is judged by noise.
# Wall time and peak RSS from /usr/bin/time (medians of REPEATS runs; ladder searches run
# each candidate once, the chosen one REPEATS times in all). Needs jq and GNU time;
# FreeFEM (Debian: freefem++ and libfreefem++ for its plugins) and gmsh are optional.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
source "$root/scripts/lib/bench_common.sh"
bench_begin bench_hp_table "${1:-3}"
tolerances=("${@:2}")
((${#tolerances[@]} > 0)) || tolerances=(1e-8 1e-10 1e-12)
command -v jq >/dev/null || { echo "bench_hp_table: needs jq" >&2; exit 1; }
read -r -a p2_ladder <<<"${P2_LADDER:-16 32 64 128 256}"
read -r -a p4_ladder <<<"${P4_LADDER:-8 16 32 64 128}"
read -r -a ff_ladder <<<"${FF_LADDER:-8:1 12:1 8:2 12:2 16:2 12:3 16:3 20:3}"

truths=$root/tests/data/truths.csv
truth_of() { awk -F, -v s="$1" -v q="$2" -v c="$3" '$1 == s && $2 == q { print $c }' "$truths"; }
mu_true=$(truth_of ref lowest_positive_mu 3)
mu_unc=$(truth_of ref lowest_positive_mu 4)
lp_true=$(truth_of ref-threshold lambda_critical_plus 3)
lm_true=$(truth_of ref-threshold lambda_critical_minus 3)
l_unc=$(truth_of ref-threshold lambda_critical_plus 4)

# relerr VALUE TRUTH: |value - truth| / |truth|
relerr() { awk -v a="$1" -v b="$2" 'BEGIN { d = (a - b) / b; printf "%.1e", (d < 0 ? -d : d) }'; }
# meets ERROR TOLERANCE TRUTH UNCERTAINTY: exit 0 when error <= tolerance + uncertainty / truth
meets() { awk -v e="$1" -v t="$2" -v v="$3" -v u="$4" \
          'BEGIN { if (v < 0) v = -v; exit !(e <= t + u / v) }'; }

# timed DIR COMMAND...: one run in DIR (made afresh) under /usr/bin/time; sets rc, wall, peak
# (MB); standard output in DIR.out, errors in DIR.err
timed() {
    local dir=$1
    shift
    rm -rf "$dir"
    mkdir -p "$dir"
    rc=0
    (cd "$dir" && /usr/bin/time -f '%e %M' -o "$dir.time" "$@" >"$dir.out" 2>"$dir.err") || rc=$?
    read -r wall peak < <(awk 'END { printf "%s %.0f\n", $1, $2 / 1024 }' "$dir.time")
}

# repeat TAG COMMAND...: REPEATS runs (the ladder's first one counted when walls_TAG is set);
# sets med_wall, med_peak. Caches by tag, so a configuration shared by rows runs once.
declare -A cache_wall cache_peak first_wall first_peak
repeat() {
    local tag=$1 walls='' peaks='' r=0
    shift
    if [[ -n ${cache_wall[$tag]:-} ]]; then
        med_wall=${cache_wall[$tag]} med_peak=${cache_peak[$tag]}
        return
    fi
    if [[ -n ${first_wall[$tag]:-} ]]; then
        walls=${first_wall[$tag]} peaks=${first_peak[$tag]} r=1
    fi
    for (( ; r < repeats; r++)); do
        timed "$work/$tag" "$@"
        walls+=" $wall" peaks+=" $peak"
    done
    med_wall=$(echo "$walls" | median) med_peak=$(echo "$peaks" | median)
    cache_wall[$tag]=$med_wall cache_peak[$tag]=$med_peak
}

rows=()
declare -A hp_wall
# row METHOD TOLERANCE DOFS WALL PEAK ERROR BAR NOTE [REFERENCE_WALL]
row() {
    local ratio=-
    [[ -n ${9:-} ]] && ratio=$(awk -v a="$4" -v b="$9" 'BEGIN { printf "%.1f", a / b }')
    rows+=("$(printf '| %s | %s | %s | %s | %s | %s | %s | %s | %s |' "$1" "$2" "$3" "$4" "$5" \
              "$6" "$7" "$ratio" "$8")")
    echo "  done: $1 $2 ($4 s)" >&2
}

# why TAG: the reason an adaptive run gave for stopping short (its error line, shortened)
why() { sed -n 's/.*not met: //p' "$work/$1.err" | head -1 | sed 's/ (the set of the last level is written)//'; }

# nceig_adapt TAG TOLERANCE INPUT SETTINGS...: an adaptive nceig run to the tolerance
nceig_adapt() {
    local tag=$1 tol=$2 input=$3 s
    shift 3
    repeat "$tag" "$nceig" "$input" --set adapt%tolerance="$tol" \
        --set output%directory="$work/$tag/out" "$@"
    s=$work/$tag/out/summary.json
    [[ -f $s ]] || { echo "bench_hp_table: $tag failed: $(cat "$work/$tag.err")" >&2; exit 1; }
    err=$(relerr "$(key "$s" lowest_positive_mu)" "$mu_true")
    bar=$(printf '%.1e' "$(key "$s" lowest_positive_error_bar)")
    dofs=$(key "$s" n_dofs)
    note=met
    [[ $(jq -r .adapt_converged "$s") == true ]] || note="not met: $(why "$tag")"
}

echo "# nceig $("$nceig" --version | cut -d' ' -f2), $(nproc) cores, $repeats runs each"
echo "# uptime at start: $(uptime)"

# --- hp -----------------------------------------------------------------------------------
cat >"$work/hp.nml" <<'NML'
&mesh nx = 2, ny = 2, element = 'p1' /
&analysis kind = 'eigen', lambda = 5.0 /
&adapt strategy = 'hp' /
&output modes = 1, plot = .false. /
NML
for tol in "${tolerances[@]}"; do
    nceig_adapt "hp_$tol" "$tol" "$work/hp.nml"
    hp_wall[$tol]=$med_wall
    row "nceig hp" "$tol" "$dofs" "$med_wall" "$med_peak" "$err" "$bar" "$note" "$med_wall"
done

# --- h-adaptive P3 --------------------------------------------------------------------------
for tol in "${tolerances[@]}"; do
    nceig_adapt "h_$tol" "$tol" "$root/input/adapt.nml" --set output%plot=.false.
    row "nceig h P3" "$tol" "$dofs" "$med_wall" "$med_peak" "$err" "$bar" "$note" \
        "${hp_wall[$tol]}"
done

# choose ERRORS TOLERANCE LAST KEY...: of the ladder KEY... (in order; ERRORS names the
# associative array of the errors of the candidates run), sets pick to the first whose error
# meets the tolerance and met=yes, else pick=LAST and met=no
choose() {
    local -n errors=$1
    local tol=$2 candidate
    pick=$3 met=no
    shift 3
    for candidate in "$@"; do
        [[ -n ${errors[$candidate]:-} ]] || break
        if meets "${errors[$candidate]}" "$tol" "$mu_true" "$mu_unc"; then
            pick=$candidate met=yes
            break
        fi
    done
}

# --- uniform P2, P4 -------------------------------------------------------------------------
# ladder: each N once, in order, until the finest tolerance is met
uniform() {
    local el=$1 n tol s
    shift
    declare -A n_err n_dofs
    local last=
    for n in "$@"; do
        timed "$work/u${el}_$n" "$nceig" "$root/input/square.nml" --set mesh%element="$el" \
            --set mesh%nx="$n" --set mesh%ny="$n" --set eigen%estimate=off \
            --set output%vtk=.false. --set output%plot=.false. \
            --set output%directory="$work/u${el}_$n/out"
        s=$work/u${el}_$n/out/summary.json
        [[ -f $s ]] || { echo "bench_hp_table: uniform $el N = $n failed" >&2; exit 1; }
        first_wall[u${el}_$n]=$wall first_peak[u${el}_$n]=$peak
        n_err[$n]=$(relerr "$(key "$s" lowest_positive_mu)" "$mu_true")
        n_dofs[$n]=$(key "$s" n_dofs)
        echo "# ladder uniform ${el^^} N = $n: ${n_dofs[$n]} dofs, error ${n_err[$n]}, $wall s"
        last=$n
        meets "${n_err[$n]}" "${tolerances[-1]}" "$mu_true" "$mu_unc" && break
    done
    for tol in "${tolerances[@]}"; do
        choose n_err "$tol" "$last" "$@"
        note="stalls at ${n_err[$last]} with ${n_dofs[$last]} dofs (N = $last, the ladder's largest)"
        [[ $met == yes ]] && note="met at N = $pick"
        repeat "u${el}_$pick" "$nceig" "$root/input/square.nml" --set mesh%element="$el" \
            --set mesh%nx="$pick" --set mesh%ny="$pick" --set eigen%estimate=off \
            --set output%vtk=.false. --set output%plot=.false. \
            --set output%directory="$work/u${el}_$pick/out"
        row "uniform ${el^^}" "$tol" "${n_dofs[$pick]}" "$med_wall" "$med_peak" \
            "${n_err[$pick]}" - "$note" "${hp_wall[$tol]}"
    done
}
uniform p2 "${p2_ladder[@]}"
uniform p4 "${p4_ladder[@]}"

# --- FreeFEM graded P4 ----------------------------------------------------------------------
freefem=$(command -v FreeFem++-nw || true)
[[ -z ${FF_LOADPATH:-} && -d /usr/lib/freefem++ ]] && export FF_LOADPATH=/usr/lib/freefem++
edp=$root/scripts/bench/graded_p4.edp
ff_ok=no
if [[ -n $freefem ]]; then
    timed "$work/ffprobe" "$freefem" -nw "$edp" -order 1 -structured 2
    grep -q '^mu ' "$work/ffprobe.out" && ff_ok=yes
fi
if [[ $ff_ok == no ]]; then
    echo "# FreeFEM: not installed or without its plugins (Debian: apt-get install freefem++" \
        "libfreefem++); no FreeFEM rows"
else
    # the same discrete problem on the same graded mesh (8 layers, split 2), read back by nceig
    if command -v gmsh >/dev/null; then
        for order in 1 2 4; do
            timed "$work/ffcheck$order" "$freefem" -nw "$edp" -order "$order" -layers 8 \
                -split 2 -savemsh "$work/check.msh"
            ffmu=$(awk '/^mu / { print $2 }' "$work/ffcheck$order.out")
            printf 'Merge "%s";\nSetOrder %s;\nMesh.MshFileVersion = 2.2;\nSave "%s";\n' \
                "$work/check.msh" "$order" "$work/check$order.msh" >"$work/order.geo"
            gmsh "$work/order.geo" -0 >"$work/gmsh.log" 2>&1
            cat >"$work/check.nml" <<NML
&mesh source = 'gmsh', file = '$work/check$order.msh', dirichlet = 'top',
      neumann = 'left right', contact = 'bottom' /
&analysis kind = 'eigen', lambda = 5.0 /
&eigen estimate = 'off' /
&output directory = '$work/check_out', vtk = .false., plot = .false. /
NML
            "$nceig" "$work/check.nml" >/dev/null 2>&1
            ncmu=$(key "$work/check_out/summary.json" lowest_positive_mu)
            echo "# check, graded mesh 8 layers split 2, P$order: FreeFEM $ffmu, nceig $ncmu," \
                "apart $(relerr "$ffmu" "$ncmu")"
        done
    fi
    declare -A ff_err ff_dofs
    ff_last=
    for cfg in "${ff_ladder[@]}"; do
        timed "$work/ff_$cfg" "$freefem" -nw "$edp" -layers "${cfg%:*}" -split "${cfg#*:}"
        grep -q '^mu ' "$work/ff_$cfg.out" ||
            { echo "bench_hp_table: FreeFEM $cfg failed: $(tail -3 "$work/ff_$cfg.out")" >&2; exit 1; }
        first_wall[ff_$cfg]=$wall first_peak[ff_$cfg]=$peak
        ff_err[$cfg]=$(relerr "$(awk '/^mu / { print $2 }' "$work/ff_$cfg.out")" "$mu_true")
        ff_dofs[$cfg]=$(awk '/^mu / { print $4 }' "$work/ff_$cfg.out")
        echo "# ladder FreeFEM layers:split $cfg: ${ff_dofs[$cfg]} dofs, error ${ff_err[$cfg]}," \
            "$wall s ($(awk '/^mu / { printf "%.1f", $8 }' "$work/ff_$cfg.out") s on FreeFEM's clock)"
        ff_last=$cfg
        meets "${ff_err[$cfg]}" "${tolerances[-1]}" "$mu_true" "$mu_unc" && break
    done
    for tol in "${tolerances[@]}"; do
        choose ff_err "$tol" "$ff_last" "${ff_ladder[@]}"
        note="stalls at ${ff_err[$pick]} with ${ff_dofs[$pick]} dofs (layers:split $pick, the ladder's last)"
        [[ $met == yes ]] && note="met at layers:split $pick"
        repeat "ff_$pick" "$freefem" -nw "$edp" -layers "${pick%:*}" -split "${pick#*:}"
        row "FreeFEM graded P4" "$tol" "${ff_dofs[$pick]}" "$med_wall" "$med_peak" \
            "${ff_err[$pick]}" - "$note" "${hp_wall[$tol]}"
    done
fi

# --- critical lambdas -----------------------------------------------------------------------
thr_tol=${THR_TOLERANCE:-1e-10}
threshold() {
    local tag=$1 s
    shift
    repeat "$tag" "$nceig" "$root/input/threshold_adapt.nml" --set adapt%tolerance=$thr_tol \
        --set output%plot=.false. --set output%directory="$work/$tag/out" "$@"
    s=$work/$tag/out/summary.json
    [[ -f $s ]] || { echo "bench_hp_table: $tag failed: $(cat "$work/$tag.err")" >&2; exit 1; }
    err=$(awk -v a="$(key "$s" lambda_critical_plus)" -v b="$lp_true" \
              -v c="$(key "$s" lambda_critical_minus)" -v d="$lm_true" \
              'BEGIN { e = (a - b) / b; f = (c - d) / d; e = e < 0 ? -e : e;
                       f = f < 0 ? -f : f; printf "%.1e", (e > f ? e : f) }')
    bar=$(awk -v a="$(key "$s" lambda_critical_plus_error_bar)" \
              -v b="$(key "$s" lambda_critical_minus_error_bar)" \
              'BEGIN { printf "%.1e", (a > b ? a : b) }')
    dofs=$(key "$s" n_dofs)
    note=met
    [[ $(jq -r .adapt_converged "$s") == true ]] || note="not met: $(why "$tag")"
}
thr_hp_wall=
timed "$work/thr_probe" "$nceig" "$root/input/threshold_adapt.nml" --set adapt%strategy=hp \
    --set adapt%tolerance=1e-4 --set output%directory="$work/thr_probe/out"
if [[ -f $work/thr_probe/out/summary.json ]]; then
    threshold thr_hp --set adapt%strategy=hp
    thr_hp_wall=$med_wall
    row "nceig hp, lambda+-" "$thr_tol" "$dofs" "$med_wall" "$med_peak" "$err" "$bar" \
        "$note" "$thr_hp_wall"
else
    rows+=("| nceig hp, lambda+- | $thr_tol | - | - | - | - | - | - | not available: $(head -1 "$work/thr_probe.err" | sed 's/^nceig: //') |")
fi
# the h loop of the thresholds has no floating-point floor stop: past about 1e5 dofs its bar
# grows with the round-off part (measured: 2.8e-9 at 117k dofs, 4.7e-9 at 339k, 1.8 GB), so
# it is capped
threshold thr_h --set adapt%max_dofs="${THR_MAX_DOFS:-120000}"
row "nceig h P3, lambda+-" "$thr_tol" "$dofs" "$med_wall" "$med_peak" "$err" "$bar" "$note" \
    "$thr_hp_wall"

echo
echo "| method | tolerance | dofs | wall s | peak MB | true error | own bar | time / hp | note |"
echo "|---|---|---|---|---|---|---|---|---|"
printf '%s\n' "${rows[@]}"
echo
echo "# truth: c_n = $mu_true +- $mu_unc, lambda+- = $lp_true, $lm_true +- $l_unc (tests/data/truths.csv);"
echo "# true errors and bars relative; met = |error| <= tolerance + the truth's relative uncertainty"
echo "# uptime at end: $(uptime)"
