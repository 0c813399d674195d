! SPDX-License-Identifier: MIT
!> The lowest positive mu of an hp level past the round-off of the stored K. Each stored
!> entry of K carries a relative error of eps, and on graded hp meshes y' K x is some 1e4
!> times smaller than |y|' |K| |x| (a small cell's displacement is large next to its
!> gradient), so the solver's mu carries about 1e-11 of round-off (module roundoff's data
!> term) although its residual is near 1e-16. Here K is never stored: the two-sided
!> Rayleigh quotient
!>     mu_q = y' K x / (y' B x)
!> of the solver's right and left eigenvectors x, y takes y' K x cell by cell, each field's
!> gradient with its vertex part from coefficient differences (hp_stiffness_form), which
!> rounds to some 60 eps of y' K x instead of 1e4 (tests/eigen/test_hp_rayleigh.f90 checks
!> it against quadruple precision). If x = x* + dx and y = y* + dy with (mu*, x*, y*) the
!> exact eigentriple of the discrete pencil, mu_q - mu* = dy' (K - mu* B) dx / (y' B x):
!> second order in the vectors' errors, which first-order perturbation theory puts at
!> (the solver's bound) / (relative gap to the nearest other eigenvalue) each. y' B x is
!> taken from the assembled B (assemble_b): its entries do not cancel beyond what
!> contact_abs_form measures, and that is counted in the quotient's bound.
module hp_rayleigh
    use kinds, only: wp
    use status, only: status_t
    use mesh, only: mesh_t
    use csr_matrix, only: csr_matrix_t
    use contact_boundary, only: contact_t
    use elasticity, only: lame_coefficients
    use hp_space, only: hp_space_t
    use hp_stiffness, only: hp_tables_t, hp_cell_fields
    use roundoff, only: contact_abs_form, ROUNDOFF_UNITS
    implicit none
    private
    public :: refine_lowest_mu, hp_stiffness_form

    !> the second-order term's multiple of bound^2 / gap: the vectors' errors are each
    !> estimated to first order only
    real(wp), parameter :: SECOND_ORDER_FACTOR = 10.0_wp

contains

    !> mu_q from the double pair (mu, x) and left vector y (free dofs of `space` on the
    !> graded mesh `m`, units of the assembly: `young`, `poisson`, `contact`'s mass, b), and
    !> its relative round-off bound: ROUNDOFF_UNITS eps times the data that stays in double
    !> (the contact form's componentwise size over |y' K x|, and 1 for E, nu and the final
    !> rounding) plus SECOND_ORDER_FACTOR bound^2 / gap, with `bound` the double value's
    !> round-off bound and `gap` = min |mu_j - mu| / |mu| over the other eigenvalues known.
    !> mu and `refined` are in the units of the assembly; `refined` = mu where the quotient
    !> is not a positive number.
    subroutine refine_lowest_mu(m, space, young, poisson, contact, b, lambda, mu, x, y, &
                                bound, gap, refined, refined_bound, stat)
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        real(wp), intent(in) :: young, poisson, lambda, mu, x(:), y(:), bound, gap
        type(contact_t), intent(in) :: contact
        type(csr_matrix_t), intent(in) :: b   !! B(lambda) on the free dofs (assemble_b)
        real(wp), intent(out) :: refined, refined_bound
        type(status_t), intent(out) :: stat
        real(wp) :: ykx, ykx_abs, ybx, bx(size(x))
        refined = mu
        refined_bound = bound
        call hp_stiffness_form(m, space, young, poisson, x, y, ykx, ykx_abs, stat)
        if (.not. stat%ok()) return
        call b%matvec(x, bx)
        ybx = dot_product(y, bx)
        if (.not. (abs(ybx) > 0.0_wp .and. ykx/ybx > 0.0_wp)) return
        refined = ykx/ybx
        refined_bound = ROUNDOFF_UNITS*epsilon(1.0_wp)* &
                        ((ykx_abs + abs(refined)*contact_abs_form(contact, lambda, x, y))/ &
                         abs(ykx) + 1.0_wp) + SECOND_ORDER_FACTOR*bound**2/max(gap, tiny(1.0_wp))
    end subroutine refine_lowest_mu

    !> y' K x over the cells of `m` and its componentwise size `form_abs` (what its
    !> rounding is relative to): the interior coefficients recovered from each cell's element
    !> stiffness, then the plane-strain energy form lambda div x div y + 2 G eps(x) : eps(y)
    !> integrated exactly on straight cells (the rule of the cell's hp_tables_t, exact to
    !> degree 2p, the integrand's being 2(p - 1)). A field's gradient takes its
    !> vertex part from coefficient differences, sum_v c_v grad l_v = (c_2 - c_1, c_3 - c_1)
    !> in the reference cell (exact: the gradients of l_v sum to zero), so the large
    !> displacement of a small cell never meets its small gradient.
    subroutine hp_stiffness_form(m, space, young, poisson, x, y, form, form_abs, stat)
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        real(wp), intent(in) :: young, poisson, x(:), y(:)
        real(wp), intent(out) :: form, form_abs
        type(status_t), intent(out) :: stat
        type(hp_tables_t), allocatable :: tables(:)
        real(wp), allocatable :: coefficients(:, :), fields(:, :)
        real(wp) :: lame_l, shear_g, cell, cell_abs
        integer :: c, n_tables, t
        allocate (fields(size(x), 2))
        fields(:, 1) = x
        fields(:, 2) = y
        form = 0.0_wp
        form_abs = 0.0_wp
        call lame_coefficients(young, poisson, lame_l, shear_g)
        n_tables = 0
        do c = 1, m%n_cells()
            call hp_cell_fields(m, space, c, young, poisson, fields, tables, n_tables, &
                                coefficients, t, stat)
            if (.not. stat%ok()) then
                stat%message = 'hp Rayleigh quotient: '//stat%message
                return
            end if
            call cell_form(m%coords(:, m%cells(1:3, c)), tables(t), lame_l, shear_g, &
                           coefficients(:, 1), coefficients(:, 2), cell, cell_abs)
            form = form + cell
            form_abs = form_abs + cell_abs
        end do
    end subroutine hp_stiffness_form

    !> The energy form of one straight cell with corners xy and full coefficient vectors
    !> cx, cy (interleaved x, y per local function), and its componentwise size.
    pure subroutine cell_form(xy, table, lame_l, shear_g, cx, cy, form, form_abs)
        real(wp), intent(in) :: xy(2, 3), lame_l, shear_g, cx(:), cy(:)
        type(hp_tables_t), intent(in) :: table
        real(wp), intent(out) :: form, form_abs
        real(wp) :: jacobian(2, 2), inverse_t(2, 2), det, gx(2, 2), gy(2, 2), ax(2, 2), &
                    ay(2, 2)
        real(wp), dimension(2, size(table%g, 2)) :: rx, ry, rx_abs, ry_abs
        integer :: q, nq
        nq = table%rule%n_points()
        jacobian(:, 1) = xy(:, 2) - xy(:, 1)
        jacobian(:, 2) = xy(:, 3) - xy(:, 1)
        det = jacobian(1, 1)*jacobian(2, 2) - jacobian(1, 2)*jacobian(2, 1)
        inverse_t = reshape([jacobian(2, 2), -jacobian(1, 2), -jacobian(2, 1), &
                             jacobian(1, 1)], [2, 2])/det
        ! reference gradients of both fields (component, point: d/dxi, then d/deta)
        call reference_gradients(cx, table, rx, rx_abs)
        call reference_gradients(cy, table, ry, ry_abs)
        form = 0.0_wp
        form_abs = 0.0_wp
        do q = 1, nq
            ! physical gradients g(a, i) = d u_a / d x_i = sum_k r(a, k) C(i, k)
            gx = physical(rx(:, q), rx(:, nq + q), inverse_t)
            gy = physical(ry(:, q), ry(:, nq + q), inverse_t)
            ax = physical(rx_abs(:, q), rx_abs(:, nq + q), abs(inverse_t))
            ay = physical(ry_abs(:, q), ry_abs(:, nq + q), abs(inverse_t))
            form = form + table%rule%weights(q)*energy_density(gx, gy, lame_l, shear_g)
            form_abs = form_abs + table%rule%weights(q)*energy_density(ax, ay, lame_l, shear_g)
        end do
        form = det*form
        form_abs = abs(det)*form_abs
    end subroutine cell_form

    !> d u_a / d xi, then d u_a / d eta, at every point of `table` (r(a, point), as
    !> table%g) of the field with coefficients c (interleaved x, y), the vertex part by
    !> differences, and the same sums over absolute values.
    pure subroutine reference_gradients(c, table, r, r_abs)
        real(wp), intent(in) :: c(:)
        type(hp_tables_t), intent(in) :: table
        real(wp), intent(out) :: r(:, :), r_abs(:, :)   !! (2, 2 n_points)
        real(wp) :: u(2, size(c)/2)
        integer :: a, nq, n
        nq = size(table%g, 2)/2
        n = size(c)/2
        u = reshape(c, [2, n])
        r = 0.0_wp
        r_abs = 0.0_wp
        if (n > 3) then
            r = matmul(u(:, 4:), table%g(4:, :))
            r_abs = matmul(abs(u(:, 4:)), table%g_abs(4:, :))
        end if
        do a = 1, 2
            r(a, 1:nq) = r(a, 1:nq) + (u(a, 2) - u(a, 1))
            r(a, nq + 1:) = r(a, nq + 1:) + (u(a, 3) - u(a, 1))
            r_abs(a, 1:nq) = r_abs(a, 1:nq) + abs(u(a, 2) - u(a, 1))
            r_abs(a, nq + 1:) = r_abs(a, nq + 1:) + abs(u(a, 3) - u(a, 1))
        end do
    end subroutine reference_gradients

    pure function physical(r_xi, r_eta, inverse_t) result(g)
        real(wp), intent(in) :: r_xi(2), r_eta(2), inverse_t(2, 2)
        real(wp) :: g(2, 2)
        integer :: i
        do i = 1, 2
            g(:, i) = r_xi*inverse_t(i, 1) + r_eta*inverse_t(i, 2)
        end do
    end function physical

    !> lambda tr(gx) tr(gy) + 2 G eps(gx) : eps(gy) for displacement gradients gx, gy (the
    !> same of componentwise sizes gives the size of the density).
    pure real(wp) function energy_density(gx, gy, lame_l, shear_g) result(density)
        real(wp), intent(in) :: gx(2, 2), gy(2, 2), lame_l, shear_g
        density = lame_l*(gx(1, 1) + gx(2, 2))*(gy(1, 1) + gy(2, 2)) + &
                  0.5_wp*shear_g*sum((gx + transpose(gx))*(gy + transpose(gy)))
    end function energy_density
end module hp_rayleigh
