! SPDX-License-Identifier: MIT
!> Isotropic plane-strain elasticity: Hooke's law and element stiffness matrices of the
!> bilinear form a(u, v) = int sigma(u) : eps(v).
module elasticity
    use kinds, only: wp
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, element_nodes_per_cell, element_dimension
    use quadrature, only: quadrature_rule_t, triangle_rule, quad_rule
    use shape_functions, only: evaluate_shape, reference_nodes, MAX_NODES
    use cell_geometry, only: det_range_of, jacobian_of, orientation_of, CELL_ANTICLOCKWISE, &
                             local_coordinates
    implicit none
    private
    public :: plane_strain_matrix, lame_coefficients, lame_ratio, element_stiffness, &
              stiffness_rule, load_rule, stiffness_tables, element_energy
    public :: ELEMENT_OK, ELEMENT_INVERTED, ELEMENT_BAD_ARGUMENT

    ! Outcomes of element_stiffness; the caller, which knows the cell number, words them.
    integer, parameter :: ELEMENT_OK = 0
    !> det J <= 0, or negligible by cell_geometry's test (the Gmsh reader's too)
    integer, parameter :: ELEMENT_INVERTED = 1
    integer, parameter :: ELEMENT_BAD_ARGUMENT = 2   !! unknown element or wrong array shapes

    !> What element_stiffness needs of the reference cell, the same for every cell of one
    !> element type: the stiffness rule and the reference gradients of the shape functions
    !> at its points and at the nodes (for the det J checks). A loop over cells builds it
    !> once (stiffness_tables) instead of evaluating the shape functions per cell.
    type, public :: stiffness_tables_t
        integer :: element = 0
        type(quadrature_rule_t) :: rule
        real(wp), allocatable :: at_points(:, :, :)   !! (2, nodes, rule points)
        real(wp), allocatable :: at_nodes(:, :, :)    !! (2, nodes, nodes); none for P1
    end type stiffness_tables_t

contains

    !> Plane-strain constitutive matrix, Voigt order (xx, yy, xy), engineering shear strain.
    pure function plane_strain_matrix(young, poisson) result(d)
        real(wp), intent(in) :: young, poisson   !! Pa, dimensionless (-1 < nu < 1/2)
        real(wp) :: d(3, 3), lame_l, shear_g
        call lame_coefficients(young, poisson, lame_l, shear_g)
        d = reshape([lame_l + 2.0_wp*shear_g, lame_l, 0.0_wp, &
                     lame_l, lame_l + 2.0_wp*shear_g, 0.0_wp, &
                     0.0_wp, 0.0_wp, shear_g], [3, 3])
    end function plane_strain_matrix

    !> Lame coefficients L = E nu / ((1 + nu)(1 - 2 nu)) and G = E / (2 (1 + nu)).
    pure subroutine lame_coefficients(young, poisson, lame_l, shear_g)
        real(wp), intent(in) :: young, poisson   !! Pa, dimensionless (-1 < nu < 1/2)
        real(wp), intent(out) :: lame_l, shear_g   !! Pa
        lame_l = young*poisson/((1.0_wp + poisson)*(1.0_wp - 2.0_wp*poisson))
        shear_g = 0.5_wp*young/(1.0_wp + poisson)
    end subroutine lame_coefficients

    !> L/G = 2 nu / (1 - 2 nu): how close to incompressible the material is (the spread of
    !> K's pivots, the locking of low-order elements).
    elemental real(wp) function lame_ratio(poisson)
        real(wp), intent(in) :: poisson
        lame_ratio = 2.0_wp*poisson/(1.0_wp - 2.0_wp*poisson)
    end function lame_ratio

    !> The quadrature rule element_stiffness uses: exact for affine cells (straight-sided
    !> triangles, parallelograms), where the integrand is a polynomial of degree 2(p - 1). P1:
    !> 1 point (degree 0), P2: degree 2, P3: degree 4 (6 points), P4: degree 6, Q1: 2 x 2
    !> Gauss, Q2: 3 x 3 Gauss. Empty for an unknown element.
    pure function stiffness_rule(element) result(rule)
        integer, intent(in) :: element
        type(quadrature_rule_t) :: rule
        select case (element)
        case (ELEMENT_P1); rule = triangle_rule(1)
        case (ELEMENT_P2); rule = triangle_rule(2)
        case (ELEMENT_Q1); rule = quad_rule(2)
        case (ELEMENT_Q2); rule = quad_rule(3)
        case (ELEMENT_P3); rule = triangle_rule(4)
        case (ELEMENT_P4); rule = triangle_rule(6)
        end select
    end function stiffness_rule

    !> The quadrature rule of the body-force loads: the stiffness rule, which is exact for
    !> N_a on affine cells (degree p <= 2(p - 1) from P2 on), except for the cubic and quartic
    !> triangles, which take a rule exact to degree 2p (6 for P3, 8 for P4): exact for N_a
    !> times a linear density, and for a mass-type product N_a N_b.
    pure function load_rule(element) result(rule)
        integer, intent(in) :: element
        type(quadrature_rule_t) :: rule
        select case (element)
        case (ELEMENT_P3); rule = triangle_rule(6)
        case (ELEMENT_P4); rule = triangle_rule(8)
        case default; rule = stiffness_rule(element)
        end select
    end function load_rule

    !> The stiffness tables of `element` (see stiffness_tables_t); empty for an unknown one.
    pure function stiffness_tables(element) result(tables)
        integer, intent(in) :: element
        type(stiffness_tables_t) :: tables
        real(wp) :: values(MAX_NODES), gradients(2, MAX_NODES), ref_nodes(2, MAX_NODES)
        integer :: n, q
        tables%element = element
        n = element_nodes_per_cell(element)
        tables%rule = stiffness_rule(element)
        allocate (tables%at_points(2, n, tables%rule%n_points))
        do q = 1, tables%rule%n_points
            call evaluate_shape(element, tables%rule%points(:, q), values, gradients)
            tables%at_points(:, :, q) = gradients(:, 1:n)
        end do
        ! det J at the nodes too, unless J is constant (P1): a bilinear quadrilateral with a
        ! re-entrant corner can have det J > 0 at every Gauss point, and for Q1 det J is
        ! linear in (xi, eta), so its minimum is at a corner.
        if (element == ELEMENT_P1) then
            allocate (tables%at_nodes(2, n, 0))
        else
            allocate (tables%at_nodes(2, n, n))
            call reference_nodes(element, ref_nodes)
            do q = 1, n
                call evaluate_shape(element, ref_nodes(:, q), values, gradients)
                tables%at_nodes(:, :, q) = gradients(:, 1:n)
            end do
        end if
    end function stiffness_tables

    !> Element stiffness matrix in dof order (u_x1, u_y1, u_x2, u_y2, ...), integrated with
    !> stiffness_rule(element). `info` is ELEMENT_OK, or ELEMENT_INVERTED when det J is
    !> non-positive or negligible at a node or quadrature point (an inverted or degenerate
    !> cell), or ELEMENT_BAD_ARGUMENT; `ke` is then zero. `min_det` is the smallest det J
    !> met, for the caller's message. `tables` (stiffness_tables(element)) spares a loop over
    !> cells the shape functions' evaluation per cell.
    pure subroutine element_stiffness(element, xy, young, poisson, ke, info, min_det, tables)
        integer, intent(in) :: element
        real(wp), intent(in) :: xy(:, :)            !! (2, nodes per cell), metres
        real(wp), intent(in) :: young, poisson      !! Pa, dimensionless
        real(wp), intent(out) :: ke(:, :)           !! (2 nodes, 2 nodes)
        integer, intent(out) :: info
        real(wp), intent(out), optional :: min_det
        type(stiffness_tables_t), intent(in), optional :: tables
        integer :: n, n_dim
        real(wp) :: smallest

        ke = 0.0_wp
        if (present(min_det)) min_det = 0.0_wp
        n = element_nodes_per_cell(element)
        n_dim = element_dimension(element)
        ! the plane-strain kernel below: a 2-d element only
        if (n == 0 .or. n_dim /= 2 .or. size(xy, 1) /= n_dim .or. size(xy, 2) /= n .or. &
            any(shape(ke) /= [n_dim*n, n_dim*n])) then
            info = ELEMENT_BAD_ARGUMENT
            return
        end if
        if (present(tables)) then
            if (tables%element /= element) then
                info = ELEMENT_BAD_ARGUMENT
                return
            end if
            call integrate(tables, local_coordinates(element, xy), ke, info, smallest)
        else
            call integrate(stiffness_tables(element), local_coordinates(element, xy), ke, &
                           info, smallest)
        end if
        if (present(min_det)) min_det = smallest

    contains

        !> (a pure internal procedure may not define its host's variables: all are arguments)
        pure subroutine integrate(t, xy, ke, info, smallest)
            type(stiffness_tables_t), intent(in) :: t
            real(wp), intent(in) :: xy(:, :)   !! local_coordinates of the cell
            real(wp), intent(inout) :: ke(:, :)
            integer, intent(out) :: info
            real(wp), intent(out) :: smallest
            real(wp) :: grad(2, MAX_NODES), jacobian(2, 2), inverse_t(2, 2), det
            real(wp) :: largest, node_min, node_max, lame_l, shear_g, c_normal, &
                        c_lame, c_shear
            real(wp) :: ax, ay, bx, by
            integer :: a, b, q

            call det_range_of(xy, t%at_points, smallest, largest)
            if (size(t%at_nodes, 3) > 0) then
                call det_range_of(xy, t%at_nodes, node_min, node_max)
                smallest = min(node_min, smallest)
                largest = max(node_max, largest)
            end if
            if (orientation_of(smallest, largest, xy) /= CELL_ANTICLOCKWISE) then
                info = ELEMENT_INVERTED
                return
            end if
            info = ELEMENT_OK

            call lame_coefficients(young, poisson, lame_l, shear_g)
            do q = 1, t%rule%n_points
                call jacobian_of(xy, t%at_points(:, :, q), jacobian, det)
                ! grad_x N = J^{-T} grad_xi N
                inverse_t = reshape([jacobian(2, 2), -jacobian(1, 2), &
                                     -jacobian(2, 1), jacobian(1, 1)], [2, 2])/det
                grad(:, 1:n) = matmul(inverse_t, t%at_points(:, :, q))
                c_normal = (lame_l + 2.0_wp*shear_g)*t%rule%weights(q)*det
                c_lame = lame_l*t%rule%weights(q)*det
                c_shear = shear_g*t%rule%weights(q)*det
                ! Node block (a, b) of B^T D B, with B_a = [ax 0; 0 ay; ay ax] the strain of
                ! N_a e_x, N_a e_y and D = plane_strain_matrix written out: the products with
                ! the zeros of B and D cost more than the rest of the assembly together.
                ! Only blocks a <= b are integrated; the copy below makes ke exactly symmetric.
                do b = 1, n
                    bx = grad(1, b)
                    by = grad(2, b)
                    do a = 1, b
                        ax = grad(1, a)
                        ay = grad(2, a)
                        ke(2*a - 1, 2*b - 1) = ke(2*a - 1, 2*b - 1) + c_normal*ax*bx + &
                                               c_shear*ay*by
                        ke(2*a - 1, 2*b) = ke(2*a - 1, 2*b) + c_lame*ax*by + c_shear*ay*bx
                        ke(2*a, 2*b - 1) = ke(2*a, 2*b - 1) + c_lame*ay*bx + c_shear*ax*by
                        ke(2*a, 2*b) = ke(2*a, 2*b) + c_normal*ay*by + c_shear*ax*bx
                    end do
                end do
            end do
            do b = 1, size(ke, 2)
                do a = b + 1, size(ke, 1)
                    ke(a, b) = ke(b, a)
                end do
            end do
        end subroutine integrate
    end subroutine element_stiffness

    !> a_K(u, z) = z' K_K u = int_K sigma(u) : eps(z) of one cell, with u, z its nodal
    !> values in dof order, by the quadrature of element_stiffness: O(nodes) per point, where
    !> forming K_K costs O(nodes^2). For cells the assembly has accepted (no det J check).
    pure real(wp) function element_energy(tables, xy, young, poisson, u, z) result(energy)
        type(stiffness_tables_t), intent(in) :: tables
        real(wp), intent(in) :: xy(:, :)            !! (2, nodes per cell)
        real(wp), intent(in) :: young, poisson
        real(wp), intent(in) :: u(:), z(:)          !! (2 nodes)
        real(wp) :: jacobian(2, 2), inverse_t(2, 2), det, grad(2, MAX_NODES), lame_l, &
                    shear_g, eps_u(3), eps_z(3), sigma(3), local(size(xy, 1), size(xy, 2))
        integer :: n, q
        n = size(xy, 2)
        local = local_coordinates(tables%element, xy)   ! as element_stiffness integrates
        call lame_coefficients(young, poisson, lame_l, shear_g)
        energy = 0.0_wp
        do q = 1, tables%rule%n_points
            call jacobian_of(local, tables%at_points(:, :, q), jacobian, det)
            inverse_t = reshape([jacobian(2, 2), -jacobian(1, 2), &
                                 -jacobian(2, 1), jacobian(1, 1)], [2, 2])/det
            grad(:, 1:n) = matmul(inverse_t, tables%at_points(:, :, q))
            eps_u = strain(u)
            eps_z = strain(z)
            ! plane strain Hooke's law, engineering shear strain (plane_strain_matrix)
            sigma = [(lame_l + 2.0_wp*shear_g)*eps_u(1) + lame_l*eps_u(2), &
                     lame_l*eps_u(1) + (lame_l + 2.0_wp*shear_g)*eps_u(2), shear_g*eps_u(3)]
            energy = energy + tables%rule%weights(q)*det*dot_product(sigma, eps_z)
        end do

    contains

        !> (eps_xx, eps_yy, 2 eps_xy) of nodal values v at the current point
        pure function strain(v) result(e)
            real(wp), intent(in) :: v(:)
            real(wp) :: e(3)
            e(1) = dot_product(grad(1, 1:n), v(1:2*n - 1:2))
            e(2) = dot_product(grad(2, 1:n), v(2:2*n:2))
            e(3) = dot_product(grad(2, 1:n), v(1:2*n - 1:2)) + &
                   dot_product(grad(1, 1:n), v(2:2*n:2))
        end function strain
    end function element_energy
end module elasticity
