! SPDX-License-Identifier: MIT
!> analysis = 'solve': the discrete frictional normal-compliance problem (model.md section 3,
!> m_n = m_t = 1) for the data of &solve, by the semismooth Newton method, with the state of
!> every contact node. With data = 'branch' the data are those of model.md section 9 and the
!> solution is located on the line U + delta phi (its delta and its distance from the line).
module solve_analysis
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_SOLVER
    use strings, only: short_real_text, to_string
    use ieee_arithmetic, only: ieee_is_finite
    use timer, only: wall_time, timings_t
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use loads, only: edge_loads, body_force_loads
    use dof_map, only: node_dofs
    use normal_compliance, only: compliance_t, build_compliance, STATE_SEPARATED, &
                                 STATE_SLIP_MINUS
    use semismooth_newton, only: newton_options_t, newton_report_t, newton_solve, &
                                 newton_history_text
    use branch_analysis, only: critical_data_t, critical_branch_data, branch_compliance
    implicit none
    private
    public :: solve_result_t, run_solve, solve_status, random_vector, branch_coordinates

    integer(i8), parameter :: PM_MODULUS = 2147483647_i8   !! Park-Miller minimal standard
    integer(i8), parameter :: PM_MULTIPLIER = 48271_i8

    type, public :: solve_result_t
        type(compliance_t) :: cp
        type(newton_report_t) :: report
        real(wp), allocatable :: x(:)            !! (n_free) last iterate
        integer, allocatable :: states(:)        !! (p) state of each contact node of cp
        integer :: n_state(STATE_SEPARATED:STATE_SLIP_MINUS) = 0   !! free nodes per state
        logical :: has_critical = .false.        !! the eigenpair was computed
        logical :: on_branch_data = .false.      !! data = 'branch': U is a solution
        type(critical_data_t) :: critical
        real(wp) :: branch_delta = 0.0_wp        !! least-squares delta of x - U along phi
        real(wp) :: branch_distance = 0.0_wp     !! ||x - U - delta phi||_inf / ||U||_inf
        real(wp) :: time_newton = 0.0_wp
    end type solve_result_t

contains

    !> Set up the data, the starting guess, and run Newton. A Newton failure is recorded in
    !> res%report (solve_status turns it into an error after the outputs are written).
    subroutine run_solve(inputs, prob, res, timings, stat)
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(solve_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(newton_options_t) :: options
        real(wp), allocatable :: load(:), prescribed(:)
        logical, allocatable :: loaded(:)
        real(wp) :: start
        integer :: node, a
        logical :: finite

        associate (c => inputs%solve)
            res%on_branch_data = c%data == 'branch'
            if (res%on_branch_data .or. c%start == 'branch' .or. c%start == 'mode') then
                call critical_branch_data(inputs, prob, timings, res%critical, stat)
                if (.not. stat%ok()) return
                res%has_critical = .true.
            end if
            start = wall_time()
            if (res%on_branch_data) then
                call branch_compliance(prob, res%critical, c%critical_factor, res%cp, stat)
            else
                allocate (load(size(prob%mesh%coords)), source=0.0_wp)
                allocate (loaded(size(prob%mesh%part_names)), source=.false.)
                loaded(prob%neumann_parts) = .true.
                call edge_loads(prob%mesh, loaded, [c%t1, c%t2], &
                                reshape([0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], [2, 2]), load, stat)
                if (.not. stat%ok()) return
                call body_force_loads(prob%mesh, [c%f1, c%f2], load)
                allocate (prescribed(size(load)))
                do node = 1, prob%mesh%n_nodes()
                    prescribed(node_dofs(node, prob%mesh%dim())) = [c%u_d1, c%u_d2]
                end do
                call build_compliance(prob%k_all, prob%all_contact, prob%dofs, c%c_n, c%c_t, &
                                      load, prescribed, res%cp, stat)
            end if
            if (.not. stat%ok()) return

            select case (c%start)
            case ('branch')
                res%x = res%critical%u_base(res%cp%free_to_all) + c%start_delta*res%critical%phi
            case ('mode')
                res%x = c%start_scale*res%critical%phi
            case ('random')
                res%x = c%start_scale*random_vector(res%cp%n_free(), c%seed)
            case default
                allocate (res%x(res%cp%n_free()), source=0.0_wp)
            end select
            if (abs(c%start_noise) > 0.0_wp) then
                ! a different stream from the 'random' start's for the same seed
                res%x = res%x + c%start_noise*random_vector(res%cp%n_free(), c%seed + 7919)
            end if
            options%tol = c%tol
            options%max_iterations = c%max_iterations
        end associate

        call newton_solve(res%cp, res%x, options, res%report, stat)
        if (.not. stat%ok()) return
        res%time_newton = wall_time() - start
        ! A NaN or infinity is no answer, converged or not: refuse before anything is written
        ! (a failed 'solve' commits newton.csv).
        finite = all(ieee_is_finite(res%x))
        if (finite) finite = all(ieee_is_finite(res%report%residual))
        if (.not. finite) then
            call stat%fail(STATUS_SOLVER, inputs%scene%name//': &solve: the Newton iteration '// &
                'produced a non-finite value (NaN or infinity) after '// &
                to_string(res%report%iterations)//' iterations: the data overflow the '// &
                'arithmetic (young, the loads and c_n, c_t in the input''s units)')
            return
        end if

        block
            real(wp), allocatable :: h(:)
            allocate (h(size(res%x)), res%states(res%cp%contact%p()))
            call res%cp%residual(res%x, h, res%states)
        end block
        do a = 1, res%cp%contact%p()
            if (res%cp%contact_free(1, a) == 0) cycle
            res%n_state(res%states(a)) = res%n_state(res%states(a)) + 1
        end do
        if (res%on_branch_data) then
            call branch_coordinates(res%x, res%critical%u_base(res%cp%free_to_all), &
                                    res%critical%phi, res%branch_delta, res%branch_distance)
        end if
    end subroutine run_solve

    !> x = base + delta phi + rest with delta the least-squares coefficient, and
    !> distance = ||rest||_inf / ||base||_inf: how far x is from the line of the branch.
    pure subroutine branch_coordinates(x, base, phi, delta, distance)
        real(wp), intent(in) :: x(:), base(:), phi(:)
        real(wp), intent(out) :: delta, distance
        delta = dot_product(x - base, phi)/dot_product(phi, phi)
        distance = maxval(abs(x - base - delta*phi))/maxval(abs(base))
    end subroutine branch_coordinates

    !> STATUS_SOLVER with the residual history when Newton did not converge.
    subroutine solve_status(inputs, res, stat)
        type(run_inputs_t), intent(in) :: inputs
        type(solve_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        if (res%report%converged) return
        call stat%fail(STATUS_SOLVER, inputs%scene%name//': &solve: Newton did not converge ('// &
            res%report%reason//'); relative residual history: '// &
            newton_history_text(res%report)//' (tol = '//short_real_text(inputs%solve%tol)// &
            '; see newton.csv)')
    end subroutine solve_status

    !> n numbers uniform in [-1, 1) from the Park-Miller generator seeded with `seed`:
    !> reproducible on every compiler, and no hidden global state.
    pure function random_vector(n, seed) result(v)
        integer, intent(in) :: n, seed
        real(wp) :: v(n)
        integer(i8) :: state
        integer :: i
        state = modulo(int(seed, i8), PM_MODULUS - 1_i8) + 1_i8
        do i = 1, n
            state = modulo(PM_MULTIPLIER*state, PM_MODULUS)
            v(i) = 2.0_wp*real(state - 1_i8, wp)/real(PM_MODULUS - 1_i8, wp) - 1.0_wp
        end do
    end function random_vector
end module solve_analysis
