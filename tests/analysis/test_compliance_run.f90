! SPDX-License-Identifier: MIT
!> analysis = 'branch' and 'solve' (compliance_run: branch_run_t, solve_run_t) on the single
!> element, run in process as the program runs them. At lambda = -5 its one eigenvalue is
!> mu = 105/208 (docs/model.md section 8), so the critical compliances are c_n = mu and
!> c_t = mu |lambda| = 5 mu; the members U + delta phi of the branch (section 9) solve the
!> problem to round-off, and Newton started near the branch lands on it, the one contact
!> node slipping with s = -sgn(lambda) = +1. A Newton iteration that is stopped short still
!> writes its history and ends with a failed verdict.
program test_compliance_run
    use kinds, only: wp
    use status, only: STATUS_SOLVER
    use testing, only: test_suite_t
    use run_config, only: config_t
    use mesh, only: mesh_t
    use analysis_base, only: analysis_t
    use filesystem, only: remove_tree, file_exists
    use fixtures, only: single_element_scene, run_checked, json_real, json_value, &
                        listed_files, data_rows
    implicit none

    character(len=*), parameter :: OUT = 'test_compliance_run.out'
    real(wp), parameter :: MU = 105.0_wp/208.0_wp
    type(test_suite_t) :: t

    t%name = 'test_compliance_run'
    call remove_tree(OUT)
    call branch_members_solve(t)
    call solve_lands_on_the_branch(t)
    call solve_stopped_short_fails_after_writing(t)
    call remove_tree(OUT)
    call t%report()

contains

    !> c_n = 105/208 and c_t = 5 c_n to 1e-13; 11 members in branch.csv, each residual and
    !> the base's below 1e-12 (round-off of a 6-dof system); 3 members written as VTU.
    subroutine branch_members_solve(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(mesh_t) :: m
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary, report
        character(len=255), allocatable :: names(:)
        logical :: ran
        call single_element_scene(OUT//'/branch', config, m)
        config%analysis%kind = 'branch'
        call run_checked(t, 'branch', config, analysis, summary, ran, m, report)
        if (.not. ran) return
        call t%check_close('branch: c_n = mu = 105/208', json_real(summary, 'c_n'), MU, 1.0e-13_wp)
        call t%check_close('branch: c_t = 5 mu', json_real(summary, 'c_t'), 5.0_wp*MU, 1.0e-13_wp)
        call t%check('branch: residuals of U and of every member below 1e-12', &
                     json_real(summary, 'branch_base_residual') < 1.0e-12_wp .and. &
                     json_real(summary, 'branch_max_residual') < 1.0e-12_wp)
        call t%check('branch: branch.csv has n_delta = 11 rows', &
                     data_rows(OUT//'/branch/branch.csv') == 11)
        names = listed_files(summary)
        call t%check('branch: 3 members as branch_NNN.vtu (1, 6, 11)', &
                     any(names == 'branch_001.vtu') .and. any(names == 'branch_006.vtu') .and. &
                     any(names == 'branch_011.vtu') .and. count(index(names, 'branch_') == 1) == 3)
        call t%check('branch: the report quotes c_n', &
                     index(report, 'c_n = mu = '//json_value(summary, 'c_n')) > 0)
    end subroutine branch_members_solve

    !> The data of the branch (c_n, c_t critical), started at U + 0.05 phi with noise 0.01:
    !> converged, on the line U + delta phi to 1e-12, the contact node slipping along +t,
    !> newton.csv a row per iterate, contact_states.csv one row, solution.vtu written.
    subroutine solve_lands_on_the_branch(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(mesh_t) :: m
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary
        logical :: ran
        call solve_scene(OUT//'/solve', config, m)
        call run_checked(t, 'solve', config, analysis, summary, ran, m)
        if (.not. ran) return
        call t%check('solve: converged', json_value(summary, 'converged') == 'true')
        call t%check_close('solve: c_n = 105/208', json_real(summary, 'c_n'), MU, 1.0e-13_wp)
        call t%check('solve: on the branch to 1e-12', &
                     json_real(summary, 'branch_distance') >= 0.0_wp &
                     .and. json_real(summary, 'branch_distance') < 1.0e-12_wp)
        call t%check('solve: the contact node slips along +t', &
                     nint(json_real(summary, 'n_slip_plus')) == 1 .and. &
                     nint(json_real(summary, 'n_slip_minus')) == 0)
        call t%check('solve: newton.csv has iterations + 1 rows', &
                     data_rows(OUT//'/solve/newton.csv') == &
                     nint(json_real(summary, 'iterations')) + 1)
        call t%check('solve: contact_states.csv has the one contact node', &
                     data_rows(OUT//'/solve/contact_states.csv') == 1)
        call t%check('solve: solution.vtu listed', any(listed_files(summary) == 'solution.vtu'))
    end subroutine solve_lands_on_the_branch

    !> The same with max_iterations = 1 and tol = 1e-300 (no iterate meets it): the run
    !> writes newton.csv (2 rows) and no solution.vtu; its verdict is STATUS_SOLVER (exit 5).
    subroutine solve_stopped_short_fails_after_writing(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(mesh_t) :: m
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary
        logical :: ran
        call solve_scene(OUT//'/short', config, m)
        config%solve%max_iterations = 1
        config%solve%tol = 1.0e-300_wp
        call run_checked(t, 'short', config, analysis, summary, ran, m, &
                         verdict=STATUS_SOLVER)
        if (.not. ran) return
        call t%check('short: not converged', json_value(summary, 'converged') == 'false')
        call t%check('short: newton.csv has 2 rows', data_rows(OUT//'/short/newton.csv') == 2)
        call t%check('short: no solution.vtu', .not. file_exists(OUT//'/short/solution.vtu'))
    end subroutine solve_stopped_short_fails_after_writing

    subroutine solve_scene(directory, config, m)
        character(len=*), intent(in) :: directory
        type(config_t), intent(out) :: config
        type(mesh_t), intent(out) :: m
        call single_element_scene(directory, config, m)
        config%analysis%kind = 'solve'
        config%solve%data = 'branch'
        config%solve%start = 'branch'
        config%solve%start_delta = 0.05_wp
        config%solve%start_noise = 0.01_wp
        config%solve%tol = 1.0e-13_wp
    end subroutine solve_scene
end program test_compliance_run
