! SPDX-License-Identifier: MIT
!> The floating-point part of the error bar of the lowest positive mu, the same for every
!> solver (docs/accuracy.md, "Round-off part of the bar"). First-order perturbation theory
!> on the pencil K x = mu B x with right vector x and left vector y (K y = mu B' y): a
!> perturbation (dK, dB) moves mu by y' (dK - mu dB) x / (y' B x). Two sources:
!> - the solver: the computed pair leaves the residual r = K x - mu B x, which the exact
!>   eigenvalue differs from by y' r / (y' B x) to first order, at most |y|'|r| / |y' B x|
!>   (dgeevx's or ARPACK's backward error times the eigenvalue's condition, without norms);
!> - the data: assembly and the factor of K perturb K entrywise by up to a few eps |K|, and
!>   B's factors (X = lambda T - N, the contact mass M, N) by a few eps each, so
!>   |dmu| <= ROUNDOFF_UNITS eps (|y|'|K||x| + |mu| |X y|'|M||N x|) / |y' B x|.
!> Relative: divided by |mu|, with |mu y' B x| computed as |y' K x| (equal for an eigenpair;
!> near a critical lambda y' B x ~ 1/mu cancels down to its own rounding, y' K x does not).
!> Componentwise, the bound sees what makes mu ill conditioned and no more: a nearly
!> incompressible material (|K| ~ the Lame modulus while x is nearly divergence free, so
!> |y|'|K||x| >> |y' K x|), slivers and stretched cells (large entries of |K| that cancel in
!> K x), lambda near a threshold (y' K x small against |mu| |X y|'|M||N x|). A normwise
!> bound ||K|| ||x|| ||y|| grows like cond(K) instead and was measured 1e2 to 1e4 times the
!> error.
module roundoff
    use kinds, only: wp
    use status, only: status_t, STATUS_SOLVER
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_boundary, only: contact_t
    use critical_lambda, only: thresholds_t, SIDE_PLUS, SIDE_MINUS
    use contact_reduction, only: reduced_blocks_t, lambda_unit, lift_share_t, lift_left
    use critical_set, only: critical_set_t, boundary_point_t, MECHANISM_COMPLEX_PAIR
    use lapack_interfaces, only: dgeev, lapack_info_message
    implicit none
    private
    public :: roundoff_bound, left_from_reduced, lowest_roundoff, contact_abs_form
    public :: pencil_roundoff, threshold_roundoff, collision_bound, collision_roundoffs

    !> The data term's multiple of eps. An entry of K is a sum of some 10 to 100 products
    !> (quadrature points, cells per node, the elasticity tensor) and the factor of K adds a
    !> growth of a few eps per entry; 4 is calibrated on measurements (docs/accuracy.md: the
    !> spread of mu over copies of the same discrete problem in other units (young, size)
    !> and over the three solvers: reference scene, nu -> 1/2, 1000:1 cells, Gmsh
    !> slivers, lambda near a threshold, h-adaptive P3 up to 2e5 dofs and hp levels): the
    !> bound then stays 13 to 57 times the measured spread (28 to 57 on graded meshes).
    real(wp), parameter, public :: ROUNDOFF_UNITS = 4.0_wp

contains

    !> |mu - mu_exact| / |mu| bound for the pair (mu, x) of the pencil (K, B(lambda)) with the
    !> left vector y (any scaling of x and y). huge() when y' K x = 0 (a defective or
    !> infinitely ill-conditioned eigenvalue).
    function roundoff_bound(k, b, contact, lambda, mu, x, y) result(bound)
        type(csr_matrix_t), intent(in) :: k, b
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda, mu, x(:), y(:)
        real(wp) :: bound
        real(wp) :: xs(size(x)), ys(size(y)), kx(size(x)), bx(size(x)), ykx, k_abs, b_abs
        bound = huge(1.0_wp)
        if (.not. (maxval(abs(x)) > 0.0_wp .and. maxval(abs(y)) > 0.0_wp)) return
        ! scaled by powers of two first (exact): the quotients are scale invariant, and the
        ! products then cannot overflow
        xs = scale(x, -exponent(maxval(abs(x))))
        ys = scale(y, -exponent(maxval(abs(y))))
        call k_products(k, xs, ys, kx, k_abs)
        call b%matvec(xs, bx)
        ykx = abs(dot_product(ys, kx))
        if (.not. (ykx > 0.0_wp)) return
        b_abs = abs(mu)*contact_abs_form(contact, lambda, xs, ys)
        bound = (abs(dot_product(ys, kx - mu*bx)) + &
                 ROUNDOFF_UNITS*epsilon(1.0_wp)*(k_abs + b_abs))/ykx
    end function roundoff_bound

    !> The left eigenvector y = K^-1 N' w of the pencil from w, a left eigenvector of the
    !> reduced matrix A = (lambda Kt_nt - Kt_nn) M (A' w = theta w; module dual_eigen: y is
    !> mu K^-1 N' w, the factor mu only scales it). One solve with any factor of K; with
    !> `share`, the lifts' data on `chol` (contact dofs last), its backward half alone
    !> (lift_left: half the passes over the factor, for an hp sweep's many points).
    subroutine left_from_reduced(chol, contact, n_free, w, y, stat, share)
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        integer, intent(in) :: n_free
        real(wp), intent(in) :: w(:)
        real(wp), allocatable, intent(out) :: y(:)
        type(status_t), intent(out) :: stat
        type(lift_share_t), intent(in), optional :: share
        real(wp), allocatable :: rhs(:, :), solution(:, :)
        if (present(share)) then
            if (allocated(share%l_tail)) then
                call lift_left(share, chol, contact, n_free, w, y, stat)
                return
            end if
        end if
        allocate (rhs(n_free, 1), source=0.0_wp)
        allocate (solution(n_free, 1))
        call contact%scatter(contact%normal, w, rhs(:, 1))
        call chol%solve(rhs, solution, stat)
        if (.not. stat%ok()) return
        y = solution(:, 1)
    end subroutine left_from_reduced

    !> roundoff_bound of the lowest positive mu with right vector x and left vector y;
    !> -1 (unknown) when y is not allocated or does not match x.
    subroutine lowest_roundoff(k, b, contact, lambda, mu, x, y, bound)
        type(csr_matrix_t), intent(in) :: k, b
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda, mu, x(:)
        real(wp), allocatable, intent(in) :: y(:)
        real(wp), intent(out) :: bound
        bound = -1.0_wp
        if (.not. allocated(y)) return
        if (size(y) /= size(x)) return
        bound = roundoff_bound(k, b, contact, lambda, mu, x, y)
    end subroutine lowest_roundoff

    !> |X y|' |M| |N x| with X = lambda T - N: the componentwise size of y' B x, B = X' M N.
    function contact_abs_form(contact, lambda, x, y) result(form)
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda, x(:), y(:)
        real(wp) :: form
        real(wp) :: xy(contact%p()), nx(contact%p()), m_nx(contact%p())
        integer :: i, first, last
        call contact%gather(abs(lambda*contact%tangent - contact%normal), abs(y), xy)
        call contact%gather(abs(contact%normal), abs(x), nx)
        m_nx = 0.0_wp
        do i = 1, contact%p()
            first = contact%mass%row_start(i)
            last = contact%mass%row_start(i + 1) - 1
            m_nx(i) = sum(abs(contact%mass%val(first:last))*nx(contact%mass%col(first:last)))
        end do
        form = dot_product(xy, m_nx)
    end function contact_abs_form

    !> K x and |y|' |K| |x| (abs_form) in one pass over K, which is most of the bound's cost
    !> on an hp level (its dense element blocks): K x summed as csr_matrix_t%matvec does.
    pure subroutine k_products(k, x, y, kx, k_abs)
        type(csr_matrix_t), intent(in) :: k
        real(wp), intent(in) :: x(:), y(:)
        real(wp), intent(out) :: kx(:), k_abs
        real(wp) :: row, row_abs
        integer :: i, j
        k_abs = 0.0_wp
        do i = 1, k%n()
            row = 0.0_wp
            row_abs = 0.0_wp
            do j = k%row_start(i), k%row_start(i + 1) - 1
                row = row + k%val(j)*x(k%col(j))
                row_abs = row_abs + abs(k%val(j))*abs(x(k%col(j)))
            end do
            kx(i) = row
            k_abs = k_abs + abs(y(i))*row_abs
        end do
    end subroutine k_products

    !> |y|' |K| |x|, the componentwise size of y' K x.
    real(wp) function abs_form(k, y, x)
        type(csr_matrix_t), intent(in) :: k
        real(wp), intent(in) :: y(:), x(:)
        integer :: i, first, last
        abs_form = 0.0_wp
        do i = 1, k%n()
            first = k%row_start(i)
            last = k%row_start(i + 1) - 1
            abs_form = abs_form + abs(y(i))*sum(abs(k%val(first:last))*abs(x(k%col(first:last))))
        end do
    end function abs_form

    !> |lambda - lambda_exact| / |lambda| for the computed eigenvalue lambda of the pencil
    !> A z = lambda B z with right vector z and left vector w, to first order: the solver's
    !> residual r = A z - lambda B z moves it by w' r / (w' B z), and a data perturbation
    !> (dA, dB) by w' (dA - lambda dB) z / (w' B z), whose size the caller bounds by `data`
    !> (for entrywise |dA| <= E, |dB| <= F: |w|' E |z| + |lambda| |w|' F |z|). Relative
    !> through lambda w' B z = w' A z; huge() when that is 0 (infinitely ill conditioned).
    pure real(wp) function pencil_roundoff(a, b, lambda, z, w, data) result(bound)
        real(wp), intent(in) :: a(:, :), b(:, :), lambda, z(:), w(:), data
        real(wp) :: waz
        bound = huge(1.0_wp)
        waz = abs(dot_product(w, matmul(a, z)))
        if (.not. (waz > 0.0_wp)) return
        bound = (abs(dot_product(w, matmul(a, z) - lambda*matmul(b, z))) + data)/waz
    end function pencil_roundoff

    !> thr%roundoff: the round-off part of the bars of lambda+ and lambda-, the eigenvalues
    !> of the pencil Kt_nn z = lambda Kt_nt z (critical_lambda). The blocks are
    !> N K^-1 N' and N K^-1 T', so Kt_nn - lambda Kt_nt = N K^-1 (N' - lambda T'): their
    !> data error is not eps |Kt| but that of K (assembly, factor, the dense inverse of the
    !> contact Schur complement) seen through it, and a perturbation dK moves
    !> w' (Kt_nn - lambda Kt_nt) z by y' dK phi with the full-space lifts y = K^-1 N' w and
    !> phi = K^-1 (N' - lambda T') z (the limit mode). So data = ROUNDOFF_UNITS eps
    !> |y|'|K||phi|, the same componentwise form and multiple as the bound of mu: two solves
    !> per side with the factor there is, O(nnz) besides.
    subroutine threshold_roundoff(k, chol, contact, kt_nn, kt_nt, thr, stat)
        type(csr_matrix_t), intent(in) :: k
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: kt_nn(:, :), kt_nt(:, :)
        type(thresholds_t), intent(inout) :: thr
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: rhs(:, :), lifts(:, :)
        real(wp) :: z(size(kt_nn, 1)), w(size(kt_nn, 1))
        integer :: side

        thr%roundoff = -1.0_wp
        if (.not. (any(thr%found) .and. allocated(thr%left_vectors))) return
        allocate (rhs(k%n(), 4), source=0.0_wp)
        allocate (lifts(k%n(), 4))
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. thr%found(side)) cycle
            call contact%scatter(contact%normal, thr%left_vectors(:, side), rhs(:, 2*side - 1))
            call contact%scatter(contact%normal - thr%lambda(side)*contact%tangent, &
                                 thr%vectors(:, side), rhs(:, 2*side))
        end do
        call chol%solve(rhs, lifts, stat)
        if (.not. stat%ok()) return
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. thr%found(side)) cycle
            z = thr%vectors(:, side)
            w = thr%left_vectors(:, side)
            thr%roundoff(side) = pencil_roundoff(kt_nn, kt_nt, thr%lambda(side), z, w, &
                ROUNDOFF_UNITS*epsilon(1.0_wp)*abs_form(k, lifts(:, 2*side - 1), &
                                                        lifts(:, 2*side)))
        end do
    end subroutine threshold_roundoff

    !> |lambda_c - lambda_exact| / |lambda_c| for a collision lambda_c, where two eigenvalues
    !> of A(lambda) meet (a 2 x 2 Jordan block: right vector x, left vector y, y'x = 0). A
    !> perturbation E keeps a double eigenvalue where y'(E + A' d lambda) x = 0 (the split of
    !> the pair is the square root of that, to first order), so the collision moves by
    !> d lambda = -y'Ex / y'A'x, A' = dA/dlambda; `dax` is A'x. The solver's perturbation is
    !> normwise (dgeev, backward stable: a few eps ||A||_F, `a_norm` = ||A||_F), the data's
    !> is bounded by the caller: |y' dA x| <= `data`. huge() when y'A'x = 0 (the pair does not
    !> cross: no first-order bound).
    pure real(wp) function collision_bound(a_norm, lambda, x, y, dax, data) result(bound)
        real(wp), intent(in) :: a_norm, lambda, x(:), y(:), dax(:), data
        real(wp) :: ydax
        bound = huge(1.0_wp)
        ydax = abs(dot_product(y, dax))*abs(lambda)
        if (.not. (ydax > 0.0_wp)) return
        bound = (ROUNDOFF_UNITS*epsilon(1.0_wp)*a_norm*norm2(x)*norm2(y) + data)/ydax
    end function collision_bound

    !> The round-off part (collision_roundoff) of every complex_pair point of `set`.
    subroutine collision_roundoffs(k, chol, contact, blocks, set, stat, lift)
        type(csr_matrix_t), intent(in) :: k
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        type(reduced_blocks_t), intent(in) :: blocks
        type(critical_set_t), intent(inout) :: set
        type(status_t), intent(out) :: stat
        !> (p, q) blocks of restricted forces (critical_lambda: restricted_thresholds): their
        !> vectors on the contact functions
        real(wp), intent(in), optional :: lift(:, :)
        integer :: i
        do i = 1, size(set%points)
            call collision_roundoff(k, chol, contact, blocks, set%points(i), stat, lift)
            if (.not. stat%ok()) return
        end do
    end subroutine collision_roundoffs

    !> point%roundoff for a complex_pair boundary point of the reduced matrix A(lambda) =
    !> (lambda Kt_nt - Kt_nn) M of `blocks` (collision_bound). Its vectors are dgeev's of the
    !> eigenvalue nearest where the pair meets (their real parts: at the meeting point the
    !> pair's vectors tend to x and y, a few sqrt(eps) off, which a first-order bound
    !> tolerates). The data term is that of K, as in threshold_roundoff: A = N K^-1
    !> (lambda T' - N') M, so dK moves y'Ax by the lifts' |K^-1 N'y|' |dK| |K^-1 (lambda T' -
    !> N') M x|; two solves with the factor `chol`. Other points keep -1.
    subroutine collision_roundoff(k, chol, contact, blocks, point, stat, lift)
        type(csr_matrix_t), intent(in) :: k
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        type(reduced_blocks_t), intent(in) :: blocks
        type(boundary_point_t), intent(inout) :: point
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: lift(:, :)
        real(wp), allocatable :: a(:, :), vl(:, :), vr(:, :), wr(:), wi(:), work(:), &
                                 rhs(:, :), lifts(:, :)
        real(wp) :: query(1), theta, unit, a_norm
        real(wp), allocatable :: x(:), y(:), mx(:)
        integer :: p, j, info

        point%roundoff = -1.0_wp
        if (point%mechanism /= MECHANISM_COMPLEX_PAIR .or. .not. point%mu_meet > 0.0_wp) return
        p = size(blocks%kt_nn, 1)
        unit = lambda_unit(point%lambda)
        allocate (a(p, p))   ! then filled: see dense_eigen on reallocation on assignment
        a(:, :) = blocks%matrix(point%lambda)
        a_norm = unit*norm2(a)   ! ||A||: unit times that of the matrix decomposed
        allocate (wr(p), wi(p), vl(p, p), vr(p, p), x(p), y(p), mx(p))
        call dgeev('V', 'V', p, a, p, wr, wi, vl, p, vr, p, query, -1, info)
        allocate (work(max(1, int(query(1)))))
        call dgeev('V', 'V', p, a, p, wr, wi, vl, p, vr, p, work, size(work), info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, 'collision round-off: '// &
                           lapack_info_message('dgeev', info))
            return
        end if
        ! mu_meet is 1 / theta of A itself; the matrix decomposed is A / unit
        theta = 1.0_wp/(point%mu_meet*unit)
        j = minloc(abs(cmplx(wr - theta, wi, wp)), dim=1)
        if (wi(j) < 0.0_wp) j = j - 1   ! a conjugate pair: its real parts are in column j
        x = vr(:, j)
        y = vl(:, j)
        call blocks%mass%matvec(x, mx)
        allocate (rhs(k%n(), 2), source=0.0_wp)
        allocate (lifts(k%n(), 2))
        if (present(lift)) then
            call contact%scatter(contact%normal, matmul(lift, y), rhs(:, 1))
            call contact%scatter(point%lambda*contact%tangent - contact%normal, &
                                 matmul(lift, mx), rhs(:, 2))
        else
            call contact%scatter(contact%normal, y, rhs(:, 1))
            call contact%scatter(point%lambda*contact%tangent - contact%normal, mx, rhs(:, 2))
        end if
        call chol%solve(rhs, lifts, stat)
        if (.not. stat%ok()) return
        ! A' x = Kt_nt M x
        point%roundoff = collision_bound(a_norm, point%lambda, x, y, &
            matmul(blocks%kt_nt, mx), ROUNDOFF_UNITS*epsilon(1.0_wp)*abs_form(k, lifts(:, 1), &
                                                                              lifts(:, 2)))
    end subroutine collision_roundoff
end module roundoff
