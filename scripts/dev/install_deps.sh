#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install the Debian 12 packages nceig needs to build, test and plot, skipping what is there.
set -euo pipefail
packages=(cmake make gfortran gcc pkg-config libopenblas-dev liblapack-dev libarpack2-dev
          libsuitesparse-dev libmetis-dev gmsh gnuplot-nox time jq parallel)
missing=()
for package in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" \
        || missing+=("$package")
done
if ((${#missing[@]} > 0)); then
    echo "install_deps: installing ${missing[*]}"
    sudo_cmd=()
    [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
    "${sudo_cmd[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
        "${missing[@]}" >/dev/null
fi
