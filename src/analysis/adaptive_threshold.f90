! SPDX-License-Identifier: MIT
!> The adaptive loop (adaptive_loop) of analysis 'threshold' with &adapt tolerance > 0: its
!> goal is the pair of critical lambdas, lambda+ and lambda-, the real eigenvalues of the
!> pencil Kt_nn x = lambda Kt_nt x nearest zero, each with its own error estimate
!> (threshold_estimate).
!>
!> Both sides on one mesh. Each level marks, for every side whose estimate is still above
!> the tolerance, the Doerfler set of that side's indicators, and refines the union. The
!> two sides need different refinement (on the reference scene each threshold's mode is
!> singular at the other corner of Gamma_C), so the mesh is finer than either side alone
!> needs; in exchange one mesh carries both answers and everything else a threshold run
!> reports on it (the spectrum at &analysis lambda, the confirmations and the boundary of
!> the set where a positive mu exists), and a side that meets the tolerance first stops
!> asking for cells.
module adaptive_threshold
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string, short_real_text
    use timer, only: wall_time, timings_t, PHASE_REDUCTION
    use run_config, only: config_t
    use problem, only: problem_t
    use sparse_cholesky, only: cholesky_t
    use threshold_analysis, only: factor_with_contact_blocks, threshold_result_t, &
                                  solve_thresholds
    use critical_lambda, only: thresholds_t, pencil_thresholds, SIDE_PLUS, SIDE_MINUS, &
                               SIDE_LABELS
    use error_estimate, only: ENRICHED_CONTACT_MAX
    use threshold_estimate, only: threshold_estimate_t, threshold_displacements, &
                                  estimate_threshold_errors
    use adaptive_loop, only: adapt_goal_t, adapt_mesh, doerfler_marking
    use error_bar, only: level_bar
    use element_types, only: element_degree
    implicit none
    private
    public :: adapt_thresholds, solve_adapted_thresholds

    !> One level of the loop: a row of adapt.csv, arrays by SIDE_PLUS, SIDE_MINUS.
    type, public :: threshold_level_t
        integer :: level = 0
        integer :: n_dofs = 0
        integer :: n_contact = 0
        integer :: n_cells = 0
        logical :: found(2) = .false.             !! a threshold on that side
        real(wp) :: lambda(2) = 0.0_wp
        logical :: estimated(2) = .false.
        real(wp) :: error_estimate(2) = 0.0_wp    !! |relative error estimate| of lambda
        real(wp) :: error_bar(2) = -1.0_wp         !! the bars at this level; < 0: none
        real(wp) :: time_s = 0.0_wp
    end type threshold_level_t

    type, public :: adaptive_thresholds_t
        type(threshold_level_t), allocatable :: levels(:)
        type(problem_t) :: prob                   !! the problem of the last level solved
        type(threshold_estimate_t) :: estimate    !! of its thresholds
        logical :: converged = .false.
        character(len=:), allocatable :: outcome
    end type adaptive_thresholds_t

    type, extends(adapt_goal_t) :: threshold_goal_t
        type(threshold_level_t), allocatable :: levels(:)
        type(thresholds_t) :: thr
        type(threshold_estimate_t) :: est
        real(wp) :: tolerance = 0.0_wp   !! &adapt tolerance: the sides above it mark cells
    contains
        procedure :: solve => threshold_goal_solve
        procedure :: error => threshold_goal_error
        procedure :: mark => threshold_goal_mark
        procedure :: missing => threshold_goal_missing
    end type threshold_goal_t

contains

    !> Run the loop from the problem `start` (level 0) of `config`. A limit reached is no
    !> failure (stat ok, out%converged false, out%outcome says so).
    subroutine adapt_thresholds(config, start, out, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: start
        type(adaptive_thresholds_t), intent(out) :: out
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(threshold_goal_t) :: goal

        allocate (goal%levels(0))
        call adapt_mesh(config, start, goal, out%prob, out%converged, out%outcome, timings, stat)
        if (.not. stat%ok()) return
        call move_alloc(goal%levels, out%levels)
        out%estimate = goal%est
    end subroutine adapt_thresholds

    !> The adaptive 'threshold' analysis: the loop from `start` (adapt_thresholds), then the
    !> threshold analysis on its final problem with the loop's estimates; a limit reached
    !> heads the warnings of `res` (out%converged false says so).
    subroutine solve_adapted_thresholds(config, start, out, res, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: start
        type(adaptive_thresholds_t), intent(out) :: out
        type(threshold_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        call adapt_thresholds(config, start, out, timings, stat)
        if (stat%ok()) call solve_thresholds(config, out%prob, .false., res, timings, stat, &
                                             out%estimate)
        if (stat%ok() .and. .not. out%converged) res%eigen%warnings = &
            [character(len=len(res%eigen%warnings)) :: out%outcome, res%eigen%warnings]
    end subroutine solve_adapted_thresholds

    !> Factor K, form the contact blocks, solve the pencil, and estimate both thresholds.
    subroutine threshold_goal_solve(this, config, prob, level, loop_start, timings, stat)
        class(threshold_goal_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        integer, intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(cholesky_t) :: chol
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), u(:, :)
        real(wp) :: start

        this%tolerance = config%adapt%tolerance
        call factor_with_contact_blocks(config, prob, chol, kt_nn, kt_nt, timings, stat)
        if (.not. stat%ok()) return
        start = wall_time()
        call pencil_thresholds(kt_nn, kt_nt, this%thr, stat)
        if (stat%ok()) call threshold_displacements(chol, prob%contact, prob%dofs%n_free, &
                                                    this%thr, u, stat)
        call chol%free()
        if (.not. stat%ok()) return
        deallocate (kt_nn, kt_nt)
        call estimate_threshold_errors(prob, this%thr, u, ENRICHED_CONTACT_MAX, this%est, stat)
        if (.not. stat%ok()) return
        call timings%add(PHASE_REDUCTION, wall_time() - start, ': thresholds and their '// &
                         'error estimates, level '//to_string(level))
        this%levels = [this%levels, level_row()]
        call level_bars(this%levels, element_degree(prob%mesh%element), this%est)
        call timings%note(level_line(this%levels(size(this%levels))))

    contains

        type(threshold_level_t) function level_row() result(row)
            row%level = level
            row%n_dofs = prob%dofs%n_free
            row%n_contact = prob%contact%p()
            row%n_cells = prob%mesh%n_cells()
            row%found = this%thr%found
            row%lambda = this%thr%lambda
            row%estimated = this%est%computed
            row%error_estimate = abs(this%est%relative)
            row%time_s = wall_time() - loop_start
        end function level_row

        function level_line(row) result(line)
            type(threshold_level_t), intent(in) :: row
            character(len=:), allocatable :: line
            integer :: side
            line = 'adapt level '//to_string(row%level)//': '//to_string(row%n_dofs)//' dofs'
            do side = SIDE_PLUS, SIDE_MINUS
                if (.not. row%found(side)) cycle
                line = line//', '//SIDE_LABELS(side)//' = '// &
                    short_real_text(row%lambda(side), 12)
                if (row%estimated(side)) line = line//' (estimate '// &
                    short_real_text(row%error_estimate(side))//', bar '// &
                    short_real_text(row%error_bar(side))//')'
            end do
        end function level_line
    end subroutine threshold_goal_solve

    !> The larger estimate of the sides found; negative when one of them has none, or when
    !> there is no threshold at all.
    real(wp) function threshold_goal_error(this)
        class(threshold_goal_t), intent(in) :: this
        threshold_goal_error = -1.0_wp
        if (.not. any(this%thr%found)) return
        if (any(this%thr%found .and. .not. this%est%computed)) return
        threshold_goal_error = maxval(this%est%bar, mask=this%thr%found)
    end function threshold_goal_error

    !> Each side's bar at the last of `levels` (error_bar: the last BAR_WINDOW levels where
    !> that side was found and estimated), into the last row and `est`.
    subroutine level_bars(levels, degree, est)
        type(threshold_level_t), intent(inout) :: levels(:)
        integer, intent(in) :: degree
        type(threshold_estimate_t), intent(inout) :: est
        real(wp) :: estimates(size(levels)), lambdas(size(levels))
        integer :: dofs(size(levels)), side, k, i
        k = size(levels)
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. (levels(k)%found(side) .and. levels(k)%estimated(side))) cycle
            ! plain arrays: components of a derived-type array would make temporaries
            do i = 1, k
                estimates(i) = -1.0_wp
                if (levels(i)%found(side) .and. levels(i)%estimated(side)) &
                    estimates(i) = levels(i)%error_estimate(side)
                lambdas(i) = levels(i)%lambda(side)
                dofs(i) = levels(i)%n_dofs
            end do
            levels(k)%error_bar(side) = level_bar(estimates, lambdas, dofs, degree, -1.0_wp)
            est%bar(side) = levels(k)%error_bar(side)
        end do
    end subroutine level_bars

    !> The union of the Doerfler sets of the sides still above the tolerance.
    function threshold_goal_mark(this, theta) result(marked)
        class(threshold_goal_t), intent(in) :: this
        real(wp), intent(in) :: theta
        integer, allocatable :: marked(:)
        logical, allocatable :: chosen(:)
        integer :: side, i

        allocate (chosen(size(this%est%indicators, 1)), source=.false.)
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. this%thr%found(side)) cycle
            if (this%est%bar(side) <= this%tolerance) cycle
            chosen(doerfler_marking(this%est%indicators(:, side), theta)) = .true.
        end do
        marked = pack([(i, i=1, size(chosen))], chosen)
    end function threshold_goal_mark

    function threshold_goal_missing(this) result(reason)
        class(threshold_goal_t), intent(in) :: this
        character(len=:), allocatable :: reason
        integer :: side
        reason = 'no real eigenvalue of the pencil Kt_nn x = lambda Kt_nt x: no threshold '// &
                 'to adapt to'
        do side = SIDE_PLUS, SIDE_MINUS
            if (this%thr%found(side) .and. .not. this%est%computed(side)) then
                reason = SIDE_LABELS(side)//': '//trim(this%est%skipped(side))
                if (len_trim(this%est%skipped(side)) == 0) reason = reason// &
                    'no enrichment for these cells'
                return
            end if
        end do
    end function threshold_goal_missing
end module adaptive_threshold
