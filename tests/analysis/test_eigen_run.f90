! SPDX-License-Identifier: MIT
!> analysis = 'eigen' with &adapt (eigen_run: adapt_eigen_run_t, on h levels and on hp
!> levels) run in process as the program runs it, on the reference scene from 2 x 2 P1
!> squares at lambda = 5: a run that meets its tolerance quotes a bar that holds the
!> continuum value (tests/data/truths.csv) and writes one adapt.csv row per level and the
!> final mesh (hp: and degrees.csv, a row per cell); one stopped by max_levels ends with the
!> verdict STATUS_NOT_MET and still writes its set.
program test_eigen_run
    use kinds, only: wp
    use status, only: STATUS_NOT_MET
    use testing, only: test_suite_t
    use strings, only: to_string
    use run_config, only: config_t
    use analysis_base, only: analysis_t
    use filesystem, only: remove_tree
    use fixtures, only: adaptive_scene, run_checked, json_real, json_value, listed_files, &
                        check_limit_not_met, &
                        data_rows, REF_MU
    implicit none

    character(len=*), parameter :: OUT = 'test_eigen_run.out'
    type(test_suite_t) :: t

    t%name = 'test_eigen_run'
    call remove_tree(OUT)
    call met_tolerance_holds_the_truth(t)
    call max_levels_is_not_met(t)
    call hp_meets_its_tolerance(t)
    ! hp levels: 1e-8 within max_levels = 2: not met, 2 rows of adapt.csv
    call check_limit_not_met(t, 'eigen', 'hp', 2, OUT//'/hp_not_met', 2)
    call remove_tree(OUT)
    call t%report()

contains

    !> Tolerance 1e-2 (24 levels, about 0.2 s): converged, the continuum mu within the
    !> relative bar quoted (the bar is meant to be at least the true error), the bar at most
    !> the tolerance, adapt.csv with adapt_levels + 1 rows (the start and each refinement),
    !> mesh.msh listed.
    subroutine met_tolerance_holds_the_truth(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary, report
        real(wp) :: mu, bar
        logical :: ran
        call adaptive_scene('eigen', 'h', 1.0e-2_wp, 0, OUT//'/met', config)
        call run_checked(t, 'met', config, analysis, summary, ran, report=report)
        if (.not. ran) return
        mu = json_real(summary, 'lowest_positive_mu')
        bar = json_real(summary, 'lowest_positive_error_bar')
        call t%check('met: adapt_converged true', json_value(summary, 'adapt_converged') == 'true')
        call t%check('met: bar at most the tolerance', bar > 0.0_wp .and. bar <= 1.0e-2_wp)
        call t%check('met: |mu - truth| <= bar mu', abs(mu - REF_MU) <= bar*mu)
        call t%check('met: adapt.csv has adapt_levels + 1 rows', data_rows(OUT// &
                     '/met/adapt.csv') == nint(json_real(summary, 'adapt_levels')) + 1)
        call t%check('met: mesh.msh and adapt.csv listed', &
                     any(listed_files(summary) == 'mesh.msh') .and. &
                     any(listed_files(summary) == 'adapt.csv'))
        call t%check('met: the report counts the refinements from the 12 dofs of 2 x 2 P1', &
                     index(report, to_string(nint(json_real(summary, 'adapt_levels')))// &
                           ' refinements from 12 dofs') > 0)
    end subroutine met_tolerance_holds_the_truth

    !> Tolerance 1e-6 with max_levels = 2: the verdict STATUS_NOT_MET, the set written
    !> (adapt.csv with 3 rows, summary.json saying not converged after 2 levels).
    subroutine max_levels_is_not_met(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary
        logical :: ran
        call adaptive_scene('eigen', 'h', 1.0e-6_wp, 2, OUT//'/not_met', config)
        call run_checked(t, 'not met', config, analysis, summary, ran, verdict=STATUS_NOT_MET)
        if (.not. ran) return
        call t%check('not met: summary says 2 levels, not converged', &
                     json_value(summary, 'adapt_converged') == 'false' .and. &
                     nint(json_real(summary, 'adapt_levels')) == 2)
        call t%check('not met: adapt.csv has 3 rows', data_rows(OUT//'/not_met/adapt.csv') == 3)
    end subroutine max_levels_is_not_met

    !> Tolerance 1e-3 (3 levels): converged, the truth within the bar; level k has degrees
    !> up to k + 1, so the last one's hp_degree_max is adapt_levels + 1; the files complete.
    subroutine hp_meets_its_tolerance(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary, report
        real(wp) :: mu
        integer :: levels
        logical :: ran
        call adaptive_scene('eigen', 'hp', 1.0e-3_wp, 0, OUT//'/hp', config)
        call run_checked(t, 'hp', config, analysis, summary, ran, report=report)
        if (.not. ran) return
        mu = json_real(summary, 'lowest_positive_mu')
        levels = nint(json_real(summary, 'adapt_levels'))
        call t%check('hp: converged', json_value(summary, 'adapt_converged') == 'true')
        call t%check('hp: |mu - truth| <= bar mu', abs(mu - REF_MU) <= &
                     json_real(summary, 'lowest_positive_error_bar')*mu)
        call t%check('hp: degrees 1 to adapt_levels + 1', &
                     nint(json_real(summary, 'hp_degree_min')) == 1 .and. &
                     nint(json_real(summary, 'hp_degree_max')) == levels + 1)
        call t%check('hp: adapt.csv has a row per level', &
                     data_rows(OUT//'/hp/adapt.csv') == levels)
        call t%check('hp: degrees.csv has a row per cell', &
                     data_rows(OUT//'/hp/degrees.csv') == nint(json_real(summary, 'n_cells')))
        call t%check('hp: mode_001.vtu, mesh.msh, degrees.csv listed', &
                     any(listed_files(summary) == 'mode_001.vtu') .and. &
                     any(listed_files(summary) == 'mesh.msh') .and. &
                     any(listed_files(summary) == 'degrees.csv'))
        call t%check('hp: the report counts the levels from the 8-cell mesh', &
                     index(report, 'hp, '//json_value(summary, 'adapt_levels')// &
                           ' levels from the 8-cell input mesh') > 0)
    end subroutine hp_meets_its_tolerance
end program test_eigen_run
