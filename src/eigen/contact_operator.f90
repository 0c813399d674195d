! SPDX-License-Identifier: MIT
!> The operators ARPACK runs on (module arpack_eigen), one type each behind the abstract
!> contact_operator_t, whose `apply` is what the reverse communication asks for:
!> - reduced_operator_t: A = N K^-1 X' M on the contact nodes, from the trailing block of a
!>   contact-last factor of K, shift-inverted as (I - sigma A)^-1 A for a target sigma;
!> - full_operator_t: (K - sigma B)^-1 B in the n free dofs;
!> - explicit_operator_t: a p x p matrix A the caller formed (a lambda sweep), sigma = 0.
!> Each also applies its transpose, whose eigenvectors are the left ones. Every type owns
!> what it reads; the factor of K, which only the unshifted full operator solves with, is
!> an argument of `apply`, never kept.
module contact_operator
    use kinds, only: wp
    use status, only: status_t, STATUS_SOLVER, STATUS_BAD_INPUT, STATUS_SINGULAR
    use strings, only: to_string, short => short_real_text
    use real_format, only: real_to_text
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_boundary, only: contact_t
    use sparse_lu, only: lu_t
    use lapack_interfaces, only: dtrsv, dgetrf, dgetrs, dgemv, dlacn2
    use contact_reduction, only: contact_tail, flexibility_blocks, scaled_reduced_matrix, &
                                 lambda_unit, mu_of_theta
    use unit_scaling, only: units_t
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

    !> What every operator shares: its dimension, the shift, and mu of an eigenvalue nu.
    type, abstract, public :: contact_operator_t
        integer :: p = 0                        !! contact nodes (the rank of B)
        integer :: n = 0                        !! ARPACK's dimension
        real(wp) :: sigma = 0.0_wp
        real(wp) :: lambda = 0.0_wp
        !> The operator is built on A / lambda_scale (a power of two ~ |lambda| when
        !> |lambda| > 1, else 1): A ~ lambda overflowed ARPACK's norms from |lambda| ~ 1e160
        real(wp) :: lambda_scale = 1.0_wp
        !> ARPACK's start vector goes through the operator first: the full operator's null
        !> space, that of B (n - p wide), holds no eigenvector of a finite mu, and a start
        !> vector inside it would only feed round-off back
        logical :: start_in_range = .false.
    contains
        procedure(apply_interface), deferred :: apply
        procedure :: mu_of => operator_mu_of
        procedure :: check_target => operator_check_target
    end type contact_operator_t

    abstract interface
        !> ARPACK's OP (or its transpose, `transposed`): out = OP y. `factor` is the factor
        !> of K the operator was set up from.
        subroutine apply_interface(this, factor, y, out, transposed, stat)
            import :: contact_operator_t, cholesky_t, wp, status_t
            class(contact_operator_t), intent(inout) :: this   !! (UMFPACK's solve updates its record)
            type(cholesky_t), intent(in) :: factor
            real(wp), intent(in) :: y(:)
            real(wp), intent(out) :: out(:)
            logical, intent(in) :: transposed
            type(status_t), intent(out) :: stat
        end subroutine apply_interface
    end interface

    !> The reduced operator on the contact nodes: theta-mode y -> A y (sigma = 0) or
    !> shift-invert y -> (I - sigma A)^-1 A y, from L_c, the trailing 2p x 2p block of a
    !> contact-last factor of K.
    type, extends(contact_operator_t), public :: reduced_operator_t
        real(wp) :: normal(2) = 0.0_wp, tangent(2) = 0.0_wp
        real(wp) :: direction(2) = 0.0_wp      !! (lambda t - n) / lambda_scale
        real(wp), allocatable :: l_tail(:, :)   !! (2p, 2p) trailing block of the factor
        integer, allocatable :: slot(:, :)      !! (2, p) row in l_tail of contact dof (c, a)
        type(csr_matrix_t) :: mass              !! (p, p) boundary mass M
        real(wp), allocatable :: lu(:, :)       !! (p, p) LU of I - sigma A (sigma /= 0)
        integer, allocatable :: pivots(:)
    contains
        procedure :: setup => reduced_setup
        procedure :: apply => reduced_apply
        procedure :: dense_a => reduced_dense_a
    end type reduced_operator_t

    !> A p x p matrix A given by the caller (sigma = 0): one O(p^2) product per application.
    type, extends(contact_operator_t), public :: explicit_operator_t
        real(wp), allocatable :: a(:, :)
    contains
        procedure :: setup => explicit_setup
        procedure :: apply => explicit_apply
    end type explicit_operator_t

    !> The full operator y -> (K - sigma B)^-1 (B / lambda_scale) y in the n free dofs: the
    !> LU of K - sigma B (sigma /= 0) or solves with the factor of K (sigma = 0). The
    !> transposed one needs the contact (B' = N' M X).
    type, extends(contact_operator_t), public :: full_operator_t
        type(csr_matrix_t) :: b_scaled          !! B / lambda_scale
        type(lu_t) :: shifted                   !! LU of K - sigma B (sigma /= 0)
        type(contact_t) :: contact
        real(wp) :: direction(2) = 0.0_wp      !! (lambda t - n) / lambda_scale
    contains
        procedure :: setup => full_setup
        procedure :: apply => full_apply
        procedure :: norm_estimate => full_norm_estimate
    end type full_operator_t

contains

    !> The shared part of every setup.
    subroutine operator_init(this, p, n, lambda, sigma)
        class(contact_operator_t), intent(inout) :: this
        integer, intent(in) :: p, n
        real(wp), intent(in) :: lambda, sigma
        this%p = p
        this%n = n
        this%lambda = lambda
        this%sigma = sigma
        this%lambda_scale = lambda_unit(lambda)
    end subroutine operator_init

    !> Build the reduced operator from a factor of K whose last 2p pivots are the contact
    !> dofs (see node_ordering), and factor I - sigma A when sigma /= 0, after checking
    !> |sigma| ||A|| <= TARGET_RANGE (STATUS_BAD_INPUT naming &eigen target otherwise).
    subroutine reduced_setup(this, chol, contact, lambda, sigma, stat, target_input, units)
        class(reduced_operator_t), intent(inout) :: this
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda, sigma
        type(status_t), intent(out) :: stat
        real(wp), intent(in) :: target_input      !! sigma as the input gave it (messages)
        type(units_t), intent(in) :: units        !! of mu here (messages)
        real(wp) :: a_norm
        integer :: a, info

        call operator_init(this, contact%p(), contact%p(), lambda, sigma)
        this%normal = contact%normal
        this%tangent = contact%tangent
        this%direction = contact%slip_direction(lambda, this%lambda_scale)
        this%mass = contact%mass
        call contact_tail(chol, contact, this%l_tail, this%slot, stat)
        if (.not. stat%ok()) return
        if (.not. (abs(sigma) > 0.0_wp)) return

        call this%dense_a(this%lu, stat)
        if (.not. stat%ok()) return
        ! this%lu is A / lambda_scale here
        a_norm = maxval(sum(abs(this%lu), dim=2))
        call this%check_target(a_norm, target_input, units, stat)
        if (.not. stat%ok()) return
        ! LU of I - sigma A (A itself is applied through L_c)
        this%lu = -(sigma*this%lambda_scale)*this%lu
        do a = 1, this%p
            this%lu(a, a) = this%lu(a, a) + 1.0_wp
        end do
        allocate (this%pivots(this%p))
        call dgetrf(this%p, this%p, this%lu, this%p, this%pivots, info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, 'arpack: K - sigma B is singular for sigma = '// &
                to_string(sigma)//' (an eigenvalue equals the target; move the target)')
        end if
    end subroutine reduced_setup

    !> The explicit operator on a copy of `a`: A itself, or with `lambda` the scaled
    !> A / lambda_unit(lambda) (scaled_reduced_matrix), whose mu_of then undoes the scaling as
    !> the reduced operator's does.
    subroutine explicit_setup(this, a, lambda)
        class(explicit_operator_t), intent(inout) :: this
        real(wp), intent(in) :: a(:, :)
        real(wp), intent(in), optional :: lambda
        real(wp) :: at
        at = 0.0_wp
        if (present(lambda)) at = lambda
        call operator_init(this, size(a, 1), size(a, 1), at, 0.0_wp)
        this%a = a
    end subroutine explicit_setup

    !> The full operator (K - sigma B)^-1 B / lambda_scale in the n free dofs. sigma = 0
    !> solves with `chol`, the factor of K, passed to every `apply` (no second
    !> factorization); sigma /= 0 factors K - sigma B once with UMFPACK, after the range
    !> check of reduced_setup with ||A||_inf estimated (norm_estimate: a few sparse solves
    !> with `chol` instead of forming A). Nothing of order p^2.
    subroutine full_setup(this, k, b, chol, contact, lambda, sigma, stat, target_input, units)
        class(full_operator_t), intent(inout) :: this
        type(csr_matrix_t), intent(in) :: k, b
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda, sigma
        type(status_t), intent(out) :: stat
        real(wp), intent(in) :: target_input
        type(units_t), intent(in) :: units
        real(wp) :: a_norm

        call operator_init(this, contact%p(), k%n(), lambda, sigma)
        this%start_in_range = .true.
        this%b_scaled = b
        this%b_scaled%val = b%val/this%lambda_scale
        this%contact = contact
        this%direction = contact%slip_direction(lambda, this%lambda_scale)
        if (.not. (abs(sigma) > 0.0_wp)) return
        call this%norm_estimate(chol, a_norm, stat)
        if (.not. stat%ok()) return
        call this%check_target(a_norm, target_input, units, stat)
        if (.not. stat%ok()) return
        ! no iterative refinement: ARPACK needs a backward-stable solve, which the LU gives,
        ! and every eigenpair's backward error on (K, B) is checked; refinement tripled the
        ! cost of each application (measured, docs/performance.md)
        call this%shifted%factor_shifted(k, b, sigma, stat, refinement_steps=0)
        if (stat%code /= STATUS_SINGULAR) return
        stat%message = 'arpack: K - sigma B for sigma = '//to_string(sigma)//': '// &
                       stat%message//' (an eigenvalue equals the target; move the target)'
    end subroutine full_setup

    !> |sigma| ||A|| <= TARGET_RANGE, with a_norm = ||A / lambda_scale||_inf; written with
    !> quotients, which cannot overflow (sigma may be clamped to huge: units_mu_to_scaled).
    !> Otherwise STATUS_BAD_INPUT in one line naming the variable (the caller adds the file).
    subroutine operator_check_target(this, a_norm, target_input, units, stat)
        class(contact_operator_t), intent(in) :: this
        real(wp), intent(in) :: a_norm, target_input
        type(units_t), intent(in) :: units
        type(status_t), intent(out) :: stat
        if (.not. abs(this%sigma) > (TARGET_RANGE/a_norm)/this%lambda_scale) return
        call stat%fail(STATUS_BAD_INPUT, '&eigen: target = '// &
            real_to_text(target_input)//': expected |target| <= '// &
            short(units%mu_to_input((TARGET_RANGE/a_norm)/this%lambda_scale))// &
            ' (1e6 / ||A||, the scale of the spectrum here: further out, mu = target '// &
            '+ 1/nu cancels and loses more than 6 of the 16 digits)')
    end subroutine operator_check_target

    !> ||A / lambda_scale||_inf = ||(A / lambda_scale)'||_1 estimated by LAPACK dlacn2
    !> (Higham's estimator: a lower bound, exact on the scenes measured), with A = N K^-1 X' M
    !> and A' = M X K^-1 N' applied through solves with the sparse factor `chol` of K:
    !> about five, O(nnz(L)) each, where forming A costs O(p^3) and p^2 memory.
    subroutine full_norm_estimate(this, chol, estimate, stat)
        class(full_operator_t), intent(in) :: this
        type(cholesky_t), intent(in) :: chol
        real(wp), intent(out) :: estimate
        type(status_t), intent(out) :: stat
        real(wp) :: v(this%p), x(this%p), product(this%p), mx(this%p)
        integer :: isgn(this%p), kase, isave(3)
        estimate = 0.0_wp
        kase = 0
        do
            call dlacn2(this%p, v, x, isgn, estimate, kase, isave)
            if (kase == 0) exit
            if (kase == 1) then   ! A' x = M (X K^-1 N' x)
                call compliance(this%contact%normal, x, this%direction, mx)
                call this%contact%mass%matvec(mx, product)
            else                  ! A x = N K^-1 X' (M x)
                call this%contact%mass%matvec(x, mx)
                call compliance(this%direction, mx, this%contact%normal, product)
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
            call this%contact%scatter(column, y, z(:, 1))
            call chol%solve(z, w, stat)
            call this%contact%gather(row, w(:, 1), out)
        end subroutine compliance
    end subroutine full_norm_estimate

    !> A = (lambda Kt_nt - Kt_nn) M / lambda_scale as a dense p x p matrix, with Kt_nn and
    !> Kt_nt formed from L_c as the dense solver forms them (contact_reduction: dpotri,
    !> O(p^3)).
    subroutine reduced_dense_a(this, a, stat)
        class(reduced_operator_t), intent(in) :: this
        real(wp), allocatable, intent(out) :: a(:, :)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :)
        call flexibility_blocks(this%l_tail, this%slot, this%normal, this%tangent, kt_nn, &
                                kt_nt, stat)
        if (.not. stat%ok()) return
        ! allocated first: reallocation on assignment would read the undefined bounds that
        ! intent(out) leaves (UBSan saw their arithmetic overflow)
        allocate (a(this%p, this%p))
        a(:, :) = scaled_reduced_matrix(kt_nn, kt_nt, this%mass, this%lambda)
    end subroutine reduced_dense_a

    !> mu of an eigenvalue nu of the operator: A y = theta y with nu = (theta / lambda_scale)
    !> / (1 - sigma theta), i.e. mu = 1 / theta = sigma + 1 / (lambda_scale nu).
    elemental complex(wp) function operator_mu_of(this, nu) result(mu)
        class(contact_operator_t), intent(in) :: this
        complex(wp), intent(in) :: nu
        mu = this%sigma + mu_of_theta(nu, this%lambda_scale)
    end function operator_mu_of

    !> out(a) = d_out . (K^-1 f)(dofs(:, a)) for the contact forces f(dofs(:, b)) = d_in v(b):
    !> K^-1 on the contact dofs as L_c^-T L_c^-1.
    subroutine reduced_compliance(this, d_in, d_out, v, out)
        class(reduced_operator_t), intent(in) :: this
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
    end subroutine reduced_compliance

    !> A (sigma = 0) or (I - sigma A)^-1 A, divided by lambda_scale, through two triangular
    !> solves with L_c: A y = N K^-1 X' M y. Transposed: A' (I - sigma A)^-T, with
    !> A' y = M X K^-1 N' y through the same solves. `factor` is not read (L_c is kept).
    subroutine reduced_apply(this, factor, y, out, transposed, stat)
        class(reduced_operator_t), intent(inout) :: this
        type(cholesky_t), intent(in) :: factor
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: out(:)
        logical, intent(in) :: transposed
        type(status_t), intent(out) :: stat
        real(wp) :: v(this%p), w(this%p)
        integer :: info
        if (transposed) then
            w = y
            if (abs(this%sigma) > 0.0_wp) call dgetrs('T', this%p, 1, this%lu, this%p, &
                                                       this%pivots, w, this%p, info)
            call reduced_compliance(this, this%normal, this%direction, w, v)
            call this%mass%matvec(v, out)
            return
        end if
        call this%mass%matvec(y, v)
        call reduced_compliance(this, this%direction, this%normal, v, out)
        if (.not. (abs(this%sigma) > 0.0_wp)) return
        ! dgetrf succeeded in setup, so dgetrs cannot fail on these arguments
        call dgetrs('N', this%p, 1, this%lu, this%p, this%pivots, out, this%p, info)
    end subroutine reduced_apply

    !> A y or A' y by one dense product. `factor` is not read. dgemv, not dgemm with one
    !> column: OpenBLAS's dgemm packs all of A into its buffers on every call, which cost
    !> twice the product itself (measured with perf on an hp sweep, p = 361).
    subroutine explicit_apply(this, factor, y, out, transposed, stat)
        class(explicit_operator_t), intent(inout) :: this
        type(cholesky_t), intent(in) :: factor
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: out(:)
        logical, intent(in) :: transposed
        type(status_t), intent(out) :: stat
        call dgemv(merge('T', 'N', transposed), this%p, this%p, 1.0_wp, this%a, this%p, y, 1, &
                   0.0_wp, out, 1)
    end subroutine explicit_apply

    !> (K - sigma B)^-1 B / lambda_scale. Transposed: (K - sigma B)^-T B' =
    !> (K - sigma B')^-1 B' (K symmetric; UMFPACK solves with the transpose of the same LU),
    !> the shift-invert operator of the pencil (K, B'), whose eigenvectors are the left
    !> eigenvectors y of (K, B): K y = mu B' y. sigma = 0 solves with `factor`.
    subroutine full_apply(this, factor, y, out, transposed, stat)
        class(full_operator_t), intent(inout) :: this
        type(cholesky_t), intent(in) :: factor
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: out(:)
        logical, intent(in) :: transposed
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: by(:, :), x(:, :), xy(:), mxy(:)
        allocate (by(this%n, 1))
        if (transposed) then
            ! left: (K - sigma B)^-T B' y / lambda_scale, B' = N' M X
            allocate (xy(this%p), mxy(this%p))
            call this%contact%gather(this%direction, y, xy)
            call this%contact%mass%matvec(xy, mxy)
            by = 0.0_wp
            call this%contact%scatter(this%contact%normal, mxy, by(:, 1))
        else
            call this%b_scaled%matvec(y, by(:, 1))
        end if
        if (abs(this%sigma) > 0.0_wp) then
            call this%shifted%solve(by(:, 1), out, stat, transposed=transposed)
        else
            allocate (x(this%n, 1))
            call factor%solve(by, x, stat)
            out = x(:, 1)
        end if
    end subroutine full_apply
end module contact_operator
