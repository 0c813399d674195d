# SPDX-License-Identifier: MIT
# The harness the shell tests source (tests/cli/cli_*.sh, tests/cli/check_layers_selftest.sh): a
# scratch folder, named checks, the closing count line and exit status. It lives in lib/ so
# that the CTest glob tests/cli/cli_*.sh does not run it as a test. After `set -u`:
#     source "$(dirname "$0")/lib/cli_common.sh"
#     cli_begin cli_example          # $work: a fresh scratch folder
#     check 'what it asserts' 'bash condition'
#     cli_end                        # last: prints the count line, exits 1 if any check failed
# KEEP=1 in the environment keeps $work for inspection and prints where it is.

# cli_begin NAME: counters, and $work, removed on exit (even where a test made parts of it
# read-only) unless KEEP is set.
cli_begin() {
    cli_name=$1
    passed=0 failed=0
    work=$(mktemp -d)
    trap cli_remove_work EXIT
    if [[ -n ${KEEP:-} ]]; then echo "work: $work"; fi
}

cli_remove_work() {
    if [[ -n ${KEEP:-} ]]; then return; fi
    chmod -R u+rwx "$work" 2>/dev/null
    rm -rf "$work"
}

# check WHAT CONDITION: evaluate the bash text CONDITION and count a PASS or a FAIL. It runs
# in a subshell, so an `exit 1` inside (a loop over files) fails this check, not the script.
check() {
    if (eval "$2"); then
        passed=$((passed + 1))
        echo "PASS  $1"
    else
        failed=$((failed + 1))
        echo "FAIL  $1"
    fi
}

# cli_skip NAME REASON: nothing can run here (e.g. a tool is missing): one SKIP line, pass.
cli_skip() {
    echo "SKIP  $2"
    echo "$1: 0 passed, 0 failed"
    exit 0
}

# cli_end: the count line; the exit status fails the CTest test if any check failed.
cli_end() {
    echo "$cli_name: $passed passed, $failed failed"
    if [[ $failed -ne 0 ]]; then exit 1; fi
    exit 0
}

# json FILE KEY: the value of the first "KEY": line of a JSON file as nceig writes it (one
# key per line), without its trailing comma, and without the quotes if it is one string.
json() {
    sed -n "s/^ *\"$2\": *\(.*\)$/\1/p" "$1" | head -n 1 | sed 's/,$//; s/^"\([^"]*\)"$/\1/'
}

# drawn DIR FILE: the picture FILE is a non-empty PNG in DIR, listed in DIR/summary.json.
drawn() {
    [[ -s $1/$2 && $(head -c 4 "$1/$2" | tail -c 3) == PNG ]] && grep -q "\"$2\"" "$1/summary.json"
}

# close A B TOL: |A - B| <= TOL |B|, and A is not empty.
close() {
    awk -v a="$1" -v b="$2" -v tol="$3" 'BEGIN {
        d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b
        exit !(a != "" && d <= tol * m) }'
}
