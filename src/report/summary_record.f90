! SPDX-License-Identifier: MIT
!> The summary of a run: one record of every fact the run reports (run_summary_t), in the
!> input's units, filled once from the analysis's result (run_report), and rendered by this
!> module alone, as summary.json (summary_json: one key per fact, in the documented order,
!> docs/outputs.md) and as the text printed on stdout (summary_text). A fact both show is
!> formed once, in the record; the renderers only format it.
module summary_record
    use kinds, only: wp, i8
    use strings, only: to_string, short_real_text, seconds_text
    use real_format, only: real_to_text, known_text
    use timer, only: timings_t
    use json_writer, only: json_object_t
    use accuracy, only: WARNING_LEN
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use moving_side, only: moving_side_t, moving_words, FAR_NAMES
    use pencil_tracking, only: TRACK_NAMES, TRACK_MOVING
    implicit none
    private
    public :: summary_json, summary_text, boundary_lines

    character(len=*), parameter :: NL = new_line('a')
    character(len=*), parameter :: SIDE_NAME(2) = [character(len=5) :: 'plus', 'minus']
    character(len=*), parameter :: SIDE_LABEL(2) = [character(len=7) :: 'lambda+', 'lambda-']

    !> The spectrum at one lambda and its lowest positive mu (every analysis but 'solve'
    !> without the branch data has one).
    type, public :: eigen_facts_t
        logical :: solved = .false.            !! a spectrum was computed
        real(wp) :: lambda = 0.0_wp            !! where (else &analysis lambda)
        integer :: slip_sign = 0               !! s = -sgn(lambda)
        character(len=:), allocatable :: solver, operator   !! 'dense', 'arpack'; 'reduced', 'full'
        integer :: n_eigenvalues = 0
        real(wp) :: max_residual = 0.0_wp      !! the largest backward error of the pairs
        integer :: n_operator = 0              !! ARPACK's operator applications
        logical :: dense_decision = .false.    !! ARPACK's answer decided densely
        real(wp) :: roundoff_seconds = 0.0_wp  !! the round-off bound's part of the eigen time
        logical :: has_lowest = .false.        !! a positive mu exists
        real(wp) :: mu = 0.0_wp                !! lowest positive mu = critical c_n, input units
        real(wp) :: c_t = 0.0_wp               !! critical c_t = mu |lambda|, input units
        real(wp) :: condition = -1.0_wp        !! of mu; < 0: unknown (ARPACK)
        real(wp) :: residual = 0.0_wp          !! its backward error
        logical :: estimated = .false.         !! the relative error estimate exists
        real(wp) :: estimate = 0.0_wp          !! |relative error estimate|
        character(len=:), allocatable :: estimate_label   !! how it was made
        !> the estimate is the change to the previous hp level (that level's error: the bar
        !> may be below it)
        logical :: level_change = .false.
        !> hp: the relative change of mu to the check one degree higher (in the bar); < 0: none
        real(wp) :: check = -1.0_wp
        real(wp) :: bar = -1.0_wp              !! relative error bar; < 0: none
        character(len=:), allocatable :: skipped   !! why no estimate (unallocated: no reason)
        real(wp) :: roundoff = -1.0_wp         !! relative round-off bound of mu; < 0: unknown
        logical :: quotient = .false.          !! mu is the Rayleigh quotient without a stored K
        real(wp) :: cn_max = 0.0_wp            !! &eigen cn_max, input units
        real(wp), allocatable :: critical(:)   !! every positive mu in (0, cn_max], input units
        character(len=WARNING_LEN), allocatable :: warnings(:)
    end type eigen_facts_t

    !> One side of the thresholds (lambda+ or lambda-).
    type, public :: side_facts_t
        logical :: found = .false.
        real(wp) :: lambda = 0.0_wp
        real(wp) :: residual = 0.0_wp          !! its backward error on the pencil
        real(wp) :: roundoff = -1.0_wp         !! relative; < 0: unknown
        logical :: confirmed = .false.
        real(wp) :: lambda_outside = 0.0_wp, lambda_inside = 0.0_wp
        logical :: has_mu_outside = .false., has_mu_inside = .false.
        real(wp) :: mu_outside = 0.0_wp, mu_inside = 0.0_wp   !! input units
        logical :: estimated = .false.
        real(wp) :: estimate = 0.0_wp          !! |relative error estimate|
        real(wp) :: bar = -1.0_wp              !! relative; < 0: none
        character(len=:), allocatable :: estimate_label
        logical :: level_change = .false.      !! as eigen_facts_t's
        !> hp: the level whose value and bar are quoted, where the side met the tolerance
        !> (0: none)
        integer :: met_level = 0
        character(len=:), allocatable :: skipped   !! why no estimate ('' : no reason)
        !> hp, a side that did not converge: its values over the levels, where its vector
        !> sits, the wedge there (moving_side; known false: none)
        type(moving_side_t) :: moving
    end type side_facts_t

    !> One boundary point of {lambda : a positive mu exists}.
    type, public :: boundary_point_t
        real(wp) :: lambda = 0.0_wp
        character(len=12) :: mechanism = ''    !! 'pencil' or 'complex_pair'
        logical :: appears = .false.           !! a positive mu appears as lambda increases
        integer :: n_below = 0, n_above = 0    !! positive mu just below and above
        logical :: confirmed = .false.
        real(wp) :: bar = -1.0_wp              !! relative; < 0: none
        real(wp) :: roundoff = -1.0_wp         !! its round-off part; < 0: unknown
        logical :: pair = .false.              !! complex_pair: the next two exist
        real(wp) :: discriminant = 0.0_wp
        real(wp) :: mu_meet = 0.0_wp           !! where the pair meets, input units
    end type boundary_point_t

    type, public :: threshold_facts_t
        type(side_facts_t) :: side(2)          !! by SIDE_PLUS, SIDE_MINUS
        real(wp) :: confirm_offset = 0.0_wp
        integer :: n_real = 0, n_complex = 0, n_infinite = 0   !! the pencil's eigenvalues
        real(wp) :: lambda_min = 0.0_wp, lambda_max = 0.0_wp   !! the range searched
        type(boundary_point_t), allocatable :: points(:)   !! ascending lambda
        integer :: onset(2) = 0                !! per side, its onset in points (0: none)
        real(wp), allocatable :: lower(:), upper(:)   !! the intervals with a positive mu
        integer :: n_evaluations = 0, scan_contact = 0, contact = 0
        real(wp) :: time_threshold = 0.0_wp    !! s
    end type threshold_facts_t

    type, public :: sweep_facts_t
        character(len=:), allocatable :: file, spacing
        integer :: n_lambda = 0, n_with_mu = 0, n_arpack = 0, n_dense = 0
        real(wp) :: lambda_min = 0.0_wp, lambda_max = 0.0_wp
        logical :: adapted = .false.           !! each point adapted (&adapt)
        integer :: n_reused = 0, n_not_met = 0
        !> a point's loop failed: the set holds the n_complete points complete before it
        logical :: partial = .false.
        integer :: n_complete = 0
        real(wp) :: max_estimate = -1.0_wp, max_bar = -1.0_wp   !! relative; < 0: none
        real(wp) :: time_sweep = 0.0_wp        !! s
    end type sweep_facts_t

    type, public :: adapt_facts_t
        real(wp) :: tolerance = 0.0_wp, theta = 0.0_wp
        integer :: levels = 0                  !! h: refinements; hp: levels
        integer :: start_dofs = 0
        logical :: converged = .false., floor_reached = .false.
        character(len=:), allocatable :: outcome, mesh_file
        logical :: hp = .false.
        real(wp) :: sigma = 0.0_wp
        integer :: p_max = 0
        character(len=:), allocatable :: degrees_file
        logical :: has_degrees = .false.       !! the last level's degrees exist
        integer :: degree_min = 0, degree_max = 0
        integer :: start_cells = 0
    end type adapt_facts_t

    type, public :: branch_facts_t
        real(wp) :: alpha = 0.0_wp, beta = 0.0_wp, c_n = 0.0_wp, c_t = 0.0_wp
        real(wp) :: delta_max = 0.0_wp, residual_base = 0.0_wp, max_residual = 0.0_wp
        real(wp) :: load_norm = 0.0_wp, time_branch = 0.0_wp
        integer :: n_delta = 0
    end type branch_facts_t

    type, public :: solve_facts_t
        character(len=:), allocatable :: data, start, newton_stop
        real(wp) :: c_n = 0.0_wp, c_t = 0.0_wp, residual = 0.0_wp, tol = 0.0_wp
        real(wp) :: load_norm = 0.0_wp, time_newton = 0.0_wp
        logical :: converged = .false.
        integer :: iterations = 0
        integer :: n_state(4) = 0              !! separated, stick, slip+, slip-
        logical :: on_branch = .false.         !! data = 'branch': where on the line
        real(wp) :: branch_delta = 0.0_wp, branch_distance = 0.0_wp
    end type solve_facts_t

    type, public :: run_summary_t
        character(len=:), allocatable :: version, input, analysis, directory
        character(len=:), allocatable :: element, mesh_source, diagonal, mesh_file
        integer :: nx = 0, ny = 0               !! the rectangle's (mesh_source 'rectangle')
        real(wp) :: young = 0.0_wp, poisson = 0.0_wp
        integer :: n_nodes = 0, n_cells = 0, n_dofs = 0, n_contact = 0
        integer(i8) :: nnz_k = 0   !! stored entries of K
        type(eigen_facts_t) :: eigen
        character(len=:), allocatable :: blas_library, blas_config, blas_threads_source
        integer :: blas_threads = 0
        type(timings_t) :: timings
        !> where a picture is or why not; unallocated where none was asked for
        character(len=:), allocatable :: mode_plot, adapt_plot, sweep_plot
        type(threshold_facts_t), allocatable :: thresholds
        type(sweep_facts_t), allocatable :: sweep
        type(adapt_facts_t), allocatable :: adapt
        type(branch_facts_t), allocatable :: branch
        type(solve_facts_t), allocatable :: solve
    end type run_summary_t

contains

    !> summary.json of the run, without its 'files' list (the commit adds it).
    function summary_json(rec) result(summary)
        type(run_summary_t), intent(in) :: rec
        type(json_object_t) :: summary
        call add_eigen_keys(summary, rec)
        if (allocated(rec%thresholds)) call add_threshold_keys(summary, rec%thresholds)
        if (allocated(rec%adapt)) call add_adapt_keys(summary, rec%adapt)
        if (allocated(rec%sweep)) call add_sweep_keys(summary, rec%sweep)
        if (allocated(rec%branch)) call add_branch_keys(summary, rec%branch)
        if (allocated(rec%solve)) call add_solve_keys(summary, rec%solve, rec%timings)
    end function summary_json

    !> The summary printed on stdout once the outputs are in place.
    function summary_text(rec) result(text)
        type(run_summary_t), intent(in) :: rec
        character(len=:), allocatable :: text
        if (allocated(rec%branch)) then
            text = branch_lines(rec)
            return
        end if
        if (allocated(rec%solve)) then
            text = solve_lines(rec)
            return
        end if
        text = eigen_lines(rec)
        if (allocated(rec%thresholds)) text = text//threshold_lines(rec%thresholds, rec%sweep)
        if (allocated(rec%sweep_plot)) text = text//NL//'  plot        '//rec%sweep_plot
        if (allocated(rec%adapt)) text = text//adapt_lines(rec%adapt, rec%directory)
        if (allocated(rec%adapt_plot)) then
            if (len(rec%adapt_plot) > 0) text = text//NL//'  adapt plot  '//rec%adapt_plot
        end if
    end function summary_text

    !> The keys every summary.json starts with: the run, the mesh, the problem sizes, the
    !> lowest positive eigenvalue with its meaning (null without a spectrum), the timings.
    subroutine add_eigen_keys(summary, rec)
        type(json_object_t), intent(inout) :: summary
        type(run_summary_t), intent(in) :: rec
        character(len=*), parameter :: LOWEST_KEYS(8) = [character(len=30) :: &
            'lowest_positive_mu', 'critical_c_n', 'critical_c_t', &
            'lowest_positive_condition', 'lowest_positive_residual', &
            'lowest_positive_error_estimate', 'lowest_positive_error_bar', &
            'lowest_positive_roundoff']
        integer :: i

        associate (e => rec%eigen, t => rec%timings)
            call summary%add_string('nceig_version', rec%version)
            call summary%add_string('input', rec%input)
            call summary%add_string('analysis', rec%analysis)
            call summary%add_real('lambda', e%lambda)
            ! From the mesh: a Gmsh file decides its element type, not &mesh element.
            call summary%add_string('element', rec%element)
            call summary%add_string('mesh_source', rec%mesh_source)
            if (rec%mesh_source == 'rectangle') then
                call summary%add_integer('nx', rec%nx)
                call summary%add_integer('ny', rec%ny)
                call summary%add_string('diagonal', rec%diagonal)
            end if
            if (rec%mesh_source == 'gmsh') call summary%add_string('mesh_file', rec%mesh_file)
            call summary%add_real('young', rec%young)
            call summary%add_real('poisson', rec%poisson)
            call summary%add_integer('n_nodes', rec%n_nodes)
            call summary%add_integer('n_cells', rec%n_cells)
            call summary%add_integer('n_dofs', rec%n_dofs)
            call summary%add_integer('nnz_k', rec%nnz_k)
            call summary%add_integer('n_contact', rec%n_contact)
            if (e%solved) then
                call summary%add_string('solver', e%solver)
                call summary%add_string('operator', e%operator)
            else
                call summary%add_null('solver')
                call summary%add_null('operator')
            end if
            if (e%has_lowest) then
                call summary%add_real('lowest_positive_mu', e%mu)
                call summary%add_real('critical_c_n', e%mu)
                call summary%add_real('critical_c_t', e%c_t)
                ! ARPACK gives no condition number: null, never a number to misread
                call summary%add_real_or_null('lowest_positive_condition', e%condition, &
                                              e%condition >= 0.0_wp)
                call summary%add_real('lowest_positive_residual', e%residual)
                ! |mu - mu_h| / mu_h estimated (error_estimate); null where not computed
                call summary%add_real_or_null('lowest_positive_error_estimate', e%estimate, &
                                              e%estimated)
                ! the relative bar quoted with c_n (error_bar); null where there is none
                call summary%add_real_or_null('lowest_positive_error_bar', e%bar, &
                                              e%estimated .and. e%bar >= 0.0_wp)
                ! the round-off part of that bar (module roundoff); null where unknown
                call summary%add_real_or_null('lowest_positive_roundoff', e%roundoff, &
                                              e%roundoff >= 0.0_wp)
            else
                do i = 1, size(LOWEST_KEYS)
                    call summary%add_null(trim(LOWEST_KEYS(i)))
                end do
            end if
            call summary%add_real('cn_max', e%cn_max)
            call summary%add_real_array('critical_cn', e%critical)
            call summary%add_integer('slip_sign', e%slip_sign)
            call summary%add_integer('n_eigenvalues', e%n_eigenvalues)
            if (e%solved) then
                call summary%add_real('max_residual', e%max_residual)
                call summary%add_integer('operator_applications', e%n_operator)
                call summary%add_logical('dense_decision', e%dense_decision)
            else
                call summary%add_null('max_residual')
                call summary%add_integer('operator_applications', 0)
                call summary%add_null('dense_decision')
            end if
            call summary%add_string('blas_library', rec%blas_library)
            call summary%add_string('blas_config', rec%blas_config)
            call summary%add_integer('blas_threads', rec%blas_threads)
            call summary%add_string('blas_threads_source', rec%blas_threads_source)
            call summary%add_real('time_assembly_s', t%assembly)
            call summary%add_real('time_ordering_s', t%ordering)
            call summary%add_real('time_factor_s', t%factor)
            call summary%add_real('time_reduction_s', t%reduction)
            call summary%add_real('time_eigen_s', t%eigen)
            ! part of time_eigen_s: the left eigenvector and the round-off bound
            call summary%add_real('time_roundoff_s', e%roundoff_seconds)
            call summary%add_real('time_output_s', t%output)
            call summary%add_real('time_total_s', t%total)
            call summary%add_string_array('warnings', [character(len=1) ::])
            if (allocated(e%warnings)) call summary%add_string_array('warnings', e%warnings)
        end associate
    end subroutine add_eigen_keys

    !> The human summary of the spectrum: mesh, sizes, the headline eigenvalue and the time
    !> of each phase, the pictures and the warnings.
    function eigen_lines(rec) result(text)
        type(run_summary_t), intent(in) :: rec
        character(len=:), allocatable :: text
        integer :: i

        associate (e => rec%eigen, t => rec%timings)
            text = 'nceig '//rec%version//': '//rec%input//NL// &
                '  mesh        '//rec%mesh_source//', '//rec%element// &
                ', '//to_string(rec%n_cells)//' cells, '//to_string(rec%n_nodes)// &
                ' nodes'//NL// &
                '  problem     '//to_string(rec%n_dofs)//' dofs, '// &
                to_string(rec%n_contact)//' contact nodes, lambda = '//real_to_text(e%lambda)// &
                NL//'  solver      '//e%solver//': '//to_string(e%n_eigenvalues)// &
                ' eigenvalues, max backward error '//short_real_text(e%max_residual)//NL
            if (e%has_lowest) then
                text = text//'  lowest positive mu = critical c_n = '//real_to_text(e%mu)
                ! the headline quotes its bar, absolute: c_n = X +- B
                if (e%estimated .and. e%bar >= 0.0_wp) text = text//' +- '// &
                    short_real_text(e%bar*e%mu)
                if (e%estimated .and. e%bar >= 1.0_wp) text = text//' (no certain digit)'
                text = text//NL// &
                    '  critical c_t = mu |lambda| = '//real_to_text(e%c_t)// &
                    ', slip sign s = '//to_string(e%slip_sign)// &
                    ' (u_t '//merge('< 0', '> 0', e%slip_sign < 0)//' along t)'//NL
                if (e%estimated .and. e%level_change) then
                    ! the change is the previous level's error: the bar may be below it
                    text = text//'  relative change of mu to the previous hp level: '// &
                        short_real_text(e%estimate)//' (the error of that level); error bar '// &
                        short_real_text(e%bar)
                    if (e%check >= 0.0_wp) text = text//' (with the check one degree higher, '// &
                        'which moves mu by '//short_real_text(e%check)//')'
                    text = text//NL
                else if (e%estimated) then
                    text = text//'  relative error estimate of mu: '// &
                        short_real_text(e%estimate)//' ('//e%estimate_label//'); error bar '// &
                        short_real_text(e%bar)//NL
                end if
                if (allocated(e%skipped)) text = text//'  relative error estimate of mu: '// &
                    e%skipped//NL
                if (e%roundoff >= 0.0_wp) then
                    text = text//'  round-off bound of mu: '//short_real_text(e%roundoff)// &
                           ' relative'
                    if (e%quotient) text = text//' (Rayleigh quotient without a stored K)'
                    if (e%estimated) text = text//' (in the error bar)'
                    text = text//NL
                end if
            else
                text = text//'  no positive real eigenvalue for this lambda'//NL
            end if
            if (e%cn_max > 0.0_wp) then
                text = text//'  critical c_n in (0, '//real_to_text(e%cn_max)//']: '// &
                    to_string(size(e%critical))
                do i = 1, size(e%critical)
                    text = text//merge(': ', ', ', i == 1)//real_to_text(e%critical(i))
                end do
                text = text//NL
            end if
            text = text//'  time [s]    assembly '//seconds_text(t%assembly)// &
                ', ordering '//seconds_text(t%ordering)// &
                ', factor '//seconds_text(t%factor)// &
                ', reduction '//seconds_text(t%reduction)// &
                ', eigen '//seconds_text(t%eigen)// &
                ', output '//seconds_text(t%output)// &
                ', total '//seconds_text(t%total)//NL// &
                '  output      '//rec%directory
            if (allocated(rec%mode_plot)) then
                if (len(rec%mode_plot) > 0) text = text//NL//'  mode plot   '//rec%mode_plot
            end if
            if (allocated(e%warnings)) then
                do i = 1, size(e%warnings)
                    text = text//NL//'warning: '//trim(e%warnings(i))
                end do
            end if
        end associate
    end function eigen_lines

    !> lambda_critical_plus/minus (null where none), the backward error of each on the pencil,
    !> the pencil's eigenvalue counts, the confirming solves on each side, the boundary.
    subroutine add_threshold_keys(summary, f)
        type(json_object_t), intent(inout) :: summary
        type(threshold_facts_t), intent(in) :: f
        integer :: side
        character(len=:), allocatable :: s

        do side = 1, 2
            call summary%add_real_or_null('lambda_critical_'//trim(SIDE_NAME(side)), &
                                          f%side(side)%lambda, f%side(side)%found)
        end do
        do side = 1, 2
            s = trim(SIDE_NAME(side))
            associate (d => f%side(side))
                call summary%add_real_or_null('lambda_critical_'//s//'_residual', d%residual, &
                                              d%found)
                ! |dlambda| / |lambda| from floating point (roundoff: threshold_roundoff)
                call summary%add_real_or_null('lambda_critical_'//s//'_roundoff', d%roundoff, &
                                              d%found .and. d%roundoff >= 0.0_wp)
                call summary%add_logical('lambda_critical_'//s//'_confirmed', d%confirmed)
                call summary%add_real_or_null('lambda_'//s//'_outside', d%lambda_outside, d%found)
                call summary%add_real_or_null('mu_'//s//'_outside', d%mu_outside, &
                                              d%has_mu_outside)
                call summary%add_real_or_null('lambda_'//s//'_inside', d%lambda_inside, d%found)
                call summary%add_real_or_null('mu_'//s//'_inside', d%mu_inside, d%has_mu_inside)
            end associate
        end do
        ! |lambda_h - lambda| / |lambda_h| estimated (threshold_estimate); null where not
        do side = 1, 2
            call summary%add_real_or_null('lambda_critical_'//trim(SIDE_NAME(side))// &
                '_error_estimate', f%side(side)%estimate, f%side(side)%estimated)
        end do
        ! the relative bars quoted with them (error_bar); null where none
        do side = 1, 2
            call summary%add_real_or_null('lambda_critical_'//trim(SIDE_NAME(side))// &
                '_error_bar', f%side(side)%bar, &
                f%side(side)%estimated .and. f%side(side)%bar >= 0.0_wp)
        end do
        ! hp: the level whose value and bar are quoted (where the side met the tolerance)
        do side = 1, 2
            if (f%side(side)%met_level > 0) then
                call summary%add_integer('lambda_critical_'//trim(SIDE_NAME(side))// &
                                         '_met_level', f%side(side)%met_level)
            else
                call summary%add_null('lambda_critical_'//trim(SIDE_NAME(side))//'_met_level')
            end if
        end do
        ! hp: what is known of a side that did not converge (moving_side); null otherwise
        do side = 1, 2
            call add_moving(summary, 'lambda_critical_'//trim(SIDE_NAME(side))//'_moving', &
                            f%side(side)%moving)
        end do
        ! |lambda*| is the friction coefficient of the Signorini-Coulomb eigenproblem
        ! (model.md section 7), whether or not a positive mu appears there
        do side = 1, 2
            call summary%add_real_or_null('critical_friction_coefficient_'// &
                                          trim(SIDE_NAME(side)), abs(f%side(side)%lambda), &
                                          f%side(side)%found)
        end do
        call summary%add_real('confirm_offset', f%confirm_offset)
        call summary%add_integer('pencil_n_real', f%n_real)
        call summary%add_integer('pencil_n_complex', f%n_complex)
        call summary%add_integer('pencil_n_infinite', f%n_infinite)
        call add_boundary_keys(summary, f)
        call summary%add_real('time_threshold_s', f%time_threshold)
    end subroutine add_threshold_keys

    !> Key `key`: a side that did not converge (docs/outputs.md), as an object; null when
    !> `side` is not known.
    subroutine add_moving(summary, key, side)
        type(json_object_t), intent(inout) :: summary
        character(len=*), intent(in) :: key
        type(moving_side_t), intent(in) :: side
        type(json_object_t) :: object
        if (.not. side%known) then
            call summary%add_null(key)
            return
        end if
        associate (v => side%verdict)
            if (side%alternates) then
                call object%add_string('verdict', 'alternating')
            else
                call object%add_string('verdict', trim(TRACK_NAMES(v%kind)))
            end if
            call object%add_real_or_null('alternate_value', side%other, side%alternates)
            call object%add_integer('levels', v%length)
            call object%add_real('value', v%value)
            call object%add_real_or_null('rate', v%rate, v%rate >= 0.0_wp)
            ! an extrapolation of a value that moves, never a converged value
            call object%add_real_or_null('limit', v%limit, v%has_limit .and. &
                                         v%kind == TRACK_MOVING)
            call object%add_real('s', side%s)
            call object%add_real('length', side%length)
            call object%add_real_array('point', side%point)
            call object%add_logical('at_end', side%end > 0)
            call object%add_real_or_null('end_share', v%end_share(max(side%end, 1)), &
                                         side%end > 0)
            call object%add_logical('concentrating', side%end > 0 .and. &
                                    v%concentrating(max(side%end, 1)))
            call object%add_real_or_null('corner_degrees', side%angle_degrees, &
                                         side%end > 0 .and. side%far > 0)
            if (side%end > 0 .and. side%far > 0) then
                call object%add_string('other_side', trim(FAR_NAMES(side%far)))
            else
                call object%add_null('other_side')
            end if
            call object%add_real_or_null('wedge_lambda', side%wedge_lambda, side%has_exponent)
            call object%add_real_or_null('wedge_exponent', side%exponent, side%has_exponent)
            call object%add_real_or_null('wedge_crossing', side%crossing, side%has_crossing)
            call object%add_logical('past_crossing', side%past_crossing)
        end associate
        call summary%add_object(key, object)
    end subroutine add_moving

    !> The boundary points of {lambda : a positive mu exists} in the searched range, one
    !> array entry per point (ascending lambda), and the intervals they bound.
    subroutine add_boundary_keys(summary, f)
        type(json_object_t), intent(inout) :: summary
        type(threshold_facts_t), intent(in) :: f
        real(wp), allocatable :: lambdas(:), discriminants(:), mu_meets(:), bars(:), roundoffs(:)
        integer, allocatable :: below(:), above(:)
        logical, allocatable :: confirmed(:)
        character(len=12), allocatable :: mechanisms(:)
        character(len=8), allocatable :: directions(:)
        integer :: i, n, side

        ! Plain arrays, filled point by point: a component of an array of derived type
        ! passed as an array makes a temporary (a runtime warning under -fcheck=all).
        n = size(f%points)
        allocate (lambdas(n), discriminants(n), mu_meets(n), below(n), above(n), confirmed(n), &
                  mechanisms(n), directions(n), bars(n), roundoffs(n))
        do i = 1, n
            associate (b => f%points(i))
                ! the relative bar of each point (boundary_estimate); NaN is written as null
                bars(i) = nan_unless(b%bar >= 0.0_wp, b%bar)
                roundoffs(i) = nan_unless(b%roundoff >= 0.0_wp, b%roundoff)   ! its round-off
                lambdas(i) = b%lambda
                below(i) = b%n_below
                above(i) = b%n_above
                confirmed(i) = b%confirmed
                mechanisms(i) = b%mechanism
                directions(i) = merge('appears ', 'vanishes', b%appears)
                ! null for pencil points, where no pair meets
                discriminants(i) = nan_unless(b%pair, b%discriminant)
                mu_meets(i) = nan_unless(b%pair, b%mu_meet)
            end associate
        end do
        ! where a positive mu first exists going out from lambda = 0 (where none does)
        do side = 1, 2
            i = f%onset(side)
            if (i > 0) then
                call summary%add_real('lambda_onset_'//trim(SIDE_NAME(side)), lambdas(i))
                call summary%add_string('lambda_onset_'//trim(SIDE_NAME(side))// &
                                        '_mechanism', trim(mechanisms(i)))
            else
                call summary%add_null('lambda_onset_'//trim(SIDE_NAME(side)))
                call summary%add_null('lambda_onset_'//trim(SIDE_NAME(side))//'_mechanism')
            end if
        end do
        call summary%add_real('boundary_lambda_min', f%lambda_min)
        call summary%add_real('boundary_lambda_max', f%lambda_max)
        call summary%add_integer('boundary_n_points', n)
        call summary%add_real_array('boundary_lambda', lambdas)
        call summary%add_string_array('boundary_mechanism', mechanisms)
        call summary%add_real_array('boundary_error_bar', bars)
        call summary%add_real_array('boundary_roundoff', roundoffs)
        call summary%add_string_array('boundary_direction', directions)
        call summary%add_logical_array('boundary_confirmed', confirmed)
        call summary%add_integer_array('boundary_n_positive_below', below)
        call summary%add_integer_array('boundary_n_positive_above', above)
        call summary%add_real_array('boundary_discriminant', discriminants)
        call summary%add_real_array('boundary_mu_meet', mu_meets)
        call summary%add_real_array('positive_mu_intervals_lower', f%lower)
        call summary%add_real_array('positive_mu_intervals_upper', f%upper)
        call summary%add_integer('boundary_n_evaluations', f%n_evaluations)
        call summary%add_integer('boundary_scan_contact', f%scan_contact)
    end subroutine add_boundary_keys

    !> `x` where `known`, else NaN (written as null).
    elemental real(wp) function nan_unless(known, x)
        logical, intent(in) :: known
        real(wp), intent(in) :: x
        nan_unless = ieee_value(1.0_wp, ieee_quiet_nan)
        if (known) nan_unless = x
    end function nan_unless

    !> The thresholds with their confirmations, the boundary, and the sweep's line.
    function threshold_lines(f, sweep) result(text)
        type(threshold_facts_t), intent(in) :: f
        type(sweep_facts_t), intent(in), optional :: sweep
        character(len=:), allocatable :: text
        integer :: side

        text = ''
        do side = 1, 2
            associate (d => f%side(side))
                text = text//NL//'  '//SIDE_LABEL(side)//'     '
                if (.not. d%found) then
                    text = text//'none (no real eigenvalue of Kt_nn x = lambda Kt_nt x ' &
                        //merge('> 0', '< 0', side == 1)//')'
                    cycle
                end if
                text = text//real_to_text(d%lambda)
                ! the headline quotes its bar, absolute: lambda = X +- B
                if (d%estimated .and. d%bar >= 0.0_wp) &
                    text = text//' +- '//short_real_text(d%bar*abs(d%lambda))
                text = text//' (pencil backward error '//short_real_text(d%residual)//'), '// &
                    trim(merge('confirmed    ', 'NOT confirmed', d%confirmed))
                if (d%estimated .and. d%level_change) then
                    ! the change is the previous level's error: the bar may be below it
                    text = text//NL//'              relative change to the previous hp level '// &
                        short_real_text(d%estimate)//' (the error of that level); error bar '// &
                        short_real_text(d%bar)
                    if (d%met_level > 0) text = text//NL// &
                        '              the tolerance met at hp level '// &
                        to_string(d%met_level)//': the value and bar of that level'
                else if (d%estimated) then
                    text = text//NL//'              relative error estimate '// &
                        short_real_text(d%estimate)//' ('//d%estimate_label//'); error bar '// &
                        short_real_text(d%bar)
                else if (len(d%skipped) > 0) then
                    text = text//NL//'              relative error estimate '//d%skipped
                end if
                if (d%moving%known) text = text//NL//'              '// &
                    moving_words('not converged: '//SIDE_LABEL(side), d%moving)
                text = text//NL// &
                    '              just outside, lambda = '// &
                    real_to_text(d%lambda_outside)//': lowest positive mu = '// &
                    known_text(d%has_mu_outside, d%mu_outside, 'none')//NL// &
                    '              just inside,  lambda = '// &
                    real_to_text(d%lambda_inside)//': lowest positive mu = '// &
                    known_text(d%has_mu_inside, d%mu_inside, 'none')
            end associate
        end do
        text = text//boundary_lines(f)
        text = text//NL//'  time [s]    thresholds '//short_real_text(f%time_threshold)
        if (present(sweep)) then
            text = text//', sweep '//short_real_text(sweep%time_sweep)//NL//'  sweep       '// &
                to_string(sweep%n_lambda)//' lambdas from '// &
                real_to_text(sweep%lambda_min)//' to '// &
                real_to_text(sweep%lambda_max)//', a positive mu at '// &
                to_string(sweep%n_with_mu)//' of them: '//sweep%file
        end if
    end function threshold_lines

    !> One line per boundary point, then the intervals with a positive mu.
    function boundary_lines(f) result(text)
        type(threshold_facts_t), intent(in) :: f
        character(len=:), allocatable :: text
        integer :: i

        text = NL//'  boundary    of {lambda : a positive mu exists} in ['// &
            real_to_text(f%lambda_min)//', '//real_to_text(f%lambda_max)//']: '// &
            to_string(size(f%points))//trim(merge(' point ', ' points', size(f%points) == 1))
        if (f%scan_contact /= f%contact) text = text//' (scanned on a coarser level, '// &
            to_string(f%scan_contact)//' contact functions; located on this one)'
        do i = 1, size(f%points)
            associate (b => f%points(i))
                text = text//NL//'              lambda = '//real_to_text(b%lambda)
                if (b%bar >= 0.0_wp) text = text//' +- '//short_real_text(b%bar*abs(b%lambda))
                text = text//' '//trim(b%mechanism)//', '
                if (b%n_below == b%n_above) then
                    ! no change of the count across it: neither appears nor vanishes
                    text = text//'the count of positive mu is '//to_string(b%n_below)// &
                        ' on both sides, '
                else
                    text = text//'positive mu '// &
                        trim(merge('appears ', 'vanishes', b%appears))// &
                        ' as lambda increases ('//to_string(b%n_below)//' -> '// &
                        to_string(b%n_above)//'), '
                end if
                text = text//trim(merge('confirmed    ', 'NOT confirmed', b%confirmed))
            end associate
        end do
        text = text//NL//'              positive mu on'
        if (size(f%lower) == 0) text = text//' no part of the range'
        do i = 1, size(f%lower)
            text = text//' ['//real_to_text(f%lower(i))//', '//real_to_text(f%upper(i))//']'
        end do
    end function boundary_lines

    !> What a sweep ran: its file, size, range and spacing, and how many points had a mu.
    subroutine add_sweep_keys(summary, f)
        type(json_object_t), intent(inout) :: summary
        type(sweep_facts_t), intent(in) :: f
        call summary%add_string('sweep_file', f%file)
        call summary%add_string('sweep_spacing', f%spacing)
        call summary%add_integer('sweep_n_lambda', f%n_lambda)
        call summary%add_real('sweep_lambda_min', f%lambda_min)
        call summary%add_real('sweep_lambda_max', f%lambda_max)
        call summary%add_integer('sweep_n_with_positive_mu', f%n_with_mu)
        call summary%add_integer('sweep_n_arpack', f%n_arpack)
        call summary%add_integer('sweep_n_dense', f%n_dense)
        ! with &adapt: the points adapted (every one), those whose mesh needed no refinement
        ! (the previous point's served), the largest estimate met
        if (f%adapted) then
            call summary%add_integer('sweep_n_adapted', f%n_lambda)
            call summary%add_integer('sweep_n_mesh_reused', f%n_reused)
            call summary%add_integer('sweep_n_not_met', f%n_not_met)
            call summary%add_logical('adapt_converged', f%n_not_met == 0 .and. .not. f%partial)
            ! a point's loop failed: the rows are those of the points complete before
            call summary%add_logical('sweep_partial', f%partial)
            call summary%add_integer('sweep_n_complete', f%n_complete)
            call summary%add_real_or_null('sweep_max_error_estimate', f%max_estimate, &
                                          f%max_estimate >= 0.0_wp)
            call summary%add_real_or_null('sweep_max_error_bar', f%max_bar, f%max_bar >= 0.0_wp)
        end if
        call summary%add_real('time_sweep_s', f%time_sweep)
    end subroutine add_sweep_keys

    !> The keys of an adaptive loop (any goal), and those of hp levels.
    subroutine add_adapt_keys(summary, f)
        type(json_object_t), intent(inout) :: summary
        type(adapt_facts_t), intent(in) :: f
        call summary%add_real('adapt_tolerance', f%tolerance)
        call summary%add_real('adapt_theta', f%theta)
        call summary%add_integer('adapt_levels', f%levels)
        call summary%add_integer('adapt_start_dofs', f%start_dofs)
        call summary%add_logical('adapt_converged', f%converged)
        call summary%add_logical('adapt_floor_reached', f%floor_reached)
        call summary%add_string('adapt_outcome', f%outcome)
        call summary%add_string('adapted_mesh_file', f%mesh_file)
        if (.not. f%hp) return
        call summary%add_string('adapt_strategy', 'hp')
        call summary%add_real('adapt_sigma', f%sigma)
        call summary%add_integer('adapt_p_max', f%p_max)
        call summary%add_string('degrees_file', f%degrees_file)
        if (f%has_degrees) then
            call summary%add_integer('hp_degree_min', f%degree_min)
            call summary%add_integer('hp_degree_max', f%degree_max)
        end if
        call summary%add_integer('adapt_start_cells', f%start_cells)
    end subroutine add_adapt_keys

    !> The stdout lines of an adaptive loop: its levels and outcome, the mesh files.
    function adapt_lines(f, directory) result(text)
        type(adapt_facts_t), intent(in) :: f
        character(len=*), intent(in) :: directory
        character(len=:), allocatable :: text
        if (.not. f%hp) then
            text = NL//'  adapt       '//to_string(f%levels)//' refinements from '// &
                to_string(f%start_dofs)//' dofs; '//f%outcome//NL//'  mesh        '// &
                directory//'/'//f%mesh_file//' (the final mesh, for &mesh source = ''gmsh'')'
            return
        end if
        text = NL//'  adapt       hp, '//to_string(f%levels)// &
            trim(merge(' level ', ' levels', f%levels == 1))//' from the '// &
            to_string(f%start_cells)//'-cell input mesh'
        if (f%has_degrees) text = text//' (last: degrees '//to_string(f%degree_min)// &
            ' to '//to_string(f%degree_max)//')'
        text = text//'; '//f%outcome//NL//'  mesh        '//directory//'/'//f%mesh_file// &
            ' and '//f%degrees_file//' (the last graded mesh and its cell degrees)'
    end function adapt_lines

    subroutine add_branch_keys(summary, f)
        type(json_object_t), intent(inout) :: summary
        type(branch_facts_t), intent(in) :: f
        call summary%add_real('alpha', f%alpha)
        call summary%add_real('beta', f%beta)
        call summary%add_real('c_n', f%c_n)
        call summary%add_real('c_t', f%c_t)
        call summary%add_real('delta_max', f%delta_max)
        call summary%add_integer('n_delta', f%n_delta)
        call summary%add_real('branch_base_residual', f%residual_base)
        call summary%add_real('branch_max_residual', f%max_residual)
        call summary%add_real('load_norm', f%load_norm)
        call summary%add_real('time_branch_s', f%time_branch)
    end subroutine add_branch_keys

    !> The first lines of 'branch' and 'solve': the run and the problem's sizes, up to the
    !> parameters that follow them.
    function compliance_head(rec, analysis) result(text)
        type(run_summary_t), intent(in) :: rec
        character(len=*), intent(in) :: analysis
        character(len=:), allocatable :: text
        text = 'nceig '//rec%version//': '//rec%input//' ('//analysis//')'//NL// &
            '  problem     '//to_string(rec%n_dofs)//' dofs, '//to_string(rec%n_contact)// &
            ' contact nodes, '
    end function compliance_head

    function branch_lines(rec) result(text)
        type(run_summary_t), intent(in) :: rec
        character(len=:), allocatable :: text
        associate (f => rec%branch)
            text = compliance_head(rec, 'branch')//'lambda = '//real_to_text(rec%eigen%lambda)// &
                NL// &
                '  critical    c_n = mu = '//real_to_text(f%c_n)//', c_t = '// &
                real_to_text(f%c_t)//NL// &
                '  branch      U + delta phi for |delta| <= delta_max = '// &
                real_to_text(f%delta_max)//' (alpha = '//real_to_text(f%alpha)// &
                ', beta = '//real_to_text(f%beta)//')'//NL// &
                '  residual    U: '//short_real_text(f%residual_base)//', max over '// &
                to_string(f%n_delta)//' members: '//short_real_text(f%max_residual)// &
                ' (relative to the load)'//NL// &
                '  output      '//rec%directory
        end associate
    end function branch_lines

    !> The keys of the compliance problem; its times replace the eigen solve's.
    subroutine add_solve_keys(summary, f, t)
        type(json_object_t), intent(inout) :: summary
        type(solve_facts_t), intent(in) :: f
        type(timings_t), intent(in) :: t
        call summary%add_string('data', f%data)
        call summary%add_string('start', f%start)
        call summary%add_real('c_n', f%c_n)
        call summary%add_real('c_t', f%c_t)
        call summary%add_logical('converged', f%converged)
        call summary%add_string('newton_stop', f%newton_stop)
        call summary%add_integer('iterations', f%iterations)
        call summary%add_real('residual', f%residual)
        call summary%add_real('tol', f%tol)
        call summary%add_real('load_norm', f%load_norm)
        call summary%add_integer('n_separated', f%n_state(1))
        call summary%add_integer('n_stick', f%n_state(2))
        call summary%add_integer('n_slip_plus', f%n_state(3))
        call summary%add_integer('n_slip_minus', f%n_state(4))
        if (f%on_branch) then
            call summary%add_real('branch_delta', f%branch_delta)
            call summary%add_real('branch_distance', f%branch_distance)
        end if
        call summary%add_real('time_assembly_s', t%assembly)
        call summary%add_real('time_factor_s', t%factor)
        call summary%add_real('time_eigen_s', t%eigen)
        call summary%add_real('time_newton_s', f%time_newton)
        call summary%add_real('time_output_s', t%output)
        call summary%add_real('time_total_s', t%total)
    end subroutine add_solve_keys

    function solve_lines(rec) result(text)
        type(run_summary_t), intent(in) :: rec
        character(len=:), allocatable :: text
        associate (f => rec%solve)
            text = compliance_head(rec, 'solve')//'c_n = '//real_to_text(f%c_n)// &
                ', c_t = '//real_to_text(f%c_t)//NL// &
                '  newton      '//f%newton_stop//' after '// &
                to_string(f%iterations)//' iterations, relative residual '// &
                short_real_text(f%residual)//NL// &
                '  contact     '//to_string(f%n_state(1))//' separated, '// &
                to_string(f%n_state(2))//' stick, '// &
                to_string(f%n_state(3))//' slip+, '// &
                to_string(f%n_state(4))//' slip-'//NL
            if (f%on_branch) then
                text = text//'  branch      x = U + delta phi + r with delta = '// &
                    real_to_text(f%branch_delta)//', ||r|| / ||U|| = '// &
                    short_real_text(f%branch_distance)//NL
            end if
            text = text//'  output      '//rec%directory
        end associate
    end function solve_lines
end module summary_record
