! SPDX-License-Identifier: MIT
!> The computed Gauss rules against closed forms: the n-point Gauss-Legendre rule integrates
!> s^k over [-1, 1] to 2/(k + 1) (k even) or 0 (odd) for k <= 2n - 1 and not for k = 2n,
!> its points are the roots of P_n; the collapsed triangle rule integrates x^i y^j over the
!> reference triangle to i! j! / (i + j + 2)! for i + j up to its degree. Up to degree 40,
!> beyond the hp elements' 2 x 20.
program test_gauss_rules
    use kinds, only: wp
    use gauss_rules, only: gauss_legendre, line_rule_exact, triangle_rule_exact, gauss_rule_t
    use testing, only: test_suite_t
    implicit none

    !> a rule sums n positive terms of a moment <= 2 with points computed to a few ulps:
    !> relative error a few hundred eps at n = 21
    real(wp), parameter :: TOL = 1.0e-13_wp
    type(test_suite_t) :: t
    integer :: n, degree

    t%name = 'test_gauss_rules'
    do n = 1, 21, 4
        call check_legendre(n)
    end do
    call check_line_rules()
    do degree = 0, 40, 5
        call check_triangle(degree)
    end do
    call t%report()

contains

    !> int_{-1}^{1} s^k ds
    pure real(wp) function line_moment(k)
        integer, intent(in) :: k
        line_moment = merge(2.0_wp/real(k + 1, wp), 0.0_wp, mod(k, 2) == 0)
    end function line_moment

    subroutine check_legendre(n)
        integer, intent(in) :: n
        real(wp) :: x(n), w(n), worst, p, previous, older, next_moment, error
        integer :: k, i, j
        character(len=8) :: label
        write (label, '(i0)') n
        call gauss_legendre(n, x, w)
        worst = 0.0_wp
        do k = 0, 2*n - 1
            worst = max(worst, abs(sum(w*x**k) - line_moment(k)))
        end do
        call t%check(trim(label)//'-point Gauss-Legendre: exact to degree 2n - 1', worst <= TOL)
        ! at degree 2n the error is int of the monic P_n squared,
        ! 2^(2n+1) (n!)^4 / ((2n + 1) ((2n)!)^2): 0.67 at n = 1, 7e-13 at n = 21
        next_moment = sum(w*x**(2*n))
        error = exp(real(2*n + 1, wp)*log(2.0_wp) + 4.0_wp*log_gamma(real(n + 1, wp)) - &
                    log(real(2*n + 1, wp)) - 2.0_wp*log_gamma(real(2*n + 1, wp)))
        call t%check(trim(label)//'-point Gauss-Legendre: at degree 2n, the error of the '// &
                     'closed form', abs(line_moment(2*n) - next_moment - error) <= &
                     1.0e-14_wp + 1.0e-10_wp*error)
        call t%check(trim(label)//'-point: ascending, symmetric, positive weights summing to 2', &
                     all(x(2:) > x(:n - 1)) .and. all(abs(x + x(n:1:-1)) <= 0.0_wp) .and. &
                     all(w > 0.0_wp) .and. abs(sum(w) - 2.0_wp) <= TOL)
        ! P_n at every point by Bonnet's recurrence: |P_n| <= 1 on [-1, 1], so an absolute
        ! bound of a few hundred eps says root
        worst = 0.0_wp
        do i = 1, n
            older = 1.0_wp
            p = x(i)
            do j = 2, n
                previous = p
                p = (real(2*j - 1, wp)*x(i)*previous - real(j - 1, wp)*older)/real(j, wp)
                older = previous
            end do
            if (n == 1) p = x(i)
            worst = max(worst, abs(p))
        end do
        call t%check(trim(label)//'-point: the points are the roots of P_n', worst <= TOL)
    end subroutine check_legendre

    subroutine check_line_rules()
        type(gauss_rule_t) :: rule
        integer :: degree, k
        real(wp) :: worst
        logical :: sizes
        worst = 0.0_wp
        sizes = .true.
        do degree = 0, 40
            rule = line_rule_exact(degree)
            sizes = sizes .and. rule%n_points() == degree/2 + 1 .and. size(rule%points, 1) == 1
            do k = 0, degree
                worst = max(worst, abs(sum(rule%weights*rule%points(1, :)**k) - line_moment(k)))
            end do
        end do
        call t%check('line_rule_exact(d): the fewest points, d/2 + 1, exact to degree d', &
                     sizes .and. worst <= TOL)
        call t%check('n_points of an empty rule is 0', empty_rule_points() == 0)
    end subroutine check_line_rules

    pure integer function empty_rule_points()
        type(gauss_rule_t) :: empty
        empty_rule_points = empty%n_points()
    end function empty_rule_points

    !> int over the reference triangle of x^i y^j = i! j! / (i + j + 2)!, through log_gamma
    !> (factorials to 42! overflow nothing, but their quotient is cleaner so).
    subroutine check_triangle(degree)
        integer, intent(in) :: degree
        type(gauss_rule_t) :: rule
        real(wp) :: exact, approx, worst
        integer :: i, j
        character(len=8) :: label
        write (label, '(i0)') degree
        rule = triangle_rule_exact(degree)
        worst = 0.0_wp
        do i = 0, degree
            do j = 0, degree - i
                exact = exp(log_gamma(real(i + 1, wp)) + log_gamma(real(j + 1, wp)) - &
                            log_gamma(real(i + j + 3, wp)))
                approx = sum(rule%weights*rule%points(1, :)**i*rule%points(2, :)**j)
                worst = max(worst, abs(approx - exact)/exact)
            end do
        end do
        call t%check('collapsed triangle rule exact to degree '//trim(label)// &
                     ' (relative to each moment)', worst <= 1.0e2_wp*TOL)
        call t%check('collapsed rule '//trim(label)//': points inside the triangle, '// &
                     'weights positive, area 1/2', all(rule%points >= 0.0_wp) .and. &
                     all(sum(rule%points, dim=1) <= 1.0_wp) .and. all(rule%weights > 0.0_wp) &
                     .and. abs(sum(rule%weights) - 0.5_wp) <= TOL)
    end subroutine check_triangle
end program test_gauss_rules
