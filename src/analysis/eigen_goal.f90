! SPDX-License-Identifier: MIT
!> The goal of the adaptive loop (adapt_driver) for analysis 'eigen' and the points of an
!> adapted 'lambda_sweep': the lowest positive mu at each of its lambdas, one target each.
!> On h levels (h_refiner: Doerfler marking on the cell indicators of the estimate, which
!> refines where the eigenfunction is singular, the corners of Gamma_C, and leaves the
!> smooth interior coarse) each level solves the eigenproblem as the eigen analysis does
!> (dense or ARPACK as &eigen asks) and estimates the error of mu (error_estimate); h levels
!> serve one lambda (a sweep adapts each point by a loop of its own). On hp levels
!> (hp_levels) each level is factored once and solved at every lambda still active, the
!> lowest mu refined to its Rayleigh quotient where its round-off could decide the stop
!> (hp_rayleigh); its bar comes from the changes between levels, and once the loop ends
!> from one check on the last level's cells with every degree raised by one (eigen_goal_check).
module eigen_goal
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string, short_real_text, seconds_text, given_real_text
    use timer, only: wall_time, timings_t, PHASE_REDUCTION
    use scene, only: scene_t
    use method_options, only: eigen_options_t, adapt_options_t, ESTIMATE_ON, REFINE_HP, &
                              SOLVER_DENSE, OPERATOR_REDUCED
    use problem, only: problem_t
    use unit_scaling, only: units_t
    use hp_space, only: hp_space_t
    use sparse_cholesky, only: cholesky_t
    use csr_matrix, only: csr_matrix_t
    use contact_boundary, only: b_pattern, fill_b
    use contact_reduction, only: contact_flexibility, lift_share, lift_share_t
    use eigen_solve, only: eigen_result_t, solve_eigen, estimate_eigen, eigen_with_factor, &
                           choose_solver
    use accuracy, only: WARNING_LEN, MU_VANISHED
    use error_bar, only: theta_warnings, checked_bar
    use hp_rayleigh, only: refine_lowest_mu
    use adapt_driver, only: adapt_goal_t, refiner_t, adapt_level_t, adapt_levels, judge_target, &
                            check_target, absence_confirmed, NONE_LEVELS, TARGET_MET, &
                            TARGET_STOPPED, adapt_target_t, built_check_t
    use h_refiner, only: h_refiner_t, doerfler_marking
    use moving_side, only: contact_ends_t, contact_ends, past_crossing_end, unconfirmed_words
    use hp_levels, only: hp_refiner_t, HP_ESTIMATE, check_words
    implicit none
    private
    public :: adapt_eigen

    public :: HP_ESTIMATE   ! the hp refiner's, for the report

    !> One level of one lambda's loop: a row of adapt.csv.
    type, public :: eigen_level_t
        integer :: level = 0
        integer :: layers = 0        !! hp: the layers of grading (the level); h: 0
        integer :: p_min = 0         !! hp: the lowest cell degree; h: 0
        integer :: p_max = 0         !! hp: the highest cell degree; h: 0
        integer :: n_dofs = 0        !! free dofs (hp: of the condensed system)
        integer :: n_contact = 0     !! contact nodes (hp: contact functions)
        integer :: n_cells = 0
        logical :: has_mu = .false.           !! a positive mu exists
        !> lowest positive mu, in the units of the loop's problems (adapted_eigen_t%units:
        !> every level's, whose E and extent are the starting mesh's)
        real(wp) :: mu = 0.0_wp
        logical :: estimated = .false.        !! h: the level's estimate was computed
        real(wp) :: error_estimate = 0.0_wp   !! h: |relative error estimate| of mu
        real(wp) :: error_bar = -1.0_wp       !! the bar at this level (error_bar); < 0: none
        !> hp: |mu - mu of the previous level| / |mu|, what the bar is made of; < 0: none
        real(wp) :: change = -1.0_wp
        real(wp) :: roundoff = -1.0_wp        !! its round-off part (module roundoff); < 0: unknown
        !> hp: mu has stopped converging (error_bar: hp_run_bar): no bar, the loop stops
        logical :: stalled = .false.
        !> hp, the last level of a lambda: |mu - mu of the check one degree higher| / |mu|
        !> (eigen_goal_check), folded into error_bar; < 0: not checked (or no positive mu there)
        real(wp) :: check_change = -1.0_wp
        integer :: check_dofs = 0             !! the check's free dofs; 0: no check
        real(wp) :: time_s = 0.0_wp           !! wall time from the loop's start to the level's end
    end type eigen_level_t

    !> One lambda's loop.
    type, public :: adapted_eigen_t
        real(wp) :: lambda = 0.0_wp
        type(eigen_level_t), allocatable :: levels(:)
        !> the last level solved (kept on request): its problem (hp: graded P1 mesh, condensed
        !> K, hp contact, dofs%n_free only) and its hp space (cell degrees; h: none)
        type(problem_t) :: prob
        type(hp_space_t) :: space
        type(eigen_result_t) :: res        !! its spectrum, error estimate, bar and warnings
        !> of mu in `levels` and `res`: the levels' problems' (problem_t%units; hp: the input's)
        type(units_t) :: units
        logical :: converged = .false.     !! the bar met the tolerance
        logical :: floor_reached = .false. !! stopped by round-off, not by a limit
        !> the last level has no positive mu where an earlier one had (accuracy: MU_VANISHED)
        logical :: mu_vanished = .false.
        !> one line: the tolerance met, or why not and what was reached
        character(len=:), allocatable :: outcome
        !> a level after the first that failed (adapt_goal_t: failure): `res` and `levels`
        !> are the last complete level's; ok: none
        type(status_t) :: failure
    end type adapted_eigen_t

    integer, parameter :: COST_LEN = 160   !! a line of cost_lines

    !> What the point solves of one hp level (or check) cost: their count, seconds (of the
    !> timer: wall, or CPU in a build with NCEIG_CPU_TIMERS), the round-off bounds' part and
    !> the operator applications (ARPACK's products with A).
    type :: point_cost_t
        integer :: points = 0
        integer :: products = 0
        real(wp) :: begin = 0.0_wp
        real(wp) :: roundoff = 0.0_wp
    contains
        procedure :: start => point_cost_start
        procedure :: add => point_cost_add
        procedure :: words => point_cost_words
    end type point_cost_t

    !> The lowest positive mu at each of `points`' lambdas.
    type, extends(adapt_goal_t), public :: eigen_goal_t
        !> the run's, with the estimate on (h): the loop is driven by it, whatever the size
        type(eigen_options_t) :: options
        real(wp) :: tolerance = 0.0_wp
        logical :: keep_problem = .true.
        !> the caller keeps of each point its lowest positive mu, bar and outcome alone (an hp
        !> sweep: keep_problem false): ARPACK then runs on the level's p x p matrix from its
        !> shared contact blocks and lifts that one mu (its mode, backward error and
        !> round-off bound), not every eigenvalue found (eigen_with_factor: lowest_only)
        logical :: lowest_only = .false.
        logical :: hp = .false.   !! hp levels (else h)
        type(adapted_eigen_t), allocatable :: points(:)
        !> h: the ends of Gamma_C (of the first level; refinement keeps them) and Poisson's
        !> ratio, for the crossings a lambda without a positive mu may lie past (past_end)
        logical :: ends_known = .false.
        type(contact_ends_t) :: ends
        real(wp) :: poisson = 0.0_wp
        !> hp: what each level's (and check's) point solves cost, one line each since the
        !> caller last took them (joint_goal: its progress lines; the points' own are silenced)
        character(len=COST_LEN), allocatable :: cost_lines(:)
    contains
        procedure :: solve => eigen_goal_solve
        procedure :: judge => eigen_goal_judge
        procedure :: bar_text => eigen_goal_bar_text
        procedure :: mark => eigen_goal_mark
        procedure :: check => eigen_goal_check
        procedure :: setup => eigen_goal_setup
        procedure :: finish => eigen_goal_finish
        procedure :: solve_factored => eigen_goal_solve_factored
    end type eigen_goal_t

contains

    !> The loop of the lowest positive mu at each of `lambdas` from the problem `start` of the
    !> scene `scn`, solved as `options` and refined as `adapt` asks (h: one lambda; hp: one
    !> climb of the levels for all). outs(i) is lambdas(i)'s loop; its problem and space are
    !> the last level's with `keep_problem`. A limit reached is no failure (stat ok,
    !> outs(i)%converged false, its outcome heading its warnings). A failure (stat) still
    !> gives outs: outs(i)%outcome is '' where lambdas(i)'s loop had not ended, and its
    !> result is complete where it had.
    subroutine adapt_eigen(scn, lambdas, options, adapt, start, outs, timings, stat, &
                           keep_problem)
        type(scene_t), intent(in) :: scn
        real(wp), intent(in) :: lambdas(:)
        type(eigen_options_t), intent(in) :: options
        type(adapt_options_t), intent(in) :: adapt
        type(problem_t), intent(in) :: start
        type(adapted_eigen_t), allocatable, intent(out) :: outs(:)
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        logical, intent(in) :: keep_problem
        class(refiner_t), allocatable :: refiner
        type(eigen_goal_t) :: goal

        if (adapt%refine == REFINE_HP) then
            allocate (hp_refiner_t :: refiner)
        else
            allocate (h_refiner_t :: refiner)
        end if
        call goal%setup(lambdas, options, adapt, keep_problem)
        call adapt_levels(scn, adapt, start, refiner, goal, timings, stat)
        call goal%finish(refiner, adapt, stat, outs)
    end subroutine adapt_eigen

    !> The goal of the lowest positive mu at each of `lambdas`, every target active, for the
    !> loop `adapt` asks (h levels: the estimate on, whatever the size).
    subroutine eigen_goal_setup(this, lambdas, options, adapt, keep_problem)
        class(eigen_goal_t), intent(inout) :: this
        real(wp), intent(in) :: lambdas(:)
        type(eigen_options_t), intent(in) :: options
        type(adapt_options_t), intent(in) :: adapt
        logical, intent(in) :: keep_problem
        integer :: i
        this%options = options
        if (.not. adapt%refine == REFINE_HP) this%options%estimate = ESTIMATE_ON
        this%tolerance = adapt%tolerance
        this%keep_problem = keep_problem
        this%lowest_only = .not. keep_problem
        this%hp = adapt%refine == REFINE_HP
        if (allocated(this%targets)) deallocate (this%targets)
        if (allocated(this%points)) deallocate (this%points)
        allocate (this%targets(size(lambdas)), this%points(size(lambdas)))
        do i = 1, size(lambdas)
            this%targets(i)%outcome = ''
            this%points(i)%lambda = lambdas(i)
            allocate (this%points(i)%levels(0))
        end do
    end subroutine eigen_goal_setup

    !> Each lambda's loop once the loop (`stat` its status) has ended: outs(i), moved out of
    !> the goal. A failed loop still gives the points whose targets had ended (an outcome,
    !> not ''): a sweep writes those as a partial set.
    subroutine eigen_goal_finish(this, refiner, adapt, stat, outs)
        class(eigen_goal_t), intent(inout) :: this
        class(refiner_t), intent(in) :: refiner
        type(adapt_options_t), intent(in) :: adapt
        type(status_t), intent(in) :: stat
        type(adapted_eigen_t), allocatable, intent(out) :: outs(:)
        integer :: i
        call move_alloc(this%points, outs)
        do i = 1, size(outs)
            associate (o => outs(i), t => this%targets(i))
                o%outcome = t%outcome
                o%failure = this%failure
                if (.not. stat%ok() .and. t%active()) cycle
                o%converged = t%converged()
                o%floor_reached = t%floor_reached()
                o%mu_vanished = o%res%spec%lowest_positive() == 0 .and. any(o%levels%has_mu)
                if (.not. o%converged) o%res%warnings = [character(len=WARNING_LEN) :: &
                                                         o%outcome, o%res%warnings]
                if (refiner%estimated()) o%res%warnings = [character(len=WARNING_LEN) :: &
                    o%res%warnings, theta_warnings(adapt%theta)]
            end associate
        end do
    end subroutine eigen_goal_finish

    !> Each active lambda on `level`: h, its own solve and estimate; hp, one factor for all.
    subroutine eigen_goal_solve(this, scn, refiner, level, loop_start, timings, refused, stat)
        class(eigen_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable, intent(out) :: refused
        type(status_t), intent(out) :: stat
        refused = ''
        call solve_level(this, scn, refiner, level, loop_start, timings, stat)
    end subroutine eigen_goal_solve

    !> Each active lambda on the hp `level` with the factor `chol` of its K (contact dofs
    !> last) that another goal of the same loop made, and its Kt_nn, Kt_nt: a level is then
    !> factored once for both (joint_goal).
    subroutine eigen_goal_solve_factored(this, scn, refiner, level, chol, kt_nn, kt_nt, &
                                         loop_start, timings, stat)
        class(eigen_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: level
        type(cholesky_t), intent(in) :: chol
        real(wp), intent(in) :: kt_nn(:, :), kt_nt(:, :)
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        call solve_level(this, scn, refiner, level, loop_start, timings, stat, chol, kt_nn, &
                         kt_nt)
    end subroutine eigen_goal_solve_factored

    !> eigen_goal_solve; on hp levels with the factor and blocks `given` (else its own).
    subroutine solve_level(this, scn, refiner, level, loop_start, timings, stat, given, &
                           kt_nn_given, kt_nt_given)
        class(eigen_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(cholesky_t), intent(in), target, optional :: given
        real(wp), intent(in), optional :: kt_nn_given(:, :), kt_nt_given(:, :)
        type(cholesky_t), target :: own
        type(cholesky_t), pointer :: chol
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :)
        type(csr_matrix_t) :: b_level   !! B's sparsity on the hp level, for every lambda
        type(lift_share_t) :: share     !! the lifts' data on the level's factor
        type(point_cost_t) :: cost
        integer :: i

        chol => own
        if (.not. refiner%estimated()) then
            if (present(given)) then
                chol => given
                if (wants_blocks(this, level%prob%contact%p())) then
                    kt_nn = kt_nn_given
                    kt_nt = kt_nt_given
                end if
                if (this%any_active() .and. wants_share(this, level%prob%contact%p())) &
                    call lift_share(level%prob%k, given, level%prob%contact, share, stat)
                if (.not. stat%ok()) return
            else
                call refiner%factor(level, own, timings, stat)
                if (.not. stat%ok()) return
                if (this%any_active()) call level_blocks(this, level%prob, own, kt_nn, kt_nt, &
                                                         share, timings, stat)
                if (.not. stat%ok()) then
                    call own%free()
                    return
                end if
            end if
        end if
        if (.not. refiner%estimated()) call b_pattern(level%prob%contact, &
                                                      level%prob%dofs%n_free, b_level)
        call cost%start()
        if (refiner%estimated() .and. .not. this%ends_known) then
            this%ends = contact_ends(level%prob)
            this%poisson = level%prob%poisson
            this%ends_known = .true.
        end if
        do i = 1, size(this%points)
            if (.not. this%targets(i)%active()) cycle
            if (refiner%estimated()) then
                call solve_h_level(this%points(i), stat)
            else
                call solve_hp_level(this%points(i), stat)
            end if
            if (.not. stat%ok()) exit
        end do
        if (cost%points > 0) call add_cost_line(this, 'the points of hp level '// &
            to_string(level%number)//', '//cost%words(level%prob%contact%p()))
        if (.not. refiner%estimated() .and. .not. present(given)) call own%free()

    contains

        !> An h level at p%lambda: the eigen solve with its own factor, the estimate (which
        !> drives the loop and marks the cells), the row and the bar over the levels so far.
        subroutine solve_h_level(p, stat)
            type(adapted_eigen_t), intent(inout) :: p
            type(status_t), intent(out) :: stat
            type(eigen_level_t) :: row
            type(eigen_result_t) :: res
            ! into `res`: a level that fails leaves p%res the last complete level's
            call solve_eigen(scn, level%prob, p%lambda, this%options, res, timings, stat)
            if (.not. stat%ok()) return
            p%res = res
            ! an adaptive run judges resolution by the change of mu between its levels
            call estimate_eigen(scn, level%prob, this%options, .false., p%res, timings)
            call fill_row(row, p%res)
            row%estimated = p%res%error%computed
            if (row%estimated) row%error_estimate = abs(p%res%error%relative)
            row%time_s = wall_time() - loop_start
            p%levels = [p%levels, row]
            call set_bar(p%levels, refiner)
            if (p%levels(size(p%levels))%estimated) &
                p%res%error%bar = p%levels(size(p%levels))%error_bar
            if (this%keep_problem) p%prob = level%prob
            p%units = level%prob%units
            call timings%note(h_level_line(p%levels(size(p%levels)), level%prob%units))
        end subroutine solve_h_level

        !> An hp level, factored in `chol`, at p%lambda: the eigen solve, the row and its bar
        !> from the changes between levels; the result becomes p%res.
        subroutine solve_hp_level(p, stat)
            type(adapted_eigen_t), intent(inout) :: p
            type(status_t), intent(out) :: stat
            type(eigen_result_t) :: res
            type(eigen_level_t) :: row
            integer :: k
            res%lambda = p%lambda
            res%b = b_level
            call fill_b(level%prob%contact, res%lambda, res%b, stat)
            if (.not. stat%ok()) return
            res%solver = choose_solver(this%options, level%prob%contact%p())
            call solve_point(scn, level%prob, this%options, chol, kt_nn, kt_nt, share, &
                             this%lowest_only, res, timings, stat)
            if (.not. stat%ok()) return
            k = res%spec%lowest_positive()
            if (k > 0) then
                call refine_level_mu(level, this%tolerance, res, k, stat)
                if (.not. stat%ok()) return
            end if
            call cost%add(res)
            call fill_row(row, res)
            row%layers = level%number
            row%p_min = minval(level%degree)
            row%p_max = maxval(level%degree)
            p%levels = [p%levels, row]
            call set_bar(p%levels, refiner)
            row = p%levels(size(p%levels))
            if (row%error_bar >= 0.0_wp) then
                res%error%computed = .true.
                res%error%bar = row%error_bar
                res%error%relative = row%change
                res%error%method = HP_ESTIMATE
            else if (row%stalled) then
                res%error%skipped = 'none: mu does not converge under hp refinement'
            end if
            p%levels(size(p%levels))%time_s = wall_time() - loop_start
            if (this%keep_problem) then
                p%prob = level%prob
                p%space = level%space
            end if
            p%res = res
            p%units = level%prob%units
            call timings%note(hp_level_line(p%levels(size(p%levels)), level%prob%units))
        end subroutine solve_hp_level

        !> The row's sizes and mu from the level and `res`.
        subroutine fill_row(row, res)
            type(eigen_level_t), intent(out) :: row
            type(eigen_result_t), intent(in) :: res
            integer :: lowest
            row%level = level%number
            row%n_dofs = level%prob%dofs%n_free
            row%n_contact = level%prob%contact%p()
            row%n_cells = level%prob%mesh%n_cells()
            lowest = res%spec%lowest_positive()
            row%has_mu = lowest > 0
            if (row%has_mu) row%mu = real(res%spec%mu(lowest), wp)
            row%roundoff = res%roundoff
        end subroutine fill_row
    end subroutine solve_level

    !> `line` appended to this%cost_lines.
    subroutine add_cost_line(this, line)
        class(eigen_goal_t), intent(inout) :: this
        character(len=*), intent(in) :: line
        if (.not. allocated(this%cost_lines)) allocate (this%cost_lines(0))
        this%cost_lines = [character(len=COST_LEN) :: this%cost_lines, line]
    end subroutine add_cost_line

    subroutine point_cost_start(this)
        class(point_cost_t), intent(out) :: this
        this%begin = wall_time()
    end subroutine point_cost_start

    subroutine point_cost_add(this, res)
        class(point_cost_t), intent(inout) :: this
        type(eigen_result_t), intent(in) :: res
        this%points = this%points + 1
        this%products = this%products + res%spec%n_operator
        this%roundoff = this%roundoff + res%spec%roundoff_seconds
    end subroutine point_cost_add

    !> 'N lambdas at p = P: S s (round-off bounds R s), K products with A'
    function point_cost_words(this, p) result(words)
        class(point_cost_t), intent(in) :: this
        integer, intent(in) :: p
        character(len=:), allocatable :: words
        words = to_string(this%points)//' lambdas at p = '//to_string(p)//': '// &
            seconds_text(wall_time() - this%begin)//' s (round-off bounds '// &
            seconds_text(this%roundoff)//' s), '//to_string(this%products)//' products with A'
    end function point_cost_words

    !> res%spec%mu(i), the lowest positive mu on the hp level `level`, and res%roundoff
    !> replaced by the Rayleigh quotient of its vectors that never stores K (hp_rayleigh) when
    !> the double value's round-off bound is at least REFINE_FRACTION of `tolerance`: below,
    !> it cannot decide the stop, and the quotient costs about half of a level's assembly.
    subroutine refine_level_mu(level, tolerance, res, i, stat)
        type(adapt_level_t), intent(in) :: level
        real(wp), intent(in) :: tolerance
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
        associate (prob => level%prob)
            call refine_lowest_mu(prob%mesh, level%space, prob%young, prob%poisson, &
                prob%contact, res%b, res%lambda, mu, &
                real(res%spec%vectors(:, i), wp), res%spec%left, res%roundoff, gap, &
                refined, refined_bound, stat)
            if (.not. stat%ok()) return
            res%spec%mu(i) = refined
        end associate
        res%roundoff = refined_bound
        res%quotient = .true.
        res%spec%roundoff_seconds = res%spec%roundoff_seconds + wall_time() - start
        res%spec%roundoff(i) = refined_bound
    end subroutine refine_level_mu

    !> The check of the last level `last` (adapt_driver): for every lambda whose last row has
    !> a bar, the lowest positive mu on the same cells with every degree raised by one
    !> (refiner%check_level; one factor for all lambdas, the mu refined as a level's is),
    !> folded into that row's bar and the result's (error_bar: checked_bar), and the target
    !> judged again (check_target: one met at `last` climbs on with `reopen`).
    subroutine eigen_goal_check(this, scn, start, refiner, last, tolerance, reopen, timings, &
                                stat, built)
        class(eigen_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: start
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: last
        real(wp), intent(in) :: tolerance
        logical, intent(in) :: reopen
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        !> where built%built, the check level (with its factor and contact blocks) to solve on
        type(built_check_t), intent(inout), target, optional :: built
        type(adapt_level_t), target :: own_check
        type(adapt_level_t), pointer :: check
        type(cholesky_t), target :: own_chol
        type(cholesky_t), pointer :: chol
        type(eigen_result_t) :: res
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :)
        type(csr_matrix_t) :: b_check   !! B's sparsity on the check's level
        type(lift_share_t) :: share     !! the lifts' data on the check's factor
        type(point_cost_t) :: cost
        real(wp) :: series, bar, begin
        character(len=:), allocatable :: why
        integer :: i, k
        logical :: made, none, given_built

        begin = wall_time()
        made = .false.
        given_built = .false.
        if (present(built)) given_built = built%built
        check => own_check
        chol => own_chol
        if (given_built) then
            check => built%level
            chol => built%chol
        end if
        do i = 1, size(this%points)
            if (size(this%points(i)%levels) == 0) cycle
            associate (p => this%points(i), &
                       row => this%points(i)%levels(size(this%points(i)%levels)))
                ! a lambda met as 'none' is checked too: its levels' changes bound nothing
                none = this%targets(i)%met_absent()
                if (row%error_bar < 0.0_wp .and. .not. none) cycle
                if (.not. made) then
                    select type (refiner)
                    class is (hp_refiner_t)
                        if (.not. given_built) &
                            call refiner%check_level(start, last, check, timings, stat)
                    class default
                        return   ! h levels carry their own estimate: no check
                    end select
                    made = .true.
                    if (given_built) then
                        if (wants_blocks(this, check%prob%contact%p())) then
                            kt_nn = built%kt_nn
                            kt_nt = built%kt_nt
                        end if
                        if (wants_share(this, check%prob%contact%p())) share = built%share
                    else
                        if (stat%ok()) call refiner%factor(check, chol, timings, stat)
                        if (.not. stat%ok()) return
                        call level_blocks(this, check%prob, chol, kt_nn, kt_nt, share, &
                                          timings, stat)
                        if (.not. stat%ok()) exit
                    end if
                    call b_pattern(check%prob%contact, check%prob%dofs%n_free, b_check)
                    call cost%start()
                end if
                res%lambda = p%lambda
                res%b = b_check
                call fill_b(check%prob%contact, res%lambda, res%b, stat)
                if (.not. stat%ok()) exit
                res%solver = choose_solver(this%options, check%prob%contact%p())
                call solve_point(scn, check%prob, this%options, chol, kt_nn, kt_nt, share, &
                                 this%lowest_only, res, timings, stat)
                if (.not. stat%ok()) exit
                k = res%spec%lowest_positive()
                if (none) then
                    call check_none(this%targets(i), p%lambda, no_mu_levels(p, this%hp), &
                                    res, k, check%prob%dofs%n_free, last%number, timings)
                    cycle
                end if
                if (k > 0) call refine_level_mu(check, tolerance, res, k, stat)
                if (.not. stat%ok()) exit
                call cost%add(res)
                row%check_dofs = check%prob%dofs%n_free
                series = row%error_bar
                if (k > 0) then
                    row%check_change = abs(row%mu - real(res%spec%mu(k), wp))/abs(row%mu)
                    bar = checked_bar(series, row%mu, .true., real(res%spec%mu(k), wp), &
                                      row%roundoff, res%roundoff)
                    why = check_words(row%check_dofs)//' moves mu by '// &
                        short_real_text(row%check_change)//' (relative): error bar '// &
                        short_real_text(bar)//' at '//to_string(row%n_dofs)//' dofs'
                    p%res%error%check = row%check_change
                else
                    bar = -1.0_wp
                    why = check_words(row%check_dofs)//' has no positive mu, so mu has '// &
                        'no error bar'
                    p%res%error%computed = .false.
                    p%res%error%skipped = 'none: the check one degree higher has no positive mu'
                end if
                call timings%note('hp check of level '//to_string(last%number)// &
                    ' at lambda = '//short_real_text(p%lambda)//': '//why)
                if (len(refiner%cap_words(last)) > 0) why = why//'; '//refiner%cap_words(last)
                row%error_bar = bar
                if (bar >= 0.0_wp) p%res%error%bar = bar
                ! the checked bar's round-off part is both values' (the floor test)
                call check_target(this%targets(i), tolerance, series, bar, &
                                  max(row%roundoff, 0.0_wp) + max(res%roundoff, 0.0_wp), &
                                  reopen .and. row%level == last%number, why)
            end associate
        end do
        if (.not. made) return
        call add_cost_line(this, 'the points'' check of hp level '//to_string(last%number)// &
                           ', '//cost%words(check%prob%contact%p()))
        if (.not. given_built) call chol%free()
        if (.not. stat%ok()) return
        call timings%note('hp check of level '//to_string(last%number)//': '// &
                          seconds_text(wall_time() - begin)//' s')
    end subroutine eigen_goal_check

    !> hp: lambda `lambda`, met as 'none' (no positive mu at its last NONE_LEVELS levels), is
    !> confirmed only where the check of the last level `level` (`res`, its spectrum on `dofs`
    !> free dofs with every degree raised by one; `k` its lowest positive mu, 0: none) has no
    !> positive mu either. A mu the check finds appears with the degree: target `t` stops as
    !> not converged (exit 8), its outcome naming that mu.
    subroutine check_none(t, lambda, levels, res, k, dofs, level, timings)
        type(adapt_target_t), intent(inout) :: t
        real(wp), intent(in) :: lambda
        character(len=*), intent(in) :: levels   !! the levels without a mu (no_mu_levels)
        type(eigen_result_t), intent(in) :: res
        integer, intent(in) :: k, dofs, level
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable :: head, words
        head = check_words(dofs, level)
        if (k == 0) then
            call timings%note(head//' at lambda = '//short_real_text(lambda)// &
                              ' has no positive mu either')
            return
        end if
        words = 'tolerance not met: '//levels//', but '// &
            head//' finds mu = '//short_real_text(real(res%spec%mu(k), wp), 6)// &
            ': it appears with the degree, not converged'
        call timings%note(words)
        call t%finish(TARGET_STOPPED, words)
    end subroutine check_none

    !> The eigen solve of `res` (res%lambda, res%b and res%solver set) on `prob` factored in
    !> `chol`, with the level's blocks and the lifts' shared data where it has them.
    subroutine solve_point(scn, prob, options, chol, kt_nn, kt_nt, share, lowest_only, res, &
                           timings, stat)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(eigen_options_t), intent(in) :: options
        type(cholesky_t), intent(in) :: chol
        real(wp), allocatable, intent(in) :: kt_nn(:, :), kt_nt(:, :)
        type(lift_share_t), intent(in) :: share
        logical, intent(in) :: lowest_only
        type(eigen_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (allocated(kt_nn) .and. allocated(share%l_tail)) then
            call eigen_with_factor(scn, prob, options, chol, res, timings, stat, kt_nn, kt_nt, &
                                   lowest_only=lowest_only, share=share)
        else if (allocated(kt_nn)) then
            call eigen_with_factor(scn, prob, options, chol, res, timings, stat, kt_nn, kt_nt, &
                                   lowest_only=lowest_only)
        else if (allocated(share%l_tail)) then
            call eigen_with_factor(scn, prob, options, chol, res, timings, stat, &
                                   lowest_only=lowest_only, share=share)
        else
            call eigen_with_factor(scn, prob, options, chol, res, timings, stat, &
                                   lowest_only=lowest_only)
        end if
    end subroutine solve_point

    !> Kt_nn and Kt_nt of an hp level factored in `chol` (contact dofs last), where the goal
    !> solves with them (wants_blocks): they do not depend on lambda, so a level forms them
    !> once for all its lambdas instead of once per lambda (the dense solver's largest cost
    !> after dgeevx). Left unallocated otherwise: ARPACK applies them through the factor.
    !> `share`, the lifts' data on `chol` (wants_share), is made from the same trailing block.
    subroutine level_blocks(goal, prob, chol, kt_nn, kt_nt, share, timings, stat)
        class(eigen_goal_t), intent(in) :: goal
        type(problem_t), intent(in) :: prob
        type(cholesky_t), intent(in) :: chol
        real(wp), allocatable, intent(out) :: kt_nn(:, :), kt_nt(:, :)
        type(lift_share_t), intent(out) :: share
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp) :: start
        if (.not. wants_blocks(goal, prob%contact%p())) then
            if (wants_share(goal, prob%contact%p())) &
                call lift_share(prob%k, chol, prob%contact, share, stat)
            return
        end if
        start = wall_time()
        call contact_flexibility(chol, prob%contact, kt_nn, kt_nt, stat, prob%k, share)
        if (stat%ok()) call timings%add(PHASE_REDUCTION, wall_time() - start, &
            ': contact blocks of K^-1, '//to_string(prob%contact%p())//' x '// &
            to_string(prob%contact%p())//', once for the level''s lambdas')
    end subroutine level_blocks

    !> Whether the goal's solves on a level of p contact functions lift their eigenvectors
    !> through the factor's trailing block (the dense solver and the reduced operator; the
    !> full operator's vectors need no lift and it keeps nothing of order p^2): the block and
    !> ||K|| are then made once for the level's lambdas (lift_share_t), not once per lambda.
    logical function wants_share(goal, p)
        class(eigen_goal_t), intent(in) :: goal
        integer, intent(in) :: p
        wants_share = choose_solver(goal%options, p) == SOLVER_DENSE .or. &
                      goal%options%operator == OPERATOR_REDUCED
    end function wants_share

    !> Whether the goal's solves on a level of p contact functions use its contact blocks:
    !> the dense solver's, and with lowest_only ARPACK's without shift on the reduced
    !> operator (one O(p^2) product per step on the p x p matrix formed from them, where the
    !> factor's trailing block costs two triangular solves of order 2p; 41 lambdas repay the
    !> blocks' O(p^3) once per level many times over: docs/studies.md "Cost").
    logical function wants_blocks(goal, p)
        class(eigen_goal_t), intent(in) :: goal
        integer, intent(in) :: p
        wants_blocks = choose_solver(goal%options, p) == SOLVER_DENSE
        if (goal%lowest_only) wants_blocks = wants_blocks .or. &
            (goal%options%operator == OPERATOR_REDUCED .and. &
             .not. abs(goal%options%target) > 0.0_wp)
    end function wants_blocks

    !> The bar (and change, and stall) of the last of `levels` over the levels so far, as the
    !> refiner makes bars: h from the estimates (only where the last level has one), hp from
    !> the values since the last level without a mu. Plain arrays, filled level by level: a
    !> component of an array of derived type passed as an array makes a temporary (a
    !> runtime warning under -fcheck=all).
    pure subroutine set_bar(levels, refiner)
        type(eigen_level_t), intent(inout) :: levels(:)
        class(refiner_t), intent(in) :: refiner
        logical :: have(size(levels))
        real(wp) :: estimates(size(levels)), mu(size(levels))
        integer :: dofs(size(levels)), i, k
        k = size(levels)
        if (refiner%estimated() .and. .not. levels(k)%estimated) return
        do i = 1, k
            have(i) = levels(i)%has_mu
            estimates(i) = -1.0_wp
            if (levels(i)%estimated .and. levels(i)%has_mu) estimates(i) = levels(i)%error_estimate
            mu(i) = levels(i)%mu
            dofs(i) = levels(i)%n_dofs
        end do
        associate (last => levels(k))
            call refiner%series_bar(have, mu, estimates, dofs, last%roundoff, last%error_bar, &
                                    last%change, last%stalled)
        end associate
    end subroutine set_bar

    !> Each active lambda after `level`. One without a positive mu at every level so far has
    !> missed no value yet: it stays active (h: every cell refined, eigen_goal_mark) until
    !> its absence is confirmed as a threshold side's 'none' is (absence_confirmed), which
    !> meets it as 'none, confirmed', or a limit stops it short (not met). Else judge_target
    !> on its last row: a mu that appears after levels without one is judged as usual (h:
    !> met from the level after it), one that vanishes stops it (not converged), and an h
    !> level with a mu but no bar stops it (the estimate is missing: why).
    subroutine eigen_goal_judge(this, refiner, level, tolerance)
        class(eigen_goal_t), intent(inout) :: this
        class(refiner_t), intent(in) :: refiner
        integer, intent(in) :: level
        real(wp), intent(in) :: tolerance
        character(len=:), allocatable :: no_value, why
        real(wp) :: bar, roundoff, crossing(2)
        integer :: i, n, j
        logical :: confirmed, past(2)

        if (allocated(this%grade)) deallocate (this%grade)
        allocate (this%grade(2, 0))
        do i = 1, size(this%points)
            if (.not. this%targets(i)%active()) cycle
            n = size(this%points(i)%levels)
            associate (p => this%points(i), last => this%points(i)%levels(n))
                if (.not. any(p%levels%has_mu)) then
                    ! h: uniform levels cannot see a mode that concentrates at an end past
                    ! its crossing, below their scale: the next level is graded toward it
                    call past_end(this, p%lambda, past, crossing)
                    this%grade = this%ends%point(:, pack([1, 2], past))
                    if (.not. absence_confirmed([(p%levels(j)%has_mu, j=1, n)], &
                                                [(p%levels(j)%n_dofs, j=1, n)], &
                                                refiner%estimated())) cycle
                    why = unconfirmed_text(this, p%lambda)
                    if (len(why) == 0) then
                        call this%targets(i)%finish(TARGET_MET, 'none, confirmed: '// &
                                                    no_mu_levels(p, this%hp), absent=.true.)
                    else
                        call this%targets(i)%finish(TARGET_STOPPED, 'tolerance '// &
                            given_real_text(tolerance)//' not met: '// &
                            no_mu_levels(p, this%hp)//', '//why)
                    end if
                    cycle
                end if
                confirmed = .false.
                if (n >= 2) confirmed = p%levels(n - 1)%has_mu
                no_value = 'tolerance not met: no positive mu at level '//to_string(level)
                if (any(p%levels%has_mu)) no_value = no_value//': '//MU_VANISHED
                if (refiner%estimated()) then
                    ! the bar quoted; its round-off part where the level is estimated
                    bar = -1.0_wp
                    if (p%res%error%computed) bar = p%res%error%bar
                    roundoff = -1.0_wp
                    if (last%estimated) roundoff = p%res%roundoff
                else
                    bar = last%error_bar
                    roundoff = last%roundoff
                end if
                call judge_target(this%targets(i), refiner, level, tolerance, last%n_dofs, &
                                  last%has_mu, no_value, bar, roundoff, last%stalled, 'mu', &
                                  missing(p), confirmed)
            end associate
        end do
    end subroutine eigen_goal_judge

    !> h: per end of Gamma_C, whether `lambda` lies past its crossing (none on hp levels,
    !> graded toward every corner) and that crossing (moving_side: past_crossing_end).
    subroutine past_end(this, lambda, past, crossing)
        class(eigen_goal_t), intent(in) :: this
        real(wp), intent(in) :: lambda
        logical, intent(out) :: past(2)
        real(wp), intent(out) :: crossing(2)
        past = .false.
        crossing = 0.0_wp
        if (this%hp .or. .not. this%ends_known) return
        call past_crossing_end(this%ends, this%poisson, lambda, past, crossing)
    end subroutine past_end

    !> h: why levels without a positive mu at `lambda` cannot confirm its absence, from the
    !> first end of Gamma_C past whose crossing it lies ('' where none: uniform levels can).
    function unconfirmed_text(this, lambda) result(text)
        class(eigen_goal_t), intent(in) :: this
        real(wp), intent(in) :: lambda
        character(len=:), allocatable :: text
        real(wp) :: crossing(2)
        logical :: past(2)
        integer :: end
        text = ''
        call past_end(this, lambda, past, crossing)
        end = findloc(past, .true., 1)
        if (end == 0) return
        text = unconfirmed_words(this%ends, end, 'lambda = '//short_real_text(lambda)// &
                                 ' is past that end''s crossing '// &
                                 short_real_text(crossing(end)), .true.)
    end function unconfirmed_text

    !> Why the estimate of a lambda's last level is missing: no positive mu (none at all, or
    !> none left of the earlier levels': MU_VANISHED), its size (skipped), or its failure.
    function missing(p) result(reason)
        type(adapted_eigen_t), intent(in) :: p
        character(len=:), allocatable :: reason
        reason = 'the estimate failed'
        if (p%res%spec%lowest_positive() == 0) then
            reason = 'no positive mu to adapt to'
            if (any(p%levels%has_mu)) reason = reason//': '//MU_VANISHED
        else if (allocated(p%res%error%skipped)) then
            reason = p%res%error%skipped
        else if (allocated(p%res%error%failure)) then
            reason = 'the estimate failed: '//p%res%error%failure
        end if
    end function missing

    !> The words of the levels of `p`, none with a positive mu: 'no positive mu at h levels
    !> 0 to 2 (81 to 331 dofs)'.
    function no_mu_levels(p, hp) result(words)
        type(adapted_eigen_t), intent(in) :: p
        logical, intent(in) :: hp
        character(len=:), allocatable :: words
        associate (first => p%levels(1), last => p%levels(size(p%levels)))
            words = 'no positive mu at '//trim(merge('hp levels', 'h levels ', hp))//' '// &
                to_string(first%level)//' to '//to_string(last%level)//' ('// &
                to_string(first%n_dofs)//' to '//to_string(last%n_dofs)//' dofs)'
        end associate
    end function no_mu_levels

    !> Lambda i's bar at its last level, as a limit's outcome quotes it: 'B at N dofs', 'none
    !> at N dofs'; where no level has a positive mu, that its absence is not confirmed.
    function eigen_goal_bar_text(this, i) result(text)
        class(eigen_goal_t), intent(in) :: this
        integer, intent(in) :: i
        character(len=:), allocatable :: text, why
        text = 'none'
        if (size(this%points(i)%levels) == 0) return
        associate (p => this%points(i), &
                   last => this%points(i)%levels(size(this%points(i)%levels)))
            if (last%error_bar >= 0.0_wp) text = short_real_text(last%error_bar)
            text = text//' at '//to_string(last%n_dofs)//' dofs'
            if (.not. any(p%levels%has_mu)) then
                ! past an end's crossing no number of levels confirms it (eigen_goal_judge)
                why = unconfirmed_text(this, p%lambda)
                if (len(why) > 0) then
                    text = text//'; '//no_mu_levels(p, this%hp)//', '//why
                    return
                end if
                text = text//'; '//no_mu_levels(p, this%hp)//', its absence not confirmed '// &
                    '(that needs '//to_string(NONE_LEVELS)//' levels without it'
                if (.not. this%hp) text = text//', over which the dofs double'
                text = text//')'
            end if
        end associate
    end function eigen_goal_bar_text

    !> Doerfler's set of the (one) lambda's indicators; every cell where its last level has
    !> no positive mu (no indicators: refined uniformly until its absence is confirmed, as
    !> the threshold goal refines where no side has them).
    function eigen_goal_mark(this, theta) result(marked)
        class(eigen_goal_t), intent(in) :: this
        real(wp), intent(in) :: theta
        integer, allocatable :: marked(:)
        integer :: i
        associate (p => this%points(1))
            if (p%levels(size(p%levels))%has_mu) then
                marked = doerfler_marking(p%res%error%indicators, theta)
            else
                marked = [(i, i=1, p%levels(size(p%levels))%n_cells)]
            end if
        end associate
    end function eigen_goal_mark

    !> The progress line of an h level (mu in the input's units: `units` are the level's).
    function h_level_line(row, units) result(line)
        type(eigen_level_t), intent(in) :: row
        type(units_t), intent(in) :: units
        character(len=:), allocatable :: line
        line = 'adapt level '//to_string(row%level)//': '//to_string(row%n_dofs)//' dofs'
        if (row%has_mu) line = line//', mu = '//short_real_text(units%mu_to_input(row%mu), 12)
        if (row%estimated) line = line//', estimate '//short_real_text(row%error_estimate)// &
            ', bar '//short_real_text(row%error_bar)
    end function h_level_line

    !> The progress line of an hp level (mu in the input's units: `units` are the level's).
    function hp_level_line(r, units) result(line)
        type(eigen_level_t), intent(in) :: r
        type(units_t), intent(in) :: units
        character(len=:), allocatable :: line
        line = 'hp level '//to_string(r%level)//': '//to_string(r%n_dofs)//' dofs, '// &
            'degrees '//to_string(r%p_min)//' to '//to_string(r%p_max)
        if (r%has_mu) line = line//', mu = '//short_real_text(units%mu_to_input(r%mu), 12)
        if (r%error_bar >= 0.0_wp) line = line//', bar '//short_real_text(r%error_bar)
    end function hp_level_line
end module eigen_goal
