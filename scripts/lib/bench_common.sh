# SPDX-License-Identifier: MIT
# What the benchmark scripts share (scripts/bench/bench_scaling.sh, bench_operator.sh, and
# for the Fortran bench programs bench_mesh_refine.sh, bench_hp.sh); sourced after they have
# read their own --options:
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

# bench_program NAME: compiles scripts/bench/NAME.f90 against the Release library of $build
# (no CMake target, so the build files stay untouched) into $work/NAME (a scratch folder
# removed on exit); stops unless the library is built.
bench_program() {
    local name=$1 libs
    [[ -f $build/libnceig_lib.a ]] ||
        { echo "$name: build first (scripts/dev/build.sh Release)" >&2; exit 1; }
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    # The link line of a test program, minus its own object and the test library.
    libs=$(sed -e 's/^.* -o [^ ]* *//' -e 's/libnceig_testing.a//' \
           -e "s#\.\./libnceig_lib.a#$build/libnceig_lib.a#" \
           "$build/tests/CMakeFiles/test_mesh_refine.dir/link.txt")
    gfortran -O3 -std=f2008 -Wall -Wextra -fimplicit-none -I "$build/modules" \
        "$root/scripts/bench/$name.f90" -o "$work/$name" $libs
}

# key FILE KEY: a summary.json value (empty when absent or null)
key() { jq -r --arg key "$2" '.[$key] // empty' "$1"; }

# median: of the numbers on standard input (separated by spaces or lines)
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
