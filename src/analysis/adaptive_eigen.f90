! SPDX-License-Identifier: MIT
!> The adaptive loop of analysis 'eigen' with &adapt tolerance > 0: solve, estimate, mark,
!> refine, until the error estimate of the lowest positive mu is at most the tolerance or a
!> limit is reached.
!>
!> Solve: the eigen solve of the analysis (dense or ARPACK as &eigen asks) on the current
!> mesh. Estimate: the dual-weighted residual of error_estimate, whose enriched space is one
!> degree higher on the same cells; its cell indicators drive the marking. Mark: Doerfler's
!> bulk criterion, the fewest cells whose indicators hold the fraction theta of their sum,
!> which refines where the eigenfunction is singular (the corners of Gamma_C) and leaves the
!> smooth interior coarse. Refine: newest-vertex bisection (mesh_refine), conforming and
!> nested, parts and the contact segment carried to the children. Each level assembles and
!> factors once for the solve and once for the enriched problem of the estimate; nothing is
!> read from disk between levels.
module adaptive_eigen
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: to_string, short_real_text
    use timer, only: wall_time, timings_t, PHASE_ASSEMBLY
    use run_config, only: config_t
    use mesh, only: mesh_t
    use mesh_refine, only: refinable_mesh_t, build_refinable_mesh
    use element_types, only: element_name
    use problem, only: problem_t, build_problem
    use eigen_analysis, only: eigen_result_t, solve_eigen
    use error_estimate, only: enriched_element
    use accuracy, only: WARNING_LEN
    use sorting, only: sort_index
    implicit none
    private
    public :: adapt_eigen, doerfler_marking

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
        real(wp) :: time_s = 0.0_wp           !! wall time from the loop's start to this level's end
    end type adapt_level_t

    type, public :: adaptive_result_t
        type(adapt_level_t), allocatable :: levels(:)
        type(problem_t) :: prob            !! the problem of the last level solved
        type(eigen_result_t) :: res        !! its spectrum and error estimate
        logical :: converged = .false.     !! the estimate met the tolerance
        !> one line: the tolerance met, or why not and what was reached
        character(len=:), allocatable :: outcome
    end type adaptive_result_t

contains

    !> Run the loop from the problem `start` (level 0) of `config`; `out` holds every level
    !> and the last one solved. A limit reached is no failure (stat ok, out%converged false,
    !> out%outcome and a warning of out%res say so); bad input is: a starting mesh with more
    !> free dofs than max_dofs, or cells with no refinement or no enriched space.
    subroutine adapt_eigen(config, start, out, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: start
        type(adaptive_result_t), intent(out) :: out
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(config_t) :: level_config
        type(refinable_mesh_t) :: tree
        type(mesh_t) :: refined
        type(problem_t) :: next
        integer :: level, element
        integer, allocatable :: marked(:)
        real(wp) :: loop_start, level_start

        loop_start = wall_time()
        allocate (marked(0))   ! (gfortran 12 warns of an unallocated one at -O3)
        element = start%mesh%element
        if (enriched_element(element) == 0) then
            call stat%fail(STATUS_BAD_INPUT, config%input_file//': &adapt: tolerance = '// &
                short_real_text(config%adapt%tolerance)//': expected 0 for '// &
                element_name(element)//' cells (adaptation refines triangles p1, p2 or p3)')
            return
        end if
        if (start%dofs%n_free > config%adapt%max_dofs) then
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
        ! the loop is driven by the estimate: it is computed at every level, whatever its size
        level_config = config
        level_config%eigen%estimate = 'on'
        out%prob = start
        allocate (out%levels(0))
        level = 0
        do
            call solve_eigen(level_config, out%prob, config%analysis%lambda, out%res, timings, &
                             stat, with_error_estimate=.true.)
            if (.not. stat%ok()) return
            out%levels = [out%levels, level_row(level)]
            call timings%note(level_line(out%levels(size(out%levels))))
            if (.not. out%res%error%computed) then
                out%outcome = 'tolerance not met: no error estimate at level '// &
                    to_string(level)//' ('//no_estimate_reason()//')'
                exit
            end if
            if (abs(out%res%error%relative) <= config%adapt%tolerance) then
                out%converged = .true.
                out%outcome = 'tolerance '//short_real_text(config%adapt%tolerance)// &
                    ' met at level '//to_string(level)//': estimate '// &
                    short_real_text(abs(out%res%error%relative))//', '// &
                    to_string(out%prob%dofs%n_free)//' dofs'
                exit
            end if
            if (level >= config%adapt%max_levels) then
                out%outcome = 'tolerance '//short_real_text(config%adapt%tolerance)// &
                    ' not met: max_levels = '//to_string(config%adapt%max_levels)// &
                    ' reached with estimate '//short_real_text(abs(out%res%error%relative))// &
                    ' at '//to_string(out%prob%dofs%n_free)//' dofs'
                exit
            end if
            level_start = wall_time()
            marked = doerfler_marking(out%res%error%indicators, config%adapt%theta)
            call tree%refine(marked, stat)
            if (stat%ok()) call tree%to_mesh(element, refined, stat)
            if (stat%ok()) call build_problem(config, next, stat, given_mesh=refined)
            if (.not. stat%ok()) return
            call timings%add(PHASE_ASSEMBLY, wall_time() - level_start, ': level '// &
                to_string(level + 1)//', '//to_string(size(marked))//' cells marked, '// &
                to_string(refined%n_cells())//' cells, '//to_string(next%dofs%n_free)//' dofs')
            if (next%dofs%n_free > config%adapt%max_dofs) then
                out%outcome = 'tolerance '//short_real_text(config%adapt%tolerance)// &
                    ' not met: the next level would have '//to_string(next%dofs%n_free)// &
                    ' dofs, more than max_dofs = '//to_string(config%adapt%max_dofs)// &
                    '; reached estimate '//short_real_text(abs(out%res%error%relative))// &
                    ' at '//to_string(out%prob%dofs%n_free)//' dofs'
                exit
            end if
            out%prob = next
            level = level + 1
        end do
        if (.not. out%converged) out%res%warnings = [character(len=WARNING_LEN) :: &
                                                     out%outcome, out%res%warnings]

    contains

        type(adapt_level_t) function level_row(level) result(row)
            integer, intent(in) :: level
            integer :: lowest
            row%level = level
            row%n_dofs = out%prob%dofs%n_free
            row%n_contact = out%prob%contact%p()
            row%n_cells = out%prob%mesh%n_cells()
            lowest = out%res%spec%lowest_positive()
            row%has_mu = lowest > 0
            if (row%has_mu) row%mu = real(out%res%spec%mu(lowest), wp)
            row%estimated = out%res%error%computed
            if (row%estimated) row%error_estimate = abs(out%res%error%relative)
            row%time_s = wall_time() - loop_start
        end function level_row

        function level_line(row) result(line)
            type(adapt_level_t), intent(in) :: row
            character(len=:), allocatable :: line
            line = 'adapt level '//to_string(row%level)//': '//to_string(row%n_dofs)//' dofs'
            if (row%has_mu) line = line//', mu = '//short_real_text(row%mu, 12)
            if (row%estimated) line = line//', estimate '//short_real_text(row%error_estimate)
        end function level_line

        !> Why the estimate is missing: no positive mu, its size (est%skipped), or the
        !> warning its failure left (eigen_analysis: 'no error estimate for ...: why').
        function no_estimate_reason() result(reason)
            character(len=:), allocatable :: reason
            character(len=*), parameter :: FAILED = 'no error estimate for the lowest positive mu: '
            integer :: i
            reason = 'the estimate failed'
            if (out%res%spec%lowest_positive() == 0) then
                reason = 'no positive mu to adapt to'
            else if (allocated(out%res%error%skipped)) then
                reason = out%res%error%skipped
            else if (allocated(out%res%warnings)) then
                do i = 1, size(out%res%warnings)
                    if (index(out%res%warnings(i), FAILED) == 1) &
                        reason = 'the estimate failed: '//trim(out%res%warnings(i)(len(FAILED) + 1:))
                end do
            end if
        end function no_estimate_reason
    end subroutine adapt_eigen

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
end module adaptive_eigen
