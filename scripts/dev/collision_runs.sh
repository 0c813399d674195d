#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The adaptive P2 runs of collision onsets in docs/adaptive.md ("Collision onsets to a
# tolerance"): the trapezoid (nu = 0.3 and 0.1) from a Delaunay P2 mesh of size 1/8 to 1e-6,
# and the half-contact example to 1e-7 with max_levels = 30. For each adapted side: bar /
# true error of the adapt.csv collision columns (error_bar_collision_*) against
# tests/data/truths.csv, over the levels from the 3rd on (as scripts/dev/bar_quality.sh
# counts, and like it skipping true errors below 100 times the truth's uncertainty): levels, min, median, max, how many in [1, 10], and the last level's dofs, true
# error and bar. One thread (OPENBLAS_NUM_THREADS=1); the runs take some minutes each.
# Usage: scripts/dev/collision_runs.sh [--keep DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
[[ -x $nceig ]] || { echo "collision_runs: build first (scripts/dev/build.sh Release)" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "collision_runs: needs gmsh" >&2; exit 1; }
if [[ ${1:-} == --keep ]]; then
    mkdir -p "$2"
    work=$(cd "$2" && pwd)
else
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
fi
export OPENBLAS_NUM_THREADS=1
truths=$root/tests/data/truths.csv
truth() { awk -F, -v s="$1" -v q="$2" '$1 == s && $2 == q { print $3, $4 }' "$truths"; }

gmsh "$root/tests/data/truths/trapezoid.geo" -setnumber graded 0 -clmax 0.125 -2 -order 2 \
    -format msh41 -o "$work/trap.msh" >/dev/null
trap_mesh="&mesh source = 'gmsh', file = '$work/trap.msh', dirichlet = 'top', neumann = 'left right', contact = 'bottom' /"

# run NAME NML_BODY ARGS...: nceig on NAME.nml, output in out/NAME
run() {
    local name=$1 body=$2
    shift 2
    printf '%s\n&output directory = %s, vtk = .false., plot = .false. /\n' "$body" \
        "'$work/out/$name'" >"$work/$name.nml"
    "$nceig" "$work/$name.nml" --set output%progress=.false. "$@" >"$work/$name.log" 2>&1 || true
}
run trap03 "$trap_mesh
&analysis kind = 'threshold', lambda = 5.0 /
&adapt tolerance = 1e-6 /"
run trap01 "$trap_mesh
&material poisson = 0.1 /
&analysis kind = 'threshold', lambda = 5.0 /
&adapt tolerance = 1e-6 /"
run half "$(sed '/^&output/,$d' "$root/input/half_contact.nml" |
            sed "s|'meshes/|'$root/input/meshes/|")
&adapt tolerance = 1e-7, max_levels = 30 /"

echo "| run (P2) | side | levels | min | median | max | in [1, 10] | final: dofs, true error, bar |"
echo "|---|---|---|---|---|---|---|---|"
# row LABEL NAME SCENE SIDE
row() {
    local csv=$work/out/$2/adapt.csv t u
    [[ -f $csv ]] || { echo "| $1 | $4 | (no adapt.csv: $(tail -1 "$work/$2.log")) |"; return; }
    read -r t u < <(truth "$3" "lambda_onset_$4")
    awk -F, -v side="$4" -v t="$t" -v u="$u" -v label="$1" '
        NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
        {
            v = $col["collision_" side]; b = $col["error_bar_collision_" side]
            if (v == "" || b == "") next
            e = (v - t) / t; if (e < 0) e = -e
            last_dofs = $col["n_dofs"]; last_e = e; last_b = b
            if ($col["level"] < 2 || e < 100 * u) next   # below the truth: not judged
            r[++n] = b / e
        }
        END {
            if (n == 0) { printf "| %s | %s | 0 | | | | | |\n", label, (side == "plus" ? "+" : "-"); exit }
            for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (r[j] < r[i]) { x = r[i]; r[i] = r[j]; r[j] = x }
            inside = 0; for (i = 1; i <= n; i++) if (r[i] >= 1 && r[i] <= 10) inside++
            med = (n % 2) ? r[(n + 1) / 2] : (r[n / 2] + r[n / 2 + 1]) / 2
            printf "| %s | %s | %d | %.2f | %.2f | %.3g | %d | %d, %.1e, %.1e |\n", label,
                (side == "plus" ? "+" : "-"), n, r[1], med, r[n], inside, last_dofs, last_e, last_b
        }' "$csv"
}
row "trapezoid, nu = 0.3, to 1e-6" trap03 trapezoid-threshold minus
row "trapezoid, nu = 0.3, to 1e-6" trap03 trapezoid-threshold plus
row "trapezoid, nu = 0.1, to 1e-6" trap01 trapezoid-nu0.1-threshold minus
row "trapezoid, nu = 0.1, to 1e-6" trap01 trapezoid-nu0.1-threshold plus
row "half contact, 1e-7, max_levels = 30" half half-contact-threshold minus
for n in trap03 trap01 half; do
    echo "# $n: $(grep -h '^  adapt' "$work/$n.log" | head -1 | sed 's/^  adapt *//')"
done
