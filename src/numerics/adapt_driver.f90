! SPDX-License-Identifier: MIT
!> The adaptive loop of &adapt tolerance > 0, once for every goal and every refinement: a
!> refiner (refiner_t: h_refiner, Doerfler marking and bisection at a fixed degree; hp_levels,
!> graded meshes with rising degrees) makes the levels, and a goal (adapt_goal_t: the lowest
!> positive mu at one or more lambdas, the critical lambdas) solves each level for its
!> targets still active and judges them. The loop stops when no target is active, or at a
!> limit: max_levels, max_dofs (or the memory available), a level the goal cannot take.
!>
!> A target (adapt_target_t) is one value the goal adapts to, with its own state and the
!> one line that says how it ended (its outcome). The goal keeps each target's values and
!> bars level by level; the refiner says how a series of levels makes a bar (series_bar:
!> from the enriched estimates of h levels, from the changes between hp levels) and whether
!> a level carries an estimate of its own (estimated). judge_target is the rule of one
!> target with one bar: met (from level 1 on, where an earlier level confirms the bar),
!> at the floating-point floor, or stopped with its reason.
!>
!> Where the refiner's bars rest on the changes between its levels (hp), the last level is
!> checked once the loop ends (the goal's check: one solve with every degree raised by one,
!> folded into each target's bar by error_bar's checked_bar; check_target): a target that
!> the check takes above its tolerance climbs again where more levels can lower its error,
!> and otherwise stops, the refiner saying why more levels would not help (&adapt p_max).
!> h levels are offered the same check; the threshold goal uses it for a side met past the
!> crossing of an end of Gamma_C (one solve on the last mesh graded toward that end).
!>
!> A value a level does not have (no positive mu, no real pencil value on a side) is not
!> taken as absent on one level: the loop refines on until absence_confirmed holds (a
!> threshold side's 'none', an eigen lambda's 'no positive mu'), or a limit stops it short.
!>
!> With the default limits (max_levels = 0, max_dofs = 0) only the memory the machine has
!> ends a loop that has not met its tolerance, never a level count.
module adapt_driver
    use kinds, only: wp
    use status, only: status_t, STATUS_NOT_MET, STATUS_SOLVER
    use strings, only: to_string, short_real_text, given_real_text
    use timer, only: wall_time, timings_t
    use scene, only: scene_t
    use method_options, only: adapt_options_t
    use problem, only: problem_t
    use hp_space, only: hp_space_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: lift_share_t
    use error_bar, only: floor_reached, floor_outcome, stall_outcome
    implicit none
    private
    public :: adapt_levels, judge_target, check_target, no_estimate_outcome
    public :: test_failing_level, injected_failure, absent_since, absence_confirmed

    !> A value absent from this many levels in a row (h: over which the dofs at least
    !> doubled) is confirmed absent (absence_confirmed)
    integer, parameter, public :: NONE_LEVELS = 3

    integer, parameter, public :: TARGET_ACTIVE = 0    !! the loop still refines for it
    integer, parameter, public :: TARGET_MET = 1       !! its bar met the tolerance
    integer, parameter, public :: TARGET_FLOOR = 2     !! its bar stopped at round-off
    integer, parameter, public :: TARGET_STOPPED = 3   !! stopped short: its outcome says why

    !> One value a goal adapts to: its state and how it ended.
    type, public :: adapt_target_t
        integer :: state = TARGET_ACTIVE
        !> one line: the tolerance met, or why not and what was reached ('' while active)
        character(len=:), allocatable :: outcome
        !> met as no value: its absence confirmed ('none'), which a later level or the check
        !> must not contradict
        logical :: absent = .false.
    contains
        procedure :: active => target_is_active
        procedure :: converged => target_converged
        procedure :: met_absent => target_met_absent
        procedure :: floor_reached => target_floor_reached
        procedure :: finish => target_finish
    end type adapt_target_t

    !> A level as the refiner made it.
    type, public :: adapt_level_t
        !> h: 0 (the starting mesh), 1, 2, ...; hp: the layers of grading, 1, 2, ...
        integer :: number = 0
        !> h: the problem on the refined mesh; hp: the graded P1 mesh with the input's parts
        !> and material, the condensed K and the hp contact (nodes: basis functions),
        !> dofs%n_free only
        type(problem_t) :: prob
        type(hp_space_t) :: space            !! hp: the level's space (cell degrees)
        integer, allocatable :: degree(:)    !! hp: per cell of prob%mesh; h: unallocated
    end type adapt_level_t

    !> A check level built, factored and reduced by one goal's check for another goal's check
    !> of the same level (joint_goal: the thresholds', then the points'), so that its
    !> assembly, factor and contact blocks are made once; `built` says it was.
    type, public :: built_check_t
        logical :: built = .false.
        type(adapt_level_t) :: level
        type(cholesky_t) :: chol
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :)
        type(lift_share_t) :: share   !! the lifts' data on chol (contact_flexibility)
    end type built_check_t

    !> What makes the levels.
    type, abstract, public :: refiner_t
        character(len=:), allocatable :: name    !! the scene's, for messages
        type(adapt_options_t) :: adapt
        integer :: max_dofs = 0                  !! a level's free dofs at most
        character(len=:), allocatable :: dof_limit   !! the words naming that limit
        integer :: next_dofs = 0                 !! the free dofs of the level made last
        !> why the next level cannot be made, where not its dofs (hp: the mesh builder's
        !> limits); unallocated: the dofs (too_big_words)
        character(len=:), allocatable :: stop_reason
    contains
        !> before the first level: check the starting problem, set the limits
        procedure(refiner_begin), deferred :: begin
        !> the next level (the first: `solved` = 0); `too_big`: it has more free dofs than the
        !> limit while earlier levels were solved (the loop stops before it)
        procedure(refiner_next), deferred :: next
        !> K of a level factored with the contact dofs last
        procedure(refiner_factor), deferred :: factor
        !> the bar of the last of a series of levels of one value (and the relative change to
        !> the level before, and whether it has stopped converging: hp)
        procedure(refiner_series_bar), deferred :: series_bar
        !> whether each level carries its own error estimate (h: the enriched one, which
        !> also marks the cells to refine) rather than a bar from the changes between levels
        procedure(refiner_estimated), deferred :: estimated
        !> the words after '&adapt: ' in a message about a level ("strategy = 'hp': " or '')
        procedure(refiner_words), deferred :: strategy_words
        procedure :: too_big_words => refiner_too_big_words
        !> whether the last level gets an independent check (hp: its bars come from the
        !> changes between levels alone; h: the goal checks only what its estimate cannot see)
        procedure(refiner_estimated), deferred :: checked
        !> why more levels cannot lower an error the check found at level `last` ('': they can)
        procedure(refiner_cap_words), deferred :: cap_words
    end type refiner_t

    !> What the loop adapts to: a set of targets, each with its own state.
    type, abstract, public :: adapt_goal_t
        type(adapt_target_t), allocatable :: targets(:)
        !> a level after the first solved that failed (its solve, its making or the check
        !> of the last level): that failure, its message naming the level; the goal keeps
        !> the last complete level, which the run writes before it exits with its code
        type(status_t) :: failure
        !> points (x y, point) toward which the next h level is graded beyond what `mark`
        !> asks, set by judge (h_refiner: the cells at each refined GRADE_PASSES times more);
        !> unallocated or none: no grading
        real(wp), allocatable :: grade(:, :)
    contains
        !> solve `level` for the targets still active; `refused` (not '' ) says why the level
        !> cannot be solved at all (the memory of its contact blocks), before any change
        procedure(goal_solve), deferred :: solve
        !> the state of each active target after the level just solved
        procedure(goal_judge), deferred :: judge
        !> target i's bar at its last level, as outcomes quote it: 'B at N dofs' ('none at ...')
        procedure(goal_bar_text), deferred :: bar_text
        !> the cells of the last level to refine (h levels)
        procedure(goal_mark), deferred :: mark
        !> the check of the last level solved where refiner%checked() (hp: hp_levels'
        !> check_level), folded into the targets' bars (check_target)
        procedure(goal_check), deferred :: check
        procedure :: any_active => goal_any_active
    end type adapt_goal_t

    abstract interface
        subroutine refiner_begin(this, scn, adapt, start, stat)
            import :: refiner_t, scene_t, adapt_options_t, problem_t, status_t
            class(refiner_t), intent(inout) :: this
            type(scene_t), intent(in) :: scn
            type(adapt_options_t), intent(in) :: adapt
            type(problem_t), intent(in) :: start
            type(status_t), intent(out) :: stat
        end subroutine refiner_begin

        subroutine refiner_next(this, scn, start, goal, solved, level, too_big, timings, stat)
            import :: refiner_t, scene_t, problem_t, adapt_goal_t, adapt_level_t, timings_t, &
                      status_t
            class(refiner_t), intent(inout) :: this
            type(scene_t), intent(in) :: scn
            type(problem_t), intent(in) :: start
            class(adapt_goal_t), intent(in) :: goal
            integer, intent(in) :: solved
            type(adapt_level_t), intent(inout) :: level
            logical, intent(out) :: too_big
            type(timings_t), intent(inout) :: timings
            type(status_t), intent(out) :: stat
        end subroutine refiner_next

        subroutine refiner_factor(this, level, chol, timings, stat)
            import :: refiner_t, adapt_level_t, cholesky_t, timings_t, status_t
            class(refiner_t), intent(in) :: this
            type(adapt_level_t), intent(in) :: level
            type(cholesky_t), intent(inout) :: chol
            type(timings_t), intent(inout) :: timings
            type(status_t), intent(out) :: stat
        end subroutine refiner_factor

        pure subroutine refiner_series_bar(this, have, values, estimates, dofs, roundoff, bar, &
                                           change, stalled)
            import :: refiner_t, wp
            class(refiner_t), intent(in) :: this
            !> per level: the value exists, the value, its |relative estimate| (< 0: none),
            !> the free dofs; the last level's round-off bound (< 0: unknown)
            logical, intent(in) :: have(:)
            real(wp), intent(in) :: values(:), estimates(:)
            integer, intent(in) :: dofs(:)
            real(wp), intent(in) :: roundoff
            real(wp), intent(out) :: bar      !! relative; < 0: none
            real(wp), intent(out) :: change   !! |relative change| to the level before; < 0: none
            logical, intent(out) :: stalled
        end subroutine refiner_series_bar

        pure logical function refiner_estimated(this)
            import :: refiner_t
            class(refiner_t), intent(in) :: this
        end function refiner_estimated

        pure function refiner_cap_words(this, last) result(words)
            import :: refiner_t, adapt_level_t
            class(refiner_t), intent(in) :: this
            type(adapt_level_t), intent(in) :: last
            character(len=:), allocatable :: words
        end function refiner_cap_words

        pure function refiner_words(this) result(words)
            import :: refiner_t
            class(refiner_t), intent(in) :: this
            character(len=:), allocatable :: words
        end function refiner_words

        subroutine goal_solve(this, scn, refiner, level, loop_start, timings, refused, stat)
            import :: adapt_goal_t, scene_t, refiner_t, adapt_level_t, timings_t, status_t, wp
            class(adapt_goal_t), intent(inout) :: this
            type(scene_t), intent(in) :: scn
            class(refiner_t), intent(in) :: refiner
            type(adapt_level_t), intent(in) :: level
            real(wp), intent(in) :: loop_start   !! wall_time() at the start of the loop
            type(timings_t), intent(inout) :: timings
            character(len=:), allocatable, intent(out) :: refused
            type(status_t), intent(out) :: stat
        end subroutine goal_solve

        subroutine goal_judge(this, refiner, level, tolerance)
            import :: adapt_goal_t, refiner_t, wp
            class(adapt_goal_t), intent(inout) :: this
            class(refiner_t), intent(in) :: refiner
            integer, intent(in) :: level
            real(wp), intent(in) :: tolerance
        end subroutine goal_judge

        function goal_bar_text(this, i) result(text)
            import :: adapt_goal_t
            class(adapt_goal_t), intent(in) :: this
            integer, intent(in) :: i
            character(len=:), allocatable :: text
        end function goal_bar_text

        subroutine goal_check(this, scn, start, refiner, last, tolerance, reopen, timings, stat, &
                              built)
            import :: adapt_goal_t, scene_t, problem_t, refiner_t, adapt_level_t, timings_t, &
                      status_t, wp, built_check_t
            class(adapt_goal_t), intent(inout) :: this
            type(scene_t), intent(in) :: scn
            type(problem_t), intent(in) :: start
            class(refiner_t), intent(in) :: refiner
            !> the last level solved: its number, mesh (prob%mesh) and degrees only
            type(adapt_level_t), intent(in) :: last
            real(wp), intent(in) :: tolerance
            !> a target met at `last` that the check takes above the tolerance may climb on
            logical, intent(in) :: reopen
            type(timings_t), intent(inout) :: timings
            type(status_t), intent(out) :: stat
            !> a check level shared with another goal's check of the same level (joint_goal):
            !> the threshold goal keeps the one it makes there, the eigen goal solves on it
            !> where built%built; the other goals ignore it
            type(built_check_t), intent(inout), target, optional :: built
        end subroutine goal_check

        function goal_mark(this, theta) result(marked)
            import :: adapt_goal_t, wp
            class(adapt_goal_t), intent(in) :: this
            real(wp), intent(in) :: theta
            integer, allocatable :: marked(:)
        end function goal_mark
    end interface

contains

    !> Run the loop from the problem `start` of the scene `scn`, as `adapt` asks, with the
    !> levels of `refiner` and the targets of `goal` (allocated, all active). A limit reached
    !> is no failure (stat ok; the targets still active are stopped, their outcomes say
    !> what was reached); bad input is (refiner: a start it cannot refine, a first level
    !> over an explicit max_dofs), and so is a first level the goal refuses
    !> (STATUS_NOT_MET). The goal keeps what it solved.
    subroutine adapt_levels(scn, adapt, start, refiner, goal, timings, stat)
        type(scene_t), intent(in) :: scn
        type(adapt_options_t), intent(in) :: adapt
        type(problem_t), intent(in) :: start
        class(refiner_t), intent(inout) :: refiner
        class(adapt_goal_t), intent(inout) :: goal
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(adapt_level_t) :: level
        !> the last level solved: its number, mesh and degrees (what its check is made of)
        type(adapt_level_t) :: last
        character(len=:), allocatable :: refused
        real(wp) :: loop_start
        integer :: solved, checked, failing_level
        logical :: too_big

        loop_start = wall_time()
        failing_level = test_failing_level()
        call refiner%begin(scn, adapt, start, stat)
        if (.not. stat%ok()) return
        solved = 0
        checked = -1
        do
            call refiner%next(scn, start, goal, solved, level, too_big, timings, stat)
            if (.not. stat%ok()) then
                if (solved > 0) call level_failed(last%number + 1, stat)
                return
            end if
            if (too_big) then
                call stop_active(goal, 'tolerance '//given_real_text(adapt%tolerance)// &
                    ' not met: '//refiner%too_big_words()//'; reached error bar ')
                call check_last(.false., stat)
                exit
            end if
            ! h: before the level (hp: its factor, inside the goal's solve: hp_levels)
            if (refiner%estimated() .and. level%number == failing_level) &
                call stat%fail(STATUS_SOLVER, injected_failure(level%number))
            if (stat%ok()) call goal%solve(scn, refiner, level, loop_start, timings, refused, &
                                           stat)
            if (.not. stat%ok()) then
                if (solved > 0) call level_failed(level%number, stat)
                return
            end if
            if (len(refused) > 0) then
                if (solved == 0) then
                    call stat%fail(STATUS_NOT_MET, scn%name//': &adapt: '// &
                                   refiner%strategy_words()//refused)
                    return
                end if
                call stop_active(goal, 'tolerance '//given_real_text(adapt%tolerance)// &
                                 ' not met: the next '//refused//'; reached error bar ')
                call check_last(.false., stat)
                exit
            end if
            solved = solved + 1
            last%number = level%number
            last%prob%mesh = level%prob%mesh
            if (allocated(level%degree)) last%degree = level%degree
            call goal%judge(refiner, level%number, adapt%tolerance)
            if (.not. goal%any_active()) then
                ! more levels may lower what the check finds: unless capped or at max_levels
                call check_last(len(refiner%cap_words(last)) == 0 .and. .not. &
                    (adapt%max_levels > 0 .and. level%number >= adapt%max_levels), stat)
                if (.not. stat%ok()) return
                if (.not. goal%any_active()) exit
            end if
            if (adapt%max_levels > 0 .and. level%number >= adapt%max_levels) then
                call stop_active(goal, 'tolerance '//given_real_text(adapt%tolerance)// &
                    ' not met: max_levels = '//to_string(adapt%max_levels)// &
                    ' reached with error bar ')
                call check_last(.false., stat)
                exit
            end if
        end do

    contains

        !> The goal's check of the last level solved, once per level (a level whose check
        !> reopened a target and that the loop then stops at is not checked again).
        subroutine check_last(reopen, stat)
            logical, intent(in) :: reopen
            type(status_t), intent(out) :: stat
            if (.not. refiner%checked() .or. solved == 0 .or. checked == last%number) return
            checked = last%number
            call goal%check(scn, start, refiner, last, adapt%tolerance, reopen, timings, stat)
            if (.not. stat%ok()) call level_failed(last%number, stat, checking=.true.)
        end subroutine check_last

        !> Level `number` (after the first solved) failed with `stat`: kept in goal%failure,
        !> its message naming the level, `stat` cleared; every target still active, and one
        !> the failed check of that level was to confirm, stopped saying so, with the bar of
        !> the last complete level.
        subroutine level_failed(number, stat, checking)
            integer, intent(in) :: number
            type(status_t), intent(inout) :: stat
            logical, intent(in), optional :: checking
            character(len=:), allocatable :: words
            integer :: i
            words = 'level '//to_string(number)
            if (present(checking)) words = 'the check of '//words
            do i = 1, size(goal%targets)
                associate (t => goal%targets(i))
                    if (present(checking) .and. (t%converged() .or. t%floor_reached())) &
                        call t%finish(TARGET_ACTIVE, '')
                end associate
            end do
            call stop_active(goal, 'tolerance '//given_real_text(adapt%tolerance)// &
                             ' not met: '//words//' failed ('//stat%message// &
                             '); reached error bar ')
            goal%failure = stat
            goal%failure%message = stat%message//' ('//words//' failed)'
            stat = status_t()
        end subroutine level_failed
    end subroutine adapt_levels

    !> The message of the failure test_failing_level asks for at level `number`.
    function injected_failure(number) result(message)
        integer, intent(in) :: number
        character(len=:), allocatable :: message
        message = 'level '//to_string(number)//': the failure NCEIG_TEST_FAIL_LEVEL asks for'
    end function injected_failure

    !> The level whose solve fails as a numerical library's failure would, for the tests of
    !> what a run writes then (tests/cli/cli_level_failure.sh): NCEIG_TEST_FAIL_LEVEL, a
    !> level number; -1 (none) when unset or not a number. h levels fail before their solve,
    !> hp levels at their factor, once the goal has begun to take the level in.
    integer function test_failing_level() result(number)
        character(len=20) :: text
        integer :: length, ios
        number = -1
        call get_environment_variable('NCEIG_TEST_FAIL_LEVEL', text, length)
        if (length < 1 .or. length > len(text)) return
        read (text, *, iostat=ios) number
        if (ios /= 0) number = -1
    end function test_failing_level

    !> Why the next level is too big (refiner_next's too_big): stop_reason, else its dofs
    !> over the limit.
    function refiner_too_big_words(this) result(words)
        class(refiner_t), intent(in) :: this
        character(len=:), allocatable :: words
        if (allocated(this%stop_reason)) then
            words = this%stop_reason
        else
            words = 'the next level would have '//to_string(this%next_dofs)// &
                ' dofs, more than '//this%dof_limit
        end if
    end function refiner_too_big_words

    !> The target `t` after the check of the last level: its bar `series` from the levels
    !> became `bar` (checked_bar; `roundoff` its round-off part), `why` the words that say
    !> what the check found. A target met or at the floor that the check takes above the
    !> tolerance (off the floor) climbs again with `reopen`, else stops (TARGET_STOPPED,
    !> exit 8) saying why; a stopped target whose bar grew says so in its outcome.
    subroutine check_target(t, tolerance, series, bar, roundoff, reopen, why)
        type(adapt_target_t), intent(inout) :: t
        real(wp), intent(in) :: tolerance, series, bar, roundoff
        logical, intent(in) :: reopen
        character(len=*), intent(in) :: why
        logical :: fails
        select case (t%state)
        case (TARGET_MET)
            fails = bar < 0.0_wp .or. bar > tolerance
        case (TARGET_FLOOR)
            fails = .not. floor_reached(bar, roundoff)
        case default
            if (bar > series .or. (bar < 0.0_wp .and. series >= 0.0_wp)) &
                t%outcome = t%outcome//'; '//why
            return
        end select
        if (.not. fails) return
        if (reopen) then
            call t%finish(TARGET_ACTIVE, '')
        else
            call t%finish(TARGET_STOPPED, 'tolerance '//given_real_text(tolerance)// &
                          ' not met: '//why)
        end if
    end subroutine check_target

    !> Every active target of `goal` stopped, its outcome `words` and its bar.
    subroutine stop_active(goal, words)
        class(adapt_goal_t), intent(inout) :: goal
        character(len=*), intent(in) :: words
        integer :: i
        do i = 1, size(goal%targets)
            if (goal%targets(i)%active()) call goal%targets(i)%finish(TARGET_STOPPED, &
                                                                      words//goal%bar_text(i))
        end do
    end subroutine stop_active

    !> The rule of one target with one bar after level `level` (`dofs` free dofs), as the
    !> refiner makes bars. With levels that carry their own estimate (h) a missing `bar` (< 0)
    !> stops the target, `missing` saying why, and the tolerance can be met from level 1 on:
    !> a bar needs an earlier level to confirm it (a collision onset's estimate at h = 1/8
    !> was 0.09 times its true error). With bars from the changes between levels (hp) the
    !> first level has none, and a target stops without a value (`no_value`: why) or when it
    !> has stopped converging (`stalled`; `stall_what` names it). Both stop at the
    !> floating-point floor (the round-off part `roundoff` at least the rest of the bar).
    !> `confirmed` (h): whether the level before had the value, to confirm the bar (default:
    !> level >= 1; a value that appears after levels without it waits one level).
    subroutine judge_target(t, refiner, level, tolerance, dofs, has_value, no_value, bar, &
                            roundoff, stalled, stall_what, missing, confirmed)
        type(adapt_target_t), intent(inout) :: t
        class(refiner_t), intent(in) :: refiner
        integer, intent(in) :: level, dofs
        real(wp), intent(in) :: tolerance, bar, roundoff
        logical, intent(in) :: has_value, stalled
        character(len=*), intent(in) :: no_value, stall_what, missing
        logical, intent(in), optional :: confirmed
        logical :: confirmable

        confirmable = level >= 1
        if (present(confirmed)) confirmable = confirmed
        if (refiner%estimated()) then
            if (bar < 0.0_wp) then
                call t%finish(TARGET_STOPPED, no_estimate_outcome(level, missing))
            else if (bar <= tolerance .and. confirmable) then
                call t%finish(TARGET_MET, 'tolerance '//given_real_text(tolerance)// &
                    ' met at level '//to_string(level)//': error bar '// &
                    short_real_text(bar)//', '//to_string(dofs)//' dofs')
            else if (floor_reached(bar, roundoff)) then
                call t%finish(TARGET_FLOOR, floor_outcome(tolerance, roundoff, bar, &
                                                          to_string(dofs)))
            end if
            return
        end if
        if (.not. has_value) then
            call t%finish(TARGET_STOPPED, no_value)
        else if (stalled) then
            call t%finish(TARGET_STOPPED, stall_outcome(tolerance, stall_what))
        else if (bar >= 0.0_wp .and. bar <= tolerance) then
            call t%finish(TARGET_MET, 'tolerance '//given_real_text(tolerance)// &
                ' met at level '//to_string(level)//': error bar '//short_real_text(bar)// &
                ' at '//to_string(dofs)//' dofs')
        else if (floor_reached(bar, roundoff)) then
            call t%finish(TARGET_FLOOR, floor_outcome(tolerance, roundoff, bar, to_string(dofs)))
        end if
    end subroutine judge_target

    !> The outcome of a target stopped at h level `level` for want of an error estimate,
    !> `why` saying why it has none.
    pure function no_estimate_outcome(level, why) result(outcome)
        integer, intent(in) :: level
        character(len=*), intent(in) :: why
        character(len=:), allocatable :: outcome
        outcome = 'tolerance not met: no error estimate at level '//to_string(level)//' ('// &
                  why//')'
    end function no_estimate_outcome

    !> The first of the trailing levels without the value (`have` false; size(have) + 1
    !> where the last level has it).
    pure integer function absent_since(have) result(first)
        logical, intent(in) :: have(:)
        first = size(have) + 1
        do while (first > 1)
            if (have(first - 1)) exit
            first = first - 1
        end do
    end function absent_since

    !> Whether a value absent from the last levels (`have` per level, `dofs` their free
    !> dofs) is confirmed absent: none at the last NONE_LEVELS levels and, with levels that
    !> carry their own estimate (`estimated`: h, where a level may add a fraction of the
    !> dofs), the dofs at least doubled over the run without it. One level's absence is no
    !> answer: a coarse mesh can miss a value a finer one finds.
    pure logical function absence_confirmed(have, dofs, estimated) result(confirmed)
        logical, intent(in) :: have(:)
        integer, intent(in) :: dofs(:)
        logical, intent(in) :: estimated
        integer :: first
        first = absent_since(have)
        confirmed = size(have) - first + 1 >= NONE_LEVELS
        if (estimated .and. confirmed) confirmed = dofs(size(dofs)) >= 2*dofs(first)
    end function absence_confirmed

    pure logical function target_is_active(this)
        class(adapt_target_t), intent(in) :: this
        target_is_active = this%state == TARGET_ACTIVE
    end function target_is_active

    pure logical function target_converged(this)
        class(adapt_target_t), intent(in) :: this
        target_converged = this%state == TARGET_MET
    end function target_converged

    pure logical function target_met_absent(this)
        class(adapt_target_t), intent(in) :: this
        target_met_absent = this%state == TARGET_MET .and. this%absent
    end function target_met_absent

    pure logical function target_floor_reached(this)
        class(adapt_target_t), intent(in) :: this
        target_floor_reached = this%state == TARGET_FLOOR
    end function target_floor_reached

    !> The target ends in `state` (TARGET_MET, _FLOOR or _STOPPED) with `outcome`;
    !> `absent`: met as no value (default: with one).
    pure subroutine target_finish(this, state, outcome, absent)
        class(adapt_target_t), intent(inout) :: this
        integer, intent(in) :: state
        character(len=*), intent(in) :: outcome
        logical, intent(in), optional :: absent
        this%state = state
        this%outcome = outcome
        this%absent = .false.
        if (present(absent)) this%absent = absent .and. state == TARGET_MET
    end subroutine target_finish

    pure logical function goal_any_active(this)
        class(adapt_goal_t), intent(in) :: this
        integer :: i
        goal_any_active = .false.
        do i = 1, size(this%targets)
            if (this%targets(i)%active()) goal_any_active = .true.
        end do
    end function goal_any_active
end module adapt_driver
