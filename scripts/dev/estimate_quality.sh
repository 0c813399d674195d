#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# How good the error estimate of the lowest positive mu is: estimate / true error, level by
# level, along adaptive P2 runs on several scenes, and on uniform P1, P2 and P3 meshes of the
# reference scene. The true error is against an adaptive P3 run of the same scene to
# 1e-11 (its own estimate, printed, bounds the uncertainty of the true errors).
# Usage: scripts/dev/estimate_quality.sh [TOLERANCE]   (the P2 runs' tolerance, default 1e-7)
# Levels from the 5th on and with a true error above 100 times the reference's estimate
# count; the table gives min / median / max of the ratio and the share of levels with the
# ratio in [0.5, 2] and in [1, 10]. Needs gmsh (the partial-contact scene) and jq. Several
# minutes on 2 cores (the references).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
nceig=${NCEIG:-$root/build/nceig}
tolerance=${1:-1e-7}
[[ -x $nceig ]] || { echo "estimate_quality: build first (scripts/dev/build.sh Release)" >&2; exit 1; }
command -v jq >/dev/null || { echo "estimate_quality: needs jq" >&2; exit 1; }
command -v gmsh >/dev/null || { echo "estimate_quality: needs gmsh" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source "$root/scripts/lib/bench_common.sh"   # key FILE KEY

for order in 2 3; do
    gmsh "$root/input/meshes/half_contact.geo" -2 -clmax 0.25 -order $order -format msh41 \
        -o "$work/half_p$order.msh" >/dev/null
done

# scene NAME: the &mesh, &material and &analysis lines of a scene, for element EL
scene() {
    local name=$1 el=$2
    case $name in
        reference) echo "&mesh nx = 4, ny = 4, element = '$el' / &analysis lambda = 5.0 /" ;;
        lambda-3) echo "&mesh nx = 4, ny = 4, element = '$el' / &analysis lambda = -3.0 /" ;;
        nu0.45-lambda20) echo "&mesh nx = 4, ny = 4, element = '$el' / &material poisson = 0.45 /
            &analysis lambda = 20.0 /" ;;
        nu0.1) echo "&mesh nx = 4, ny = 4, element = '$el' / &material poisson = 0.1 /
            &analysis lambda = 5.0 /" ;;
        wide3x1) echo "&mesh width = 3.0, height = 1.0, nx = 12, ny = 4, element = '$el' /
            &analysis lambda = 5.0 /" ;;
        half-contact) echo "&mesh source = 'gmsh', file = '$work/half_${el}.msh',
            dirichlet = 'top', neumann = 'bottom_free right left', contact = 'contact' /
            &analysis lambda = -3.0 /" ;;
    esac
}

# run NAME EL TOLERANCE OUT [SETTINGS...]
run() {
    local name=$1 el=$2 tol=$3 out=$4
    shift 4
    {
        scene "$name" "$el"
        echo "&eigen estimate = 'on' /"
        echo "&output directory = '$work/$out', vtk = .false., plot = .false., progress = .false. /"
        echo "&adapt tolerance = $tol /"
    } >"$work/$out.nml"
    "$nceig" "$work/$out.nml" "$@" >/dev/null || { echo "estimate_quality: $out failed" >&2; exit 1; }
}

# ratios REFERENCE REFERENCE_ESTIMATE: estimate/true of the adapt.csv rows on stdin
ratios() {
    awk -F, -v ref="$1" -v floor="$2" 'NR > 1 && $1 >= 5 && $6 != "" {
        t = ($5 - ref) / ref; if (t < 0) t = -t
        if (t > 100 * floor) print $6 / t }'
}
summary_of() {   # min median max share[0.5,2] share[1,10] of the ratios on stdin
    sort -g | awk '{ v[NR] = $1; if ($1 >= 0.5 && $1 <= 2) a++; if ($1 >= 1 && $1 <= 10) b++ }
        END { if (NR == 0) { print "no level counts"; exit }
              printf "%7.2f %7.2f %7.2f %6.0f%% %6.0f%% %4d", v[1], v[int((NR + 1) / 2)], v[NR],
                     100 * a / NR, 100 * b / NR, NR }'
}

echo "# nceig $("$nceig" --version | cut -d' ' -f2): estimate / true error, adaptive P2 to $tolerance"
printf '%-16s %-20s %9s | %7s %7s %7s %7s %7s %4s\n' scene 'reference mu' 'its est.' min median \
    max '[.5,2]' '[1,10]' n
for name in reference lambda-3 nu0.45-lambda20 nu0.1 wide3x1 half-contact; do
    el=p3
    run "$name" $el 1e-11 ref --set adapt%max_dofs=400000 --set adapt%max_levels=200
    ref_mu=$(key "$work/ref/summary.json" lowest_positive_mu)
    ref_est=$(key "$work/ref/summary.json" lowest_positive_error_estimate)
    if [[ -z $ref_mu ]]; then
        printf '%-16s no positive mu\n' "$name"
        continue
    fi
    run "$name" p2 "$tolerance" p2 --set adapt%max_levels=200
    printf '%-16s %-20s %9.1e | %s\n' "$name" "$ref_mu" "$ref_est" \
        "$(ratios "$ref_mu" "$ref_est" <"$work/p2/adapt.csv" | summary_of)"
    if [[ $name == reference ]]; then reference_mu=$ref_mu; fi
done

echo
echo "uniform meshes of the reference scene (no adaptation): estimate / true error"
printf '%4s %5s %8s %10s %10s %7s\n' el N dofs estimate true ratio
for el in p1 p2 p3; do
    for n in 8 16 32; do
        run reference "$el" 0 uni --set mesh%nx=$n --set mesh%ny=$n
        s=$work/uni/summary.json
        awk -v e="$(key "$s" lowest_positive_error_estimate)" -v mu="$(key "$s" lowest_positive_mu)" \
            -v ref="$reference_mu" -v el=$el -v n=$n -v dofs="$(key "$s" n_dofs)" 'BEGIN {
            t = (mu - ref) / ref; if (t < 0) t = -t
            printf "%4s %5s %8s %10.2e %10.2e %7.2f\n", el, n, dofs, e, t, e / t }'
    done
done
