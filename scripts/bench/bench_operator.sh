#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The two ARPACK operators on the reference scene (P1 'right', N x N, lambda = 5): &eigen
# operator = 'reduced' (p x p, O(p^2) per step after an O(p^3)-free setup) against 'full'
# ((K - target B)^-1 B in the n free dofs), and, where python3-slepc4py is installed,
# SLEPc's Krylov-Schur with shift-and-invert and MUMPS on the same K.mtx and B.mtx.
# Usage: scripts/bench/bench_operator.sh [--target T] [--slepc-max N] [REPEATS] [N ...]
#   defaults: target 0, SLEPc up to N = 512 (the Matrix Market text of N = 1024 is 1.3 GB),
#   3 repeats, N = 64 128 256 512 1024.
# Every run of one N alternates the operators, so that load from other jobs falls on both;
# columns are medians over the repeats. eigen = time_eigen_s of summary.json (for 'full' it
# includes the UMFPACK factorization of K - target B; both share the Cholesky factor of K,
# time_factor_s, which is not in it), total = time_total_s, peakMB = maximum resident set
# from /usr/bin/time -v, ops = operator applications (summary.json; SLEPc: KSPSolve calls).
# ratio = full eigen / reduced eigen in the same runs. SLEPc: setup + solve with the
# matrices in memory (nev = 6 nearest the target, tol 1e-12: one run, where nceig makes
# at least two to certify), its peak includes Python and the text reader.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
target=0
slepc_max=512
while [[ ${1:-} == --* ]]; do
    case $1 in
        --target) target=$2 ;;
        --slepc-max) slepc_max=$2 ;;
        *) echo "bench_operator: unknown option $1" >&2; exit 2 ;;
    esac
    shift 2
done
source "$root/scripts/lib/bench_common.sh"
bench_begin bench_operator "$@"

# Debian installs SLEPc and PETSc under versioned folders; without the alternatives set,
# slepc4py's .pth file needs them named
python=/usr/bin/python3
for dir in /usr/lib/petscdir/petsc3.*/x86_64-linux-gnu-real; do
    [[ -d $dir ]] && export PETSC_DIR=${PETSC_DIR:-$dir}
done
for dir in /usr/lib/slepcdir/slepc3.*/x86_64-linux-gnu-real; do
    [[ -d $dir ]] && export SLEPC_DIR=${SLEPC_DIR:-$dir}
done
slepc=no
"$python" -c 'import slepc4py' 2>/dev/null && slepc=yes

peak_mb() { grep 'Maximum resident' "$1" | awk '{print $NF / 1024}'; }

# write_input N OPERATOR MATRICES [NAME]: the input file NAME.nml of one run, output in NAME/
write_input() {
    local name=${4:-$2}
    cat >"$work/$name.nml" <<NML
&mesh nx = $1, ny = $1, element = 'p1', diagonal = 'right' /
&analysis kind = 'eigen', lambda = 5.0 /
&eigen solver = 'arpack', operator = '$2', target = $target, estimate = 'off' /
&output directory = '$work/$name', vtk = .false., plot = .false., matrices = $3 /
NML
}

echo "# nceig $("$nceig" --version | cut -d' ' -f2), $(nproc) cores, target = $target," \
    "SLEPc: $slepc, load at start: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%5s %8s %5s | %7s %7s %7s %5s | %7s %7s %7s %5s | %5s | %7s %7s %5s | %s\n' N dofs p \
    red_eig red_tot red_MB ops full_eig full_tot full_MB ops ratio slepc slepcMB ops \
    'max |mu - mu_reduced| / mu'
for n in "${sizes[@]}"; do
    declare -A col=()
    for operator in reduced full; do write_input "$n" $operator .false.; done
    for ((r = 1; r <= repeats; r++)); do
        for operator in reduced full; do
            /usr/bin/time -v "$nceig" "$work/$operator.nml" >"$work/stdout" 2>"$work/time" \
                || { cat "$work/time" >&2; exit 1; }
            s=$work/$operator/summary.json
            col[$operator.eigen]="${col[$operator.eigen]:-} $(key "$s" time_eigen_s)"
            col[$operator.total]="${col[$operator.total]:-} $(key "$s" time_total_s)"
            col[$operator.peak]="${col[$operator.peak]:-} $(peak_mb "$work/time")"
            col[$operator.ops]=$(key "$s" operator_applications)
            col[$operator.mu]=$(key "$s" lowest_positive_mu)
        done
        col[ratio]="${col[ratio]:-} $(awk -v f="$(key "$work/full/summary.json" time_eigen_s)" \
            -v r="$(key "$work/reduced/summary.json" time_eigen_s)" 'BEGIN { print f / r }')"
    done
    slepc_time=- slepc_peak=- slepc_ops=- slepc_mu=-
    if [[ $slepc == yes ]] && ((n <= slepc_max)); then
        write_input "$n" reduced .true. export
        "$nceig" "$work/export.nml" >/dev/null
        times=''
        peaks=''
        for ((r = 1; r <= repeats; r++)); do
            /usr/bin/time -v "$python" "$root/scripts/bench/bench_slepc.py" "$work/export" "$target" \
                6 1e-12 >"$work/slepc" 2>"$work/time" || { cat "$work/time" >&2; exit 1; }
            read -r seconds slepc_ops slepc_mu _ <"$work/slepc"
            times="$times $seconds"
            peaks="$peaks $(peak_mb "$work/time")"
        done
        slepc_time=$(echo "$times" | median)
        slepc_peak=$(echo "$peaks" | median)
        rm -rf "$work/export"
    fi
    med() { echo "${col[$1]}" | median; }
    deviation=$(awk -v a="${col[full.mu]}" -v b="${col[reduced.mu]}" -v c="$slepc_mu" 'BEGIN {
        d = (a - b) / b; d = d < 0 ? -d : d
        if (c != "none" && c != "-") { e = (c - b) / b; e = e < 0 ? -e : e; c = sprintf("%.1e", e) }
        printf "full %.1e, slepc %s", d, c }')
    printf '%5d %8d %5d | %7.3f %7.3f %7.0f %5d | %7.3f %7.3f %7.0f %5d | %5.2f | %7s %7s %5s | %s\n' \
        "$n" "$(key "$work/reduced/summary.json" n_dofs)" \
        "$(key "$work/reduced/summary.json" n_contact)" "$(med reduced.eigen)" \
        "$(med reduced.total)" "$(med reduced.peak)" "${col[reduced.ops]}" "$(med full.eigen)" \
        "$(med full.total)" "$(med full.peak)" "${col[full.ops]}" "$(med ratio)" \
        "$slepc_time" "${slepc_peak%.*}" "$slepc_ops" "$deviation"
    unset col
done
echo "# times in s, medians of $repeats runs; load at end: $(cut -d' ' -f1-3 /proc/loadavg)"
