#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Quick start 1: install what is missing, build the program (Release; the test programs are
# left to quick start 2, scripts/run_tests.sh) and run the reference scene.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/dev/install_deps.sh"
bash "$root/scripts/dev/build.sh" Release --target nceig
cd "$root"
build/nceig input/square.nml
