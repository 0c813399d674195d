! SPDX-License-Identifier: MIT
!> Test doubles of the loop's interfaces (a program cannot bind procedures to its types).
module adapt_driver_doubles
    use kinds, only: wp
    use status, only: status_t
    use strings, only: short_real_text, to_string
    use timer, only: timings_t
    use scene, only: scene_t
    use method_options, only: adapt_options_t
    use problem, only: problem_t
    use sparse_cholesky, only: cholesky_t
    use adapt_driver, only: refiner_t, adapt_goal_t, adapt_level_t, judge_target, check_target, &
                            built_check_t
    implicit none
    private
    public :: counting_refiner_t, geometric_goal_t

    !> Levels 1, 2, ... of 4^k free dofs; bars from the change between levels.
    type, extends(refiner_t) :: counting_refiner_t
        logical :: with_estimates = .false.   !! answer estimated() so (for judge_target)
        logical :: with_check = .false.       !! answer checked() so
        integer :: capped_from = huge(0)      !! cap_words says 'capped' from this level on
    contains
        procedure :: begin => counting_begin
        procedure :: next => counting_next
        procedure :: factor => counting_factor
        procedure :: series_bar => counting_series_bar
        procedure :: estimated => counting_estimated
        procedure :: strategy_words => counting_words
        procedure :: checked => counting_checked
        procedure :: cap_words => counting_cap_words
    end type counting_refiner_t

    !> Target i converges like 1 + rate(i)^k; levels from `refuse_from` on are refused.
    type, extends(adapt_goal_t) :: geometric_goal_t
        real(wp), allocatable :: rate(:)
        integer, allocatable :: solves(:)     !! levels solved per target
        real(wp), allocatable :: bar(:)       !! each target's bar at its last level
        integer, allocatable :: dofs(:)       !! and that level's dofs
        integer :: refuse_from = huge(0)
        !> its check (counting_refiner_t with_check) finds this times the bar from the levels
        real(wp) :: check_factor = 0.0_wp
        integer :: checks = 0                 !! checks made
    contains
        procedure :: solve => geometric_solve
        procedure :: judge => geometric_judge
        procedure :: bar_text => geometric_bar_text
        procedure :: mark => geometric_mark
        procedure :: check => geometric_check
    end type geometric_goal_t

contains

    subroutine counting_begin(this, scn, adapt, start, stat)
        class(counting_refiner_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(adapt_options_t), intent(in) :: adapt
        type(problem_t), intent(in) :: start
        type(status_t), intent(out) :: stat
        this%name = scn%name
        this%adapt = adapt
        this%max_dofs = huge(0)
        this%dof_limit = 'the memory'
        if (adapt%max_dofs > 0) then
            this%max_dofs = adapt%max_dofs
            this%dof_limit = 'max_dofs = '//to_string(adapt%max_dofs)
        end if
        stat = status_t()
    end subroutine counting_begin

    !> Level `solved` + 1, of 4^k free dofs.
    subroutine counting_next(this, scn, start, goal, solved, level, too_big, timings, stat)
        class(counting_refiner_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: start
        class(adapt_goal_t), intent(in) :: goal
        integer, intent(in) :: solved
        type(adapt_level_t), intent(inout) :: level
        logical, intent(out) :: too_big
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        level%number = solved + 1
        this%next_dofs = 4**level%number
        too_big = this%next_dofs > this%max_dofs .and. solved > 0
        level%prob%dofs%n_free = this%next_dofs
        stat = status_t()
    end subroutine counting_next

    subroutine counting_factor(this, level, chol, timings, stat)
        class(counting_refiner_t), intent(in) :: this
        type(adapt_level_t), intent(in) :: level
        type(cholesky_t), intent(inout) :: chol
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        stat = status_t()   ! (the goal of this test solves without a factor)
    end subroutine counting_factor

    !> The relative change of the last value to the one before; none at the first level.
    pure subroutine counting_series_bar(this, have, values, estimates, dofs, roundoff, bar, &
                                        change, stalled)
        class(counting_refiner_t), intent(in) :: this
        logical, intent(in) :: have(:)
        real(wp), intent(in) :: values(:), estimates(:)
        integer, intent(in) :: dofs(:)
        real(wp), intent(in) :: roundoff
        real(wp), intent(out) :: bar, change
        logical, intent(out) :: stalled
        integer :: k
        k = size(values)
        bar = -1.0_wp
        if (k >= 2 .and. all(have)) bar = abs(values(k) - values(k - 1))/abs(values(k))
        change = bar
        stalled = .false.
    end subroutine counting_series_bar

    pure logical function counting_estimated(this)
        class(counting_refiner_t), intent(in) :: this
        counting_estimated = this%with_estimates
    end function counting_estimated

    pure function counting_words(this) result(words)
        class(counting_refiner_t), intent(in) :: this
        character(len=:), allocatable :: words
        words = ''
    end function counting_words

    pure logical function counting_checked(this)
        class(counting_refiner_t), intent(in) :: this
        counting_checked = this%with_check
    end function counting_checked

    pure function counting_cap_words(this, last) result(words)
        class(counting_refiner_t), intent(in) :: this
        type(adapt_level_t), intent(in) :: last
        character(len=:), allocatable :: words
        words = ''
        if (last%number >= this%capped_from) words = 'capped'
    end function counting_cap_words

    !> The check of level `last`: each target's bar becomes the larger of its own and
    !> check_factor times it ('the check says so'; '; capped' where the refiner says so).
    subroutine geometric_check(this, scn, start, refiner, last, tolerance, reopen, timings, &
                               stat, built)
        class(geometric_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: start
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: last
        real(wp), intent(in) :: tolerance
        logical, intent(in) :: reopen
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(built_check_t), intent(inout), target, optional :: built
        real(wp) :: series
        character(len=:), allocatable :: why
        integer :: i
        this%checks = this%checks + 1
        why = 'the check says so'
        if (len(refiner%cap_words(last)) > 0) why = why//'; '//refiner%cap_words(last)
        do i = 1, size(this%rate)
            if (this%bar(i) < 0.0_wp) cycle
            series = this%bar(i)
            this%bar(i) = max(series, this%check_factor*series)
            call check_target(this%targets(i), tolerance, series, this%bar(i), -1.0_wp, &
                              reopen, why)
        end do
        stat = status_t()
    end subroutine geometric_check

    !> Every active target's value 1 + q^k at level k, its bar over its levels so far.
    subroutine geometric_solve(this, scn, refiner, level, loop_start, timings, refused, stat)
        class(geometric_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable, intent(out) :: refused
        type(status_t), intent(out) :: stat
        real(wp) :: change
        real(wp), allocatable :: values(:)
        logical :: stalled
        integer :: i, j, k
        refused = ''
        if (level%number >= this%refuse_from) then
            refused = 'level '//to_string(level%number)//' is refused'
            return
        end if
        k = level%number
        do i = 1, size(this%rate)
            if (.not. this%targets(i)%active()) cycle
            this%solves(i) = this%solves(i) + 1
            values = [(1.0_wp + this%rate(i)**j, j = 1, k)]
            call refiner%series_bar([(.true., j = 1, k)], values, -values, [(4**j, j = 1, k)], &
                                    -1.0_wp, this%bar(i), change, stalled)
            this%dofs(i) = level%prob%dofs%n_free
        end do
        stat = status_t()
    end subroutine geometric_solve

    subroutine geometric_judge(this, refiner, level, tolerance)
        class(geometric_goal_t), intent(inout) :: this
        class(refiner_t), intent(in) :: refiner
        integer, intent(in) :: level
        real(wp), intent(in) :: tolerance
        integer :: i
        do i = 1, size(this%rate)
            if (.not. this%targets(i)%active()) cycle
            call judge_target(this%targets(i), refiner, level, tolerance, this%dofs(i), .true., &
                              '', this%bar(i), -1.0_wp, .false., '', '')
        end do
    end subroutine geometric_judge

    function geometric_bar_text(this, i) result(text)
        class(geometric_goal_t), intent(in) :: this
        integer, intent(in) :: i
        character(len=:), allocatable :: text
        text = short_real_text(this%bar(i))//' at '//to_string(this%dofs(i))//' dofs'
    end function geometric_bar_text

    function geometric_mark(this, theta) result(marked)
        class(geometric_goal_t), intent(in) :: this
        real(wp), intent(in) :: theta
        integer, allocatable :: marked(:)
        allocate (marked(0))   ! (the levels of this test are not refined cells)
    end function geometric_mark
end module adapt_driver_doubles

!> The adaptive loop (adapt_driver) on its own, with a refiner and a goal of this test whose
!> answers are known in closed form: level k has 4^k free dofs, and target i's value at level
!> k is 1 + q_i^k, so its change to the level before, the bar (as hp levels make bars, none at
!> the first level), is q_i^(k-1) (1 - q_i) / (1 + q_i^k). Each target stops at the first
!> level where that is within the tolerance, independently of the others (a target that
!> stopped is solved no more), and the loop stops when none is active or at a limit
!> (max_levels, max_dofs, a level the goal refuses), each active target with its own words.
!> judge_target's rules are checked case by case, for levels with an estimate of their own
!> (h) and without (hp).
program test_adapt_driver
    use adapt_driver_doubles, only: counting_refiner_t, geometric_goal_t
    use kinds, only: wp
    use status, only: status_t, STATUS_NOT_MET
    use strings, only: short_real_text
    use testing, only: test_suite_t
    use timer, only: timings_t
    use scene, only: scene_t
    use method_options, only: adapt_options_t
    use problem, only: problem_t
    use sparse_cholesky, only: cholesky_t
    use error_bar, only: floor_outcome, stall_outcome
    use adapt_driver, only: refiner_t, adapt_goal_t, adapt_level_t, adapt_target_t, &
                            adapt_levels, judge_target, TARGET_ACTIVE, TARGET_STOPPED, &
                            absent_since, absence_confirmed, NONE_LEVELS
    implicit none

    real(wp), parameter :: TOLERANCE = 1.0e-3_wp
    type(test_suite_t) :: t

    t%name = 'test_adapt_driver'
    call targets_stop_on_their_own(t)
    call max_levels_stops_the_active(t)
    call max_dofs_stops_before_the_level(t)
    call refused_levels_stop_the_loop(t)
    call judge_target_rules(t)
    call absence_rules(t)
    call a_failed_check_climbs_on(t)
    call a_capped_check_stops(t)
    call t%report()

contains

    !> k where q^(k-1) (1 - q) / (1 + q^k) first is at most TOLERANCE (k >= 2).
    integer function met_level(q)
        real(wp), intent(in) :: q
        met_level = 2
        do while (q**(met_level - 1)*(1.0_wp - q)/(1.0_wp + q**met_level) > TOLERANCE)
            met_level = met_level + 1
        end do
    end function met_level

    !> Rates 0.25 and 0.5 (met at levels 6 and 10): each target is solved up to its own
    !> level and no further, met, its outcome naming that level; the loop ends with both.
    subroutine targets_stop_on_their_own(t)
        type(test_suite_t), intent(inout) :: t
        type(geometric_goal_t) :: goal
        type(status_t) :: stat
        integer :: i
        call run([0.25_wp, 0.5_wp], adapt_options_t(tolerance=TOLERANCE), goal, stat)
        call t%check('independent targets: runs', stat%ok())
        call t%check('independent targets: met at levels 6 and 10 (closed form)', &
                     met_level(0.25_wp) == 6 .and. met_level(0.5_wp) == 10)
        do i = 1, 2
            call t%check('independent targets: target solved up to its own level', &
                         goal%solves(i) == met_level(goal%rate(i)))
            call t%check('independent targets: met, the outcome names its level', &
                         goal%targets(i)%converged() .and. index(goal%targets(i)%outcome, &
                         ' met at level '//to_text(met_level(goal%rate(i)))//':') > 0)
        end do
    end subroutine targets_stop_on_their_own

    !> max_levels = 4: both targets stopped at level 4, each outcome with its own bar at the
    !> 4^4 = 256 dofs of that level.
    subroutine max_levels_stops_the_active(t)
        type(test_suite_t), intent(inout) :: t
        type(geometric_goal_t) :: goal
        type(status_t) :: stat
        integer :: i
        call run([0.25_wp, 0.5_wp], adapt_options_t(tolerance=TOLERANCE, max_levels=4), &
                 goal, stat)
        call t%check('max_levels: runs', stat%ok())
        do i = 1, 2
            call t%check('max_levels: stopped after 4 levels, its bar at 256 dofs', &
                         goal%solves(i) == 4 .and. &
                         goal%targets(i)%state == TARGET_STOPPED .and. &
                         goal%targets(i)%outcome == 'tolerance '//short_real_text(TOLERANCE)// &
                         ' not met: max_levels = 4 reached with error bar '// &
                         short_real_text(goal%bar(i))//' at 256 dofs')
        end do
    end subroutine max_levels_stops_the_active

    !> max_dofs = 300: level 5 (1024 dofs) is never solved; the outcome names its size.
    subroutine max_dofs_stops_before_the_level(t)
        type(test_suite_t), intent(inout) :: t
        type(geometric_goal_t) :: goal
        type(status_t) :: stat
        call run([0.5_wp], adapt_options_t(tolerance=TOLERANCE, max_dofs=300), goal, stat)
        call t%check('max_dofs: runs, 4 levels solved', stat%ok() .and. goal%solves(1) == 4)
        call t%check('max_dofs: the outcome names the next level and the limit', &
                     index(goal%targets(1)%outcome, 'the next level would have 1024 dofs, '// &
                           'more than max_dofs = 300; reached error bar ') > 0)
    end subroutine max_dofs_stops_before_the_level

    !> A goal that refuses level 3 stops the loop there, its words in the outcome; one that
    !> refuses the first level fails the run (STATUS_NOT_MET) with the scene's name.
    subroutine refused_levels_stop_the_loop(t)
        type(test_suite_t), intent(inout) :: t
        type(geometric_goal_t) :: goal
        type(status_t) :: stat
        call run([0.5_wp], adapt_options_t(tolerance=TOLERANCE), goal, stat, refuse_from=3)
        call t%check('refused level 3: runs, 2 levels solved', stat%ok() .and. &
                     goal%solves(1) == 2)
        call t%check('refused level 3: the outcome says why', index(goal%targets(1)%outcome, &
                     'not met: the next level 3 is refused; reached error bar ') > 0)
        call run([0.5_wp], adapt_options_t(tolerance=TOLERANCE), goal, stat, refuse_from=1)
        call t%check('refused level 1: STATUS_NOT_MET naming the scene', &
                     stat%code == STATUS_NOT_MET .and. &
                     index(stat%message, 'scene.nml: &adapt: level 1 is refused') == 1)
    end subroutine refused_levels_stop_the_loop

    !> A check that finds 4 times the bar of the levels (rate 0.5: the bar at level k is
    !> 0.5^(k-1) 0.5 / (1 + 0.5^k)) at every level where the target meets the tolerance:
    !> the target climbs on until 4 times its bar meets it, at level 12 (closed form: 4 b(11)
    !> = 1.95e-3, 4 b(12) = 9.8e-4), checked at levels 10, 11 and 12; met. Without the
    !> refiner's check (with_check false) no check is made.
    subroutine a_failed_check_climbs_on(t)
        type(test_suite_t), intent(inout) :: t
        type(geometric_goal_t) :: goal
        type(status_t) :: stat
        call run([0.5_wp], adapt_options_t(tolerance=TOLERANCE), goal, stat, with_check=.true., &
                 check_factor=4.0_wp)
        call t%check('failed check: climbs on to level 12, checked 3 times, met', &
                     stat%ok() .and. goal%solves(1) == 12 .and. goal%checks == 3 .and. &
                     goal%targets(1)%converged() .and. &
                     4.0_wp*0.5_wp**12/(1.0_wp + 0.5_wp**12) <= TOLERANCE .and. &
                     4.0_wp*0.5_wp**11/(1.0_wp + 0.5_wp**11) > TOLERANCE)
        call run([0.5_wp], adapt_options_t(tolerance=TOLERANCE), goal, stat, &
                 check_factor=4.0_wp)
        call t%check('no check without the refiner''s: met at level 10', &
                     goal%checks == 0 .and. goal%solves(1) == 10 .and. &
                     goal%targets(1)%converged())
    end subroutine a_failed_check_climbs_on

    !> The same check where the refiner says more levels cannot help (capped): the target
    !> stops at level 10 with the check's words and the refiner's, not converged; a check
    !> that agrees (factor 1) leaves it met; at max_levels a failed check stops it too.
    subroutine a_capped_check_stops(t)
        type(test_suite_t), intent(inout) :: t
        type(geometric_goal_t) :: goal
        type(status_t) :: stat
        call run([0.5_wp], adapt_options_t(tolerance=TOLERANCE), goal, stat, with_check=.true., &
                 check_factor=4.0_wp, capped_from=1)
        call t%check('capped check: stopped at level 10, saying why', stat%ok() .and. &
                     goal%solves(1) == 10 .and. goal%checks == 1 .and. &
                     goal%targets(1)%state == TARGET_STOPPED .and. goal%targets(1)%outcome == &
                     'tolerance 1.00E-03 not met: the check says so; capped')
        call run([0.5_wp], adapt_options_t(tolerance=TOLERANCE), goal, stat, with_check=.true., &
                 check_factor=1.0_wp, capped_from=1)
        call t%check('agreeing check: met at level 10', goal%solves(1) == 10 .and. &
                     goal%checks == 1 .and. goal%targets(1)%converged())
        call run([0.5_wp], adapt_options_t(tolerance=TOLERANCE, max_levels=10), goal, stat, &
                 with_check=.true., check_factor=4.0_wp)
        call t%check('failed check at max_levels: stopped', goal%solves(1) == 10 .and. &
                     goal%checks == 1 .and. goal%targets(1)%state == TARGET_STOPPED)
    end subroutine a_capped_check_stops

    !> judge_target, case by case. With levels that carry their estimate: a missing bar
    !> stops the target with the reason; a bar within the tolerance at level 0 is not yet met
    !> (nothing confirms it), at level 1 it is; a round-off part at least half the bar is the
    !> floor. Without: no value stops the target, a stall does, the first level has no bar.
    subroutine judge_target_rules(t)
        type(test_suite_t), intent(inout) :: t
        type(counting_refiner_t) :: h, hp
        type(adapt_target_t) :: x
        h%with_estimates = .true.
        call judge(x, h, 0, -1.0_wp, -1.0_wp, .true., .false.)
        call t%check('h: no bar stops, with the reason', x%state == TARGET_STOPPED .and. &
                     x%outcome == 'tolerance not met: no error estimate at level 0 (why)')
        call judge(x, h, 0, 0.5e-3_wp, -1.0_wp, .true., .false.)
        call t%check('h: within the tolerance at level 0: still active', &
                     x%state == TARGET_ACTIVE)
        call judge(x, h, 1, 0.5e-3_wp, -1.0_wp, .true., .false.)
        call t%check('h: within the tolerance at level 1: met', x%converged() .and. &
                     x%outcome == 'tolerance 1.00E-03 met at level 1: error bar 5.00E-04, '// &
                     '64 dofs')
        call judge(x, h, 1, 4.0e-3_wp, 2.0e-3_wp, .true., .false.)
        call t%check('h: round-off half the bar: the floor', x%floor_reached() .and. &
                     x%outcome == floor_outcome(TOLERANCE, 2.0e-3_wp, 4.0e-3_wp, '64'))
        call judge(x, h, 1, 4.0e-3_wp, 1.9e-3_wp, .true., .false.)
        call t%check('h: round-off below half the bar: active', x%state == TARGET_ACTIVE)
        call judge(x, hp, 3, -1.0_wp, -1.0_wp, .false., .false.)
        call t%check('hp: no value stops, with its words', x%state == TARGET_STOPPED .and. &
                     x%outcome == 'none here')
        call judge(x, hp, 3, 1.0e-2_wp, -1.0_wp, .true., .true.)
        call t%check('hp: a stall stops', x%state == TARGET_STOPPED .and. &
                     x%outcome == stall_outcome(TOLERANCE, 'it'))
        call judge(x, hp, 1, -1.0_wp, -1.0_wp, .true., .false.)
        call t%check('hp: the first level (no bar): active', x%state == TARGET_ACTIVE)
        call judge(x, hp, 2, 0.5e-3_wp, -1.0_wp, .true., .false.)
        call t%check('hp: within the tolerance: met', x%converged() .and. &
                     x%outcome == 'tolerance 1.00E-03 met at level 2: error bar 5.00E-04 '// &
                     'at 64 dofs')

    end subroutine judge_target_rules

    !> What confirms a value absent (a threshold side's 'none', an eigen lambda's 'no
    !> positive mu'), case by case: NONE_LEVELS levels without it in a row, on h levels over
    !> which the dofs at least doubled (a level may add a fraction of them), on hp levels
    !> whatever the dofs; a value at the last level, or fewer levels, confirm nothing. And a
    !> value that has just appeared on h levels meets no tolerance before a level confirms it.
    subroutine absence_rules(t)
        type(test_suite_t), intent(inout) :: t
        type(counting_refiner_t) :: h
        type(adapt_target_t) :: x
        logical, parameter :: F = .false., T_ = .true.
        call t%check('NONE_LEVELS is three, as a threshold side''s none needs', NONE_LEVELS == 3)
        call t%check('absent_since: the first of the trailing levels without the value', &
                     absent_since([T_, F, F]) == 2 .and. absent_since([F, F, F]) == 1 .and. &
                     absent_since([F, T_]) == 3 .and. absent_since([logical ::]) == 1)
        call t%check('h: three levels without, the dofs doubled: confirmed', &
                     absence_confirmed([F, F, F], [40, 72, 144], .true.))
        call t%check('h: three levels without, the dofs not doubled: not yet', &
                     .not. absence_confirmed([F, F, F], [40, 50, 79], .true.))
        call t%check('h: the run without counts from its first level', &
                     absence_confirmed([T_, F, F, F], [10, 40, 60, 80], .true.) .and. &
                     .not. absence_confirmed([T_, F, F, F], [10, 41, 60, 81], .true.))
        call t%check('two levels without: not yet, whatever the dofs', &
                     .not. absence_confirmed([F, F], [40, 1000], .true.) .and. &
                     .not. absence_confirmed([F, F], [40, 1000], .false.))
        call t%check('hp: three levels without: confirmed, whatever the dofs', &
                     absence_confirmed([F, F, F], [40, 50, 60], .false.))
        call t%check('a value at the last level: no absence', &
                     .not. absence_confirmed([F, F, F, T_], [1, 2, 4, 8], .true.))
        h%with_estimates = .true.
        x%outcome = ''
        call judge_target(x, h, 3, TOLERANCE, 64, .true., 'none here', 0.5e-3_wp, -1.0_wp, &
                          .false., 'it', 'why', confirmed=.false.)
        call t%check('h: a value new at level 3, within the tolerance: still active', &
                     x%state == TARGET_ACTIVE)
    end subroutine absence_rules

    !> `x` judged at `level` with `bar` and the rest as given (64 dofs, the stall named
    !> 'it', the missing estimate 'why', no value 'none here').
    subroutine judge(x, refiner, level, bar, roundoff, has_value, stalled)
        type(adapt_target_t), intent(out) :: x
        type(counting_refiner_t), intent(in) :: refiner
        integer, intent(in) :: level
        real(wp), intent(in) :: bar, roundoff
        logical, intent(in) :: has_value, stalled
        x%outcome = ''
        call judge_target(x, refiner, level, TOLERANCE, 64, has_value, 'none here', bar, &
                          roundoff, stalled, 'it', 'why')
    end subroutine judge

    !> The loop with targets of `rates` as `adapt` asks.
    subroutine run(rates, adapt, goal, stat, refuse_from, with_check, check_factor, capped_from)
        real(wp), intent(in) :: rates(:)
        type(adapt_options_t), intent(in) :: adapt
        type(geometric_goal_t), intent(out) :: goal
        type(status_t), intent(out) :: stat
        integer, intent(in), optional :: refuse_from, capped_from
        logical, intent(in), optional :: with_check
        real(wp), intent(in), optional :: check_factor
        type(counting_refiner_t) :: refiner
        type(scene_t) :: scn
        type(problem_t) :: start
        type(timings_t) :: timings
        integer :: i
        scn%name = 'scene.nml'
        goal%rate = rates
        allocate (goal%targets(size(rates)), goal%solves(size(rates)), goal%bar(size(rates)), &
                  goal%dofs(size(rates)))
        goal%solves = 0
        goal%bar = -1.0_wp
        goal%dofs = 0
        do i = 1, size(rates)
            goal%targets(i)%outcome = ''
        end do
        if (present(refuse_from)) goal%refuse_from = refuse_from
        if (present(with_check)) refiner%with_check = with_check
        if (present(capped_from)) refiner%capped_from = capped_from
        if (present(check_factor)) goal%check_factor = check_factor
        call adapt_levels(scn, adapt, start, refiner, goal, timings, stat)
    end subroutine run

    pure function to_text(i) result(text)
        integer, intent(in) :: i
        character(len=:), allocatable :: text
        character(len=12) :: buffer
        write (buffer, '(i0)') i
        text = trim(buffer)
    end function to_text










end program test_adapt_driver
