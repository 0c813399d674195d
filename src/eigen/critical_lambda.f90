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
    use strings, only: to_string
    use lapack_interfaces, only: dggev, dgeev, lapack_info_message
    use contact_reduction, only: reduced_blocks_t, lambda_unit
    implicit none
    private
    public :: thresholds_t, pencil_thresholds, lowest_positive_mu, confirm_thresholds
    public :: SIDE_PLUS, SIDE_MINUS, CONFIRM_OFFSET

    integer, parameter :: SIDE_PLUS = 1    !! index of lambda+ > 0 in thresholds_t arrays
    integer, parameter :: SIDE_MINUS = 2   !! index of lambda- < 0
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
        real(wp) :: lambda_outside(2) = 0.0_wp     !! lambda* (1 + CONFIRM_OFFSET)
        real(wp) :: lambda_inside(2) = 0.0_wp      !! lambda* (1 - CONFIRM_OFFSET)
        logical :: has_mu_outside(2) = .false.     !! a positive mu exists there (expected)
        logical :: has_mu_inside(2) = .false.      !! a positive mu exists there (not expected)
        real(wp) :: mu_outside(2) = 0.0_wp         !! lowest positive mu there, if any
        real(wp) :: mu_inside(2) = 0.0_wp
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
        real(wp), allocatable :: a(:, :), b(:, :), alphar(:), alphai(:), beta(:), vr(:, :), &
                                 work(:)
        real(wp) :: vl(1, 1), query(1), norm_nn, norm_nt, lambda
        integer :: p, info, j, best(2), side, ierr

        p = size(kt_nn, 1)
        ! sourced allocation: assigning to an unallocated array draws false -Wuninitialized
        allocate (a, source=kt_nn, stat=ierr)
        if (ierr == 0) allocate (b, source=kt_nt, stat=ierr)
        if (ierr == 0) allocate (alphar(p), alphai(p), beta(p), vr(p, p), stat=ierr)
        if (ierr /= 0) then
            call stat%fail(STATUS_SOLVER, 'critical lambda: cannot allocate the p x p pencil '// &
                           '(p = '//to_string(p)//' contact nodes): out of memory')
            return
        end if
        call dggev('N', 'V', p, a, p, b, p, alphar, alphai, beta, vl, 1, vr, p, query, -1, info)
        allocate (work(max(1, int(query(1)))))
        call dggev('N', 'V', p, a, p, b, p, alphar, alphai, beta, vl, 1, vr, p, work, &
                   size(work), info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, 'critical lambda: '//lapack_info_message('dggev', info))
            return
        end if

        norm_nn = maxval(sum(abs(kt_nn), dim=2))
        norm_nt = maxval(sum(abs(kt_nt), dim=2))
        best = 0
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
            thr%n_real = thr%n_real + 1
            lambda = alphar(j)/beta(j)
            ! lambda = 0 would need Kt_nn singular, which SPD excludes.
            side = SIDE_PLUS
            if (lambda < 0.0_wp) side = SIDE_MINUS
            if (best(side) == 0) then
                best(side) = j
            else if (abs(lambda) < abs(alphar(best(side))/beta(best(side)))) then
                best(side) = j
            end if
        end do
        do side = SIDE_PLUS, SIDE_MINUS
            if (best(side) == 0) cycle
            j = best(side)
            thr%found(side) = .true.
            thr%lambda(side) = alphar(j)/beta(j)
            thr%residual(side) = maxval(abs(matmul(kt_nn, vr(:, j)) - &
                                            thr%lambda(side)*matmul(kt_nt, vr(:, j)))) / &
                ((norm_nn + abs(thr%lambda(side))*norm_nt)*maxval(abs(vr(:, j))))
        end do
    end subroutine pencil_thresholds

    !> The lowest positive real mu of K phi = mu B_lambda phi from the reduced problem
    !> (lambda Kt_nt - Kt_nn) M y = (1/mu) y, eigenvalues only (dgeev, balanced): O(p^3)
    !> with a small constant, and no sparse work. `found` is false when no eigenvalue is
    !> positive real; `n_positive` counts them.
    subroutine lowest_positive_mu(blocks, lambda, mu, found, n_positive, stat)
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: lambda
        real(wp), intent(out) :: mu
        logical, intent(out) :: found
        integer, intent(out) :: n_positive
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: a(:, :), wr(:), wi(:), work(:)
        real(wp) :: vl(1, 1), vr(1, 1), query(1), theta_max
        integer :: p, info, j

        p = size(blocks%kt_nn, 1)
        mu = 0.0_wp
        found = .false.
        n_positive = 0
        allocate (a(p, p))   ! then filled: see dense_eigen on reallocation on assignment
        a(:, :) = blocks%matrix(lambda)
        allocate (wr(p), wi(p))
        call dgeev('N', 'N', p, a, p, wr, wi, vl, 1, vr, 1, query, -1, info)
        allocate (work(max(1, int(query(1)))))
        call dgeev('N', 'N', p, a, p, wr, wi, vl, 1, vr, 1, work, size(work), info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, 'reduced problem at lambda: '// &
                           lapack_info_message('dgeev', info))
            return
        end if
        theta_max = 0.0_wp
        do j = 1, p
            ! theta below tiny would overflow 1/theta: mu is then infinite, not an eigenvalue
            if (abs(wi(j)) > 0.0_wp .or. .not. wr(j) > tiny(1.0_wp)) cycle
            n_positive = n_positive + 1
            theta_max = max(theta_max, wr(j))
        end do
        if (n_positive > 0) then
            found = .true.
            mu = (1.0_wp/theta_max)/lambda_unit(lambda)   ! blocks%matrix is A / lambda_unit
        end if
    end subroutine lowest_positive_mu

    !> Solve the reduced problem just outside (lambda* (1 + CONFIRM_OFFSET), away from zero)
    !> and just inside (lambda* (1 - CONFIRM_OFFSET)) each threshold found.
    subroutine confirm_thresholds(blocks, thr, stat)
        type(reduced_blocks_t), intent(in) :: blocks
        type(thresholds_t), intent(inout) :: thr
        type(status_t), intent(out) :: stat
        integer :: side, n_positive

        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. thr%found(side)) cycle
            thr%lambda_outside(side) = thr%lambda(side)*(1.0_wp + CONFIRM_OFFSET)
            thr%lambda_inside(side) = thr%lambda(side)*(1.0_wp - CONFIRM_OFFSET)
            call lowest_positive_mu(blocks, thr%lambda_outside(side), &
                                    thr%mu_outside(side), thr%has_mu_outside(side), &
                                    n_positive, stat)
            if (.not. stat%ok()) return
            call lowest_positive_mu(blocks, thr%lambda_inside(side), &
                                    thr%mu_inside(side), thr%has_mu_inside(side), &
                                    n_positive, stat)
            if (.not. stat%ok()) return
        end do
    end subroutine confirm_thresholds
end module critical_lambda
