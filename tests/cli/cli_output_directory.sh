#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# What a run does to its output directory and around it: a failed run creates nothing (a
# 4229-character path, longer than the 4096 of &output directory, is refused as bad input
# and leaves no directory); a run replaces the
# previous set as a whole (the older run's extra mode files go), keeps the user's files,
# and refuses to replace a directory holding a folder of the user's, or one the user made
# read-only; a link to a directory yet to be made stays a link; an input named ..nml gets
# output/..nml.
# Usage: cli_output_directory.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$2/tests/cli/lib/output_sets.bash"
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_output_directory

long="$work/long"
while ((${#long} < 4229)); do long="$long/abcdefghi"; done
long=${long:0:4229}
cat >"$work/long.nml" <<NML
&mesh nx = 6, ny = 6 /
&output directory = '$long' /
NML
"$nceig" "$work/long.nml" >/dev/null 2>"$work/stderr"
rc=$?
echo "      $(grep "^nceig: " "$work/stderr" | cut -c1-200)"
check 'a 4229-character path: exit status 2, the limit named' \
    '[[ $rc -eq 2 ]] && grep -q "directory = .*at most 4096 characters" "$work/stderr"'
check 'a 4229-character path: one stderr line of nceig' '[[ $(grep -c "^nceig: " "$work/stderr") -eq 1 ]]'
check 'a 4229-character path: no directory left' '[[ ! -e "$work/long" ]]'

out="$work/out"
nml() {   # nml NAME LAMBDA MODES
    cat >"$work/$1.nml" <<NML
&mesh nx = 6, ny = 6 /
&analysis lambda = $2 /
&output directory = '$out', modes = $3, plot = .false. /
NML
}
nml three 5 3
nml two 4 2
"$nceig" "$work/three.nml" >/dev/null 2>&1
echo 'my notes' >"$out/notes.txt"
ln -s notes.txt "$out/notes.link"
chmod 750 "$out"
"$nceig" "$work/two.nml" >/dev/null 2>&1
check 'the older set'\''s extra mode file is gone' '[[ ! -e "$out/mode_003.vtu" ]]'
check 'the new set is whole' '[[ $(listed_files "$out" | tr "\n" " ") == "eigenvalues.csv mode_001.vtu mode_002.vtu summary.json " ]]'
check 'the user'\''s file is kept' '[[ $(cat "$out/notes.txt") == "my notes" ]]'
check 'the user'\''s link is kept' '[[ -L "$out/notes.link" && $(cat "$out/notes.link") == "my notes" ]]'
check 'the directory keeps its permissions' '[[ $(stat -c %a "$out") == 750 ]]'

mkdir "$out/plots"
cp "$out/summary.json" "$work/summary.before"
"$nceig" "$work/three.nml" >/dev/null 2>"$work/stderr"
rc=$?
echo "      $(cat "$work/stderr")"
check 'a folder of the user'\''s: exit status 4 naming it' '[[ $rc -eq 4 ]] && grep -q plots "$work/stderr"'
check 'a folder of the user'\''s: the previous set stays' 'cmp -s "$out/summary.json" "$work/summary.before" && [[ -d "$out/plots" ]]'
check 'no staging folder left' '[[ -z $(ls -A "$work" | grep nceig-staging) ]]'

# A link to the output directory: the directory it names is replaced, the link stays.
rmdir "$out/plots"
mkdir "$work/real"
ln -s real "$work/linked"
sed "s|'$out'|'$work/linked'|" "$work/three.nml" >"$work/linked.nml"
"$nceig" "$work/linked.nml" >/dev/null 2>&1
check 'a link to the directory stays a link' '[[ -L "$work/linked" && -s "$work/real/summary.json" ]]'

# A link to a directory that does not exist yet (dangling): the directory is made where the
# link points, the link stays (it was replaced by a real directory); a loop of links is
# refused (exit 4) and stays as it was.
ln -s new/target "$work/dangling"
sed "s|'$out'|'$work/dangling'|" "$work/three.nml" >"$work/dangling.nml"
"$nceig" "$work/dangling.nml" >/dev/null 2>&1
rc=$?
check 'a dangling link: exit 0, the set where it points, the link stays a link' \
    '[[ $rc -eq 0 && -L "$work/dangling" && -s "$work/new/target/summary.json" ]]'
ln -s loop_b "$work/loop_a"
ln -s loop_a "$work/loop_b"
sed "s|'$out'|'$work/loop_a'|" "$work/three.nml" >"$work/loop.nml"
"$nceig" "$work/loop.nml" >/dev/null 2>"$work/stderr"
rc=$?
echo "      $(cat "$work/stderr")"
check 'a loop of links: exit 4, one line, both links as they were' \
    '[[ $rc -eq 4 && $(wc -l <"$work/stderr") -eq 1 && -L "$work/loop_a" && -L "$work/loop_b" ]]'

# A read-only directory (chmod 0555): the user's word; refused with exit 4 (root too, whom
# the permission bits do not stop: the swap replaced it with exit 0), the set inside kept.
"$nceig" "$work/three.nml" >/dev/null 2>&1
cp -a "$out" "$work/readonly.before"
chmod 0555 "$out"
"$nceig" "$work/two.nml" >/dev/null 2>"$work/stderr"
rc=$?
echo "      $(cat "$work/stderr")"
check 'a read-only output directory: exit 4, one line naming it read-only' \
    '[[ $rc -eq 4 && $(wc -l <"$work/stderr") -eq 1 ]] && grep -q "is read-only" "$work/stderr"'
check 'a read-only output directory: untouched, still read-only' \
    '[[ $(stat -c %a "$out") == 555 ]] && diff -r "$out" "$work/readonly.before" >/dev/null'
chmod 0755 "$out"

# An input named '..nml': the default directory was output/. (output/ itself, where the
# set then replaced whatever the user kept); now output/..nml.
mkdir -p "$work/cwd/output"
echo 'kept' >"$work/cwd/output/notes.txt"
printf '&mesh nx = 4, ny = 4 /\n&output plot = .false. /\n' >"$work/cwd/..nml"
(cd "$work/cwd" && "$nceig" ..nml >/dev/null 2>&1)
rc=$?
check 'an input ..nml writes output/..nml, not output/ itself' \
    '[[ $rc -eq 0 && -s "$work/cwd/output/..nml/summary.json" && ! -e "$work/cwd/output/summary.json" ]]'

cli_end
