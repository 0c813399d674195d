#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Layer check: a module may `use` modules of its own folder and of folders below it in
# LAYERS, never of a folder above. Files directly in the source folder (main.f90,
# nceig_extrapolate.f90) are the top and may use anything; a folder that does not exist is
# skipped; a folder that is not in LAYERS is an error (place it in the order first).
# Prints one line per violation (file, module used, that module's folder) and exits 1 if
# there is any, 0 otherwise.
# Usage: scripts/dev/check_layers.sh [SRC_DIR]   (default: src/ next to this script)

# Bottom first: each folder may use only the folders to its left (and itself).
LAYERS=(core input sparse element mesh fem contact eigen io analysis)

set -u
src=${1:-$(cd "$(dirname "$0")/../.." && pwd)/src}
src=${src%/}
[[ -d $src ]] || { echo "check_layers: $src is not a directory" >&2; exit 2; }
# Shown paths start at the source folder's own name (src/core/kinds.f90).
base=$(dirname "$src")/

mapfile -t files < <(find "$src" -name '*.f90' -type f | LC_ALL=C sort)

# LAYERS, then every file's top folder ('.' for the top files) and the modules it defines
# and uses, as awk input: the rank check is one awk program over all files.
{
    echo "LAYERS ${LAYERS[*]}"
    for file in "${files[@]}"; do
        relative=${file#"$src"/}
        folder=.
        [[ $relative == */* ]] && folder=${relative%%/*}
        echo "FILE ${file#"$base"} $folder"
        # Lowercase (Fortran is case-blind); `module procedure/function/subroutine` and
        # `end module` do not define a module; `use, intrinsic ::` and `use ::` forms too.
        tr 'A-Z' 'a-z' <"$file" | awk '
            /^[ \t]*module[ \t]+[a-z_0-9]+[ \t]*(!.*)?$/ \
                && $2 != "procedure" && $2 != "function" && $2 != "subroutine" {
                print "DEFINES " $2
            }
            /^[ \t]*use[ \t,:]/ {
                line = $0
                sub(/^[ \t]*use/, "", line)
                sub(/^[ \t]*,[ \t]*(non_)?intrinsic[ \t]*/, "", line)
                sub(/^[ \t]*::/, "", line)
                if (match(line, /^[ \t]*[a-z_][a-z_0-9]*/))
                    print "USES " substr(line, RSTART, RLENGTH)
            }'
    done
} | awk '
    $1 == "LAYERS" { for (i = 2; i <= NF; i++) rank[$i] = i - 1; top = NF; next }
    $1 == "FILE" {
        file = $2; n_files++; files[n_files] = file; folder_of[file] = $3
        if ($3 == ".") file_rank[file] = top
        else if ($3 in rank) file_rank[file] = rank[$3]
        else { print file ": folder " $3 "/ is not in the layer order"; bad = 1 }
        next
    }
    $1 == "DEFINES" { module_folder[$2] = folder_of[file]; next }
    $1 == "USES" && !((file, $2) in seen) {
        seen[file, $2] = 1; n_uses++; use_file[n_uses] = file; use_module[n_uses] = $2; next }
    END {
        for (u = 1; u <= n_uses; u++) {
            file = use_file[u]; module = use_module[u]
            if (!(file in file_rank) || !(module in module_folder)) continue
            folder = module_folder[module]
            if (folder == "." || !(folder in rank)) continue
            if (rank[folder] > file_rank[file]) {
                print file ": uses " module " from " folder "/, above " folder_of[file] "/"
                bad = 1
            }
        }
        exit bad
    }'
