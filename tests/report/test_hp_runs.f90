! SPDX-License-Identifier: MIT
!> The hp strategy of &adapt, run in process as the program runs it: analysis 'eigen'
!> (hp_adapt_run) and 'threshold' (hp_threshold_run) on the reference scene from 2 x 2 P1
!> squares at lambda = 5. A met tolerance quotes bars that hold the continuum values of
!> tests/data/truths.csv; adapt.csv has a row per level, degrees.csv a row per cell of the
!> last mesh; a loop stopped by max_levels ends with STATUS_NOT_MET and writes its set.
program test_hp_runs
    use kinds, only: wp
    use status, only: STATUS_NOT_MET
    use testing, only: test_suite_t
    use run_config, only: config_t
    use analysis_base, only: analysis_t
    use filesystem, only: remove_tree
    use fixtures, only: adaptive_scene, run_checked, json_real, json_value, listed_files, &
                        data_rows, thresholds_within_bars, REF_MU, REF_LAMBDA_PLUS, &
                        REF_LAMBDA_MINUS
    implicit none

    character(len=*), parameter :: OUT = 'test_hp_runs.out'
    type(test_suite_t) :: t

    t%name = 'test_hp_runs'
    call remove_tree(OUT)
    call hp_eigen_meets_its_tolerance(t)
    call hp_threshold_meets_its_tolerance(t)
    call hp_limits_are_not_met(t)
    call remove_tree(OUT)
    call t%report()

contains

    !> Tolerance 1e-3 (3 levels): converged, the truth within the bar; level k has degrees
    !> up to k + 1, so the last one's hp_degree_max is adapt_levels + 1; the files complete.
    subroutine hp_eigen_meets_its_tolerance(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary, report
        real(wp) :: mu
        integer :: levels
        logical :: ran
        call adaptive_scene('eigen', 'hp', 1.0e-3_wp, 0, OUT//'/eigen', config)
        call run_checked(t, 'eigen', config, analysis, summary, ran, report=report)
        if (.not. ran) return
        mu = json_real(summary, 'lowest_positive_mu')
        levels = nint(json_real(summary, 'adapt_levels'))
        call t%check('eigen: converged', json_value(summary, 'adapt_converged') == 'true')
        call t%check('eigen: |mu - truth| <= bar mu', abs(mu - REF_MU) <= &
                     json_real(summary, 'lowest_positive_error_bar')*mu)
        call t%check('eigen: degrees 1 to adapt_levels + 1', &
                     nint(json_real(summary, 'hp_degree_min')) == 1 .and. &
                     nint(json_real(summary, 'hp_degree_max')) == levels + 1)
        call t%check('eigen: adapt.csv has a row per level', &
                     data_rows(OUT//'/eigen/adapt.csv') == levels)
        call t%check('eigen: degrees.csv has a row per cell', &
                     data_rows(OUT//'/eigen/degrees.csv') == nint(json_real(summary, 'n_cells')))
        call t%check('eigen: mode_001.vtu, mesh.msh, degrees.csv listed', &
                     any(listed_files(summary) == 'mode_001.vtu') .and. &
                     any(listed_files(summary) == 'mesh.msh') .and. &
                     any(listed_files(summary) == 'degrees.csv'))
        call t%check('eigen: the report counts the levels from the 8-cell mesh', &
                     index(report, 'hp, '//json_value(summary, 'adapt_levels')// &
                           ' levels from the 8-cell input mesh') > 0)
    end subroutine hp_eigen_meets_its_tolerance

    !> Tolerance 1e-3: converged, both continuum thresholds within their bars, a row per
    !> level in adapt.csv and per cell in degrees.csv.
    subroutine hp_threshold_meets_its_tolerance(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary
        logical :: ran
        call adaptive_scene('threshold', 'hp', 1.0e-3_wp, 0, OUT//'/threshold', config)
        call run_checked(t, 'threshold', config, analysis, summary, ran)
        if (.not. ran) return
        call t%check('threshold: converged', json_value(summary, 'adapt_converged') == 'true')
        call t%check('threshold: lambda+ and lambda- within their bars of the truth', &
                     thresholds_within_bars(summary, REF_LAMBDA_PLUS, REF_LAMBDA_MINUS))
        call t%check('threshold: adapt.csv has a row per level', &
                     data_rows(OUT//'/threshold/adapt.csv') == &
                     nint(json_real(summary, 'adapt_levels')))
        call t%check('threshold: degrees.csv has a row per cell', &
                     data_rows(OUT//'/threshold/degrees.csv') == &
                     nint(json_real(summary, 'n_cells')))
    end subroutine hp_threshold_meets_its_tolerance

    !> Tolerance 1e-8 within max_levels = 2, for either goal: STATUS_NOT_MET, 2 rows of
    !> adapt.csv, the set complete.
    subroutine hp_limits_are_not_met(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: KINDS(2) = [character(len=9) :: 'eigen', 'threshold']
        type(config_t) :: config
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary, folder
        integer :: i
        logical :: ran
        do i = 1, size(KINDS)
            folder = OUT//'/not_met_'//trim(KINDS(i))
            call adaptive_scene(trim(KINDS(i)), 'hp', 1.0e-8_wp, 2, folder, config)
            call run_checked(t, trim(KINDS(i))//' not met', config, analysis, summary, ran, &
                             verdict=STATUS_NOT_MET)
            if (ran) call t%check(trim(KINDS(i))//' not met: adapt.csv has 2 rows', &
                                  data_rows(folder//'/adapt.csv') == 2)
        end do
    end subroutine hp_limits_are_not_met
end program test_hp_runs
