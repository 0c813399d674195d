#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Nothing lost on a full disk: on a 200 KB tmpfs holding a previous complete set, a run whose
# outputs do not fit must exit 4 with one stderr line naming the file that did not fit, and
# leave the previous set byte for byte, with no staging folder and the space given back.
# The mount point itself, which cannot be renamed, works as an output directory (in place).
# Needs to mount a tmpfs (root); otherwise skipped (exit 77) with the reason.
# Usage: cli_full_disk.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$2/tests/cli/lib/output_sets.bash"
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_full_disk
disk="$work/disk"
mkdir "$disk"
if ! mount -t tmpfs -o size=200k tmpfs "$disk" 2>"$work/mount.err"; then
    echo "SKIP  cannot mount a tmpfs here: $(head -1 "$work/mount.err")"
    exit 77
fi
trap 'umount "$disk"; cli_remove_work' EXIT
out="$disk/out"

nml() {   # nml NAME NX LAMBDA MODES [OUTPUT OPTIONS]: an input file writing into $out
    cat >"$work/$1.nml" <<NML
&mesh nx = $2, ny = $2 /
&analysis lambda = $3 /
&output directory = '$out', modes = $4 ${5:-} /
NML
}
nml small 6 5 2
nml big 60 5 3
nml big_ascii 60 5 3 ", vtk_format = 'ascii'"
nml matrices 60 5 1 ", vtk = .false., matrices = .true."
nml other 6 4 3

# The mount point itself cannot be renamed: it is committed in place, file by file.
cat >"$work/mount_point.nml" <<NML
&mesh nx = 6, ny = 6 /
&output directory = '$disk', modes = 3 /
NML
"$nceig" "$work/mount_point.nml" >/dev/null 2>"$work/stderr"
rc=$?
sed -i 's/modes = 3/modes = 2/' "$work/mount_point.nml"
"$nceig" "$work/mount_point.nml" >/dev/null 2>>"$work/stderr"
rc=$((rc + $?))
check 'the mount point as output directory: two runs succeed' '[[ $rc -eq 0 && ! -s "$work/stderr" ]]'
check 'the mount point as output directory: it holds the second set, whole' \
    '[[ $(set_state "$disk" "$disk") == "ref 0" && ! -e "$disk/mode_003.vtu" ]]'
check 'the mount point as output directory: no staging folder left' \
    '[[ -z $(ls -A "$disk" | grep nceig-partial) ]]'
rm -rf "${disk:?}"/* "$disk"/.nceig-*

"$nceig" "$work/small.nml" >/dev/null 2>&1
check 'a small run fits' '[[ -s "$out/summary.json" ]]'
mkdir "$work/ref_small"
cp -p "$out"/* "$work/ref_small/"
free_before=$(df -k --output=avail "$disk" | tail -1)

for case in big big_ascii matrices; do
    "$nceig" "$work/$case.nml" >"$work/stdout" 2>"$work/stderr"
    rc=$?
    echo "      $case: exit $rc: $(cat "$work/stderr")"
    check "$case: exit status 4" '[[ $rc -eq 4 ]]'
    check "$case: one stderr line naming the file" \
        '[[ $(wc -l <"$work/stderr") -eq 1 ]] && grep -Eq "(mode_00[0-9]\.vtu|K\.mtx|B\.mtx|eigenvalues\.csv|summary\.json).*(disk full|No space)" "$work/stderr"'
    check "$case: the previous set is whole and unchanged" \
        '[[ $(set_state "$out" "$work/ref_small") == "ref 0" ]] && cmp -s "$out/summary.json" "$work/ref_small/summary.json"'
    check "$case: no staging folder left" '[[ -z $(ls -A "$disk" | grep nceig-staging) ]]'
    check "$case: the space is given back" \
        '[[ $(df -k --output=avail "$disk" | tail -1) -ge $((free_before - 4)) ]]'
done

# Only summary.json, the last file, does not fit (a filler leaves 3 pages: eigenvalues.csv
# takes one, mode_001.vtu two): json_writer's close is checked too.
nml one_mode 6 4 1
avail=$(df -k --output=avail "$disk" | tail -1)
head -c $(((avail - 12) * 1024)) /dev/zero >"$disk/filler" 2>/dev/null
"$nceig" "$work/one_mode.nml" >/dev/null 2>"$work/stderr"
rc=$?
echo "      summary.json: exit $rc: $(cat "$work/stderr")"
check 'summary.json does not fit: exit status 4 naming it' \
    '[[ $rc -eq 4 ]] && grep -q "summary.json" "$work/stderr"'
check 'summary.json does not fit: the previous set is whole and unchanged' \
    '[[ $(set_state "$out" "$work/ref_small") == "ref 0" ]] && cmp -s "$out/summary.json" "$work/ref_small/summary.json"'
rm -f "$disk/filler"

# The disk is not left unusable: a run that fits still commits.
"$nceig" "$work/other.nml" >/dev/null 2>&1
check 'a run that fits commits after the failures' \
    '[[ $(set_state "$out" "$work/ref_small") != "ref 0" && $(grep "\"lambda\":" "$out/summary.json") == *4* ]]'
check 'and its set is whole' '[[ $(set_state "$out" "$out") == "ref 0" ]]'

cli_end
