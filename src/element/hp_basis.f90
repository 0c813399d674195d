! SPDX-License-Identifier: MIT
!> Hierarchical H1 basis on the reference triangle (0,0), (1,0), (0,1) of any degree, with a
!> degree per edge (the minimum rule: an edge takes the smaller degree of its two cells) and
!> one for the interior. In barycentric coordinates l1 = 1 - x - y, l2 = x, l3 = y:
!>
!> - vertex k: l_k;
!> - edge from vertex a to vertex b, i = 2..p_e: the scaled integrated Legendre polynomial
!>   Lhat_i(l_b - l_a, l_a + l_b) = (l_a + l_b)^i Lhat_i((l_b - l_a)/(l_a + l_b)), with
!>   Lhat_i(s) = int_{-1}^s P_{i-1}. It vanishes on the other two edges (Lhat_i(+-1) = 0),
!>   and on its own edge it is Lhat_i(s) of the position s in [-1, 1] from a to b alone, so
!>   two cells agree on their common edge when both run it the same way: a global direction
!>   (from the lower to the higher vertex number) given to each cell as `flip`;
!> - interior, total degree n = 3..p, i = 2..n-1, j = n - 1 - i:
!>   Lhat_i(l2 - l1, l1 + l2) l3 P_j(2 l3 - 1), which vanish on the boundary.
!>
!> Integrated Legendre polynomials are orthogonal in the H1 seminorm in 1D, which keeps the
!> stiffness matrix's condition number growing only polynomially in p. Local order: the three
!> vertices, the edges' functions (edge k from vertex k to k + 1, i ascending), the interior
!> ones (n ascending): lower degrees first, so the space of degree p is a prefix.
module hp_basis
    use kinds, only: wp
    implicit none
    private
    public :: hp_local_count, hp_bubble_count, hp_triangle_shape, hp_edge_trace, &
              scaled_legendre, scaled_integrated_legendre, MAX_HP_DEGREE

    integer, parameter :: MAX_HP_DEGREE = 20   !! beyond this, round-off in the recurrences
    !> reference gradients of l1, l2, l3
    real(wp), parameter :: GRAD_L(2, 3) = reshape([-1.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, &
                                                   0.0_wp, 1.0_wp], [2, 3])

contains

    !> Interior functions of a cell of degree p: (p - 1)(p - 2)/2.
    elemental integer function hp_bubble_count(p)
        integer, intent(in) :: p
        hp_bubble_count = max(0, (p - 1)*(p - 2)/2)
    end function hp_bubble_count

    !> Local functions of a cell with edge degrees `edge_degree` and interior degree p.
    pure integer function hp_local_count(edge_degree, p)
        integer, intent(in) :: edge_degree(3), p
        hp_local_count = 3 + sum(max(0, edge_degree - 1)) + hp_bubble_count(p)
    end function hp_local_count

    !> Scaled Legendre polynomials P_i(s, t) = t^i P_i(s/t), i = 0..n, and their partial
    !> derivatives, by i P_i = (2i - 1) s P_{i-1} - (i - 1) t^2 P_{i-2}.
    pure subroutine scaled_legendre(n, s, t, p, dp_ds, dp_dt)
        integer, intent(in) :: n
        real(wp), intent(in) :: s, t
        real(wp), intent(out) :: p(0:n), dp_ds(0:n), dp_dt(0:n)
        integer :: i
        real(wp) :: a, b
        p(0) = 1.0_wp
        dp_ds(0) = 0.0_wp
        dp_dt(0) = 0.0_wp
        if (n < 1) return
        p(1) = s
        dp_ds(1) = 1.0_wp
        dp_dt(1) = 0.0_wp
        do i = 2, n
            a = real(2*i - 1, wp)/real(i, wp)
            b = real(i - 1, wp)/real(i, wp)
            p(i) = a*s*p(i - 1) - b*t*t*p(i - 2)
            dp_ds(i) = a*(p(i - 1) + s*dp_ds(i - 1)) - b*t*t*dp_ds(i - 2)
            dp_dt(i) = a*s*dp_dt(i - 1) - b*(2.0_wp*t*p(i - 2) + t*t*dp_dt(i - 2))
        end do
    end subroutine scaled_legendre

    !> Scaled integrated Legendre polynomials Lhat_i(s, t) = (P_i - t^2 P_{i-2})/(2i - 1)
    !> (scaled), i = 2..n, and their partial derivatives. At t = 1, Lhat_i(s) = int_{-1}^s
    !> P_{i-1}, which vanishes at s = -1 and s = 1.
    pure subroutine scaled_integrated_legendre(n, s, t, l, dl_ds, dl_dt)
        integer, intent(in) :: n
        real(wp), intent(in) :: s, t
        real(wp), intent(out) :: l(2:), dl_ds(2:), dl_dt(2:)   !! (2:n)
        real(wp) :: p(0:max(n, 1)), dp_ds(0:max(n, 1)), dp_dt(0:max(n, 1)), c
        integer :: i
        call scaled_legendre(max(n, 1), s, t, p, dp_ds, dp_dt)
        do i = 2, n
            c = 1.0_wp/real(2*i - 1, wp)
            l(i) = c*(p(i) - t*t*p(i - 2))
            dl_ds(i) = c*(dp_ds(i) - t*t*dp_ds(i - 2))
            dl_dt(i) = c*(dp_dt(i) - 2.0_wp*t*p(i - 2) - t*t*dp_dt(i - 2))
        end do
    end subroutine scaled_integrated_legendre

    !> The traces on an edge of degree p_e, at s in [-1, 1] along its global direction (from
    !> vertex a to vertex b): [l_a, l_b, Lhat_2(s), ..., Lhat_pe(s)] with l_a = (1 - s)/2.
    pure function hp_edge_trace(p_e, s) result(values)
        integer, intent(in) :: p_e
        real(wp), intent(in) :: s
        real(wp) :: values(1 + max(p_e, 1))
        real(wp) :: l(2:max(p_e, 2)), dl_ds(2:max(p_e, 2)), dl_dt(2:max(p_e, 2))
        values(1:2) = [0.5_wp*(1.0_wp - s), 0.5_wp*(1.0_wp + s)]
        if (p_e < 2) return
        call scaled_integrated_legendre(p_e, s, 1.0_wp, l, dl_ds, dl_dt)
        values(3:) = l(2:p_e)
    end function hp_edge_trace

    !> Values and reference gradients (d/dx, d/dy) at `xi` of the local functions of a cell
    !> with edge degrees `edge_degree` (edge k from vertex k to vertex k + 1), interior degree
    !> p (>= every edge degree) and `flip`(k) true when edge k's global direction runs from
    !> vertex k + 1 to vertex k. Only the first hp_local_count entries are written.
    pure subroutine hp_triangle_shape(edge_degree, p, flip, xi, values, gradients)
        integer, intent(in) :: edge_degree(3), p
        logical, intent(in) :: flip(3)
        real(wp), intent(in) :: xi(2)
        real(wp), intent(out) :: values(:)          !! (>= hp_local_count)
        real(wp), intent(out) :: gradients(:, :)    !! (2, >= hp_local_count)
        real(wp) :: lam(3), l(2:max(p, 2)), dl_ds(2:max(p, 2)), dl_dt(2:max(p, 2)), &
                    leg(0:max(p, 1)), dleg(0:max(p, 1)), unused(0:max(p, 1)), h, dh, f_a, f_b
        integer :: k, a, b, i, j, n, f

        lam = [1.0_wp - xi(1) - xi(2), xi(1), xi(2)]
        values(1:3) = lam
        gradients(:, 1:3) = GRAD_L
        f = 3
        do k = 1, 3
            if (edge_degree(k) < 2) cycle
            a = k
            b = mod(k, 3) + 1
            if (flip(k)) then
                a = b
                b = k
            end if
            call scaled_integrated_legendre(edge_degree(k), lam(b) - lam(a), lam(a) + lam(b), &
                                            l, dl_ds, dl_dt)
            do i = 2, edge_degree(k)
                f = f + 1
                values(f) = l(i)
                ! d/dl_a = -d/ds + d/dt, d/dl_b = d/ds + d/dt
                f_a = dl_dt(i) - dl_ds(i)
                f_b = dl_dt(i) + dl_ds(i)
                gradients(:, f) = f_a*GRAD_L(:, a) + f_b*GRAD_L(:, b)
            end do
        end do
        if (p < 3) return
        call scaled_integrated_legendre(p - 1, lam(2) - lam(1), lam(1) + lam(2), l, dl_ds, &
                                        dl_dt)
        call scaled_legendre(p - 3, 2.0_wp*lam(3) - 1.0_wp, 1.0_wp, leg, dleg, unused)
        do n = 3, p
            do i = 2, n - 1
                j = n - 1 - i
                f = f + 1
                h = lam(3)*leg(j)                          ! l3 P_j(2 l3 - 1)
                dh = leg(j) + 2.0_wp*lam(3)*dleg(j)        ! its d/dl3
                values(f) = l(i)*h
                gradients(:, f) = h*((dl_dt(i) - dl_ds(i))*GRAD_L(:, 1) + &
                                     (dl_dt(i) + dl_ds(i))*GRAD_L(:, 2)) + l(i)*dh*GRAD_L(:, 3)
            end do
        end do
    end subroutine hp_triangle_shape
end module hp_basis
