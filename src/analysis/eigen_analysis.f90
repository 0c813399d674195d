! SPDX-License-Identifier: MIT
!> analysis = 'eigen': the boundary eigenproblem K phi = mu B phi for one lambda, solved by
!> the solver the input asks for, with the phase timings of SPEC section 7.
module eigen_analysis
    use kinds, only: wp
    use status, only: status_t
    use timer, only: wall_time, timings_t
    use run_config, only: config_t
    use problem, only: problem_t
    use mesh, only: element_name
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness
    use memory_budget, only: check_contact_memory, contact_peak_blocks
    use contact_boundary, only: assemble_b
    use spectrum, only: spectrum_t
    use dense_eigen, only: dense_spectrum
    use accuracy, only: accuracy_warnings, WARNING_LEN
    use arpack_eigen, only: arpack_spectrum, arpack_options_t
    implicit none
    private
    public :: eigen_result_t, solve_eigen, choose_solver, eigen_with_factor, solver_name
    public :: SOLVER_DENSE, SOLVER_ARPACK

    !> The eigensolver a run used (&eigen solver = 'auto' resolves to one of them).
    integer, parameter :: SOLVER_DENSE = 1    !! all p eigenpairs of the reduced problem
    integer, parameter :: SOLVER_ARPACK = 2   !! a few, by ARPACK, with the certificate

    type, public :: eigen_result_t
        real(wp) :: lambda = 0.0_wp
        integer :: solver = SOLVER_DENSE          !! the solver actually used
        type(csr_matrix_t) :: b                   !! B for this lambda
        type(spectrum_t) :: spec
        !> accuracy lost or the result not certified, and why (empty when trustworthy)
        character(len=WARNING_LEN), allocatable :: warnings(:)
    end type eigen_result_t

contains

    !> The solver &eigen solver names; 'auto' means dense while the p x p dense problem is
    !> cheap.
    pure integer function choose_solver(requested, p, dense_max_contact) result(solver)
        character(len=*), intent(in) :: requested
        integer, intent(in) :: p, dense_max_contact
        solver = SOLVER_DENSE
        select case (trim(requested))
        case ('arpack')
            solver = SOLVER_ARPACK
        case ('auto')
            if (p > dense_max_contact) solver = SOLVER_ARPACK
        end select
    end function choose_solver

    !> 'dense' or 'arpack', as summary.json and the stdout summary name the solver.
    pure function solver_name(solver) result(name)
        integer, intent(in) :: solver
        character(len=:), allocatable :: name
        name = 'dense'
        if (solver == SOLVER_ARPACK) name = 'arpack'
    end function solver_name

    !> Assemble B for `lambda`, factor K (factor_stiffness: contact dofs last, which both
    !> solvers read the contact blocks from), and compute the spectrum.
    subroutine solve_eigen(config, prob, lambda, res, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: lambda
        type(eigen_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(cholesky_t) :: chol
        real(wp) :: start

        res%lambda = lambda
        start = wall_time()
        call assemble_b(prob%contact, prob%dofs%n_free, lambda, res%b, stat)
        if (.not. stat%ok()) return
        timings%assembly = timings%assembly + (wall_time() - start)

        res%solver = choose_solver(config%eigen%solver, prob%contact%p(), &
                                   config%eigen%dense_max_contact)
        call check_contact_memory(config, prob%contact%p(), contact_peak_blocks( &
            res%solver == SOLVER_ARPACK .and. .not. abs(config%eigen%target) > 0.0_wp), stat)
        if (.not. stat%ok()) return
        call factor_stiffness(prob%k, prob%mesh, prob%dofs, prob%contact, chol, timings, stat)
        if (.not. stat%ok()) return
        call eigen_with_factor(config, prob, chol, res, timings, stat)
        call chol%free()
    end subroutine solve_eigen

    !> The spectrum at res%lambda (res%b assembled, res%solver chosen) from a factor of K made
    !> by factor_stiffness, which stays allocated for the caller (the threshold analysis reads
    !> the contact blocks off the same factor). A caller that already has Kt_nn and Kt_nt
    !> passes them to spare the dense solver forming them again.
    subroutine eigen_with_factor(config, prob, chol, res, timings, stat, kt_nn, kt_nt)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(cholesky_t), intent(in) :: chol
        type(eigen_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: kt_nn(:, :), kt_nt(:, :)   !! (p, p) both
        type(arpack_options_t) :: options
        real(wp) :: start, reduction_seconds
        character(len=:), allocatable :: certificate   !! why ARPACK's answer is not certified
        integer :: n_keep

        n_keep = max(1, config%output%modes)
        start = wall_time()
        certificate = ''
        if (res%solver == SOLVER_ARPACK) then
            options = arpack_options_t(nev=config%eigen%nev, ncv=config%eigen%ncv, &
                maxit=config%eigen%maxit, tol=config%eigen%tol, target=config%eigen%target)
            call arpack_spectrum(prob%k, res%b, chol, prob%contact, res%lambda, options, n_keep, &
                                 res%spec, certificate, stat)
            if (.not. stat%ok()) return
            timings%eigen = timings%eigen + (wall_time() - start)
        else
            reduction_seconds = 0.0_wp
            if (present(kt_nn) .and. present(kt_nt)) then
                call dense_spectrum(prob%k, res%b, chol, prob%contact, res%lambda, n_keep, &
                                    res%spec, stat, kt_nn_given=kt_nn, kt_nt_given=kt_nt)
            else
                call dense_spectrum(prob%k, res%b, chol, prob%contact, res%lambda, n_keep, &
                                    res%spec, stat, reduction_seconds)
            end if
            if (.not. stat%ok()) return
            timings%reduction = timings%reduction + reduction_seconds
            timings%eigen = timings%eigen + (wall_time() - start - reduction_seconds)
        end if
        res%warnings = accuracy_warnings(res%spec, element_name(prob%mesh%element), prob%poisson)
        if (len(certificate) > 0) res%warnings = [character(len=WARNING_LEN) :: certificate, &
                                                  res%warnings]
    end subroutine eigen_with_factor
end module eigen_analysis
