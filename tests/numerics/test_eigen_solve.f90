! SPDX-License-Identifier: MIT
!> The eigen solve of one problem (eigen_solve): the solver chosen by the options (dense up
!> to dense_max_contact contact nodes, ARPACK beyond or for the full operator, as asked
!> otherwise); the estimate asked for ('auto' up to 40000 free dofs, saying why beyond);
!> the estimate of an element without a degree above (Q1) is the difference to the halved
!> mesh, (mu_h/2 - mu_h) / mu_h, which an independent solve of the halved scene reproduces
!> to round-off; and a value that cannot be reported in the input's units is refused before
!> any is written, naming what pushes it out of range: E, or lambda (of a sweep).
program test_eigen_solve
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use testing, only: test_suite_t
    use timer, only: timings_t
    use element_types, only: ELEMENT_Q1
    use unit_scaling, only: units_t
    use scene, only: scene_t
    use problem, only: problem_t, build_problem
    use method_options, only: eigen_options_t, SOLVER_AUTO, SOLVER_DENSE, SOLVER_ARPACK, &
                              ESTIMATE_AUTO, ESTIMATE_ON, OPERATOR_FULL
    use eigen_solve, only: eigen_result_t, solve_eigen, estimate_eigen, choose_solver, &
                           estimate_wanted, check_input_range, ESTIMATE_AUTO_MAX_DOFS
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_eigen_solve'
    call solver_choice(t)
    call estimate_choice(t)
    call halved_mesh_estimate(t)
    call input_range(t)
    call t%report()

contains

    subroutine solver_choice(t)
        type(test_suite_t), intent(inout) :: t
        type(eigen_options_t) :: options
        options%solver = SOLVER_AUTO
        options%dense_max_contact = 24
        call t%check('auto: dense at 24 contact nodes, ARPACK at 25', &
                     choose_solver(options, 24) == SOLVER_DENSE .and. &
                     choose_solver(options, 25) == SOLVER_ARPACK)
        options%operator = OPERATOR_FULL
        call t%check('auto with the full operator: ARPACK at 2', &
                     choose_solver(options, 2) == SOLVER_ARPACK)
        options%solver = SOLVER_DENSE
        call t%check('dense asked: dense at 1000', choose_solver(options, 1000) == SOLVER_DENSE)
        options%solver = SOLVER_ARPACK
        call t%check('ARPACK asked: ARPACK at 3', choose_solver(options, 3) == SOLVER_ARPACK)
    end subroutine solver_choice

    subroutine estimate_choice(t)
        type(test_suite_t), intent(inout) :: t
        type(eigen_options_t) :: options
        character(len=:), allocatable :: why_not
        options%estimate = ESTIMATE_AUTO
        call t%check('auto: an estimate up to the limit', &
                     estimate_wanted(options, ESTIMATE_AUTO_MAX_DOFS, why_not) .and. &
                     len(why_not) == 0)
        call t%check('auto: none beyond, saying why', &
                     .not. estimate_wanted(options, ESTIMATE_AUTO_MAX_DOFS + 1, why_not) .and. &
                     index(why_not, 'more than the 40000') > 0)
        options%estimate = ESTIMATE_ON
        call t%check('on: an estimate at any size', estimate_wanted(options, 10**7, why_not))
    end subroutine estimate_choice

    !> Q1 on 4 x 4 at lambda = 5: the estimate (mu_h/2 - mu_h) / mu_h against the two
    !> solves made here, on the scene and on its halved scene (8 x 8): the same solves,
    !> so to a few ulps.
    subroutine halved_mesh_estimate(t)
        type(test_suite_t), intent(inout) :: t
        type(scene_t) :: scn
        type(problem_t) :: prob, fine
        type(eigen_options_t) :: options
        type(eigen_result_t) :: res, fine_res
        type(timings_t) :: timings
        type(status_t) :: stat
        real(wp) :: mu, mu_fine
        scn%name = 'in.nml'
        scn%nx = 4
        scn%ny = 4
        scn%element = ELEMENT_Q1
        options%solver = SOLVER_DENSE
        options%estimate = ESTIMATE_ON
        call build_problem(scn, prob, stat)
        if (stat%ok()) call solve_eigen(scn, prob, 5.0_wp, options, res, timings, stat)
        if (stat%ok()) call estimate_eigen(scn, prob, options, .false., res, timings)
        if (stat%ok()) call build_problem(scn%halved(), fine, stat)
        if (stat%ok()) call solve_eigen(scn%halved(), fine, 5.0_wp, options, fine_res, &
                                        timings, stat)
        call t%check('Q1 4 x 4 and 8 x 8: solved', stat%ok())
        if (.not. stat%ok()) return
        mu = real(res%spec%mu(res%spec%lowest_positive()), wp)
        mu_fine = real(fine_res%spec%mu(fine_res%spec%lowest_positive()), wp)
        call t%check('Q1: the estimate is the halved mesh''s', res%error%computed .and. &
                     res%error%halved_mesh)
        call t%check('Q1: (mu_h/2 - mu_h) / mu_h, to round-off', &
                     abs(res%error%relative - (mu_fine - mu)/mu) <= &
                     16.0_wp*epsilon(1.0_wp)*abs(mu_fine/mu))
    end subroutine halved_mesh_estimate

    !> mu of 1 in units of 2^1100 is 2^1100 in the input's: overflow, blamed on E when E
    !> moved the unit; mu of 2^-600 in units of 2^-500 underflows, and with lambda = 2^600
    !> pushing further than E (mu ~ 1 / lambda) it is blamed on lambda, named as a point of
    !> the sweep with of_sweep.
    subroutine input_range(t)
        type(test_suite_t), intent(inout) :: t
        type(scene_t) :: scn
        type(units_t) :: units
        type(status_t) :: stat
        complex(wp) :: mu(2)
        scn%name = 'in.nml'
        scn%material%young = 1.0e300_wp
        mu = [(1.0_wp, 0.0_wp), (0.5_wp, 0.0_wp)]
        units%young_exponent = 1100
        call check_input_range(scn, units, 5.0_wp, .false., mu, stat)
        call t%check('overflow: refused naming young', stat%code == STATUS_BAD_INPUT .and. &
                     index(stat%message, 'in.nml: &material: young = ') == 1)
        units%young_exponent = 0
        call check_input_range(scn, units, 5.0_wp, .false., mu, stat)
        call t%check('in range: accepted', stat%ok())
        units%young_exponent = -500
        mu = [cmplx(2.0_wp**(-600), 0.0_wp, wp), cmplx(2.0_wp**(-601), 0.0_wp, wp)]
        call check_input_range(scn, units, 2.0_wp**600, .true., mu, stat)
        call t%check('underflow with a huge lambda of a sweep: refused naming it', &
                     stat%code == STATUS_BAD_INPUT .and. &
                     index(stat%message, '&sweep: lambda = ') > 0 .and. &
                     index(stat%message, 'a point of the sweep') > 0)
    end subroutine input_range
end program test_eigen_solve
