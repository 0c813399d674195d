#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The round-off error of the collision points (complex_pair boundary points), measured,
# against its bound (summary.json boundary_roundoff): the same discrete problem in 10
# roundings, young E in {1, 3.7, 0.61, 1.9, 0.27} x two scans of &sweep (n_lambda 401 and
# 397: other brackets, so other steps of the root search); lambda is dimensionless, so the
# points themselves are compared.
# Usage: scripts/dev/collision_roundoff_spread.sh NCEIG NAME INPUT.nml [--set ...]
# Prints per collision point: NAME, lambda, spread (max - min) / |lambda|, the largest
# bound, the ratio.
set -u
nceig=$1 name=$2 input=$3
shift 3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for e in 1 3.7 0.61 1.9 0.27; do
    for n in 401 397; do
        rm -rf "$work/out"
        "$nceig" "$input" "$@" --set material%young=$e --set sweep%n_lambda=$n \
            --set eigen%estimate=off --set output%directory="$work/out" \
            --set output%vtk=.false. --set output%plot=.false. >"$work/stdout" 2>&1
        python3 - "$work/out/summary.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for lam, mech, r in zip(d['boundary_lambda'], d['boundary_mechanism'], d['boundary_roundoff']):
    if mech == 'complex_pair':
        print(lam, r if r is not None else -1)
PY
    done
done >"$work/rows"
[[ -n ${ROUNDOFF_ROWS:-} ]] && cat "$work/rows" >&2
# group the rows by point (the points of one run are in order; all runs find the same)
python3 - "$work/rows" "$name" <<'PY'
import sys
rows = [tuple(map(float, l.split())) for l in open(sys.argv[1]) if l.strip()]
points = {}
for lam, r in rows:
    key = next((k for k in points if abs(k - lam) <= 1e-6 * abs(k)), lam)
    points.setdefault(key, []).append((lam, r))
for k, v in sorted(points.items()):
    lams = [a for a, _ in v]
    spread = (max(lams) - min(lams)) / abs(lams[0])
    bound = max(b for _, b in v)
    ratio = bound / spread if spread > 0 else float('inf')
    print(f"{sys.argv[2]:<26} lambda {lams[0]:.15g}  runs {len(v)}  spread {spread:.2e}  "
          f"bound {bound:.2e}  bound/spread {ratio:.3g}")
PY
