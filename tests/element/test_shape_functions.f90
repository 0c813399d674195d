! SPDX-License-Identifier: MIT
!> The Lagrange shape functions reproduce every polynomial of their space exactly: with
!> nodal values q(x_a), sum_a q(x_a) N_a = q and sum_a q(x_a) grad N_a = grad q at any
!> point, for q = x^i y^j with i + j <= p (triangles P_p) or i, j <= p (quadrilaterals Q_p);
!> a monomial of the next degree is not reproduced (the test can fail). q = 1 is the
!> partition of unity. The edge functions do the same on [-1, 1], and reference_nodes
!> gives the points where N_a is 1.
program test_shape_functions
    use kinds, only: wp
    use element_types, only: MAX_ELEMENT, element_nodes_per_cell, element_degree, &
                             element_corners, element_name, element_dimension
    use shape_functions, only: evaluate_shape, evaluate_line_shape, reference_nodes, &
                               MAX_NODES, MAX_EDGE_NODES
    use testing, only: test_suite_t
    implicit none

    !> sums of at most 15 products of values <= 1 in size: a few ulps each
    real(wp), parameter :: TOL = 1.0e-13_wp
    !> points inside the reference cells (triangle, square), off every symmetry line
    real(wp), parameter :: TRIANGLE_POINTS(2, 4) = reshape([0.21_wp, 0.33_wp, 0.05_wp, &
        0.9_wp, 0.6_wp, 0.1_wp, 0.3_wp, 0.3_wp], [2, 4])
    real(wp), parameter :: SQUARE_POINTS(2, 4) = reshape([0.21_wp, -0.33_wp, -0.95_wp, &
        0.9_wp, 0.6_wp, 0.1_wp, -0.3_wp, -0.7_wp], [2, 4])
    type(test_suite_t) :: t
    integer :: element, n

    t%name = 'test_shape_functions'
    do element = 1, MAX_ELEMENT
        call check_reproduction(element)
    end do
    do n = 2, MAX_EDGE_NODES
        call check_line(n)
    end do
    call t%report()

contains

    !> Whether x^i y^j lies in the space of `element`.
    pure logical function in_space(element, i, j)
        integer, intent(in) :: element, i, j
        if (element_corners(element) == 3) then
            in_space = i + j <= element_degree(element)
        else
            in_space = max(i, j) <= element_degree(element)
        end if
    end function in_space

    subroutine check_reproduction(element)
        integer, intent(in) :: element
        real(wp) :: nodes(2, MAX_NODES), values(MAX_NODES), gradients(2, MAX_NODES), &
                    points(2, 4), x(2), q(MAX_NODES), exact, exact_gradient(2), worst, &
                    worst_gradient, worst_outside, at_node, miss
        integer :: n, p, i, j, k, a
        character(len=:), allocatable :: label
        label = ' ('//element_name(element)//')'
        n = element_nodes_per_cell(element)
        p = element_degree(element)
        call reference_nodes(element, nodes)
        points = TRIANGLE_POINTS
        if (element_corners(element) == 4) points = SQUARE_POINTS
        worst = 0.0_wp
        worst_gradient = 0.0_wp
        worst_outside = huge(1.0_wp)
        do i = 0, p + 1
            do j = 0, p + 1
                q(1:n) = nodes(1, 1:n)**i*nodes(2, 1:n)**j
                miss = 0.0_wp
                do k = 1, size(points, 2)
                    x = points(:, k)
                    call evaluate_shape(element, x, values, gradients)
                    exact = x(1)**i*x(2)**j
                    if (in_space(element, i, j)) then
                        exact_gradient = [real(i, wp)*x(1)**max(i - 1, 0)*x(2)**j, &
                                          real(j, wp)*x(1)**i*x(2)**max(j - 1, 0)]
                        worst = max(worst, abs(dot_product(q(1:n), values(1:n)) - exact))
                        worst_gradient = max(worst_gradient, maxval(abs(matmul(gradients(:, 1:n), &
                                             q(1:n)) - exact_gradient)))
                    else
                        miss = max(miss, abs(dot_product(q(1:n), values(1:n)) - exact))
                    end if
                end do
                ! the monomials just outside: total degree p + 1 (triangles), or one
                ! exponent p + 1 (quadrilaterals)
                if (.not. in_space(element, i, j) .and. (i + j == p + 1 .or. &
                    element_corners(element) == 4)) worst_outside = min(worst_outside, miss)
            end do
        end do
        call t%check('reproduces every monomial of its space'//label, worst <= TOL)
        call t%check('and its gradient'//label, worst_gradient <= 10*TOL)
        ! each monomial just outside the space missed at one of the points at least
        call t%check('no monomial of the next degree is reproduced'//label, &
                     worst_outside > 1.0e-4_wp)
        worst = 0.0_wp
        do a = 1, n
            call evaluate_shape(element, nodes(:, a), values, gradients)
            at_node = values(a)
            values(a) = values(a) - 1.0_wp
            worst = max(worst, maxval(abs(values(1:n))))
        end do
        call t%check('reference_nodes: N_a is 1 at node a, 0 at the others'//label, &
                     worst <= TOL .and. abs(at_node - 1.0_wp) <= TOL)
        call t%check('reference points and gradients of dimension '// &
                     'element_dimension = 2'//label, element_dimension(element) == 2)
        values = -1.0_wp
        call evaluate_shape(element, points(:, 1), values, gradients)
        call t%check('entries beyond the nodes are zero (MAX_NODES buffers)'//label, &
                     all(abs(values(n + 1:)) <= 0.0_wp) .and. all(abs(gradients(:, n + 1:)) &
                     <= 0.0_wp))
    end subroutine check_reproduction

    !> The n-node edge functions reproduce s^k, k <= n - 1, and their derivatives.
    subroutine check_line(n)
        integer, intent(in) :: n
        real(wp) :: nodes(MAX_EDGE_NODES), values(MAX_EDGE_NODES), &
                    derivatives(MAX_EDGE_NODES), s, worst
        integer :: k, a
        character(len=8) :: label
        write (label, '(i0)') n
        ! the ends, then the inner nodes from -1 towards +1
        nodes(1:2) = [-1.0_wp, 1.0_wp]
        do a = 3, n
            nodes(a) = -1.0_wp + 2.0_wp*real(a - 2, wp)/real(n - 1, wp)
        end do
        worst = 0.0_wp
        s = 0.37_wp
        call evaluate_line_shape(n, s, values, derivatives)
        do k = 0, n - 1
            worst = max(worst, abs(dot_product(nodes(1:n)**k, values(1:n)) - s**k), &
                        abs(dot_product(nodes(1:n)**k, derivatives(1:n)) - &
                            real(k, wp)*s**max(k - 1, 0)))
        end do
        call t%check(trim(label)//'-node edge: reproduces s^k and its derivative, k < n', &
                     worst <= 10*TOL)
        call t%check(trim(label)//'-node edge: not s^n', &
                     abs(dot_product(nodes(1:n)**n, values(1:n)) - s**n) > 1.0e-4_wp)
    end subroutine check_line
end program test_shape_functions
