! SPDX-License-Identifier: MIT
!> &adapt strategy = 'hp' for analysis 'eigen': instead of refining where an estimate
!> marks, the loop climbs the levels of hp_levels (level k: the input mesh graded in k
!> layers toward the singular points, degrees 1 + layer). The lowest
!> positive mu of each level is solved as the eigen analysis does (dense or ARPACK by
!> &eigen, with its round-off bound); the bar comes from the changes between levels
!> (error_bar: hp_level_bar). The loop stops when the bar meets &adapt tolerance, when the
!> round-off part is at least the rest of the bar (the floating-point floor: more levels
!> cannot lower it), or at max_levels / max_dofs / the memory available.
!> This module computes; hp_adapt_run writes.
module hp_adaptive
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: to_string, short_real_text, given_real_text
    use timer, only: wall_time, timings_t
    use run_config, only: config_t
    use problem, only: problem_t
    use hp_space, only: hp_space_t
    use hp_levels, only: hp_ladder_t
    use sparse_cholesky, only: cholesky_t
    use contact_boundary, only: assemble_b
    use eigen_analysis, only: eigen_result_t, eigen_with_factor, choose_solver
    use accuracy, only: WARNING_LEN, MU_VANISHED
    use error_bar, only: hp_run_bar, floor_reached, floor_outcome, stall_outcome
    use hp_rayleigh, only: refine_lowest_mu
    implicit none
    private
    public :: hp_adapt_eigen, hp_adapt_lambdas

    character(len=*), parameter, public :: HP_ESTIMATE = 'change to the previous hp level'

    !> One level: a row of adapt.csv.
    type, public :: hp_level_t
        integer :: level = 0
        integer :: layers = 0
        integer :: p_min = 0
        integer :: p_max = 0
        integer :: n_dofs = 0        !! free dofs of the condensed system
        integer :: n_contact = 0     !! contact functions
        integer :: n_cells = 0
        logical :: has_mu = .false.
        real(wp) :: mu = 0.0_wp      !! lowest positive mu, input units
        real(wp) :: error_bar = -1.0_wp   !! relative; < 0: none (the first level)
        !> |mu - mu of the previous level| / |mu|, what the bar is made of; < 0: none
        real(wp) :: change = -1.0_wp
        real(wp) :: roundoff = -1.0_wp    !! its round-off part; < 0: unknown
        !> mu has stopped converging (error_bar: hp_run_bar): no bar, the loop stops
        logical :: stalled = .false.
        real(wp) :: time_s = 0.0_wp       !! wall time from the loop's start to this level's end
    end type hp_level_t

    type, public :: hp_result_t
        type(hp_level_t), allocatable :: levels(:)
        !> the last level: graded P1 mesh, condensed K, hp contact (nodes: basis functions),
        !> dofs%n_free only
        type(problem_t) :: prob
        type(hp_space_t) :: space          !! its space (cell degrees)
        type(eigen_result_t) :: res        !! its spectrum, bar, round-off and warnings
        logical :: converged = .false.
        logical :: floor_reached = .false. !! stopped by round-off, not by a limit
        !> the last level has no positive mu where an earlier one had (accuracy: MU_VANISHED)
        logical :: mu_vanished = .false.
        character(len=:), allocatable :: outcome
    end type hp_result_t

contains

    !> Run the loop from the problem `start` (its mesh and parts; its K is not used) at
    !> &analysis lambda. A limit reached is no failure (stat ok, out%converged false,
    !> out%outcome and a warning of out%res say so).
    subroutine hp_adapt_eigen(config, start, out, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: start
        type(hp_result_t), intent(out) :: out
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(hp_result_t), allocatable :: outs(:)
        call hp_adapt_lambdas(config, start, [config%analysis%lambda], outs, timings, stat, &
                              keep_problem=.true.)
        if (stat%ok()) out = outs(1)
    end subroutine hp_adapt_eigen

    !> The loop of hp_adapt_eigen at each of `lambdas` on one climb of the ladder: the levels
    !> do not depend on lambda, so each is built and factored once and solved at every
    !> lambda whose loop has not stopped there. outs(i) is what hp_adapt_eigen gives at
    !> lambdas(i); its prob and space (the last level's) only with `keep_problem` (one
    !> problem per lambda), else its levels say what was solved.
    subroutine hp_adapt_lambdas(config, start, lambdas, outs, timings, stat, keep_problem)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: start
        real(wp), intent(in) :: lambdas(:)
        type(hp_result_t), allocatable, intent(out) :: outs(:)
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        logical, intent(in) :: keep_problem
        type(hp_ladder_t) :: ladder
        type(problem_t) :: prob
        type(cholesky_t) :: chol
        type(config_t) :: point_config
        real(wp) :: loop_start, tolerance
        logical :: active(size(lambdas)), too_big
        integer :: layers, i, solved

        loop_start = wall_time()
        tolerance = config%adapt%tolerance
        allocate (outs(size(lambdas)))
        do i = 1, size(lambdas)
            allocate (outs(i)%levels(0))
            outs(i)%outcome = ''
        end do
        active = .true.
        solved = 0
        point_config = config
        call ladder%begin(config, start, stat)
        if (.not. stat%ok()) return
        do
            call ladder%climb(config, start, solved, too_big, stat)
            if (.not. stat%ok()) return
            layers = ladder%layers
            if (too_big) then
                do i = 1, size(lambdas)
                    if (active(i)) outs(i)%outcome = ladder%limit_outcome(tolerance, &
                                                                         bar_text(outs(i)))
                end do
                exit
            end if
            call ladder%problem(config, start, prob, timings, stat)
            if (stat%ok()) call ladder%factor(config, prob, chol, timings, stat)
            if (.not. stat%ok()) return
            solved = solved + 1
            do i = 1, size(lambdas)
                if (.not. active(i)) cycle
                point_config%analysis%lambda = lambdas(i)
                call solve_level(outs(i), stat)
                if (.not. stat%ok()) exit
                call timings%note(level_line(outs(i)%levels(size(outs(i)%levels))))
                active(i) = .not. stops_here(outs(i))
            end do
            call chol%free()
            if (.not. stat%ok()) return
            if (.not. any(active)) exit
            if (config%adapt%max_levels > 0 .and. layers >= config%adapt%max_levels) then
                do i = 1, size(lambdas)
                    if (active(i)) outs(i)%outcome = 'tolerance '// &
                        given_real_text(tolerance)//' not met: max_levels = '// &
                        to_string(config%adapt%max_levels)//' reached with error bar '// &
                        bar_text(outs(i))
                end do
                exit
            end if
        end do
        do i = 1, size(lambdas)
            if (.not. outs(i)%converged) outs(i)%res%warnings = [character(len=WARNING_LEN) :: &
                outs(i)%outcome, outs(i)%res%warnings]
        end do

    contains

        !> The current level (`prob`, factored in `chol`) at point_config's lambda: the eigen
        !> solve, its row and its bar; the result becomes out%res (and the problem out%prob).
        subroutine solve_level(out, stat)
            type(hp_result_t), intent(inout) :: out
            type(status_t), intent(out) :: stat
            type(eigen_result_t) :: res
            type(hp_level_t) :: row
            integer :: k
            res%lambda = point_config%analysis%lambda
            call assemble_b(prob%contact, prob%dofs%n_free, res%lambda, res%b, stat)
            if (.not. stat%ok()) return
            res%solver = choose_solver(config%eigen%solver, prob%contact%p(), &
                                       config%eigen%dense_max_contact, config%eigen%operator)
            call eigen_with_factor(point_config, prob, chol, res, timings, stat)
            if (.not. stat%ok()) return

            row%level = layers
            row%layers = layers
            row%p_min = minval(ladder%degree)
            row%p_max = maxval(ladder%degree)
            row%n_dofs = prob%dofs%n_free
            row%n_contact = prob%contact%p()
            row%n_cells = prob%mesh%n_cells()
            k = res%spec%lowest_positive()
            row%has_mu = k > 0
            row%mu = 0.0_wp
            if (row%has_mu) then
                call refine_level_mu(res, k, stat)
                if (.not. stat%ok()) return
                row%mu = real(res%spec%mu(k), wp)
            end if
            row%roundoff = res%roundoff
            out%levels = [out%levels, row]
            call set_bar(out%levels)
            row = out%levels(size(out%levels))
            if (row%error_bar >= 0.0_wp) then
                res%error%computed = .true.
                res%error%bar = row%error_bar
                res%error%relative = row%change
                res%error%method = HP_ESTIMATE
            else if (row%stalled) then
                res%error%skipped = 'none: mu does not converge under hp refinement'
            end if
            out%levels(size(out%levels))%time_s = wall_time() - loop_start
            if (keep_problem) then
                out%prob = prob
                out%space = ladder%space
            end if
            out%res = res
        end subroutine solve_level

        !> res%spec%mu(i), the lowest positive mu, and res%roundoff replaced by the Rayleigh
        !> quotient of its vectors that never stores K (hp_rayleigh) when the double value's
        !> round-off bound is at least REFINE_FRACTION of the tolerance: below, it cannot
        !> decide the stop, and the quotient costs about half of a level's assembly.
        subroutine refine_level_mu(res, i, stat)
            type(eigen_result_t), intent(inout) :: res
            integer, intent(in) :: i
            type(status_t), intent(out) :: stat
            real(wp), parameter :: REFINE_FRACTION = 0.01_wp
            real(wp) :: mu, refined, refined_bound, gap, start
            integer :: j
            if (.not. (res%roundoff >= REFINE_FRACTION*tolerance .and. &
                       allocated(res%spec%left))) return
            start = wall_time()
            mu = real(res%spec%mu(i), wp)
            gap = 1.0_wp
            do j = 1, res%spec%n()
                if (j /= i) gap = min(gap, abs(res%spec%mu(j) - mu)/abs(mu))
            end do
            call refine_lowest_mu(prob%mesh, ladder%space, prob%young, prob%poisson, &
                prob%contact, res%b, res%lambda, prob%units%mu_to_scaled(mu), &
                real(res%spec%vectors(:, i), wp), res%spec%left, res%roundoff, gap, refined, &
                refined_bound, stat)
            if (.not. stat%ok()) return
            res%spec%mu(i) = prob%units%mu_to_input(refined)
            res%roundoff = refined_bound
            res%quotient = .true.
            res%spec%roundoff_seconds = res%spec%roundoff_seconds + wall_time() - start
            res%spec%roundoff(i) = refined_bound
        end subroutine refine_level_mu

        !> Whether the loop of `out` stops after its last level: no positive mu, the bar
        !> within the tolerance, mu stalled, or the floor reached (its outcome says which).
        logical function stops_here(out)
            type(hp_result_t), intent(inout) :: out
            stops_here = .true.
            associate (last => out%levels(size(out%levels)))
                if (.not. last%has_mu) then
                    out%outcome = 'tolerance not met: no positive mu at level '// &
                                  to_string(last%level)
                    out%mu_vanished = any(out%levels%has_mu)
                    if (out%mu_vanished) out%outcome = out%outcome//': '//MU_VANISHED
                    return
                end if
                if (last%stalled) then
                    out%outcome = stall_outcome(tolerance, 'mu')
                    return
                end if
                if (last%error_bar >= 0.0_wp .and. last%error_bar <= tolerance) then
                    out%converged = .true.
                    out%outcome = 'tolerance '//given_real_text(tolerance)//' met at level '// &
                        to_string(last%level)//': error bar '//bar_text(out)
                    return
                end if
                if (floor_reached(last%error_bar, last%roundoff)) then
                    out%floor_reached = .true.
                    out%outcome = floor_outcome(tolerance, last%roundoff, last%error_bar, &
                                                to_string(last%n_dofs))
                    return
                end if
            end associate
            stops_here = .false.
        end function stops_here

        !> The bar and the change of the last level from the mu of the levels since the last
        !> one without a positive mu (hp_run_bar; plain arrays: see adaptive_eigen's
        !> set_level_bar).
        subroutine set_bar(levels)
            type(hp_level_t), intent(inout) :: levels(:)
            logical :: have(size(levels))
            real(wp) :: mu(size(levels))
            integer :: j
            do j = 1, size(levels)
                have(j) = levels(j)%has_mu
                mu(j) = levels(j)%mu
            end do
            associate (last => levels(size(levels)))
                call hp_run_bar(have, mu, last%roundoff, last%error_bar, last%change, &
                                last%stalled)
            end associate
        end subroutine set_bar

        function bar_text(out) result(text)
            type(hp_result_t), intent(in) :: out
            character(len=:), allocatable :: text
            text = 'none'
            if (size(out%levels) == 0) return
            associate (last => out%levels(size(out%levels)))
                if (last%error_bar >= 0.0_wp) text = short_real_text(last%error_bar)
                text = text//' at '//to_string(last%n_dofs)//' dofs'
            end associate
        end function bar_text

        function level_line(r) result(line)
            type(hp_level_t), intent(in) :: r
            character(len=:), allocatable :: line
            line = 'hp level '//to_string(r%level)//': '//to_string(r%n_dofs)//' dofs, '// &
                'degrees '//to_string(r%p_min)//' to '//to_string(r%p_max)
            if (r%has_mu) line = line//', mu = '//short_real_text(r%mu, 12)
            if (r%error_bar >= 0.0_wp) line = line//', bar '//short_real_text(r%error_bar)
        end function level_line
    end subroutine hp_adapt_lambdas
end module hp_adaptive
