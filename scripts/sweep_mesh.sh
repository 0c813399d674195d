#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Mesh refinement sweep: the lowest positive eigenvalue of TEMPLATE.nml on meshes of growing
# fineness, for several element and mesh types, its Richardson-extrapolated limits and the
# measured accuracy/time trade. See docs/meshes.md, "Mesh refinement sweeps".
#
#   scripts/sweep_mesh.sh [-e FAMILIES] [-n SIZES] [-j JOBS] [-o OUTDIR] [-g GEO] [-s] [--] TEMPLATE.nml
#   scripts/sweep_mesh.sh --run OUTDIR FAMILY N      (one run; what a SLURM array task does)
#   scripts/sweep_mesh.sh --collect OUTDIR           (tables and plots from the runs present)
#
# Paths (the working folder, OUTDIR, the install prefix) may hold any character but a newline
# (nceig takes no newline in a --set value): they travel as arguments, environment variables
# and files of NUL-separated words, never as text a shell or GNU parallel parses.
set -uo pipefail

root=$(cd -- "$(dirname -- "$0")/.." && pwd)
self="$root/scripts/sweep_mesh.sh"
# shellcheck source=lib/slurm_jobs.sh
source "$root/scripts/lib/slurm_jobs.sh" || exit 2
DEFAULT_FAMILIES=p1:right,p1:left,q1,p2,q2,delaunay
DEFAULT_SIZES=4,8,16,32,64

usage() {
    cat <<EOF
usage: scripts/sweep_mesh.sh [-e FAMILIES] [-n SIZES] [-j JOBS] [-o OUTDIR] [-g GEO] [-s] [--] TEMPLATE.nml
  -e FAMILIES  comma list of element[:mesh]: element p1, q1, p2, q2, p3, p4; mesh 'right'
               or 'left' (structured triangles, default: the template's diagonal) or 'delaunay'
               (a Gmsh mesh, triangles only); 'delaunay' alone means p1:delaunay.
               Default: $DEFAULT_FAMILIES
  -n SIZES     comma list of N, the mesh size being h = 1/N. Default: $DEFAULT_SIZES
  -j JOBS      runs at a time, through GNU parallel (default 1; use 1 for timings you want
               to quote); with more than one, each run has one BLAS thread
  -o OUTDIR    default: output/sweep_<template stem>
  -g GEO       the Gmsh geometry of a template whose body is a Gmsh mesh (&mesh source =
               'gmsh'): its 'delaunay' families mesh GEO with h = 1/N; its physical groups
               must carry the names the template uses. Only 'delaunay' families refine such a
               body, and without -g the sweep refuses it. A rectangle template needs no -g:
               its 'delaunay' families mesh the template's own width x height rectangle.
  -s           write a SLURM job-array script and its collection step instead of running
A TEMPLATE whose name starts with '-' follows '--' (or is written ./-name.nml).
Each (family, N) is one nceig process in OUTDIR/runs/<family>_n<N>/; a run whose
summary.json exists is not redone. Outputs: OUTDIR/results.csv, extrapolation.csv,
tradeoff.csv, convergence.png, tradeoff.png. nceig is \$NCEIG, else build/, else on PATH.
EOF
}

die() { echo "sweep_mesh: $*" >&2; exit 2; }

# absolute_dir VARIABLE DIR: sets VARIABLE to the absolute path of the folder DIR, exact even
# when DIR ends in a newline (which a command substitution drops) and whatever CDPATH says.
absolute_dir() {  # (its locals have names no caller uses: printf -v would set those)
    local absolute_dir_in=$2 absolute_dir_out
    [[ $absolute_dir_in == /* ]] || absolute_dir_in=./$absolute_dir_in
    absolute_dir_out=$(cd -- "$absolute_dir_in" && pwd && echo x) || return 1
    printf -v "$1" '%s' "${absolute_dir_out%$'\n'x}"
}

# A name as one printable line: newlines and other controls shown as $'...' escapes.
printable() { if [[ $1 == *[[:cntrl:]]* ]]; then printf '%q' "$1"; else printf '%s' "$1"; fi; }

# ------------------------------------------------------------------------- programs

# The nceig of this tree first (a source tree's build/, or an install's bin/ as nceig-sweep
# sets NCEIG), so an older nceig on PATH never answers for this one; PATH last.
find_nceig() {
    local exe
    if [[ -n ${NCEIG:-} ]]; then exe=$NCEIG
    elif [[ -x $root/build/nceig ]]; then exe=$root/build/nceig
    elif command -v nceig >/dev/null 2>&1; then exe=$(command -v nceig)
    else die "nceig not found: not in $root/build nor on PATH (run scripts/dev/build.sh Release, or set NCEIG)"
    fi
    [[ -x $exe ]] || die "NCEIG=$(printable "$exe") is not an executable"
    local dir=.
    [[ $exe == */* ]] && dir=${exe%/*}/
    absolute_dir dir "$dir" || exit 2
    printf '%s\n' "$dir/${exe##*/}"
}

# nceig-extrapolate is built next to nceig; a wrapped NCEIG (tests) falls back on PATH, build/.
find_extrapolate() {
    local nceig=$1 candidate
    for candidate in "$(dirname "$nceig")/nceig-extrapolate" "$(command -v nceig-extrapolate)" \
                     "$root/build/nceig-extrapolate"; do
        [[ -n $candidate && -x $candidate ]] && { echo "$candidate"; return 0; }
    done
    die "nceig-extrapolate not found next to $nceig, on PATH or in $root/build"
}

# ------------------------------------------------------------------------- families

# "p1:right" -> "p1 right"; "q1" -> "q1 quad"; "delaunay" -> "p1 delaunay"; "p2" -> "p2 " (the
# template's diagonal). Prints nothing for a malformed family.
parse_family() {
    local family=$1 element mesh
    [[ $family == delaunay ]] && family=p1:delaunay
    element=${family%%:*}
    mesh=
    [[ $family == *:* ]] && mesh=${family#*:}
    case $element in
        p1 | p2 | p3 | p4) [[ -z $mesh || $mesh =~ ^(right|left|delaunay)$ ]] || return 0 ;;
        q1 | q2) [[ -z $mesh ]] || return 0; mesh=quad ;;
        *) return 0 ;;
    esac
    echo "$element $mesh"
}

run_name() { local family=${1//:/-}; printf '%s_n%04d' "$family" "$2"; }

# template_value FILE GROUP VARIABLE: the value the namelist FILE gives VARIABLE in &GROUP,
# unquoted and lower-cased ('' when not given). Comments (! outside quotes) are dropped and
# the file read as one text, so a group may span lines or share one with others.
template_value() {
    awk -v group="$2" -v variable="$3" -v q="'" -v dq='"' '
        function strip(s,    i, c, quote, out) {  # s up to a ! outside quotes
            quote = ""; out = ""
            for (i = 1; i <= length(s); i++) {
                c = substr(s, i, 1)
                if (quote == "" && c == "!") break
                if (quote == "" && (c == q || c == dq)) quote = c
                else if (c == quote) quote = ""
                out = out c
            }
            return out
        }
        { text = text " " strip($0) }
        END {
            text = tolower(text); gsub(/[\t\r]/, " ", text)
            if (!match(text, "&" group "[ ,]")) exit
            rest = substr(text, RSTART + RLENGTH); quote = ""; body = ""
            for (i = 1; i <= length(rest); i++) {  # the group ends at a / outside quotes
                c = substr(rest, i, 1)
                if (quote == "" && c == "/") break
                if (quote == "" && (c == q || c == dq)) quote = c
                else if (c == quote) quote = ""
                body = body c
            }
            pattern = "(^|[ ,])" variable " *= *(" q "[^" q "]*" q "|" dq "[^" dq "]*" dq "|[^ ,]+)"
            if (match(body, pattern)) {
                value = substr(body, RSTART, RLENGTH)
                sub(/^[ ,]*[a-z_0-9]+ *= */, "", value)
                if (substr(value, 1, 1) == q || substr(value, 1, 1) == dq)
                    value = substr(value, 2, length(value) - 2)
                print value
            }
        }' "$1"
}

# write_rectangle_geo FILE WIDTH HEIGHT: the Gmsh geometry of nceig's rectangle (corner at
# the origin), with the side names as physical groups, so that a template's dirichlet,
# neumann and contact sides name the same sides on its Delaunay meshes.
write_rectangle_geo() {
    cat >"$1" <<GEO
// The rectangle of the sweep's template, written by sweep_mesh.sh for its delaunay families.
Point(1) = {0, 0, 0, 1e22};
Point(2) = {$2, 0, 0, 1e22};
Point(3) = {$2, $3, 0, 1e22};
Point(4) = {0, $3, 0, 1e22};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("body") = {1};
Mesh.Algorithm = 5;
GEO
}

# ------------------------------------------------------------------------- one run

# --run OUTDIR FAMILY N: make the input from OUTDIR/template.nml, run nceig under
# /usr/bin/time, record the outcome in runs/<name>/status. Exit 0 when done or reused.
run_one() {
    local outdir=$1 family=$2 n=$3 parsed element mesh dir input nceig rc line status
    local mesh_s=0 t0 t1
    parsed=$(parse_family "$family")
    [[ -n $parsed ]] || die "malformed family '$family'"
    absolute_dir outdir "$outdir" || die "$(printable "$outdir"): no such folder"
    read -r element mesh <<<"$parsed"
    dir="$outdir/runs/$(run_name "$family" "$n")"
    if [[ -s $dir/output/summary.json ]]; then
        echo "reused  $family N=$n"
        return 0
    fi
    nceig=$(find_nceig) || exit 2
    command -v jq >/dev/null 2>&1 || die "jq not found: it reads summary.json (Debian package jq)"
    rm -rf "$dir"
    mkdir -p "$dir" || die "cannot create $dir"
    printf 'family=%s\nelement=%s\nmesh=%s\nn=%s\n' "$family" "$element" "$mesh" "$n" \
        >"$dir/run.info"
    input="$dir/input.nml"
    cp "$outdir/template.nml" "$input"

    # The template stays as it is; the mesh and the output folder of this run are
    # command-line overrides, checked by nceig like the file's own values.
    local -a settings
    if [[ $mesh == delaunay ]]; then
        local order=${element#p}
        if [[ ! -f $root/scripts/make_mesh.sh ]]; then
            echo "failed: scripts/make_mesh.sh is missing (Gmsh meshes)" >"$dir/status"
        elif [[ ! -f $outdir/geometry.geo ]]; then
            echo "failed: $outdir/geometry.geo is missing (start the sweep again)" >"$dir/status"
        else
            t0=$(date +%s.%N)
            if ! bash "$root/scripts/make_mesh.sh" "$n" "$order" "$dir/mesh.msh" msh41 \
                    "$outdir/geometry.geo" >"$dir/mesh.log" 2>&1; then
                echo "failed: mesh generation: $(tail -n 1 "$dir/mesh.log")" >"$dir/status"
            fi
            t1=$(date +%s.%N)
            mesh_s=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')
        fi
        settings=(--set mesh%source=gmsh --set "mesh%file=$dir/mesh.msh"
                  --set "mesh%element=$element")
    else
        settings=(--set mesh%source=rectangle --set "mesh%nx=$n" --set "mesh%ny=$n"
                  --set "mesh%element=$element")
        [[ -n $mesh && $mesh != quad ]] && settings+=(--set "mesh%diagonal=$mesh")
    fi
    settings+=(--set "output%directory=$dir/output")
    echo "$mesh_s" >"$dir/mesh_time"
    if [[ -f $dir/status ]]; then
        echo "FAILED  $family N=$n: $(cut -d' ' -f2- "$dir/status")"
        return 1
    fi
    # What was run, for a reader to repeat: quoted for bash, whatever the paths hold.
    printf 'nceig input.nml' >"$dir/command"
    printf ' %q' "${settings[@]}" >>"$dir/command"
    echo >>"$dir/command"

    if [[ -x /usr/bin/time ]]; then
        /usr/bin/time -f '%e %M' -o "$dir/time.txt" "$nceig" "$input" "${settings[@]}" \
            >"$dir/stdout.log" 2>"$dir/stderr.log"
        rc=$?
    else  # no peak memory without GNU time (Debian package 'time')
        t0=$(date +%s.%N)
        "$nceig" "$input" "${settings[@]}" >"$dir/stdout.log" 2>"$dir/stderr.log"
        rc=$?
        t1=$(date +%s.%N)
        awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f\n", b - a }' >"$dir/time.txt"
    fi
    # The body solved must be the one this family refines: a rectangle for the structured
    # families, the mesh made here for 'delaunay', never whatever the template says.
    local solved want=rectangle
    [[ $mesh == delaunay ]] && want=gmsh
    if [[ $rc -eq 0 && -s $dir/output/summary.json ]]; then
        solved=$(json_value "$dir/output/summary.json" mesh_source)
        if [[ $solved != "$want" ]]; then
            echo "failed: nceig solved a '$solved' mesh, not the family's $want" >"$dir/status"
            echo "FAILED  $family N=$n: nceig solved a '$solved' mesh, not the family's $want"
            return 1
        fi
    fi
    if [[ $rc -eq 0 && -s $dir/output/summary.json ]]; then
        echo ok >"$dir/status"
        echo "done    $family N=$n: mu = $(json_value "$dir/output/summary.json" \
            lowest_positive_mu), $(awk '{ print $1 }' "$dir/time.txt" | tail -n 1) s"
        return 0
    fi
    line=$(tail -n 1 "$dir/stderr.log" 2>/dev/null)
    status=$(grep -m 1 -E 'Command (exited|terminated)' "$dir/time.txt" 2>/dev/null)
    [[ $status == *signal\ 9* ]] && status+=" (out of memory?)"
    echo "failed: exit $rc: ${line:-$status}" >"$dir/status"
    echo "FAILED  $family N=$n: exit $rc: ${line:-$status}"
    return 1
}

# Value of "key" in a summary.json, read as JSON ('' for null or absent).
json_value() {
    jq -r --arg key "$2" '.[$key] // empty' "$1"
}

# ------------------------------------------------------------------------- collection

collect() {
    local outdir=$1 nceig extrapolate dir tmp
    [[ -d $outdir/runs ]] || die "$outdir/runs: no runs to collect"
    tmp=$(mktemp -d) || exit 1
    {
        echo "family,element,mesh,n,h,n_dofs,n_contact,solver,lowest_positive_mu,time_total_s,time_output_s,time_mesh_s,wall_s,peak_rss_mb,status,message,error_bar"
        for dir in "$outdir"/runs/*/; do
            [[ -f $dir/run.info ]] || continue
            collect_row "$dir"
        done | sort -t, -k1,1 -k4,4n
    } >"$tmp/results.csv"
    mv "$tmp/results.csv" "$outdir/results.csv"

    nceig=$(find_nceig) || exit 2
    extrapolate=$(find_extrapolate "$nceig") || exit 2
    command -v jq >/dev/null 2>&1 || die "jq not found: it reads summary.json (Debian package jq)"
    local ok=1
    if "$extrapolate" "$outdir/results.csv" >"$tmp/extrapolation.csv"; then
        mv "$tmp/extrapolation.csv" "$outdir/extrapolation.csv"
    else
        ok=0
    fi
    if "$extrapolate" --tradeoff "$outdir/results.csv" >"$tmp/tradeoff.csv"; then
        mv "$tmp/tradeoff.csv" "$outdir/tradeoff.csv"
    else
        rm -f "$outdir/tradeoff.csv"
        ok=0
    fi
    if [[ $ok -eq 1 ]]; then
        plot "$outdir" "$tmp"
    fi
    rm -rf "$tmp"
    print_tables "$outdir"
    [[ $ok -eq 1 ]]
}

collect_row() {
    local dir=$1 family element mesh n summary status message wall rss mesh_s
    family=$(sed -n 's/^family=//p' "$dir/run.info")
    element=$(sed -n 's/^element=//p' "$dir/run.info")
    mesh=$(sed -n 's/^mesh=//p' "$dir/run.info")
    n=$(sed -n 's/^n=//p' "$dir/run.info")
    summary="$dir/output/summary.json"
    mesh_s=$(cat "$dir/mesh_time" 2>/dev/null || echo 0)
    local h
    h=$(awk -v n="$n" 'BEGIN { printf "%.17g", 1 / n }')
    if [[ -s $summary ]]; then
        [[ -z $mesh ]] && mesh=$(json_value "$summary" diagonal)
        # The last line of time.txt is "wall_s peak_rss_kb" (GNU time) or "wall_s".
        read -r wall rss < <(tail -n 1 "$dir/time.txt" 2>/dev/null)
        [[ -n ${rss:-} ]] && rss=$(awk -v k="$rss" 'BEGIN { printf "%.1f", k / 1024 }')
        echo "$family,$element,$mesh,$n,$h,$(json_value "$summary" n_dofs),$(json_value "$summary" n_contact),$(json_value "$summary" solver),$(json_value "$summary" lowest_positive_mu),$(json_value "$summary" time_total_s),$(json_value "$summary" time_output_s),$mesh_s,${wall:-},${rss:-},ok,,$(json_value "$summary" lowest_positive_error_bar)"
    else
        status=$(cat "$dir/status" 2>/dev/null || echo "failed: not finished")
        [[ $status == ok ]] && status="failed: summary.json missing"
        message=$(echo "${status#failed: }" | tr ',' ';')
        echo "$family,$element,$mesh,$n,$h,,,,,,,$mesh_s,,,failed,$message,"
    fi
}

# 1-based index of the column called NAME in the header of a CSV file.
csv_column() {
    awk -F, -v name="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == name) print i; exit }' "$1"
}

print_tables() {
    local outdir=$1
    echo
    echo "results ($outdir/results.csv):"
    awk -F, 'NR == 1 { next }
        { printf "  %-12s N = %-5s mu = %-20s bar %-9s time %9.3g s  peak %8.1f MB  %s\n", \
              $1, $4, ($15 == "ok" ? $9 : "-"), ($17 == "" ? "-" : sprintf("%.3g", $17)), \
              $10, $14, ($15 == "ok" ? "" : "FAILED: " $16) }' \
        "$outdir/results.csv"
    if [[ -s $outdir/extrapolation.csv ]]; then
        echo "extrapolation ($outdir/extrapolation.csv):"
        awk -F, 'NR == 1 { next }
            { printf "  %-12s N = %s,%s,%s  limit %-20s order %-8.5s est %-9s bar %-9s %s\n", \
                  $1, $5, $6, $7, ($9 == "" ? "-" : $9), ($10 == "" ? "-" : $10), \
                  ($13 == "" ? "-" : sprintf("%.3g", $13)), \
                  ($14 == "" ? "-" : sprintf("%.3g", $14)), \
                  ($17 == "yes" ? "(reference) " : "") $18 }' \
            "$outdir/extrapolation.csv"
    fi
}

# ------------------------------------------------------------------------- plots

plot() {
    local outdir=$1 tmp=$2 terminal families n_families
    command -v gnuplot >/dev/null 2>&1 || { echo "sweep_mesh: gnuplot not found: no plots" >&2; return 0; }
    terminal="pngcairo size 1400,560 font 'Sans,11'"
    gnuplot -e 'set terminal pngcairo' >/dev/null 2>&1 || terminal="png size 1400,560"

    # One data block per family (gnuplot 'index'), in the order of extrapolation.csv.
    families=$(awk -F, 'NR > 1 { print $1 }' "$outdir/extrapolation.csv")
    n_families=$(echo "$families" | grep -c .)
    local col_h col_mu col_status col_n col_time col_err family reference
    col_h=$(csv_column "$outdir/results.csv" h)
    col_mu=$(csv_column "$outdir/results.csv" lowest_positive_mu)
    col_status=$(csv_column "$outdir/results.csv" status)
    : >"$tmp/mu.dat"; : >"$tmp/limits.dat"; : >"$tmp/tradeoff.dat"
    for family in $families; do
        awk -F, -v f="$family" -v ch="$col_h" -v cm="$col_mu" -v cs="$col_status" \
            'NR > 1 && $1 == f && $cs == "ok" && $cm != "" { print $ch, $cm }' \
            "$outdir/results.csv" | sort -g -r >>"$tmp/mu.dat"
        printf '\n\n' >>"$tmp/mu.dat"
        # The limit as a dashed level over the family's range of h (nothing without a limit).
        awk -F, -v f="$family" -v ch="$col_h" -v cm="$col_mu" -v cs="$col_status" \
            'NR > 1 && $1 == f && $cs == "ok" && $cm != "" { print $ch }' \
            "$outdir/results.csv" | sort -g >"$tmp/h.txt"
        local limit
        limit=$(awk -F, -v f="$family" 'NR > 1 && $1 == f { print $9 }' "$outdir/extrapolation.csv")
        if [[ -n $limit && -s $tmp/h.txt ]]; then
            printf '%s %s\n%s %s\n' "$(head -n 1 "$tmp/h.txt")" "$limit" \
                "$(tail -n 1 "$tmp/h.txt")" "$limit" >>"$tmp/limits.dat"
        else
            echo "NaN NaN" >>"$tmp/limits.dat"
        fi
        printf '\n\n' >>"$tmp/limits.dat"
        col_n=$(csv_column "$outdir/tradeoff.csv" n)
        col_time=$(csv_column "$outdir/tradeoff.csv" time_s)
        col_err=$(csv_column "$outdir/tradeoff.csv" relative_error)
        awk -F, -v f="$family" -v cn="$col_n" -v ct="$col_time" -v ce="$col_err" \
            'NR > 1 && $1 == f && $ce > 0 { print $cn, $ct, $ce, 1 / $cn }' \
            "$outdir/tradeoff.csv" | sort -g >>"$tmp/tradeoff.dat"
        printf '\n\n' >>"$tmp/tradeoff.dat"
    done
    reference=$(awk -F, 'NR == 2 { print $13 }' "$outdir/tradeoff.csv")
    # Tics at h = 1/N labelled '1/N': every N of the sweep, or only powers of two when many.
    local xtics
    xtics=$(awk -F, -v cn="$(csv_column "$outdir/results.csv" n)" -v cs="$col_status" \
        'NR > 1 && $cs == "ok" { seen[$cn] = 1 }
         END { m = 0; for (n in seen) m++
               for (n in seen) if (m <= 8 || and_pow2(n)) printf "%s\"1/%d\" %.17g", \
                   (k++ ? ", " : ""), n, 1 / n }
         function and_pow2(n) { while (n > 1 && n % 2 == 0) n /= 2; return n == 1 }' \
        "$outdir/results.csv")
    local ref_limit
    ref_limit=$(awk -F, 'NR == 2 { print $12 }' "$outdir/tradeoff.csv")

    cat >"$tmp/plot.gp" <<EOF
set terminal $terminal
set datafile missing 'NaN'
# Distinct colours that read on white (gnuplot's 5th default is a pale yellow).
palette = "#1f77b4 #d62728 #2ca02c #9467bd #ff7f0e #17becf #8c564b #e377c2 #7f7f7f #bcbd22"
do for [i=1:10] { set linetype i lc rgb word(palette, i) }
names = "$(echo $families)"
set key outside right top box opaque
set grid
set style line 100 lc rgb '#888888' dt 3
set output 'convergence.png'
set multiplot layout 1,2
set logscale x
set autoscale xfix
set offsets graph 0.04, graph 0.04, 0, 0
set xtics ($xtics)
set xlabel 'mesh size h'
set title 'lowest positive mu; dashed: Richardson limits'
set ylabel 'lowest positive mu'
set format y '%.4f'
unset key
plot for [i=1:$n_families] 'mu.dat' index (i-1) using 1:2 with linespoints lw 2 pt 7 lc i title word(names, i), \
     for [i=1:$n_families] 'limits.dat' index (i-1) using 1:2 with lines dt 2 lw 1.5 lc i notitle
set key outside right top box opaque
set logscale y
set format y '10^{%L}'
set title "relative error against the reference limit $ref_limit ($reference)"
set ylabel 'relative error'
plot for [i=1:$n_families] 'tradeoff.dat' index (i-1) using 4:3 with linespoints lw 2 pt 7 lc i title word(names, i)
unset multiplot

set output 'tradeoff.png'
set terminal $terminal
set size 1,1
set xtics autofreq
unset offsets
set autoscale x
set title "accuracy against compute time (labels: N); reference limit $ref_limit ($reference)"
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'compute time [s] (time_total_s - time_output_s)' noenhanced
set ylabel 'relative error of the lowest positive mu'
set arrow from graph 0, first 1e-2 to graph 1, first 1e-2 nohead ls 100
set arrow from graph 0, first 1e-3 to graph 1, first 1e-3 nohead ls 100
set arrow from graph 0, first 1e-4 to graph 1, first 1e-4 nohead ls 100
plot for [i=1:$n_families] 'tradeoff.dat' index (i-1) using 2:3 with linespoints lw 2 pt 7 lc i title word(names, i), \
     for [i=1:$n_families] 'tradeoff.dat' index (i-1) using 2:3:(sprintf('%d', \$1)) with labels offset 0,0.8 font ',8' tc lt i notitle
EOF
    # run in $tmp with relative names: no path is part of gnuplot's text
    if (cd -- "$tmp" && gnuplot plot.gp) 2>"$tmp/gnuplot.log"; then
        mv "$tmp/convergence.png" "$tmp/tradeoff.png" "$outdir/"
    else
        echo "sweep_mesh: gnuplot failed: $(head -n 3 "$tmp/gnuplot.log")" >&2
    fi
}

# ------------------------------------------------------------------------- engines

# The runs of a sweep, one per line of OUTDIR/slurm/tasks: "FAMILY<tab>N" (slurm_task). Both
# engines read this list; a run is `sweep_mesh.sh --run OUTDIR FAMILY N`.
write_tasks() {
    local outdir=$1 run
    shift
    mkdir -p -- "$outdir/slurm" || die "cannot create $(printable "$outdir")/slurm"
    for run in "$@"; do
        # shellcheck disable=SC2086  # "FAMILY N": checked names and digits
        slurm_task $run || exit 2
    done >"$outdir/slurm/tasks"
}

# SLURM: a job array over the task list and a collection job after it, written by
# scripts/lib/slurm_jobs.sh; what the jobs run (this script, OUTDIR, the nceig to use) is in
# OUTDIR/slurm/*.argv as NUL-separated words, so no path is part of any script's text.
write_slurm() {
    local outdir=$1 jobs=$2 nceig=$3 n_runs=$4
    slurm_write_argv "$outdir/slurm/task.argv" env "NCEIG=$nceig" bash "$self" --run "$outdir"
    slurm_write_argv "$outdir/slurm/collect.argv" env "NCEIG=$nceig" bash "$self" --collect "$outdir"
    slurm_write_jobs "$outdir" sweep "$jobs" 1 || exit 2
    echo "sweep_mesh: wrote slurm_sweep.sh ($n_runs array tasks, at most $jobs at a time),"
    echo "  slurm_collect.sh and slurm_submit.sh in $outdir; on the cluster run (quoted for bash)"
    printf '  bash %q [--time=... --mem=... further sbatch options]\n' "$outdir/slurm_submit.sh"
}

# Local runs through GNU parallel: its command is fixed text, the paths reach it as
# environment variables and the task list as a file (GNU parallel hands its command to a
# shell, so no path may be part of it). Each invocation keeps a job log (log/*.joblog: exit
# status and time of every run). Resuming is the run folders' business, not --resume-failed:
# a run with a summary.json is reused and any other is redone, which stays right when the
# families or sizes change between calls (GNU parallel resumes by job number) or a run
# folder is removed.
run_parallel() {
    local outdir=$1 jobs=$2 log=$3
    SWEEP_SCRIPT=$self SWEEP_OUTDIR=$outdir PARALLEL_SHELL=$BASH \
        parallel --jobs "$jobs" --joblog "${log%.log}.joblog" --colsep '\t' \
            --arg-file "$outdir/slurm/tasks" \
            'bash "$SWEEP_SCRIPT" --run "$SWEEP_OUTDIR" {1} {2}' </dev/null 2>&1 | tee -a "$log"
}

# Without GNU parallel: the same runs, at most JOBS at a time, from this shell.
run_builtin() {
    local outdir=$1 jobs=$2 log=$3 running=0 family n
    while IFS=$'\t' read -r family n; do
        if ((running >= jobs)); then
            wait -n
            running=$((running - 1))
        fi
        bash "$self" --run "$outdir" "$family" "$n" </dev/null 2>&1 | tee -a "$log" &
        running=$((running + 1))
    done <"$outdir/slurm/tasks"
    wait
}

# ------------------------------------------------------------------------- main

case ${1:-} in
    --run) [[ $# -eq 4 ]] || die "usage: sweep_mesh.sh --run OUTDIR FAMILY N"
           run_one "$2" "$3" "$4"; exit $? ;;
    --collect) [[ $# -eq 2 ]] || die "usage: sweep_mesh.sh --collect OUTDIR"
               absolute_dir outdir "$2" || die "$(printable "$2"): no such folder"
               collect "$outdir"; exit $? ;;
    --help | -h) usage; exit 0 ;;
esac

families=$DEFAULT_FAMILIES sizes=$DEFAULT_SIZES jobs=1 outdir= slurm=0 geometry=
while getopts ':e:n:j:o:g:sh' option; do
    case $option in
        e) families=$OPTARG ;;
        n) sizes=$OPTARG ;;
        j) jobs=$OPTARG ;;
        o) outdir=$OPTARG ;;
        g) geometry=$OPTARG ;;
        s) slurm=1 ;;
        h) usage; exit 0 ;;
        :) die "option -$OPTARG needs a value" ;;
        *) die "unknown option -$OPTARG (see --help; a template named -x.nml follows --)" ;;
    esac
done
shift $((OPTIND - 1))
[[ $# -eq 1 ]] || { usage >&2; exit 2; }
template=$1
# Names go to cp, awk and basename as ./NAME when relative, so that none is read as an option
# (-n.nml, --help.nml) or, by awk, as an assignment (a=b.nml).
[[ $template == *$'\n'* ]] &&
    die "template $(printable "$template"): a newline in its name is not supported (rename it)"
[[ -n $template && $template != /* ]] && template=./$template
[[ -f $template ]] || die "$(printable "$template"): no such template file"
[[ -n $geometry && $geometry != /* ]] && geometry=./$geometry
[[ $jobs =~ ^[1-9][0-9]*$ ]] || die "-j $jobs: expected a positive integer"
IFS=, read -r -a family_list <<<"$families"
IFS=, read -r -a size_list <<<"$sizes"
((${#family_list[@]} > 0)) || die "-e: no family given"
((${#size_list[@]} > 0)) || die "-n: no size given"
for family in "${family_list[@]}"; do
    [[ -n $(parse_family "$family") ]] || die "-e: malformed family '$family': expected element[:mesh] with element p1, q1, p2, q2, p3 or p4 and mesh right, left or delaunay (triangles only), or 'delaunay'"
done
for n in "${size_list[@]}"; do
    [[ $n =~ ^[1-9][0-9]*$ ]] || die "-n: '$n' is not a positive integer"
done
# The body: a sweep refines the template's own geometry, never another one.
source=$(template_value "$template" mesh source)
case ${source:-rectangle} in
    rectangle)
        [[ -z $geometry ]] || die "-g $(printable "$geometry"): the body of $template is its rectangle (&mesh source = 'rectangle'); -g is for a template whose &mesh source is 'gmsh'"
        width=$(template_value "$template" mesh width)
        height=$(template_value "$template" mesh height)
        width=${width:-1.0} height=${height:-1.0}
        width=${width//d/e} height=${height//d/e}
        # plain numbers only: they are written into the Gmsh geometry of the delaunay families
        number='^[+]?([0-9]+[.]?[0-9]*|[.][0-9]+)(e[-+]?[0-9]+)?$'
        [[ $width =~ $number && $height =~ $number ]] &&
            awk -v w="$width" -v h="$height" 'BEGIN { exit !(w + 0 > 0 && h + 0 > 0) }' \
            || die "$template: &mesh width = $width, height = $height: expected positive numbers" ;;
    gmsh)
        for family in "${family_list[@]}"; do
            [[ $(parse_family "$family") == *' delaunay' ]] || die "$template: &mesh source = 'gmsh': family '$family' would solve a rectangle, not this body; only 'delaunay' families (e.g. -e p1:delaunay,p2:delaunay) refine a Gmsh body"
        done
        [[ -n $geometry ]] || die "$template: &mesh source = 'gmsh': give the body's Gmsh geometry with -g FILE.geo, which the 'delaunay' families mesh with h = 1/N"
        [[ -f $geometry ]] || die "-g $(printable "$geometry"): no such geometry file" ;;
    *) die "$template: &mesh source = '$source': expected 'rectangle' or 'gmsh'" ;;
esac
[[ -n $outdir ]] || outdir="output/sweep_$(basename -- "${template%.*}")"
mkdir -p -- "$outdir/runs" 2>/dev/null || die "cannot create $(printable "$outdir")/runs"
absolute_dir outdir "$outdir" || die "cannot enter $(printable "$outdir")"
# nceig takes its output folder as a --set value, which may not hold a newline.
[[ $outdir == *$'\n'* ]] &&
    die "output folder $(printable "$outdir"): a newline in its path is not supported (nceig takes none in --set)"
# Resuming reuses runs: only with the same template, else results of two scenes would mix.
if [[ -f $outdir/template.nml ]] && ! cmp -s -- "$template" "$outdir/template.nml"; then
    die "$outdir holds a sweep of another template (template.nml differs from $template): choose another -o or remove it"
fi
cp -- "$template" "$outdir/template.nml"
if [[ -n $geometry ]]; then
    if [[ -f $outdir/geometry.geo ]] && ! cmp -s -- "$geometry" "$outdir/geometry.geo"; then
        die "$outdir holds a sweep of another geometry (geometry.geo differs from $(printable "$geometry")): choose another -o or remove it"
    fi
    cp -- "$geometry" "$outdir/geometry.geo"
else
    write_rectangle_geo "$outdir/geometry.geo" "$width" "$height"
fi
nceig=$(find_nceig) || exit 2

runs=()
for family in "${family_list[@]}"; do
    for n in "${size_list[@]}"; do
        runs+=("$family $n")
    done
done
write_tasks "$outdir" "${runs[@]}"

if [[ $slurm -eq 1 ]]; then
    write_slurm "$outdir" "$jobs" "$nceig" "${#runs[@]}"
    exit 0
fi

engine=parallel
if ! command -v parallel >/dev/null 2>&1; then
    engine=built-in
    echo "sweep_mesh: GNU parallel not found (Debian package parallel): the built-in runner runs the sweep" >&2
fi
echo "sweep_mesh: ${#runs[@]} runs of $template in $outdir, $jobs at a time ($engine), with $nceig"
export NCEIG=$nceig
# Runs beside each other share the cores: one BLAS thread each (alone, nceig's default).
((jobs > 1)) && export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1
mkdir -p -- "$outdir/log"
log=$(mktemp "$outdir/log/sweep_$(date +%Y%m%d_%H%M%S)_XXXX.log") || exit 1
if [[ $engine == parallel ]]; then
    run_parallel "$outdir" "$jobs" "$log"
else
    run_builtin "$outdir" "$jobs" "$log"
fi
n_reused=$(grep -c '^reused' "$log")
n_done=$(grep -c '^done' "$log")
# A run failed unless its folder says ok: this counts a run killed before it could report.
n_failed=0 failed_runs=()
for run in "${runs[@]}"; do
    read -r family n <<<"$run"
    dir="$outdir/runs/$(run_name "$family" "$n")"
    status=$(cat "$dir/status" 2>/dev/null)
    if [[ ! -s $dir/output/summary.json || $status == failed* ]]; then
        n_failed=$((n_failed + 1))
        failed_runs+=("$family N=$n: ${status#failed: }")
    fi
done
echo "sweep_mesh: ${#runs[@]} runs: $n_done done, $n_reused reused, $n_failed failed"
collect "$outdir"
collected=$?
if ((n_failed > 0)); then
    echo "sweep_mesh: failed runs (see runs/*/stderr.log; run again to retry them):" >&2
    printf '  %s\n' "${failed_runs[@]}" >&2
    exit 1
fi
exit $collected
