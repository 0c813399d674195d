! SPDX-License-Identifier: MIT
!> Semismooth (generalized) Newton method for H(x) = 0 of normal_compliance, with a
!> backtracking line search on the merit function ||H||_2^2.
!>
!> Each step solves (J + nu_k D) dx = -H(x_k) with J an element of the generalized Jacobian,
!> D = diag(K_free) and nu_k = min(NU_MAX, e_k), e_k = ||H(x_k)||_inf / ||f - K u_D||_inf.
!> The shift vanishes like the residual, so the convergence stays quadratic on a regular
!> problem (e_{k+1} <= C e_k^2), but at a critical c_n, where J is singular along the branch
!> direction phi (K phi = mu B phi), the step is still defined and has no component along
!> phi: each starting guess keeps its own coordinate along the branch and converges to its
!> own member of the continuum of solutions instead of one picked by round-off.
module semismooth_newton
    use kinds, only: wp
    use status, only: status_t, STATUS_SINGULAR
    use csr_matrix, only: csr_matrix_t
    use sparse_lu, only: lu_t
    use normal_compliance, only: compliance_t
    use strings, only: to_string
    implicit none
    private
    public :: newton_options_t, newton_report_t, newton_solve, newton_history_text

    real(wp), parameter :: NU_MAX = 1.0e-3_wp        !! largest relative shift
    real(wp), parameter :: ARMIJO = 1.0e-4_wp        !! sufficient decrease of ||H||^2
    integer, parameter :: MAX_HALVINGS = 40          !! smallest step 2^-40
    integer, parameter :: SHIFT_RETRIES = 3          !! singular J + nu D: nu x 100 and retry

    type, public :: newton_options_t
        real(wp) :: tol = 1.0e-10_wp     !! stop when e_k <= tol
        integer :: max_iterations = 50
    end type newton_options_t

    type, public :: newton_report_t
        logical :: converged = .false.
        integer :: iterations = 0
        real(wp), allocatable :: residual(:)   !! (0:iterations) e_k
        real(wp), allocatable :: step(:)       !! (0:iterations) line-search step to x_k (0: x_0)
        real(wp), allocatable :: shift(:)      !! (0:iterations) nu used to reach x_k
        character(len=:), allocatable :: reason   !! why it stopped
    end type newton_report_t

contains

    !> Solve H(x) = 0 from the starting guess x (overwritten by the last iterate). A failed
    !> iteration (no convergence, no decrease) is not an error: `report` says so; `stat`
    !> fails only when the sparse LU fails.
    subroutine newton_solve(cp, x, options, report, stat)
        type(compliance_t), intent(in) :: cp
        real(wp), intent(inout) :: x(:)
        type(newton_options_t), intent(in) :: options
        type(newton_report_t), intent(out) :: report
        type(status_t), intent(out) :: stat
        type(csr_matrix_t) :: jac
        type(lu_t) :: lu
        real(wp), allocatable :: h(:), h_trial(:), dx(:), x_trial(:), diagonal(:)
        real(wp) :: scale, e, t, nu
        integer :: k, halving, retry, i
        logical :: accepted

        scale = cp%load_norm
        if (.not. scale > 0.0_wp) scale = 1.0_wp
        allocate (h(size(x)), h_trial(size(x)), dx(size(x)), x_trial(size(x)))
        diagonal = stiffness_diagonal(cp%free_stiffness())
        call cp%residual(x, h)
        e = norm_inf(h)/scale
        report%residual = [e]
        report%step = [0.0_wp]
        report%shift = [0.0_wp]
        report%reason = 'the iteration limit '//to_string(options%max_iterations)//' was reached'
        do k = 1, options%max_iterations + 1
            if (e <= options%tol) then
                report%converged = .true.
                report%reason = 'converged'
                exit
            end if
            if (k > options%max_iterations) exit

            call cp%jacobian(x, jac, stat)
            if (.not. stat%ok()) return
            nu = min(NU_MAX, e)
            do retry = 0, SHIFT_RETRIES
                do i = 1, size(diagonal)
                    associate (slot => jac%slot(i, i))
                        jac%val(slot) = jac%val(slot) + nu*diagonal(i)
                    end associate
                end do
                call lu%factor(jac, stat)
                if (stat%code /= STATUS_SINGULAR .or. retry == SHIFT_RETRIES) exit
                ! undo this shift before trying a larger one
                do i = 1, size(diagonal)
                    associate (slot => jac%slot(i, i))
                        jac%val(slot) = jac%val(slot) - nu*diagonal(i)
                    end associate
                end do
                nu = max(100.0_wp*nu, 1.0e-8_wp)
            end do
            if (.not. stat%ok()) then
                stat%message = 'Newton iteration '//to_string(k)//': '//stat%message
                return
            end if
            call lu%solve(-h, dx, stat)
            call lu%free()
            if (.not. stat%ok()) return

            t = 1.0_wp
            accepted = .false.
            do halving = 0, MAX_HALVINGS
                x_trial = x + t*dx
                call cp%residual(x_trial, h_trial)
                if (sufficient_decrease(h_trial, h, t)) then
                    accepted = .true.
                    exit
                end if
                t = 0.5_wp*t
            end do
            if (.not. accepted) then
                report%reason = 'the line search found no decrease of ||H||^2 at iteration ' &
                                //to_string(k)
                exit
            end if
            x = x_trial
            h = h_trial
            e = norm_inf(h)/scale
            report%iterations = k
            report%residual = [report%residual, e]
            report%step = [report%step, t]
            report%shift = [report%shift, nu]
        end do
    end subroutine newton_solve

    !> "e_0 e_1 ..." with 3 significant digits, for a one-line failure message.
    function newton_history_text(report) result(text)
        type(newton_report_t), intent(in) :: report
        character(len=:), allocatable :: text
        character(len=16) :: buffer
        integer :: k
        text = ''
        do k = 1, size(report%residual)
            write (buffer, '(es10.3)') report%residual(k)
            if (k > 1) text = text//' '
            text = text//trim(adjustl(buffer))
        end do
    end function newton_history_text

    !> Armijo's test ||H_trial||^2 <= (1 - 2 ARMIJO t) ||H||^2. Sums of squares while they
    !> cannot overflow (as always before, so that paths and results stay the same); beyond
    !> (u_d1 = 1e300 trapped), the same test on norm2, which scales. A NaN or infinity in
    !> h_trial fails it, so the step is halved.
    pure logical function sufficient_decrease(h_trial, h, t)
        real(wp), intent(in) :: h_trial(:), h(:), t
        !> |entries| below which n squares stay finite for n up to 1.8e8
        real(wp), parameter :: SQUARES_SAFE = 1.0e150_wp
        real(wp) :: largest
        largest = max(norm_inf(h_trial), norm_inf(h))
        if (largest < SQUARES_SAFE) then
            sufficient_decrease = sum(h_trial**2) <= (1.0_wp - 2.0_wp*ARMIJO*t)*sum(h**2)
        else
            sufficient_decrease = norm2(h_trial) <= sqrt(1.0_wp - 2.0_wp*ARMIJO*t)*norm2(h)
        end if
    end function sufficient_decrease

    pure real(wp) function norm_inf(v)
        real(wp), intent(in) :: v(:)
        norm_inf = 0.0_wp
        if (size(v) > 0) norm_inf = maxval(abs(v))
    end function norm_inf

    !> Diagonal of K (positive: K is SPD), the scale of the shift.
    pure function stiffness_diagonal(k) result(d)
        type(csr_matrix_t), intent(in) :: k
        real(wp) :: d(k%n())
        integer :: i
        do i = 1, k%n()
            d(i) = k%val(k%slot(i, i))
        end do
    end function stiffness_diagonal
end module semismooth_newton
