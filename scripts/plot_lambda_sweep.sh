#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Draw OUTDIR/lambda_sweep.png from OUTDIR/lambda_sweep.csv and OUTDIR/summary.json of an
# nceig run with kind = 'lambda_sweep': critical c_n and c_t against lambda on log y axes,
# the thresholds lambda+ and lambda- as dashed vertical lines, error bars where the sweep
# was adapted (&adapt). A 'log' sweep (one sign) is drawn against |lambda| on a log axis.
# Needs gnuplot (Debian gnuplot-nox: pngcairo) and jq.
# Usage: plot_lambda_sweep.sh OUTDIR [SUMMARY]   (SUMMARY: the summary.json to read, by
# default OUTDIR's; nceig passes its own while the set is still being staged)
set -euo pipefail
source "$(dirname "$0")/lib/plot_common.sh"
plot_begin lambda_sweep.csv "run nceig with kind = 'lambda_sweep'" "$@"
plus=$(value lambda_critical_plus)
minus=$(value lambda_critical_minus)
spacing=$(value sweep_spacing)
title="$(value element) $(value mesh_source)"
if [[ $(value mesh_source) == rectangle ]]; then
    title="$title $(value nx)x$(value ny)"
    [[ $(value element) != p* ]] || title="$title $(value diagonal)"   # triangles only
fi
# An adapted sweep solves each lambda on its own adapted mesh: the summary's mesh is only
# where every point started.
if [[ $(value sweep_n_adapted) =~ ^[1-9] ]]; then
    title="${title} start, each lambda adapted (largest estimate $(printf "%.2g" "$(value sweep_max_error_estimate)"))"
else
    title="${title}, $(value n_contact) contact nodes"
fi

# A log x axis needs one sign: |lambda| then.
xcol='($1)' xlabel='{/Symbol l}  (dimensionless)' xlog=''
if [[ $spacing == log ]]; then
    xcol='(abs($1))' xlabel='|{/Symbol l}|  (dimensionless)' xlog='set logscale x'
fi

marks=''
mark() {  # threshold value, label, side of the line for the label (left|right)
    [[ $1 != null && -n $1 ]] || return 0
    local x=$1 offset='0.6' align=left
    [[ $spacing != log ]] || x=${x#-}
    [[ $3 == right ]] || { offset='-0.6'; align=right; }
    marks+="set arrow from $x, graph 0 to $x, graph 1 nohead dashtype 2 linewidth 1.5 lc rgb '#c0392b' front; "
    marks+="set label sprintf('$2 = %.6g', $1) at $x, graph 0.93 $align offset $offset, 0 textcolor rgb '#c0392b' front; "
}
if [[ $spacing != log ]]; then
    mark "$plus" '{/Symbol l}_+' right
    mark "$minus" '{/Symbol l}_-' left
elif [[ $(value sweep_lambda_min) == -* ]]; then   # a log sweep has one sign: its threshold
    mark "$minus" '{/Symbol l}_-' right
else
    mark "$plus" '{/Symbol l}_+' right
fi

# An adapted sweep (&adapt) has an error bar per point (column 8): drawn then.
style=linespoints cn_bar='' ct_bar='' bar_title=''
if awk -F, 'NR > 1 && $8 != "" { found = 1 } END { exit !found }' "$csv"; then
    style=yerrorlines cn_bar=':(cell(2)*cell(8))' ct_bar=':(cell(3)*cell(8))'
    bar_title=' {/Symbol \261} error bar'
fi

{
    gnuplot_preamble
    cat <<GNUPLOT
set multiplot layout 2, 1 title "nceig lambda sweep: $title" font ',13'
set grid xtics ytics mytics lc rgb '#dddddd'
set logscale y
$xlog
set key top right
set xlabel "$xlabel"
$marks
set ylabel 'critical c_n = lowest positive {/Symbol m}  [E / length]'
plot $(gnuplot_string "$csv") using $xcol:(cell(2))$cn_bar skip 1 with $style pt 7 ps 0.4 lw 1.5 lc rgb '#1f77b4' title 'c_n$bar_title'
set ylabel 'critical c_t = {/Symbol m} |{/Symbol l}|  [E / length]'
plot $(gnuplot_string "$csv") using $xcol:(cell(3))$ct_bar skip 1 with $style pt 7 ps 0.4 lw 1.5 lc rgb '#2ca02c' title 'c_t$bar_title'
unset multiplot
GNUPLOT
} | gnuplot
plot_commit
