! SPDX-License-Identifier: MIT
!> Lagrange shape functions on the reference elements, in Gmsh node order: the triangle
!> (0,0), (1,0), (0,1) for P1 to P4 and the square [-1, 1]^2 for Q1/Q2; corners
!> anticlockwise, then edge nodes (edge k from corner k to corner k+1), then interior nodes
!> (element_types' triangle_lattice). Edges use the segment [-1, 1] with the end nodes at -1
!> and +1, then the inner nodes equally spaced from -1 towards +1. Reference points and
!> gradients have element_dimension(element) components (2 for every element here).
module shape_functions
    use kinds, only: wp
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, element_degree, element_nodes_per_cell, &
                             triangle_lattice
    implicit none
    private
    public :: evaluate_shape, evaluate_line_shape, reference_nodes, MAX_NODES, MAX_EDGE_NODES

    integer, parameter :: MAX_NODES = 15   !! nodes of the largest element (P4)
    integer, parameter :: MAX_EDGE_NODES = 5   !! nodes of the longest edge (P4)

    ! Reference coordinates of the Q2 nodes; Q1 uses the first four.
    real(wp), parameter :: QUAD_XI(9) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, &
                                         0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp, 0.0_wp]
    real(wp), parameter :: QUAD_ETA(9) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, &
                                          -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp]

contains

    !> Values and reference gradients (d/dxi, d/deta) of the shape functions of `element` at
    !> the reference point `xi`. Only the first nodes-per-cell entries are written, so
    !> MAX_NODES-sized buffers serve every element. Unknown element codes leave zeros.
    pure subroutine evaluate_shape(element, xi, values, gradients)
        integer, intent(in) :: element
        real(wp), intent(in) :: xi(:)               !! (element_dimension(element))
        real(wp), intent(out) :: values(:)          !! (>= nodes per cell)
        real(wp), intent(out) :: gradients(:, :)    !! (element dimension, >= nodes per cell)
        real(wp) :: l1, l2, l3, lx(3), ly(3), dlx(3), dly(3)
        integer :: a, ix, iy

        values = 0.0_wp
        gradients = 0.0_wp
        select case (element)
        case (ELEMENT_P1)
            values(1:3) = [1.0_wp - xi(1) - xi(2), xi(1), xi(2)]
            gradients(:, 1) = [-1.0_wp, -1.0_wp]
            gradients(:, 2) = [1.0_wp, 0.0_wp]
            gradients(:, 3) = [0.0_wp, 1.0_wp]
        case (ELEMENT_P2)
            ! Barycentric coordinates l1, l2, l3 with grad l1 = (-1,-1), grad l2 = (1,0),
            ! grad l3 = (0,1).
            l1 = 1.0_wp - xi(1) - xi(2)
            l2 = xi(1)
            l3 = xi(2)
            values(1:6) = [l1*(2.0_wp*l1 - 1.0_wp), l2*(2.0_wp*l2 - 1.0_wp), &
                           l3*(2.0_wp*l3 - 1.0_wp), 4.0_wp*l1*l2, 4.0_wp*l2*l3, 4.0_wp*l3*l1]
            gradients(:, 1) = (4.0_wp*l1 - 1.0_wp)*[-1.0_wp, -1.0_wp]
            gradients(:, 2) = [4.0_wp*l2 - 1.0_wp, 0.0_wp]
            gradients(:, 3) = [0.0_wp, 4.0_wp*l3 - 1.0_wp]
            gradients(:, 4) = 4.0_wp*[l1 - l2, -l2]
            gradients(:, 5) = 4.0_wp*[l3, l2]
            gradients(:, 6) = 4.0_wp*[-l3, l1 - l3]
        case (ELEMENT_Q1)
            do a = 1, 4
                values(a) = 0.25_wp*(1.0_wp + QUAD_XI(a)*xi(1))*(1.0_wp + QUAD_ETA(a)*xi(2))
                gradients(1, a) = 0.25_wp*QUAD_XI(a)*(1.0_wp + QUAD_ETA(a)*xi(2))
                gradients(2, a) = 0.25_wp*QUAD_ETA(a)*(1.0_wp + QUAD_XI(a)*xi(1))
            end do
        case (ELEMENT_Q2)
            ! Products of 1D quadratics, indexed by node coordinate -1, 0, +1 -> 1, 2, 3.
            call line_quadratic(xi(1), lx, dlx)
            call line_quadratic(xi(2), ly, dly)
            do a = 1, 9
                ix = nint(QUAD_XI(a)) + 2
                iy = nint(QUAD_ETA(a)) + 2
                values(a) = lx(ix)*ly(iy)
                gradients(:, a) = [dlx(ix)*ly(iy), lx(ix)*dly(iy)]
            end do
        case (ELEMENT_P3, ELEMENT_P4)
            call lagrange_triangle(element, xi, values, gradients)
        end select
    end subroutine evaluate_shape

    !> Silvester's form of the Lagrange triangle of degree p: the node at lattice index
    !> (i1, i2, i3) has N = s_i1(l1) s_i2(l2) s_i3(l3), s_i(l) = prod_{m<i} (p l - m)/(m + 1),
    !> which is 1 at l = i/p and 0 at l = 0, 1/p, ..., (i - 1)/p. Gradients by the product
    !> rule, with grad l1 = (-1, -1), grad l2 = (1, 0), grad l3 = (0, 1).
    pure subroutine lagrange_triangle(element, xi, values, gradients)
        integer, intent(in) :: element
        real(wp), intent(in) :: xi(:)
        real(wp), intent(inout) :: values(:), gradients(:, :)
        integer :: lattice(3, MAX_NODES), p, a, k
        real(wp) :: l(3), s(0:4, 3), ds(0:4, 3)
        p = element_degree(element)
        call triangle_lattice(element, lattice)
        l = [1.0_wp - xi(1) - xi(2), xi(1), xi(2)]
        do k = 1, 3
            call silvester(p, l(k), s(:, k), ds(:, k))
        end do
        do a = 1, element_nodes_per_cell(element)
            associate (i1 => lattice(1, a), i2 => lattice(2, a), i3 => lattice(3, a))
                values(a) = s(i1, 1)*s(i2, 2)*s(i3, 3)
                gradients(1, a) = -ds(i1, 1)*s(i2, 2)*s(i3, 3) + s(i1, 1)*ds(i2, 2)*s(i3, 3)
                gradients(2, a) = -ds(i1, 1)*s(i2, 2)*s(i3, 3) + s(i1, 1)*s(i2, 2)*ds(i3, 3)
            end associate
        end do
    end subroutine lagrange_triangle

    !> s_i(l) and d s_i / d l for i = 0..p (at most 4), see lagrange_triangle.
    pure subroutine silvester(p, l, s, ds)
        integer, intent(in) :: p
        real(wp), intent(in) :: l
        real(wp), intent(out) :: s(0:4), ds(0:4)
        real(wp) :: factor
        integer :: i
        s = 0.0_wp
        ds = 0.0_wp
        s(0) = 1.0_wp
        do i = 1, p
            factor = (p*l - real(i - 1, wp))/real(i, wp)
            ds(i) = ds(i - 1)*factor + s(i - 1)*real(p, wp)/real(i, wp)
            s(i) = s(i - 1)*factor
        end do
    end subroutine silvester

    !> Values and d/ds on the reference segment [-1, 1] of the edge functions with `n_nodes`
    !> (2 to 5) nodes, in boundary-edge node order: the ends at -1 and +1, then the inner nodes
    !> -1 + 2k/(n_nodes - 1), k = 1, ..., n_nodes - 2 (the mid node 0 for 3 nodes).
    pure subroutine evaluate_line_shape(n_nodes, s, values, derivatives)
        integer, intent(in) :: n_nodes
        real(wp), intent(in) :: s
        real(wp), intent(out) :: values(:), derivatives(:)   !! (>= n_nodes)
        real(wp) :: l(3), dl(3)
        values = 0.0_wp
        derivatives = 0.0_wp
        select case (n_nodes)
        case (2)
            values(1:2) = [0.5_wp*(1.0_wp - s), 0.5_wp*(1.0_wp + s)]
            derivatives(1:2) = [-0.5_wp, 0.5_wp]
        case (3)
            call line_quadratic(s, l, dl)
            values(1:3) = l([1, 3, 2])
            derivatives(1:3) = dl([1, 3, 2])
        case (4:MAX_EDGE_NODES)
            call line_lagrange(n_nodes, s, values, derivatives)
        end select
    end subroutine evaluate_line_shape

    !> The 1D Lagrange functions of equally spaced nodes in edge order (see
    !> evaluate_line_shape), as products over the other nodes.
    pure subroutine line_lagrange(n_nodes, s, values, derivatives)
        integer, intent(in) :: n_nodes
        real(wp), intent(in) :: s
        real(wp), intent(inout) :: values(:), derivatives(:)
        real(wp) :: nodes(MAX_EDGE_NODES), term
        integer :: a, b, c
        nodes(1:2) = [-1.0_wp, 1.0_wp]
        do a = 3, n_nodes
            nodes(a) = -1.0_wp + 2.0_wp*real(a - 2, wp)/real(n_nodes - 1, wp)
        end do
        do a = 1, n_nodes
            values(a) = 1.0_wp
            derivatives(a) = 0.0_wp
            do b = 1, n_nodes
                if (b == a) cycle
                values(a) = values(a)*(s - nodes(b))/(nodes(a) - nodes(b))
                term = 1.0_wp/(nodes(a) - nodes(b))
                do c = 1, n_nodes
                    if (c == a .or. c == b) cycle
                    term = term*(s - nodes(c))/(nodes(a) - nodes(c))
                end do
                derivatives(a) = derivatives(a) + term
            end do
        end do
    end subroutine line_lagrange

    !> Reference coordinates of the nodes of `element`, columns in node order; unused
    !> columns (and every column for an unknown code) are zero.
    pure subroutine reference_nodes(element, xi)
        integer, intent(in) :: element
        real(wp), intent(out) :: xi(:, :)   !! (element dimension, >= nodes per cell)
        integer :: lattice(3, MAX_NODES), n
        xi = 0.0_wp
        select case (element)
        case (ELEMENT_P1)
            xi(:, 1:3) = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 3])
        case (ELEMENT_P2)
            xi(:, 1:6) = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
                                  0.5_wp, 0.0_wp, 0.5_wp, 0.5_wp, 0.0_wp, 0.5_wp], [2, 6])
        case (ELEMENT_Q1)
            xi(1, 1:4) = QUAD_XI(1:4)
            xi(2, 1:4) = QUAD_ETA(1:4)
        case (ELEMENT_Q2)
            xi(1, 1:9) = QUAD_XI
            xi(2, 1:9) = QUAD_ETA
        case (ELEMENT_P3, ELEMENT_P4)
            call triangle_lattice(element, lattice)
            n = element_nodes_per_cell(element)
            xi(:, 1:n) = real(lattice(2:3, 1:n), wp)/real(element_degree(element), wp)
        end select
    end subroutine reference_nodes

    !> The 1D quadratic Lagrange functions of the nodes -1, 0, +1 and their derivatives.
    pure subroutine line_quadratic(s, l, dl)
        real(wp), intent(in) :: s
        real(wp), intent(out) :: l(3), dl(3)
        l = [0.5_wp*s*(s - 1.0_wp), 1.0_wp - s*s, 0.5_wp*s*(s + 1.0_wp)]
        dl = [s - 0.5_wp, -2.0_wp*s, s + 0.5_wp]
    end subroutine line_quadratic
end module shape_functions
