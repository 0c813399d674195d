#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The reference scene's thresholds (input/threshold.nml, hp) at 50 settings a user may choose:
# tolerance 1e-6 and 1e-9, sigma 0.01 to 0.5, p_max unset, 1, 2, 3, 6. One line per run:
# its exit status and, per side, the relative error against the graded-P4 truth
# |lambda+-| = 1.9447114426738574 (docs/accuracy.md, "Independent truths") and whether the
# bar covers it ('MISSED' where it does not), or the value without a bar, or none.
#   scripts/dev/threshold_settings.sh [NCEIG] [OUTDIR]   (default build/nceig, a temporary folder)
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
N=$(realpath "${1:-$root/build/nceig}")
out=${2:-$(mktemp -d)}
mkdir -p "$out" && cd "$out" || exit 2
T=1.9447114426738574
for tol in 1e-6 1e-9; do for s in 0.01 0.05 0.15 0.3 0.5; do for p in 0 1 2 3 6; do
  extra=(); [[ $p != 0 ]] && extra=(--set adapt%p_max=$p)
  d=r_${tol}_${s}_$p
  timeout 600 nice -n 5 "$N" "$root/input/threshold.nml" --set adapt%strategy=hp --set adapt%sigma=$s --set adapt%tolerance=$tol "${extra[@]}" --set output%directory="$d" --set output%progress=.false. --set output%vtk=.false. --set output%plot=.false. >"$d.log" 2>&1
  rc=$?
  jq -r --arg rc $rc --arg d $d --argjson t $T '[$d, $rc] + ([["plus", .lambda_critical_plus, .lambda_critical_plus_error_bar], ["minus", .lambda_critical_minus, .lambda_critical_minus_error_bar]] | map(
      if .[1] == null then "\(.[0]) none" elif .[2] == null then "\(.[0]) \(.[1]) nobar" else
      (((.[1] | fabs) - $t | fabs) / $t) as $e | "\(.[0]) err \($e) bar \(.[2]) \(if $e <= .[2] then "covered" else "MISSED" end)" end)) | join(" | ")' "$d/summary.json" 2>/dev/null || echo "$d rc=$rc no summary"
done; done; done | tee -a runs.txt
echo "sides: $(grep -o covered runs.txt | wc -l) with a bar that covers the truth, $(grep -o MISSED runs.txt | wc -l) missed, $(grep -o nobar runs.txt | wc -l) without a bar, $(grep -oE '(plus|minus) none' runs.txt | wc -l) none (in $out)"
