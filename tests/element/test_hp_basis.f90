! SPDX-License-Identifier: MIT
!> The hierarchical basis and its Gauss rules against mathematics: exact moments of the
!> rules, reproduction of every polynomial of degree p by the space of degree p (p = 1..12,
!> every edge direction), gradients against the exact ones, traces that agree across an
!> edge whatever the cells' local orders, and the minimum rule's space.
program test_hp_basis
    use kinds, only: wp
    use testing, only: test_suite_t
    use gauss_rules, only: gauss_rule_t, line_rule_exact, triangle_rule_exact
    use hp_basis, only: hp_triangle_shape, hp_local_count, hp_edge_trace
    use lapack_interfaces, only: dgetrf, dgetrs
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_hp_basis'
    call line_rules_are_exact(t)
    call triangle_rules_are_exact(t)
    call space_of_degree_p_holds_every_polynomial(t)
    call minimum_rule_space_holds_its_degree(t)
    call traces_agree_across_an_edge(t)
    call t%report()

contains

    !> int_{-1}^{1} x^k = 2/(k + 1) for even k, 0 for odd k, to a few ulps (sums of at most
    !> 11 positive terms of size <= 2): 1e-14.
    subroutine line_rules_are_exact(t)
        type(test_suite_t), intent(inout) :: t
        type(gauss_rule_t) :: rule
        real(wp) :: worst, exact
        integer :: degree, k
        worst = 0.0_wp
        do degree = 0, 40
            rule = line_rule_exact(degree)
            do k = 0, degree
                exact = 0.0_wp
                if (mod(k, 2) == 0) exact = 2.0_wp/real(k + 1, wp)
                worst = max(worst, abs(sum(rule%weights*rule%points(1, :)**k) - exact))
            end do
        end do
        call t%check_close('Gauss-Legendre moments x^k, k <= degree <= 40', worst, 0.0_wp, &
                           0.0_wp, 1.0e-14_wp)
    end subroutine line_rules_are_exact

    !> int_T x^a y^b = a! b! / (a + b + 2)! on the reference triangle, for a + b <= degree
    !> <= 24; relative 1e-12 (the moments fall to 1e-16 and below, hence relative).
    subroutine triangle_rules_are_exact(t)
        type(test_suite_t), intent(inout) :: t
        type(gauss_rule_t) :: rule
        real(wp) :: worst, exact
        integer :: degree, a, b
        worst = 0.0_wp
        do degree = 0, 24
            rule = triangle_rule_exact(degree)
            do a = 0, degree
                do b = 0, degree - a
                    exact = gamma(real(a + 1, wp))*gamma(real(b + 1, wp))/ &
                            gamma(real(a + b + 3, wp))
                    worst = max(worst, abs(sum(rule%weights*rule%points(1, :)**a* &
                                               rule%points(2, :)**b) - exact)/exact)
                end do
            end do
        end do
        call t%check_close('collapsed Gauss moments x^a y^b, a + b <= degree <= 24', worst, &
                           0.0_wp, 0.0_wp, 1.0e-12_wp)
    end subroutine triangle_rules_are_exact

    !> The L2 projection of f(x, y) = ((1 + x - 2y)/2)^p + x^(p-1) y onto the space of degree p
    !> (all edges of degree p) is f itself when the space holds P_p; its dimension is that
    !> of P_p, (p + 1)(p + 2)/2, so the basis is one of P_p. The projection solves with the
    !> mass matrix, whose condition grows with p (the interior functions use Legendre, not
    !> Jacobi, polynomials): the errors grow from 1e-16 at p = 1 to 5e-12 (values, |f| <= 2)
    !> and 4e-10 (gradients, p^2 larger) at p = 12, hence 1e-10 and 1e-8.
    subroutine space_of_degree_p_holds_every_polynomial(t)
        type(test_suite_t), intent(inout) :: t
        integer :: p, variant
        logical :: flip(3)
        real(wp) :: value_error, gradient_error
        character(len=80) :: what
        do p = 1, 12
            value_error = 0.0_wp
            gradient_error = 0.0_wp
            do variant = 0, 7
                flip = [btest(variant, 0), btest(variant, 1), btest(variant, 2)]
                call projection_error([p, p, p], p, p, flip, value_error, gradient_error)
            end do
            write (what, '(a, i0)') 'degree p space holds P_p (values), p = ', p
            call t%check_close(trim(what), value_error, 0.0_wp, 0.0_wp, 1.0e-10_wp)
            write (what, '(a, i0)') 'degree p space holds P_p (gradients), p = ', p
            call t%check_close(trim(what), gradient_error, 0.0_wp, 0.0_wp, 1.0e-8_wp)
            write (what, '(a, i0)') 'dimension (p + 1)(p + 2)/2, p = ', p
            call t%check(trim(what), hp_local_count([p, p, p], p) == (p + 1)*(p + 2)/2)
        end do
    end subroutine space_of_degree_p_holds_every_polynomial

    !> A cell of degree 6 whose edges have degrees 2, 3 and 4 (neighbours of lower degree):
    !> its space holds P_2 exactly (the smallest edge degree), not P_3.
    subroutine minimum_rule_space_holds_its_degree(t)
        type(test_suite_t), intent(inout) :: t
        real(wp) :: value_error, gradient_error
        value_error = 0.0_wp
        gradient_error = 0.0_wp
        call projection_error([2, 3, 4], 6, 2, [.true., .false., .true.], value_error, &
                              gradient_error)
        call t%check_close('edges 2, 3, 4 and interior 6 hold P_2', value_error, 0.0_wp, &
                           0.0_wp, 1.0e-11_wp)
        value_error = 0.0_wp
        call projection_error([2, 3, 4], 6, 3, [.true., .false., .true.], value_error, &
                              gradient_error)
        call t%check('... but not P_3 (the edge of degree 2 cannot carry a cubic trace)', &
                     value_error > 1.0e-4_wp)
    end subroutine minimum_rule_space_holds_its_degree

    !> Two cells share the edge from (1,0) to (0,1): cell A = (0,0), (1,0), (0,1) (local
    !> edge 2, from its vertex 2 to 3) and cell B = (1,1), (0,1), (1,0) (local edge 2 from
    !> (0,1) to (1,0)): opposite local directions, so with the global direction from (1,0) to
    !> (0,1) A's flip is false and B's true. Every edge function must then take the same
    !> value from both sides at every point of the edge, and match hp_edge_trace.
    subroutine traces_agree_across_an_edge(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: P = 9
        real(wp) :: va(100), ga(2, 100), vb(100), gb(2, 100), trace(P + 1), s, worst
        integer :: i, first
        worst = 0.0_wp
        first = 3 + (P - 1) + 1   ! edge 2's functions follow edge 1's
        do i = 0, 10
            s = -1.0_wp + 0.2_wp*real(i, wp)
            ! the point (1 - u, u) with u = (1 + s)/2 from (1,0) toward (0,1)
            call hp_triangle_shape([P, P, P], P, [.false., .false., .false.], &
                                   [0.5_wp*(1.0_wp - s), 0.5_wp*(1.0_wp + s)], va, ga)
            ! in B's reference coordinates: B(xi) = (1,1) + xi1 ((0,1) - (1,1)) +
            ! xi2 ((1,0) - (1,1)) = (1 - xi1, 1 - xi2), so (1 - u, u) is xi = (u, 1 - u)
            call hp_triangle_shape([P, P, P], P, [.false., .true., .false.], &
                                   [0.5_wp*(1.0_wp + s), 0.5_wp*(1.0_wp - s)], vb, gb)
            trace = hp_edge_trace(P, s)
            worst = max(worst, maxval(abs(va(first:first + P - 2) - vb(first:first + P - 2))), &
                        maxval(abs(va(first:first + P - 2) - trace(3:))))
        end do
        call t%check_close('edge functions agree across a shared edge (degree 9)', worst, &
                           0.0_wp, 0.0_wp, 1.0e-13_wp)
    end subroutine traces_agree_across_an_edge

    !> Largest error (values, gradients) at the points of a rule of another degree of the L2
    !> projection of f of degree `degree` onto the cell space; accumulated into the maxima.
    subroutine projection_error(edge_degree, p, degree, flip, value_error, gradient_error)
        integer, intent(in) :: edge_degree(3), p, degree
        logical, intent(in) :: flip(3)
        real(wp), intent(inout) :: value_error, gradient_error
        type(gauss_rule_t) :: rule, check_rule
        real(wp), allocatable :: mass(:, :), rhs(:, :), v(:), g(:, :)
        integer, allocatable :: pivots(:)
        real(wp) :: f, fx, fy
        integer :: n, q, info
        n = hp_local_count(edge_degree, p)
        allocate (mass(n, n), source=0.0_wp)
        allocate (rhs(n, 1), source=0.0_wp)
        allocate (v(n), g(2, n), pivots(n))
        rule = triangle_rule_exact(2*p)
        do q = 1, rule%n_points()
            call hp_triangle_shape(edge_degree, p, flip, rule%points(:, q), v, g)
            call poly(degree, rule%points(:, q), f, fx, fy)
            mass = mass + rule%weights(q)*spread(v, 2, n)*spread(v, 1, n)
            rhs(:, 1) = rhs(:, 1) + rule%weights(q)*f*v
        end do
        call dgetrf(n, n, mass, n, pivots, info)
        call dgetrs('N', n, 1, mass, n, pivots, rhs, n, info)
        check_rule = triangle_rule_exact(2*p + 3)
        do q = 1, check_rule%n_points()
            call hp_triangle_shape(edge_degree, p, flip, check_rule%points(:, q), v, g)
            call poly(degree, check_rule%points(:, q), f, fx, fy)
            value_error = max(value_error, abs(dot_product(v, rhs(:, 1)) - f))
            gradient_error = max(gradient_error, abs(dot_product(g(1, :), rhs(:, 1)) - fx), &
                                 abs(dot_product(g(2, :), rhs(:, 1)) - fy))
        end do

    end subroutine projection_error

    !> f = ((1 + x - 2y)/2)^d + x^(d-1) y (the second term from d = 2) and its gradient.
    pure subroutine poly(degree, xy, f, fx, fy)
        integer, intent(in) :: degree
        real(wp), intent(in) :: xy(2)
        real(wp), intent(out) :: f, fx, fy
        real(wp) :: base
        base = 0.5_wp*(1.0_wp + xy(1) - 2.0_wp*xy(2))
        f = base**degree
        fx = 0.5_wp*real(degree, wp)*base**(degree - 1)
        fy = -real(degree, wp)*base**(degree - 1)
        if (degree >= 2) then
            f = f + xy(1)**(degree - 1)*xy(2)
            fx = fx + real(degree - 1, wp)*xy(1)**(degree - 2)*xy(2)
            fy = fy + xy(1)**(degree - 1)
        end if
    end subroutine poly
end program test_hp_basis
