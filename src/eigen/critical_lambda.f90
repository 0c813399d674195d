! SPDX-License-Identifier: MIT
!> The critical lambda of model.md sections 4-7, computed directly: a positive mu appears when an
!> eigenvalue theta = 1/mu of (lambda Kt_nt - Kt_nn) M crosses zero, i.e. when
!> det(lambda Kt_nt - Kt_nn) = 0 (M is SPD), so the thresholds are the real eigenvalues of the
!> pencil Kt_nn x = lambda Kt_nt x nearest to zero on each side. Also the cheap p x p
!> evaluation of the lowest positive mu at any lambda once Kt_nn and Kt_nt are known,
!> which confirms the thresholds and draws the c_n(lambda) curve.
!>
!> Why QZ (dggev) on the pencil rather than a Cholesky reduction Kt_nn = R^T R and dgeev on
!> R^-T Kt_nt R^-1 (eigenvalues 1/lambda): QZ is backward stable for the pencil itself, with
!> perturbations of order eps ||Kt_nn|| and eps ||Kt_nt||, while the reduction multiplies the
!> error by up to cond(Kt_nn), which grows as the mesh is refined (Kt_nn samples a flexibility
!> operator of order -1). The infinite eigenvalues (Kt_nt singular) come out of QZ as
!> beta = 0 and are simply skipped. The cost, O(p^3) once per run, is that of one dense
!> eigen-solve of the reduced problem.
module critical_lambda
    use kinds, only: wp
    use status, only: status_t, STATUS_SOLVER
    use strings, only: to_string, short_real_text
    use lapack_interfaces, only: dggev, dgeev, dgesvd, dpotrf, dtrsm, lapack_info_message
    use dual_eigen, only: reduced_left_eigenvector
    use contact_reduction, only: reduced_blocks_t, lambda_unit
    use sorting, only: sort_index
    implicit none
    private
    public :: thresholds_t, pencil_thresholds, lowest_positive_mu, confirm_thresholds
    public :: reduced_eigenvalues, count_positive, restricted_pencil, restricted_thresholds
    public :: SIDE_PLUS, SIDE_MINUS, SIDE_NAMES, SIDE_LABELS, CONFIRM_OFFSET

    integer, parameter :: SIDE_PLUS = 1    !! index of lambda+ > 0 in thresholds_t arrays
    integer, parameter :: SIDE_MINUS = 2   !! index of lambda- < 0
    !> the sides in key names (lambda_critical_plus) and in text (lambda+)
    character(len=*), parameter :: SIDE_NAMES(2) = [character(len=5) :: 'plus', 'minus']
    character(len=*), parameter :: SIDE_LABELS(2) = [character(len=7) :: 'lambda+', 'lambda-']
    !> Relative distance of the confirming solves from a threshold: far above the threshold's
    !> own relative error (~ condition * 1e-16) so that the side is certain, close enough that
    !> mu ~ C / (lambda - lambda*) is large just outside.
    real(wp), parameter :: CONFIRM_OFFSET = 1.0e-6_wp

    !> Both thresholds with their checks; arrays are indexed by SIDE_PLUS, SIDE_MINUS.
    type, public :: thresholds_t
        logical :: found(2) = .false.              !! a real pencil eigenvalue of that sign
        real(wp) :: lambda(2) = 0.0_wp             !! lambda+ > 0, lambda- < 0 when found
        real(wp) :: residual(2) = 0.0_wp           !! backward error of the pencil eigenpair
        integer :: n_real = 0                      !! finite real pencil eigenvalues
        integer :: n_complex = 0                   !! complex ones (conjugate pairs count 2)
        integer :: n_infinite = 0                  !! beta = 0 to working precision
        !> lambda* +- CONFIRM_OFFSET |lambda*|, away from zero and toward it: the very numbers
        !> the boundary search brackets a pencil point with (critical_set: side_offset)
        real(wp) :: lambda_outside(2) = 0.0_wp
        real(wp) :: lambda_inside(2) = 0.0_wp
        !> positive real mu there (-1: not solved), which that search then need not count again
        integer :: n_outside(2) = -1, n_inside(2) = -1
        logical :: has_mu_outside(2) = .false.     !! a positive mu exists there (expected)
        logical :: has_mu_inside(2) = .false.      !! a positive mu exists there (not expected)
        !> lowest positive mu there, if any, in the units of the blocks (problem_t%units)
        real(wp) :: mu_outside(2) = 0.0_wp
        real(wp) :: mu_inside(2) = 0.0_wp
        !> every finite real pencil eigenvalue, ascending: where a real theta = 1/mu crosses 0
        real(wp), allocatable :: real_lambdas(:)
        !> (p, 2) the pencil eigenvector x of each side found (largest entry 1): the contact
        !> tractions of the limit mode, model.md section 7
        real(wp), allocatable :: vectors(:, :)
        !> (p, 2) the left eigenvector w of each side (w' Kt_nn = lambda w' Kt_nt), for the
        !> round-off bound (roundoff: threshold_roundoff)
        real(wp), allocatable :: left_vectors(:, :)
        !> |dlambda| / |lambda| from floating point (threshold_roundoff); -1: not computed
        real(wp) :: roundoff(2) = -1.0_wp
    contains
        procedure :: confirmed => thresholds_confirmed
    end type thresholds_t

contains

    !> True when threshold `side` was found, a positive mu exists just outside it and none
    !> just inside.
    pure logical function thresholds_confirmed(this, side)
        class(thresholds_t), intent(in) :: this
        integer, intent(in) :: side
        thresholds_confirmed = this%found(side) .and. this%has_mu_outside(side) .and. &
                               .not. this%has_mu_inside(side)
    end function thresholds_confirmed

    !> The real eigenvalues of Kt_nn x = lambda Kt_nt x nearest to zero on each side, by QZ,
    !> with the backward error of each eigenpair on the pencil (infinity norm).
    subroutine pencil_thresholds(kt_nn, kt_nt, thr, stat)
        real(wp), intent(in) :: kt_nn(:, :), kt_nt(:, :)   !! (p, p)
        type(thresholds_t), intent(out) :: thr
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: a(:, :), b(:, :), alphar(:), alphai(:), beta(:), work(:)
        real(wp) :: query(1), norm_nn, norm_nt, lambda, vl(1, 1), vr(1, 1)
        integer :: p, info, j, best, side, ierr
        logical, allocatable :: finite(:)

        p = size(kt_nn, 1)
        ! sourced allocation: assigning to an unallocated array draws false -Wuninitialized
        allocate (a, source=kt_nn, stat=ierr)
        if (ierr == 0) allocate (b, source=kt_nt, stat=ierr)
        if (ierr == 0) allocate (alphar(p), alphai(p), beta(p), stat=ierr)
        if (ierr /= 0) then
            call stat%fail(STATUS_SOLVER, 'critical lambda: cannot allocate the p x p pencil '// &
                           '(p = '//to_string(p)//' contact nodes): out of memory')
            return
        end if
        ! Eigenvalues only: QZ with its vectors cost twice as much, and only the two
        ! thresholds' vectors are wanted (threshold_vectors).
        call dggev('N', 'N', p, a, p, b, p, alphar, alphai, beta, vl, 1, vr, 1, query, -1, info)
        allocate (work(max(1, int(query(1)))))
        call dggev('N', 'N', p, a, p, b, p, alphar, alphai, beta, vl, 1, vr, 1, work, &
                   size(work), info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, 'critical lambda: '//lapack_info_message('dggev', info))
            return
        end if

        norm_nn = maxval(sum(abs(kt_nn), dim=2))
        norm_nt = maxval(sum(abs(kt_nt), dim=2))
        allocate (thr%vectors(p, 2), thr%left_vectors(p, 2), finite(p))
        thr%vectors = 0.0_wp
        thr%left_vectors = 0.0_wp
        finite = .false.
        do j = 1, p
            ! LAPACK returns an exactly zero alphai for a real eigenvalue.
            if (abs(alphai(j)) > 0.0_wp) then
                thr%n_complex = thr%n_complex + 1
                cycle
            end if
            ! Infinite when a backward perturbation of size p eps ||Kt_nt|| could make beta zero.
            if (abs(beta(j))*norm_nn <= real(p, wp)*epsilon(1.0_wp)*abs(alphar(j))*norm_nt) then
                thr%n_infinite = thr%n_infinite + 1
                cycle
            end if
            finite(j) = .true.
        end do
        ! each side's value nearest zero (lambda = 0 would need Kt_nn singular, which SPD
        ! excludes), unless its chordal error bound reaches infinity: then it is a piece of
        ! a defective infinite eigenvalue (pencil_value_finite), counted so, and the next
        ! value of that side is taken
        do side = SIDE_PLUS, SIDE_MINUS
            do
                best = 0
                do j = 1, p
                    if (.not. finite(j)) cycle
                    lambda = alphar(j)/beta(j)
                    if ((lambda > 0.0_wp) .neqv. (side == SIDE_PLUS)) cycle
                    if (best == 0) then
                        best = j
                    else if (abs(lambda) < abs(alphar(best)/beta(best))) then
                        best = j
                    end if
                end do
                if (best == 0) exit
                lambda = alphar(best)/beta(best)
                call threshold_vectors(kt_nn, kt_nt, lambda, thr%vectors(:, side), &
                                       thr%left_vectors(:, side), stat)
                if (.not. stat%ok()) call null_vectors_svd(kt_nn, kt_nt, lambda, &
                    thr%vectors(:, side), thr%left_vectors(:, side), stat)
                if (.not. stat%ok()) return
                if (pencil_value_finite(kt_nn, kt_nt, lambda, thr%vectors(:, side), &
                                        thr%left_vectors(:, side))) exit
                finite(best) = .false.
                thr%n_infinite = thr%n_infinite + 1
                thr%vectors(:, side) = 0.0_wp
                thr%left_vectors(:, side) = 0.0_wp
            end do
            if (best == 0) cycle
            thr%found(side) = .true.
            thr%lambda(side) = lambda
            associate (x => thr%vectors(:, side))
                thr%residual(side) = maxval(abs(matmul(kt_nn, x) - &
                                                thr%lambda(side)*matmul(kt_nt, x)))/ &
                    ((norm_nn + abs(thr%lambda(side))*norm_nt)*maxval(abs(x)))
            end associate
        end do
        thr%n_real = count(finite)
        thr%real_lambdas = pack(alphar, finite)/pack(beta, finite)
        thr%real_lambdas = thr%real_lambdas(sort_index(thr%real_lambdas))
    end subroutine pencil_thresholds

    !> The pencil with the contact forces restricted to a coarser space (hp_contact:
    !> half_degree_forces): forces x = C y, C the columns `keep` of the contact mass `mass`
    !> (the forces of the kept functions' tractions), each scaled to unit length (a diagonal
    !> scaling, which leaves the eigenvalues alone and keeps QZ's perturbations relative to
    !> every column: the columns of cells 1e-8 long are 1e-8 small), and u_n = 0 imposed
    !> against the same space: (C' Kt_nn C) y = lambda (C' Kt_nt C) y. With every function
    !> kept, C is invertible and the real eigenvalues are the full pencil's.
    pure subroutine restricted_pencil(kt_nn, kt_nt, mass, keep, rn, rt, c)
        real(wp), intent(in) :: kt_nn(:, :), kt_nt(:, :), mass(:, :)   !! (p, p)
        logical, intent(in) :: keep(:)                                  !! (p)
        real(wp), allocatable, intent(out) :: rn(:, :), rt(:, :)        !! (q, q)
        real(wp), allocatable, intent(out) :: c(:, :)                   !! (p, q)
        integer :: j
        allocate (c(size(mass, 1), count(keep)))
        c(:, :) = mass(:, pack([(j, j=1, size(keep))], keep))
        do j = 1, size(c, 2)
            c(:, j) = c(:, j)/norm2(c(:, j))
        end do
        allocate (rn(size(c, 2), size(c, 2)), rt(size(c, 2), size(c, 2)))
        rn(:, :) = matmul(transpose(c), matmul(kt_nn, c))
        rt(:, :) = matmul(transpose(c), matmul(kt_nt, c))
    end subroutine restricted_pencil

    !> The thresholds of the pencil restricted to the forces `keep` (restricted_pencil), with
    !> their right and left vectors lifted to the contact functions of `full` (x = C y, each
    !> scaled to a largest entry of 1), and `restricted`, the reduced problem of the same
    !> restriction for the positive mu: forces C y tested against the same columns give
    !> (lambda Rt - Rn) y = theta Mr y with Mr = C' M^-1 C (the kept block of M, scaled), and
    !> with Mr = L L' the blocks L^-1 Rn L^-T, L^-1 Rt L^-T and the identity as the mass: its
    !> theta, and so the positive set and its boundary, are those of the restricted pencil
    !> (with every function kept they are the full problem's). `lift` = C L^-T maps a vector of
    !> `restricted` to the contact functions. The values themselves come from QZ on (Rn, Rt),
    !> not on the transformed blocks, whose scaling follows L's.
    subroutine restricted_thresholds(full, keep, thr, restricted, lift, stat)
        type(reduced_blocks_t), intent(in) :: full
        logical, intent(in) :: keep(:)
        type(thresholds_t), intent(out) :: thr
        type(reduced_blocks_t), intent(out) :: restricted
        real(wp), allocatable, intent(out) :: lift(:, :)   !! (p, q)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: mass(:, :), rn(:, :), rt(:, :), c(:, :), mr(:, :), x(:, :), &
                                 w(:, :), scale(:)
        integer, allocatable :: kept(:)
        integer :: p, q, i, k, info, side

        p = size(full%kt_nn, 1)
        allocate (mass(p, p), source=0.0_wp)
        do i = 1, p
            do k = full%mass%row_start(i), full%mass%row_start(i + 1) - 1
                mass(i, full%mass%col(k)) = full%mass%val(k)
            end do
        end do
        call restricted_pencil(full%kt_nn, full%kt_nt, mass, keep, rn, rt, c)
        q = size(c, 2)
        call pencil_thresholds(rn, rt, thr, stat)
        if (.not. stat%ok()) return
        ! the vectors of the sides found, as forces on every contact function
        allocate (x(p, 2), w(p, 2), source=0.0_wp)
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. thr%found(side)) cycle
            x(:, side) = matmul(c, thr%vectors(:, side))
            w(:, side) = matmul(c, thr%left_vectors(:, side))
            x(:, side) = x(:, side)/x(maxloc(abs(x(:, side)), 1), side)
            w(:, side) = w(:, side)/w(maxloc(abs(w(:, side)), 1), side)
        end do
        call move_alloc(x, thr%vectors)
        call move_alloc(w, thr%left_vectors)
        kept = pack([(i, i=1, p)], keep)
        allocate (mr(q, q), scale(q))
        do k = 1, q
            scale(k) = 1.0_wp/norm2(mass(:, kept(k)))   ! restricted_pencil's column scaling
        end do
        do k = 1, q
            mr(:, k) = scale*mass(kept, kept(k))*scale(k)
        end do
        call dpotrf('L', q, mr, q, info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, 'critical lambda: the mass of the restricted '// &
                           'contact forces: '//lapack_info_message('dpotrf', info))
            return
        end if
        do k = 1, q
            mr(1:k - 1, k) = 0.0_wp
        end do
        call dtrsm('L', 'L', 'N', 'N', q, q, 1.0_wp, mr, q, rn, q)
        call dtrsm('R', 'L', 'T', 'N', q, q, 1.0_wp, mr, q, rn, q)
        call dtrsm('L', 'L', 'N', 'N', q, q, 1.0_wp, mr, q, rt, q)
        call dtrsm('R', 'L', 'T', 'N', q, q, 1.0_wp, mr, q, rt, q)
        call move_alloc(rn, restricted%kt_nn)
        call move_alloc(rt, restricted%kt_nt)
        call dtrsm('R', 'L', 'T', 'N', p, q, 1.0_wp, mr, q, c, p)
        call move_alloc(c, lift)
        allocate (restricted%mass%row_start(q + 1), restricted%mass%col(q), &
                  restricted%mass%val(q))
        restricted%mass%row_start = [(i, i=1, q + 1)]
        restricted%mass%col = [(i, i=1, q)]
        restricted%mass%val = 1.0_wp
    end subroutine restricted_thresholds

    !> The right and left null vectors x, y of C = Kt_nn - lambda Kt_nt at an eigenvalue lambda
    !> of the pencil (QZ's, so C is singular to round-off), each scaled to a largest entry of
    !> 1: the eigenvectors of C' and C for the eigenvalue nearest 0 by the inverse iteration
    !> of dual_eigen (to a residual of 8 eps |C|_F), as accurate as QZ's own vectors (the
    !> residual is reported: thresholds_t%residual).
    subroutine threshold_vectors(kt_nn, kt_nt, lambda, x, y, stat)
        real(wp), intent(in) :: kt_nn(:, :), kt_nt(:, :), lambda
        real(wp), intent(out) :: x(:), y(:)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: c(:, :), v(:)
        real(wp) :: theta
        allocate (c(size(kt_nn, 1), size(kt_nn, 2)))   ! then filled: no reallocation
        c(:, :) = kt_nn - lambda*kt_nt
        call reduced_left_eigenvector(c, 0.0_wp, v, theta, stat)   ! C' y = 0
        if (.not. stat%ok()) return
        y = v/v(maxloc(abs(v), dim=1))
        c(:, :) = transpose(c)
        call reduced_left_eigenvector(c, 0.0_wp, v, theta, stat)   ! C x = 0
        if (.not. stat%ok()) return
        x = v/v(maxloc(abs(v), dim=1))
    end subroutine threshold_vectors

    !> Whether the real pencil value `lambda`, with right and left null vectors x, y of
    !> Kt_nn - lambda Kt_nt, is told apart from infinity: its chordal distance to infinity
    !> exceeds its chordal error bound p eps ||(A, B)||_F |x| |y| / |(y'Ax, y'Bx)| (the
    !> first-order bound of a simple eigenvalue of the pencil A - lambda B, here with A =
    !> Kt_nn / ||Kt_nn||_F, B = Kt_nt / ||Kt_nt||_F, so that the bound does not depend on
    !> their scales; p eps: QZ's backward error, as the infinite test of pencil_thresholds).
    !> A simple finite value has y'Bx away from zero. A defective infinite eigenvalue (a
    !> Jordan block at infinity: B singular, y'Bx = y'Ax = 0) splits under round-off into
    !> values of order eps^(-1/k) that pass the test of beta, one of them real: measured on
    !> an h-adapted random body (144 contact nodes), lambda = -4.79e6 with Kt_nt singular to
    !> 3.6e-16 of its norm, y'Ax = 6.6e-10, bound 6.9e-5 over a distance of 5.3e-7, while
    !> its true thresholds had bounds near 1e-9 at distances over 0.04.
    logical function pencil_value_finite(kt_nn, kt_nt, lambda, x, y) result(finite)
        real(wp), intent(in) :: kt_nn(:, :), kt_nt(:, :), lambda, x(:), y(:)
        real(wp) :: norm_a, norm_b, ax, bx, scaled, bound
        norm_a = norm2(kt_nn)
        norm_b = norm2(kt_nt)
        ax = dot_product(y, matmul(kt_nn, x))/norm_a
        bx = dot_product(y, matmul(kt_nt, x))/norm_b
        scaled = lambda*norm_b/norm_a   ! the value of the scaled pencil A - scaled B
        bound = real(size(x), wp)*epsilon(1.0_wp)*sqrt(2.0_wp)*norm2(x)*norm2(y)
        ! finite when bound < 1 / sqrt(1 + scaled^2) |(ax, bx)| (no division by zero)
        finite = bound*sqrt(1.0_wp + scaled**2) < hypot(ax, bx)
    end function pencil_value_finite

    !> The null vectors x, y (largest entry 1) of C = Kt_nn - lambda Kt_nt from its singular
    !> vectors of the smallest singular value, where the inverse iteration of
    !> threshold_vectors does not converge: it finds an eigenvector of C for the eigenvalue
    !> nearest 0, and at a value next to a defective eigenvalue the eigenvalues of C nearest
    !> 0 are a complex pair and a real one of one size, where it wanders.
    subroutine null_vectors_svd(kt_nn, kt_nt, lambda, x, y, stat)
        real(wp), intent(in) :: kt_nn(:, :), kt_nt(:, :), lambda
        real(wp), intent(out) :: x(:), y(:)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: c(:, :), s(:), u(:, :), vt(:, :), work(:)
        real(wp) :: query(1)
        integer :: p, info
        p = size(kt_nn, 1)
        allocate (c(p, p), s(p), u(p, p), vt(p, p))
        c(:, :) = kt_nn - lambda*kt_nt
        call dgesvd('S', 'S', p, p, c, p, s, u, p, vt, p, query, -1, info)
        allocate (work(max(1, int(query(1)))))
        call dgesvd('S', 'S', p, p, c, p, s, u, p, vt, p, work, size(work), info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, 'critical lambda: the null vectors at lambda = '// &
                           short_real_text(lambda)//': '//lapack_info_message('dgesvd', info))
            return
        end if
        x = vt(p, :)/vt(p, maxloc(abs(vt(p, :)), dim=1))
        y = u(:, p)/u(maxloc(abs(u(:, p)), dim=1), p)
    end subroutine null_vectors_svd

    !> The eigenvalues theta = 1/mu of the reduced problem (lambda Kt_nt - Kt_nn) M y = theta y,
    !> divided by lambda_unit(lambda) (see reduced_blocks_matrix): dgeev, balanced, no vectors,
    !> O(p^3) with a small constant and no sparse work.
    subroutine reduced_eigenvalues(blocks, lambda, wr, wi, stat)
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: lambda
        real(wp), allocatable, intent(out) :: wr(:), wi(:)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: a(:, :), work(:)
        real(wp) :: vl(1, 1), vr(1, 1), query(1)
        integer :: p, info

        p = size(blocks%kt_nn, 1)
        allocate (a(p, p))   ! then filled: see dense_eigen on reallocation on assignment
        a(:, :) = blocks%matrix(lambda)
        allocate (wr(p), wi(p))
        call dgeev('N', 'N', p, a, p, wr, wi, vl, 1, vr, 1, query, -1, info)
        allocate (work(max(1, int(query(1)))))
        call dgeev('N', 'N', p, a, p, wr, wi, vl, 1, vr, 1, work, size(work), info)
        if (info /= 0) call stat%fail(STATUS_SOLVER, 'reduced problem at lambda: '// &
                                      lapack_info_message('dgeev', info))
    end subroutine reduced_eigenvalues

    !> How many of the eigenvalues (wr, wi) of reduced_eigenvalues are positive real: LAPACK
    !> returns an exactly zero wi for a real one, and theta below tiny would overflow 1/theta
    !> (mu infinite, not an eigenvalue).
    pure integer function count_positive(wr, wi)
        real(wp), intent(in) :: wr(:), wi(:)
        count_positive = count(abs(wi) <= 0.0_wp .and. wr > tiny(1.0_wp))
    end function count_positive

    !> The lowest positive real mu of K phi = mu B_lambda phi from the reduced problem
    !> (reduced_eigenvalues). `found` is false when no eigenvalue is positive real;
    !> `n_positive` counts them.
    subroutine lowest_positive_mu(blocks, lambda, mu, found, n_positive, stat)
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: lambda
        real(wp), intent(out) :: mu
        logical, intent(out) :: found
        integer, intent(out) :: n_positive
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: wr(:), wi(:)

        mu = 0.0_wp
        found = .false.
        n_positive = 0
        call reduced_eigenvalues(blocks, lambda, wr, wi, stat)
        if (.not. stat%ok()) return
        n_positive = count_positive(wr, wi)
        if (n_positive > 0) then
            found = .true.
            ! blocks%matrix is A / lambda_unit: mu = 1 / (lambda_unit theta)
            mu = (1.0_wp/maxval(wr, mask=abs(wi) <= 0.0_wp .and. wr > tiny(1.0_wp)))/ &
                 lambda_unit(lambda)
        end if
    end subroutine lowest_positive_mu

    !> Solve the reduced problem just outside (lambda* (1 + CONFIRM_OFFSET), away from zero)
    !> and just inside (lambda* (1 - CONFIRM_OFFSET)) each threshold found.
    subroutine confirm_thresholds(blocks, thr, stat)
        type(reduced_blocks_t), intent(in) :: blocks
        type(thresholds_t), intent(inout) :: thr
        type(status_t), intent(out) :: stat
        integer :: side
        real(wp) :: offset

        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. thr%found(side)) cycle
            offset = sign(CONFIRM_OFFSET*abs(thr%lambda(side)), thr%lambda(side))
            thr%lambda_outside(side) = thr%lambda(side) + offset
            thr%lambda_inside(side) = thr%lambda(side) - offset
            call lowest_positive_mu(blocks, thr%lambda_outside(side), &
                                    thr%mu_outside(side), thr%has_mu_outside(side), &
                                    thr%n_outside(side), stat)
            if (.not. stat%ok()) return
            call lowest_positive_mu(blocks, thr%lambda_inside(side), &
                                    thr%mu_inside(side), thr%has_mu_inside(side), &
                                    thr%n_inside(side), stat)
            if (.not. stat%ok()) return
        end do
    end subroutine confirm_thresholds
end module critical_lambda
