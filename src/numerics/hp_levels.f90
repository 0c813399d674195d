! SPDX-License-Identifier: MIT
!> The levels of &adapt strategy = 'hp' (refiner_t of adapt_driver), which every goal climbs
!> alike: level k (k = 1, 2, ...) is the input mesh (its vertices) graded geometrically in k
!> layers toward the singular points (mesh_singular: corners, ends of the boundary parts;
!> factor &adapt sigma), with cell degrees 1 + layer up to min(k + 1, &adapt p_max)
!> (mesh_geometric), on hp_space's space with the interior functions condensed. A level
!> carries no estimate of its own: a value's bar comes from its changes between levels
!> (error_bar: hp_run_bar), which also tells a value that has stopped converging, and at the
!> last level from one check that does not rest on those changes: the same cells with every
!> degree raised by one (check_level; error_bar: checked_bar). Where &adapt p_max caps the
!> degrees, more levels refine only toward the singular points: the inner cells keep their
!> size and degree, the changes between levels vanish and their error stays; the check sees
!> it, and cap_words says why climbing on would not help.
module hp_levels
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_SOLVER
    use strings, only: to_string, short_real_text
    use real_format, only: real_to_text
    use timer, only: timings_t
    use scene, only: scene_t
    use method_options, only: adapt_options_t
    use problem, only: problem_t
    use mesh, only: mesh_t
    use element_types, only: element_corners, element_name
    use mesh_singular, only: singular_vertices
    use mesh_geometric, only: geometric_mesh, cell_layers, layer_degrees, MESH_GRADED, &
                              MESH_BELOW_RESOLUTION
    use hp_space, only: build_hp_space
    use hp_basis, only: MAX_HP_DEGREE
    use hp_eigen, only: hp_assembled_problem, factor_hp_stiffness
    use sparse_cholesky, only: cholesky_t
    use error_bar, only: hp_run_bar
    use adapt_driver, only: refiner_t, adapt_goal_t, adapt_level_t, test_failing_level, &
                            injected_failure
    use h_refiner, only: level_dof_limit
    implicit none
    private
    public :: hp_level_degrees, check_words

    !> How an hp value's estimate is named in every report: its change to the previous level
    character(len=*), parameter, public :: HP_ESTIMATE = 'change to the previous hp level'

    !> the degrees rise by this per layer away from the singular points (bench_hp's ladder)
    real(wp), parameter :: DEGREE_SLOPE = 1.0_wp
    integer, parameter :: P_MIN = 1   !! the degree of the cells at a singular point

    type, extends(refiner_t), public :: hp_refiner_t
        real(wp), allocatable :: points(:, :)   !! the singular points of the input mesh
    contains
        procedure :: begin => hp_begin
        procedure :: next => hp_next
        procedure :: factor => hp_factor
        procedure :: series_bar => hp_series_bar
        procedure :: estimated => hp_estimated
        procedure :: strategy_words => hp_strategy_words
        procedure :: checked => hp_checked
        !> the check of a solved level: its cells, every degree raised by one
        procedure :: check_level => hp_check_level
        procedure :: cap_words => hp_cap_words
    end type hp_refiner_t

contains

    !> The degrees of the cells of level `layers` (its graded mesh `graded`, singular
    !> points `points`, h_min of geometric_mesh).
    pure function hp_level_degrees(graded, points, sigma, h_min, layers, p_max) result(degree)
        type(mesh_t), intent(in) :: graded
        real(wp), intent(in) :: points(:, :), sigma, h_min
        integer, intent(in) :: layers, p_max
        integer, allocatable :: degree(:)
        degree = layer_degrees(cell_layers(graded, points, sigma, h_min), P_MIN, DEGREE_SLOPE, &
                               min(layers + 1, p_max))
    end function hp_level_degrees

    !> Before the first level: the input mesh `start` (of the scene `scn`) must have
    !> triangles; its singular points and the dof limit of `adapt`.
    subroutine hp_begin(this, scn, adapt, start, stat)
        class(hp_refiner_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(adapt_options_t), intent(in) :: adapt
        type(problem_t), intent(in) :: start
        type(status_t), intent(out) :: stat
        this%name = scn%name
        this%adapt = adapt
        if (element_corners(start%mesh%element) /= 3) then
            call stat%fail(STATUS_BAD_INPUT, scn%name//": &adapt: strategy = 'hp': "// &
                'expected triangles (the mesh has '//element_name(start%mesh%element)// &
                ' cells)')
            return
        end if
        call level_dof_limit(adapt, this%max_dofs, this%dof_limit)
        this%points = start%mesh%coords(:, singular_vertices(start%mesh))
    end subroutine hp_begin

    !> The next level: its graded mesh, degrees and space and, unless it is too big, its
    !> problem (not factored: hp_factor). Too big: more free dofs than the limit, so many
    !> cells that it must have (the mesh builder stops at CELLS_PER_DOF cells a dof), or
    !> cells at the singular points below binary64's resolution of the coordinates
    !> (stop_reason says which but for the dofs). The first level over an explicit &adapt
    !> max_dofs, or over the memory, or below the resolution is refused (STATUS_BAD_INPUT):
    !> so every loop checks its limits before its first level.
    subroutine hp_next(this, scn, start, goal, solved, level, too_big, timings, stat)
        class(hp_refiner_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: start
        class(adapt_goal_t), intent(in) :: goal
        integer, intent(in) :: solved
        type(adapt_level_t), intent(inout) :: level
        logical, intent(out) :: too_big
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        !> a P1 mesh has about one free dof per cell (two per node, a node per two cells),
        !> higher degrees more: a level of more cells than 4 max_dofs is over the limit
        integer, parameter :: CELLS_PER_DOF = 4
        type(mesh_t) :: graded
        real(wp) :: h_min
        integer :: built, max_cells
        too_big = .false.
        if (allocated(this%stop_reason)) deallocate (this%stop_reason)
        if (solved == 0) level%number = 0
        level%number = level%number + 1
        max_cells = huge(0)
        if (this%max_dofs < (huge(0) - start%mesh%n_cells())/CELLS_PER_DOF) &
            max_cells = CELLS_PER_DOF*this%max_dofs + start%mesh%n_cells()
        call geometric_mesh(start%mesh, this%points, this%adapt%sigma, level%number, graded, &
                            h_min, stat, max_cells, built)
        if (.not. stat%ok()) return
        if (built /= MESH_GRADED) then
            if (built == MESH_BELOW_RESOLUTION) then
                this%stop_reason = 'level '//to_string(level%number)//'''s cells at the '// &
                    'singular points ('//short_real_text(h_min)//') would be below what '// &
                    'binary64 resolves of the coordinates'
            else
                this%stop_reason = 'level '//to_string(level%number)//' would have more '// &
                    'than '//to_string(max_cells)//' cells, more dofs than '//this%dof_limit
            end if
            too_big = solved > 0
            if (solved == 0) call stat%fail(STATUS_BAD_INPUT, scn%name// &
                ": &adapt: strategy = 'hp': "//this%stop_reason//" (&adapt sigma = "// &
                real_to_text(this%adapt%sigma)//'): no level can be solved')
            return
        end if
        level%degree = hp_level_degrees(graded, this%points, this%adapt%sigma, h_min, &
                                        level%number, this%adapt%p_max)
        call build_hp_space(graded, level%degree, start%dirichlet_parts, level%space, stat)
        if (.not. stat%ok()) return
        this%next_dofs = level%space%n_free()
        if (this%adapt%max_dofs > 0 .and. this%next_dofs > this%max_dofs .and. &
            solved == 0) then
            call stat%fail(STATUS_BAD_INPUT, scn%name//': &adapt: max_dofs = '// &
                to_string(this%max_dofs)//": expected at least the "// &
                to_string(this%next_dofs)//" free dofs of the first hp level")
            return
        end if
        too_big = this%next_dofs > this%max_dofs .and. solved > 0
        if (too_big) return
        call level_problem(this%name, start, graded, 'hp level ', level, timings, stat)
    end subroutine hp_next

    !> `level` (its number, space and degrees on the cells of `graded`) as a problem: the
    !> graded P1 mesh with the input's (`start`) parts and material, the condensed K and the
    !> hp contact (nodes: basis functions), dofs%n_free only; `what` heads the timings' note.
    subroutine level_problem(name, start, graded, what, level, timings, stat)
        character(len=*), intent(in) :: name, what
        type(problem_t), intent(in) :: start
        type(mesh_t), intent(in) :: graded
        type(adapt_level_t), intent(inout) :: level
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(problem_t) :: prob
        prob%mesh = graded
        prob%dirichlet_parts = start%dirichlet_parts
        prob%neumann_parts = start%neumann_parts
        prob%contact_part = start%contact_part
        prob%young = start%young
        prob%poisson = start%poisson
        call hp_assembled_problem(graded, level%space, start%contact_part, start%young, &
                                  start%poisson, prob%contact, prob%k, timings, stat)
        if (.not. stat%ok()) then
            call prefix(name, level%number, stat)
            return
        end if
        prob%dofs%n_free = level%space%n_free()
        level%prob = prob
        call timings%note(what//to_string(level%number)//': '// &
            to_string(graded%n_cells())//' cells, degrees '//to_string(minval(level%degree))// &
            ' to '//to_string(maxval(level%degree))//', '//to_string(level%space%n_free())// &
            ' dofs')
    end subroutine level_problem

    pure logical function hp_checked(this)
        class(hp_refiner_t), intent(in) :: this
        hp_checked = .true.
    end function hp_checked

    !> The check of the solved level `last` (its number, graded mesh and degrees): the same
    !> cells with every degree raised by one (at most MAX_HP_DEGREE), as a problem.
    subroutine hp_check_level(this, start, last, check, timings, stat)
        class(hp_refiner_t), intent(in) :: this
        type(problem_t), intent(in) :: start
        type(adapt_level_t), intent(in) :: last
        type(adapt_level_t), intent(out) :: check
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        check%number = last%number
        check%degree = min(last%degree + 1, MAX_HP_DEGREE)
        call build_hp_space(last%prob%mesh, check%degree, start%dirichlet_parts, check%space, &
                            stat)
        if (.not. stat%ok()) then
            call prefix(this%name, last%number, stat)
            return
        end if
        call level_problem(this%name, start, last%prob%mesh, 'hp check of level ', check, &
                           timings, stat)
    end subroutine hp_check_level

    !> How a message names the check of a level (hp_check_level) of `dofs` free dofs: 'the
    !> check with every degree raised by one (D dofs)', with `level`: 'the check of hp level
    !> N with every degree ...'.
    pure function check_words(dofs, level) result(words)
        integer, intent(in) :: dofs
        integer, intent(in), optional :: level
        character(len=:), allocatable :: words
        words = 'the check'
        if (present(level)) words = words//' of hp level '//to_string(level)
        words = words//' with every degree raised by one ('//to_string(dofs)//' dofs)'
    end function check_words

    !> Why more levels cannot lower an error the check found at `last`: &adapt p_max holds
    !> the degrees of its inner cells (level k would give them k + 1), so further levels only
    !> add layers at the singular points. '' while the degrees still rise.
    pure function hp_cap_words(this, last) result(words)
        class(hp_refiner_t), intent(in) :: this
        type(adapt_level_t), intent(in) :: last
        character(len=:), allocatable :: words
        words = ''
        if (last%number + 1 <= this%adapt%p_max) return
        words = '&adapt p_max = '//to_string(this%adapt%p_max)//' caps the degrees, so '// &
            'more levels only add layers at the singular points and leave the error of the '// &
            'inner cells, which keep their size and degree: the cap stops convergence (raise '// &
            'p_max, or give a finer input mesh)'
    end function hp_cap_words

    !> K of `level` factored with the contact dofs last.
    subroutine hp_factor(this, level, chol, timings, stat)
        class(hp_refiner_t), intent(in) :: this
        type(adapt_level_t), intent(in) :: level
        type(cholesky_t), intent(inout) :: chol
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (level%number == test_failing_level()) then
            call stat%fail(STATUS_SOLVER, injected_failure(level%number))
            return
        end if
        call factor_hp_stiffness(level%prob%k, level%prob%mesh, level%space, &
                                 level%prob%contact, chol, timings, stat)
        if (.not. stat%ok()) call prefix(this%name, level%number, stat)
    end subroutine hp_factor

    !> hp_run_bar over the levels since the last one without the value (`estimates` and
    !> `dofs` unused: hp levels carry no estimate).
    pure subroutine hp_series_bar(this, have, values, estimates, dofs, roundoff, bar, change, &
                                  stalled)
        class(hp_refiner_t), intent(in) :: this
        logical, intent(in) :: have(:)
        real(wp), intent(in) :: values(:), estimates(:)
        integer, intent(in) :: dofs(:)
        real(wp), intent(in) :: roundoff
        real(wp), intent(out) :: bar, change
        logical, intent(out) :: stalled
        call hp_run_bar(have, values, roundoff, bar, change, stalled)
    end subroutine hp_series_bar

    pure logical function hp_estimated(this)
        class(hp_refiner_t), intent(in) :: this
        hp_estimated = .false.
    end function hp_estimated

    pure function hp_strategy_words(this) result(words)
        class(hp_refiner_t), intent(in) :: this
        character(len=:), allocatable :: words
        words = "strategy = 'hp': "
    end function hp_strategy_words

    subroutine prefix(name, layers, stat)
        character(len=*), intent(in) :: name
        integer, intent(in) :: layers
        type(status_t), intent(inout) :: stat
        stat%message = name//": &adapt: strategy = 'hp': level "// &
                       to_string(layers)//': '//stat%message
    end subroutine prefix
end module hp_levels
