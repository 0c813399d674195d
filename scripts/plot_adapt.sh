#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Draw OUTDIR/adapt.png from OUTDIR/adapt.csv and OUTDIR/summary.json of an nceig run with
# &adapt tolerance > 0: the error bar of the goal (solid, what the loop stops on) and its
# estimate (dashed) against the free dofs (log-log, the
# tolerance as a dashed line) above the goal with its error bar against the dofs (log x),
# one point per level. The goal: the lowest positive mu (kind = 'eigen'), or both critical
# lambdas (kind = 'threshold': lambda+ and |lambda-|). Needs gnuplot (Debian gnuplot-nox:
# pngcairo) and jq.
# Usage: plot_adapt.sh OUTDIR [SUMMARY]   (SUMMARY: the summary.json to read, by default
# OUTDIR's; nceig passes its own while the set is still being staged)
set -euo pipefail
source "$(dirname "$0")/lib/plot_common.sh"
plot_begin adapt.csv "run nceig with &adapt tolerance > 0" "$@"
tolerance=$(value adapt_tolerance)

# each curve: value column|estimate column|title|colour|sign (from the header: one goal, or
# two sides)
header=$(head -n 1 "$csv")
if [[ $header == *lambda_plus* ]]; then
    sides=("5|6|10|lambda+|#1f77b4|1" "7|8|11|-lambda-|#ff7f0e|-1")
    goal='critical {/Symbol l}  (dimensionless)'
    title="$(value element), the critical lambdas, start $(value adapt_start_dofs) dofs"
else
    sides=("5|6|8|{/Symbol m}|#1f77b4|1")
    goal='lowest positive {/Symbol m} = critical c_n  [E / length]'
    title="$(value element), lambda = $(value lambda), start $(value adapt_start_dofs) dofs"
fi
estimates=$(for s in "${sides[@]}"; do IFS='|' read -r _ e _ _ <<<"$s"; echo "$e"; done)
if ! awk -F, -v cols="$estimates" 'BEGIN { n = split(cols, c, "\n") }
    NR > 1 { for (i = 1; i <= n; i++) if ($c[i] != "") found = 1 } END { exit !found }' "$csv"; then
    echo "$0: $csv: no level has an error estimate: nothing to draw" >&2
    exit 4
fi
# the lower end of the estimate axis: a third below the smaller of the tolerance and the
# smallest estimate, so that the tolerance line never sits on the frame
ymin=$(awk -F, -v t="$tolerance" -v cols="$estimates" 'BEGIN { n = split(cols, c, "\n") }
    NR > 1 { for (i = 1; i <= n; i++) if ($c[i] != "" && (m == "" || $c[i] < m)) m = $c[i] }
    END { if (m == "" || t < m) m = t; print m / 3 }' "$csv")
estimate_plot='' value_plot=''
for s in "${sides[@]}"; do
    IFS='|' read -r v e b name colour sign <<<"$s"
    estimate_plot+="$(gnuplot_string "$csv") using 2:(cell($b)) skip 1 with linespoints pt 7 ps 0.6 lw 1.5 lc rgb '$colour' title '$name: error bar', "
    estimate_plot+="$(gnuplot_string "$csv") using 2:(cell($e)) skip 1 with lines dt 2 lw 1 lc rgb '$colour' title '$name: estimate', "
    value_plot+="$(gnuplot_string "$csv") using 2:($sign*cell($v)):(abs(cell($v))*cell($b)) skip 1 with yerrorlines pt 7 ps 0.6 lw 1.5 lc rgb '$colour' title '$name {/Symbol \261} error bar', "
done
{
    gnuplot_preamble
    cat <<GNUPLOT
set multiplot layout 2, 1 title "nceig adaptive refinement: $title" font ',13'
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set logscale x
set xlabel 'free degrees of freedom'
set logscale y
set format y '10^{%L}'
set key top right
set ylabel 'relative error  (dimensionless)'
set yrange [$ymin:*]
plot $estimate_plot \
     $tolerance with lines dashtype 2 lw 1.5 lc rgb '#c0392b' title sprintf('tolerance %g', $tolerance)
unset logscale y
set yrange [*:*]
set format y '%.10g'
set ylabel '$goal'
plot ${value_plot%, }
unset multiplot
GNUPLOT
} | gnuplot
plot_commit
