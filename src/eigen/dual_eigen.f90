! SPDX-License-Identifier: MIT
!> The left eigenvector of the reduced problem, which a goal-oriented error estimate weighs
!> the residual with: for A y = theta y with A = (lambda Kt_nt - Kt_nn) M, the left
!> eigenvector psi of the pencil (psi^T K = mu psi^T B) is psi = mu K^-1 N' w, w the left
!> eigenvector of A (A^T w = theta w). Check: psi^T B = mu w^T N K^-1 (lambda T' - N') M N
!> = mu w^T A N = mu theta w^T N = w^T N = psi^T K / mu. So one extra solve with the factor
!> of K gives psi once w is known.
module dual_eigen
    use kinds, only: wp
    use status, only: status_t, STATUS_SOLVER
    use strings, only: to_string, short_real_text
    use lapack_interfaces, only: dgetrf, dgetrs
    implicit none
    private
    public :: reduced_left_eigenvector

    !> Inverse iteration steps at most; from a shift as close as a discrete theta_h is to the
    !> enriched one, each step gains a factor |theta - theta_h| / |theta_2 - theta_h| ~ h^2.
    integer, parameter :: MAX_STEPS = 50
    !> residual / |A|_F accepted after MAX_STEPS: the estimate only needs a few digits of w
    real(wp), parameter :: ACCEPT = 1.0e-10_wp
    !> Steps on one shift before the shift moves to the current quotient theta. From a coarse
    !> theta_h far from the enriched eigenvalue, next to the partner it is about to collide
    !> with, a step gains a factor near 1 (measured: 0.7 per step on a trapezoid's first
    !> P1 level, residual 2e-10 after 50 steps); one LU more at theta converges in a few.
    integer, parameter :: STEPS_PER_SHIFT = 10

contains

    !> w with A^T w = theta w, |w| = 1, for the eigenvalue theta of A nearest `shift`, by
    !> inverse iteration on A^T - shift I (one LU, p^3 / 3 flops; then p^2 per step; the
    !> shift moves to theta every STEPS_PER_SHIFT steps), and theta = w^T A^T w. Stops at a
    !> residual |A^T w - theta w| <= 8 eps |A|_F, else after MAX_STEPS; fails
    !> (STATUS_SOLVER) when it is then above ACCEPT |A|_F.
    subroutine reduced_left_eigenvector(a, shift, w, theta, stat)
        real(wp), intent(in) :: a(:, :)        !! (p, p)
        real(wp), intent(in) :: shift
        real(wp), allocatable, intent(out) :: w(:)
        real(wp), intent(out) :: theta
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: lu(:, :), a_t_w(:)
        integer, allocatable :: pivot(:)
        real(wp) :: residual, a_norm
        integer :: p, i, step, info

        p = size(a, 1)
        a_norm = norm2(a)
        allocate (lu(p, p), pivot(p), w(p), a_t_w(p))
        call factor(shift, stat)
        if (.not. stat%ok()) return
        w = 1.0_wp/sqrt(real(p, wp))
        residual = huge(1.0_wp)
        theta = shift
        do step = 1, MAX_STEPS
            call dgetrs('N', p, 1, lu, p, pivot, w, p, info)
            w = w/norm2(w)
            a_t_w = matmul(w, a)   ! A^T w
            theta = dot_product(w, a_t_w)
            residual = norm2(a_t_w - theta*w)
            if (residual <= 8.0_wp*epsilon(1.0_wp)*a_norm) return
            if (mod(step, STEPS_PER_SHIFT) == 0 .and. step < MAX_STEPS) then
                call factor(theta, stat)
                if (.not. stat%ok()) return
            end if
        end do
        ! round-off stalls the residual above 8 eps |A| on some large p: still a left vector
        if (residual <= ACCEPT*a_norm) return
        call stat%fail(STATUS_SOLVER, 'left eigenvector: inverse iteration near theta = '// &
            short_real_text(shift)//' did not converge in '//to_string(MAX_STEPS)// &
            ' steps (residual '//short_real_text(residual/a_norm)//' relative)')

    contains

        !> lu, pivot: the LU of A^T - sigma I, sigma moved off by a few ulps where it is an
        !> eigenvalue to the last bit.
        subroutine factor(sigma, stat)
            real(wp), intent(in) :: sigma
            type(status_t), intent(out) :: stat
            real(wp) :: nudge
            nudge = 0.0_wp
            do
                lu = transpose(a)
                do i = 1, p
                    lu(i, i) = lu(i, i) - (sigma + nudge)
                end do
                call dgetrf(p, p, lu, p, pivot, info)
                if (info <= 0) exit
                nudge = nudge + 4.0_wp*spacing(max(abs(sigma), a_norm))
            end do
            if (info < 0) call stat%fail(STATUS_SOLVER, 'left eigenvector: dgetrf info = '// &
                                         to_string(info))
        end subroutine factor
    end subroutine reduced_left_eigenvector
end module dual_eigen
