! SPDX-License-Identifier: MIT
!> The mesh: nodes, cells of one element type, and the boundary edges with the name of the
!> boundary part each belongs to. Generators (structured, Gmsh) fill it; nothing else edits it.
module mesh
    use kinds, only: wp
    use element_types, only: ELEMENT_P1, element_dimension, element_name
    use strings, only: NAME_LEN, to_string
    use status, only: status_t, STATUS_BAD_INPUT
    implicit none
    private
    public :: mesh_t

    type :: mesh_t
        integer :: element = ELEMENT_P1
        real(wp), allocatable :: coords(:, :)    !! (dim(), n_nodes)
        integer, allocatable :: cells(:, :)      !! (nodes_per_cell, n_cells), anticlockwise
        integer, allocatable :: edges(:, :)      !! (nodes_per_edge, n_edges): ends, then mid node
        integer, allocatable :: edge_part(:)     !! (n_edges) index into part_names
        character(len=NAME_LEN), allocatable :: part_names(:)  !! boundary parts ('bottom'...)
        ! Where a mesh read from a file came from, so that later checks (contact segment,
        ! inverted cells) can name the file and line; unallocated for generated meshes.
        character(len=:), allocatable :: file        !! path of the mesh file
        integer, allocatable :: cell_line(:)         !! (n_cells) line defining each cell
        integer, allocatable :: edge_line(:)         !! (n_edges) line defining each edge
    contains
        procedure :: n_nodes => mesh_n_nodes
        procedure :: n_cells => mesh_n_cells
        procedure :: dim => mesh_dim
        procedure :: part_index => mesh_part_index
        procedure :: require_complete => mesh_require_complete
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

    !> The spatial dimension: that of its element (element_dimension), which its
    !> coordinates have (coords is (dim, n_nodes)) and every node's displacement.
    pure integer function mesh_dim(this)
        class(mesh_t), intent(in) :: this
        mesh_dim = element_dimension(this%element)
    end function mesh_dim

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

    !> Fail (bad input of `who`, the procedure handed this mesh) unless nodes, cells,
    !> boundary edges and part names are all there, the nodes with dim() coordinates: what a
    !> writer or a refinement reads.
    subroutine mesh_require_complete(this, who, stat)
        class(mesh_t), intent(in) :: this
        character(len=*), intent(in) :: who
        type(status_t), intent(inout) :: stat
        if (.not. (allocated(this%coords) .and. allocated(this%cells) .and. &
                   allocated(this%edges) .and. allocated(this%edge_part) .and. &
                   allocated(this%part_names))) &
            call stat%fail(STATUS_BAD_INPUT, who//': the mesh is incomplete (no nodes, cells, '// &
                           'boundary edges or part names)')
        if (.not. stat%ok()) return
        if (size(this%coords, 1) /= this%dim()) &
            call stat%fail(STATUS_BAD_INPUT, who//': the nodes have '// &
                           to_string(size(this%coords, 1))//' coordinates, the '// &
                           element_name(this%element)//' element '//to_string(this%dim()))
    end subroutine mesh_require_complete
end module mesh
