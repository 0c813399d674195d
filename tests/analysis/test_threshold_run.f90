! SPDX-License-Identifier: MIT
!> analysis = 'threshold' and 'lambda_sweep' (threshold_run), and 'threshold' with &adapt
!> on h and on hp levels, run in process as the program runs them. The single element
!> (docs/model.md section 8) has one threshold, lambda- = -(L + 3G)/(L + G) = -1.8, and no
!> lambda+, and at each lambda below lambda- the one eigenvalue of its closed form; the
!> reference scene's adapted thresholds hold the continuum values of tests/data/truths.csv
!> within their bars.
program test_threshold_run
    use kinds, only: wp
    use status, only: status_t, STATUS_NOT_MET
    use testing, only: test_suite_t
    use run_config, only: config_t
    use mesh, only: mesh_t
    use analysis_base, only: analysis_t
    use csv_table, only: csv_table_t, read_csv_table
    use filesystem, only: remove_tree
    use fixtures, only: single_element_scene, single_element_mu, single_element_lambda_minus, &
                        check_limit_not_met, &
                        adaptive_scene, run_checked, json_real, json_value, listed_files, &
                        data_rows, thresholds_within_bars, REF_LAMBDA_PLUS, REF_LAMBDA_MINUS
    implicit none

    character(len=*), parameter :: OUT = 'test_threshold_run.out'
    type(test_suite_t) :: t

    t%name = 'test_threshold_run'
    call remove_tree(OUT)
    call single_element_threshold(t)
    call single_element_sweep(t)
    call adapted_thresholds_hold_the_truth(t)
    call adapted_thresholds_not_met(t)
    call hp_thresholds_meet_their_tolerance(t)
    ! hp levels: 1e-8 within max_levels = 2: not met, 2 rows of adapt.csv
    call check_limit_not_met(t, 'threshold', 'hp', 2, OUT//'/hp_not_met', 2)
    call remove_tree(OUT)
    call t%report()

contains

    !> lambda- = -1.8 to 1e-13 (a 2 x 2 pencil), lambda+ null, both sides' keys written, the
    !> mu of the spectrum at lambda = -5 the closed form 105/208.
    subroutine single_element_threshold(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(mesh_t) :: m
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary, report
        logical :: ran
        call single_element_scene(OUT//'/threshold', config, m)
        config%analysis%kind = 'threshold'
        call run_checked(t, 'threshold', config, analysis, summary, ran, m, report)
        if (.not. ran) return
        call t%check_close('threshold: lambda- = -(L + 3G)/(L + G)', &
                           json_real(summary, 'lambda_critical_minus'), &
                           single_element_lambda_minus(0.3_wp), 1.0e-13_wp)
        call t%check('threshold: no lambda+', &
                     json_value(summary, 'lambda_critical_plus') == 'null')
        call t%check_close('threshold: mu at lambda = -5 is 105/208', &
                           json_real(summary, 'lowest_positive_mu'), 105.0_wp/208.0_wp, 1.0e-13_wp)
        call t%check('threshold: the report says there is no lambda+', &
                     index(report, 'none (no real eigenvalue of Kt_nn x = lambda Kt_nt x > 0)') &
                     > 0)
        call t%check('threshold: one boundary point, said so in the singular ("1 points")', &
                     index(report, ': 1 point'//new_line('a')) > 0 .and. &
                     index(report, '1 points') == 0)
    end subroutine single_element_threshold

    !> A sweep over the list -5, -3, -2, -1, 2: lambda_sweep.csv has one row per lambda in
    !> input order, critical_c_n the closed form where lambda < lambda- (1e-13) and empty
    !> where no mu is positive; summary.json counts 3 points with a positive mu.
    subroutine single_element_sweep(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: LAMBDAS(5) = [-5.0_wp, -3.0_wp, -2.0_wp, -1.0_wp, 2.0_wp]
        type(config_t) :: config
        type(mesh_t) :: m
        class(analysis_t), allocatable :: analysis
        type(status_t) :: stat
        type(csv_table_t) :: table
        character(len=:), allocatable :: summary
        integer :: i, column
        real(wp) :: expected, value
        logical :: all_match, ran
        call single_element_scene(OUT//'/sweep', config, m)
        config%analysis%kind = 'lambda_sweep'
        config%sweep%lambdas(1:5) = LAMBDAS
        call run_checked(t, 'sweep', config, analysis, summary, ran, m)
        if (.not. ran) return
        call t%check('sweep: lambda_sweep.csv listed', &
                     any(listed_files(summary) == 'lambda_sweep.csv'))
        call t%check('sweep: 5 rows', data_rows(OUT//'/sweep/lambda_sweep.csv') == 5)
        call t%check('sweep: 3 points with a positive mu', &
                     nint(json_real(summary, 'sweep_n_with_positive_mu')) == 3)
        call read_csv_table(OUT//'/sweep/lambda_sweep.csv', table, stat)
        call t%check('sweep: lambda_sweep.csv reads', stat%ok())
        if (.not. stat%ok()) return
        column = table%column('critical_c_n')
        all_match = table%n_rows() == 5 .and. column > 0
        do i = 1, min(5, table%n_rows())
            expected = single_element_mu(LAMBDAS(i), 0.3_wp, 2.0_wp)
            if (LAMBDAS(i) < single_element_lambda_minus(0.3_wp)) then
                value = table%number(i, column)
                if (abs(value - expected) > 1.0e-13_wp*expected) all_match = .false.
            else if (len(table%text(i, column)) > 0) then
                all_match = .false.
            end if
        end do
        call t%check('sweep: critical_c_n the closed form below lambda-, empty above', all_match)
    end subroutine single_element_sweep

    !> The reference scene from 2 x 2 P1 adapted to 1e-2: converged, both continuum
    !> thresholds within their relative bars, adapt.csv with adapt_levels + 1 rows.
    subroutine adapted_thresholds_hold_the_truth(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary
        logical :: ran
        call adaptive_scene('threshold', 'h', 1.0e-2_wp, 0, OUT//'/adapt', config)
        call run_checked(t, 'adapt', config, analysis, summary, ran)
        if (.not. ran) return
        call t%check('adapt: converged', json_value(summary, 'adapt_converged') == 'true')
        call t%check('adapt: lambda+ and lambda- within their bars of the truth', &
                     thresholds_within_bars(summary, REF_LAMBDA_PLUS, REF_LAMBDA_MINUS))
        call t%check('adapt: adapt.csv has adapt_levels + 1 rows', data_rows(OUT// &
                     '/adapt/adapt.csv') == nint(json_real(summary, 'adapt_levels')) + 1)
    end subroutine adapted_thresholds_hold_the_truth

    !> Tolerance 1e-8 within one level: the verdict STATUS_NOT_MET, the set written.
    subroutine adapted_thresholds_not_met(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary
        logical :: ran
        call adaptive_scene('threshold', 'h', 1.0e-8_wp, 1, OUT//'/not_met', config)
        call run_checked(t, 'not met', config, analysis, summary, ran, verdict=STATUS_NOT_MET)
        if (ran) call t%check('not met: adapt.csv has 2 rows', &
                              data_rows(OUT//'/not_met/adapt.csv') == 2)
    end subroutine adapted_thresholds_not_met

    !> Tolerance 1e-3: converged, both continuum thresholds within their bars, a row per
    !> level in adapt.csv and per cell in degrees.csv.
    subroutine hp_thresholds_meet_their_tolerance(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary
        logical :: ran
        call adaptive_scene('threshold', 'hp', 1.0e-3_wp, 0, OUT//'/hp', config)
        call run_checked(t, 'hp', config, analysis, summary, ran)
        if (.not. ran) return
        call t%check('hp: converged', json_value(summary, 'adapt_converged') == 'true')
        call t%check('hp: lambda+ and lambda- within their bars of the truth', &
                     thresholds_within_bars(summary, REF_LAMBDA_PLUS, REF_LAMBDA_MINUS))
        call t%check('hp: adapt.csv has a row per level', &
                     data_rows(OUT//'/hp/adapt.csv') == &
                     nint(json_real(summary, 'adapt_levels')))
        call t%check('hp: degrees.csv has a row per cell', &
                     data_rows(OUT//'/hp/degrees.csv') == &
                     nint(json_real(summary, 'n_cells')))
    end subroutine hp_thresholds_meet_their_tolerance
end program test_threshold_run
