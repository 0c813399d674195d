! SPDX-License-Identifier: MIT
!> The levels of &adapt strategy = 'h' (refiner_t of adapt_driver): level 0 is the starting
!> problem; each next level refines the cells the goal marks (Doerfler's bulk criterion on its
!> cell indicators: doerfler_marking) by newest-vertex bisection (mesh_refine: conforming and
!> nested, parts and the contact segment carried to the children) at the element's degree,
!> and builds its problem in memory. Each level carries the goal's own error estimate (the
!> dual-weighted residual of module enrichment, the element one degree higher on the same
!> cells); a level's bar is level_bar's over a window of levels (error_bar). The dof limit
!> of every refiner (level_dof_limit) is here too.
module h_refiner
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_BAD_INPUT
    use system_memory, only: available_memory_bytes
    use strings, only: to_string, short_real_text, given_real_text
    use timer, only: wall_time, timings_t, PHASE_ASSEMBLY
    use scene, only: scene_t
    use method_options, only: adapt_options_t
    use mesh, only: mesh_t
    use mesh_refine, only: refinable_mesh_t, build_refinable_mesh
    use element_types, only: element_name, element_degree
    use problem, only: problem_t, build_problem, explain_singular_k
    use enrichment, only: enriched_element
    use sorting, only: sort_index
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness
    use error_bar, only: level_bar
    use adapt_driver, only: refiner_t, adapt_goal_t, adapt_level_t
    implicit none
    private
    public :: doerfler_marking, adaptive_dof_limit, level_dof_limit

    !> Peak bytes per free dof of one adaptive level (its factor, the enriched problem of
    !> the estimate one degree higher and its factor, the mesh tree): 4.7 kB measured for P3
    !> at 34 200 and 254 388 dofs (168 MB, 1.2 GB); with a margin for the next level's
    !> peak.
    real(wp), parameter :: BYTES_PER_DOF = 8192.0_wp
    !> The extra bisections per level of the cells at a point the goal grades toward
    !> (adapt_goal_t: grade): two halve their size, so with the level's own bisection the
    !> cells there go from h to h/2^2.5 where the rest go to h/sqrt(2) (a mode past a corner's
    !> crossing lives below the scale of uniform levels: docs/adaptive.md)
    integer, parameter, public :: GRADE_PASSES = 4

    type, extends(refiner_t), public :: h_refiner_t
        type(scene_t) :: scene                !! for the levels' problems and messages
        type(refinable_mesh_t) :: tree        !! the bisection history of the starting mesh
        integer :: element = 0                !! of every level
    contains
        procedure :: begin => h_begin
        procedure :: next => h_next
        procedure :: factor => h_factor
        procedure :: series_bar => h_series_bar
        procedure :: estimated => h_estimated
        procedure :: strategy_words => h_strategy_words
        procedure :: checked => h_checked
        procedure :: cap_words => h_cap_words
        procedure :: graded_level => h_graded_level
    end type h_refiner_t

contains

    !> The starting problem's cells must have an enriched space (triangles P1 to P3) and, with
    !> an explicit max_dofs, at most that many free dofs (STATUS_BAD_INPUT otherwise).
    subroutine h_begin(this, scn, adapt, start, stat)
        class(h_refiner_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(adapt_options_t), intent(in) :: adapt
        type(problem_t), intent(in) :: start
        type(status_t), intent(out) :: stat
        this%name = scn%name
        this%scene = scn
        this%adapt = adapt
        this%element = start%mesh%element
        if (enriched_element(this%element) == 0) then
            call stat%fail(STATUS_BAD_INPUT, scn%name//': &adapt: tolerance = '// &
                given_real_text(adapt%tolerance)//': expected 0 for '// &
                element_name(this%element)//' cells (adaptation refines triangles p1, p2 or p3)')
            return
        end if
        call level_dof_limit(adapt, this%max_dofs, this%dof_limit)
        if (adapt%max_dofs > 0 .and. start%dofs%n_free > this%max_dofs) then
            call stat%fail(STATUS_BAD_INPUT, scn%name//': &adapt: max_dofs = '// &
                to_string(adapt%max_dofs)//': expected at least the '// &
                to_string(start%dofs%n_free)//' free dofs of the starting mesh')
            return
        end if
        call build_refinable_mesh(start%mesh, this%tree, stat)
        if (.not. stat%ok()) stat%message = scn%name//': &adapt: '//stat%message
    end subroutine h_begin

    !> Level 0: the starting problem; then the cells `goal` marks refined, the level's
    !> problem built (its time and sizes in `timings`).
    subroutine h_next(this, scn, start, goal, solved, level, too_big, timings, stat)
        class(h_refiner_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: start
        class(adapt_goal_t), intent(in) :: goal
        integer, intent(in) :: solved
        type(adapt_level_t), intent(inout) :: level
        logical, intent(out) :: too_big
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(mesh_t) :: refined
        type(problem_t) :: next
        integer, allocatable :: marked(:)
        real(wp) :: level_start

        too_big = .false.
        if (solved == 0) then
            level%number = 0
            level%prob = start
            return
        end if
        level_start = wall_time()
        allocate (marked(0))   ! (gfortran 12 warns of an unallocated one at -O3)
        marked = goal%mark(this%adapt%theta)
        call this%tree%refine(marked, stat)
        ! goal%grade unallocated: not present, nothing graded
        if (stat%ok()) call graded_problem(scn, this%element, this%tree, refined, next, stat, &
                                           goal%grade)
        if (.not. stat%ok()) return
        call timings%add(PHASE_ASSEMBLY, wall_time() - level_start, ': level '// &
            to_string(level%number + 1)//', '//to_string(size(marked))//' cells marked, '// &
            to_string(refined%n_cells())//' cells, '//to_string(next%dofs%n_free)//' dofs')
        this%next_dofs = next%dofs%n_free
        too_big = next%dofs%n_free > this%max_dofs
        if (too_big) return
        level%prob = next
        level%number = level%number + 1
    end subroutine h_next

    !> A level's problem from `tree`: its cells at `points` (where present) bisected
    !> GRADE_PASSES times more, then its mesh of `element` cells (`mesh`) and the problem on
    !> it. Every h level (h_next) and the graded check (h_graded_level) are made this way.
    subroutine graded_problem(scn, element, tree, mesh, prob, stat, points)
        type(scene_t), intent(in) :: scn
        integer, intent(in) :: element
        type(refinable_mesh_t), intent(inout) :: tree
        type(mesh_t), intent(out) :: mesh
        type(problem_t), intent(out) :: prob
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: points(:, :)
        if (present(points)) call grade_toward(tree, points, stat)
        if (stat%ok()) call tree%to_mesh(element, mesh, stat)
        if (stat%ok()) call build_problem(scn, prob, stat, given_mesh=mesh)
    end subroutine graded_problem

    !> The cells of `tree` at each of `points` (a vertex there) bisected GRADE_PASSES times.
    subroutine grade_toward(tree, points, stat)
        type(refinable_mesh_t), intent(inout) :: tree
        real(wp), intent(in) :: points(:, :)
        type(status_t), intent(out) :: stat
        logical, allocatable :: at(:)
        real(wp) :: near
        integer :: pass, i, c
        if (size(points, 2) == 0) return
        ! the points are vertices of the starting mesh: equal to round-off of its extent
        near = 1.0e-9_wp*maxval(abs(tree%coords))
        do pass = 1, GRADE_PASSES
            allocate (at(tree%n_vertices()), source=.false.)
            do i = 1, size(points, 2)
                at = at .or. (abs(tree%coords(1, :) - points(1, i)) <= near .and. &
                              abs(tree%coords(2, :) - points(2, i)) <= near)
            end do
            call tree%refine(pack([(c, c=1, tree%n_cells())], &
                                  [(any(at(tree%cells(:, c))), c=1, tree%n_cells())]), stat)
            deallocate (at)
            if (.not. stat%ok()) return
        end do
    end subroutine grade_toward

    !> K of `level` factored with the contact dofs last; a singular K explained by the scene.
    subroutine h_factor(this, level, chol, timings, stat)
        class(h_refiner_t), intent(in) :: this
        type(adapt_level_t), intent(in) :: level
        type(cholesky_t), intent(inout) :: chol
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        call factor_stiffness(level%prob%k, level%prob%mesh, level%prob%dofs, &
                              level%prob%contact, chol, timings, stat)
        call explain_singular_k(this%scene, level%prob%mesh, stat)
    end subroutine h_factor

    !> level_bar over the window of the levels with an estimate (`have` unused: a level without
    !> the value has no estimate either); no change, never stalled.
    pure subroutine h_series_bar(this, have, values, estimates, dofs, roundoff, bar, change, &
                                 stalled)
        class(h_refiner_t), intent(in) :: this
        logical, intent(in) :: have(:)
        real(wp), intent(in) :: values(:), estimates(:)
        integer, intent(in) :: dofs(:)
        real(wp), intent(in) :: roundoff
        real(wp), intent(out) :: bar, change
        logical, intent(out) :: stalled
        bar = level_bar(estimates, values, dofs, element_degree(this%element), roundoff)
        change = -1.0_wp
        stalled = .false.
    end subroutine h_series_bar

    !> The last level is offered to the goal's check: each h level carries its own estimate,
    !> but an estimate one degree higher on the same cells cannot see a mode that lives below
    !> the cells' scale at an end past its crossing; the goal checks those values on the
    !> last mesh graded toward that end (graded_level) and checks nothing else.
    pure logical function h_checked(this)
        class(h_refiner_t), intent(in) :: this
        h_checked = .true.
    end function h_checked

    !> The check of the solved level `last` toward `points` (vertices of the starting mesh):
    !> its mesh with the cells at each point bisected GRADE_PASSES times more, as a problem at
    !> the same degree, made as a level is (graded_problem).
    subroutine h_graded_level(this, last, points, check, timings, stat)
        class(h_refiner_t), intent(in) :: this
        type(adapt_level_t), intent(in) :: last
        real(wp), intent(in) :: points(:, :)
        type(adapt_level_t), intent(out) :: check
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(refinable_mesh_t) :: tree
        type(mesh_t) :: graded
        real(wp) :: begin
        begin = wall_time()
        check%number = last%number
        call build_refinable_mesh(last%prob%mesh, tree, stat)
        if (stat%ok()) call graded_problem(this%scene, this%element, tree, graded, check%prob, &
                                           stat, points)
        if (.not. stat%ok()) then
            stat%message = this%name//': the graded check of h level '// &
                to_string(last%number)//': '//stat%message
            return
        end if
        call timings%add(PHASE_ASSEMBLY, wall_time() - begin, ': graded check of level '// &
            to_string(last%number)//', '//to_string(graded%n_cells())//' cells, '// &
            to_string(check%prob%dofs%n_free)//' dofs')
    end subroutine h_graded_level

    pure function h_cap_words(this, last) result(words)
        class(h_refiner_t), intent(in) :: this
        type(adapt_level_t), intent(in) :: last
        character(len=:), allocatable :: words
        words = ''
    end function h_cap_words

    pure logical function h_estimated(this)
        class(h_refiner_t), intent(in) :: this
        h_estimated = .true.
    end function h_estimated

    pure function h_strategy_words(this) result(words)
        class(h_refiner_t), intent(in) :: this
        character(len=:), allocatable :: words
        words = ''
    end function h_strategy_words

    !> The most free dofs a level may have (&adapt max_dofs, or what the memory available
    !> now allows when it is 0) and the words that name that limit in an outcome.
    subroutine level_dof_limit(adapt, max_dofs, dof_limit)
        type(adapt_options_t), intent(in) :: adapt
        integer, intent(out) :: max_dofs
        character(len=:), allocatable, intent(out) :: dof_limit
        max_dofs = adapt%max_dofs
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
end module h_refiner
