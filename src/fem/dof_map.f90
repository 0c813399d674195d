! SPDX-License-Identifier: MIT
!> Numbering of the free degrees of freedom: one displacement component per spatial dimension
!> of the mesh (mesh_t%dim) at each node, minus those prescribed (Dirichlet) on the chosen
!> boundary parts, which are eliminated.
module dof_map
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use strings, only: to_string
    implicit none
    private
    public :: build_dof_map, cell_dofs, all_dof, node_dofs

    type, public :: dof_map_t
        !> (dim, n_nodes): number of dof (component, node) in the free system, 1-based;
        !> 0 when the dof is prescribed. Its first extent is the mesh's dimension.
        integer, allocatable :: free_dof(:, :)
        integer :: n_free = 0   !! size of the free system
    contains
        procedure :: free_to_all => dof_map_free_to_all
        procedure :: expand => dof_map_expand
        procedure :: nodal_field => dof_map_nodal_field
        procedure :: dim => dof_map_dim
    end type dof_map_t

contains

    !> Number of dof (component, node) in the numbering of all dofs of a mesh of dimension
    !> `n_dim`, node-major: the numbering build_dof_map gives when no dof is prescribed, in
    !> which loads and K on all dofs live.
    elemental integer function all_dof(component, node, n_dim)
        integer, intent(in) :: component, node, n_dim
        all_dof = n_dim*(node - 1) + component
    end function all_dof

    !> The dofs (x, y, ...) of `node` in the numbering of all dofs of a mesh of dimension
    !> `n_dim`.
    pure function node_dofs(node, n_dim) result(dofs)
        integer, intent(in) :: node, n_dim
        integer :: dofs(n_dim), c
        dofs = [(all_dof(c, node, n_dim), c=1, n_dim)]
    end function node_dofs

    !> Displacement components per node: the dimension of the mesh the map was built on.
    pure integer function dof_map_dim(this)
        class(dof_map_t), intent(in) :: this
        dof_map_dim = 0
        if (allocated(this%free_dof)) dof_map_dim = size(this%free_dof, 1)
    end function dof_map_dim

    !> (n_free) the number of each free dof in the numbering of all dofs.
    pure function dof_map_free_to_all(this) result(map)
        class(dof_map_t), intent(in) :: this
        integer :: map(this%n_free)
        integer :: node, c
        do node = 1, size(this%free_dof, 2)
            do c = 1, this%dim()
                if (this%free_dof(c, node) > 0) &
                    map(this%free_dof(c, node)) = all_dof(c, node, this%dim())
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
        real(wp) :: u(size(this%free_dof))
        integer :: node, c, i
        do node = 1, size(this%free_dof, 2)
            do c = 1, this%dim()
                i = all_dof(c, node, this%dim())
                if (this%free_dof(c, node) > 0) then
                    u(i) = x(this%free_dof(c, node))
                else if (present(prescribed)) then
                    u(i) = prescribed(i)
                else
                    u(i) = 0.0_wp
                end if
            end do
        end do
    end function dof_map_expand

    !> A free-dof vector as a (dim, n_nodes) nodal field, zero on the prescribed dofs.
    pure function dof_map_nodal_field(this, x) result(field)
        class(dof_map_t), intent(in) :: this
        real(wp), intent(in) :: x(:)
        real(wp) :: field(size(this%free_dof, 1), size(this%free_dof, 2))
        field = reshape(this%expand(x), shape(field))
    end function dof_map_nodal_field

    !> Fix every component of every node of every boundary edge in the parts
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

        allocate (dofs%free_dof(m%dim(), m%n_nodes()), source=0)
        count = 0
        do node = 1, m%n_nodes()
            if (fixed(node)) cycle
            do i = 1, m%dim()
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
        integer :: numbers(size(dofs%free_dof, 1)*size(m%cells, 1))
        numbers = reshape(dofs%free_dof(:, m%cells(:, cell)), [size(numbers)])
    end function cell_dofs
end module dof_map
