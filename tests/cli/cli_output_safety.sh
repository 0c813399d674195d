#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# What a run must never do to its output directory and around it, even under odd limits:
# lose the user's files when the directory cannot be listed (out of descriptors, no read
# permission), die of SIGXFSZ past a file size limit, replace a file the run read, or
# refuse a legal long directory name. Each failure is one stderr line and exit 4 (2 for
# bad input), leaving the previous set, the user's files, and no staging folder.
# Usage: cli_output_safety.sh NCEIG SOURCE_DIR
set -u
nceig=$(realpath "$1")
source "$2/tests/cli/lib/output_sets.bash"
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_output_safety
chmod 755 "$work"   # the unprivileged runs below must reach it
out="$work/out"

nml() {   # nml NAME DIRECTORY [MORE NAMELISTS]: a small run writing into DIRECTORY
    cat >"$work/$1.nml" <<NML
&mesh nx = 4, ny = 4 /
&output directory = '$2', modes = 1, plot = .false. /
${3:-}
NML
}

# staging_left DIR: the staging folders next to DIR and inside it
staging_left() { ls -A "$(dirname "$1")" "$1" 2>/dev/null | grep -E 'nceig-(staging|partial|old)'; }

# unchanged DIR REF: DIR holds REF's set byte for byte, and the user's notes.txt
unchanged() {
    local f
    [[ -s $1/summary.json ]] || return 1
    for f in $(listed_files "$2") summary.json notes.txt; do cmp -s "$1/$f" "$2/$f" || return 1; done
    [[ "$(ls -A "$1")" == "$(ls -A "$2")" ]]
}

# --- A directory that cannot be listed fails the run (its files would not be carried over).
nml listed "$out"
"$nceig" "$work/listed.nml" >/dev/null 2>&1
echo mine >"$out/notes.txt"
cp -a "$out" "$work/ref"
# The descriptors a run needs depend on what the caller left open (ctest leaves some): each
# limit must end in success or exit 4, never in a lost file; some limit must hit the listing.
n_listing=0 bad=''
for n in 4 5 6 7 8 9 10; do
    bash -c "ulimit -n $n; exec \"\$0\" \"\$1\"" "$nceig" "$work/listed.nml" >/dev/null \
        2>"$work/stderr"
    rc=$?
    grep -q 'error while loading shared libraries' "$work/stderr" && continue   # too few to start
    echo "      ulimit -n $n: exit $rc: $(cat "$work/stderr")"
    if [[ $rc -eq 4 ]]; then
        [[ $(wc -l <"$work/stderr") -eq 1 ]] || bad+=" $n:lines"
        if grep -q "cannot list directory .*out: Too many open files" "$work/stderr"; then
            n_listing=$((n_listing + 1))
        fi
        unchanged "$out" "$work/ref" || bad+=" $n:changed"
    elif [[ $rc -eq 0 ]]; then
        [[ $(cat "$out/notes.txt" 2>/dev/null) == mine ]] || bad+=" $n:notes-lost"
        cp -a "$out/." "$work/ref/"
    else
        bad+=" $n:exit-$rc"
    fi
    [[ -z $(staging_left "$out") ]] || bad+=" $n:staging-left"
done
check 'out of descriptors: each run succeeds or exits 4 with one line, nothing lost' '[[ -z $bad ]]'
check 'out of descriptors: a failed listing is reported (directory and reason)' \
    '[[ $n_listing -ge 1 ]]'
# --- A file over the size limit (ulimit -f) is a failed write, like a full disk, not SIGXFSZ.
cat >"$work/big.nml" <<NML
&mesh nx = 32, ny = 32 /
&output directory = '$out', modes = 3, plot = .false. /
NML
rm -rf "$work/ref" && cp -a "$out" "$work/ref"
bash -c 'ulimit -f 50; exec "$0" "$1"' "$nceig" "$work/big.nml" >/dev/null 2>"$work/stderr"
rc=$?
echo "      ulimit -f 50: exit $rc: $(head -3 "$work/stderr")"
check 'ulimit -f 50: exit 4, one line naming the file and the size limit' \
    '[[ $rc -eq 4 && $(wc -l <"$work/stderr") -eq 1 ]] && grep -q "mode_00[0-9]\.vtu: .*file size limit" "$work/stderr"'
check 'ulimit -f 50: the previous set and the notes stay' 'unchanged "$out" "$work/ref"'
check 'ulimit -f 50: no staging folder left' '[[ -z $(staging_left "$out") ]]'

# --- A run never replaces a file it read: an output directory holding the input file or
# the mesh file is refused (exit 2) before any computing; here an adaptive run, whose set
# has a mesh.msh, reading the mesh.msh of the directory it would write.
cat >"$work/adapt.nml" <<NML
&mesh nx = 2, ny = 2, element = 'p2', dirichlet = 'top', neumann = 'left right', contact = 'bottom' /
&adapt tolerance = 1e-3 /
&output directory = '$work/X', modes = 1, plot = .false. /
NML
"$nceig" "$work/adapt.nml" >/dev/null 2>&1
cp -a "$work/X" "$work/ref_X"
sed -i "s|&mesh .*|\&mesh source = 'gmsh', file = 'X/mesh.msh', dirichlet = 'top', neumann = 'left right', contact = 'bottom' /|" "$work/adapt.nml"
for spelling in X X/. "$work/X/"; do
    sed "s|directory = '[^']*'|directory = '$spelling'|" "$work/adapt.nml" >"$work/read_mesh.nml"
    (cd "$work" && "$nceig" read_mesh.nml >/dev/null 2>"$work/stderr")
    rc=$?
    echo "      the mesh read from '$spelling': exit $rc: $(cat "$work/stderr")"
    check "the mesh read from '$spelling': exit 2, one line naming &output directory and the file" \
        '[[ $rc -eq 2 && $(wc -l <"$work/stderr") -eq 1 ]] && grep -q "&output directory = .* holds &mesh file X/mesh.msh, which this run reads" "$work/stderr"'
    check "the mesh read from '$spelling': the directory is untouched" \
        'diff -r "$work/X" "$work/ref_X" >/dev/null && [[ -z $(staging_left "$work/X") ]]'
done
mkdir -p "$work/X/sub"
printf "&mesh nx = 4, ny = 4 /\n&output directory = '%s', plot = .false. /\n" "$work/X" \
    >"$work/X/sub/in.nml"
"$nceig" "$work/X/sub/in.nml" >/dev/null 2>"$work/stderr"
rc=$?
echo "      the input file below the directory: exit $rc: $(cat "$work/stderr")"
check 'the input file below the output directory: exit 2 naming it' \
    '[[ $rc -eq 2 ]] && grep -q "holds the input file .*X/sub/in.nml" "$work/stderr"'

if [[ $(id -u) -eq 0 ]] && command -v setpriv >/dev/null; then
    # root reads any directory: the unreadable one is tried as nobody
    as_nobody() { setpriv --reuid=65534 --regid=65534 --clear-groups "$@"; }
    mkdir -m 777 "$work/shared"
    nml nobody "$work/shared/out"
    as_nobody "$nceig" "$work/nobody.nml" >/dev/null 2>&1
    echo mine >"$work/shared/out/notes.txt"
    cp -a "$work/shared/out" "$work/ref_nobody"
    chmod 300 "$work/shared/out"
    as_nobody "$nceig" "$work/nobody.nml" >/dev/null 2>"$work/stderr"
    rc=$?
    chmod 755 "$work/shared/out"
    echo "      unreadable directory: exit $rc: $(cat "$work/stderr")"
    check 'unreadable directory: exit 4, one line naming it and the reason' \
        '[[ $rc -eq 4 && $(wc -l <"$work/stderr") -eq 1 ]] && grep -q "cannot list directory .*shared/out: Permission denied" "$work/stderr"'
    check 'unreadable directory: the previous set and the notes stay' \
        'unchanged "$work/shared/out" "$work/ref_nobody"'
    check 'unreadable directory: no staging folder left' '[[ -z $(staging_left "$work/shared/out") ]]'
fi

cli_end
