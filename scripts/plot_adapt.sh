#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Draw OUTDIR/adapt.png from OUTDIR/adapt.csv and OUTDIR/summary.json of an nceig run with
# &adapt tolerance > 0: the error estimate of the lowest positive mu against the free dofs
# (log-log, the tolerance as a dashed line) above mu with its error bar against the dofs
# (log x), one point per level. Needs gnuplot (Debian gnuplot-nox: pngcairo) and jq.
# Usage: plot_adapt.sh OUTDIR [SUMMARY]   (SUMMARY: the summary.json to read, by default
# OUTDIR's; nceig passes its own while the set is still being staged)
set -euo pipefail
source "$(dirname "$0")/lib/plot_common.sh"
plot_begin adapt.csv "run nceig with &adapt tolerance > 0" "$@"
tolerance=$(value adapt_tolerance)
title="$(value element), lambda = $(value lambda), start $(value adapt_start_dofs) dofs"

if ! awk -F, 'NR > 1 && $6 != "" { found = 1 } END { exit !found }' "$csv"; then
    echo "$0: $csv: no level has an error estimate: nothing to draw" >&2
    exit 4
fi
# the lower end of the estimate axis: a third below the smaller of the tolerance and the
# smallest estimate, so that the tolerance line never sits on the frame
ymin=$(awk -F, -v t="$tolerance" 'NR > 1 && $6 != "" && (m == "" || $6 < m) { m = $6 }
    END { if (m == "" || t < m) m = t; print m / 3 }' "$csv")
{
    gnuplot_preamble
    cat <<GNUPLOT
set multiplot layout 2, 1 title "nceig adaptive refinement: $title" font ',13'
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set logscale x
set xlabel 'free dofs'
set logscale y
set format y '10^{%L}'
set key top right
set ylabel 'relative error estimate of {/Symbol m}'
set yrange [$ymin:*]
plot '$csv' using 2:(cell(6)) skip 1 with linespoints pt 7 ps 0.6 lw 1.5 lc rgb '#1f77b4' title 'estimate', \
     $tolerance with lines dashtype 2 lw 1.5 lc rgb '#c0392b' title sprintf('tolerance %g', $tolerance)
unset logscale y
set yrange [*:*]
set format y '%.10g'
set ylabel 'lowest positive {/Symbol m} = critical c_n'
plot '$csv' using 2:(cell(5)):(cell(5)*cell(6)) skip 1 with yerrorlines pt 7 ps 0.6 lw 1.5 lc rgb '#2ca02c' title '{/Symbol m} {/Symbol \261} estimate'
unset multiplot
GNUPLOT
} | gnuplot
plot_commit
