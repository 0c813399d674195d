# SPDX-License-Identifier: MIT
# The scenes of the independent truths (tests/data/truths.csv, docs/accuracy.md,
# "Independent truths"), shared by scripts/dev/continuum_truths.sh and scripts/dev/bar_quality.sh.
# Sourced with $root set. E = 1, top fixed, the other sides free, contact on the bottom
# unless said.
truth_scenes=(ref lambda-3 nu0.45-lambda20 nu0.1 rect3x1 rect2x1-nu0.25-lambda-4 trapezoid half-contact ref-threshold
    trapezoid-threshold trapezoid-nu0.1-threshold half-contact-threshold rect3x1-threshold
    nu0.1-threshold)

# scene_info NAME: sets geo (the .geo of tests/data/truths), gset (its -setnumber
# arguments), W, H (rectangle size; W = '' for a shape that is not a rectangle), nu,
# lam, kind ('eigen' or 'threshold'), contact, neumann (the physical groups), onsets (for a
# threshold scene whose critical lambdas are collision onsets, not the pencil's lambda+-: the
# summary.json keys of its truths)
scene_info() {
    geo=$root/tests/data/truths/rectangle.geo gset=() W=1 H=1 nu=0.3 lam=5.0 kind=eigen
    contact=bottom neumann='left right' onsets=
    case $1 in
        ref) ;;
        lambda-3) lam=-3.0 ;;
        nu0.45-lambda20) nu=0.45 lam=20.0 ;;
        nu0.1) nu=0.1 ;;
        rect3x1) W=3 gset=(-setnumber W 3) ;;
        rect2x1-nu0.25-lambda-4) W=2 gset=(-setnumber W 2) nu=0.25 lam=-4.0 ;;
        trapezoid) geo=$root/tests/data/truths/trapezoid.geo W= ;;
        half-contact) geo=$root/tests/data/truths/half_contact.geo W= lam=-3.0 contact=contact
            neumann='left right bottom_free'
            # Gmsh's Delaunay (and Frontal-Delaunay) algorithm leaves a zero-area boundary
            # sliver at (1/2, 0) for hmin = 1e-6; MeshAdapt does not
            gset=(-setnumber algorithm 1) ;;
        ref-threshold) kind=threshold ;;
        rect3x1-threshold) scene_info rect3x1; kind=threshold ;;
        nu0.1-threshold) scene_info nu0.1; kind=threshold ;;
        # a positive mu appears at a collision of two real mu on both sides (mirror images),
        # inside the pencil's lambda+- (not confirmed)
        trapezoid-threshold) geo=$root/tests/data/truths/trapezoid.geo W= kind=threshold
            onsets='lambda_onset_plus lambda_onset_minus' ;;
        trapezoid-nu0.1-threshold) scene_info trapezoid-threshold; nu=0.1 ;;
        # a positive mu vanishes at a collision as lambda rises through lambda_onset_minus
        half-contact-threshold) scene_info half-contact; kind=threshold
            onsets=lambda_onset_minus ;;
        *) echo "truth_scenes: unknown scene $1" >&2; return 1 ;;
    esac
}

# scene_mesh_nml FILE: the &mesh line of a Gmsh mesh of the current scene
scene_mesh_nml() {
    echo "&mesh source = 'gmsh', file = '$1', dirichlet = 'top', neumann = '$neumann', contact = '$contact' /"
}

# scene_rect_nml N ELEMENT: the &mesh line of the rectangle with N cells per unit length
scene_rect_nml() {
    echo "&mesh width = $W, height = $H, nx = $(($1 * W)), ny = $(($1 * H)), element = '$2' /"
}

# scene_physics_nml: the &material and &analysis lines
scene_physics_nml() {
    echo "&material poisson = $nu / &analysis kind = '$kind', lambda = $lam /"
}

# scene_gmsh OUT ORDER [-setnumber ...]: a Gmsh mesh of the scene's .geo (graded = 1 with
# alpha, hmin, hmax set by the caller; graded = 0 with -clmax for a plain Delaunay mesh)
scene_gmsh() {
    local out=$1 order=$2
    shift 2
    gmsh "$geo" "${gset[@]}" "$@" -2 -order "$order" -format msh41 -o "$out" >"$out.log" 2>&1 ||
        { cat "$out.log" >&2; echo "truth_scenes: gmsh failed for $out" >&2; return 1; }
}
