! SPDX-License-Identifier: MIT
!> One hp climb for a lambda sweep and its thresholds (&sweep adapt_thresholds): the goal of
!> the adaptive loop (adapt_driver) that holds the goal of the lowest positive mu at every
!> lambda of the sweep (eigen_goal) and the goal of lambda+, lambda- and their onsets
!> (threshold_goal), its targets theirs end to end: the points first, then the two sides.
!> The levels, their factor and their contact blocks Kt_nn, Kt_nt do not depend on lambda:
!> each level is built once, factored once (by the threshold goal, which keeps the last
!> factor for its report) and its blocks formed once, and the points' solves borrow them.
!> Each part is judged, checked and ends as it does alone; a part whose targets have all
!> ended is no longer solved, while the loop climbs on for the other. hp levels only (h
!> levels refine each point's mesh on its own: input_validation refuses the combination).
module joint_goal
    use kinds, only: wp
    use status, only: status_t, STATUS_SOLVER
    use timer, only: wall_time, timings_t
    use scene, only: scene_t
    use method_options, only: eigen_options_t, adapt_options_t, REFINE_HP
    use problem, only: problem_t
    use adapt_driver, only: adapt_goal_t, refiner_t, adapt_level_t, adapt_levels, built_check_t
    use hp_levels, only: hp_refiner_t
    use eigen_goal, only: eigen_goal_t, adapted_eigen_t
    use threshold_goal, only: threshold_goal_t, adaptive_thresholds_t, threshold_goal_setup, &
                              threshold_goal_finish
    use threshold_analysis, only: threshold_result_t, start_sweep_curve, record_hp_sweep, &
                                  end_adapted_sweep
    implicit none
    private
    public :: solve_joint_sweep

    !> The points' goal and the thresholds' goal in one loop.
    type, extends(adapt_goal_t), public :: joint_goal_t
        type(eigen_goal_t) :: points
        type(threshold_goal_t) :: sides
        !> the points' phases: one line per lambda and level would flood the progress lines
        type(timings_t) :: quiet
        !> what a part's own check needs when its targets end before the loop does (judge):
        !> the scene, the loop's starting problem, the level just solved (number, mesh,
        !> degrees) and the loop's limits; early(k): part k (1 points, 2 sides) was checked
        !> so and has not climbed since, so the loop's last check leaves it alone
        type(scene_t) :: scn
        type(problem_t), pointer :: start => null()
        type(adapt_level_t) :: level
        type(adapt_options_t) :: adapt
        logical :: early(2) = .false.
    contains
        procedure :: solve => joint_goal_solve
        procedure :: judge => joint_goal_judge
        procedure :: bar_text => joint_goal_bar_text
        procedure :: mark => joint_goal_mark
        procedure :: check => joint_goal_check
        procedure :: join => joint_goal_join
    end type joint_goal_t

contains

    !> The adapted 'lambda_sweep' with its thresholds in the same hp climb from the problem
    !> `start` of the scene `scn`: the thresholds, their levels and the report of the last
    !> level at `lambda` as the adaptive threshold analysis gives them (`out`, `res`), and
    !> res%sweep the curve at `lambdas` as the adapted sweep gives it. A limit reached is no
    !> failure (stat ok; out%converged and res%sweep%n_not_met say what was met); a failed
    !> loop is (no partial set: the thresholds' report needs the loop's last level).
    subroutine solve_joint_sweep(scn, lambda, lambdas, options, adapt, scan, start, out, res, &
                                 timings, stat)
        type(scene_t), intent(in) :: scn
        real(wp), intent(in) :: lambda, lambdas(:)
        type(eigen_options_t), intent(in) :: options
        type(adapt_options_t), intent(in) :: adapt
        real(wp), intent(in) :: scan(:)
        type(problem_t), intent(in), target :: start
        type(adaptive_thresholds_t), intent(out) :: out
        type(threshold_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        class(refiner_t), allocatable :: refiner
        type(joint_goal_t) :: goal
        type(adapted_eigen_t), allocatable :: outs(:)
        type(status_t) :: loop
        real(wp) :: begin

        if (adapt%refine /= REFINE_HP) then
            call stat%fail(STATUS_SOLVER, 'solve_joint_sweep: hp levels only')
            return
        end if
        begin = wall_time()
        allocate (hp_refiner_t :: refiner)
        call threshold_goal_setup(goal%sides, options, adapt, scan)
        call goal%points%setup(lambdas, options, adapt, .false.)
        ! allocated, then filled: an array constructor of targets (allocatable outcomes)
        ! leaks under gfortran 12 (docs/testing.md)
        allocate (goal%targets(size(lambdas) + 2))
        call goal%join(.false.)
        goal%start => start
        goal%adapt = adapt
        call adapt_levels(scn, adapt, start, refiner, goal, timings, loop)
        call goal%join(.true.)   ! the targets a failed level stopped
        goal%sides%failure = goal%failure
        call goal%points%finish(refiner, adapt, loop, outs)
        stat = loop
        call threshold_goal_finish(scn, goal%sides, refiner, lambda, options, adapt, scan, out, &
                                   res, timings, stat)
        if (.not. stat%ok()) return
        call start_sweep_curve(lambdas, start, res%sweep)
        call record_hp_sweep(outs, res%sweep, timings, stat)
        if (.not. stat%ok()) return
        call end_adapted_sweep(adapt, begin, res, timings)
    end subroutine solve_joint_sweep

    !> The parts' targets from the loop's (`down`), or the loop's from the parts'.
    subroutine joint_goal_join(this, down)
        class(joint_goal_t), intent(inout) :: this
        logical, intent(in) :: down
        integer :: n
        n = size(this%points%targets)
        if (down) then
            this%points%targets(:) = this%targets(1:n)
            this%sides%targets(:) = this%targets(n + 1:n + 2)
        else
            this%targets(1:n) = this%points%targets
            this%targets(n + 1:n + 2) = this%sides%targets
        end if
    end subroutine joint_goal_join

    !> `level` for each part with a target still active: the thresholds' part factors it and
    !> forms its contact blocks, which the points' solves then borrow; the points' part alone
    !> factors it itself. A level the thresholds' part refuses (its blocks' memory) is
    !> refused.
    subroutine joint_goal_solve(this, scn, refiner, level, loop_start, timings, refused, stat)
        class(joint_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable, intent(out) :: refused
        type(status_t), intent(out) :: stat
        refused = ''
        this%scn = scn
        this%level%number = level%number
        this%level%prob%mesh = level%prob%mesh
        if (allocated(level%degree)) this%level%degree = level%degree
        call this%join(.true.)
        if (this%sides%any_active()) then
            call this%sides%solve(scn, refiner, level, loop_start, timings, refused, stat)
            if (stat%ok() .and. len(refused) == 0 .and. this%points%any_active()) &
                call this%points%solve_factored(scn, refiner, level, this%sides%chol, &
                    this%sides%blocks%kt_nn, this%sides%blocks%kt_nt, loop_start, this%quiet, &
                    stat)
        else if (this%points%any_active()) then
            call this%points%solve(scn, refiner, level, loop_start, this%quiet, refused, stat)
        end if
        call note_points(timings, this%points%cost_lines)
        call this%join(.false.)
    end subroutine joint_goal_solve

    !> The progress lines of the points' solves since the last call, one per level or check
    !> (eigen_goal_t%cost_lines: their own lines are silenced), taken out of `lines`.
    subroutine note_points(timings, lines)
        type(timings_t), intent(inout) :: timings
        character(len=*), allocatable, intent(inout) :: lines(:)
        integer :: i
        if (.not. allocated(lines)) return
        do i = 1, size(lines)
            call timings%note(trim(lines(i)))
        end do
        deallocate (lines)
    end subroutine note_points

    !> Each part judges its active targets as it does alone. A part whose targets all end
    !> here while the other climbs on is checked at once, as its own loop would be when it
    !> ends (adapt_driver: the check of the last level, which may reopen a target that the
    !> check takes above the tolerance): a check at a later level could not reopen it.
    subroutine joint_goal_judge(this, refiner, level, tolerance)
        class(joint_goal_t), intent(inout) :: this
        class(refiner_t), intent(in) :: refiner
        integer, intent(in) :: level
        real(wp), intent(in) :: tolerance
        type(status_t) :: stat
        logical :: was(2), reopen
        call this%join(.true.)
        was = [this%points%any_active(), this%sides%any_active()]
        if (was(1)) call this%points%judge(refiner, level, tolerance)
        if (was(2)) call this%sides%judge(refiner, level, tolerance)
        if (was(1)) this%early(1) = .false.
        if (was(2)) this%early(2) = .false.
        reopen = len(refiner%cap_words(this%level)) == 0 .and. .not. &
            (this%adapt%max_levels > 0 .and. level >= this%adapt%max_levels)
        if (was(1) .and. .not. this%points%any_active() .and. this%sides%any_active()) then
            call this%points%check(this%scn, this%start, refiner, this%level, tolerance, &
                                   reopen, this%quiet, stat)
            this%early(1) = stat%ok() .and. .not. this%points%any_active()
        else if (was(2) .and. .not. this%sides%any_active() .and. &
                 this%points%any_active()) then
            call this%sides%check(this%scn, this%start, refiner, this%level, tolerance, &
                                  reopen, this%quiet, stat)
            this%early(2) = stat%ok() .and. .not. this%sides%any_active()
        end if
        call this%join(.false.)
    end subroutine joint_goal_judge

    !> Each part's check of the last level, but a part checked when its targets ended
    !> (judge) and not reopened: the loop then ends as each part's own loop would have. The
    !> check level, its factor and contact blocks that the thresholds' check makes serve the
    !> points' check too (same cells, same degrees: the same matrices).
    subroutine joint_goal_check(this, scn, start, refiner, last, tolerance, reopen, timings, &
                                stat, built)
        class(joint_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: start
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: last
        real(wp), intent(in) :: tolerance
        logical, intent(in) :: reopen
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(built_check_t), intent(inout), target, optional :: built
        type(built_check_t), target :: own
        type(built_check_t), pointer :: both   !! the check level of both parts, made once
        both => own
        if (present(built)) both => built
        call this%join(.true.)
        if (.not. this%early(2)) call this%sides%check(scn, start, refiner, last, tolerance, &
                                                       reopen, timings, stat, both)
        if (stat%ok() .and. .not. this%early(1)) call this%points%check(scn, start, refiner, &
            last, tolerance, reopen, this%quiet, stat, both)
        call note_points(timings, this%points%cost_lines)
        call this%join(.false.)
    end subroutine joint_goal_check

    function joint_goal_bar_text(this, i) result(text)
        class(joint_goal_t), intent(in) :: this
        integer, intent(in) :: i
        character(len=:), allocatable :: text
        integer :: n
        n = size(this%points%targets)
        if (i <= n) then
            text = this%points%bar_text(i)
        else
            text = this%sides%bar_text(i - n)
        end if
    end function joint_goal_bar_text

    !> h levels only, which this goal does not climb: the thresholds' marking.
    function joint_goal_mark(this, theta) result(marked)
        class(joint_goal_t), intent(in) :: this
        real(wp), intent(in) :: theta
        integer, allocatable :: marked(:)
        marked = this%sides%mark(theta)
    end function joint_goal_mark
end module joint_goal
