! SPDX-License-Identifier: MIT
!> The contact boundary Gamma_C: one straight segment, its outward normal n and tangent
!> t = (n2, -n1), the free nodes on it, their boundary mass matrix M, and the operators
!> N, T that take the normal and tangential components of a free-dof vector at those nodes.
!> B of model.md sections 4-7 is (lambda T^T - N^T) M N.
module contact_boundary
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_MESH
    use mesh, only: mesh_t
    use element_types, only: element_nodes_per_edge, element_corners
    use quadrature, only: quadrature_rule_t, line_rule
    use shape_functions, only: evaluate_line_shape, MAX_EDGE_NODES
    use dof_map, only: dof_map_t
    use csr_matrix, only: csr_matrix_t, csr_from_element_dofs
    use strings, only: to_string
    use sorting, only: sort_index
    implicit none
    private
    public :: contact_t, build_contact, assemble_b, b_pattern, fill_b, edge_mass

    !> Collinearity tolerance, relative to the segment length: Gmsh writes coordinates with
    !> about 16 significant digits, so 1e-10 accepts every straight line it can produce.
    real(wp), parameter :: STRAIGHT_TOL = 1.0e-10_wp

    type, public :: contact_t
        integer, allocatable :: nodes(:)      !! (p) free mesh nodes on Gamma_C, in order along t
        integer, allocatable :: dofs(:, :)    !! (2, p) free dofs (x, y) of those nodes
        real(wp) :: normal(2) = 0.0_wp        !! outward unit normal
        real(wp) :: tangent(2) = 0.0_wp       !! (n2, -n1)
        real(wp) :: length = 0.0_wp           !! length of the segment
        type(csr_matrix_t) :: mass            !! (p, p) boundary mass matrix on the free nodes
    contains
        procedure :: p => contact_p
        procedure :: gather => contact_gather
        procedure :: scatter => contact_scatter
        procedure :: mass_dense => contact_mass_dense
        procedure :: slip_direction => contact_slip_direction
    end type contact_t

contains

    pure integer function contact_p(this)
        class(contact_t), intent(in) :: this
        contact_p = 0
        if (allocated(this%nodes)) contact_p = size(this%nodes)
    end function contact_p

    !> y(a) = direction . x(dofs(:, a)) for every contact node a (N x with direction = n).
    pure subroutine contact_gather(this, direction, x, y)
        class(contact_t), intent(in) :: this
        real(wp), intent(in) :: direction(2), x(:)
        real(wp), intent(out) :: y(:)
        integer :: a
        do a = 1, size(this%nodes)
            y(a) = direction(1)*x(this%dofs(1, a)) + direction(2)*x(this%dofs(2, a))
        end do
    end subroutine contact_gather

    !> x(dofs(:, a)) += direction * y(a) (N^T y with direction = n); other entries untouched.
    pure subroutine contact_scatter(this, direction, y, x)
        class(contact_t), intent(in) :: this
        real(wp), intent(in) :: direction(2), y(:)
        real(wp), intent(inout) :: x(:)
        integer :: a
        do a = 1, size(this%nodes)
            x(this%dofs(:, a)) = x(this%dofs(:, a)) + direction*y(a)
        end do
    end subroutine contact_scatter

    !> M as a dense p x p array, for the reduced dense problem.
    pure function contact_mass_dense(this) result(m_dense)
        class(contact_t), intent(in) :: this
        real(wp) :: m_dense(size(this%nodes), size(this%nodes))
        integer :: a, k
        m_dense = 0.0_wp
        do a = 1, size(this%nodes)
            do k = this%mass%row_start(a), this%mass%row_start(a + 1) - 1
                m_dense(a, this%mass%col(k)) = this%mass%val(k)
            end do
        end do
    end function contact_mass_dense

    !> Consistent 1D mass matrix of a straight edge of length h with equally spaced nodes;
    !> node order: ends, then the inner nodes from the first end. Closed forms for 2 and 3
    !> nodes; for 4 (cubic) and 5 (quartic) nodes, Gauss with as many points as nodes, exact
    !> for the products N_a N_b of degree 2(n - 1) <= 2n - 1.
    pure function edge_mass(nodes_per_edge, h) result(me)
        integer, intent(in) :: nodes_per_edge
        real(wp), intent(in) :: h
        real(wp) :: me(nodes_per_edge, nodes_per_edge)
        type(quadrature_rule_t) :: rule
        real(wp) :: values(MAX_EDGE_NODES), derivatives(MAX_EDGE_NODES)
        integer :: q, a
        if (nodes_per_edge == 2) then
            me = h/6.0_wp*reshape([2.0_wp, 1.0_wp, 1.0_wp, 2.0_wp], [2, 2])
        else if (nodes_per_edge == 3) then
            me = h/30.0_wp*reshape([4.0_wp, -1.0_wp, 2.0_wp, -1.0_wp, 4.0_wp, 2.0_wp, &
                                    2.0_wp, 2.0_wp, 16.0_wp], [3, 3])
        else
            me = 0.0_wp
            rule = line_rule(nodes_per_edge)
            do q = 1, rule%n_points
                call evaluate_line_shape(nodes_per_edge, rule%points(1, q), values, derivatives)
                do a = 1, nodes_per_edge
                    ! ds = (h/2) d(reference s)
                    me(:, a) = me(:, a) + 0.5_wp*h*rule%weights(q)*values(a)* &
                               values(1:nodes_per_edge)
                end do
            end do
        end if
    end function edge_mass

    !> Collect Gamma_C from the boundary part `part` of the mesh: check that it is one straight
    !> segment, orient n outward (away from the cells that own its edges), list the free nodes in
    !> order along t, and assemble M on them.
    subroutine build_contact(m, part, dofs, contact, stat)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: part               !! index into m%part_names
        type(dof_map_t), intent(in) :: dofs
        type(contact_t), intent(out) :: contact
        type(status_t), intent(out) :: stat
        integer, allocatable :: edge_list(:), local(:), edge_local(:, :), order(:), on_edge(:)
        real(wp), allocatable :: position(:)
        real(wp) :: start(2), finish(2), direction(2), offset, s_min, s_max, inner(2), fraction, &
                    first_end(2), last_end(2)
        integer :: e, i, a, node, n_edges, per_edge, p
        character(len=:), allocatable :: name

        name = trim(m%part_names(part))
        per_edge = element_nodes_per_edge(m%element)
        edge_list = pack([(e, e=1, size(m%edge_part))], m%edge_part == part)
        n_edges = size(edge_list)
        if (n_edges == 0) then
            call stat%fail(STATUS_BAD_INPUT, 'contact boundary '''//name//''' has no edges')
            return
        end if

        ! The segment's line through its two extreme nodes along the first edge's direction;
        ! every node must lie on it. Not the first edge's own line: on a graded mesh that
        ! edge may be 1e-9 long, its direction then good only to 1e-7 (the rounding of O(1)
        ! coordinates over its length), which puts far nodes of a slanted segment off it.
        start = m%coords(:, m%edges(1, edge_list(1)))
        finish = m%coords(:, m%edges(2, edge_list(1)))
        direction = (finish - start)/norm2(finish - start)
        s_min = huge(1.0_wp)
        s_max = -huge(1.0_wp)
        allocate (on_edge(m%n_nodes()), source=0)   ! an edge of Gamma_C holding the node
        do i = 1, n_edges
            do a = 1, per_edge
                node = m%edges(a, edge_list(i))
                on_edge(node) = edge_list(i)
                if (dot_product(m%coords(:, node) - start, direction) < s_min) then
                    s_min = dot_product(m%coords(:, node) - start, direction)
                    first_end = m%coords(:, node)
                end if
                if (dot_product(m%coords(:, node) - start, direction) > s_max) then
                    s_max = dot_product(m%coords(:, node) - start, direction)
                    last_end = m%coords(:, node)
                end if
            end do
        end do
        start = first_end
        direction = (last_end - first_end)/norm2(last_end - first_end)
        contact%length = norm2(last_end - first_end)
        do node = 1, size(on_edge)
            if (on_edge(node) == 0) cycle
            offset = abs(cross(direction, m%coords(:, node) - start))
            if (offset > STRAIGHT_TOL*contact%length) then
                call stat%fail(STATUS_MESH, place_of(on_edge(node))//'contact boundary '''// &
                    name//''' is not one straight segment: the node at ('// &
                    to_string(m%coords(1, node))//', '//to_string(m%coords(2, node))// &
                    ') is off the line through its two ends; expected one straight segment')
                return
            end if
        end do
        ! The edge mass matrix of higher order is that of a straight edge with its inner nodes
        ! equally spaced (an affine map); Gmsh and the rectangle generator place them so.
        do i = 1, n_edges
            do a = 3, per_edge
                associate (ends => m%coords(:, m%edges(1:2, edge_list(i))), &
                           inner_xy => m%coords(:, m%edges(a, edge_list(i))))
                    fraction = real(a - 2, wp)/real(per_edge - 1, wp)
                    if (norm2(inner_xy - ((1.0_wp - fraction)*ends(:, 1) + fraction*ends(:, 2))) &
                        > STRAIGHT_TOL*contact%length) then
                        if (per_edge == 3) then
                            call stat%fail(STATUS_MESH, place_of(edge_list(i))// &
                                'contact boundary '''//name//''': the mid node of this edge ' &
                                //'is not at its middle; expected straight quadratic edges')
                        else
                            call stat%fail(STATUS_MESH, place_of(edge_list(i))// &
                                'contact boundary '''//name//''': inner node '// &
                                to_string(a - 2)//' of this edge is not at '// &
                                to_string(a - 2)//'/'//to_string(per_edge - 1)// &
                                ' of its length; expected straight edges with equally ' &
                                //'spaced nodes')
                        end if
                        return
                    end if
                end associate
            end do
        end do
        ! One segment, not several pieces of a line: the edge lengths must add up to its span.
        if (abs(sum([(edge_length(edge_list(i)), i=1, n_edges)]) - contact%length) > &
            STRAIGHT_TOL*n_edges*contact%length) then
            call stat%fail(STATUS_MESH, place_of(edge_list(1))//'contact boundary '''//name// &
                ''' is not one connected straight segment (its edges overlap or leave gaps)')
            return
        end if

        ! Outward: pointing away from a node of a cell that owns the first edge but is off it.
        inner = interior_point(edge_list(1))
        contact%normal = [direction(2), -direction(1)]
        if (dot_product(contact%normal, inner - start) > 0.0_wp) contact%normal = -contact%normal
        contact%tangent = [contact%normal(2), -contact%normal(1)]

        ! Free nodes on Gamma_C in order along t (a node with a prescribed dof is not free).
        ! (filled in place: appending one entry at a time made this O(p^2), minutes at p = 1e6)
        allocate (position(count(on_edge /= 0)))
        allocate (local(m%n_nodes()), source=0)
        p = 0
        do node = 1, size(on_edge)
            if (on_edge(node) == 0) cycle
            if (dofs%free_dof(1, node) == 0 .or. dofs%free_dof(2, node) == 0) cycle
            p = p + 1
            position(p) = dot_product(m%coords(:, node), contact%tangent)
            local(node) = p
        end do
        if (p == 0) then
            call stat%fail(STATUS_BAD_INPUT, 'contact boundary '''//name// &
                ''' has no free node: every node on it is also on the Dirichlet boundary')
            return
        end if
        allocate (contact%nodes(p))
        do node = 1, size(local)
            if (local(node) > 0) contact%nodes(local(node)) = node
        end do
        order = sort_index(position(:p))
        contact%nodes = contact%nodes(order)
        do a = 1, p
            local(contact%nodes(a)) = a
        end do
        allocate (contact%dofs(2, p))
        do a = 1, p
            contact%dofs(:, a) = dofs%free_dof(:, contact%nodes(a))
        end do

        ! Boundary mass matrix on the free contact nodes, assembled edge by edge.
        allocate (edge_local(per_edge, n_edges))
        do i = 1, n_edges
            edge_local(:, i) = local(m%edges(:, edge_list(i)))
        end do
        call csr_from_element_dofs(p, edge_local, contact%mass)
        do i = 1, n_edges
            call contact%mass%add_block(edge_local(:, i), &
                edge_mass(per_edge, edge_length(edge_list(i))), stat)
            if (.not. stat%ok()) return
        end do

    contains

        !> 'file:line: ' of a boundary edge for a mesh read from a file, else ''.
        function place_of(edge) result(text)
            integer, intent(in) :: edge
            character(len=:), allocatable :: text
            text = ''
            if (allocated(m%file) .and. allocated(m%edge_line)) &
                text = m%file//':'//to_string(m%edge_line(edge))//': '
        end function place_of

        real(wp) function edge_length(edge)
            integer, intent(in) :: edge
            edge_length = norm2(m%coords(:, m%edges(2, edge)) - m%coords(:, m%edges(1, edge)))
        end function edge_length

        !> A point inside the body next to `edge`: the centroid of a cell holding its two ends.
        function interior_point(edge) result(point)
            integer, intent(in) :: edge
            real(wp) :: point(2)
            integer :: c, corners
            corners = element_corners(m%element)
            point = start
            do c = 1, size(m%cells, 2)
                if (any(m%cells(1:corners, c) == m%edges(1, edge)) .and. &
                    any(m%cells(1:corners, c) == m%edges(2, edge))) then
                    point = sum(m%coords(:, m%cells(1:corners, c)), dim=2)/corners
                    return
                end if
            end do
        end function interior_point
    end subroutine build_contact

    !> B = (lambda T^T - N^T) M N on the free dofs: row (test) dof of node a, column (trial)
    !> dof of node b hold (lambda t_i - n_i) M_ab n_j.
    subroutine assemble_b(contact, n_free, lambda, b, stat)
        type(contact_t), intent(in) :: contact
        integer, intent(in) :: n_free
        real(wp), intent(in) :: lambda
        type(csr_matrix_t), intent(out) :: b
        type(status_t), intent(out) :: stat
        call b_pattern(contact, n_free, b)
        call fill_b(contact, lambda, b, stat)
    end subroutine assemble_b

    !> The sparsity of B on the free dofs, its values zero: it does not depend on lambda, so
    !> a caller that assembles B at many lambdas on one mesh builds it once (fill_b), the
    !> larger part of assemble_b's cost.
    subroutine b_pattern(contact, n_free, b)
        type(contact_t), intent(in) :: contact
        integer, intent(in) :: n_free
        type(csr_matrix_t), intent(out) :: b
        integer, allocatable :: pair_dofs(:, :)
        integer :: a, k, n_pairs
        ! Each nonzero M_ab couples the two dofs of a with the two of b: one 4-dof "element".
        n_pairs = size(contact%mass%col)
        allocate (pair_dofs(4, n_pairs))
        do a = 1, contact%p()
            do k = contact%mass%row_start(a), contact%mass%row_start(a + 1) - 1
                pair_dofs(:, k) = [contact%dofs(:, a), contact%dofs(:, contact%mass%col(k))]
            end do
        end do
        call csr_from_element_dofs(n_free, pair_dofs, b)
    end subroutine b_pattern

    !> B at `lambda` on `b`, a copy of b_pattern's matrix (its values overwritten): the same
    !> sums in the same order as assemble_b, so the same values to the last bit.
    subroutine fill_b(contact, lambda, b, stat)
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda
        type(csr_matrix_t), intent(inout) :: b
        type(status_t), intent(out) :: stat
        integer :: a, k, col_node, i, j
        real(wp) :: row_factor(2)
        b%val = 0.0_wp
        row_factor = contact%slip_direction(lambda)
        do a = 1, contact%p()
            do k = contact%mass%row_start(a), contact%mass%row_start(a + 1) - 1
                col_node = contact%mass%col(k)
                do i = 1, 2
                    do j = 1, 2
                        call b%add_to(contact%dofs(i, a), contact%dofs(j, col_node), &
                            row_factor(i)*contact%mass%val(k)*contact%normal(j), stat)
                        if (.not. stat%ok()) return
                    end do
                end do
            end do
        end do
    end subroutine fill_b

    pure real(wp) function cross(u, v)
        real(wp), intent(in) :: u(2), v(2)
        cross = u(1)*v(2) - u(2)*v(1)
    end function cross

    !> lambda t - n, the direction of b_lambda's test functions on Gamma_C (docs/model.md,
    !> section 4), divided by `unit` (a power of two that keeps it and what it multiplies in
    !> range for huge |lambda|, contact_reduction::lambda_unit; default 1): the one place it
    !> is formed.
    pure function contact_slip_direction(this, lambda, unit) result(direction)
        class(contact_t), intent(in) :: this
        real(wp), intent(in) :: lambda
        real(wp), intent(in), optional :: unit
        real(wp) :: direction(2)
        if (present(unit)) then
            direction = lambda/unit*this%tangent - this%normal/unit
        else
            direction = lambda*this%tangent - this%normal
        end if
    end function contact_slip_direction
end module contact_boundary
