! SPDX-License-Identifier: MIT
!> The discrete problem every analysis starts from: mesh, boundary parts, free dofs, the
!> contact boundary and the stiffness matrix K on the free dofs.
module problem
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_SINGULAR
    use strings, only: NAME_LEN, split_names, to_string, short => short_real_text, joined
    use real_format, only: real_to_text
    use run_config, only: UNSCALED_YOUNG_RANGE, UNSCALED_SIZE_RANGE
    use scene, only: scene_t, MESH_RECTANGLE, MESH_GMSH
    use mesh, only: mesh_t
    use cell_geometry, only: cell_thinness
    use mesh_structured, only: structured_rectangle
    use mesh_gmsh, only: read_gmsh
    use mesh_check, only: check_mesh
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use elasticity, only: lame_ratio
    use contact_boundary, only: contact_t, build_contact
    use csr_matrix, only: csr_matrix_t
    use unit_scaling, only: units_t, units_of
    implicit none
    private
    public :: problem_t, build_problem, assemble_all_dofs, explain_singular_k
    public :: SINGULAR_LAME_RATIO, SINGULAR_ASPECT_RATIO

    !> A K that CHOLMOD finds numerically singular is blamed on &material poisson from this
    !> L/G = 2 nu / (1 - 2 nu): K's pivots then span a factor L/G at least (the volumetric
    !> stiffness L against the shear G), and CHOLMOD gives up at a pivot ratio of 1e3 eps;
    !> seen at L/G = 5e12 (nu = 0.4999999999999) while 5e11 still solves to round-off.
    real(wp), parameter :: SINGULAR_LAME_RATIO = 1.0e10_wp
    !> ... and on the rectangle's cell shape from this aspect ratio: cond(K) grows like its
    !> square; seen singular at 1e6, backward errors of 1e-8 (warned) at 1e4.
    real(wp), parameter :: SINGULAR_ASPECT_RATIO = 1.0e4_wp
    !> ... and on a sliver cell (a mesh file's: a rectangle's cells are all alike) whose
    !> |det J| / diameter^2 (cell_thinness) is below this: its stiffness, ~ 1 / thinness
    !> times the others', alone spans half of the 1 / (1e3 eps) pivot ratio CHOLMOD allows.
    !> Seen singular at 1e-13 (a triangle with a corner 1e-13 off the opposite side).
    real(wp), parameter :: SLIVER_THINNESS = 1.0e-8_wp

    type, public :: problem_t
        type(mesh_t) :: mesh
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: k                  !! stiffness on the free dofs
        !> Only for analyses with non-zero Dirichlet data (with_all_dofs): K and Gamma_C on all
        !> dofs, prescribed ones included; k is then their restriction to the free dofs.
        type(dof_map_t) :: all_dofs
        type(csr_matrix_t) :: k_all
        type(contact_t) :: all_contact
        integer, allocatable :: dirichlet_parts(:), neumann_parts(:)
        integer :: contact_part = 0
        real(wp) :: young = 0.0_wp
        real(wp) :: poisson = 0.0_wp
        !> The units of k and contact%mass (units_t): scaled for the eigen analyses (see
        !> build_problem), the input's for 'branch' and 'solve'.
        type(units_t) :: units
    end type problem_t

contains

    !> Mesh the scene, resolve its boundary part names, number the free dofs, collect the
    !> contact boundary and assemble K. Without `input_units_for` (the eigen analyses) K and
    !> Gamma_C are in the scaled units of prob%units; prob%mesh keeps the input coordinates.
    !> With it (the name of an analysis with non-zero Dirichlet data, for messages) K and
    !> Gamma_C are in the input's units and also kept on all dofs. `given_mesh` replaces the
    !> scene's own mesh (a level of an adaptive loop, a halved mesh).
    subroutine build_problem(scn, prob, stat, input_units_for, given_mesh)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(out) :: prob
        type(status_t), intent(out) :: stat
        character(len=*), intent(in), optional :: input_units_for
        type(mesh_t), intent(in), optional :: given_mesh
        integer, allocatable :: contact_parts(:)

        if (present(given_mesh)) then
            prob%mesh = given_mesh
        else
            call make_mesh(stat)
            if (.not. stat%ok()) return
        end if
        call resolve_parts('dirichlet', scn%dirichlet, prob%dirichlet_parts, stat)
        if (.not. stat%ok()) return
        call resolve_parts('neumann', scn%neumann, prob%neumann_parts, stat)
        if (.not. stat%ok()) return
        call resolve_parts('contact', scn%contact, contact_parts, stat)
        if (.not. stat%ok()) return
        prob%contact_part = contact_parts(1)
        call check_mesh(prob%mesh, prob%dirichlet_parts, prob%neumann_parts, contact_parts, stat)
        if (.not. stat%ok()) then
            if (.not. allocated(prob%mesh%file)) &
                stat%message = scn%name//': &mesh: '//stat%message
            return
        end if
        prob%young = scn%material%young
        prob%poisson = scn%material%poisson
        call build_dof_map(prob%mesh, prob%dirichlet_parts, prob%dofs, stat)
        if (.not. stat%ok()) return

        if (present(input_units_for)) then
            call all_dof_system(stat)
        else
            call unit_system(stat)
        end if

    contains

        !> The mesh of the scene's source: the rectangle generator or a Gmsh file.
        subroutine make_mesh(stat)
            type(status_t), intent(out) :: stat
            select case (scn%source)
            case (MESH_RECTANGLE)
                call structured_rectangle(scn%width, scn%height, scn%nx, scn%ny, scn%element, &
                                          scn%diagonal, prob%mesh, stat)
                if (.not. stat%ok()) stat%message = scn%name//': &mesh: '//stat%message
            case (MESH_GMSH)
                ! The element type comes from the file; &mesh element is not used.
                call read_gmsh(scn%file, prob%mesh, stat)
            end select
        end subroutine make_mesh

        !> Gamma_C on the free dofs; the message of a generated mesh names the input file (a
        !> mesh-file message already names the file and line).
        subroutine free_contact(stat)
            type(status_t), intent(out) :: stat
            call build_contact(prob%mesh, prob%contact_part, prob%dofs, prob%contact, stat)
            if (.not. stat%ok() .and. .not. allocated(prob%mesh%file)) &
                stat%message = scn%name//': &mesh: contact: '//stat%message
        end subroutine free_contact

        !> The eigen analyses: K and Gamma_C in the scaled units (units_t), where E and the
        !> mesh size are in [1, 2). prob%mesh keeps the input coordinates.
        subroutine unit_system(stat)
            type(status_t), intent(out) :: stat
            real(wp), allocatable :: physical_coords(:, :)
            prob%units = units_of(prob%young, prob%mesh%coords)
            allocate (physical_coords, source=prob%mesh%coords)
            prob%mesh%coords = prob%units%scaled_lengths(prob%mesh%coords)
            ! a coordinate more than ~600 decades below the largest (width = 1e-300 with
            ! height = 1e300) leaves the normal range in any one unit
            if (any(abs(physical_coords) > 0.0_wp .and. &
                    abs(prob%mesh%coords) < tiny(1.0_wp))) then
                call stat%fail(STATUS_BAD_INPUT, scn%name//': &mesh: coordinates '// &
                    'from '//short(minval(abs(physical_coords), abs(physical_coords) > 0.0_wp)) &
                    //' to '//short(maxval(abs(physical_coords)))//' in magnitude: more than '// &
                    'the 2.2e-308 to 1.8e308 of binary64 can hold in one unit of length')
            else
                call free_contact(stat)
                if (stat%ok()) call assemble_stiffness(prob%mesh, prob%dofs, &
                    prob%units%scaled_young(prob%young), prob%poisson, prob%k, stat)
            end if
            call move_alloc(physical_coords, prob%mesh%coords)
        end subroutine unit_system

        !> 'branch' and 'solve': the input's units (their loads and displacements have units),
        !> within a range of E and of the size the arithmetic holds; K assembled once on all
        !> dofs with Gamma_C, and K on the free dofs its restriction.
        subroutine all_dof_system(stat)
            type(status_t), intent(out) :: stat
            real(wp) :: size_of_mesh
            call free_contact(stat)
            if (.not. stat%ok()) return
            size_of_mesh = maxval(abs(prob%mesh%coords))
            if (prob%young > UNSCALED_YOUNG_RANGE .or. &
                prob%young < 1.0_wp/UNSCALED_YOUNG_RANGE) then
                call stat%fail(STATUS_BAD_INPUT, scn%name//': &material: young = '// &
                    real_to_text(prob%young)//': expected 1e-100 <= young <= 1e100 for '// &
                    'analysis '''//input_units_for//''', which works in the '// &
                    'input''s units (the eigen analyses rescale E away)')
                return
            end if
            if (size_of_mesh > UNSCALED_SIZE_RANGE .or. &
                size_of_mesh < 1.0_wp/UNSCALED_SIZE_RANGE) then
                call stat%fail(STATUS_BAD_INPUT, scn%name//': &mesh: the largest '// &
                    '|coordinate| is '//short(size_of_mesh)//': expected 1e-50 to 1e50 '// &
                    'for analysis '''//input_units_for//''', which works in the '// &
                    'input''s units (the eigen analyses scale the size away)')
                return
            end if
            call assemble_all_dofs(prob%mesh, prob%young, prob%poisson, prob%contact_part, &
                                   prob%all_dofs, prob%k_all, prob%all_contact, stat)
            if (stat%ok()) prob%k = prob%k_all%restrict(free_numbers(prob%dofs))
        end subroutine all_dof_system

        !> The free number of every dof in the numbering of all dofs (0 where prescribed).
        pure function free_numbers(dofs) result(numbers)
            type(dof_map_t), intent(in) :: dofs
            integer :: numbers(size(dofs%free_dof))
            numbers = reshape(dofs%free_dof, [size(dofs%free_dof)])
        end function free_numbers

        !> Indices of the mesh's boundary parts named in `list`.
        subroutine resolve_parts(variable, list, parts, stat)
            character(len=*), intent(in) :: variable, list
            integer, allocatable, intent(out) :: parts(:)
            type(status_t), intent(out) :: stat
            character(len=NAME_LEN), allocatable :: names(:)
            character(len=:), allocatable :: known
            integer :: i
            allocate (names(0))   ! see split_names: avoids a false -Wuninitialized at -O3
            names = split_names(list)
            allocate (parts(size(names)))
            do i = 1, size(names)
                parts(i) = prob%mesh%part_index(trim(names(i)))
                if (parts(i) == 0) then
                    known = joined(prob%mesh%part_names)
                    if (allocated(prob%mesh%file)) then
                        ! A Gmsh file: the parts are its 1D physical groups.
                        call stat%fail(STATUS_BAD_INPUT, scn%name//': &mesh: '// &
                            variable//' = '''//trim(list)//''': the mesh file '// &
                            prob%mesh%file//' has no 1D physical group '''//trim(names(i))// &
                            ''' (it has: '//known//')')
                        return
                    end if
                    call stat%fail(STATUS_BAD_INPUT, scn%name//': &mesh: '//variable// &
                        ' = '''//trim(list)//''': the mesh has no boundary part '''// &
                        trim(names(i))//''' (it has: '//known//')')
                    return
                end if
            end do
        end subroutine resolve_parts

    end subroutine build_problem

    !> When `stat` says K is singular (STATUS_SINGULAR) and the input explains it, one line
    !> naming that input instead (STATUS_BAD_INPUT): poisson so near 0.5, or rectangle cells
    !> so elongated, that K is singular in binary64 although not in exact arithmetic; or, still
    !> STATUS_SINGULAR, naming a sliver cell of `m` (a mesh file's) as the likely cause.
    subroutine explain_singular_k(scn, m, stat)
        type(scene_t), intent(in) :: scn
        type(mesh_t), intent(in) :: m
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: detail, place
        real(wp) :: ratio, aspect   !! ratio: L/G; aspect: log10 of the cells' aspect ratio
        real(wp) :: thinness
        integer :: at, worst

        if (stat%code /= STATUS_SINGULAR) return
        detail = ''
        at = index(stat%message, '(CHOLMOD')
        if (at > 0) detail = ' '//stat%message(at:)
        ratio = lame_ratio(scn%material%poisson)
        if (ratio >= SINGULAR_LAME_RATIO) then
            call stat%fail(STATUS_BAD_INPUT, scn%name//': &material: poisson = '// &
                real_to_text(scn%material%poisson)//': so close to 0.5 that L/G = 2 nu / '// &
                '(1 - 2 nu) = '//short(ratio)//' makes K numerically singular'//detail// &
                '; expected L/G below '//short(SINGULAR_LAME_RATIO)//' (poisson <= 0.49999999995)')
            return
        end if
        ! a rectangle's cells are all alike: their aspect ratio, below, says more
        worst = 0
        thinness = huge(1.0_wp)
        if (scn%source /= MESH_RECTANGLE) call thinnest_cell(m, worst, thinness)
        if (worst > 0 .and. thinness < SLIVER_THINNESS) then
            place = 'cell '//to_string(worst)
            if (allocated(m%file) .and. allocated(m%cell_line)) place = 'the cell at '// &
                m%file//':'//to_string(m%cell_line(worst))
            stat%message = scn%name//': &mesh: the stiffness matrix K is singular, '// &
                'likely from a sliver: '//place//' has |det J| = '//short(thinness)// &
                ' x its squared diameter (a near-zero area; its stiffness swamps the '// &
                'others'')'//detail//'; expected cells with |det J| above '// &
                short(SLIVER_THINNESS)//' x their squared diameter (remesh)'
            return
        end if
        if (scn%source /= MESH_RECTANGLE) return
        ! log10 of the aspect ratio: the ratio can overflow (width = 1e-300, height = 1e300)
        aspect = abs(log10(scn%width/scn%nx) - log10(scn%height/scn%ny))
        if (aspect >= log10(SINGULAR_ASPECT_RATIO)) then
            call stat%fail(STATUS_BAD_INPUT, scn%name//': &mesh: width = '// &
                real_to_text(scn%width)//', height = '// &
                real_to_text(scn%height)//', nx = '//to_string(scn%nx)// &
                ', ny = '//to_string(scn%ny)//': cells of aspect ratio 1e'// &
                to_string(nint(aspect))//' make K numerically singular (its condition grows '// &
                'like the square)'//detail//'; expected (width / nx) / (height / ny) within '// &
                'a factor '//short(SINGULAR_ASPECT_RATIO)//' of 1')
        end if
    end subroutine explain_singular_k

    !> The cell of smallest cell_thinness and its thinness (worst = 0: no cells).
    subroutine thinnest_cell(m, worst, thinness)
        type(mesh_t), intent(in) :: m
        integer, intent(out) :: worst
        real(wp), intent(out) :: thinness
        real(wp) :: x
        integer :: c
        worst = 0
        thinness = huge(1.0_wp)
        do c = 1, m%n_cells()
            x = cell_thinness(m%element, m%coords(:, m%cells(:, c)))
            if (x < thinness) then
                worst = c
                thinness = x
            end if
        end do
    end subroutine thinnest_cell

    !> K and the contact boundary on all dofs (none prescribed), in the node-major numbering
    !> of dof_map::all_dof: what the compliance problem with Dirichlet data needs.
    subroutine assemble_all_dofs(m, young, poisson, contact_part, all_dofs, k_all, &
                                 all_contact, stat)
        type(mesh_t), intent(in) :: m
        real(wp), intent(in) :: young, poisson
        integer, intent(in) :: contact_part
        type(dof_map_t), intent(out) :: all_dofs
        type(csr_matrix_t), intent(out) :: k_all
        type(contact_t), intent(out) :: all_contact
        type(status_t), intent(out) :: stat
        call build_dof_map(m, [integer ::], all_dofs, stat)
        if (stat%ok()) call assemble_stiffness(m, all_dofs, young, poisson, k_all, stat)
        if (stat%ok()) call build_contact(m, contact_part, all_dofs, all_contact, stat)
    end subroutine assemble_all_dofs
end module problem
