# SPDX-License-Identifier: MIT
# What the benchmark scripts of the reference scene share (scripts/bench/bench_scaling.sh,
# scripts/bench/bench_operator.sh); sourced after they have read their own --options:
#     source "$root/scripts/lib/bench_common.sh"
#     bench_begin NAME "$@"      # REPEATS and N... from what is left of the arguments
# $nceig must name the executable.

# bench_begin NAME [REPEATS] [N ...]: sets repeats (default 3), sizes (default 64 128 256
# 512 1024) and work (a scratch folder removed on exit); stops unless nceig is built and
# GNU time is installed.
bench_begin() {
    local name=$1
    shift
    repeats=${1:-3}
    shift || true
    sizes=("$@")
    ((${#sizes[@]} > 0)) || sizes=(64 128 256 512 1024)
    [[ -x $nceig ]] || { echo "$name: build first (scripts/dev/build.sh Release)" >&2; exit 1; }
    [[ -x /usr/bin/time ]] || { echo "$name: needs /usr/bin/time (package time)" >&2; exit 1; }
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
}

# key FILE KEY: a summary.json value (empty when absent or null)
key() { jq -r --arg key "$2" '.[$key] // empty' "$1"; }

# median: of the numbers on standard input (separated by spaces or lines)
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
