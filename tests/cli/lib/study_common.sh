# SPDX-License-Identifier: MIT
# shellcheck shell=bash
# What the study tests (tests/cli/cli_study.sh, cli_study_slurm.sh) share: the small study
# they run and the comparison of two study tables. Sourced after cli_common.sh; not a test.

# study_input FILE TOLERANCE: the 2 x 2 study of the tests: the reference scene's rectangle
# at widths 1 and 2 (2 x 2 P1 squares, the hp climb grades them), nu = 0.25 and 0.3,
# lambda = -5, 2.5, 5, both quantities, hp to TOLERANCE; no mode files or pictures per run
# but the mode of each c_n run (study.pvd).
study_input() {
    cat >"$1" <<EOF
! The 2 x 2 study of the tests
&study
    geometry = 'rectangle'
    widths = 1.0, 2.0
    poisson = 0.25, 0.3
    lambda = -5.0, 2.5, 5.0
/
&mesh
    nx = 2, ny = 2, element = 'p1'
/
&adapt
    tolerance = $2
/
&output
    progress = .false.
/
EOF
}

# same_study A B: two study.csv files agree row by row in every column but the times
# (seconds): numbers to a relative 1e-9, text exactly. The same nceig on the same inputs on
# one BLAS thread gives the same numbers; 1e-9 leaves room for nothing but round-off.
same_study() {
    awk -F, '
        function num(s) { return s ~ /^[-+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][-+]?[0-9]+)?$/ }
        NR == FNR { a[FNR] = $0; n = FNR; next }
        FNR == 1 { for (i = 1; i <= NF; i++) name[i] = $i }
        { m = FNR; split(a[FNR], x, ",")
          for (i = 1; i <= NF; i++) {
              if (name[i] == "\"seconds\"") continue
              if (num(x[i]) && num($i)) {
                  d = x[i] - $i; d = d < 0 ? -d : d; r = $i < 0 ? -$i : $i
                  if (d > 1e-9 * r) { print "differ: " name[i] " row " FNR ": " x[i] " " $i; bad = 1 }
              } else if (x[i] != $i) { print "differ: " name[i] " row " FNR ": " x[i] " " $i; bad = 1 }
          } }
        END { if (m != n) { print "rows: " n " and " m; bad = 1 }; exit bad }' "$1" "$2"
}
