! SPDX-License-Identifier: MIT
!> analysis = 'threshold' and 'lambda_sweep' with ARPACK (dense_max_contact lowered so that
!> 'auto' picks it on small meshes) against the same analyses with the dense solver: the
!> thresholds and their confirmations, the spectrum at &analysis lambda and the whole sweep
!> curve must agree, and the sweep must really have used ARPACK where it could certify.
program test_threshold_analysis
    use kinds, only: wp
    use run_inputs, only: run_inputs_t, translate_input
    use fixtures, only: problem_of
    use status, only: status_t
    use testing, only: test_suite_t
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use timer, only: timings_t
    use threshold_analysis, only: threshold_result_t, solve_thresholds
    use critical_lambda, only: SIDE_PLUS, SIDE_MINUS
    use arpack_eigen, only: arpack_options_t, arpack_lowest_positive
    use method_options, only: SOLVER_DENSE, SOLVER_ARPACK
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_threshold_analysis'
    call arpack_sweep_agrees_with_dense(t)
    call explicit_operator_on_a_diagonal_matrix(t)
    call t%report()

contains

    !> One run of solve_thresholds (with the sweep) on an N x N mesh.
    subroutine run(n, element, diagonal, solver, res, ok)
        integer, intent(in) :: n
        character(len=*), intent(in) :: element, diagonal, solver
        type(threshold_result_t), intent(out) :: res
        logical, intent(out) :: ok
        type(config_t) :: config
        type(problem_t) :: prob
        type(run_inputs_t) :: inputs
        type(timings_t) :: timings
        type(status_t) :: stat
        config%input_file = 'test'
        config%mesh%nx = n
        config%mesh%ny = n
        config%mesh%element = element
        config%mesh%diagonal = diagonal
        config%analysis%kind = 'lambda_sweep'
        config%analysis%lambda = 5.0_wp
        config%output%modes = 2
        config%eigen%solver = solver
        config%eigen%dense_max_contact = 4   ! 'auto' is ARPACK from p = 5 on
        ! both signs, both sides of each threshold, near them (|lambda| = 2.0) and far out
        config%sweep%lambda_min = -40.0_wp
        config%sweep%lambda_max = 40.0_wp
        config%sweep%n_lambda = 41
        call problem_of(config, prob, stat)
        call translate_input(config, inputs)
        if (stat%ok()) call solve_thresholds(inputs%scene, prob, inputs%point%lambda, &
            inputs%eigen, inputs%scan, res, timings, stat, inputs%sweep, inputs%adapt)
        ok = stat%ok()
    end subroutine run

    !> Both paths share the factor, the Kt blocks and the QZ, so the thresholds and their
    !> (dense) confirmations must be identical up to rounding in the pencil (1e-12); the
    !> sweep points are eigenvalues with condition numbers below 1e4 away from the
    !> thresholds (see test_arpack_eigen), and both solvers are backward stable, so 1e-9
    !> relative bounds their difference, as for the eigen analysis; a missed or wrong
    !> eigenvalue (the next one is at least 10x away) fails by orders of magnitude.
    subroutine arpack_sweep_agrees_with_dense(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: ELEMENTS(3) = ['p1', 'p1', 'q1']
        character(len=*), parameter :: DIAGONALS(3) = [character(len=5) :: 'right', 'left', &
                                                                            'right']
        integer, parameter :: SIZES(2) = [8, 20]
        type(threshold_result_t) :: dense, arpack
        logical :: ok_dense, ok_arpack
        character(len=64) :: what
        integer :: e, s, side, i, lowest_d, lowest_a
        do s = 1, size(SIZES)
            do e = 1, size(ELEMENTS)
                write (what, '(a, i0, 1x, a, 1x, a)') 'N = ', SIZES(s), ELEMENTS(e), &
                    trim(DIAGONALS(e))
                call run(SIZES(s), ELEMENTS(e), DIAGONALS(e), 'dense', dense, ok_dense)
                call run(SIZES(s), ELEMENTS(e), DIAGONALS(e), 'auto', arpack, ok_arpack)
                call t%check(trim(what)//': both succeed', ok_dense .and. ok_arpack)
                if (.not. (ok_dense .and. ok_arpack)) cycle
                call t%check(trim(what)//': solvers dense and arpack', &
                             dense%eigen%solver == SOLVER_DENSE .and. arpack%eigen%solver == SOLVER_ARPACK)
                do side = SIDE_PLUS, SIDE_MINUS
                    call t%check(trim(what)//': same thresholds found', &
                                 dense%thresholds%found(side) .eqv. arpack%thresholds%found(side))
                    call t%check_close(trim(what)//': threshold', arpack%thresholds%lambda(side), &
                                       dense%thresholds%lambda(side), 1.0e-12_wp)
                    call t%check(trim(what)//': confirmed with ARPACK', &
                                 arpack%thresholds%confirmed(side) .or. &
                                 .not. arpack%thresholds%found(side))
                    call t%check_close(trim(what)//': mu just outside', &
                                       arpack%thresholds%mu_outside(side), &
                                       dense%thresholds%mu_outside(side), 1.0e-9_wp)
                end do
                lowest_d = dense%eigen%spec%lowest_positive()
                lowest_a = arpack%eigen%spec%lowest_positive()
                call t%check(trim(what)//': a lowest positive mu at lambda = 5 by both', &
                             lowest_d > 0 .and. lowest_a > 0)
                if (lowest_d > 0 .and. lowest_a > 0) call t%check_close(trim(what)// &
                    ': lowest positive mu at lambda = 5', real(arpack%eigen%spec%mu(lowest_a), &
                    wp), real(dense%eigen%spec%mu(lowest_d), wp), 1.0e-9_wp)
                call t%check(trim(what)//': ARPACK backward errors <= 1e-12', &
                             arpack%eigen%spec%max_residual() <= 1.0e-12_wp)
                call t%check(trim(what)//': same existence along the sweep', &
                             all(arpack%sweep%found .eqv. dense%sweep%found))
                do i = 1, size(dense%sweep%lambda)
                    if (.not. (dense%sweep%found(i) .and. arpack%sweep%found(i))) cycle
                    call t%check_close(trim(what)//': sweep mu', arpack%sweep%mu(i), &
                                       dense%sweep%mu(i), 1.0e-9_wp)
                end do
                call t%check(trim(what)//': ARPACK certified sweep points, dense decided the '// &
                             'rest', arpack%sweep%n_arpack > 0 .and. arpack%sweep%n_arpack + &
                             arpack%sweep%n_dense == size(arpack%sweep%lambda))
                call t%check(trim(what)//': the dense sweep used no ARPACK', &
                             dense%sweep%n_arpack == 0)
            end do
        end do
    end subroutine arpack_sweep_agrees_with_dense

    !> A = diag(d) has the eigenvalues d: theta = 1/mu, so the lowest positive mu is
    !> 1 / max(d > 0) exactly (ARPACK converges to eps relative on a normal matrix: 1e-12);
    !> with no positive d no certificate is possible without the whole spectrum, so the
    !> search must answer 'not certified' rather than 'none'.
    subroutine explicit_operator_on_a_diagonal_matrix(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: P = 60
        real(wp) :: a(P, P), mu
        logical :: found, certified
        integer :: i, n_operator
        type(status_t) :: stat
        a = 0.0_wp
        do i = 1, P
            ! negative values of large modulus, a few small positive ones
            a(i, i) = -real(i, wp)
            if (mod(i, 17) == 0) a(i, i) = 1.0_wp/real(i, wp)
        end do
        call arpack_lowest_positive(a, arpack_options_t(), mu, found, certified, n_operator, &
                                    stat)
        call t%check('diagonal: succeeds', stat%ok())
        ! the positive ones are 1/17, 1/34, 1/51: mu = 17, 34, 51, far beyond |mu| = 1/60..1,
        ! so the certificate needs the whole spectrum; ARPACK may or may not get there
        if (certified) then
            call t%check('diagonal: found', found)
            call t%check_close('diagonal: lowest positive mu = 17', mu, 17.0_wp, 1.0e-12_wp)
        end if
        a(17, 17) = 200.0_wp   ! the largest theta: mu = 1/200 is the nearest, certifiable
        call arpack_lowest_positive(a, arpack_options_t(), mu, found, certified, n_operator, &
                                    stat)
        call t%check('diagonal, mu = 1/200: certified and found', stat%ok() .and. certified &
                     .and. found)
        call t%check_close('diagonal, mu = 1/200', mu, 0.005_wp, 1.0e-12_wp)
        call t%check('diagonal, mu = 1/200: products counted', n_operator > 0)
        a = 0.0_wp
        do i = 1, P
            a(i, i) = -real(i, wp)
        end do
        call arpack_lowest_positive(a, arpack_options_t(), mu, found, certified, n_operator, &
                                    stat)
        call t%check('diagonal, no positive: not certified (the caller decides densely)', &
                     stat%ok() .and. .not. certified)
    end subroutine explicit_operator_on_a_diagonal_matrix
end program test_threshold_analysis
