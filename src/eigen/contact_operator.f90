! SPDX-License-Identifier: MIT
!> The operator ARPACK runs on (module arpack_eigen): the reduced operator on the contact
!> nodes, A = N K^-1 X' M from the trailing block of a contact-last factor of K, shift-
!> inverted as (I - sigma A)^-1 A for a target sigma; or the full one, (K - sigma B)^-1 B in
!> the n free dofs; and the transposes of both, whose eigenvectors are the left ones.
module contact_operator
    use kinds, only: wp
    use status, only: status_t, STATUS_SOLVER, STATUS_BAD_INPUT, STATUS_SINGULAR
    use strings, only: to_string, short => short_real_text
    use real_format, only: real_to_text
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_boundary, only: contact_t
    use sparse_lu, only: lu_t
    use lapack_interfaces, only: dtrsv, dgetrf, dgetrs, dgemm, dlacn2
    use contact_reduction, only: contact_tail, flexibility_blocks, reduced_matrix, lambda_unit
    implicit none
    private

    !> Largest |sigma| ||A||_inf accepted for a target sigma. mu = sigma + 1/nu cancels: an
    !> eigenvalue mu comes back with an absolute error of about eps |sigma|, i.e. a relative
    !> error eps |sigma| / |mu| <= eps |sigma| ||A|| (every |mu| >= 1 / ||A||, as
    !> |theta| <= ||A||), and the nu = 1/(mu - sigma) of the low eigenvalues crowd within a
    !> relative eps |sigma| ||A|| of each other, where ARPACK cannot tell them apart. 1e6
    !> keeps both below 2.2e-10, well inside AGREE_TOL; beyond it (e.g. target = 1e15 on the
    !> reference scene) the answers were wrong in every digit with a certificate that held.
    real(wp), parameter, public :: TARGET_RANGE = 1.0e6_wp

    !> The reduced operator on the contact nodes: theta-mode y -> A y (sigma = 0) or
    !> shift-invert y -> (I - sigma A)^-1 A y.
    type, public :: contact_operator_t
        integer :: p = 0
        integer :: n = 0                        !! ARPACK's dimension: p, or n_free when full
        real(wp) :: sigma = 0.0_wp
        real(wp) :: lambda = 0.0_wp
        !> The operator is built on A / lambda_scale (a power of two ~ |lambda| when
        !> |lambda| > 1, else 1): A ~ lambda overflowed ARPACK's norms from |lambda| ~ 1e160
        real(wp) :: lambda_scale = 1.0_wp
        real(wp) :: normal(2) = 0.0_wp, tangent(2) = 0.0_wp
        real(wp), allocatable :: l_tail(:, :)   !! (2p, 2p) trailing block of the factor
        integer, allocatable :: slot(:, :)      !! (2, p) row in l_tail of contact dof (c, a)
        type(csr_matrix_t) :: mass              !! (p, p) boundary mass M
        real(wp), allocatable :: a(:, :)        !! (p, p) A, then LU of I - sigma A (sigma /= 0)
        integer, allocatable :: pivots(:)
        !> `a` is A itself, given by the caller (sigma = 0): one O(p^2) product per application
        logical :: explicit = .false.
        !> The full operator y -> (K - sigma B)^-1 (B / lambda_scale) y: B / lambda_scale,
        !> and the LU of K - sigma B (sigma /= 0) or the caller's factor of K (sigma = 0; a
        !> pointer, valid while the arpack_spectrum call that set it runs)
        logical :: full = .false.
        type(csr_matrix_t) :: b_scaled
        type(lu_t) :: shifted
        type(cholesky_t), pointer :: chol => null()
        !> Apply the transposed operator instead: same eigenvalues, and its eigenvectors are
        !> the left ones (of A, or of the pencil for the full operator), for the round-off
        !> bound. The full one needs the contact (B' = N' M X) kept here.
        logical :: transposed = .false.
        type(contact_t) :: contact
    contains
        procedure :: setup => operator_setup
        procedure :: setup_full => operator_setup_full
        procedure :: apply_a => operator_apply_a
        procedure :: x_direction => operator_x_direction
        procedure :: contact_compliance => operator_contact_compliance
        procedure :: apply => operator_apply
        procedure :: dense_a => operator_dense_a
        procedure :: mu_of => operator_mu_of
        procedure :: norm_estimate => operator_norm_estimate
        procedure :: check_target => operator_check_target
    end type contact_operator_t

contains

    !> Build the reduced operator from a factor of K whose last 2p pivots are the contact
    !> dofs (see node_ordering), and factor I - sigma A when sigma /= 0, after checking
    !> |sigma| ||A|| <= TARGET_RANGE (STATUS_BAD_INPUT naming &eigen target otherwise).
    subroutine operator_setup(this, chol, contact, lambda, sigma, stat, target_input, &
                              unit_exponent)
        class(contact_operator_t), intent(inout) :: this
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda, sigma
        type(status_t), intent(out) :: stat
        real(wp), intent(in) :: target_input      !! sigma as the input gave it (messages)
        integer, intent(in) :: unit_exponent      !! input mu = 2^unit_exponent mu here
        real(wp) :: a_norm
        integer :: a, info

        this%p = contact%p()
        this%n = this%p
        this%lambda = lambda
        this%sigma = sigma
        this%lambda_scale = lambda_unit(lambda)
        this%normal = contact%normal
        this%tangent = contact%tangent
        this%mass = contact%mass
        call contact_tail(chol, contact, this%l_tail, this%slot, stat)
        if (.not. stat%ok()) return
        if (.not. (abs(sigma) > 0.0_wp)) return

        call this%dense_a(this%a, stat)
        if (.not. stat%ok()) return
        ! |sigma| ||A|| > TARGET_RANGE, this%a being A / lambda_scale; written as quotients,
        ! which cannot overflow (sigma may be clamped to huge, see eigen_analysis)
        a_norm = maxval(sum(abs(this%a), dim=2))
        call this%check_target(a_norm, target_input, unit_exponent, stat)
        if (.not. stat%ok()) return
        ! LU of I - sigma A, kept in place of A (A itself is applied through L_c)
        this%a = -(sigma*this%lambda_scale)*this%a
        do a = 1, this%p
            this%a(a, a) = this%a(a, a) + 1.0_wp
        end do
        allocate (this%pivots(this%p))
        call dgetrf(this%p, this%p, this%a, this%p, this%pivots, info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, 'arpack: K - sigma B is singular for sigma = '// &
                to_string(sigma)//' (an eigenvalue equals the target; move the target)')
        end if
    end subroutine operator_setup

    !> The full operator (K - sigma B)^-1 B / lambda_scale in the n free dofs. sigma = 0 uses
    !> `chol`, the factor of K (no second factorization); sigma /= 0 factors K - sigma B once
    !> with UMFPACK, after the range check of operator_setup with ||A||_inf estimated
    !> (norm_estimate: a few sparse solves instead of forming A). Nothing of order p^2.
    subroutine operator_setup_full(this, k, b, chol, contact, lambda, sigma, stat, &
                                   target_input, unit_exponent)
        class(contact_operator_t), intent(inout) :: this
        type(csr_matrix_t), intent(in) :: k, b
        type(cholesky_t), intent(in), target :: chol
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda, sigma
        type(status_t), intent(out) :: stat
        real(wp), intent(in) :: target_input
        integer, intent(in) :: unit_exponent
        real(wp) :: a_norm

        this%full = .true.
        this%p = contact%p()
        this%n = k%n()
        this%lambda = lambda
        this%sigma = sigma
        this%lambda_scale = lambda_unit(lambda)
        this%b_scaled = b
        this%b_scaled%val = b%val/this%lambda_scale
        this%chol => chol
        this%contact = contact
        this%mass = contact%mass
        this%normal = contact%normal
        this%tangent = contact%tangent
        if (.not. (abs(sigma) > 0.0_wp)) return
        call this%norm_estimate(contact, a_norm, stat)
        if (.not. stat%ok()) return
        call this%check_target(a_norm, target_input, unit_exponent, stat)
        if (.not. stat%ok()) return
        ! no iterative refinement: ARPACK needs a backward-stable solve, which the LU gives,
        ! and every eigenpair's backward error on (K, B) is checked; refinement tripled the
        ! cost of each application (measured, docs/performance.md)
        call this%shifted%factor_shifted(k, b, sigma, stat, refinement_steps=0)
        if (stat%code /= STATUS_SINGULAR) return
        stat%message = 'arpack: K - sigma B for sigma = '//to_string(sigma)//': '// &
                       stat%message//' (an eigenvalue equals the target; move the target)'
    end subroutine operator_setup_full

    !> |sigma| ||A|| <= TARGET_RANGE, with a_norm = ||A / lambda_scale||_inf; written with
    !> quotients, which cannot overflow (sigma may be clamped to huge, see eigen_analysis).
    !> Otherwise STATUS_BAD_INPUT in one line naming the variable (the caller adds the file).
    subroutine operator_check_target(this, a_norm, target_input, unit_exponent, stat)
        class(contact_operator_t), intent(in) :: this
        real(wp), intent(in) :: a_norm, target_input
        integer, intent(in) :: unit_exponent
        type(status_t), intent(out) :: stat
        if (.not. abs(this%sigma) > (TARGET_RANGE/a_norm)/this%lambda_scale) return
        call stat%fail(STATUS_BAD_INPUT, '&eigen: target = '// &
            real_to_text(target_input)//': expected |target| <= '// &
            short(scale((TARGET_RANGE/a_norm)/this%lambda_scale, unit_exponent))// &
            ' (1e6 / ||A||, the scale of the spectrum here: further out, mu = target '// &
            '+ 1/nu cancels and loses more than 6 of the 16 digits)')
    end subroutine operator_check_target

    !> ||A / lambda_scale||_inf = ||(A / lambda_scale)'||_1 estimated by LAPACK dlacn2
    !> (Higham's estimator: a lower bound, exact on the scenes measured), with A = N K^-1 X' M
    !> and A' = M X K^-1 N' applied through solves with the sparse factor of K (this%chol):
    !> about five, O(nnz(L)) each, where forming A costs O(p^3) and p^2 memory.
    subroutine operator_norm_estimate(this, contact, estimate, stat)
        class(contact_operator_t), intent(in) :: this
        type(contact_t), intent(in) :: contact
        real(wp), intent(out) :: estimate
        type(status_t), intent(out) :: stat
        real(wp) :: v(this%p), x(this%p), product(this%p), mx(this%p), direction(2)
        integer :: isgn(this%p), kase, isave(3)
        direction = this%lambda/this%lambda_scale*contact%tangent - &
                    contact%normal/this%lambda_scale
        estimate = 0.0_wp
        kase = 0
        do
            call dlacn2(this%p, v, x, isgn, estimate, kase, isave)
            if (kase == 0) exit
            if (kase == 1) then   ! A' x = M (X K^-1 N' x)
                call compliance(contact%normal, x, direction, mx)
                call contact%mass%matvec(mx, product)
            else                  ! A x = N K^-1 X' (M x)
                call contact%mass%matvec(x, mx)
                call compliance(direction, mx, contact%normal, product)
            end if
            if (.not. stat%ok()) return
            x = product
        end do

    contains

        !> out(a) = row . (K^-1 z)(node a) with z(node b) = column y(b), zero elsewhere.
        subroutine compliance(column, y, row, out)
            real(wp), intent(in) :: column(2), y(:), row(2)
            real(wp), intent(out) :: out(:)
            real(wp), allocatable :: z(:, :), w(:, :)
            allocate (z(this%n, 1), source=0.0_wp)
            allocate (w(this%n, 1))
            call contact%scatter(column, y, z(:, 1))
            call this%chol%solve(z, w, stat)
            call contact%gather(row, w(:, 1), out)
        end subroutine compliance
    end subroutine operator_norm_estimate

    !> A = (lambda Kt_nt - Kt_nn) M as a dense p x p matrix, with Kt_nn and Kt_nt formed from
    !> L_c as the dense solver forms them (contact_reduction: dpotri, O(p^3)).
    subroutine operator_dense_a(this, a, stat)
        class(contact_operator_t), intent(in) :: this
        real(wp), allocatable, intent(out) :: a(:, :)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :)
        if (this%explicit) then
            allocate (a, source=this%a)
            return
        end if
        call flexibility_blocks(this%l_tail, this%slot, this%normal, this%tangent, kt_nn, &
                                kt_nt, stat)
        if (.not. stat%ok()) return
        ! allocated first: reallocation on assignment would read the undefined bounds that
        ! intent(out) leaves (UBSan saw their arithmetic overflow)
        allocate (a(this%p, this%p))
        a(:, :) = reduced_matrix(kt_nn/this%lambda_scale, kt_nt, this%mass, &
                                 this%lambda/this%lambda_scale)
    end subroutine operator_dense_a

    !> mu of an eigenvalue nu of the operator: A y = theta y with nu = (theta / lambda_scale)
    !> / (1 - sigma theta), i.e. mu = 1 / theta = sigma + 1 / (lambda_scale nu).
    elemental complex(wp) function operator_mu_of(this, nu) result(mu)
        class(contact_operator_t), intent(in) :: this
        complex(wp), intent(in) :: nu
        mu = this%sigma + (1.0_wp/nu)/this%lambda_scale
    end function operator_mu_of

    !> out = A y / lambda_scale = N K^-1 (lambda T' - N') M y / lambda_scale, through two
    !> triangular solves with L_c; with `transposed`, A' y / lambda_scale = M X K^-1 N' y /
    !> lambda_scale (X = lambda T - N) through the same solves.
    subroutine operator_apply_a(this, y, out, transposed)
        class(contact_operator_t), intent(in) :: this
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: out(:)
        logical, intent(in) :: transposed
        real(wp) :: v(this%p)
        if (this%explicit) then
            call dgemm(merge('T', 'N', transposed), 'N', this%p, 1, this%p, 1.0_wp, this%a, &
                       this%p, y, this%p, 0.0_wp, out, this%p)
        else if (transposed) then
            call this%contact_compliance(this%normal, this%x_direction(), y, v)
            call this%mass%matvec(v, out)
        else
            call this%mass%matvec(y, v)
            call this%contact_compliance(this%x_direction(), this%normal, v, out)
        end if
    end subroutine operator_apply_a

    !> (lambda t - n) / lambda_scale: the direction of X (X y(a) = it . y(dofs(:, a))).
    pure function operator_x_direction(this) result(direction)
        class(contact_operator_t), intent(in) :: this
        real(wp) :: direction(2)
        direction = this%lambda/this%lambda_scale*this%tangent - this%normal/this%lambda_scale
    end function operator_x_direction

    !> out(a) = d_out . (K^-1 f)(dofs(:, a)) for the contact forces f(dofs(:, b)) = d_in v(b):
    !> K^-1 on the contact dofs as L_c^-T L_c^-1.
    subroutine operator_contact_compliance(this, d_in, d_out, v, out)
        class(contact_operator_t), intent(in) :: this
        real(wp), intent(in) :: d_in(2), d_out(2), v(:)
        real(wp), intent(out) :: out(:)
        real(wp) :: z(2*this%p)
        integer :: a
        z = 0.0_wp
        do a = 1, this%p
            z(this%slot(:, a)) = d_in*v(a)
        end do
        call dtrsv('L', 'N', 'N', 2*this%p, this%l_tail, 2*this%p, z, 1)
        call dtrsv('L', 'T', 'N', 2*this%p, this%l_tail, 2*this%p, z, 1)
        do a = 1, this%p
            out(a) = dot_product(d_out, z(this%slot(:, a)))
        end do
    end subroutine operator_contact_compliance

    !> ARPACK's OP: A (sigma = 0) or (I - sigma A)^-1 A, divided by lambda_scale; the full
    !> operator (K - sigma B)^-1 B / lambda_scale. With `transposed` their transposes, whose
    !> eigenvalues are the same: A' (I - sigma A)^-T, and for the full operator
    !> (K - sigma B)^-T B' = (K - sigma B')^-1 B' (K symmetric; UMFPACK solves with the
    !> transpose of the same LU), the shift-invert operator of the pencil (K, B'), whose
    !> eigenvectors are the left eigenvectors y of (K, B): K y = mu B' y.
    subroutine operator_apply(this, y, out, stat)
        class(contact_operator_t), intent(inout) :: this
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: out(:)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: by(:, :), x(:, :), xy(:), mxy(:), w(:)
        integer :: info
        if (this%full) then
            allocate (by(this%n, 1))
            if (this%transposed) then
                ! left: (K - sigma B)^-T B' y / lambda_scale, B' = N' M X
                allocate (xy(this%p), mxy(this%p))
                call this%contact%gather(this%x_direction(), y, xy)
                call this%mass%matvec(xy, mxy)
                by = 0.0_wp
                call this%contact%scatter(this%normal, mxy, by(:, 1))
            else
                call this%b_scaled%matvec(y, by(:, 1))
            end if
            if (abs(this%sigma) > 0.0_wp) then
                call this%shifted%solve(by(:, 1), out, stat, transposed=this%transposed)
            else
                allocate (x(this%n, 1))
                call this%chol%solve(by, x, stat)
                out = x(:, 1)
            end if
            return
        end if
        if (this%transposed) then
            w = y
            if (abs(this%sigma) > 0.0_wp) call dgetrs('T', this%p, 1, this%a, this%p, &
                                                       this%pivots, w, this%p, info)
            call this%apply_a(w, out, transposed=.true.)
            return
        end if
        call this%apply_a(y, out, transposed=.false.)
        if (.not. (abs(this%sigma) > 0.0_wp)) return
        ! dgetrf succeeded in setup, so dgetrs cannot fail on these arguments
        call dgetrs('N', this%p, 1, this%a, this%p, this%pivots, out, this%p, info)
    end subroutine operator_apply
end module contact_operator
