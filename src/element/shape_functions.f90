! SPDX-License-Identifier: MIT
!> Lagrange shape functions on the reference elements, in Gmsh node order: the triangle
!> (0,0), (1,0), (0,1) for P1/P2 and the square [-1, 1]^2 for Q1/Q2; corners anticlockwise,
!> then mid-edge nodes (edge k from corner k to corner k+1), then the Q2 centre. Edges use
!> the segment [-1, 1] with the end nodes at -1 and +1 and the mid node at 0.
module shape_functions
    use kinds, only: wp
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2
    implicit none
    private
    public :: evaluate_shape, evaluate_line_shape, reference_nodes, MAX_NODES

    integer, parameter :: MAX_NODES = 9   !! nodes of the largest element (Q2)

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
        real(wp), intent(in) :: xi(2)
        real(wp), intent(out) :: values(:)          !! (>= nodes per cell)
        real(wp), intent(out) :: gradients(:, :)    !! (2, >= nodes per cell)
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
        end select
    end subroutine evaluate_shape

    !> Values and d/ds on the reference segment [-1, 1] of the 2-node (ends at -1, +1) or
    !> 3-node (ends, then the mid node at 0) edge functions, in boundary-edge node order.
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
        end select
    end subroutine evaluate_line_shape

    !> Reference coordinates of the nodes of `element`, columns in node order; unused
    !> columns (and every column for an unknown code) are zero.
    pure subroutine reference_nodes(element, xi)
        integer, intent(in) :: element
        real(wp), intent(out) :: xi(:, :)   !! (2, >= nodes per cell)
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
