! SPDX-License-Identifier: MIT
!> model.md section 9 on the discrete problem: U and U + delta phi solve the FULL frictional law to
!> round-off for |delta| <= delta_max, and clearly do not beyond the sign change; the
!> geometry and eigenvalue preconditions fail with clear messages.
program test_branch_analysis
    use kinds, only: wp
    use run_inputs, only: run_inputs_t, translate_input
    use fixtures, only: problem_of
    use status, only: status_t, STATUS_BAD_INPUT
    use testing, only: test_suite_t
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use branch_analysis, only: branch_result_t, run_branch, branch_deltas, &
                               critical_data_t, critical_branch_data
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_branch_analysis'
    call delta_lists(t)
    call members_solve_to_round_off(t)
    call geometry_and_eigenvalue_preconditions(t)
    call t%report()

contains

    subroutine delta_lists(t)
        type(test_suite_t), intent(inout) :: t
        call t%check('5 deltas in [-0.1, 0.1]', all(abs(branch_deltas(0.1_wp, 5) - &
            [-0.1_wp, -0.05_wp, 0.0_wp, 0.05_wp, 0.1_wp]) <= 1.0e-17_wp))
        call t%check('one delta is 0', all(abs(branch_deltas(0.1_wp, 1)) <= 0.0_wp))
    end subroutine delta_lists

    !> The residual is a sum of terms bounded by ||K|| ||x|| (the contact terms are smaller),
    !> so its round-off is about (row length) eps ||K|| ||x||: relative to the load norm the
    !> bound is 100 eps ||K|| ||x|| / ||b||, itself well below 1e-10 on these meshes. Beyond
    !> delta_max a node loses u_n > 0 or its slip sign, which costs a residual of the order of
    !> the contact forces: 1e-6 of the load is "clearly not a solution".
    subroutine members_solve_to_round_off(t)
        type(test_suite_t), intent(inout) :: t
        character(len=2), parameter :: ELEMENTS(5) = ['p1', 'p1', 'q1', 'p2', 'q2']
        character(len=5), parameter :: DIAGONALS(5) = ['right', 'left ', 'right', 'left ', 'right']
        real(wp), parameter :: LAMBDAS(5) = [5.0_wp, -6.0_wp, 5.0_wp, 8.0_wp, -5.0_wp]
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        type(problem_t) :: prob
        type(branch_result_t) :: res
        type(timings_t) :: timings
        type(status_t) :: stat
        real(wp), allocatable :: x_base(:)
        real(wp) :: bound, beyond
        character(len=40) :: what
        integer :: c

        do c = 1, size(ELEMENTS)
            config%input_file = 'test.nml'
            config%mesh%nx = 6
            config%mesh%ny = 5
            config%mesh%element = ELEMENTS(c)
            config%mesh%diagonal = DIAGONALS(c)
            config%analysis%kind = 'branch'
            config%analysis%lambda = LAMBDAS(c)
            config%branch%alpha = 0.02_wp*c
            config%branch%beta = 0.05_wp
            config%branch%n_delta = 9
            write (what, '(a, a, 1x, a, a, f5.1)') ELEMENTS(c), '/', trim(DIAGONALS(c)), &
                ', lambda', LAMBDAS(c)
            call problem_of(config, prob, stat, with_all_dofs=.true.)
            call translate_input(config, inputs)
            if (stat%ok()) call run_branch(inputs, prob, res, timings, stat)
            call t%check(trim(what)//': runs', stat%ok())
            if (.not. stat%ok()) then
                call t%check(stat%message, .false.)
                cycle
            end if
            x_base = res%critical%u_base(res%cp%free_to_all)
            bound = 100.0_wp*epsilon(1.0_wp)*res%cp%k_all%norm_inf()* &
                    (maxval(abs(res%critical%u_base)) + res%delta_max)/res%cp%load_norm
            call t%check(trim(what)//': round-off bound below 1e-10', bound < 1.0e-10_wp)
            call t%check(trim(what)//': delta_max > 0', res%delta_max > 0.0_wp)
            call t%check(trim(what)//': residual of U is round-off', res%residual_base <= bound)
            call t%check(trim(what)//': every member U + delta phi is round-off', &
                         res%max_residual <= bound)
            call t%check(trim(what)//': the end member at delta_max too', &
                res%cp%relative_residual(x_base + res%beyond_sign*res%delta_max* &
                                         res%critical%phi) <= bound)
            beyond = res%cp%relative_residual(x_base + 1.5_wp*res%beyond_sign*res%delta_max* &
                                              res%critical%phi)
            call t%check(trim(what)//': 1.5 delta_max past the sign change is no solution', &
                         beyond > 1.0e-6_wp)
        end do
    end subroutine members_solve_to_round_off

    subroutine geometry_and_eigenvalue_preconditions(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        type(problem_t) :: prob
        type(critical_data_t) :: crit
        type(timings_t) :: timings
        type(status_t) :: stat

        config%input_file = 'test.nml'
        config%mesh%nx = 3
        config%mesh%ny = 3
        config%mesh%dirichlet = 'bottom'
        config%mesh%contact = 'top'
        config%analysis%kind = 'branch'
        call problem_of(config, prob, stat, with_all_dofs=.true.)
        call translate_input(config, inputs)
        call critical_branch_data(inputs, prob, timings, crit, stat)
        call t%check('contact on top: bad input', stat%code == STATUS_BAD_INPUT)
        if (.not. stat%ok()) call t%check('contact on top: message names the normal', &
                                          index(stat%message, 'normal (0, -1)') > 0)

        config%mesh%dirichlet = 'top'
        config%mesh%contact = 'bottom'
        config%analysis%lambda = 0.5_wp   ! below the threshold: no positive eigenvalue
        call problem_of(config, prob, stat, with_all_dofs=.true.)
        call translate_input(config, inputs)
        call critical_branch_data(inputs, prob, timings, crit, stat)
        call t%check('lambda = 0.5: bad input', stat%code == STATUS_BAD_INPUT)
        if (.not. stat%ok()) call t%check('lambda = 0.5: message says no positive eigenvalue', &
                                          index(stat%message, 'no positive real eigenvalue') > 0)
    end subroutine geometry_and_eigenvalue_preconditions
end program test_branch_analysis
