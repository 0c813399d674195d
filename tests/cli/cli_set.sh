#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# --set group%variable=value on the command line: overrides reach the run, text values need
# no quotes, and every misuse (unknown group or variable, bad value, broken rule, malformed
# option) gives one stderr line naming --set, the group and the variable, exit status 2 and
# no output. Usage: cli_set.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_set

cat >"$work/small.nml" <<NML
&mesh nx = 4, ny = 4 /
&output directory = '$work/out', vtk = .false. /
NML

"$nceig" --help >"$work/help" 2>&1
check '--help documents --set' 'grep -q -- "--set group%variable=value" "$work/help"'

"$nceig" "$work/small.nml" --set analysis%lambda=2.5 --set mesh%element=Q1 >/dev/null \
    2>"$work/err"; rc=$?
check 'two overrides run' '[[ $rc -eq 0 && ! -s "$work/err" ]]'
check 'the lambda of --set is used' 'grep -q "\"lambda\": 2.5" "$work/out/summary.json"'
check 'a name needs no quotes and is lowercased' 'grep -q "\"element\": \"q1\"" "$work/out/summary.json"'
rm -rf "$work/out"
"$nceig" --set mesh%nx=3 "$work/small.nml" >/dev/null 2>"$work/err"; rc=$?
check 'the input file may follow the options' '[[ $rc -eq 0 && -s "$work/out/summary.json" ]]'

# bad NAME SETTING WORD...: one stderr line with --set and every WORD, exit 2, no output.
bad() {
    local name=$1 setting=$2
    shift 2
    rm -rf "$work/out"
    "$nceig" "$work/small.nml" --set "$setting" >/dev/null 2>"$work/err"; local rc=$?
    local ok=1
    [[ $rc -eq 2 ]] || ok=0
    [[ $(wc -l <"$work/err") -eq 1 ]] || ok=0
    for word in --set "$@"; do grep -q -F -- "$word" "$work/err" || ok=0; done
    [[ ! -e "$work/out" ]] || ok=0
    check "$name: $(cat "$work/err")" '[[ $ok -eq 1 ]]'
}
bad 'unknown group' 'meshes%nx=3' '&meshes' 'known groups'
bad 'unknown variable' 'mesh%nxx=3' '&mesh' nxx 'knows'
bad 'value of the wrong type' 'analysis%lambda=abc' '&analysis' lambda 'a real number'
bad 'value out of range' 'mesh%nx=0' '&mesh' nx 'from 1 to'
bad 'unknown name' 'mesh%element=p7' '&mesh' element "'q2'"
bad 'rule across variables' 'eigen%ncv=3' '&eigen' ncv 'nev + 2'
bad 'two variables in one --set' 'mesh%nx=3, ny=0' '&mesh' nx 'one variable'
bad 'a value cut short' 'mesh%nx=3/4' '&mesh' nx 'one value'
bad 'no group' 'lambda=2' 'group%variable=value'
bad 'no value' 'analysis%lambda=' "&analysis: lambda: no value after '=': expected one"
bad 'a newline between two settings' $'mesh%nx=4\nmesh%ny=8' 'newline'
bad 'a newline ending the value' $'analysis%lambda=5\n' 'newline'
bad 'a carriage return' $'analysis%lambda=5\r' 'control character'

# A tab is a blank, as in the file (gfortran's read took it as part of the number).
"$nceig" "$work/small.nml" --set $'analysis%lambda=2.5\t' >/dev/null 2>"$work/err"; rc=$?
check 'a tab after a --set value is a blank' '[[ $rc -eq 0 ]] && grep -q "\"lambda\": 2.5" "$work/out/summary.json"'

"$nceig" "$work/small.nml" --set >/dev/null 2>"$work/err"; rc=$?
check '--set without its value: exit 2, one line' '[[ $rc -eq 2 && $(wc -l <"$work/err") -eq 1 ]] && grep -q -- --set "$work/err"'
"$nceig" --set mesh%nx=3 >/dev/null 2>"$work/err"; rc=$?
check '--set without an input file: exit 2, one line' '[[ $rc -eq 2 && $(wc -l <"$work/err") -eq 1 ]]'
printf '&mesh nx = 0 /\n' >"$work/broken.nml"
"$nceig" "$work/broken.nml" --set analysis%lambda=1 >/dev/null 2>"$work/err"; rc=$?
check 'the file'"'"'s own error still names the file' '[[ $rc -eq 2 ]] && grep -q "broken.nml: &mesh: nx" "$work/err"'
"$nceig" "$work/broken.nml" --set mesh%nx=2 --set output%directory="$work/out" >/dev/null 2>"$work/err"; rc=$?
check '--set can repair the file' '[[ $rc -eq 0 && -s "$work/out/summary.json" ]]'

cli_end
