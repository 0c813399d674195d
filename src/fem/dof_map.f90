! SPDX-License-Identifier: MIT
!> Numbering of the free degrees of freedom: two displacement components per node, minus
!> those prescribed (Dirichlet) on the chosen boundary parts, which are eliminated.
module dof_map
    use kinds, only: wp, N_DIM
    use status, only: status_t, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use strings, only: to_string
    implicit none
    private
    public :: build_dof_map, cell_dofs, all_dof, node_dofs

    type, public :: dof_map_t
        !> (2, n_nodes): number of dof (component, node) in the free system, 1-based;
        !> 0 when the dof is prescribed.
        integer, allocatable :: free_dof(:, :)
        integer :: n_free = 0   !! size of the free system
    contains
        procedure :: free_to_all => dof_map_free_to_all
        procedure :: expand => dof_map_expand
        procedure :: nodal_field => dof_map_nodal_field
    end type dof_map_t

contains

    !> Number of dof (component, node) in the numbering of all dofs, node-major: the numbering
    !> build_dof_map gives when no dof is prescribed, in which loads and K on all dofs live.
    elemental integer function all_dof(component, node)
        integer, intent(in) :: component, node
        all_dof = N_DIM*(node - 1) + component
    end function all_dof

    !> The two dofs (x, y) of `node` in the numbering of all dofs.
    pure function node_dofs(node) result(dofs)
        integer, intent(in) :: node
        integer :: dofs(N_DIM)
        dofs = [all_dof(1, node), all_dof(2, node)]
    end function node_dofs

    !> (n_free) the number of each free dof in the numbering of all dofs.
    pure function dof_map_free_to_all(this) result(map)
        class(dof_map_t), intent(in) :: this
        integer :: map(this%n_free)
        integer :: node, c
        do node = 1, size(this%free_dof, 2)
            do c = 1, N_DIM
                if (this%free_dof(c, node) > 0) map(this%free_dof(c, node)) = all_dof(c, node)
            end do
        end do
    end function dof_map_free_to_all

    !> A free-dof vector on all dofs: x on the free dofs, `prescribed` (all dofs; only its
    !> prescribed entries are read) or zero elsewhere. The one map from the free system to
    !> the nodes: nodal fields, the compliance problem's u and the loads all go through it.
    pure function dof_map_expand(this, x, prescribed) result(u)
        class(dof_map_t), intent(in) :: this
        real(wp), intent(in) :: x(:)
        real(wp), intent(in), optional :: prescribed(:)
        real(wp) :: u(N_DIM*size(this%free_dof, 2))
        integer :: node, c
        do node = 1, size(this%free_dof, 2)
            do c = 1, N_DIM
                if (this%free_dof(c, node) > 0) then
                    u(all_dof(c, node)) = x(this%free_dof(c, node))
                else if (present(prescribed)) then
                    u(all_dof(c, node)) = prescribed(all_dof(c, node))
                else
                    u(all_dof(c, node)) = 0.0_wp
                end if
            end do
        end do
    end function dof_map_expand

    !> A free-dof vector as a (2, n_nodes) nodal field, zero on the prescribed dofs.
    pure function dof_map_nodal_field(this, x) result(field)
        class(dof_map_t), intent(in) :: this
        real(wp), intent(in) :: x(:)
        real(wp) :: field(N_DIM, size(this%free_dof, 2))
        field = reshape(this%expand(x), shape(field))
    end function dof_map_nodal_field

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
