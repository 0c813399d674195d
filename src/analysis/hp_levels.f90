! SPDX-License-Identifier: MIT
!> The levels of &adapt strategy = 'hp', which every hp loop (hp_adaptive for 'eigen',
!> hp_threshold for 'threshold') climbs alike: level k (k = 1, 2, ...) is the input mesh (its
!> vertices) graded geometrically in k layers toward the singular points (mesh_singular:
!> corners, ends of the boundary parts; factor &adapt sigma), with cell degrees 1 + layer up
!> to min(k + 1, &adapt p_max) (mesh_geometric), on hp_space's space with the interior
!> functions condensed. The loops differ only in what they solve on a level.
module hp_levels
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: to_string, short_real_text, given_real_text
    use real_format, only: real_to_text
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t
    use mesh, only: mesh_t
    use element_types, only: element_corners, element_name
    use mesh_singular, only: singular_vertices
    use mesh_geometric, only: geometric_mesh, cell_layers, layer_degrees, MESH_GRADED, &
                              MESH_BELOW_RESOLUTION
    use hp_space, only: hp_space_t, build_hp_space
    use hp_eigen, only: hp_assembled_problem, factor_hp_stiffness
    use sparse_cholesky, only: cholesky_t
    use adaptive_loop, only: level_dof_limit
    implicit none
    private
    public :: hp_level_degrees

    !> the degrees rise by this per layer away from the singular points (bench_hp's ladder)
    real(wp), parameter :: DEGREE_SLOPE = 1.0_wp
    integer, parameter :: P_MIN = 1   !! the degree of the cells at a singular point

    !> The ladder of levels from one input problem; the current level's mesh, degrees and
    !> space.
    type, public :: hp_ladder_t
        real(wp), allocatable :: points(:, :)   !! the singular points of the input mesh
        integer :: layers = 0                   !! the current level's (0: none yet)
        integer :: max_dofs = 0                 !! a level's free dofs at most
        character(len=:), allocatable :: dof_limit   !! where max_dofs comes from
        character(len=:), allocatable :: stop_reason   !! why the next level cannot be built
        type(mesh_t) :: graded
        integer, allocatable :: degree(:)       !! per cell of graded
        type(hp_space_t) :: space
    contains
        procedure :: begin => ladder_begin
        procedure :: climb => ladder_climb
        procedure :: problem => ladder_problem
        procedure :: factor => ladder_factor
        procedure :: limit_outcome => ladder_limit_outcome
    end type hp_ladder_t

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

    !> Before the first level: the input mesh `start` must have triangles; its singular
    !> points and the dof limit.
    subroutine ladder_begin(this, config, start, stat)
        class(hp_ladder_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: start
        type(status_t), intent(out) :: stat
        if (element_corners(start%mesh%element) /= 3) then
            call stat%fail(STATUS_BAD_INPUT, config%input_file//": &adapt: strategy = 'hp': "// &
                'expected triangles (the mesh has '//element_name(start%mesh%element)// &
                ' cells)')
            return
        end if
        call level_dof_limit(config, this%max_dofs, this%dof_limit)
        this%points = start%mesh%coords(:, singular_vertices(start%mesh))
        this%layers = 0
    end subroutine ladder_begin

    !> The next level's graded mesh, degrees and space. `too_big`: it cannot be built or
    !> solved, and `solved` levels came before it (the loop stops there, stop_reason says
    !> why): more free dofs than the limit, so many cells that it must have (the mesh is
    !> not finished: a level is at least one dof per CELLS_PER_DOF cells), or cells at the
    !> singular points below binary64's resolution of the coordinates. The first level
    !> over an explicit &adapt max_dofs, or over the memory, or below the resolution is
    !> refused (STATUS_BAD_INPUT): so every loop checks its limits before its first level.
    subroutine ladder_climb(this, config, start, solved, too_big, stat)
        class(hp_ladder_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: start
        integer, intent(in) :: solved
        logical, intent(out) :: too_big
        type(status_t), intent(out) :: stat
        !> a P1 mesh has about one free dof per cell (two per node, a node per two cells),
        !> higher degrees more: a level of more cells than 4 max_dofs is over the limit
        integer, parameter :: CELLS_PER_DOF = 4
        real(wp) :: h_min
        integer :: built, max_cells
        too_big = .false.
        this%layers = this%layers + 1
        max_cells = huge(0)
        if (this%max_dofs < (huge(0) - start%mesh%n_cells())/CELLS_PER_DOF) &
            max_cells = CELLS_PER_DOF*this%max_dofs + start%mesh%n_cells()
        call geometric_mesh(start%mesh, this%points, config%adapt%sigma, this%layers, &
                            this%graded, h_min, stat, max_cells, built)
        if (.not. stat%ok()) return
        if (built /= MESH_GRADED) then
            if (built == MESH_BELOW_RESOLUTION) then
                this%stop_reason = 'level '//to_string(this%layers)//'''s cells at the '// &
                    'singular points ('//short_real_text(h_min)//') would be below what '// &
                    'binary64 resolves of the coordinates'
            else
                this%stop_reason = 'level '//to_string(this%layers)//' would have more '// &
                    'than '//to_string(max_cells)//' cells, more dofs than '//this%dof_limit
            end if
            too_big = solved > 0
            if (solved == 0) call stat%fail(STATUS_BAD_INPUT, config%input_file// &
                ": &adapt: strategy = 'hp': "//this%stop_reason//" (&adapt sigma = "// &
                real_to_text(config%adapt%sigma)//'): no level can be solved')
            return
        end if
        this%degree = hp_level_degrees(this%graded, this%points, config%adapt%sigma, h_min, &
                                       this%layers, config%adapt%p_max)
        call build_hp_space(this%graded, this%degree, start%dirichlet_parts, this%space, stat)
        if (.not. stat%ok()) return
        if (config%adapt%max_dofs > 0 .and. this%space%n_free() > this%max_dofs .and. &
            solved == 0) then
            call stat%fail(STATUS_BAD_INPUT, config%input_file//': &adapt: max_dofs = '// &
                to_string(this%max_dofs)//": expected at least the "// &
                to_string(this%space%n_free())//" free dofs of the first hp level")
            return
        end if
        too_big = this%space%n_free() > this%max_dofs .and. solved > 0
        this%stop_reason = 'the next level would have '//to_string(this%space%n_free())// &
            ' dofs, more than '//this%dof_limit
    end subroutine ladder_climb

    !> The outcome of a loop stopped because the next level is too big, its last bar
    !> described by `bar_text`.
    function ladder_limit_outcome(this, tolerance, bar_text) result(outcome)
        class(hp_ladder_t), intent(in) :: this
        real(wp), intent(in) :: tolerance
        character(len=*), intent(in) :: bar_text
        character(len=:), allocatable :: outcome
        outcome = 'tolerance '//given_real_text(tolerance)//' not met: '// &
            this%stop_reason//'; reached error bar '//bar_text
    end function ladder_limit_outcome

    !> The current level as a problem: the graded P1 mesh with the input's parts and
    !> material, the condensed K and the hp contact (nodes: basis functions), dofs%n_free
    !> only; not factored (ladder_factor).
    subroutine ladder_problem(this, config, start, prob, timings, stat)
        class(hp_ladder_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: start
        type(problem_t), intent(out) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        prob%mesh = this%graded
        prob%dirichlet_parts = start%dirichlet_parts
        prob%neumann_parts = start%neumann_parts
        prob%contact_part = start%contact_part
        prob%young = start%young
        prob%poisson = start%poisson
        call hp_assembled_problem(this%graded, this%space, start%contact_part, start%young, &
                                  start%poisson, prob%contact, prob%k, timings, stat)
        if (.not. stat%ok()) then
            call prefix(config, this%layers, stat)
            return
        end if
        prob%dofs%n_free = this%space%n_free()
        call timings%note('hp level '//to_string(this%layers)//': '// &
            to_string(this%graded%n_cells())//' cells, degrees 1 to '// &
            to_string(maxval(this%degree))//', '//to_string(this%space%n_free())//' dofs')
    end subroutine ladder_problem

    !> K of the current level's problem `prob` factored with the contact dofs last.
    subroutine ladder_factor(this, config, prob, chol, timings, stat)
        class(hp_ladder_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(cholesky_t), intent(inout) :: chol
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        call factor_hp_stiffness(prob%k, this%graded, this%space, prob%contact, chol, &
                                 timings, stat)
        if (.not. stat%ok()) call prefix(config, this%layers, stat)
    end subroutine ladder_factor

    subroutine prefix(config, layers, stat)
        type(config_t), intent(in) :: config
        integer, intent(in) :: layers
        type(status_t), intent(inout) :: stat
        stat%message = config%input_file//": &adapt: strategy = 'hp': level "// &
                       to_string(layers)//': '//stat%message
    end subroutine prefix
end module hp_levels
