! SPDX-License-Identifier: MIT
!> Gauss quadrature rules on the reference elements: the triangle (0,0), (1,0), (0,1) of area
!> 1/2, the square [-1, 1]^2 and the segment [-1, 1]. Rules are small fixed-size values, so
!> element loops need no allocation.
module quadrature
    use kinds, only: wp
    implicit none
    private
    public :: triangle_rule, quad_rule, line_rule, MAX_POINTS

    integer, parameter :: MAX_POINTS = 25   !! 5 x 5 collapsed Gauss, the largest rule

    !> Points and weights of one rule; only the first `n_points` entries are meaningful.
    type, public :: quadrature_rule_t
        integer :: n_points = 0
        real(wp) :: points(2, MAX_POINTS) = 0.0_wp   !! reference coordinates; 1D rules use row 1
        real(wp) :: weights(MAX_POINTS) = 0.0_wp     !! sum to the reference measure
    end type quadrature_rule_t

    ! Dunavant's 6-point rule (degree 4) and Radon's 7-point rule (degree 5) in closed form,
    ! so no digit is lost to a truncated table. Weights are for a triangle of area 1.
    real(wp), parameter :: D4_A1 = (8.0_wp - sqrt(10.0_wp) &
                                    + sqrt(38.0_wp - 44.0_wp*sqrt(0.4_wp)))/18.0_wp
    real(wp), parameter :: D4_A2 = (8.0_wp - sqrt(10.0_wp) &
                                    - sqrt(38.0_wp - 44.0_wp*sqrt(0.4_wp)))/18.0_wp
    real(wp), parameter :: D4_W1 = (620.0_wp + sqrt(213125.0_wp &
                                    - 53320.0_wp*sqrt(10.0_wp)))/3720.0_wp
    real(wp), parameter :: D4_W2 = (620.0_wp - sqrt(213125.0_wp &
                                    - 53320.0_wp*sqrt(10.0_wp)))/3720.0_wp
    real(wp), parameter :: R5_A1 = (6.0_wp - sqrt(15.0_wp))/21.0_wp
    real(wp), parameter :: R5_A2 = (6.0_wp + sqrt(15.0_wp))/21.0_wp
    real(wp), parameter :: R5_W1 = (155.0_wp - sqrt(15.0_wp))/1200.0_wp
    real(wp), parameter :: R5_W2 = (155.0_wp + sqrt(15.0_wp))/1200.0_wp

contains

    !> The smallest stored rule on the reference triangle integrating every polynomial of
    !> total degree <= `degree` exactly (degree 1: 1 point, 2: 3, 3-4: 6, 5: 7, 6: 16, 7-8:
    !> 25). A degree above 8 gives an empty rule (n_points = 0), which callers must treat as
    !> an error. Degrees 6 to 8 (the loads of P3 and P4, the stiffness of P4) use the
    !> collapsed (Duffy) product of n-point Gauss-Legendre rules, n = 4 or 5: a few more
    !> points than Dunavant's tables (12, 16), but every weight and point in closed form.
    pure function triangle_rule(degree) result(rule)
        integer, intent(in) :: degree
        type(quadrature_rule_t) :: rule
        select case (degree)
        case (:1)
            rule%n_points = 1
            rule%points(:, 1) = [1.0_wp, 1.0_wp]/3.0_wp
            rule%weights(1) = 0.5_wp
        case (2)
            ! Interior points (1/6, 1/6), ...: the edge-midpoint rule is also degree 2, but its
            ! points are the P2 mid-nodes, where all corner functions vanish (singular mass).
            rule%n_points = 3
            call add_orbit(rule, 1, 1.0_wp/6.0_wp, 1.0_wp/6.0_wp)
        case (3:4)
            rule%n_points = 6
            call add_orbit(rule, 1, D4_A1, 0.5_wp*D4_W1)
            call add_orbit(rule, 4, D4_A2, 0.5_wp*D4_W2)
        case (5)
            rule%n_points = 7
            rule%points(:, 1) = [1.0_wp, 1.0_wp]/3.0_wp
            rule%weights(1) = 0.5_wp*9.0_wp/40.0_wp
            call add_orbit(rule, 2, R5_A1, 0.5_wp*R5_W1)
            call add_orbit(rule, 5, R5_A2, 0.5_wp*R5_W2)
        case (6)
            rule = collapsed_rule(4)
        case (7:8)
            rule = collapsed_rule(5)
        case default
            rule%n_points = 0
        end select
    end function triangle_rule

    !> The square rule quad_rule(n) mapped onto the reference triangle by the collapse
    !> (u, v) -> (x, y) = ((1 + u)(1 - v)/4, (1 + v)/2), Jacobian (1 - v)/8: a polynomial of
    !> total degree d becomes one of degree d in u and d + 1 in v, so the rule is exact for
    !> d <= 2n - 2. Points stay inside the triangle, weights positive.
    pure function collapsed_rule(n) result(rule)
        integer, intent(in) :: n
        type(quadrature_rule_t) :: rule
        integer :: q
        real(wp) :: u, v
        rule = quad_rule(n)
        do q = 1, rule%n_points
            u = rule%points(1, q)
            v = rule%points(2, q)
            rule%points(:, q) = [0.25_wp*(1.0_wp + u)*(1.0_wp - v), 0.5_wp*(1.0_wp + v)]
            rule%weights(q) = rule%weights(q)*0.125_wp*(1.0_wp - v)
        end do
    end function collapsed_rule

    !> Tensor Gauss-Legendre rule with `n` points per direction on [-1, 1]^2 (1 <= n <= 5;
    !> exact for degree <= 2n - 1 in each variable). Other n give an empty rule.
    pure function quad_rule(n) result(rule)
        integer, intent(in) :: n
        type(quadrature_rule_t) :: rule, line
        integer :: i, j, q
        line = line_rule(n)
        rule%n_points = line%n_points**2
        q = 0
        do j = 1, line%n_points
            do i = 1, line%n_points
                q = q + 1
                rule%points(:, q) = [line%points(1, i), line%points(1, j)]
                rule%weights(q) = line%weights(i)*line%weights(j)
            end do
        end do
    end function quad_rule

    !> Gauss-Legendre rule with `n` points on [-1, 1] (1 <= n <= 5; exact for degree
    !> <= 2n - 1), stored in row 1 of `points`. Other n give an empty rule.
    pure function line_rule(n) result(rule)
        integer, intent(in) :: n
        type(quadrature_rule_t) :: rule
        real(wp) :: a, b
        select case (n)
        case (1)
            rule%points(1, 1:1) = [0.0_wp]
            rule%weights(1:1) = [2.0_wp]
        case (2)
            a = 1.0_wp/sqrt(3.0_wp)
            rule%points(1, 1:2) = [-a, a]
            rule%weights(1:2) = [1.0_wp, 1.0_wp]
        case (3)
            a = sqrt(0.6_wp)
            rule%points(1, 1:3) = [-a, 0.0_wp, a]
            rule%weights(1:3) = [5.0_wp, 8.0_wp, 5.0_wp]/9.0_wp
        case (4)
            a = sqrt(3.0_wp/7.0_wp - 2.0_wp/7.0_wp*sqrt(1.2_wp))
            b = sqrt(3.0_wp/7.0_wp + 2.0_wp/7.0_wp*sqrt(1.2_wp))
            rule%points(1, 1:4) = [-b, -a, a, b]
            rule%weights(1:4) = [18.0_wp - sqrt(30.0_wp), 18.0_wp + sqrt(30.0_wp), &
                                 18.0_wp + sqrt(30.0_wp), 18.0_wp - sqrt(30.0_wp)]/36.0_wp
        case (5)
            a = sqrt(5.0_wp - 2.0_wp*sqrt(10.0_wp/7.0_wp))/3.0_wp
            b = sqrt(5.0_wp + 2.0_wp*sqrt(10.0_wp/7.0_wp))/3.0_wp
            rule%points(1, 1:5) = [-b, -a, 0.0_wp, a, b]
            rule%weights(1:5) = [322.0_wp - 13.0_wp*sqrt(70.0_wp), &
                                 322.0_wp + 13.0_wp*sqrt(70.0_wp), 512.0_wp, &
                                 322.0_wp + 13.0_wp*sqrt(70.0_wp), &
                                 322.0_wp - 13.0_wp*sqrt(70.0_wp)]/900.0_wp
        case default
            rule%n_points = 0
            return
        end select
        rule%n_points = n
    end function line_rule

    !> The three points (a, a), (1 - 2a, a), (a, 1 - 2a) with weight w, from index `first`.
    pure subroutine add_orbit(rule, first, a, w)
        type(quadrature_rule_t), intent(inout) :: rule
        integer, intent(in) :: first
        real(wp), intent(in) :: a, w
        rule%points(:, first) = [a, a]
        rule%points(:, first + 1) = [1.0_wp - 2.0_wp*a, a]
        rule%points(:, first + 2) = [a, 1.0_wp - 2.0_wp*a]
        rule%weights(first:first + 2) = w
    end subroutine add_orbit
end module quadrature
