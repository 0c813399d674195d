#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Issue "Nothing lost, nothing wrong", items 5, 8 and 10: nothing of the input is silently
# cut, misread or echoed raw. Item 5: a value longer than its variable (512 for lists, 64
# for names, 4096 for paths) is refused naming the variable and the limit, from the file and
# from --set. Item 8: reading is linear (a 200000-character value in well under a second),
# an input over 1 MiB or /dev/zero is refused, a FIFO and <(...) are read once. Item 10:
# control bytes are never echoed, echoed values are capped, more than 1000 lambdas, a
# logical like .trash., a variable given twice and an unreadable number are refused with
# their line; an output directory that cannot be made names the input file and &output.
# Each refusal: exit 2 (4 for the output directory), exactly one line on stderr.
# Usage: cli_input_faults.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_input_faults
out="$work/out"

# refused NAME RC FILE [ARGS...] -- WORD...: exit RC, one stderr line holding every WORD,
# no control byte in it.
refused() {
    local name=$1 rc_expected=$2 file=$3
    shift 3
    local args=()
    while [[ $# -gt 0 && $1 != -- ]]; do args+=("$1"); shift; done
    shift
    timeout 20 "$nceig" "$file" "${args[@]}" >"$work/stdout" 2>"$work/err"
    local rc=$? ok=1
    [[ $rc -eq $rc_expected ]] || ok=0
    [[ $(wc -l <"$work/err") -eq 1 ]] || ok=0
    ! LC_ALL=C grep -q '[[:cntrl:]]' <(tr -d '\n' <"$work/err") || ok=0
    for word in "$@"; do grep -q -F -- "$word" "$work/err" || ok=0; done
    check "$name" '[[ $ok -eq 1 ]]'
    echo "      rc=$rc $(head -c 300 "$work/err" | tr -d '\n')"
}

# nml FILE TEXT: TEXT plus an &output group pointing at $out.
nml() { printf '%s\n&output directory = '"'%s'"', plot = .false. /\n' "$2" "$out" >"$1"; }
blanks=$(printf '%600s' '')

# --- item 5: nothing cut without a word
nml "$work/list.nml" "&mesh dirichlet = 'top${blanks}left' /"
refused 'item 5: a list past 512 characters' 2 "$work/list.nml" -- \
    'list.nml: &mesh: line 1: dirichlet' 'at most 512 characters'
nml "$work/bogus.nml" "&mesh dirichlet = 'top${blanks}bogus' /"
refused 'item 5: the cut part is not dropped unseen' 2 "$work/bogus.nml" -- \
    '&mesh: line 1: dirichlet' 'at most 512'
nml "$work/name.nml" "&analysis kind = 'eigen$(printf '%70s' '')x' /"
refused 'item 5: a name past 64 characters' 2 "$work/name.nml" -- '&analysis: line 1: kind' \
    'at most 64'
long=$(printf 'd%.0s' $(seq 4229))
printf "&output directory = '%s' /\n" "$work/$long" >"$work/path.nml"
refused 'item 5: a path past 4096 characters' 2 "$work/path.nml" -- '&output: line 1: directory' \
    'at most 4096'
nml "$work/good.nml" "&mesh nx = 4, ny = 2 /"
refused 'item 5: the same through --set' 2 "$work/good.nml" \
    --set "mesh%neumann=left${blanks}right" \
    -- '--set' '&mesh: neumann' 'at most 512'

# --- item 8: linear, bounded, any kind of file
python3 -c "print(\"&mesh dirichlet = '\" + 'x' * 200000 + \"' /\")" \
    >"$work/wide.nml" 2>/dev/null ||
    { printf "&mesh dirichlet = '"; head -c 200000 /dev/zero | tr '\0' x; printf "' /\n"; } \
        >"$work/wide.nml"
start=$(date +%s%N)
refused 'item 8: a 200000-character value is refused' 2 "$work/wide.nml" -- 'at most 512'
elapsed_ms=$(( ($(date +%s%N) - start) / 1000000 ))
check "item 8: ... in under 2 s (took $elapsed_ms ms; 13.9 s before)" '[[ $elapsed_ms -lt 2000 ]]'
refused 'item 8: /dev/zero is refused, not read forever' 2 /dev/zero -- '/dev/zero' '1048576 bytes'
{ head -c 1100000 /dev/zero | tr '\0' ' '; echo; } >"$work/big.nml"
refused 'item 8: an input over 1 MiB' 2 "$work/big.nml" -- 'big.nml' '1 MiB'
timeout 20 "$nceig" <(cat "$work/good.nml") >"$work/stdout" 2>"$work/err"
check 'item 8: <(...) input is read once and runs' '[[ $? -eq 0 && ! -s "$work/err" ]]'
mkfifo "$work/fifo.nml"
cat "$work/good.nml" >"$work/fifo.nml" &
timeout 20 "$nceig" "$work/fifo.nml" >"$work/stdout" 2>"$work/err"
check 'item 8: a FIFO input is read once and runs' '[[ $? -eq 0 && ! -s "$work/err" ]]'
wait

# --- item 10: messages
nml "$work/control.nml" "&mesh dirichlet = 'to$(printf '\001')p$(printf '\033')[31m' /"
refused 'item 10: control bytes are not echoed' 2 "$work/control.nml" -- "to?p?[31m"
nml "$work/nul.nml" "&mesh contact = 'bot"
printf "\0tom' /\n" >>"$work/nul.nml"
timeout 20 "$nceig" "$work/nul.nml" >/dev/null 2>"$work/err"
check 'item 10: no NUL byte on stderr' \
    '[[ $(tr -d "\0" <"$work/err" | wc -c) -eq $(wc -c <"$work/err") ]]'
nml "$work/huge.nml" "&mesh source = '$(printf 'y%.0s' $(seq 3000))' /"
refused 'item 10: a long echoed value is capped' 2 "$work/huge.nml" -- '...'
check 'item 10: ... the line stays short' '[[ $(wc -c <"$work/err") -lt 400 ]]'
nml "$work/lambdas.nml" "&analysis kind = 'lambda_sweep' /
&sweep lambdas = $(printf '1.0, %.0s' $(seq 1001)) /"
refused 'item 10: more than 1000 lambdas' 2 "$work/lambdas.nml" -- '&sweep: line 2: lambdas' \
    'at most 1000 values'
printf "&mesh nx = 2 /\n&output directory = '%s', vtk = .trash. /\n" "$out" >"$work/trash.nml"
refused 'item 10: vtk = .trash. is not a logical' 2 "$work/trash.nml" -- \
    '&output: line 2: vtk = .trash.' '.true. or .false.'
refused 'item 10: ... nor through --set' 2 "$work/good.nml" --set 'output%vtk=.trash.' -- \
    '--set' '.true. or .false.'
nml "$work/twice.nml" "&mesh nx = 4,
   nx = 6 /"
refused 'item 10: a variable given twice' 2 "$work/twice.nml" -- '&mesh: line 2: nx' \
    'given twice (first on line 1)'
nml "$work/number.nml" "&material
   young = 1.0e /"
refused 'item 10: an unreadable number names the variable and the line' 2 \
    "$work/number.nml" -- 'number.nml: &material: line 2: young = 1.0e' 'a real number'
touch "$work/in_the_way"
printf "&mesh nx = 4, ny = 2 /\n&output directory = '%s', plot = .false. /\n" \
    "$work/in_the_way/sub/out" >"$work/exit4.nml"
refused 'item 10: exit 4 names the input file and &output directory' 4 "$work/exit4.nml" -- \
    'exit4.nml: &output directory: output directory'
cli_end
