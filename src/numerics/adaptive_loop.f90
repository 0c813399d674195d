! SPDX-License-Identifier: MIT
!> The adaptive loop of &adapt tolerance > 0, for any goal: solve, estimate, mark, refine,
!> until the goal's error bar (error_bar) is at most the tolerance or a limit is reached. With
!> the default limits (max_levels = 0, max_dofs = 0) only the memory the machine has ends a
!> loop that has not met its tolerance, never a level count.
!>
!> The loop stops at the tolerance from level 1 on: a bar is confirmed by the levels before
!> it (error_bar: level_bar's window and the change of the value), which level 0 has not.
!>
!> A goal (adapt_goal_t) solves its problem on a mesh, estimates its error by the
!> dual-weighted residual of module enrichment (the element one degree higher on the same
!> cells), and marks cells from its indicators; the loop refines the marked cells by
!> newest-vertex bisection (mesh_refine: conforming and nested, parts and the contact
!> segment carried to the children) and builds the next level's problem in memory. The
!> goals: the lowest positive mu (adaptive_eigen) and the critical lambdas
!> (adaptive_threshold).
module adaptive_loop
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_BAD_INPUT
    use system_memory, only: available_memory_bytes
    use strings, only: to_string, short_real_text, given_real_text
    use timer, only: wall_time, timings_t, PHASE_ASSEMBLY
    use run_config, only: config_t
    use mesh, only: mesh_t
    use mesh_refine, only: refinable_mesh_t, build_refinable_mesh
    use element_types, only: element_name
    use problem, only: problem_t, build_problem
    use enrichment, only: enriched_element
    use sorting, only: sort_index
    use error_bar, only: floor_reached, floor_outcome
    implicit none
    private
    public :: adapt_mesh, doerfler_marking, adaptive_dof_limit, level_dof_limit

    !> Peak bytes per free dof of one adaptive level (its factor, the enriched problem of
    !> the estimate one degree higher and its factor, the mesh tree): 4.7 kB measured for P3
    !> at 34 200 and 254 388 dofs (168 MB, 1.2 GB); with a margin for the next level's
    !> peak.
    real(wp), parameter :: BYTES_PER_DOF = 8192.0_wp

    !> What the loop adapts to.
    type, abstract, public :: adapt_goal_t
        !> the round-off part of error(), set by solve; negative: unknown (no floor test)
        real(wp) :: roundoff = -1.0_wp
    contains
        !> solve and estimate on `prob` (level `level`; `loop_start` the loop's wall_time)
        procedure(goal_solve), deferred :: solve
        !> the largest relative error bar of the goal (error_bar); negative when one is missing
        procedure(goal_error), deferred :: error
        !> the cells to refine
        procedure(goal_mark), deferred :: mark
        !> why the estimate is missing
        procedure(goal_missing), deferred :: missing
    end type adapt_goal_t

    abstract interface
        subroutine goal_solve(this, config, prob, level, loop_start, timings, stat)
            import :: adapt_goal_t, config_t, problem_t, timings_t, status_t, wp
            class(adapt_goal_t), intent(inout) :: this
            type(config_t), intent(in) :: config
            type(problem_t), intent(in) :: prob
            integer, intent(in) :: level
            real(wp), intent(in) :: loop_start
            type(timings_t), intent(inout) :: timings
            type(status_t), intent(out) :: stat
        end subroutine goal_solve

        real(wp) function goal_error(this)
            import :: adapt_goal_t, wp
            class(adapt_goal_t), intent(in) :: this
        end function goal_error

        function goal_mark(this, theta) result(marked)
            import :: adapt_goal_t, wp
            class(adapt_goal_t), intent(in) :: this
            real(wp), intent(in) :: theta
            integer, allocatable :: marked(:)
        end function goal_mark

        function goal_missing(this) result(reason)
            import :: adapt_goal_t
            class(adapt_goal_t), intent(in) :: this
            character(len=:), allocatable :: reason
        end function goal_missing
    end interface

contains

    !> Run the loop from the problem `start` (level 0) of `config`; `prob` is the problem of
    !> the last level solved, whose solution `goal` holds. A limit reached is no failure (stat
    !> ok, converged false, `outcome` says what was reached; `floor` true when that is the
    !> floating-point floor); bad input is: a starting mesh with more free dofs than
    !> max_dofs, or cells with no refinement or no enriched space.
    subroutine adapt_mesh(config, start, goal, prob, converged, floor, outcome, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: start
        class(adapt_goal_t), intent(inout) :: goal
        type(problem_t), intent(out) :: prob
        logical, intent(out) :: converged, floor
        character(len=:), allocatable, intent(out) :: outcome
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(refinable_mesh_t) :: tree
        type(mesh_t) :: refined
        type(problem_t) :: next
        integer :: level, element, max_dofs
        character(len=:), allocatable :: dof_limit
        integer, allocatable :: marked(:)
        real(wp) :: loop_start, level_start, error

        loop_start = wall_time()
        converged = .false.
        floor = .false.
        outcome = ''
        allocate (marked(0))   ! (gfortran 12 warns of an unallocated one at -O3)
        element = start%mesh%element
        if (enriched_element(element) == 0) then
            call stat%fail(STATUS_BAD_INPUT, config%input_file//': &adapt: tolerance = '// &
                given_real_text(config%adapt%tolerance)//': expected 0 for '// &
                element_name(element)//' cells (adaptation refines triangles p1, p2 or p3)')
            return
        end if
        call level_dof_limit(config, max_dofs, dof_limit)
        if (config%adapt%max_dofs > 0 .and. start%dofs%n_free > max_dofs) then
            call stat%fail(STATUS_BAD_INPUT, config%input_file//': &adapt: max_dofs = '// &
                to_string(config%adapt%max_dofs)//': expected at least the '// &
                to_string(start%dofs%n_free)//' free dofs of the starting mesh')
            return
        end if
        call build_refinable_mesh(start%mesh, tree, stat)
        if (.not. stat%ok()) then
            stat%message = config%input_file//': &adapt: '//stat%message
            return
        end if
        prob = start
        level = 0
        do
            call goal%solve(config, prob, level, loop_start, timings, stat)
            if (.not. stat%ok()) return
            error = goal%error()
            if (error < 0.0_wp) then
                outcome = 'tolerance not met: no error estimate at level '// &
                    to_string(level)//' ('//goal%missing()//')'
                exit
            end if
            ! never on the starting level alone: its bar has no earlier level to confirm
            ! it (a collision onset's estimate at h = 1/8 was 0.09 times its true error)
            if (error <= config%adapt%tolerance .and. level >= 1) then
                converged = .true.
                outcome = 'tolerance '//given_real_text(config%adapt%tolerance)// &
                    ' met at level '//to_string(level)//': error bar '// &
                    short_real_text(error)//', '//to_string(prob%dofs%n_free)//' dofs'
                exit
            end if
            if (floor_reached(error, goal%roundoff)) then
                floor = .true.
                outcome = floor_outcome(config%adapt%tolerance, goal%roundoff, error, &
                                        to_string(prob%dofs%n_free))
                exit
            end if
            if (config%adapt%max_levels > 0 .and. level >= config%adapt%max_levels) then
                outcome = 'tolerance '//given_real_text(config%adapt%tolerance)// &
                    ' not met: max_levels = '//to_string(config%adapt%max_levels)// &
                    ' reached with error bar '//short_real_text(error)//' at '// &
                    to_string(prob%dofs%n_free)//' dofs'
                exit
            end if
            level_start = wall_time()
            marked = goal%mark(config%adapt%theta)
            call tree%refine(marked, stat)
            if (stat%ok()) call tree%to_mesh(element, refined, stat)
            if (stat%ok()) call build_problem(config, next, stat, given_mesh=refined)
            if (.not. stat%ok()) return
            call timings%add(PHASE_ASSEMBLY, wall_time() - level_start, ': level '// &
                to_string(level + 1)//', '//to_string(size(marked))//' cells marked, '// &
                to_string(refined%n_cells())//' cells, '//to_string(next%dofs%n_free)//' dofs')
            if (next%dofs%n_free > max_dofs) then
                outcome = 'tolerance '//given_real_text(config%adapt%tolerance)// &
                    ' not met: the next level would have '//to_string(next%dofs%n_free)// &
                    ' dofs, more than '//dof_limit// &
                    '; reached error bar '//short_real_text(error)//' at '// &
                    to_string(prob%dofs%n_free)//' dofs'
                exit
            end if
            prob = next
            level = level + 1
        end do
    end subroutine adapt_mesh

    !> The most free dofs a level may have (&adapt max_dofs, or what the memory available
    !> now allows when it is 0) and the words that name that limit in an outcome.
    subroutine level_dof_limit(config, max_dofs, dof_limit)
        type(config_t), intent(in) :: config
        integer, intent(out) :: max_dofs
        character(len=:), allocatable, intent(out) :: dof_limit
        max_dofs = config%adapt%max_dofs
        dof_limit = 'max_dofs = '//to_string(max_dofs)
        if (max_dofs == 0) then
            max_dofs = adaptive_dof_limit(available_memory_bytes())
            dof_limit = 'the '//to_string(max_dofs)//' that the memory available allows'
        end if
    end subroutine level_dof_limit

    !> The most free dofs a level may have when `available` bytes of memory are free (a
    !> negative `available`: unknown, no limit), at BYTES_PER_DOF.
    pure integer function adaptive_dof_limit(available)
        integer(i8), intent(in) :: available
        real(wp) :: dofs
        adaptive_dof_limit = huge(0)
        if (available < 0) return
        dofs = real(available, wp)/BYTES_PER_DOF
        if (dofs < real(huge(0), wp)) adaptive_dof_limit = max(1, int(dofs))
    end function adaptive_dof_limit

    !> Doerfler's bulk marking: the cells of the largest indicators, fewest first, whose sum
    !> reaches theta times the sum of all (ties broken by cell order). Every cell with a
    !> positive indicator when theta = 1; none when all indicators vanish.
    pure function doerfler_marking(eta, theta) result(marked)
        real(wp), intent(in) :: eta(:)
        real(wp), intent(in) :: theta
        integer, allocatable :: marked(:)
        integer, allocatable :: order(:)
        real(wp) :: goal, held
        integer :: n, k

        allocate (order(size(eta)))   ! (gfortran 12 warns of an unallocated one at -O3)
        order = sort_index(-eta)      ! largest first, stable
        goal = theta*sum(eta)
        held = 0.0_wp
        n = 0
        do k = 1, size(order)
            if (.not. (held < goal) .or. .not. eta(order(k)) > 0.0_wp) exit
            held = held + eta(order(k))
            n = k
        end do
        marked = order(:n)
    end function doerfler_marking
end module adaptive_loop
