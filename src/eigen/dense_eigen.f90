! SPDX-License-Identifier: MIT
!> The dense solver: all p nonzero eigenvalues of K phi = mu B phi through the reduced p x p
!> problem (lambda Kt_nt - Kt_nn) M y = (1/mu) y of model.md sections 4-7, with LAPACK dgeevx for
!> eigenvalues, eigenvectors and condition numbers, then the full eigenvectors
!> phi = mu K^-1 B phi and their backward errors on the sparse pencil. Kt_nn and Kt_nt come
!> from the trailing block of the factor of K (contact_reduction, re-exported here as
!> contact_flexibility), so nothing here is O(n p) in memory.
module dense_eigen
    use kinds, only: wp
    use timer, only: wall_time
    use strings, only: to_string
    use status, only: status_t, STATUS_SOLVER
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_boundary, only: contact_t
    use contact_reduction, only: contact_flexibility, lift_eigenvectors, &
                                 scaled_reduced_matrix, lambda_unit, mu_of_theta, lift_share_t
    use spectrum, only: spectrum_t, order_eigenvalues, KIND_POSITIVE, KIND_COMPLEX
    use lapack_interfaces, only: dgeevx, lapack_info_message, lapack_eigenvector
    use roundoff, only: left_from_reduced, lowest_roundoff
    implicit none
    private
    public :: contact_flexibility, dense_spectrum

contains

    !> All nonzero eigenvalues of K phi = mu B phi (B for `lambda`), in output order, each with
    !> its backward error on (K, B); the full eigenvectors of the first `n_keep` are kept.
    !> `chol` is the factor of K from factor_stiffness (contact dofs last). A caller that
    !> already has Kt_nn and Kt_nt (from contact_flexibility) passes them to skip forming them.
    !> `lowest_only`: only the lowest positive mu is lifted, with its backward error and
    !> round-off bound; the others keep their values, their backward errors unknown (-1), as
    !> arpack_finish does for the same caller (an hp sweep's points). `share`: the lifts'
    !> data on `chol` made once for many lambdas (lift_share_t).
    subroutine dense_spectrum(k, b, chol, contact, lambda, n_keep, spec, stat, reduction_seconds, &
                              kt_nn_given, kt_nt_given, lowest_only, share)
        type(csr_matrix_t), intent(in) :: k, b
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda
        integer, intent(in) :: n_keep
        type(spectrum_t), intent(out) :: spec
        type(status_t), intent(out) :: stat
        real(wp), intent(out), optional :: reduction_seconds   !! time to form the p x p matrix
        real(wp), intent(in), optional :: kt_nn_given(:, :), kt_nt_given(:, :)   !! (p, p) both
        logical, intent(in), optional :: lowest_only
        type(lift_share_t), intent(in), optional :: share
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), a(:, :), wr(:), wi(:), vl(:, :), &
                                 vr(:, :), scale(:), rconde(:), rcondv(:), work(:), condition(:)
        integer, allocatable :: iwork(:), order(:), kinds(:), keep(:)
        complex(wp), allocatable :: theta(:), mu(:), y(:, :)
        real(wp), allocatable :: left_lowest(:), left_full(:), residual(:)
        real(wp) :: abnrm, query(1), start, lambda_scale, roundoff_start
        integer :: p, ilo, ihi, info, j, i, n_ev, ierr, lift
        type(status_t) :: left_stat

        p = contact%p()
        start = wall_time()
        ! A / lambda_unit (contact_reduction): eigenvalues theta / lambda_unit
        lambda_scale = lambda_unit(lambda)
        if (present(kt_nn_given) .and. present(kt_nt_given)) then
            kt_nt = kt_nt_given   ! kept for the lambda sensitivity below
            allocate (a(p, p))
            a(:, :) = scaled_reduced_matrix(kt_nn_given, kt_nt, contact%mass, lambda)
        else
            call contact_flexibility(chol, contact, kt_nn, kt_nt, stat)
            if (.not. stat%ok()) return
            allocate (a(p, p))
            a(:, :) = scaled_reduced_matrix(kt_nn, kt_nt, contact%mass, lambda)
            deallocate (kt_nn)
        end if
        if (present(reduction_seconds)) reduction_seconds = wall_time() - start

        allocate (wr(p), wi(p), vl(p, p), vr(p, p), scale(p), rconde(p), rcondv(p), stat=ierr)
        if (ierr /= 0) then
            call stat%fail(STATUS_SOLVER, 'dense eigensolver: cannot allocate the '// &
                           'eigenvectors of the p x p problem (p = '//to_string(p)// &
                           '): out of memory')
            return
        end if
        allocate (iwork(max(1, 2*p - 2)))
        call dgeevx('B', 'V', 'V', 'E', p, a, p, wr, wi, vl, p, vr, p, ilo, ihi, scale, abnrm, &
                    rconde, rcondv, query, -1, iwork, info)
        allocate (work(max(1, int(query(1)))))
        call dgeevx('B', 'V', 'V', 'E', p, a, p, wr, wi, vl, p, vr, p, ilo, ihi, scale, abnrm, &
                    rconde, rcondv, work, size(work), iwork, info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, lapack_info_message('dgeevx', info))
            return
        end if
        deallocate (a, work)

        ! theta = 1/mu (here divided by lambda_scale). theta = 0 (mu infinite) happens only
        ! exactly at a critical lambda.
        allocate (theta(p))   ! first: see hp_stiffness, condense_interior
        theta = cmplx(wr, wi, wp)
        keep = pack([(j, j=1, p)], abs(theta) > 0.0_wp)
        n_ev = size(keep)
        allocate (mu(p), source=(0.0_wp, 0.0_wp))
        allocate (condition(p), source=-1.0_wp)
        do j = 1, p
            if (abs(theta(j)) > 0.0_wp) then
                mu(j) = mu_of_theta(theta(j), lambda_scale)
                if (.not. (abs(wi(j)) > 0.0_wp)) mu(j) = cmplx(mu_of_theta(wr(j), lambda_scale), &
                                                               0.0_wp, wp)
                ! relative condition of theta (hence of mu = 1/theta) on the balanced matrix
                condition(j) = abnrm/(rconde(j)*abs(theta(j)))
            end if
        end do

        allocate (order(n_ev), kinds(n_ev))
        call order_eigenvalues(mu(keep), .not. (abs(wi(keep)) > 0.0_wp), order, kinds)
        ! Allocated, then filled through (:): gfortran's reallocation on assignment reads the
        ! bounds that intent(out) leaves undefined, and UBSan saw their arithmetic overflow
        ! in 16 of 40 sanitizer runs.
        allocate (spec%mu(n_ev), spec%kind(n_ev), spec%condition(n_ev))
        spec%mu(:) = mu(keep(order))
        spec%kind(:) = kinds
        spec%dense_decision = .true.
        spec%condition(:) = condition(keep(order))
        allocate (spec%lambda_sensitivity(n_ev), source=-1.0_wp)
        if (n_ev > 0) then
            ! the lowest positive mu (first in output order) and the real mu of largest
            ! modulus: the one that comes in from infinity when lambda nears a threshold
            if (kinds(1) == KIND_POSITIVE) spec%lambda_sensitivity(1) = &
                lambda_sensitivity(keep(order(1)))
            i = 0
            do j = 1, n_ev
                if (kinds(j) == KIND_COMPLEX) cycle
                if (i == 0) then
                    i = j
                else if (abs(mu(keep(order(j)))) > abs(mu(keep(order(i))))) then
                    i = j
                end if
            end do
            if (i > 0) spec%lambda_sensitivity(i) = lambda_sensitivity(keep(order(i)))
            ! the left eigenvector of A for the round-off bound (real: mu is)
            if (kinds(1) == KIND_POSITIVE) left_lowest = vl(:, keep(order(1)))
        end if
        deallocate (vl, kt_nt)

        ! The reduced eigenvectors in output order (see lapack_eigenvector); lifting
        ! them to phi = K^-1 (lambda T' - N') M y (= phi / mu of model.md sections 4-7: same mode)
        ! in column blocks keeps memory at O(n x block + p^2).
        lift = n_ev
        if (present(lowest_only)) then
            if (lowest_only) lift = min(1, n_ev, count(kinds(1:min(1, n_ev)) == KIND_POSITIVE))
        end if
        allocate (y(p, lift))
        do i = 1, lift
            y(:, i) = lapack_eigenvector(vr, wi, keep(order(i)))
        end do
        deallocate (vr)
        call lift_eigenvectors(k, b, chol, contact, lambda, spec%mu(1:lift), y, n_keep, &
                               residual, spec%vectors, stat, share)
        if (.not. stat%ok()) return
        allocate (spec%residual(n_ev), source=-1.0_wp)
        spec%residual(1:lift) = residual
        ! the round-off bound of the lowest positive mu on the pencil (module roundoff), as
        ! every solver computes it; a failed solve there only leaves it unknown
        allocate (spec%roundoff(n_ev), source=-1.0_wp)
        if (.not. allocated(left_lowest) .or. size(spec%vectors, 2) < 1) return
        roundoff_start = wall_time()
        call left_from_reduced(chol, contact, k%n(), left_lowest, left_full, left_stat, share)
        if (left_stat%ok()) call lowest_roundoff(k, b, contact, lambda, real(spec%mu(1), wp), &
            real(spec%vectors(:, 1), wp), left_full, spec%roundoff(1))
        if (spec%roundoff(1) >= 0.0_wp) call move_alloc(left_full, spec%left)
        spec%roundoff_seconds = wall_time() - roundoff_start

    contains

        !> First-order perturbation of a simple real theta = 1/mu of A = (lambda Kt_nt -
        !> Kt_nn) M: d theta / d lambda = y^T Kt_nt M x / (y^T x), x, y its right and left
        !> eigenvectors. mu = 1/theta has the same relative sensitivity as theta.
        real(wp) function lambda_sensitivity(j)
            integer, intent(in) :: j
            real(wp) :: mass_x(p), y_dot_x
            call contact%mass%matvec(vr(:, j), mass_x)
            y_dot_x = dot_product(vl(:, j), vr(:, j))
            lambda_sensitivity = huge(1.0_wp)   ! a defective (double) eigenvalue
            if (abs(y_dot_x) > 0.0_wp) lambda_sensitivity = abs(lambda/lambda_scale)* &
                abs(dot_product(vl(:, j), matmul(kt_nt, mass_x)))/(abs(y_dot_x)*abs(theta(j)))
        end function lambda_sensitivity
    end subroutine dense_spectrum
end module dense_eigen
