! SPDX-License-Identifier: MIT
!> Quadrature rules integrate monomials exactly up to their degree; shape functions are
!> nodal (Kronecker delta), sum to one, and their gradients match finite differences.
program test_quadrature
    use kinds, only: wp
    use element_types, only: ELEMENT_P1, MAX_ELEMENT, element_nodes_per_cell, element_name
    use quadrature, only: quadrature_rule_t, triangle_rule, quad_rule, line_rule
    use shape_functions, only: evaluate_shape, evaluate_line_shape, reference_nodes, MAX_NODES
    use testing, only: test_suite_t
    implicit none
    ! Rules and closed-form points: a few ulps per point, summed over <= 16 points.
    real(wp), parameter :: EXACT_TOL = 1.0e-14_wp
    type(test_suite_t) :: t
    type(quadrature_rule_t) :: empty
    integer :: degree, n, element

    t%name = 'test_quadrature'
    do degree = 1, 8
        if (degree == 3 .or. degree == 7) cycle
        call check_triangle(degree)
    end do
    empty = triangle_rule(9)
    call t%check('triangle degree 9 is not available (empty rule)', empty%n_points == 0)
    do n = 1, 5
        call check_line_and_quad(n)
    end do
    do element = ELEMENT_P1, MAX_ELEMENT
        call check_shape(element)
    end do
    call check_line_shape()
    call t%report()

contains

    !> int over the reference triangle of x^i y^j = i! j! / (i + j + 2)!
    subroutine check_triangle(degree)
        integer, intent(in) :: degree
        type(quadrature_rule_t) :: rule
        integer :: i, j
        real(wp) :: approx, exact, worst
        character(len=8) :: label
        rule = triangle_rule(degree)
        worst = 0.0_wp
        do i = 0, degree
            do j = 0, degree - i
                approx = sum(rule%weights(1:rule%n_points)*rule%points(1, 1:rule%n_points)**i &
                             *rule%points(2, 1:rule%n_points)**j)
                exact = gamma(real(i + 1, wp))*gamma(real(j + 1, wp))/gamma(real(i + j + 3, wp))
                worst = max(worst, abs(approx - exact)/exact)
            end do
        end do
        write (label, '(i0)') degree
        call t%check('triangle rule exact to degree '//trim(label), worst <= EXACT_TOL)
        ! One degree more is not integrated exactly: the rule is what it says, not more.
        if (degree /= 2) then
            approx = sum(rule%weights(1:rule%n_points)*rule%points(1, 1:rule%n_points) &
                         **(degree + 1))
            exact = gamma(real(degree + 2, wp))/gamma(real(degree + 4, wp))
            call t%check('triangle rule '//trim(label)//' not exact one degree higher', &
                         abs(approx - exact) > 1.0e3_wp*EXACT_TOL*exact)
        end if
    end subroutine check_triangle

    !> n-point Gauss-Legendre on [-1, 1]: int s^k = 2/(k+1) for even k, 0 for odd, k <= 2n-1.
    subroutine check_line_and_quad(n)
        integer, intent(in) :: n
        type(quadrature_rule_t) :: line, square
        integer :: i, j
        real(wp) :: worst, exact
        character(len=8) :: label
        write (label, '(i0)') n
        line = line_rule(n)
        square = quad_rule(n)
        worst = 0.0_wp
        do i = 0, 2*n - 1
            do j = 0, 2*n - 1
                exact = moment(i)*moment(j)
                worst = max(worst, abs(sum(square%weights(1:square%n_points) &
                    *square%points(1, 1:square%n_points)**i &
                    *square%points(2, 1:square%n_points)**j) - exact))
            end do
            worst = max(worst, abs(sum(line%weights(1:n)*line%points(1, 1:n)**i) - moment(i)))
        end do
        call t%check(trim(label)//'-point Gauss and its square exact to degree 2n - 1', &
                     line%n_points == n .and. square%n_points == n*n .and. worst <= EXACT_TOL)
    end subroutine check_line_and_quad

    pure real(wp) function moment(k)
        integer, intent(in) :: k
        moment = merge(2.0_wp/(k + 1), 0.0_wp, modulo(k, 2) == 0)
    end function moment

    subroutine check_shape(element)
        integer, intent(in) :: element
        real(wp) :: nodes(2, MAX_NODES), values(MAX_NODES), gradients(2, MAX_NODES)
        real(wp) :: plus(MAX_NODES), minus(MAX_NODES), unused(2, MAX_NODES), point(2)
        real(wp) :: worst_delta, worst_gradient, worst_sum, difference(MAX_NODES)
        real(wp), parameter :: STEP = 1.0e-5_wp
        integer :: a, d
        character(len=:), allocatable :: label
        label = ' ('//element_name(element)//')'
        n = element_nodes_per_cell(element)
        call reference_nodes(element, nodes)
        worst_delta = 0.0_wp
        do a = 1, n
            call evaluate_shape(element, nodes(:, a), values, gradients)
            values(a) = values(a) - 1.0_wp
            worst_delta = max(worst_delta, maxval(abs(values(1:n))))
        end do
        call t%check('N_a(x_b) = delta_ab'//label, worst_delta <= EXACT_TOL)
        ! An interior point off every symmetry line.
        point = [0.21_wp, 0.33_wp]
        call evaluate_shape(element, point, values, gradients)
        worst_sum = abs(sum(values(1:n)) - 1.0_wp)
        worst_gradient = 0.0_wp
        difference = 0.0_wp
        do d = 1, 2
            ! Fourth-order central differences are exact for polynomials of degree <= 4 per
            ! variable (every element here) up to round-off ~ eps/STEP ~ 1e-11.
            call evaluate_shape(element, point + STEP*unit(d), plus, unused)
            call evaluate_shape(element, point - STEP*unit(d), minus, unused)
            difference(1:n) = 8.0_wp*(plus(1:n) - minus(1:n))
            call evaluate_shape(element, point + 2*STEP*unit(d), plus, unused)
            call evaluate_shape(element, point - 2*STEP*unit(d), minus, unused)
            difference(1:n) = (difference(1:n) - (plus(1:n) - minus(1:n)))/(12*STEP)
            worst_gradient = max(worst_gradient, maxval(abs(difference(1:n) - gradients(d, 1:n))))
        end do
        call t%check('partition of unity'//label, worst_sum <= EXACT_TOL)
        call t%check('gradients match central differences'//label, worst_gradient <= 1.0e-9_wp)
    end subroutine check_shape

    pure function unit(d) result(e)
        integer, intent(in) :: d
        real(wp) :: e(2)
        e = 0.0_wp
        e(d) = 1.0_wp
    end function unit

    subroutine check_line_shape()
        real(wp) :: values(5), derivatives(5), nodes(5), s
        integer :: n_nodes, a
        logical :: delta_ok
        ! Cubic and quartic edges: ends at -1 and 1, inner nodes equally spaced from -1.
        do n_nodes = 4, 5
            nodes(1:2) = [-1.0_wp, 1.0_wp]
            do a = 3, n_nodes
                nodes(a) = -1.0_wp + 2.0_wp*(a - 2)/real(n_nodes - 1, wp)
            end do
            delta_ok = .true.
            do a = 1, n_nodes
                call evaluate_line_shape(n_nodes, nodes(a), values, derivatives)
                values(a) = values(a) - 1.0_wp
                delta_ok = delta_ok .and. maxval(abs(values(1:n_nodes))) <= EXACT_TOL
            end do
            s = 0.3_wp
            call evaluate_line_shape(n_nodes, s, values, derivatives)
            call t%check(char(iachar('0') + n_nodes)//'-node edge: N_a(s_b) = delta_ab, '// &
                'partition of unity, d/ds reproduces s^2', delta_ok .and. &
                abs(sum(values(1:n_nodes)) - 1.0_wp) <= EXACT_TOL .and. &
                abs(sum(derivatives(1:n_nodes)*nodes(1:n_nodes)**2) - 2*s) <= 10*EXACT_TOL)
        end do
        call evaluate_line_shape(3, 0.0_wp, values, derivatives)
        call t%check('3-node edge: mid node (third) is 1 at s = 0', &
                     maxval(abs(values(1:3) - [0.0_wp, 0.0_wp, 1.0_wp])) <= EXACT_TOL)
        call evaluate_line_shape(3, 1.0_wp, values, derivatives)
        call t%check('3-node edge: second end is 1 at s = 1', &
                     maxval(abs(values(1:3) - [0.0_wp, 1.0_wp, 0.0_wp])) <= EXACT_TOL)
        call evaluate_line_shape(2, 0.5_wp, values, derivatives)
        call t%check('2-node edge: linear', maxval(abs(values(1:2) - [0.25_wp, 0.75_wp])) &
                     <= EXACT_TOL .and. maxval(abs(derivatives(1:2) - [-0.5_wp, 0.5_wp])) &
                     <= EXACT_TOL)
    end subroutine check_line_shape
end program test_quadrature
