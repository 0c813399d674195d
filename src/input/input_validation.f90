! SPDX-License-Identifier: MIT
!> The rules an input must meet once read, checked in one place (validate_config) so that
!> values from any source (file, command line) are judged alike; and the accepted values
!> of each choice, which the help text shows. A broken rule gives STATUS_BAD_INPUT with
!> one message 'path: &group: variable = value: expected ...'.
module input_validation
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use run_config, only: config_t, mesh_config_t, material_config_t, analysis_config_t, &
                          eigen_config_t, output_config_t, branch_config_t, solve_config_t, &
                          sweep_config_t, count_set_lambdas, lambda_is_set, &
                          UNSCALED_YOUNG_RANGE, UNSCALED_SIZE_RANGE
    use strings, only: to_string, split_words, count_names, quoted, one_of, &
                       NAME_LEN, LIST_LEN
    use real_format, only: real_to_text
    use ieee_arithmetic, only: ieee_is_finite
    implicit none
    private
    public :: validate_config, one_climb_possible
    public :: MESH_SOURCES, ELEMENT_NAMES, DIAGONALS, RECTANGLE_SIDES, ACCEPTED_ANALYSES, &
              ACCEPTED_SOLVERS, MAX_CELLS_PER_SIDE, SWEEP_SPACINGS, MAX_SWEEP_POINTS, &
              VTK_FORMATS, SOLVE_DATA, SOLVE_STARTS, ESTIMATE_MODES, EIGEN_OPERATORS, &
              ADAPT_ELEMENTS, ADAPT_ANALYSES, ADAPT_STRATEGIES, MAX_HP_INPUT_DEGREE, &
              SIGMA_MIN, SIGMA_MAX

    character(len=*), parameter :: MESH_SOURCES(*) = [character(len=9) :: 'rectangle', 'gmsh']
    character(len=*), parameter :: ELEMENT_NAMES(*) = [character(len=2) :: &
                                   'p1', 'q1', 'p2', 'q2', 'p3', 'p4']
    character(len=*), parameter :: DIAGONALS(*) = [character(len=5) :: 'right', 'left']
    character(len=*), parameter :: RECTANGLE_SIDES(*) = [character(len=6) :: &
                                   'top', 'bottom', 'left', 'right']
    !> Analyses this build can run; each new analysis adds its name here.
    character(len=*), parameter :: ACCEPTED_ANALYSES(*) = [character(len=12) :: 'eigen', &
                                   'threshold', 'lambda_sweep', 'branch', 'solve']
    !> Eigensolvers this build offers.
    character(len=*), parameter :: ACCEPTED_SOLVERS(*) = [character(len=6) :: 'dense', &
                                                          'arpack', 'auto']
    !> &eigen estimate: when the error estimate of the lowest positive mu is computed.
    character(len=*), parameter :: ESTIMATE_MODES(*) = [character(len=4) :: 'auto', 'on', 'off']
    !> &eigen operator: what ARPACK iterates on.
    character(len=*), parameter :: EIGEN_OPERATORS(*) = [character(len=7) :: 'reduced', 'full']
    integer, parameter :: MAX_CELLS_PER_SIDE = 1000000
    !> &adapt: the elements with a refinement (triangles) and an enriched space one degree
    !> higher for the error estimate (P4 has none: no P5 here), and the analyses that adapt.
    character(len=*), parameter :: ADAPT_ELEMENTS(*) = [character(len=2) :: 'p1', 'p2', 'p3']
    character(len=*), parameter :: ADAPT_ANALYSES(*) = [character(len=12) :: 'eigen', &
                                                         'threshold', 'lambda_sweep']
    !> &adapt strategy; 'hp' (module hp_levels, a refiner of the adaptive loop) adapts the same
    !> analyses on triangles of any degree (it keeps their vertices only), with cell degrees up
    !> to hp_basis's MAX_HP_DEGREE, which this repeats (the input layer sits below the elements).
    character(len=*), parameter :: ADAPT_STRATEGIES(*) = [character(len=2) :: 'h', 'hp']
    integer, parameter :: MAX_HP_INPUT_DEGREE = 20
    !> &adapt sigma's range: what the geometric meshes can be built with (see the check)
    real(wp), parameter :: SIGMA_MIN = 0.01_wp, SIGMA_MAX = 0.5_wp
    character(len=*), parameter :: SWEEP_SPACINGS(*) = [character(len=6) :: 'linear', 'log']
    integer, parameter :: MAX_SWEEP_POINTS = 100000   !! n_lambda of a &sweep range
    !> &solve works in the input's units, where young and the mesh size keep to
    !> UNSCALED_YOUNG_RANGE and UNSCALED_SIZE_RANGE (run_config): forces, tractions and
    !> compliances get young's range, displacements the size's, so that the residual's
    !> entries (E u, f size^2, c_n u size) stay below about 1e250 (u_d1 = 1e300 overflowed
    !> the merit).
    real(wp), parameter :: SOLVE_FORCE_RANGE = UNSCALED_YOUNG_RANGE
    real(wp), parameter :: SOLVE_LENGTH_RANGE = UNSCALED_SIZE_RANGE
    character(len=*), parameter :: SOLVE_UNITS = ' (analysis ''solve'' works in the ' &
                                                 //'input''s units)'
    !> &output vtk_format: the encodings of vtk_writer (VTK_BINARY, VTK_ASCII).
    character(len=*), parameter :: VTK_FORMATS(*) = [character(len=6) :: 'binary', 'ascii']
    !> &solve data: loads of the input, or the data of model.md section 9 at the critical point.
    character(len=*), parameter :: SOLVE_DATA(*) = [character(len=6) :: 'given', 'branch']
    !> &solve start: the starting guesses of the Newton iteration.
    character(len=*), parameter :: SOLVE_STARTS(*) = [character(len=6) :: &
                                   'zero', 'branch', 'random', 'mode']

contains

    !> Check every group of `config`, in the order of the groups, up to the first broken
    !> rule; `path` (the input file) starts the message.
    subroutine validate_config(config, path, stat)
        type(config_t), intent(in) :: config
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        call validate_mesh(config%mesh, path, stat)
        if (stat%ok()) call validate_material(config%material, path, stat)
        if (stat%ok()) call validate_analysis(config%analysis, path, stat)
        if (stat%ok()) call validate_eigen(config%eigen, path, stat)
        if (stat%ok()) call validate_output(config%output, path, stat)
        if (stat%ok()) call validate_sweep(config%sweep, path, stat)
        if (stat%ok()) call validate_branch(config%branch, path, stat)
        if (stat%ok()) call validate_solve(config%solve, path, stat)
        if (stat%ok()) call validate_adapt(config, path, stat)
        if (stat%ok() .and. config%sweep%adapt_thresholds) call validate_joint(config, path, &
                                                                                stat)
    end subroutine validate_config

    !> &sweep adapt_thresholds: one hp climb carries the sweep's points and its thresholds,
    !> so it needs an adapted hp lambda_sweep (h levels refine each point's mesh on its own).
    subroutine validate_joint(config, path, stat)
        type(config_t), intent(in) :: config
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        if (.not. one_climb_possible(config)) call fail_value(stat, path, 'sweep', &
            'adapt_thresholds', '.true.', ".false. unless &analysis kind = 'lambda_sweep' "// &
            "with &adapt tolerance > 0 and strategy = 'hp' (one hp climb for the points "// &
            'and the thresholds)')
    end subroutine validate_joint

    !> Whether `config` may set &sweep adapt_thresholds: an adapted hp lambda_sweep (the
    !> rule of validate_joint; nceig-study-plan asks it before it writes a task's input).
    pure logical function one_climb_possible(config)
        type(config_t), intent(in) :: config
        one_climb_possible = config%analysis%kind == 'lambda_sweep' .and. &
            config%adapt%tolerance > 0.0_wp .and. config%adapt%strategy == 'hp'
    end function one_climb_possible

    !> &adapt, and what adaptation needs of the other groups: an analysis that adapts, a
    !> rectangle of triangles with an enriched space (a Gmsh file's cells are checked when
    !> it is read), the error estimate on.
    subroutine validate_adapt(config, path, stat)
        type(config_t), intent(in) :: config
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        logical :: tolerance_ok, theta_ok

        associate (c => config%adapt)
            tolerance_ok = ieee_is_finite(c%tolerance)
            if (tolerance_ok) tolerance_ok = c%tolerance >= 0.0_wp .and. c%tolerance < 1.0_wp
            theta_ok = ieee_is_finite(c%theta)
            if (theta_ok) theta_ok = c%theta > 0.0_wp .and. c%theta <= 1.0_wp
            if (.not. tolerance_ok) then
                call reject('tolerance', real_to_text(c%tolerance), &
                            'a relative error with 0 <= tolerance < 1 (0: no adaptation)')
            else if (c%max_dofs < 0) then
                call reject('max_dofs', to_string(c%max_dofs), &
                            'an integer >= 0 (0: the memory available)')
            else if (c%max_levels < 0) then
                call reject('max_levels', to_string(c%max_levels), 'an integer >= 0 (0: no limit)')
            else if (.not. theta_ok) then
                call reject('theta', real_to_text(c%theta), 'a fraction with 0 < theta <= 1')
            else if (.not. any(ADAPT_STRATEGIES == c%strategy)) then
                call reject('strategy', quoted(c%strategy), 'one of '//one_of(ADAPT_STRATEGIES))
            else if (.not. (c%sigma >= SIGMA_MIN .and. c%sigma <= SIGMA_MAX)) then
                ! what the geometric meshes can be built with (mesh_geometric): above 0.5 a
                ! cell must be smaller than its distance to the singular point, and a level
                ! holds about (sigma/(1 - sigma))^2 times more cells (0.7 took 3.8 GB and
                ! minutes for what 0.15 reaches in 0.5 s; 0.999999 did not end); below 0.01
                ! the cells at the point shrink over 100-fold a level, past binary64's
                ! resolution of the coordinates in a few levels (1e-20: at the first)
                call reject('sigma', real_to_text(c%sigma), 'a grading factor with '// &
                            real_to_text(SIGMA_MIN)//' <= sigma <= '//real_to_text(SIGMA_MAX)// &
                            ' (above, a level has too many cells to build; below, its cells '// &
                            'at the singular points pass the resolution of binary64)')
            else if (c%p_max < 1 .or. c%p_max > MAX_HP_INPUT_DEGREE) then
                call reject('p_max', to_string(c%p_max), 'a degree from 1 to '// &
                            to_string(MAX_HP_INPUT_DEGREE))
            end if
            if (.not. stat%ok() .or. .not. c%tolerance > 0.0_wp) return
        end associate
        if (config%adapt%strategy == 'hp') then
            call validate_hp()
            return
        end if
        if (.not. any(ADAPT_ANALYSES == config%analysis%kind)) then
            call reject('tolerance', real_to_text(config%adapt%tolerance), "0 for &analysis "// &
                        "kind = '"//trim(config%analysis%kind)//"' (only "// &
                        one_of(ADAPT_ANALYSES)//' adapts its mesh)')
        else if (config%mesh%source == 'rectangle' .and. &
                 .not. any(ADAPT_ELEMENTS == config%mesh%element)) then
            call reject('tolerance', real_to_text(config%adapt%tolerance), "0 for &mesh "// &
                        "element = '"//trim(config%mesh%element)//"' (adaptation refines "// &
                        'triangles with an error estimate: one of '//one_of(ADAPT_ELEMENTS)//')')
        else if (config%eigen%estimate == 'off') then
            call reject('tolerance', real_to_text(config%adapt%tolerance), "0 with &eigen "// &
                        "estimate = 'off' (adaptation is driven by the error estimate)")
        end if

    contains

        subroutine reject(variable, value, expected)
            character(len=*), intent(in) :: variable, value, expected
            call fail_value(stat, path, 'adapt', variable, value, expected)
        end subroutine reject

        !> strategy = 'hp': analysis 'eigen', 'threshold' or 'lambda_sweep' on triangles (a
        !> Gmsh file's cells are checked when it is read); it needs no error estimate of
        !> &eigen.
        subroutine validate_hp()
            if (.not. any(ADAPT_ANALYSES == config%analysis%kind)) then
                call reject('strategy', "'hp'", "'h' for &analysis kind = '"// &
                            trim(config%analysis%kind)//"' (hp adapts kind = "// &
                            one_of(ADAPT_ANALYSES)//' only)')
            else if (config%mesh%source == 'rectangle' .and. &
                     config%mesh%element(1:1) /= 'p') then
                call reject('strategy', "'hp'", "'h' for &mesh element = '"// &
                            trim(config%mesh%element)//"' (hp grades triangles: p1 to p4)")
            end if
        end subroutine validate_hp
    end subroutine validate_adapt

    subroutine validate_mesh(c, path, stat)
        type(mesh_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        character(len=*), parameter :: LIST_VARIABLES(3) = [character(len=9) :: &
                                       'dirichlet', 'neumann', 'contact']
        character(len=LIST_LEN) :: lists(3)
        character(len=LIST_LEN), allocatable :: names(:), seen(:)
        integer, allocatable :: seen_in(:)
        integer :: k, i, j

        if (.not. any(MESH_SOURCES == c%source)) then
            call reject('source', quoted(c%source), 'one of '//one_of(MESH_SOURCES))
        else if (c%source == 'gmsh' .and. len_trim(c%file) == 0) then
            call reject('file', quoted(c%file), &
                        "the path of a Gmsh .msh file when source = 'gmsh'")
        else if (.not. positive_finite(c%width)) then
            call reject('width', real_to_text(c%width), 'a finite number > 0')
        else if (.not. positive_finite(c%height)) then
            call reject('height', real_to_text(c%height), 'a finite number > 0')
        else if (c%nx < 1 .or. c%nx > MAX_CELLS_PER_SIDE) then
            call reject('nx', to_string(c%nx), &
                        'an integer from 1 to '//to_string(MAX_CELLS_PER_SIDE))
        else if (c%ny < 1 .or. c%ny > MAX_CELLS_PER_SIDE) then
            call reject('ny', to_string(c%ny), &
                        'an integer from 1 to '//to_string(MAX_CELLS_PER_SIDE))
        else if (.not. any(ELEMENT_NAMES == c%element)) then
            call reject('element', quoted(c%element), 'one of '//one_of(ELEMENT_NAMES))
        else if (.not. any(DIAGONALS == c%diagonal)) then
            call reject('diagonal', quoted(c%diagonal), 'one of '//one_of(DIAGONALS))
        end if
        if (.not. stat%ok()) return

        lists = [c%dirichlet, c%neumann, c%contact]
        do k = 1, 3
            call split_words(lists(k), names)
            do i = 1, size(names)
                if (len_trim(names(i)) > NAME_LEN) then
                    call reject(trim(LIST_VARIABLES(k)), quoted(lists(k)), 'names of at most ' &
                                //to_string(NAME_LEN)//' characters')
                else if (c%source == 'rectangle' .and. &
                         .not. any(RECTANGLE_SIDES == names(i))) then
                    call reject(trim(LIST_VARIABLES(k)), quoted(lists(k)), 'sides among ' &
                                //one_of(RECTANGLE_SIDES)//" ('"//trim(names(i)) &
                                //"' is not a side of the rectangle)")
                end if
                if (.not. stat%ok()) return
            end do
        end do
        if (count_names(c%dirichlet) == 0) then
            call reject('dirichlet', quoted(c%dirichlet), &
                        'at least one side or group name (without a Dirichlet boundary K would ' &
                        //'be singular)')
            return
        end if
        if (count_names(c%contact) /= 1) then
            call reject('contact', quoted(c%contact), 'exactly one side or group name ' &
                        //'(the contact boundary is one straight segment)')
            return
        end if

        allocate (seen(0), seen_in(0))
        do k = 1, 3
            call split_words(lists(k), names)
            do i = 1, size(names)
                do j = 1, size(seen)
                    if (seen(j) /= names(i)) cycle
                    if (seen_in(j) == k) then
                        call reject(trim(LIST_VARIABLES(k)), quoted(lists(k)), &
                                    "each name once ('"//trim(names(i))//"' is named twice)")
                    else
                        call reject(trim(LIST_VARIABLES(k)), quoted(lists(k)), &
                                    'each name in only one of dirichlet, neumann, contact (' &
                                    //quoted(names(i))//' is also in ' &
                                    //trim(LIST_VARIABLES(seen_in(j)))//')')
                    end if
                    return
                end do
                seen = [character(len=LIST_LEN) :: seen, names(i)]
                seen_in = [seen_in, k]
            end do
        end do

    contains

        subroutine reject(variable, value, expected)
            character(len=*), intent(in) :: variable, value, expected
            call fail_value(stat, path, 'mesh', variable, value, expected)
        end subroutine reject
    end subroutine validate_mesh

    subroutine validate_material(c, path, stat)
        type(material_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        logical :: poisson_ok

        poisson_ok = ieee_is_finite(c%poisson)
        if (poisson_ok) poisson_ok = c%poisson > -1.0_wp .and. c%poisson < 0.5_wp
        if (.not. positive_finite(c%young)) then
            call fail_value(stat, path, 'material', 'young', real_to_text(c%young), &
                            'a finite number > 0')
        else if (.not. poisson_ok) then
            call fail_value(stat, path, 'material', 'poisson', real_to_text(c%poisson), &
                            '-1 < poisson < 0.5 (0.5 is incompressible, which this ' &
                            //'displacement formulation cannot represent)')
        end if
    end subroutine validate_material

    subroutine validate_analysis(c, path, stat)
        type(analysis_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat

        if (.not. any(ACCEPTED_ANALYSES == c%kind)) then
            call fail_value(stat, path, 'analysis', 'kind', quoted(c%kind), &
                            'one of '//one_of(ACCEPTED_ANALYSES))
        else if (.not. ieee_is_finite(c%lambda)) then
            call fail_value(stat, path, 'analysis', 'lambda', real_to_text(c%lambda), &
                            'a finite number')
        end if
    end subroutine validate_analysis

    subroutine validate_eigen(c, path, stat)
        type(eigen_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        logical :: tol_ok, cn_max_ok

        tol_ok = ieee_is_finite(c%tol)
        if (tol_ok) tol_ok = c%tol >= 0.0_wp .and. c%tol < 1.0_wp
        ! compared only when finite: NaN >= 0 traps in a Debug build
        cn_max_ok = ieee_is_finite(c%cn_max)
        if (cn_max_ok) cn_max_ok = c%cn_max >= 0.0_wp
        if (.not. any(ACCEPTED_SOLVERS == c%solver)) then
            call reject('solver', quoted(c%solver), 'one of '//one_of(ACCEPTED_SOLVERS))
        else if (c%nev < 1) then
            call reject('nev', to_string(c%nev), 'an integer >= 1')
        else if (.not. ieee_is_finite(c%target)) then
            call reject('target', real_to_text(c%target), 'a finite number')
        else if (.not. tol_ok) then
            call reject('tol', real_to_text(c%tol), 'a number in [0, 1) (0: machine precision)')
        else if (c%maxit < 1) then
            call reject('maxit', to_string(c%maxit), 'an integer >= 1')
        else if (c%ncv /= 0 .and. c%ncv < c%nev + 2) then
            call reject('ncv', to_string(c%ncv), '0 (automatic) or at least nev + 2 = ' &
                        //to_string(c%nev + 2))
        else if (c%dense_max_contact < 1) then
            call reject('dense_max_contact', to_string(c%dense_max_contact), 'an integer >= 1')
        else if (.not. any(ESTIMATE_MODES == c%estimate)) then
            call reject('estimate', quoted(c%estimate), 'one of '//one_of(ESTIMATE_MODES))
        else if (.not. any(EIGEN_OPERATORS == c%operator)) then
            call reject('operator', quoted(c%operator), 'one of '//one_of(EIGEN_OPERATORS))
        else if (c%operator == 'full' .and. c%solver == 'dense') then
            call reject('operator', quoted(c%operator), "'reduced' with solver = 'dense' "// &
                        "(the full operator is an ARPACK operator)")
        else if (.not. cn_max_ok) then
            call reject('cn_max', real_to_text(c%cn_max), 'a finite number >= 0 (0: only '// &
                        'the lowest positive mu)')
        end if

    contains

        subroutine reject(variable, value, expected)
            character(len=*), intent(in) :: variable, value, expected
            call fail_value(stat, path, 'eigen', variable, value, expected)
        end subroutine reject
    end subroutine validate_eigen

    subroutine validate_output(c, path, stat)
        type(output_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat

        if (c%modes < 0) then
            call fail_value(stat, path, 'output', 'modes', to_string(c%modes), 'an integer >= 0')
        else if (.not. any(VTK_FORMATS == c%vtk_format)) then
            call fail_value(stat, path, 'output', 'vtk_format', quoted(c%vtk_format), &
                            'one of '//one_of(VTK_FORMATS))
        end if
    end subroutine validate_output

    !> The list, when given, must be a prefix of finite values (unset entries are huge()).
    !> A range needs lambda_min < lambda_max, and for 'log' one sign and no zero.
    subroutine validate_sweep(c, path, stat)
        type(sweep_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        integer :: n_list, i

        n_list = count_set_lambdas(c)
        do i = 1, size(c%lambdas)
            if (i <= n_list) then
                if (.not. ieee_is_finite(c%lambdas(i))) then
                    call reject('lambdas('//to_string(i)//')', real_to_text(c%lambdas(i)), &
                                'a finite number')
                    return
                end if
            else if (lambda_is_set(c%lambdas(i))) then
                call reject('lambdas('//to_string(i)//')', real_to_text(c%lambdas(i)), &
                            'consecutive entries from lambdas(1) (lambdas('//to_string(i - 1) &
                            //') is unset)')
                return
            end if
        end do
        if (n_list > 0) return

        if (.not. ieee_is_finite(c%lambda_min)) then
            call reject('lambda_min', real_to_text(c%lambda_min), 'a finite number')
        else if (.not. ieee_is_finite(c%lambda_max)) then
            call reject('lambda_max', real_to_text(c%lambda_max), 'a finite number')
        else if (.not. c%lambda_max > c%lambda_min) then
            call reject('lambda_max', real_to_text(c%lambda_max), 'a number > lambda_min = ' &
                        //real_to_text(c%lambda_min))
        else if (c%n_lambda < 2 .or. c%n_lambda > MAX_SWEEP_POINTS) then
            call reject('n_lambda', to_string(c%n_lambda), 'an integer from 2 to ' &
                        //to_string(MAX_SWEEP_POINTS))
        else if (.not. any(SWEEP_SPACINGS == c%spacing)) then
            call reject('spacing', quoted(c%spacing), 'one of '//one_of(SWEEP_SPACINGS))
        else if (c%spacing == 'log' .and. .not. (c%lambda_min > 0.0_wp .or. &
                                                 c%lambda_max < 0.0_wp)) then
            call reject('lambda_min', real_to_text(c%lambda_min), "lambda_min and lambda_max" &
                        //" of one sign, both nonzero, with spacing = 'log' (lambda_max = " &
                        //real_to_text(c%lambda_max)//')')
        end if

    contains

        subroutine reject(variable, value, expected)
            character(len=*), intent(in) :: variable, value, expected
            call fail_value(stat, path, 'sweep', variable, value, expected)
        end subroutine reject
    end subroutine validate_sweep

    subroutine validate_branch(c, path, stat)
        type(branch_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat

        if (.not. positive_finite(c%alpha)) then
            call fail_value(stat, path, 'branch', 'alpha', real_to_text(c%alpha), &
                            'a finite number > 0 (u_n of U on the contact boundary)')
        else if (.not. positive_finite(c%beta)) then
            call fail_value(stat, path, 'branch', 'beta', real_to_text(c%beta), &
                            'a finite number > 0 (|u_t| of U on the contact boundary)')
        else if (c%n_delta < 1) then
            call fail_value(stat, path, 'branch', 'n_delta', to_string(c%n_delta), &
                            'an integer >= 1')
        else if (c%write_members < 0) then
            call fail_value(stat, path, 'branch', 'write_members', to_string(c%write_members), &
                            'an integer >= 0')
        end if
    end subroutine validate_branch

    subroutine validate_solve(c, path, stat)
        type(solve_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        logical :: tol_ok

        tol_ok = ieee_is_finite(c%tol)
        if (tol_ok) tol_ok = c%tol > 0.0_wp .and. c%tol < 1.0_wp
        if (.not. any(SOLVE_DATA == c%data)) then
            call reject('data', quoted(c%data), 'one of '//one_of(SOLVE_DATA))
        else if (.not. in_range(c%c_n, 1.0_wp/SOLVE_FORCE_RANGE, SOLVE_FORCE_RANGE)) then
            call reject('c_n', real_to_text(c%c_n), 'a number from 1e-100 to 1e100' &
                        //SOLVE_UNITS)
        else if (.not. in_range(c%c_t, 1.0_wp/SOLVE_FORCE_RANGE, SOLVE_FORCE_RANGE)) then
            call reject('c_t', real_to_text(c%c_t), 'a number from 1e-100 to 1e100' &
                        //SOLVE_UNITS)
        else if (.not. positive_finite(c%critical_factor)) then
            call reject('critical_factor', real_to_text(c%critical_factor), 'a finite number > 0')
        else if (.not. any(SOLVE_STARTS == c%start)) then
            call reject('start', quoted(c%start), 'one of '//one_of(SOLVE_STARTS))
        else
            call bounded('f1', c%f1, SOLVE_FORCE_RANGE, '1e100 (a force density)')
            call bounded('f2', c%f2, SOLVE_FORCE_RANGE, '1e100 (a force density)')
            call bounded('t1', c%t1, SOLVE_FORCE_RANGE, '1e100 (a traction)')
            call bounded('t2', c%t2, SOLVE_FORCE_RANGE, '1e100 (a traction)')
            call bounded('u_d1', c%u_d1, SOLVE_LENGTH_RANGE, '1e50 (a displacement)')
            call bounded('u_d2', c%u_d2, SOLVE_LENGTH_RANGE, '1e50 (a displacement)')
            call bounded('start_delta', c%start_delta, SOLVE_LENGTH_RANGE, '1e50')
            call bounded('start_scale', c%start_scale, SOLVE_LENGTH_RANGE, &
                         '1e50 (a displacement)')
            call bounded('start_noise', c%start_noise, SOLVE_LENGTH_RANGE, &
                         '1e50 (a displacement)')
        end if
        if (.not. stat%ok()) return
        if (.not. tol_ok) then
            call reject('tol', real_to_text(c%tol), 'a number with 0 < tol < 1')
        else if (c%max_iterations < 1) then
            call reject('max_iterations', to_string(c%max_iterations), 'an integer >= 1')
        end if

    contains

        subroutine reject(variable, value, expected)
            character(len=*), intent(in) :: variable, value, expected
            call fail_value(stat, path, 'solve', variable, value, expected)
        end subroutine reject

        !> |x| <= limit, up to the first broken bound.
        subroutine bounded(variable, x, limit, limit_text)
            character(len=*), intent(in) :: variable, limit_text
            real(wp), intent(in) :: x, limit
            if (.not. stat%ok()) return
            if (in_range(abs(x), 0.0_wp, limit)) return
            call reject(variable, real_to_text(x), '|'//variable//'| <= '//limit_text &
                        //SOLVE_UNITS)
        end subroutine bounded
    end subroutine validate_solve

    !> low <= x <= high, false for NaN (tested before comparing: a NaN traps in Debug).
    elemental logical function in_range(x, low, high)
        real(wp), intent(in) :: x, low, high
        in_range = ieee_is_finite(x)
        if (in_range) in_range = x >= low .and. x <= high
    end function in_range

    !> The one message format of a rejected value.
    subroutine fail_value(stat, path, group, variable, value, expected)
        type(status_t), intent(inout) :: stat
        character(len=*), intent(in) :: path, group, variable, value, expected
        call stat%fail(STATUS_BAD_INPUT, path//': &'//group//': '//variable//' = '//value &
                       //': expected '//expected)
    end subroutine fail_value

    !> Tested before any comparison: an ordered comparison with NaN traps in debug builds.
    elemental logical function positive_finite(x)
        real(wp), intent(in) :: x
        positive_finite = ieee_is_finite(x)
        if (positive_finite) positive_finite = x > 0.0_wp
    end function positive_finite
end module input_validation
