#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# docs/input.md and `nceig --help` (made from the definitions in
# src/input/input_variables.cmake) document the same variables, group by group, in the same
# order, with the same defaults: a variable added to the definitions, renamed or given a
# new default fails here until the reference follows. Usage: cli_input_reference.sh NCEIG SOURCE_DIR
set -u
nceig=$1
source_dir=$2
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_input_reference

# 'group variable default' per line, from the help: '&group ...' opens a group; an entry is
# '    name = value  description' ('f1, f2 = 0.0, 0.0' documents two).
"$nceig" --help 2>&1 | awk '
    /^&/ { group = substr($1, 2); next }
    /^    [a-z]/ && group != "" {
        line = substr($0, 5)
        eq = index(line, " = ")
        names = substr(line, 1, eq - 1)
        rest = substr(line, eq + 3)
        cut = index(rest, "  ")
        values = (cut > 0) ? substr(rest, 1, cut - 1) : rest
        n = split(names, name, ", ")
        split(values, value, ", ")
        if (n == 1) value[1] = values
        for (i = 1; i <= n; i++) print group, name[i], value[i]
    }' >"$work/help"

# The same from the docs: a line '`&group`' opens a group; a row '| `name` | default | ...'
# (or '| `f1`, `f2` | 0.0, 0.0 | ...'), backticks and escapes dropped.
awk -F' [|] ' '
    /^`&[a-z]+`/ { group = substr($1, 3); sub(/`.*/, "", group); next }
    /^[|] `/ && group != "" {
        names = $1; sub(/^[|] /, "", names); gsub(/`/, "", names)
        values = $2; gsub(/`/, "", values)
        n = split(names, name, ", ")
        if (n == 1) { print group, names, values; next }
        split(values, value, ", ")
        for (i = 1; i <= n; i++) print group, name[i], value[i]
    }' "$source_dir/docs/input.md" >"$work/docs"

check "the help documents variables ($(wc -l <"$work/help") of them)" '[[ -s $work/help ]]'
check 'docs/input.md has the help'"'"'s variables, in its order, with its defaults' \
    'diff "$work/help" "$work/docs"'
cli_end
