! SPDX-License-Identifier: MIT
!> The semismooth Newton solver against mathematics: quadratic convergence on regular
!> problems, the single-element family of model.md section 8 (every solution found lies on it,
!> and different guesses find different members), the branch of model.md section 9 seen by the
!> solver at the critical point and a unique solution away from it, and the failure report.
program test_semismooth_newton
    use kinds, only: wp
    use run_inputs, only: run_inputs_t, translate_input
    use fixtures, only: problem_of
    use status, only: status_t
    use testing, only: test_suite_t
    use fixtures, only: single_triangle
    use timer, only: timings_t
    use mesh, only: mesh_t
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use csr_matrix, only: csr_matrix_t
    use elasticity, only: lame_coefficients
    use loads, only: edge_loads
    use run_config, only: config_t
    use problem, only: problem_t, build_problem, assemble_all_dofs
    use contact_boundary, only: contact_t
    use normal_compliance, only: compliance_t, build_compliance
    use semismooth_newton, only: newton_options_t, newton_report_t, newton_solve
    use branch_analysis, only: critical_data_t, critical_branch_data, branch_compliance
    use solve_analysis, only: solve_result_t, run_solve, random_vector, branch_coordinates
    implicit none

    real(wp), parameter :: YOUNG = 1.0_wp, POISSON = 0.3_wp
    type(test_suite_t) :: t
    t%name = 'test_semismooth_newton'
    call quadratic_convergence(t)
    call single_element_family(t)
    call branch_seen_by_the_solver(t)
    call failure_is_reported(t)
    call t%report()

contains

    !> Regular problems (c_n well below the critical 0.74): once the contact states settle,
    !> the Newton step is exact on the piecewise-linear H but for the shift nu = e_k, so
    !> e_{k+1} <= C e_k^2 with C about ||J^-1 D|| (~ the condition of D^-1 K, 1e2 on 6 x 6):
    !> C = 1e3 is asserted on every step from e_k < 1e-3 that stays above round-off (1e-13).
    subroutine quadratic_convergence(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: NAMES(2) = [character(len=24) :: &
                                       'all slipping', 'stick and slip']
        real(wp), parameter :: DATA(5, 2) = reshape([ &
            1.0_wp, 0.5_wp, 0.01_wp, 0.02_wp, -0.02_wp, &    ! c_n, c_t, t1, u_d1, u_d2
            0.3_wp, 0.3_wp, 0.0_wp, 0.05_wp, -0.05_wp], [5, 2])
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        type(problem_t) :: prob
        type(solve_result_t) :: res
        type(timings_t) :: timings
        type(status_t) :: stat
        integer :: c, k, n_local
        logical :: quadratic

        do c = 1, size(NAMES)
            config%input_file = 'test.nml'
            config%mesh%nx = 6
            config%mesh%ny = 6
            config%analysis%kind = 'solve'
            config%solve%c_n = DATA(1, c)
            config%solve%c_t = DATA(2, c)
            config%solve%t1 = DATA(3, c)
            config%solve%u_d1 = DATA(4, c)
            config%solve%u_d2 = DATA(5, c)
            config%solve%tol = 1.0e-14_wp
            call problem_of(config, prob, stat, with_all_dofs=.true.)
            call translate_input(config, inputs)
            if (stat%ok()) call run_solve(inputs, prob, res, timings, stat)
            call t%check(trim(NAMES(c))//': converges', stat%ok() .and. res%report%converged)
            if (.not. res%report%converged) cycle
            associate (e => res%report%residual)
                n_local = 0
                quadratic = .true.
                do k = 1, size(e) - 1
                    if (e(k) >= 1.0e-3_wp .or. e(k + 1) <= 1.0e-13_wp) cycle
                    n_local = n_local + 1
                    if (e(k + 1) > 1.0e3_wp*e(k)**2) quadratic = .false.
                end do
            end associate
            call t%check(trim(NAMES(c))//': steps in the local regime exist', n_local >= 1)
            call t%check(trim(NAMES(c))//': e_{k+1} <= 1e3 e_k^2 there', quadratic)
            if (c == 2) call t%check('stick and slip: both states present', &
                res%n_state(1) > 0 .and. res%n_state(3) + res%n_state(2) > 0)
        end do
    end subroutine quadratic_convergence

    !> model.md section 8: one P1 triangle A = (0,0), B = (l,0), C = (0,l), B and C fixed, traction
    !> (F1, F2) on [A, C]. With c_n = mu, c_t = mu |lambda| (lambda = -10: slip sign +1) and
    !> F2 = (L+G)/(L+3G) F1, F1 < 0, the solutions form the segment U_t in [0, -l F1/(L+3G)],
    !> U_n = (-3 l F1 - 3 (L+3G) U_t) / (3 (L+G) + 2 c_t l): the open family of slipping
    !> solutions plus its ends, the stick solution (U_t = 0) and the grazing one (U_n = 0).
    !> Newton stops at 1e-12 of the load on a 2 x 2 system of condition ~10: 1e-10 relative.
    subroutine single_element_family(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: L_SIZE = 2.0_wp, LAMBDA = -10.0_wp, F1 = -0.3_wp
        integer, parameter :: N_STARTS = 12
        type(compliance_t) :: cp
        type(newton_options_t) :: options
        type(newton_report_t) :: report
        type(status_t) :: stat
        real(wp) :: lame_l, shear_g, mu, c_t, f2, x(2), u_n, u_t, upper, expected, found(N_STARTS)
        real(wp) :: away(N_STARTS), family_n(2)
        integer :: s, n_distinct
        logical :: all_converged, on_family

        call lame_coefficients(YOUNG, POISSON, lame_l, shear_g)
        mu = -6.0_wp*shear_g*(lame_l + 2.0_wp*shear_g)/ &
             ((lame_l*(LAMBDA + 1.0_wp) + shear_g*(LAMBDA + 3.0_wp))*L_SIZE)
        c_t = mu*abs(LAMBDA)
        f2 = (lame_l + shear_g)/(lame_l + 3.0_wp*shear_g)*F1
        upper = -L_SIZE*F1/(lame_l + 3.0_wp*shear_g)
        family_n = [-3.0_wp*L_SIZE*F1, -3.0_wp*(lame_l + 3.0_wp*shear_g)]/ &
                   (3.0_wp*(lame_l + shear_g) + 2.0_wp*c_t*L_SIZE)
        options%tol = 1.0e-12_wp

        call single_element_problem(L_SIZE, F1, f2, mu, c_t, cp, stat)
        call t%check('single element problem set up', stat%ok() .and. cp%n_free() == 2)
        all_converged = .true.
        on_family = .true.
        do s = 1, N_STARTS
            x = start_guess(s, upper, family_n)
            call newton_solve(cp, x, options, report, stat)
            all_converged = all_converged .and. stat%ok() .and. report%converged
            ! free dofs (x, y) of A; n = (0, -1), t = (-1, 0)
            u_n = -x(2)
            u_t = -x(1)
            expected = family_n(1) + family_n(2)*u_t
            if (u_t < -1.0e-10_wp*upper .or. u_t > upper*(1.0_wp + 1.0e-10_wp)) on_family = .false.
            if (abs(u_n - expected) > 1.0e-10_wp*upper) on_family = .false.
            found(s) = u_t
        end do
        call t%check('single element at c_n = mu: Newton converges from every guess', &
                     all_converged)
        call t%check('single element: every solution found satisfies the closed form', on_family)
        n_distinct = 0
        do s = 1, N_STARTS
            if (all(abs(found(1:s - 1) - found(s)) > 1.0e-6_wp*upper)) n_distinct = n_distinct + 1
        end do
        call t%check('single element: guesses find at least 6 different members', &
                     n_distinct >= 6)
        write (*, '(a, *(f8.4))') 'INFO  single element U_t / upper found:', found/upper

        ! Away from the critical c_n the same guesses agree (the 2 x 2 system is regular).
        call single_element_problem(L_SIZE, F1, f2, 0.6_wp*mu, 0.6_wp*c_t, cp, stat)
        do s = 1, N_STARTS
            x = start_guess(s, upper, family_n)
            call newton_solve(cp, x, options, report, stat)
            away(s) = -x(1)
            if (.not. report%converged) away(s) = huge(1.0_wp)
        end do
        call t%check('single element at c_n = 0.6 mu: one solution from every guess', &
                     maxval(away) - minval(away) <= 1.0e-10_wp*upper)

    end subroutine single_element_family

    !> Zero; then near the family (u_t = 0.1 ... 0.9 of its length, u_n off it by 5 %), where
    !> the problem is linear and singular; then random guesses of the family's size.
    function start_guess(s, upper, family_n) result(guess)
        integer, intent(in) :: s
        real(wp), intent(in) :: upper
        real(wp), intent(in) :: family_n(2)   !! U_n = family_n(1) + family_n(2) U_t
        real(wp) :: guess(2), u_t
        if (s == 1) then
            guess = 0.0_wp
        else if (s <= 7) then
            u_t = (0.1_wp + 0.16_wp*(s - 2))*upper
            guess = -[u_t, family_n(1) + family_n(2)*u_t + 0.05_wp*upper]
        else
            guess = upper*random_vector(2, s)
        end if
    end function start_guess

    !> The triangle of model.md section 8 with side l, traction (f1, f2) on [A, C].
    subroutine single_element_problem(l, f1, f2, c_n, c_t, cp, stat)
        real(wp), intent(in) :: l, f1, f2, c_n, c_t
        type(compliance_t), intent(out) :: cp
        type(status_t), intent(out) :: stat
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(csr_matrix_t) :: k, k_all
        type(dof_map_t) :: all_dofs
        type(contact_t) :: all_contact
        real(wp) :: load(6)
        real(wp), parameter :: NO_STRESS(2, 2) = 0.0_wp, CLAMPED(6) = 0.0_wp
        call single_triangle(l, m)
        call build_dof_map(m, [2], dofs, stat)
        if (stat%ok()) call assemble_stiffness(m, dofs, YOUNG, POISSON, k, stat)
        load = 0.0_wp
        if (stat%ok()) call edge_loads(m, [.false., .false., .true.], [f1, f2], NO_STRESS, &
                                       load, stat)
        if (stat%ok()) call assemble_all_dofs(m, YOUNG, POISSON, 1, all_dofs, k_all, &
                                              all_contact, stat)
        if (stat%ok()) call build_compliance(k_all, all_contact, dofs, c_n, c_t, load, CLAMPED, &
                                             cp, stat)
    end subroutine single_element_problem

    !> model.md section 9 data at the critical c_n: starting guesses U + delta_0 phi + noise that
    !> stay in the slipping region converge to solutions on the line U + delta phi (distance
    !> from it at the level of the tolerance times the condition, 1e-8 asserted) with
    !> different deltas. At 0.8 times the critical parameters the solution is unique: the same
    !> guesses agree to 1e-8.
    subroutine branch_seen_by_the_solver(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: DELTA0(4) = [0.0_wp, 0.04_wp, -0.04_wp, 0.06_wp]
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        type(problem_t) :: prob
        type(critical_data_t) :: crit
        type(compliance_t) :: cp
        type(timings_t) :: timings
        type(newton_options_t) :: options
        type(newton_report_t) :: report
        type(status_t) :: stat
        real(wp), allocatable :: x(:), base(:), first(:)
        real(wp) :: delta(size(DELTA0)), distance, spread
        logical :: converged, on_line, distinct
        integer :: s, f

        config%input_file = 'test.nml'
        config%mesh%nx = 8
        config%mesh%ny = 8
        config%analysis%kind = 'solve'
        config%branch%alpha = 0.1_wp
        config%branch%beta = 0.1_wp
        options%tol = 1.0e-11_wp
        call problem_of(config, prob, stat, with_all_dofs=.true.)
        call translate_input(config, inputs)
        if (stat%ok()) call critical_branch_data(inputs, prob, timings, crit, stat)
        call t%check('branch data set up', stat%ok())
        if (.not. stat%ok()) return
        do f = 1, 2
            call branch_compliance(prob, crit, merge(1.0_wp, 0.8_wp, f == 1), cp, stat)
            base = crit%u_base(cp%free_to_all)
            converged = .true.
            on_line = .true.
            spread = 0.0_wp
            do s = 1, size(DELTA0)
                x = base + DELTA0(s)*crit%phi + 0.01_wp*random_vector(size(base), s)
                call newton_solve(cp, x, options, report, stat)
                converged = converged .and. stat%ok() .and. report%converged
                call branch_coordinates(x, base, crit%phi, delta(s), distance)
                on_line = on_line .and. distance <= 1.0e-8_wp
                if (s == 1) first = x
                spread = max(spread, maxval(abs(x - first))/maxval(abs(first)))
            end do
            if (f == 1) then
                call t%check('critical: Newton converges from every guess', converged)
                call t%check('critical: every solution is on the line U + delta phi', on_line)
                distinct = .true.
                do s = 2, size(DELTA0)
                    if (any(abs(delta(1:s - 1) - delta(s)) < 1.0e-3_wp)) distinct = .false.
                end do
                call t%check('critical: different guesses, different members', distinct)
                write (*, '(a, *(f9.5))') 'INFO  critical: deltas found', delta
            else
                call t%check('0.8 x critical: Newton converges from every guess', converged)
                call t%check('0.8 x critical: the same solution from every guess', &
                             spread <= 1.0e-8_wp)
            end if
        end do
    end subroutine branch_seen_by_the_solver

    !> One iteration cannot solve a contact problem from zero: not converged, the reason says
    !> so and the history has e_0 and e_1.
    subroutine failure_is_reported(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        type(problem_t) :: prob
        type(solve_result_t) :: res
        type(timings_t) :: timings
        type(status_t) :: stat
        config%input_file = 'test.nml'
        config%mesh%nx = 4
        config%mesh%ny = 4
        config%analysis%kind = 'solve'
        config%solve%u_d2 = -0.05_wp
        config%solve%max_iterations = 1
        call problem_of(config, prob, stat, with_all_dofs=.true.)
        call translate_input(config, inputs)
            if (stat%ok()) call run_solve(inputs, prob, res, timings, stat)
        call t%check('max_iterations = 1: runs', stat%ok())
        call t%check('max_iterations = 1: not converged', .not. res%report%converged)
        call t%check('max_iterations = 1: reason names the limit', &
                     index(res%report%reason, 'iteration limit') > 0)
        call t%check('max_iterations = 1: history e_0, e_1', size(res%report%residual) == 2)
    end subroutine failure_is_reported
end program test_semismooth_newton
