# SPDX-License-Identifier: MIT
# What the plot scripts (plot_lambda_sweep.sh, plot_adapt.sh) share, sourced after `set -u`:
#     source "$(dirname "$0")/lib/plot_common.sh"
#     plot_begin CSV_NAME 'how to make it' "$@"   # sets dir, csv, summary, terminal, tmp
# plot_begin checks the arguments (OUTDIR [SUMMARY]) and the tools, and arranges that the
# partial picture $tmp is removed if the script ends early (a failed gnuplot must leave
# nothing behind: nceig draws in its staging folder, whose files join the output set).
# value KEY prints a key of the summary.json, read as JSON ('' for null or absent).
# gnuplot_string TEXT prints TEXT as a gnuplot single-quoted string (for paths in the
# gnuplot text: a folder named "Bob's results" must neither break nor extend the commands).

plot_begin() {
    local name=$1 hint=$2 picture=${1%.csv}.png
    shift 2
    if [[ $# -lt 1 || $# -gt 2 ]]; then
        echo "usage: $0 OUTDIR [SUMMARY]  (an nceig output folder with $name)" >&2
        exit 2
    fi
    dir=$1
    csv="$dir/$name"
    summary=${2:-$dir/summary.json}
    for f in "$csv" "$summary"; do
        [[ -r $f ]] || { echo "$0: $f: not found ($hint)" >&2; exit 2; }
    done
    command -v gnuplot >/dev/null || { echo "$0: gnuplot is not installed" >&2; exit 3; }
    command -v jq >/dev/null || { echo "$0: jq is not installed (it reads summary.json)" >&2; exit 3; }
    terminal='pngcairo size 1000,800 enhanced font "sans,11"'
    gnuplot -e 'set terminal' 2>&1 | grep -q pngcairo || terminal='png size 1000,800'
    picture_path="$dir/$picture"
    tmp="$dir/.$picture.partial"
    [[ $dir$summary != *[[:cntrl:]]* ]] ||
        { echo "$0: the path holds a control character, which gnuplot cannot quote" >&2; exit 2; }
    trap 'rm -f "$tmp"' EXIT
}

# A quote is doubled, the one escape of gnuplot's single-quoted strings.
gnuplot_string() { printf "'%s'" "${1//\'/\'\'}"; }

value() { jq -r --arg key "$1" '.[$key] // empty' "$summary"; }

# gnuplot_preamble: the first gnuplot lines of every picture: the terminal, the partial
# file, CSV input, and cell(c), the value of column c or NaN where it is empty (a value
# nceig leaves empty, which breaks the line there).
gnuplot_preamble() {
    printf '%s\n' "set terminal $terminal" "set output $(gnuplot_string "$tmp")" \
        "set datafile separator ','" \
        "cell(c) = strcol(c) eq '' ? NaN : column(c)"
}

# plot_commit: the drawn picture into place, whole.
plot_commit() { mv -f "$tmp" "$picture_path"; }
