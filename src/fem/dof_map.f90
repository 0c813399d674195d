! SPDX-License-Identifier: MIT
!> Numbering of the free degrees of freedom: two displacement components per node, minus
!> those prescribed (Dirichlet) on the chosen boundary parts, which are eliminated.
module dof_map
    use kinds, only: N_DIM
    use status, only: status_t, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use strings, only: to_string
    implicit none
    private
    public :: build_dof_map, cell_dofs

    type, public :: dof_map_t
        !> (2, n_nodes): number of dof (component, node) in the free system, 1-based;
        !> 0 when the dof is prescribed.
        integer, allocatable :: free_dof(:, :)
        integer :: n_free = 0   !! size of the free system
    end type dof_map_t

contains

    !> Fix both components of every node of every boundary edge in the parts
    !> `dirichlet_parts` (indices into m%part_names; may be empty), and number the other
    !> dofs node by node in node order, x before y, so the structured mesh's small node
    !> bandwidth carries over to the matrices.
    subroutine build_dof_map(m, dirichlet_parts, dofs, stat)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: dirichlet_parts(:)
        type(dof_map_t), intent(out) :: dofs
        type(status_t), intent(out) :: stat
        logical, allocatable :: in_dirichlet(:), fixed(:)
        integer :: n_parts, i, e, node, count

        if (.not. (allocated(m%coords) .and. allocated(m%edges) .and. &
                   allocated(m%edge_part) .and. allocated(m%part_names))) then
            call stat%fail(STATUS_BAD_INPUT, 'dof map: the mesh is incomplete (no nodes, '// &
                           'boundary edges or part names)')
            return
        end if
        n_parts = size(m%part_names)
        allocate (in_dirichlet(n_parts), source=.false.)
        do i = 1, size(dirichlet_parts)
            if (dirichlet_parts(i) < 1 .or. dirichlet_parts(i) > n_parts) then
                call stat%fail(STATUS_BAD_INPUT, 'dof map: Dirichlet part index '// &
                               to_string(dirichlet_parts(i))// &
                               ' is not a boundary part of the mesh')
                return
            end if
            in_dirichlet(dirichlet_parts(i)) = .true.
        end do

        allocate (fixed(m%n_nodes()), source=.false.)
        do e = 1, size(m%edge_part)
            if (in_dirichlet(m%edge_part(e))) fixed(m%edges(:, e)) = .true.
        end do

        allocate (dofs%free_dof(N_DIM, m%n_nodes()), source=0)
        count = 0
        do node = 1, m%n_nodes()
            if (fixed(node)) cycle
            do i = 1, N_DIM
                count = count + 1
                dofs%free_dof(i, node) = count
            end do
        end do
        dofs%n_free = count
    end subroutine build_dof_map

    !> Free-system numbers of the dofs of `cell`, in element dof order (u_x1, u_y1, u_x2,
    !> ...), 0 for prescribed dofs.
    pure function cell_dofs(dofs, m, cell) result(numbers)
        type(dof_map_t), intent(in) :: dofs
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: cell
        integer :: numbers(N_DIM*size(m%cells, 1))
        numbers = reshape(dofs%free_dof(:, m%cells(:, cell)), [size(numbers)])
    end function cell_dofs
end module dof_map
