#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Outputs before and after a change that must not change them (a refactor): every example
# of input/ and the scenes of the tests that run in seconds (h and hp adaptive eigen and
# threshold runs, lambda sweeps adapted by h and hp, branch, solve, dense and ARPACK, P1 to
# P4, Q1, Q2, Gmsh meshes, limits, extreme inputs), each on one BLAS thread, compared to the
# last digit: summary.json line by line but for the timings (time_*_s), every CSV file cell
# by cell but for the time_s column, every other file of the set byte for byte (.vtu, .msh,
# .mtx; not the pictures), the exit status, stderr, and stdout with its times masked.
#
#   compare_outputs.sh baseline NCEIG DIR   run NCEIG on every scene into DIR: DIR/scenes
#                                           (the inputs: input/ copied, the Gmsh meshes made
#                                           once) and DIR/runs/NAME (out/, stdout, stderr, rc)
#   compare_outputs.sh check NCEIG DIR [NEW]
#                                           run NCEIG on DIR's scenes into NEW (default
#                                           DIR.new) and compare with DIR/runs
#   compare_outputs.sh compare DIR NEW      compare two run folders made from DIR's scenes
#
# Prints one line per difference and a last line with the counts (runs, files, values);
# exits 1 on any difference. gmsh makes the Gmsh scenes at baseline time (skipped without it).
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1

usage() { sed -n '/^#   compare_outputs/,/^# Prints/p' "$0" >&2; exit 2; }

# NAME|NAMELIST (in scenes/)|--set arguments: every run
scene_list() {
    local f
    for f in "$scenes"/input/*.nml; do
        echo "$(basename "$f" .nml)|input/$(basename "$f")|"
    done
    cat <<'LIST'
adapt_hp|input/adapt.nml|adapt%strategy=hp
adapt_hp_limit|input/adapt.nml|adapt%strategy=hp adapt%max_levels=2
adapt_h_limit|input/adapt.nml|adapt%max_levels=2
adapt_h_dofs|input/adapt.nml|adapt%max_dofs=600
adapt_hp_dofs|input/adapt.nml|adapt%strategy=hp adapt%max_dofs=2000
adapt_hp_dense|hp.nml|eigen%solver='dense'
adapt_hp_floor|hp.nml|adapt%tolerance=1e-14
threshold_adapt_hp|input/threshold_adapt.nml|adapt%strategy=hp
threshold_hp_floor|hp_threshold.nml|adapt%tolerance=1e-13
threshold_hp_limit|hp_threshold.nml|adapt%max_levels=3
threshold_h_limit|input/threshold_adapt.nml|adapt%max_levels=3
sweep_adapt_h|sweep_adapt.nml|
sweep_adapt_hp|sweep_adapt.nml|adapt%strategy=hp
sweep_arpack|sweep_small.nml|eigen%solver='arpack'
sweep_dense|sweep_small.nml|eigen%solver='dense'
sweep_log|sweep_small.nml|sweep%spacing='log' sweep%lambda_min=0.5 sweep%lambda_max=50.0
p4|p4.nml|
p4_threshold|p4.nml|analysis%kind='threshold'
q1_lambda-3|q1.nml|
q1_threshold|q1.nml|analysis%kind='threshold' eigen%estimate='on'
q2_threshold|q2.nml|analysis%kind='threshold' eigen%estimate='on'
p2_threshold|p2_8.nml|analysis%kind='threshold'
p3_nu0.45|p3_4.nml|
rect2x1_p1|rect2x1.nml|
rect3x1_adapt_p2|rect3x1.nml|
arpack_full|input/square.nml|eigen%operator='full'
arpack_target|input/square.nml|eigen%target=0.5 eigen%cn_max=20.0
arpack_full_target|input/square.nml|eigen%operator='full' eigen%target=0.7
estimate_off|input/square.nml|eigen%estimate='off'
threshold_estimate_off|input/threshold.nml|eigen%estimate='off'
threshold_dense|input/threshold.nml|eigen%solver='dense'
branch_dense|input/branch.nml|eigen%solver='dense'
solve_branch_mode|input/solve_branch.nml|solve%start='mode' solve%start_scale=0.01
scaled_units|scaled.nml|
extreme_young|input/square.nml|material%young=1e308
extreme_width|input/square.nml|mesh%width=1e-12
extreme_lambda|input/square.nml|analysis%lambda=1.7e308
extreme_sweep|extreme_sweep.nml|
extreme_sweep_refused|extreme_sweep.nml|sweep%lambdas=5,1.7e308
extreme_target|input/square.nml|eigen%solver='arpack' eigen%target=1e300
branch_young|input/branch.nml|material%young=1e308
hp_quads|hp.nml|mesh%element='q1'
adapt_q1|q1.nml|adapt%tolerance=1e-3
single_element_threshold|input/single_element.nml|analysis%kind='threshold'
single_element_sweep|input/single_element.nml|analysis%kind='lambda_sweep' sweep%n_lambda=41
LIST
    if [[ -f $scenes/meshes/trap8.msh ]]; then
        cat <<'LIST'
trapezoid_p2|trapezoid.nml|
trapezoid_adapt_onsets|trapezoid.nml|analysis%kind='threshold' adapt%tolerance=1e-4
half_p1|half.nml|
middle_p2|middle.nml|
middle_hp|middle.nml|mesh%file='meshes/middle1.msh' adapt%tolerance=1e-10 adapt%strategy='hp'
middle_hp_threshold|middle.nml|mesh%file='meshes/middle1.msh' adapt%tolerance=1e-10 adapt%strategy='hp' analysis%kind='threshold'
trapezoid_hp_onsets|trapezoid_hp.nml|
half_hp_onsets|half_hp.nml|
half_contact_adapt|input/half_contact.nml|adapt%tolerance=1e-3 sweep%lambda_min=-3.0 sweep%lambda_max=3.0
gmsh_p2_halved_threshold|trapezoid.nml|analysis%kind='threshold' mesh%file='meshes/trap8_p1.msh'
LIST
    fi
}

# The scenes' inputs: input/ as it is now, the namelists of the test scenes, Gmsh meshes.
make_scenes() {
    mkdir -p "$scenes/meshes"
    cp -r "$root/input" "$scenes/input"
    local out="&output vtk = .true., plot = .false. /"
    cat >"$scenes/hp.nml" <<NML
&mesh nx = 2, ny = 2, element = 'p1' /
&analysis kind = 'eigen', lambda = 5.0 /
&adapt tolerance = 1e-10, strategy = 'hp' /
$out
NML
    cat >"$scenes/hp_threshold.nml" <<NML
&mesh nx = 2, ny = 2, element = 'p1' /
&analysis kind = 'threshold', lambda = 5.0 /
&adapt tolerance = 1e-10, strategy = 'hp' /
&output vtk = .false. /
NML
    cat >"$scenes/sweep_adapt.nml" <<NML
&mesh nx = 2, ny = 2, element = 'p2' /
&analysis kind = 'lambda_sweep', lambda = 5.0 /
&sweep lambdas = -5.0, -3.0, -1.0, 1.0, 3.0, 5.0, 12.0 /
&adapt tolerance = 1e-6 /
&output vtk = .false. /
NML
    cat >"$scenes/sweep_small.nml" <<NML
&mesh nx = 16, ny = 16, element = 'p1' /
&analysis kind = 'lambda_sweep', lambda = 5.0 /
&sweep lambda_min = -20.0, lambda_max = 20.0, n_lambda = 81 /
&output vtk = .false. /
NML
    cat >"$scenes/p4.nml" <<NML
&mesh nx = 4, ny = 4, element = 'p4' /
&analysis lambda = 5.0 /
$out
NML
    cat >"$scenes/q1.nml" <<NML
&mesh nx = 8, ny = 8, element = 'q1' /
&analysis lambda = -3.0 /
&output vtk = .true., plot = .false., matrices = .true. /
NML
    cat >"$scenes/q2.nml" <<NML
&mesh nx = 4, ny = 4, element = 'q2' /
&analysis lambda = 5.0 /
$out
NML
    cat >"$scenes/p2_8.nml" <<NML
&mesh nx = 8, ny = 8, element = 'p2' /
&analysis lambda = 5.0 /
$out
NML
    cat >"$scenes/p3_4.nml" <<NML
&mesh nx = 4, ny = 4, element = 'p3' /
&material poisson = 0.45 /
&analysis lambda = 20.0 /
$out
NML
    cat >"$scenes/rect2x1.nml" <<NML
&mesh width = 2, nx = 16, ny = 8, element = 'p1' /
&material poisson = 0.25 /
&analysis lambda = -4.0 /
$out
NML
    cat >"$scenes/rect3x1.nml" <<NML
&mesh width = 3, nx = 6, ny = 2, element = 'p2' /
&adapt tolerance = 1e-6 /
$out
NML
    cat >"$scenes/scaled.nml" <<NML
&mesh nx = 4, ny = 4, width = 9.5367431640625e-07, height = 9.5367431640625e-07 /
&material young = 1073741824.0 /
&output matrices = .true., vtk = .true., plot = .false. /
NML
    cat >"$scenes/extreme_sweep.nml" <<NML
&analysis kind = 'lambda_sweep' /
&sweep lambdas = 1e300, 1e160, 5, plot = .false. /
&output vtk = .false. /
NML
    command -v gmsh >/dev/null 2>&1 || { echo "compare_outputs: no gmsh: Gmsh scenes skipped"; return; }
    local truths=$root/tests/data/truths
    gmsh "$truths/trapezoid.geo" -setnumber graded 0 -clmax 0.125 -2 -order 2 -format msh41 \
        -o "$scenes/meshes/trap8.msh" >/dev/null
    gmsh "$truths/trapezoid.geo" -setnumber graded 0 -clmax 0.125 -2 -order 1 -format msh41 \
        -o "$scenes/meshes/trap8_p1.msh" >/dev/null
    gmsh "$truths/trapezoid.geo" -setnumber graded 0 -clmax 0.3 -2 -order 1 -format msh41 \
        -o "$scenes/meshes/trap_hp.msh" >/dev/null
    gmsh "$truths/half_contact.geo" -setnumber algorithm 1 -setnumber graded 0 -clmax 0.0625 \
        -2 -order 1 -format msh41 -o "$scenes/meshes/half16.msh" >/dev/null
    gmsh "$truths/half_contact.geo" -setnumber algorithm 1 -setnumber graded 0 -clmax 0.3 \
        -2 -order 1 -format msh41 -o "$scenes/meshes/half_hp.msh" >/dev/null
    cat >"$scenes/middle.geo" <<'GEO'
Point(1) = {0, 0, 0, 1e22}; Point(2) = {0.25, 0, 0, 1e22}; Point(3) = {0.75, 0, 0, 1e22};
Point(4) = {1, 0, 0, 1e22}; Point(5) = {1, 1, 0, 1e22}; Point(6) = {0, 1, 0, 1e22};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6};
Line(6) = {6, 1}; Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Plane Surface(1) = {1};
Physical Curve("free_bottom") = {1, 3}; Physical Curve("contact") = {2};
Physical Curve("right") = {4}; Physical Curve("top") = {5}; Physical Curve("left") = {6};
Physical Surface("body") = {1};
Mesh.Algorithm = 5;
GEO
    gmsh "$scenes/middle.geo" -2 -order 2 -clmax 0.0625 -format msh41 \
        -o "$scenes/meshes/middle.msh" >/dev/null
    gmsh "$scenes/middle.geo" -2 -order 1 -clmax 0.5 -format msh41 \
        -o "$scenes/meshes/middle1.msh" >/dev/null
    cat >"$scenes/trapezoid.nml" <<NML
&mesh source = 'gmsh', file = 'meshes/trap8.msh', dirichlet = 'top', neumann = 'left right', contact = 'bottom' /
&analysis lambda = 5.0 /
&sweep lambda_min = -3.0, lambda_max = 3.0 /
$out
NML
    cat >"$scenes/trapezoid_hp.nml" <<NML
&mesh source = 'gmsh', file = 'meshes/trap_hp.msh', dirichlet = 'top', neumann = 'left right', contact = 'bottom' /
&analysis kind = 'threshold', lambda = 5.0 /
&adapt tolerance = 1e-8, strategy = 'hp' /
&sweep lambda_min = -3.0, lambda_max = 3.0 /
&output vtk = .true., plot = .false. /
NML
    cat >"$scenes/half.nml" <<NML
&mesh source = 'gmsh', file = 'meshes/half16.msh', dirichlet = 'top', neumann = 'left right bottom_free', contact = 'contact' /
&analysis lambda = -3.0 /
$out
NML
    cat >"$scenes/half_hp.nml" <<NML
&mesh source = 'gmsh', file = 'meshes/half_hp.msh', dirichlet = 'top', neumann = 'left right bottom_free', contact = 'contact' /
&analysis kind = 'threshold', lambda = -3.0 /
&adapt tolerance = 1e-8, strategy = 'hp', max_levels = 5 /
&sweep lambda_min = -3.0, lambda_max = 3.0 /
&output vtk = .false. /
NML
    cat >"$scenes/middle.nml" <<NML
&mesh source = 'gmsh', file = 'meshes/middle.msh', dirichlet = 'top', neumann = 'left right free_bottom', contact = 'contact' /
&analysis lambda = 10.0 /
$out
NML
}

# run_all NCEIG RUNS: every scene into RUNS/NAME
run_all() {
    local nceig=$1 runs=$2 line name nml sets args s start
    mkdir -p "$runs"
    while IFS='|' read -r name nml sets; do
        [[ -n $name ]] || continue
        args=()
        for s in $sets; do args+=(--set "$s"); done
        rm -rf "${runs:?}/$name"
        mkdir -p "$runs/$name"
        start=$SECONDS
        (cd "$scenes" && "$nceig" "$nml" --set "output%directory='$runs/$name/out'" \
            "${args[@]}" >"$runs/$name/stdout" 2>"$runs/$name/stderr"; echo $? >"$runs/$name/rc")
        echo "  $name: exit $(cat "$runs/$name/rc"), $((SECONDS - start)) s"
    done < <(scene_list)
}

# The comparable text of a file: CSV without its time_s column, summary.json without its
# time keys, stdout with its times masked (progress ticks depend on time: dropped).
normalized() {
    local file=$1 runs=$2
    case $file in
        *.csv)
            awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "time_s") skip = i }
                { line = ""; for (i = 1; i <= NF; i++) if (i != skip) line = line (i > 1 ? "," : "") $i
                  print line }' "$file" ;;
        *summary.json) grep -v '^ *"time_[a-z_]*_s":' "$file" ;;
        */stdout)
            sed -E -e "s#$runs#RUNS#g" -e '/^  \.\. sweep, lambda [0-9]+\/[0-9]+$/d' \
                -e 's/^(  \.\. [a-z]+ +)[0-9.]+ s/\1T s/' -e 's/^(  time \[s\] ).*/\1T/' \
                "$file" ;;
        */stderr) sed -e "s#$runs#RUNS#g" "$file" ;;
        *) cat "$file" ;;
    esac
}

# values FILE: how many values a normalized CSV or summary.json holds
values() {
    case $1 in
        *.csv) awk -F, 'NR > 1 { n += NF } END { print n + 0 }' ;;
        *.json) jq '[paths(scalars)] | length' ;;
        *) echo 0 ;;
    esac
}

compare() {
    local old=$1 new=$2 runs=0 files=0 n_values=0 differences=0 name f rel a b
    for name in $(cd "$old" && ls); do
        runs=$((runs + 1))
        if [[ ! -d $new/$name ]]; then
            echo "DIFF $name: no run in $new"; differences=$((differences + 1)); continue
        fi
        # the sets of files must agree
        a=$(cd "$old/$name" && find . -type f ! -name '*.png' | LC_ALL=C sort)
        b=$(cd "$new/$name" && find . -type f ! -name '*.png' | LC_ALL=C sort)
        if [[ $a != "$b" ]]; then
            echo "DIFF $name: files differ:"; diff <(echo "$a") <(echo "$b") | sed 's/^/    /'
            differences=$((differences + 1))
        fi
        for rel in $a; do
            f=$old/$name/$rel
            [[ -f $new/$name/$rel ]] || continue
            files=$((files + 1))
            if ! cmp -s <(normalized "$f" "$old") <(normalized "$new/$name/$rel" "$new"); then
                echo "DIFF $name/${rel#./}:"
                diff <(normalized "$f" "$old") <(normalized "$new/$name/$rel" "$new") | head -n 12 |
                    sed 's/^/    /'
                differences=$((differences + 1))
            fi
            n_values=$((n_values + $(normalized "$f" "$old" | values "$f")))
        done
    done
    echo "compare_outputs: $runs runs, $files files, $n_values values (CSV cells and" \
        "summary.json scalars) compared: $differences differences"
    [[ $differences -eq 0 ]]
}

action=${1:-}
case $action in
    baseline)
        [[ $# -eq 3 ]] || usage
        nceig=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
        dir=$(mkdir -p "$3" && cd "$3" && pwd)
        scenes=$dir/scenes
        rm -rf "$scenes" "$dir/runs"
        make_scenes
        run_all "$nceig" "$dir/runs" ;;
    check)
        [[ $# -ge 3 ]] || usage
        nceig=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
        dir=$(cd "$3" && pwd)
        new=${4:-$dir.new}
        new=$(mkdir -p "$new" && cd "$new" && pwd)
        scenes=$dir/scenes
        run_all "$nceig" "$new"
        compare "$dir/runs" "$new" ;;
    compare)
        [[ $# -eq 3 ]] || usage
        dir=$(cd "$2" && pwd)
        scenes=$dir/scenes
        compare "$dir/runs" "$(cd "$3" && pwd)" ;;
    *) usage ;;
esac
