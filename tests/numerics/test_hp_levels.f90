! SPDX-License-Identifier: MIT
!> The levels of &adapt strategy = 'hp' (hp_levels) from the reference scene's 2 x 2 P1
!> squares: level k is graded in k layers with degrees 1 (at the singular points) to
!> min(k + 1, p_max), each level has more dofs than the one before, its problem is the
!> condensed hp system (K symmetric, factored with the contact functions last) with as many
!> free dofs as its space; a start of quadrilaterals is refused, a first level over an
!> explicit max_dofs is bad input and a later one over it is too big; a bar of hp levels is
!> hp_run_bar's, from the values alone.
program test_hp_levels
    use goal_doubles, only: every_cell_t
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use testing, only: test_suite_t
    use timer, only: timings_t
    use run_config, only: config_t
    use run_inputs, only: run_inputs_t, translate_input
    use scene, only: scene_t
    use problem, only: problem_t
    use sparse_cholesky, only: cholesky_t
    use error_bar, only: hp_run_bar
    use adapt_driver, only: adapt_goal_t, adapt_level_t, refiner_t
    use hp_levels, only: hp_refiner_t
    use fixtures, only: square_scene, problem_of, csr_to_dense
    implicit none


    type(test_suite_t) :: t

    t%name = 'test_hp_levels'
    call levels_climb(t, 20)
    call levels_climb(t, 2)
    call limits(t)
    call bar_is_hp_run_bar(t)
    call check_level_is_one_degree_higher(t)
    call t%report()

contains

    !> Three levels with &adapt p_max = `p_max`: the layers, the degrees, growing dofs, the
    !> problem's sizes, K symmetric (to round-off of its largest entry) and factored.
    subroutine levels_climb(t, p_max)
        type(test_suite_t), intent(inout) :: t
        integer, intent(in) :: p_max
        type(run_inputs_t) :: inputs
        type(problem_t) :: start
        type(hp_refiner_t) :: refiner
        type(every_cell_t) :: goal
        type(adapt_level_t) :: level
        type(timings_t) :: timings
        type(cholesky_t) :: chol
        type(status_t) :: stat
        real(wp), allocatable :: k(:, :)
        character(len=40) :: what
        logical :: too_big
        integer :: n, previous
        call begin(p_max, 0, inputs, start, refiner, stat)
        call t%check('begin on 2 x 2 P1', stat%ok())
        if (.not. stat%ok()) return
        previous = 0
        do n = 1, 3
            write (what, '(a, i0, a, i0)') 'p_max ', p_max, ', level ', n
            call refiner%next(inputs%scene, start, goal, n - 1, level, too_big, timings, stat)
            call t%check(trim(what)//': built', stat%ok() .and. .not. too_big)
            if (.not. stat%ok()) return
            call t%check(trim(what)//': k layers, degrees 1 to min(k + 1, p_max)', &
                         level%number == n .and. minval(level%degree) == 1 .and. &
                         maxval(level%degree) == min(n + 1, p_max))
            call t%check(trim(what)//': more dofs than the level before', &
                         level%prob%dofs%n_free > previous)
            call t%check(trim(what)//': the problem''s dofs are its space''s', &
                         level%prob%dofs%n_free == level%space%n_free() .and. &
                         level%prob%k%n() == level%space%n_free())
            k = csr_to_dense(level%prob%k)
            call t%check(trim(what)//': K symmetric', maxval(abs(k - transpose(k))) <= &
                         64.0_wp*epsilon(1.0_wp)*maxval(abs(k)))
            call refiner%factor(level, chol, timings, stat)
            call t%check(trim(what)//': K factored (positive definite)', stat%ok())
            call chol%free()
            previous = level%prob%dofs%n_free
        end do
    end subroutine levels_climb

    !> The check of level 3 with p_max = 2: the same cells, every degree the level's + 1
    !> (degrees 2 to 3), more dofs, K symmetric positive definite; the refiner is checked and
    !> names the cap (level 3 would have degree 4 without it), and with p_max = 20 it names
    !> none.
    subroutine check_level_is_one_degree_higher(t)
        type(test_suite_t), intent(inout) :: t
        type(run_inputs_t) :: inputs
        type(problem_t) :: start
        type(hp_refiner_t) :: refiner
        type(every_cell_t) :: goal
        type(adapt_level_t) :: level, check
        type(timings_t) :: timings
        type(cholesky_t) :: chol
        type(status_t) :: stat
        logical :: too_big
        integer :: n
        call begin(2, 0, inputs, start, refiner, stat)
        do n = 1, 3
            if (stat%ok()) call refiner%next(inputs%scene, start, goal, n - 1, level, too_big, &
                                             timings, stat)
        end do
        if (stat%ok()) call refiner%check_level(start, level, check, timings, stat)
        call t%check('check of level 3: built', stat%ok())
        if (.not. stat%ok()) return
        call t%check('check: the same cells, every degree + 1', &
                     check%prob%mesh%n_cells() == level%prob%mesh%n_cells() .and. &
                     all(check%degree == level%degree + 1) .and. check%number == 3)
        call t%check('check: more dofs, the space''s', check%prob%dofs%n_free > &
                     level%prob%dofs%n_free .and. check%prob%dofs%n_free == check%space%n_free())
        call refiner%factor(check, chol, timings, stat)
        call t%check('check: K factored (positive definite)', stat%ok())
        call chol%free()
        call t%check('p_max = 2 at level 3: checked, the cap named', refiner%checked() .and. &
                     index(refiner%cap_words(level), 'p_max = 2 caps the degrees') > 0)
        call begin(20, 0, inputs, start, refiner, stat)
        call t%check('p_max = 20 at level 3: no cap', len(refiner%cap_words(level)) == 0)
    end subroutine check_level_is_one_degree_higher

    !> Quadrilaterals refused at begin; max_dofs below the first level's dofs: bad input;
    !> between the first's and the second's: the second is too big.
    subroutine limits(t)
        type(test_suite_t), intent(inout) :: t
        type(run_inputs_t) :: inputs
        type(problem_t) :: start
        type(hp_refiner_t) :: refiner
        type(every_cell_t) :: goal
        type(adapt_level_t) :: level
        type(timings_t) :: timings
        type(status_t) :: stat
        type(config_t) :: config
        logical :: too_big
        integer :: first
        call square_scene(2, 'q1', 'right', config)
        config%adapt%tolerance = 1.0e-6_wp
        config%adapt%strategy = 'hp'
        call translate_input(config, inputs)
        call problem_of(config, start, stat)
        if (stat%ok()) call refiner%begin(inputs%scene, inputs%adapt, start, stat)
        call t%check('q1: bad input, expected triangles', stat%code == STATUS_BAD_INPUT .and. &
                     index(stat%message, 'expected triangles') > 0)
        call begin(20, 0, inputs, start, refiner, stat)
        if (stat%ok()) call refiner%next(inputs%scene, start, goal, 0, level, too_big, &
                                         timings, stat)
        if (.not. stat%ok()) return
        first = level%prob%dofs%n_free
        call begin(20, first - 1, inputs, start, refiner, stat)
        if (stat%ok()) call refiner%next(inputs%scene, start, goal, 0, level, too_big, &
                                         timings, stat)
        call t%check('max_dofs below the first level: bad input naming it', &
                     stat%code == STATUS_BAD_INPUT .and. &
                     index(stat%message, 'free dofs of the first hp level') > 0)
        call begin(20, first, inputs, start, refiner, stat)
        if (stat%ok()) call refiner%next(inputs%scene, start, goal, 0, level, too_big, &
                                         timings, stat)
        if (stat%ok()) call refiner%next(inputs%scene, start, goal, 1, level, too_big, &
                                         timings, stat)
        call t%check('max_dofs at the first level''s: the second is too big', stat%ok() .and. &
                     too_big .and. refiner%next_dofs > first)
    end subroutine limits

    !> hp levels carry no estimate; the bar of a series is hp_run_bar's.
    subroutine bar_is_hp_run_bar(t)
        type(test_suite_t), intent(inout) :: t
        type(hp_refiner_t) :: refiner
        real(wp), parameter :: VALUES(4) = [1.1_wp, 1.01_wp, 1.001_wp, 1.0001_wp]
        logical, parameter :: HAVE(4) = .true.
        real(wp) :: bar, change, expected_bar, expected_change
        logical :: stalled, expected_stalled
        call refiner%series_bar(HAVE, VALUES, [-1.0_wp, -1.0_wp, -1.0_wp, -1.0_wp], &
                                [1, 2, 3, 4], 1.0e-12_wp, bar, change, stalled)
        call hp_run_bar(HAVE, VALUES, 1.0e-12_wp, expected_bar, expected_change, &
                        expected_stalled)
        call t%check('series_bar: hp_run_bar''s bar, change and stall', &
                     abs(bar - expected_bar) <= 0.0_wp .and. &
                     abs(change - expected_change) <= 0.0_wp .and. &
                     (stalled .eqv. expected_stalled) .and. .not. refiner%estimated())
        call t%check('strategy words name hp', refiner%strategy_words() == "strategy = 'hp': ")
    end subroutine bar_is_hp_run_bar

    !> The reference scene on 2 x 2 P1 with &adapt strategy 'hp', p_max and max_dofs; the
    !> refiner begun on it.
    subroutine begin(p_max, max_dofs, inputs, start, refiner, stat)
        integer, intent(in) :: p_max, max_dofs
        type(run_inputs_t), intent(out) :: inputs
        type(problem_t), intent(out) :: start
        type(hp_refiner_t), intent(out) :: refiner
        type(status_t), intent(out) :: stat
        type(config_t) :: config
        call square_scene(2, 'p1', 'right', config)
        config%adapt%tolerance = 1.0e-6_wp
        config%adapt%strategy = 'hp'
        config%adapt%p_max = p_max
        config%adapt%max_dofs = max_dofs
        call translate_input(config, inputs)
        call problem_of(config, start, stat)
        if (stat%ok()) call refiner%begin(inputs%scene, inputs%adapt, start, stat)
    end subroutine begin




end program test_hp_levels
