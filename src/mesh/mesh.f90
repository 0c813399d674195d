! SPDX-License-Identifier: MIT
!> The mesh: nodes, cells of one element type, and the boundary edges with the name of the
!> boundary part each belongs to. Generators (structured, Gmsh) fill it; nothing else edits it.
module mesh
    use kinds, only: wp
    implicit none
    private
    public :: mesh_t, element_nodes_per_cell, element_nodes_per_edge, element_from_name, &
              element_name
    public :: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2

    ! Node order inside a cell follows Gmsh: corners anticlockwise, then mid-edge nodes
    ! (edge k joins corner k and corner k+1), then the centre node of Q2.
    integer, parameter :: ELEMENT_P1 = 1   !! 3-node triangle
    integer, parameter :: ELEMENT_Q1 = 2   !! 4-node quadrilateral
    integer, parameter :: ELEMENT_P2 = 3   !! 6-node triangle
    integer, parameter :: ELEMENT_Q2 = 4   !! 9-node quadrilateral

    type :: mesh_t
        integer :: element = ELEMENT_P1
        real(wp), allocatable :: coords(:, :)    !! (2, n_nodes)
        integer, allocatable :: cells(:, :)      !! (nodes_per_cell, n_cells), anticlockwise
        integer, allocatable :: edges(:, :)      !! (nodes_per_edge, n_edges): ends, then mid node
        integer, allocatable :: edge_part(:)     !! (n_edges) index into part_names
        character(len=64), allocatable :: part_names(:)  !! boundary part names ('bottom'...)
        ! Where a mesh read from a file came from, so that later checks (contact segment,
        ! inverted cells) can name the file and line; unallocated for generated meshes.
        character(len=:), allocatable :: file        !! path of the mesh file
        integer, allocatable :: cell_line(:)         !! (n_cells) line defining each cell
        integer, allocatable :: edge_line(:)         !! (n_edges) line defining each edge
    contains
        procedure :: n_nodes => mesh_n_nodes
        procedure :: n_cells => mesh_n_cells
        procedure :: part_index => mesh_part_index
    end type mesh_t

contains

    pure integer function mesh_n_nodes(this)
        class(mesh_t), intent(in) :: this
        mesh_n_nodes = 0
        if (allocated(this%coords)) mesh_n_nodes = size(this%coords, 2)
    end function mesh_n_nodes

    pure integer function mesh_n_cells(this)
        class(mesh_t), intent(in) :: this
        mesh_n_cells = 0
        if (allocated(this%cells)) mesh_n_cells = size(this%cells, 2)
    end function mesh_n_cells

    !> Index of the boundary part called `name`, or 0 when the mesh has none of that name.
    pure integer function mesh_part_index(this, name)
        class(mesh_t), intent(in) :: this
        character(len=*), intent(in) :: name
        integer :: i
        mesh_part_index = 0
        if (.not. allocated(this%part_names)) return
        do i = 1, size(this%part_names)
            if (trim(this%part_names(i)) == trim(name)) then
                mesh_part_index = i
                return
            end if
        end do
    end function mesh_part_index

    pure integer function element_nodes_per_cell(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_P1); element_nodes_per_cell = 3
        case (ELEMENT_Q1); element_nodes_per_cell = 4
        case (ELEMENT_P2); element_nodes_per_cell = 6
        case (ELEMENT_Q2); element_nodes_per_cell = 9
        case default; element_nodes_per_cell = 0
        end select
    end function element_nodes_per_cell

    pure integer function element_nodes_per_edge(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_P1, ELEMENT_Q1); element_nodes_per_edge = 2
        case (ELEMENT_P2, ELEMENT_Q2); element_nodes_per_edge = 3
        case default; element_nodes_per_edge = 0
        end select
    end function element_nodes_per_edge

    !> ELEMENT_* code of 'p1', 'q1', 'p2' or 'q2'; 0 for any other name.
    pure integer function element_from_name(name)
        character(len=*), intent(in) :: name
        select case (trim(name))
        case ('p1'); element_from_name = ELEMENT_P1
        case ('q1'); element_from_name = ELEMENT_Q1
        case ('p2'); element_from_name = ELEMENT_P2
        case ('q2'); element_from_name = ELEMENT_Q2
        case default; element_from_name = 0
        end select
    end function element_from_name

    pure function element_name(element) result(name)
        integer, intent(in) :: element
        character(len=2) :: name
        character(len=2), parameter :: NAMES(4) = ['p1', 'q1', 'p2', 'q2']
        name = '??'
        if (element >= 1 .and. element <= 4) name = NAMES(element)
    end function element_name
end module mesh
