! SPDX-License-Identifier: MIT
!> The levels of &adapt strategy = 'h' (h_refiner): Doerfler's marking on known indicators;
!> the dof limit of the memory available (8192 bytes per dof); a starting mesh it cannot
!> refine or that is over max_dofs refused; level 0 is the starting problem, and a level with
!> every cell marked is the newest-vertex bisection of each cell, which keeps the domain
!> (the areas sum to 1), the contact segment (length 1) and adds exactly the dofs of the
!> new vertices; the bar of a series is level_bar's.
program test_h_refiner
    use goal_doubles, only: every_cell_t
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_BAD_INPUT
    use testing, only: test_suite_t
    use timer, only: timings_t
    use run_config, only: config_t
    use run_inputs, only: run_inputs_t, translate_input
    use problem, only: problem_t
    use sparse_cholesky, only: cholesky_t
    use scene, only: scene_t
    use error_bar, only: level_bar
    use adapt_driver, only: adapt_goal_t, adapt_level_t, refiner_t
    use h_refiner, only: h_refiner_t, doerfler_marking, adaptive_dof_limit, level_dof_limit
    use fixtures, only: square_scene, problem_of
    implicit none


    type(test_suite_t) :: t

    t%name = 'test_h_refiner'
    call doerfler_marks_the_bulk(t)
    call dof_limits(t)
    call refused_starts(t)
    call every_cell_bisected(t)
    call bar_is_level_bar(t)
    call t%report()

contains

    !> Indicators [1, 5, 2, 2]: theta 0.5 needs the 5 alone (5 >= 5), 0.6 the 5 and the first
    !> 2 (ties in cell order), 1 all four; all zero marks nothing.
    subroutine doerfler_marks_the_bulk(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: ETA(4) = [1.0_wp, 5.0_wp, 2.0_wp, 2.0_wp]
        integer, allocatable :: marked(:)
        allocate (marked(0))   ! (gfortran 12 warns of an unallocated one at -O3)
        marked = doerfler_marking(ETA, 0.5_wp)
        call t%check('theta 0.5: the largest alone', size(marked) == 1 .and. marked(1) == 2)
        marked = doerfler_marking(ETA, 0.6_wp)
        call t%check('theta 0.6: the two largest, ties in cell order', size(marked) == 2)
        if (size(marked) == 2) call t%check('theta 0.6: cells 2, 3', all(marked == [2, 3]))
        marked = doerfler_marking(ETA, 1.0_wp)
        call t%check('theta 1: every cell', size(marked) == 4)
        marked = doerfler_marking([0.0_wp, 0.0_wp], 0.5_wp)
        call t%check('no indicator: nothing marked', size(marked) == 0)
    end subroutine doerfler_marks_the_bulk

    !> 8192 bytes per dof: 8192 * 1000 bytes allow 1000 dofs, an unknown memory (-1) no
    !> limit, an explicit max_dofs is itself and named so.
    subroutine dof_limits(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        character(len=:), allocatable :: words
        integer :: max_dofs
        call t%check('8192000 bytes: 1000 dofs', adaptive_dof_limit(8192000_i8) == 1000)
        call t%check('unknown memory: no limit', adaptive_dof_limit(-1_i8) == huge(0))
        config%adapt%tolerance = 1.0e-6_wp
        config%adapt%max_dofs = 777
        call translate_input(config, inputs)
        call level_dof_limit(inputs%adapt, max_dofs, words)
        call t%check('max_dofs = 777: itself, named', max_dofs == 777 .and. &
                     words == 'max_dofs = 777')
    end subroutine dof_limits

    !> Q1 cells (no bisection) and P4 ones (no enriched space) are refused, naming the cells;
    !> so is a start over an explicit max_dofs, naming its dofs.
    subroutine refused_starts(t)
        type(test_suite_t), intent(inout) :: t
        type(status_t) :: stat
        call begin_on('q1', 0, stat)
        call t%check('q1: bad input naming the cells', stat%code == STATUS_BAD_INPUT .and. &
                     index(stat%message, 'q1 cells') > 0)
        call begin_on('p4', 0, stat)
        call t%check('p4: bad input naming the cells', stat%code == STATUS_BAD_INPUT .and. &
                     index(stat%message, 'p4 cells') > 0)
        call begin_on('p1', 10, stat)
        call t%check('max_dofs 10 below the 12 of 2 x 2 P1: bad input naming both', &
                     stat%code == STATUS_BAD_INPUT .and. &
                     index(stat%message, 'max_dofs = 10: expected at least the 12 free dofs') > 0)
    end subroutine refused_starts

    subroutine begin_on(element, max_dofs, stat)
        character(len=*), intent(in) :: element
        integer, intent(in) :: max_dofs
        type(status_t), intent(out) :: stat
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        type(problem_t) :: start
        type(h_refiner_t) :: refiner
        call square_scene(2, element, 'right', config)
        config%adapt%tolerance = 1.0e-6_wp
        config%adapt%max_dofs = max_dofs
        call translate_input(config, inputs)
        call problem_of(config, start, stat)
        if (stat%ok()) call refiner%begin(inputs%scene, inputs%adapt, start, stat)
    end subroutine begin_on


    !> 2 x 2 P1 (8 triangles, 3 x 3 vertices, the top 3 fixed: 12 free dofs): level 0 is the
    !> start; with every cell marked, level 1 has each triangle bisected at least once (the
    !> closure may bisect more): the areas still sum to 1 and the contact edges to the
    !> bottom's length 1 (halves of binary fractions: exact), and every vertex off the fixed
    !> top has its 2 free dofs; K of level 1 factors (its Dirichlet part makes it positive
    !> definite) and the factor solves K x = b for a known x (the contact dofs ordered last
    !> change only the order of the work; K's condition is small for 12-odd dofs of a unit
    !> square, so 1e-10 n is generous).
    subroutine every_cell_bisected(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        type(problem_t) :: start
        type(h_refiner_t) :: refiner
        type(every_cell_t) :: goal
        type(adapt_level_t) :: level
        type(timings_t) :: timings
        type(cholesky_t) :: chol
        type(status_t) :: stat
        logical :: too_big
        real(wp) :: area, length, d1(2), d2(2)
        real(wp), allocatable :: x(:, :), b(:, :), solved(:, :)
        integer :: i, n
        integer :: c, e, bottom
        call square_scene(2, 'p1', 'right', config)
        config%adapt%tolerance = 1.0e-6_wp
        call translate_input(config, inputs)
        call problem_of(config, start, stat)
        if (stat%ok()) call refiner%begin(inputs%scene, inputs%adapt, start, stat)
        if (stat%ok()) call refiner%next(inputs%scene, start, goal, 0, level, too_big, &
                                         timings, stat)
        call t%check('level 0: the starting problem', stat%ok() .and. level%number == 0 .and. &
                     level%prob%dofs%n_free == start%dofs%n_free .and. .not. too_big)
        if (.not. stat%ok()) return
        goal%n_cells = level%prob%mesh%n_cells()
        call refiner%next(inputs%scene, start, goal, 1, level, too_big, timings, stat)
        call t%check('level 1: built, not too big', stat%ok() .and. .not. too_big .and. &
                     level%number == 1)
        if (.not. stat%ok()) return
        associate (m => level%prob%mesh)
            call t%check('level 1: every triangle bisected', m%n_cells() >= 16)
            area = 0.0_wp
            do c = 1, m%n_cells()
                d1 = m%coords(:, m%cells(2, c)) - m%coords(:, m%cells(1, c))
                d2 = m%coords(:, m%cells(3, c)) - m%coords(:, m%cells(1, c))
                area = area + 0.5_wp*abs(d1(1)*d2(2) - d1(2)*d2(1))
            end do
            ! areas of halves of the unit square's triangles: binary fractions, exact
            call t%check('level 1: the cells cover the unit square', abs(area - 1.0_wp) <= 0.0_wp)
            bottom = m%part_index('bottom')
            length = 0.0_wp
            do e = 1, size(m%edges, 2)
                if (m%edge_part(e) == bottom) length = length + &
                    norm2(m%coords(:, m%edges(2, e)) - m%coords(:, m%edges(1, e)))
            end do
            call t%check('level 1: the contact edges cover the bottom', &
                         abs(length - 1.0_wp) <= 0.0_wp)
            call t%check('level 1: 2 free dofs per vertex off the top', &
                         level%prob%dofs%n_free == 2*count(abs(m%coords(2, :) - 1.0_wp) > 0.0_wp))
        end associate
        call refiner%factor(level, chol, timings, stat)
        call t%check('level 1: K factored (positive definite)', stat%ok())
        if (.not. stat%ok()) return
        n = level%prob%k%n()
        allocate(x(n, 1), b(n, 1), solved(n, 1))
        x(:, 1) = [(real(i, wp), i = 1, n)]
        call level%prob%k%matvec(x(:, 1), b(:, 1))
        call chol%solve(b, solved, stat)
        call t%check('level 1: the factor solves K x = K (1, 2, ..., n) for x = (1, 2, ..., n)', &
                     stat%ok() .and. maxval(abs(solved - x)) < 1.0e-10_wp*n)
        call chol%free()
    end subroutine every_cell_bisected

    !> An h level's bar is level_bar over the window of levels with an estimate, at the
    !> element's degree (P2: 2); no change, never stalled.
    subroutine bar_is_level_bar(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        type(problem_t) :: start
        type(h_refiner_t) :: refiner
        type(status_t) :: stat
        real(wp), parameter :: VALUES(3) = [1.0_wp, 1.01_wp, 1.011_wp]
        real(wp), parameter :: ESTIMATES(3) = [1.0e-2_wp, 1.0e-3_wp, 2.0e-4_wp]
        integer, parameter :: DOFS(3) = [100, 300, 900]
        real(wp) :: bar, change
        logical :: stalled
        call square_scene(2, 'p2', 'right', config)
        config%adapt%tolerance = 1.0e-6_wp
        call translate_input(config, inputs)
        call problem_of(config, start, stat)
        if (stat%ok()) call refiner%begin(inputs%scene, inputs%adapt, start, stat)
        if (.not. stat%ok()) return
        call refiner%series_bar([.true., .true., .true.], VALUES, ESTIMATES, DOFS, 1.0e-9_wp, &
                                bar, change, stalled)
        call t%check('series_bar: level_bar at degree 2', &
                     abs(bar - level_bar(ESTIMATES, VALUES, DOFS, 2, 1.0e-9_wp)) <= 0.0_wp .and. &
                     change < 0.0_wp .and. .not. stalled .and. refiner%estimated())
    end subroutine bar_is_level_bar




end program test_h_refiner
