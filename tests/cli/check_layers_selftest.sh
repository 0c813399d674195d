#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# scripts/dev/check_layers.sh on the fake tree tests/data/layers (core/ below mesh/, a top
# main.f90): exactly its one violation, core/low.f90 using `high` of mesh/; nothing and exit
# 0 once that use is gone; a folder outside the layer order is an error.
# Usage: check_layers_selftest.sh SOURCE_DIR
set -u
source_dir=$1
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin check_layers_selftest
checker="$source_dir/scripts/dev/check_layers.sh"
tree="$source_dir/tests/data/layers"

bash "$checker" "$tree" >"$work/out" 2>"$work/err"; rc=$?
check 'fake tree: exit 1' '[[ $rc -eq 1 && ! -s "$work/err" ]]'
check 'fake tree: exactly the one violation, naming file, module and its folder' \
    '[[ $(cat "$work/out") == "layers/core/low.f90: uses high from mesh/, above core/" ]]'

# The same tree without the upward use: clean.
cp -r "$tree" "$work/layers"
sed -i '/^ *use high/d; s/ + high_value()//' "$work/layers/core/low.f90"
bash "$checker" "$work/layers" >"$work/out" 2>&1; rc=$?
check 'without the upward use: exit 0, no output' '[[ $rc -eq 0 && ! -s "$work/out" ]]'

# A folder that is not in the order cannot be ranked: an error, not a silent pass.
mkdir "$work/layers/misc"
cp "$tree/core/base.f90" "$work/layers/misc/extra.f90"
bash "$checker" "$work/layers" >"$work/out" 2>&1; rc=$?
check 'folder outside the order: exit 1, named' \
    '[[ $rc -eq 1 && $(cat "$work/out") == \
       "layers/misc/extra.f90: folder misc/ is not in the layer order" ]]'
cli_end
