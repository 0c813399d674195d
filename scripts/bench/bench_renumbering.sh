#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Node orderings of Delaunay meshes (file order, reverse Cuthill-McKee, METIS) measured by
# scripts/bench/bench_renumbering.f90: scripts/bench/bench_renumbering.sh [N...] (default 64 128 256),
# order-1 meshes of size 1/N made by scripts/make_mesh.sh. Prints a Markdown table.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
sizes=("$@")
[[ ${#sizes[@]} -gt 0 ]] || sizes=(64 128 256)
bash "$root/scripts/dev/build.sh" Release
cmake --build "$root/build" --target bench_renumbering >/dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
files=()
for n in "${sizes[@]}"; do
    bash "$root/scripts/make_mesh.sh" "$n" 1 "$work/delaunay_$n.msh"
    files+=("$work/delaunay_$n.msh")
done
"$root/build/bench_renumbering" "${files[@]}"
