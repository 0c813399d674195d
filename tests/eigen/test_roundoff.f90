! SPDX-License-Identifier: MIT
!> The round-off bound against a pencil solved by hand: one contact node (p = 1) on two
!> dofs, K = [[a, c], [c, d]] = [[2, -1], [-1, 1]], normal (0, 1), tangent (1, 0), M = [m] =
!> [1], lambda = 4, so B = X' M N = m [[0, 4], [0, -1]] and det(K - mu B) = 0 gives
!> mu = (c^2 - a d) / (m (a + 4 c)) = 1/2, right eigenvector x = (3, 2), left y = (1, 2).
!> Closed form of the bound: |K||x| = (8, 5), |y|'|K||x| = 18; |X y| = 4 + 2 = 6, |N x| = 2,
!> mu |X y| m |N x| = 6; y' K x = 2: (18 + 6) / 2 = 12 units of eps.
!> The thresholds' pencil_roundoff on A z = l B z with A = [[2, 1], [1, 3]] and
!> B = [[1, 1], [0, -1]]: det(A - l B) = 5 - l^2, l = sqrt(5), right z = (l - 1, 2 - l),
!> left w = (1, l - 2).
!> The collision bound on A(lambda) = [[1, 1], [lambda - c, 1]], eigenvalues 1 +- sqrt(lambda
!> - c): they meet at lambda = c in a Jordan block with right x = (1, 0), left y = (0, 1)
!> and A'x = (0, 1), y'A'x = 1. A + E meets where (e11 - e22)^2 + 4 (1 + e12)(lambda - c +
!> e21) = 0: the collision moves by -e21 to first order, y'Ex.
program test_roundoff
    use kinds, only: wp
    use testing, only: test_suite_t
    use csr_matrix, only: csr_matrix_t
    use contact_boundary, only: contact_t
    use roundoff, only: roundoff_bound, pencil_roundoff, collision_bound, ROUNDOFF_UNITS
    implicit none

    real(wp), parameter :: LAMBDA = 4.0_wp, MU = 0.5_wp, X(2) = [3.0_wp, 2.0_wp], &
                           Y(2) = [1.0_wp, 2.0_wp], EPS = epsilon(1.0_wp)
    type(test_suite_t) :: t
    t%name = 'test_roundoff'
    call bound_closed_form(t)
    call bound_holds_for_perturbed_data(t)
    call bound_adds_residual(t)
    call pencil_bound_holds_for_perturbed_data(t)
    call pencil_bound_adds_residual(t)
    call collision_bound_holds_for_perturbed_data(t)
    call t%report()

contains

    subroutine two_dof_pencil(k, b, contact)
        type(csr_matrix_t), intent(out) :: k, b
        type(contact_t), intent(out) :: contact
        k%row_start = [1, 3, 5]
        k%col = [1, 2, 1, 2]
        k%val = [2.0_wp, -1.0_wp, -1.0_wp, 1.0_wp]
        b%row_start = [1, 2, 3]
        b%col = [2, 2]
        b%val = [4.0_wp, -1.0_wp]
        contact%nodes = [1]
        contact%dofs = reshape([1, 2], [2, 1])
        contact%normal = [0.0_wp, 1.0_wp]
        contact%tangent = [1.0_wp, 0.0_wp]
        contact%mass%row_start = [1, 2]
        contact%mass%col = [1]
        contact%mass%val = [1.0_wp]
    end subroutine two_dof_pencil

    !> 12 ROUNDOFF_UNITS eps for the exact pair (residual exactly zero), whatever the scaling
    !> of x and y.
    subroutine bound_closed_form(t)
        type(test_suite_t), intent(inout) :: t
        type(csr_matrix_t) :: k, b
        type(contact_t) :: contact
        call two_dof_pencil(k, b, contact)
        call t%check_close('bound of the 2 x 2 pencil in closed form', &
            roundoff_bound(k, b, contact, LAMBDA, MU, X, Y), 12.0_wp*ROUNDOFF_UNITS*EPS, &
            1.0e-14_wp)
        call t%check_close('bound is invariant under scaling of x and y', &
            roundoff_bound(k, b, contact, LAMBDA, MU, -1.0e-200_wp*X, 3.0e150_wp*Y), &
            12.0_wp*ROUNDOFF_UNITS*EPS, 1.0e-14_wp)
        call t%check('y orthogonal to K x: no bound (huge)', &
            roundoff_bound(k, b, contact, LAMBDA, MU, X, [1.0_wp, 4.0_wp]) >= huge(1.0_wp))
    end subroutine bound_closed_form

    !> Entries of K perturbed by delta relative each (every sign pattern) and M by delta move
    !> mu by at most (bound / (ROUNDOFF_UNITS eps)) delta to first order (18 / 2 from K,
    !> 6 / 2 from M): the data term is that first-order bound.
    subroutine bound_holds_for_perturbed_data(t)
        type(test_suite_t), intent(inout) :: t
        type(csr_matrix_t) :: k, b
        type(contact_t) :: contact
        real(wp) :: per_delta, delta, a, c, d, m, moved
        integer :: i, s
        logical :: holds
        call two_dof_pencil(k, b, contact)
        per_delta = roundoff_bound(k, b, contact, LAMBDA, MU, X, Y)/(ROUNDOFF_UNITS*EPS)
        holds = .true.
        do i = 1, 4
            delta = 10.0_wp**(-2*i - 4)
            do s = 0, 15
                a = 2.0_wp*(1.0_wp + sgn(s, 0)*delta)
                c = -1.0_wp*(1.0_wp + sgn(s, 1)*delta)
                d = 1.0_wp*(1.0_wp + sgn(s, 2)*delta)
                m = 1.0_wp + sgn(s, 3)*delta
                moved = abs((c*c - a*d)/(m*(a + LAMBDA*c)) - MU)/MU
                holds = holds .and. moved <= per_delta*delta*(1.0_wp + 1.0e-3_wp)
            end do
        end do
        call t%check('perturbations 1e-6 to 1e-12 of K and M move mu by at most the bound', &
                     holds)
        ! the worst sign pattern moves mu by 9 delta from K and delta from M: 10 of the 12
        call t%check('the bound is at most 12/9 of the worst first-order move', &
                     per_delta <= 12.0_wp + 1.0e-12_wp)
    end subroutine bound_holds_for_perturbed_data

    !> A pair off by 1e-8 in mu: the residual r = -1e-8 mu B x adds |y' r| / |y' K x| =
    !> 1e-8 |mu y' B x| / |y' K x| = 1e-8, the first-order error it stands for.
    subroutine bound_adds_residual(t)
        type(test_suite_t), intent(inout) :: t
        type(csr_matrix_t) :: k, b
        type(contact_t) :: contact
        real(wp) :: bound
        call two_dof_pencil(k, b, contact)
        bound = roundoff_bound(k, b, contact, LAMBDA, MU*(1.0_wp + 1.0e-8_wp), X, Y)
        call t%check_close('residual part of a pair off by 1e-8 in mu', bound, &
                           1.0e-8_wp + 12.0_wp*ROUNDOFF_UNITS*EPS, 1.0e-7_wp)
        call t%check('bound at least the relative error of mu it stands for', &
                     bound >= 1.0e-8_wp/(1.0_wp + 1.0e-8_wp))
    end subroutine bound_adds_residual

    !> Entries of A and B perturbed by delta relative each, every one of the 256 sign
    !> patterns: the exact eigenvalue of the perturbed pencil (the root nearest l of
    !> det(A' - l B') = 0, a quadratic) moves by at most the first-order bound with data =
    !> delta (|w|'|A||z| + l |w|'|B||z|), and by that bound for the worst pattern
    !> (sign(w_i z_j) on A, -sign(w_i z_j) on B), up to the second order (delta^2).
    subroutine pencil_bound_holds_for_perturbed_data(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: A(2, 2) = reshape([2.0_wp, 1.0_wp, 1.0_wp, 3.0_wp], [2, 2]), &
                               B(2, 2) = reshape([1.0_wp, 0.0_wp, 1.0_wp, -1.0_wp], [2, 2])
        real(wp) :: l, z(2), w(2), bound, delta, ap(2, 2), bp(2, 2), worst
        integer :: s, i, j, bit
        logical :: holds
        l = sqrt(5.0_wp)
        z = [l - 1.0_wp, 2.0_wp - l]
        w = [1.0_wp, l - 2.0_wp]
        holds = .true.
        worst = 0.0_wp
        delta = 1.0e-7_wp
        bound = pencil_roundoff(A, B, l, z, w, delta*(dot_product(abs(w), matmul(abs(A), &
                abs(z))) + l*dot_product(abs(w), matmul(abs(B), abs(z)))))
        do s = 0, 255
            do j = 1, 2
                do i = 1, 2
                    bit = 2*(j - 1) + i - 1
                    ap(i, j) = A(i, j)*(1.0_wp + sgn(s, bit)*delta)
                    bp(i, j) = B(i, j)*(1.0_wp + sgn(s, bit + 4)*delta)
                end do
            end do
            worst = max(worst, abs(nearest_root(ap, bp, l) - l)/l)
        end do
        holds = worst <= bound*(1.0_wp + 1.0e-5_wp)
        call t%check('perturbations 1e-7 of A and B move the pencil eigenvalue by at most '// &
                     'the bound', holds)
        call t%check_close('the worst sign pattern attains the bound to first order', &
                           worst, bound, 1.0e-5_wp)
    end subroutine pencil_bound_holds_for_perturbed_data

    !> The exact vectors with l off by 1e-8 relative and no data term: the residual part is
    !> |l_c - l| |w' B z| / |w' A z| = 1e-8.
    subroutine pencil_bound_adds_residual(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: A(2, 2) = reshape([2.0_wp, 1.0_wp, 1.0_wp, 3.0_wp], [2, 2]), &
                               B(2, 2) = reshape([1.0_wp, 0.0_wp, 1.0_wp, -1.0_wp], [2, 2])
        real(wp) :: l, z(2), w(2)
        l = sqrt(5.0_wp)
        z = [l - 1.0_wp, 2.0_wp - l]
        w = [1.0_wp, l - 2.0_wp]
        call t%check_close('pencil bound of an eigenvalue off by 1e-8', &
                           pencil_roundoff(A, B, l*(1.0_wp + 1.0e-8_wp), z, w, 0.0_wp), &
                           1.0e-8_wp, 1.0e-6_wp)
    end subroutine pencil_bound_adds_residual

    !> The root nearest `near` of det(a - l b) = 0: l^2 det(b) - l (a11 b22 + a22 b11 -
    !> a12 b21 - a21 b12) + det(a) = 0.
    pure real(wp) function nearest_root(a, b, near) result(root)
        real(wp), intent(in) :: a(2, 2), b(2, 2), near
        real(wp) :: q2, q1, q0, disc, r1, r2
        q2 = b(1, 1)*b(2, 2) - b(1, 2)*b(2, 1)
        q1 = -(a(1, 1)*b(2, 2) + a(2, 2)*b(1, 1) - a(1, 2)*b(2, 1) - a(2, 1)*b(1, 2))
        q0 = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
        disc = sqrt(q1*q1 - 4.0_wp*q2*q0)
        r1 = (-q1 + disc)/(2.0_wp*q2)
        r2 = (-q1 - disc)/(2.0_wp*q2)
        root = merge(r1, r2, abs(r1 - near) < abs(r2 - near))
    end function nearest_root

    pure real(wp) function sgn(s, bit)
        integer, intent(in) :: s, bit
        sgn = merge(-1.0_wp, 1.0_wp, btest(s, bit))
    end function sgn

    !> Entries of A(c) perturbed by delta each (every one of the 16 sign patterns): the exact
    !> collision of A + E (closed form above) moves by at most the bound with data = delta
    !> (|y|'|E||x| <= delta), and by that bound, up to delta^2, for the worst pattern. The
    !> solver's part (ROUNDOFF_UNITS eps ||A||_F) is below 1e-14 of it.
    subroutine collision_bound_holds_for_perturbed_data(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: C = 2.5_wp, X2(2) = [1.0_wp, 0.0_wp], Y2(2) = [0.0_wp, 1.0_wp], &
                               DAX(2) = [0.0_wp, 1.0_wp]
        real(wp) :: delta, bound, e(4), moved, worst
        integer :: s, bit
        logical :: holds
        delta = 1.0e-8_wp
        ! ||A(c)||_F = sqrt(3)
        bound = collision_bound(sqrt(3.0_wp), C, X2, Y2, DAX, delta)
        holds = .true.
        worst = 0.0_wp
        do s = 0, 15
            do bit = 0, 3
                e(bit + 1) = sgn(s, bit)*delta
            end do
            ! e = (e11, e12, e21, e22): lambda_c = c - e21 - (e11 - e22)^2 / (4 (1 + e12))
            moved = abs(e(3) + (e(1) - e(4))**2/(4.0_wp*(1.0_wp + e(2))))/C
            holds = holds .and. moved <= bound*(1.0_wp + 1.0e-6_wp)
            worst = max(worst, moved)
        end do
        call t%check('perturbations 1e-8 of A move the collision by at most the bound', holds)
        call t%check_close('the worst pattern reaches the bound (first order)', worst, bound, &
                           1.0e-6_wp)
        call t%check('no crossing (y''A''x = 0): no bound (huge)', &
            collision_bound(sqrt(3.0_wp), C, X2, Y2, [1.0_wp, 0.0_wp], delta) >= huge(1.0_wp))
    end subroutine collision_bound_holds_for_perturbed_data
end program test_roundoff
