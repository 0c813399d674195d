#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The adaptive level bars of a folder kept by scripts/dev/bar_quality.sh --keep, recomputed
# offline with other level factors (src/numerics/error_bar.f90: level_bar = max(factor x
# envelope, change over the window) + round-off). Per degree p it prints, over the adaptive
# values with a bar:
#   n, the smallest envelope / true error (the estimates' worst underestimate, carried
#   over the window) and the value where it occurs, the smallest factor that gives every
#   value bar / true error >= 1 and >= 1.1 (values the change over the window covers
#   already need none), and bar / true error with the factors FACTORS (min, median, max,
#   share in [1, 10], count above 10).
# The round-off part of each bar is what the run's bar exceeds max(WAS x envelope, change)
# by, WAS the factor of the build that made the folder (default 3 for every degree).
# --window: the recomputed bars take the envelope and change over the other window of the
# ratios file (bar_quality.sh's WINDOW), the round-off part still from the build's.
# Usage: scripts/dev/level_factor.sh [--was F1,F2,F3] [--window] DIR F1,F2,F3
set -euo pipefail
was=3,3,3 other=0
while [[ ${1:-} == --* ]]; do
    case $1 in
        --was) [[ $# -ge 2 ]] || { echo "level_factor: --was needs F1,F2,F3" >&2; exit 2; }
            was=$2; shift 2 ;;
        --window) other=1; shift ;;
        *) echo "level_factor: unknown option $1" >&2; exit 2 ;;
    esac
done
(($# == 2)) || { echo "usage: level_factor.sh [--was F1,F2,F3] [--window] DIR F1,F2,F3" >&2; exit 2; }
dir=$1 factors=$2
[[ -f $dir/ratios ]] || { echo "level_factor: $dir/ratios missing (bar_quality.sh --keep DIR)" >&2; exit 1; }
# ratios: scene family quantity source ratio envelope/err change/err level dip
# envelope/err change/err (the other window)
awk -v was="$was" -v fac="$factors" -v other="$other" '
    BEGIN { split(was, w, ","); split(fac, f, ",") }
    $2 ~ /^adaptive-p/ && $4 == "bar" && NF >= 8 {
        if (other && NF < 11) { short++; next }
        p = substr($2, 11) + 0; env = $6; mv = $7
        core = (w[p] * env > mv) ? w[p] * env : mv
        ro = $5 - core
        if (ro < -1e-8 * core) { off++; ro = 0 }
        if (other) { env = $10; mv = $11 }
        n[p]++
        if (!(p in lo) || env < lo[p]) { lo[p] = env; at[p] = $1 " " $3 " level " $8 }
        for (t = 1; t <= 2; t++) {
            target = (t == 1) ? 1 : 1.1
            if (mv + ro < target && env > 0) { x = (target - ro) / env; if (x > need[p, t]) need[p, t] = x }
        }
        r = ((f[p] * env > mv) ? f[p] * env : mv) + ro
        ratio[p, n[p]] = r
    }
    END {
        if (short) printf "level_factor: %d lines without the other window (bar_quality.sh --analyse DIR again)\n", \
            short > "/dev/stderr"
        if (off) printf "level_factor: %d bars below max(WAS x envelope, change): not made with WAS = %s\n", \
            off, was > "/dev/stderr"
        printf "%-3s %5s %10s %8s %8s %8s %8s %8s %7s %5s  %s\n", "deg", "n", "min env/e", "need>=1", \
            "need>=1.1", "min", "median", "max", "[1,10]", ">10", "smallest envelope at"
        for (p = 1; p <= 3; p++) {
            if (!n[p]) continue
            m = n[p]
            for (i = 1; i <= m; i++) s[i] = ratio[p, i]
            for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (s[j] < s[i]) { x = s[i]; s[i] = s[j]; s[j] = x }
            in10 = 0; over = 0
            for (i = 1; i <= m; i++) { if (s[i] >= 1 && s[i] <= 10) in10++; if (s[i] > 10) over++ }
            med = (m % 2) ? s[(m + 1) / 2] : (s[m / 2] + s[m / 2 + 1]) / 2
            printf "P%-2d %5d %10.3g %8.3g %8.3g %8.3g %8.3g %8.3g %6.0f%% %5d  %s\n", p, m, lo[p], \
                need[p, 1], need[p, 2], s[1], med, s[m], 100 * in10 / m, over, at[p]
        }
    }' "$dir/ratios"
