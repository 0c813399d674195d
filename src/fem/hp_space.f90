! SPDX-License-Identifier: MIT
!> The hp finite element space on a P1 triangle mesh with a polynomial degree per cell
!> (hp_basis): its scalar basis functions are numbered vertices first (function v is vertex
!> v's), then the edges' (p_e - 1 each, edge degree p_e = the smaller degree of its cells:
!> the minimum rule). Interior functions get no global number: the stiffness condenses them
!> cell by cell (hp_stiffness). Each free function carries two dofs (x, y), numbered
!> 2k - 1, 2k for the k-th free function, so dofs stay node-major as in dof_map. A clamped
!> (Dirichlet) boundary edge removes its own functions and those of its two vertices.
module hp_space
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: to_string
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use mesh_refine, only: edge_table_t, build_edge_table, edge_number
    use hp_basis, only: MAX_HP_DEGREE
    implicit none
    private
    public :: build_hp_space

    type, public :: hp_space_t
        integer :: n_vertices = 0
        integer :: n_functions = 0                !! vertex and edge functions
        integer, allocatable :: cell_degree(:)    !! (n_cells) interior degree p
        integer, allocatable :: cell_edge(:, :)   !! (3, n_cells) edge k: vertex k to k + 1
        logical, allocatable :: cell_flip(:, :)   !! (3, n_cells) edge k runs k + 1 -> k globally
        integer, allocatable :: edge_ends(:, :)   !! (2, n_edges) lower, higher vertex number
        integer, allocatable :: edge_degree(:)    !! (n_edges)
        integer, allocatable :: edge_first(:)     !! (n_edges) function of Lhat_2 on the edge
        integer, allocatable :: edge_part(:)      !! (n_edges) mesh part, 0 inside or none
        integer, allocatable :: free_function(:)  !! (n_functions) k >= 1 free, 0 clamped
    contains
        procedure :: n_free => hp_space_n_free
        procedure :: n_edges => hp_space_n_edges
        procedure :: cell_functions => hp_space_cell_functions
        procedure :: cell_dofs => hp_space_cell_dofs
        procedure :: edge_degrees_of => hp_space_edge_degrees_of
        procedure :: max_cell_dofs => hp_space_max_cell_dofs
    end type hp_space_t

contains

    pure integer function hp_space_n_free(this)
        class(hp_space_t), intent(in) :: this
        hp_space_n_free = 0
        if (allocated(this%free_function)) hp_space_n_free = 2*maxval([0, this%free_function])
    end function hp_space_n_free

    pure integer function hp_space_n_edges(this)
        class(hp_space_t), intent(in) :: this
        hp_space_n_edges = 0
        if (allocated(this%edge_degree)) hp_space_n_edges = size(this%edge_degree)
    end function hp_space_n_edges

    !> The degrees of the three edges of `cell`, in the cell's edge order.
    pure function hp_space_edge_degrees_of(this, cell) result(degrees)
        class(hp_space_t), intent(in) :: this
        integer, intent(in) :: cell
        integer :: degrees(3)
        degrees = this%edge_degree(this%cell_edge(:, cell))
    end function hp_space_edge_degrees_of

    !> Global numbers of the vertex and edge functions of `cell` in hp_basis's local order
    !> (its interior functions, which have none, excluded).
    pure function hp_space_cell_functions(this, cell, vertices) result(functions)
        class(hp_space_t), intent(in) :: this
        integer, intent(in) :: cell
        integer, intent(in) :: vertices(3)   !! the cell's corners
        integer, allocatable :: functions(:)
        integer :: k, e, i, f
        allocate (functions(3 + sum(max(0, this%edge_degree(this%cell_edge(:, cell)) - 1))))
        functions(1:3) = vertices
        f = 3
        do k = 1, 3
            e = this%cell_edge(k, cell)
            do i = 2, this%edge_degree(e)
                f = f + 1
                functions(f) = this%edge_first(e) + i - 2
            end do
        end do
    end function hp_space_cell_functions

    !> Free dofs of the functions of cell_functions, interleaved (x, y) per function, 0 for
    !> the dofs of clamped functions.
    pure function hp_space_cell_dofs(this, cell, vertices) result(dofs)
        class(hp_space_t), intent(in) :: this
        integer, intent(in) :: cell, vertices(3)
        integer, allocatable :: dofs(:)
        integer, allocatable :: functions(:)
        integer :: a, k
        allocate (functions(0))   ! (gfortran 12 warns of an unallocated one at -O3)
        functions = this%cell_functions(cell, vertices)
        allocate (dofs(2*size(functions)))
        do a = 1, size(functions)
            k = this%free_function(functions(a))
            dofs(2*a - 1:2*a) = 0
            if (k > 0) dofs(2*a - 1:2*a) = [2*k - 1, 2*k]
        end do
    end function hp_space_cell_dofs

    !> The largest number of (condensed) dofs of one cell.
    pure integer function hp_space_max_cell_dofs(this)
        class(hp_space_t), intent(in) :: this
        integer :: c
        hp_space_max_cell_dofs = 0
        do c = 1, size(this%cell_degree)
            hp_space_max_cell_dofs = max(hp_space_max_cell_dofs, &
                2*(3 + sum(max(0, this%edge_degree(this%cell_edge(:, c)) - 1))))
        end do
    end function hp_space_max_cell_dofs

    !> The hp space of the P1 mesh `m` with interior degrees `degree` (one per cell, 1 to
    !> MAX_HP_DEGREE) and the boundary parts `dirichlet_parts` clamped.
    subroutine build_hp_space(m, degree, dirichlet_parts, space, stat)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: degree(:)
        integer, intent(in) :: dirichlet_parts(:)
        type(hp_space_t), intent(out) :: space
        type(status_t), intent(out) :: stat
        type(edge_table_t) :: table
        logical, allocatable :: clamped(:)
        integer :: c, k, e, i, n_vertices, n_free, opposite

        if (m%element /= ELEMENT_P1) then
            call stat%fail(STATUS_BAD_INPUT, 'hp space: expected a P1 triangle mesh (the '// &
                           'degrees come from the hp space, not the mesh)')
            return
        end if
        if (size(degree) /= m%n_cells() .or. any(degree < 1) .or. &
            any(degree > MAX_HP_DEGREE)) then
            call stat%fail(STATUS_BAD_INPUT, 'hp space: expected one degree per cell ('// &
                to_string(m%n_cells())//') from 1 to '//to_string(MAX_HP_DEGREE))
            return
        end if
        if (any(dirichlet_parts < 1 .or. dirichlet_parts > size(m%part_names))) then
            call stat%fail(STATUS_BAD_INPUT, 'hp space: a Dirichlet part index is not a '// &
                           'boundary part of the mesh')
            return
        end if
        n_vertices = m%n_nodes()
        space%n_vertices = n_vertices
        space%cell_degree = degree
        call build_edge_table(m%cells, n_vertices, table)
        space%edge_ends = table%ends
        allocate (space%cell_edge(3, m%n_cells()), space%cell_flip(3, m%n_cells()))
        do c = 1, m%n_cells()
            do k = 1, 3
                ! edge k runs from corner k to k + 1: the table's edge opposite corner k + 2
                opposite = mod(k + 1, 3) + 1
                e = table%cell_edge(opposite, c)
                space%cell_edge(k, c) = e
                space%cell_flip(k, c) = m%cells(k, c) > m%cells(mod(k, 3) + 1, c)
            end do
        end do
        allocate (space%edge_degree(table%n_edges), space%edge_first(table%n_edges))
        do e = 1, table%n_edges
            space%edge_degree(e) = degree(table%cells_of(1, e))
            if (table%cells_of(2, e) > 0) space%edge_degree(e) = &
                min(space%edge_degree(e), degree(table%cells_of(2, e)))
        end do
        space%n_functions = n_vertices
        do e = 1, table%n_edges
            space%edge_first(e) = space%n_functions + 1
            space%n_functions = space%n_functions + max(0, space%edge_degree(e) - 1)
        end do
        allocate (space%edge_part(table%n_edges), source=0)
        do i = 1, size(m%edge_part)
            e = edge_number(table, m%edges(1, i), m%edges(2, i))
            if (e == 0) then
                call stat%fail(STATUS_BAD_INPUT, 'hp space: boundary edge '//to_string(i)// &
                               ' is no cell side')
                return
            end if
            space%edge_part(e) = m%edge_part(i)
        end do

        allocate (clamped(space%n_functions), source=.false.)
        do e = 1, table%n_edges
            if (space%edge_part(e) == 0) cycle
            if (.not. any(dirichlet_parts == space%edge_part(e))) cycle
            clamped(space%edge_ends(:, e)) = .true.
            do i = 2, space%edge_degree(e)
                clamped(space%edge_first(e) + i - 2) = .true.
            end do
        end do
        allocate (space%free_function(space%n_functions), source=0)
        n_free = 0
        do i = 1, space%n_functions
            if (clamped(i)) cycle
            n_free = n_free + 1
            space%free_function(i) = n_free
        end do
    end subroutine build_hp_space
end module hp_space
