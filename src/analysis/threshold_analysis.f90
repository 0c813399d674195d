! SPDX-License-Identifier: MIT
!> analysis = 'threshold' and 'lambda_sweep': the critical lambdas (SPEC section 3) and the
!> curve lambda -> lowest positive mu, from ONE factorization of K and ONE formation of the
!> contact blocks Kt_nn, Kt_nt. B depends on lambda only through the reduced matrix
!> (lambda Kt_nt - Kt_nn) M, so every further lambda costs one p x p eigen-solve. Both
!> analyses also solve the eigenproblem at &analysis lambda as 'eigen' does, so that their
!> summary.json carries every key of the contract.
module threshold_analysis
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use timer, only: wall_time, timings_t
    use run_config, only: config_t
    use input_config, only: sweep_lambdas
    use problem, only: problem_t
    use sparse_cholesky, only: cholesky_t
    use contact_boundary, only: assemble_b
    use contact_reduction, only: factor_stiffness, contact_flexibility
    use dense_eigen, only: dense_spectrum
    use critical_lambda, only: thresholds_t, pencil_thresholds, confirm_thresholds, &
                               lowest_positive_mu
    use eigen_analysis, only: eigen_result_t, choose_solver
    implicit none
    private
    public :: threshold_result_t, solve_thresholds

    !> The curve of a lambda sweep, one entry per lambda.
    type, public :: sweep_curve_t
        real(wp), allocatable :: lambda(:)
        real(wp), allocatable :: mu(:)           !! lowest positive mu where found(i)
        logical, allocatable :: found(:)
        integer, allocatable :: n_positive(:)    !! positive real eigenvalues at lambda(i)
    end type sweep_curve_t

    type, public :: threshold_result_t
        type(eigen_result_t) :: eigen            !! the spectrum at &analysis lambda
        type(thresholds_t) :: thresholds
        type(sweep_curve_t) :: sweep             !! allocated for 'lambda_sweep' only
        real(wp) :: time_threshold = 0.0_wp      !! pencil QZ and the confirming solves, s
        real(wp) :: time_sweep = 0.0_wp          !! all the p x p solves of the sweep, s
    end type threshold_result_t

contains

    !> Factor K, form Kt_nn and Kt_nt, and compute the spectrum at &analysis lambda, the
    !> thresholds with their confirmations, and (with `with_sweep`) the &sweep curve.
    subroutine solve_thresholds(config, prob, with_sweep, res, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        logical, intent(in) :: with_sweep
        type(threshold_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(cholesky_t) :: chol
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), mass(:, :), nn_m(:, :), nt_m(:, :)
        real(wp) :: start
        integer :: i

        ! The thresholds need the dense blocks; a sparse solver has no pencil to offer.
        res%eigen%solver = choose_solver(config%eigen%solver, prob%contact%p(), huge(1))
        if (res%eigen%solver /= 'dense') then
            call stat%fail(STATUS_BAD_INPUT, config%input_file//': &eigen: solver = '''// &
                trim(config%eigen%solver)//''': expected ''dense'' or ''auto'' for analysis ''' &
                //trim(config%analysis%kind)//''' (it needs the dense p x p blocks)')
            return
        end if
        res%eigen%lambda = config%analysis%lambda
        start = wall_time()
        call assemble_b(prob%contact, prob%dofs%n_free, res%eigen%lambda, res%eigen%b, stat)
        if (.not. stat%ok()) return
        timings%assembly = timings%assembly + (wall_time() - start)

        call factor_stiffness(prob%k, prob%mesh, prob%dofs, prob%contact, chol, timings, stat)
        if (.not. stat%ok()) return

        start = wall_time()
        call contact_flexibility(chol, prob%contact, kt_nn, kt_nt, stat)
        if (.not. stat%ok()) then
            call chol%free()
            return
        end if
        timings%reduction = timings%reduction + (wall_time() - start)

        start = wall_time()
        call dense_spectrum(prob%k, res%eigen%b, chol, prob%contact, res%eigen%lambda, &
                            max(1, config%output%modes), res%eigen%spec, stat, &
                            kt_nn_given=kt_nn, kt_nt_given=kt_nt)
        call chol%free()
        if (.not. stat%ok()) return
        timings%eigen = timings%eigen + (wall_time() - start)

        start = wall_time()
        call pencil_thresholds(kt_nn, kt_nt, res%thresholds, stat)
        if (.not. stat%ok()) return
        mass = prob%contact%mass_dense()
        nn_m = matmul(kt_nn, mass)
        nt_m = matmul(kt_nt, mass)
        deallocate (kt_nn, kt_nt, mass)
        call confirm_thresholds(nn_m, nt_m, res%thresholds, stat)
        if (.not. stat%ok()) return
        res%time_threshold = wall_time() - start
        if (.not. with_sweep) return

        start = wall_time()
        res%sweep%lambda = sweep_lambdas(config%sweep)
        associate (n => size(res%sweep%lambda))
            allocate (res%sweep%mu(n), res%sweep%found(n), res%sweep%n_positive(n))
        end associate
        do i = 1, size(res%sweep%lambda)
            call lowest_positive_mu(nn_m, nt_m, res%sweep%lambda(i), res%sweep%mu(i), &
                                    res%sweep%found(i), res%sweep%n_positive(i), stat)
            if (.not. stat%ok()) return
        end do
        res%time_sweep = wall_time() - start
    end subroutine solve_thresholds
end module threshold_analysis
