! SPDX-License-Identifier: MIT
!> The one place the input record (config_t) is read past the input layer: translate_input
!> turns it into the types the analyses and the numerics take, the scene (the body), the
!> study point (lambda and nu), the method options (eigensolver, adaptation) as
!> enumerations, the lambdas of a sweep and of the boundary search, and the groups only one
!> analysis or the report reads. Nothing below the analyses sees config_t, and nothing
!> edits it: a different lambda is an argument, a finer mesh an operation on the scene.
module run_inputs
    use kinds, only: wp
    use run_config, only: config_t, output_config_t, branch_config_t, solve_config_t, &
                          sweep_lambdas
    use scene, only: scene_t, study_point_t, MESH_RECTANGLE, MESH_GMSH
    use method_options, only: eigen_options_t, adapt_options_t, SOLVER_AUTO, SOLVER_DENSE, &
                              SOLVER_ARPACK, ESTIMATE_AUTO, ESTIMATE_ON, ESTIMATE_OFF, &
                              OPERATOR_REDUCED, OPERATOR_FULL, REFINE_NONE, REFINE_H, REFINE_HP
    use element_types, only: element_from_name
    implicit none
    private
    public :: translate_input

    !> The analyses, by &analysis kind.
    integer, parameter, public :: ANALYSIS_EIGEN = 1
    integer, parameter, public :: ANALYSIS_THRESHOLD = 2
    integer, parameter, public :: ANALYSIS_SWEEP = 3   !! 'lambda_sweep'
    integer, parameter, public :: ANALYSIS_BRANCH = 4
    integer, parameter, public :: ANALYSIS_SOLVE = 5
    integer, parameter, public :: ANALYSIS_UNKNOWN = 0

    !> 'threshold' counts positive mu on at most this many of the &sweep lambdas (spacing 1
    !> on the default range [-20, 20]); 'lambda_sweep' on all of them (see scan_points).
    integer, parameter, public :: THRESHOLD_SCAN_POINTS = 41

    type, public :: run_inputs_t
        integer :: analysis = ANALYSIS_EIGEN
        character(len=:), allocatable :: analysis_name   !! &analysis kind, as summaries name it
        type(scene_t) :: scene
        !> &analysis lambda and &material poisson, on the run's one scene
        type(study_point_t) :: point
        type(eigen_options_t) :: eigen
        type(adapt_options_t) :: adapt
        real(wp), allocatable :: sweep(:)   !! the lambdas of &sweep, in order
        !> 'list' (&sweep lambdas given), 'linear' or 'log': how `sweep` was made
        character(len=:), allocatable :: sweep_spacing
        logical :: sweep_plot = .true.      !! &sweep plot: draw lambda_sweep.png
        !> &sweep adapt_thresholds: the thresholds adapted in the points' hp climb (joint_goal)
        logical :: sweep_thresholds = .false.
        !> where the search of the boundary of {lambda : a positive mu exists} counts the
        !> positive mu (scan_points)
        real(wp), allocatable :: scan(:)
        !> the groups one analysis reads ('branch', 'solve') and the report's
        type(branch_config_t) :: branch
        type(solve_config_t) :: solve
        type(output_config_t) :: output
    end type run_inputs_t

contains

    !> The run `config` describes, in the analyses' types. `config` is validated: every
    !> name is one of its accepted values.
    subroutine translate_input(config, inputs)
        type(config_t), intent(in) :: config
        type(run_inputs_t), intent(out) :: inputs

        inputs%analysis_name = trim(config%analysis%kind)
        select case (inputs%analysis_name)
        case ('eigen'); inputs%analysis = ANALYSIS_EIGEN
        case ('threshold'); inputs%analysis = ANALYSIS_THRESHOLD
        case ('lambda_sweep'); inputs%analysis = ANALYSIS_SWEEP
        case ('branch'); inputs%analysis = ANALYSIS_BRANCH
        case ('solve'); inputs%analysis = ANALYSIS_SOLVE
        case default; inputs%analysis = ANALYSIS_UNKNOWN
        end select

        associate (m => config%mesh, s => inputs%scene)
            s%name = config%input_file
            s%source = MESH_RECTANGLE
            if (m%source == 'gmsh') s%source = MESH_GMSH
            s%width = m%width
            s%height = m%height
            s%nx = m%nx
            s%ny = m%ny
            s%element = element_from_name(m%element)
            s%diagonal = m%diagonal
            s%file = trim(m%file)
            s%material%young = config%material%young
            s%material%poisson = config%material%poisson
            s%dirichlet = m%dirichlet
            s%neumann = m%neumann
            s%contact = m%contact
        end associate
        inputs%point%lambda = config%analysis%lambda
        inputs%point%poisson = config%material%poisson
        inputs%point%scene = 1

        associate (e => config%eigen, o => inputs%eigen)
            select case (trim(e%solver))
            case ('dense'); o%solver = SOLVER_DENSE
            case ('arpack'); o%solver = SOLVER_ARPACK
            case default; o%solver = SOLVER_AUTO
            end select
            o%nev = e%nev
            o%ncv = e%ncv
            o%maxit = e%maxit
            o%tol = e%tol
            o%target = e%target
            o%dense_max_contact = e%dense_max_contact
            select case (trim(e%estimate))
            case ('on'); o%estimate = ESTIMATE_ON
            case ('off'); o%estimate = ESTIMATE_OFF
            case default; o%estimate = ESTIMATE_AUTO
            end select
            o%operator = OPERATOR_REDUCED
            if (e%operator == 'full') o%operator = OPERATOR_FULL
            o%cn_max = e%cn_max
            o%modes = config%output%modes
        end associate

        associate (a => config%adapt, o => inputs%adapt)
            o%refine = REFINE_NONE
            if (a%tolerance > 0.0_wp) then
                o%refine = REFINE_H
                if (a%strategy == 'hp') o%refine = REFINE_HP
            end if
            o%tolerance = a%tolerance
            o%max_dofs = a%max_dofs
            o%max_levels = a%max_levels
            o%theta = a%theta
            o%sigma = a%sigma
            o%p_max = a%p_max
        end associate

        allocate (inputs%sweep, source=sweep_lambdas(config%sweep))
        inputs%sweep_spacing = 'list'
        if (.not. config%sweep%lambdas(1) < huge(1.0_wp)) inputs%sweep_spacing = &
            trim(config%sweep%spacing)
        inputs%sweep_plot = config%sweep%plot
        inputs%sweep_thresholds = config%sweep%adapt_thresholds
        inputs%scan = scan_points(inputs%sweep, inputs%analysis == ANALYSIS_SWEEP)
        inputs%branch = config%branch
        inputs%solve = config%solve
        inputs%output = config%output
    end subroutine translate_input

    !> The lambdas the boundary search counts positive mu at: a sweep's own lambdas (it solves
    !> there anyway), or for 'threshold' every k-th of them, at most THRESHOLD_SCAN_POINTS with
    !> both ends: each is a dense p x p eigen-solve, and 401 of them made 'threshold' 10 times
    !> slower at p = 257 (1.1 s -> 11.5 s); the pencil eigenvalues are added either way.
    pure function scan_points(all, with_sweep) result(lambdas)
        real(wp), intent(in) :: all(:)
        logical, intent(in) :: with_sweep
        real(wp), allocatable :: lambdas(:)
        integer :: step, n
        n = size(all)
        step = max(1, (n - 1 + THRESHOLD_SCAN_POINTS - 2)/(THRESHOLD_SCAN_POINTS - 1))
        if (with_sweep .or. step == 1) then
            lambdas = all
        else
            lambdas = [all(1:n - 1:step), all(n)]
        end if
    end function scan_points
end module run_inputs
