#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The BLAS thread policy end to end (docs/performance.md, "BLAS threads"): with no thread
# variable set, nceig gives the small factor of the reference scene one thread, whatever the
# cores (summary.json blas_threads 1, blas_threads_source 'nceig'); a count the user sets in
# OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS or OMP_NUM_THREADS is kept (2 where the policy
# would say 1; OpenBLAS caps it at the cores), and a zero count is no setting, as for
# OpenBLAS. The counts reported under the environment are
# OpenBLAS's own (openblas_get_num_threads), so they check nceig's reading of the variables
# against OpenBLAS's. With another BLAS (no openblas_set_num_threads) the source is 'blas'
# and the count 1. No timing is asserted.
# Usage: cli_blas_threads.sh NCEIG SOURCE_DIR
set -u
nceig=$1
root=$2
source "$(dirname "$0")/lib/cli_common.sh"
cli_begin cli_blas_threads

cores=$(nproc)
two=$((cores < 2 ? cores : 2))   # OpenBLAS never starts more threads than cores

# run NAME VAR=VALUE...: the reference scene, 2112 dofs, under exactly the given thread
# variables; its summary is $work/NAME/summary.json
run() {
    local name=$1
    shift
    env -u OPENBLAS_NUM_THREADS -u GOTO_NUM_THREADS -u OMP_NUM_THREADS "$@" \
        "$nceig" "$root/input/square.nml" --set output%vtk=.false. --set output%plot=.false. \
        --set "output%directory=$work/$name" >"$work/$name.out" 2>&1
}
# threads NAME: "count source" of run NAME
threads() { echo "$(json "$work/$1/summary.json" blas_threads)" \
    "$(json "$work/$1/summary.json" blas_threads_source)"; }

run policy
library=$(json "$work/policy/summary.json" blas_library)
if [[ $library != *openblas* ]]; then
    check "another BLAS ($library): one thread, source blas" '[[ $(threads policy) == "1 blas" ]]'
    run user OPENBLAS_NUM_THREADS=2
    check 'another BLAS: OPENBLAS_NUM_THREADS=2 is the environment'\''s, one thread' \
        '[[ $(threads user) == "1 environment" ]]'
    cli_end
fi
check 'no variable set: the small factor (2112 dofs < 2 x 20000) gets 1 thread, by nceig' \
    '[[ $(json "$work/policy/summary.json" n_dofs) -lt 40000 && $(threads policy) == "1 nceig" ]]'
run openblas OPENBLAS_NUM_THREADS=2
check "OPENBLAS_NUM_THREADS=2 is kept: $two thread(s), from the environment" \
    '[[ $(threads openblas) == "$two environment" ]]'
run one OPENBLAS_NUM_THREADS=1
check 'OPENBLAS_NUM_THREADS=1 is kept: 1 thread, from the environment' \
    '[[ $(threads one) == "1 environment" ]]'
run goto GOTO_NUM_THREADS=2
check "GOTO_NUM_THREADS=2 alone is kept: $two thread(s)" '[[ $(threads goto) == "$two environment" ]]'
run omp OMP_NUM_THREADS=2
check "OMP_NUM_THREADS=2 alone is kept: $two thread(s)" '[[ $(threads omp) == "$two environment" ]]'
run zero OPENBLAS_NUM_THREADS=0
check 'OPENBLAS_NUM_THREADS=0 is no setting (OpenBLAS ignores it): nceig chooses 1' \
    '[[ $(threads zero) == "1 nceig" ]]'
# the thread count changes the order of sums only: the same mu to round-off (the input's
# headline, 0.7516698639179173, to 1e-10 relative, far above round-off and far below the
# next mesh's change)
check 'every run gives the reference scene'\''s lowest mu' \
    'for d in policy openblas one goto omp zero; do
         close "$(json "$work/$d/summary.json" lowest_positive_mu)" 0.7516698639179173 1e-10 ||
             exit 1
     done'
cli_end
