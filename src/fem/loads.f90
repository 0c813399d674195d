! SPDX-License-Identifier: MIT
!> Consistent nodal forces of the data of the static problem: tractions on boundary edges and
!> a body force, as vectors on ALL dofs in the node-major numbering dim (node - 1) + component
!> (dof_map's all_dof, the numbering build_dof_map gives when no dof is prescribed), for a
!> mesh of dimension dim = 2 (edges bound the plane domain).
module loads
    use kinds, only: wp
    use status, only: status_t, STATUS_MESH
    use mesh, only: mesh_t
    use element_types, only: element_nodes_per_edge, element_nodes_per_cell, element_corners
    use quadrature, only: quadrature_rule_t, line_rule
    use shape_functions, only: evaluate_shape, evaluate_line_shape, MAX_NODES, MAX_EDGE_NODES
    use elasticity, only: load_rule
    use cell_geometry, only: jacobian_at, local_coordinates
    use strings, only: to_string
    use dof_map, only: node_dofs
    implicit none
    private
    public :: edge_loads, body_force_loads

    !> Gauss points per edge: at least 3, exact for the quadratic edge functions times the
    !> degree-1 length element of a curved P2 edge, and for a traction linear in the outward
    !> normal; p + 1 for degree p >= 3 (exact to degree 2p + 1 on a straight edge).
    integer, parameter :: MIN_EDGE_POINTS = 3

contains

    !> f += int_edge N_a (traction + stress n) ds over every boundary edge whose part is marked
    !> in `in_part`, with n the outward unit normal: a constant traction vector plus the
    !> traction of a constant stress tensor (sigma(U) n for a linear field U). Integrated with
    !> the edge shape functions, so P1/Q1 (2 nodes per edge), P2/Q2 (3), P3 (4) and P4 (5)
    !> are all exact on straight edges.
    subroutine edge_loads(m, in_part, traction, stress, f, stat)
        type(mesh_t), intent(in) :: m
        logical, intent(in) :: in_part(:)          !! (n_parts) parts that carry the load
        real(wp), intent(in) :: traction(:)        !! (m%dim()) force per unit length
        real(wp), intent(in) :: stress(:, :)       !! (m%dim(), m%dim())
        real(wp), intent(inout) :: f(:)            !! (dim n_nodes)
        type(status_t), intent(out) :: stat
        type(quadrature_rule_t) :: rule
        real(wp) :: values(MAX_EDGE_NODES), derivatives(MAX_EDGE_NODES), &
                    xy(size(traction), MAX_EDGE_NODES), dx(size(traction)), &
                    normal(size(traction)), inner(size(traction)), &
                    chord_normal(size(traction)), orientation, length_element, &
                    load(size(traction))
        real(wp), allocatable :: inner_points(:, :)
        integer :: e, q, a, per_edge, n_dim

        n_dim = m%dim()
        per_edge = element_nodes_per_edge(m%element)
        rule = line_rule(max(MIN_EDGE_POINTS, per_edge))
        call edge_inner_points(m, inner_points, stat)
        if (.not. stat%ok()) return
        do e = 1, size(m%edge_part)
            if (.not. in_part(m%edge_part(e))) cycle
            xy(:, 1:per_edge) = m%coords(:, m%edges(1:per_edge, e))
            ! Outward: away from the centroid of the cell that owns the edge.
            inner = inner_points(:, e)
            chord_normal = [xy(2, 2) - xy(2, 1), -(xy(1, 2) - xy(1, 1))]
            orientation = 1.0_wp
            if (dot_product(chord_normal, inner - xy(:, 1)) > 0.0_wp) orientation = -1.0_wp
            do q = 1, rule%n_points
                call evaluate_line_shape(per_edge, rule%points(1, q), values, derivatives)
                dx = matmul(xy(:, 1:per_edge), derivatives(1:per_edge))
                length_element = norm2(dx)
                normal = orientation*[dx(2), -dx(1)]/length_element
                load = traction + matmul(stress, normal)
                do a = 1, per_edge
                    f(node_dofs(m%edges(a, e), n_dim)) = f(node_dofs(m%edges(a, e), n_dim)) &
                        + rule%weights(q)*length_element*values(a)*load
                end do
            end do
        end do
    end subroutine edge_loads

    !> f += int_Omega N_a force dx for a constant body force, with elasticity's load_rule
    !> (exact for the shape functions on affine cells).
    subroutine body_force_loads(m, force, f)
        type(mesh_t), intent(in) :: m
        real(wp), intent(in) :: force(:)           !! (m%dim()) force per unit area
        real(wp), intent(inout) :: f(:)            !! (dim n_nodes)
        type(quadrature_rule_t) :: rule
        real(wp) :: values(MAX_NODES), gradients(size(force), MAX_NODES), &
                    jacobian(size(force), size(force)), det
        integer :: cell, q, a, n, n_dim

        if (.not. any(abs(force) > 0.0_wp)) return
        n = element_nodes_per_cell(m%element)
        n_dim = m%dim()
        rule = load_rule(m%element)
        do cell = 1, m%n_cells()
            do q = 1, rule%n_points
                call evaluate_shape(m%element, rule%points(:, q), values, gradients)
                call jacobian_at(m%element, local_coordinates(m%element, &
                                 m%coords(:, m%cells(:, cell))), rule%points(:, q), jacobian, det)
                do a = 1, n
                    f(node_dofs(m%cells(a, cell), n_dim)) = &
                        f(node_dofs(m%cells(a, cell), n_dim)) + rule%weights(q)*det*values(a)*force
                end do
            end do
        end do
    end subroutine body_force_loads

    !> For every boundary edge, the centroid of a cell holding both its end nodes (a point on
    !> the body's side of the edge), found through the node-to-cell incidence.
    subroutine edge_inner_points(m, points, stat)
        type(mesh_t), intent(in) :: m
        real(wp), allocatable, intent(out) :: points(:, :)
        type(status_t), intent(out) :: stat
        integer, allocatable :: first(:), cells_of(:), filled(:)
        integer :: corners, cell, k, node, e, slot, c
        logical :: found

        corners = element_corners(m%element)
        allocate (first(m%n_nodes() + 1), source=0)
        do cell = 1, m%n_cells()
            do k = 1, corners
                node = m%cells(k, cell)
                first(node + 1) = first(node + 1) + 1
            end do
        end do
        first(1) = 1
        do node = 1, m%n_nodes()
            first(node + 1) = first(node + 1) + first(node)
        end do
        allocate (cells_of(first(m%n_nodes() + 1) - 1), filled(m%n_nodes()), source=0)
        do cell = 1, m%n_cells()
            do k = 1, corners
                node = m%cells(k, cell)
                cells_of(first(node) + filled(node)) = cell
                filled(node) = filled(node) + 1
            end do
        end do

        allocate (points(m%dim(), size(m%edge_part)))
        do e = 1, size(m%edge_part)
            node = m%edges(1, e)
            found = .false.
            do slot = first(node), first(node + 1) - 1
                c = cells_of(slot)
                if (any(m%cells(1:corners, c) == m%edges(2, e))) then
                    points(:, e) = sum(m%coords(:, m%cells(1:corners, c)), dim=2)/corners
                    found = .true.
                    exit
                end if
            end do
            if (.not. found) then
                call stat%fail(STATUS_MESH, 'boundary edge '//to_string(e)// &
                               ' belongs to no cell')
                return
            end if
        end do
    end subroutine edge_inner_points
end module loads
