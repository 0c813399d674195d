! SPDX-License-Identifier: MIT
!> Gauss rules of any order, for the hierarchical elements of any degree: Gauss-Legendre on
!> the segment [-1, 1] and the collapsed (Duffy) product rule on the reference triangle
!> (0,0), (1,0), (0,1). Unlike quadrature.f90's fixed small tables, these are computed (Newton
!> on the Legendre recurrence), so their size is open-ended and held in allocatable arrays.
module gauss_rules
    use kinds, only: wp
    implicit none
    private
    public :: gauss_legendre, line_rule_exact, triangle_rule_exact

    !> Points and weights of one computed rule.
    type, public :: gauss_rule_t
        real(wp), allocatable :: points(:, :)   !! (dimension, n_points); 1 for lines
        real(wp), allocatable :: weights(:)     !! (n_points) sum to the reference measure
    contains
        procedure :: n_points => gauss_rule_n_points
    end type gauss_rule_t

    integer, parameter :: NEWTON_MAX = 100   !! Newton converges in < 10 steps from cos guesses

contains

    pure integer function gauss_rule_n_points(this)
        class(gauss_rule_t), intent(in) :: this
        gauss_rule_n_points = 0
        if (allocated(this%weights)) gauss_rule_n_points = size(this%weights)
    end function gauss_rule_n_points

    !> The n-point Gauss-Legendre rule on [-1, 1] (exact to degree 2n - 1): the roots of P_n
    !> by Newton from Tricomi's cosine guesses, weights 2 / ((1 - x^2) P_n'(x)^2). Symmetric
    !> by construction (the upper half is mirrored), so odd moments vanish exactly.
    pure subroutine gauss_legendre(n, x, w)
        integer, intent(in) :: n
        real(wp), intent(out) :: x(n), w(n)
        real(wp), parameter :: PI = acos(-1.0_wp)
        real(wp) :: root, p, dp, step
        integer :: i, it
        do i = 1, (n + 1)/2
            root = cos(PI*(real(i, wp) - 0.25_wp)/(real(n, wp) + 0.5_wp))
            do it = 1, NEWTON_MAX
                call legendre_and_derivative(n, root, p, dp)
                step = p/dp
                root = root - step
                if (abs(step) <= 2.0_wp*epsilon(1.0_wp)*abs(root)) exit
            end do
            call legendre_and_derivative(n, root, p, dp)
            x(i) = -root
            x(n + 1 - i) = root
            w(i) = 2.0_wp/((1.0_wp - root*root)*dp*dp)
            w(n + 1 - i) = w(i)
        end do
        if (mod(n, 2) == 1) x((n + 1)/2) = 0.0_wp
    end subroutine gauss_legendre

    !> P_n(x) and P_n'(x) by Bonnet's recurrence.
    pure subroutine legendre_and_derivative(n, x, p, dp)
        integer, intent(in) :: n
        real(wp), intent(in) :: x
        real(wp), intent(out) :: p, dp
        real(wp) :: previous, older
        integer :: k
        previous = 1.0_wp
        p = x
        if (n == 0) then
            p = 1.0_wp
            dp = 0.0_wp
            return
        end if
        do k = 2, n
            older = previous
            previous = p
            p = (real(2*k - 1, wp)*x*previous - real(k - 1, wp)*older)/real(k, wp)
        end do
        dp = real(n, wp)*(x*p - previous)/(x*x - 1.0_wp)
    end subroutine legendre_and_derivative

    !> Gauss-Legendre rule on [-1, 1] exact for polynomials of degree <= `degree`.
    pure function line_rule_exact(degree) result(rule)
        integer, intent(in) :: degree
        type(gauss_rule_t) :: rule
        integer :: n
        n = max(0, degree)/2 + 1
        allocate (rule%points(1, n), rule%weights(n))
        call gauss_legendre(n, rule%points(1, :), rule%weights)
    end function line_rule_exact

    !> Collapsed Gauss rule on the reference triangle (area 1/2) exact for polynomials of
    !> total degree <= `degree`: (u, v) in [-1, 1]^2 maps to y = (1 + v)/2,
    !> x = (1 + u)(1 - v)/4 with Jacobian (1 - v)/8. A polynomial of degree d in (x, y) is of
    !> degree d in u and d + 1 in v after the map, so n = ceil((d + 2)/2) points per direction.
    pure function triangle_rule_exact(degree) result(rule)
        integer, intent(in) :: degree
        type(gauss_rule_t) :: rule
        real(wp), allocatable :: x(:), w(:)
        integer :: n, i, j, q
        n = (max(0, degree) + 3)/2
        allocate (x(n), w(n))
        call gauss_legendre(n, x, w)
        allocate (rule%points(2, n*n), rule%weights(n*n))
        q = 0
        do j = 1, n
            do i = 1, n
                q = q + 1
                rule%points(2, q) = 0.5_wp*(1.0_wp + x(j))
                rule%points(1, q) = 0.25_wp*(1.0_wp + x(i))*(1.0_wp - x(j))
                rule%weights(q) = 0.125_wp*w(i)*w(j)*(1.0_wp - x(j))
            end do
        end do
    end function triangle_rule_exact
end module gauss_rules
