! SPDX-License-Identifier: MIT
!> The adaptive loop of analysis 'eigen' with &adapt tolerance > 0 (adaptive_loop), with the
!> lowest positive mu as its goal: each level solves the eigenproblem of the analysis
!> (dense or ARPACK as &eigen asks), estimates the error of mu (error_estimate), and marks
!> by Doerfler's bulk criterion on its cell indicators, which refines where the
!> eigenfunction is singular (the corners of Gamma_C) and leaves the smooth interior coarse.
module adaptive_eigen
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string, short_real_text
    use timer, only: wall_time, timings_t
    use scene, only: scene_t
    use method_options, only: eigen_options_t, adapt_options_t, ESTIMATE_ON
    use problem, only: problem_t
    use eigen_solve, only: eigen_result_t, solve_eigen, estimate_eigen
    use accuracy, only: WARNING_LEN, MU_VANISHED
    use adaptive_loop, only: adapt_goal_t, adapt_mesh, doerfler_marking
    use error_bar, only: level_bar, theta_warnings
    use element_types, only: element_degree
    implicit none
    private
    public :: adapt_eigen

    !> One level of the loop: a row of adapt.csv.
    type, public :: adapt_level_t
        integer :: level = 0
        integer :: n_dofs = 0
        integer :: n_contact = 0
        integer :: n_cells = 0
        logical :: has_mu = .false.           !! a positive mu exists
        real(wp) :: mu = 0.0_wp               !! lowest positive mu, input units
        logical :: estimated = .false.
        real(wp) :: error_estimate = 0.0_wp   !! |relative error estimate| of mu
        real(wp) :: error_bar = -1.0_wp       !! the bar at this level (error_bar); < 0: none
        real(wp) :: roundoff = -1.0_wp        !! its round-off part (module roundoff); < 0: unknown
        real(wp) :: time_s = 0.0_wp           !! wall time from the loop's start to this level's end
    end type adapt_level_t

    type, public :: adaptive_result_t
        type(adapt_level_t), allocatable :: levels(:)
        type(problem_t) :: prob            !! the problem of the last level solved
        type(eigen_result_t) :: res        !! its spectrum and error estimate
        logical :: converged = .false.     !! the estimate met the tolerance
        logical :: floor_reached = .false. !! stopped by round-off, not by a limit
        !> the last level has no positive mu where an earlier one had (accuracy: MU_VANISHED)
        logical :: mu_vanished = .false.
        !> one line: the tolerance met, or why not and what was reached
        character(len=:), allocatable :: outcome
    end type adaptive_result_t

    !> The goal: the lowest positive mu at `lambda`.
    type, extends(adapt_goal_t) :: eigen_goal_t
        real(wp) :: lambda = 0.0_wp
        !> the run's, with the estimate on: the loop is driven by it, whatever the size
        type(eigen_options_t) :: options
        type(adapt_level_t), allocatable :: levels(:)
        type(eigen_result_t) :: res
    contains
        procedure :: solve => eigen_goal_solve
        procedure :: error => eigen_goal_error
        procedure :: mark => eigen_goal_mark
        procedure :: missing => eigen_goal_missing
    end type eigen_goal_t

contains

    !> Run the loop for the lowest positive mu at `lambda` from the problem `start` (level 0)
    !> of the scene `scn`, solved as `options` and refined as `adapt` ask; `out` holds every
    !> level and the last one solved. A limit reached is no failure (stat ok, out%converged
    !> false, out%outcome and a warning of out%res say so).
    subroutine adapt_eigen(scn, lambda, options, adapt, start, out, timings, stat)
        type(scene_t), intent(in) :: scn
        real(wp), intent(in) :: lambda
        type(eigen_options_t), intent(in) :: options
        type(adapt_options_t), intent(in) :: adapt
        type(problem_t), intent(in) :: start
        type(adaptive_result_t), intent(out) :: out
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(eigen_goal_t) :: goal

        allocate (goal%levels(0))
        goal%lambda = lambda
        goal%options = options
        goal%options%estimate = ESTIMATE_ON
        call adapt_mesh(scn, adapt, start, goal, out%prob, out%converged, out%floor_reached, &
                        out%outcome, timings, stat)
        if (.not. stat%ok()) return
        call move_alloc(goal%levels, out%levels)
        out%res = goal%res
        out%mu_vanished = out%res%spec%lowest_positive() == 0 .and. any(out%levels%has_mu)
        if (.not. out%converged) out%res%warnings = [character(len=WARNING_LEN) :: &
                                                     out%outcome, out%res%warnings]
        out%res%warnings = [character(len=WARNING_LEN) :: out%res%warnings, &
                            theta_warnings(adapt%theta)]
    end subroutine adapt_eigen

    subroutine eigen_goal_solve(this, scn, prob, level, loop_start, timings, stat)
        class(eigen_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        integer, intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat

        call solve_eigen(scn, prob, this%lambda, this%options, this%res, timings, stat)
        if (.not. stat%ok()) return
        ! an adaptive run judges resolution by the change of mu between its levels
        call estimate_eigen(scn, prob, this%options, .false., this%res, timings)
        this%levels = [this%levels, level_row()]
        call set_level_bar(this%levels, element_degree(prob%mesh%element))
        this%roundoff = -1.0_wp
        if (this%levels(size(this%levels))%estimated) then
            this%res%error%bar = this%levels(size(this%levels))%error_bar
            this%roundoff = this%res%roundoff
        end if
        call timings%note(level_line(this%levels(size(this%levels))))

    contains

        type(adapt_level_t) function level_row() result(row)
            integer :: lowest
            row%level = level
            row%n_dofs = prob%dofs%n_free
            row%n_contact = prob%contact%p()
            row%n_cells = prob%mesh%n_cells()
            lowest = this%res%spec%lowest_positive()
            row%has_mu = lowest > 0
            if (row%has_mu) row%mu = real(this%res%spec%mu(lowest), wp)
            row%estimated = this%res%error%computed
            if (row%estimated) row%error_estimate = abs(this%res%error%relative)
            row%roundoff = this%res%roundoff
            row%time_s = wall_time() - loop_start
        end function level_row

        function level_line(row) result(line)
            type(adapt_level_t), intent(in) :: row
            character(len=:), allocatable :: line
            line = 'adapt level '//to_string(row%level)//': '//to_string(row%n_dofs)//' dofs'
            if (row%has_mu) line = line//', mu = '//short_real_text(row%mu, 12)
            if (row%estimated) line = line//', estimate '//short_real_text(row%error_estimate)// &
                ', bar '//short_real_text(row%error_bar)
        end function level_line
    end subroutine eigen_goal_solve

    !> The bar over the levels so far into the last one (error_bar): one dip of the estimate
    !> cannot make it small. Plain arrays, filled level by level: a component of an array of
    !> derived type passed as an array makes a temporary (a runtime warning under -fcheck=all).
    pure subroutine set_level_bar(levels, degree)
        type(adapt_level_t), intent(inout) :: levels(:)
        integer, intent(in) :: degree
        real(wp) :: estimates(size(levels)), mu(size(levels))
        integer :: dofs(size(levels)), i, k
        k = size(levels)
        if (.not. levels(k)%estimated) return
        do i = 1, k
            estimates(i) = -1.0_wp
            if (levels(i)%estimated .and. levels(i)%has_mu) estimates(i) = levels(i)%error_estimate
            mu(i) = levels(i)%mu
            dofs(i) = levels(i)%n_dofs
        end do
        levels(k)%error_bar = level_bar(estimates, mu, dofs, degree, levels(k)%roundoff)
    end subroutine set_level_bar

    real(wp) function eigen_goal_error(this)
        class(eigen_goal_t), intent(in) :: this
        eigen_goal_error = -1.0_wp
        if (this%res%error%computed) eigen_goal_error = this%res%error%bar
    end function eigen_goal_error

    function eigen_goal_mark(this, theta) result(marked)
        class(eigen_goal_t), intent(in) :: this
        real(wp), intent(in) :: theta
        integer, allocatable :: marked(:)
        marked = doerfler_marking(this%res%error%indicators, theta)
    end function eigen_goal_mark

    !> Why the estimate is missing: no positive mu (none at all, or none left of the earlier
    !> levels': MU_VANISHED), its size (est%skipped), or its failure.
    function eigen_goal_missing(this) result(reason)
        class(eigen_goal_t), intent(in) :: this
        character(len=:), allocatable :: reason
        reason = 'the estimate failed'
        if (this%res%spec%lowest_positive() == 0) then
            reason = 'no positive mu to adapt to'
            if (any(this%levels%has_mu)) reason = reason//': '//MU_VANISHED
        else if (allocated(this%res%error%skipped)) then
            reason = this%res%error%skipped
        else if (allocated(this%res%error%failure)) then
            reason = 'the estimate failed: '//this%res%error%failure
        end if
    end function eigen_goal_missing
end module adaptive_eigen
