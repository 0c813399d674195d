! SPDX-License-Identifier: MIT
!> The report of a run (run_report) in process: a run commits a complete set whose
!> summary.json lists every file, replaces the set of an earlier run and keeps a user's
!> file, and fails without a set where the output directory cannot be made; and the one
!> summary record of a run (summary_record) says the same in summary.json and on stdout. The
!> runs are of the single element (docs/model.md section 8), whose one eigenvalue has a
!> closed form, and of its thresholds (lambda- = -1.8, no lambda+).
program test_run_report
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use run_config, only: config_t
    use mesh, only: mesh_t
    use analysis_base, only: analysis_t
    use filesystem, only: file_exists, remove_tree
    use summary_record, only: threshold_facts_t, boundary_lines
    use real_format, only: real_to_text
    use fixtures, only: single_element_scene, single_element_mu, single_element_lambda_minus, &
                        run_as_main, run_checked, json_real, json_value, listed_files, &
                        write_text
    implicit none

    character(len=*), parameter :: OUT = 'test_run_report.out'
    type(test_suite_t) :: t

    t%name = 'test_run_report'
    call remove_tree(OUT)
    call a_run_commits_a_listed_set(t)
    call a_second_run_replaces_the_set(t)
    call an_unmakeable_directory_fails(t)
    call threshold_summary_says_one_thing(t)
    call boundary_lines_say_the_counts(t)
    call remove_tree(OUT)
    call t%report()

contains

    !> The eigen run of the single element at lambda = -5: the set in place, every file
    !> summary.json lists present and not empty (run_checked), summary.json among them, its mu the
    !> closed form 105/208 (1e-13: a 2 x 2 solve and a 1 x 1 eigenproblem, a few ulps).
    subroutine a_run_commits_a_listed_set(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(mesh_t) :: m
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary, report
        character(len=255), allocatable :: names(:)
        logical :: ran
        call single_element_scene(OUT//'/first', config, m)
        call run_checked(t, 'run', config, analysis, summary, ran, m, report)
        if (.not. ran) return
        names = listed_files(summary)
        call t%check('run: summary.json lists itself, eigenvalues.csv and mode_001.vtu', &
                     any(names == 'summary.json') .and. any(names == 'eigenvalues.csv') .and. &
                     any(names == 'mode_001.vtu'))
        call t%check_close('run: mu = 105/208', json_real(summary, 'lowest_positive_mu'), &
                           105.0_wp/208.0_wp, 1.0e-13_wp)
        call t%check('run: the report quotes the summary''s mu', index(report, &
                     'lowest positive mu = critical c_n = '// &
                     json_value(summary, 'lowest_positive_mu')) > 0)
    end subroutine a_run_commits_a_listed_set

    !> A second run into the same directory, at lambda = -3: the new set replaces the old
    !> (its mu the closed form at -3, 35/24), a file of the old set it does not write
    !> (mode_001.vtu, now vtk = .false.) is gone, a file of the user's stays.
    subroutine a_second_run_replaces_the_set(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(mesh_t) :: m
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary
        logical :: ran
        call single_element_scene(OUT//'/second', config, m)
        call run_checked(t, 'replace, first run', config, analysis, summary, ran, m)
        if (.not. ran) return
        call write_text(OUT//'/second/notes.txt', 'mine')
        config%analysis%lambda = -3.0_wp
        config%output%vtk = .false.
        call run_checked(t, 'replace, second run', config, analysis, summary, ran, m)
        if (.not. ran) return
        call t%check_close('replace: mu at lambda = -3 is the closed form', &
                           json_real(summary, 'lowest_positive_mu'), &
                           single_element_mu(-3.0_wp, 0.3_wp, 2.0_wp), 1.0e-13_wp)
        call t%check('replace: the old mode_001.vtu is gone', &
                     .not. file_exists(OUT//'/second/mode_001.vtu'))
        call t%check('replace: the user''s file stays', file_exists(OUT//'/second/notes.txt'))
    end subroutine a_second_run_replaces_the_set

    !> An output directory below a regular file cannot be made: the run fails (no set, no
    !> summary), its message naming the input file and the &output directory.
    subroutine an_unmakeable_directory_fails(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(mesh_t) :: m
        class(analysis_t), allocatable :: analysis
        type(status_t) :: stat
        character(len=:), allocatable :: summary
        call write_text(OUT//'/plain_file', 'not a folder')
        call single_element_scene(OUT//'/plain_file/set', config, m)
        call run_as_main(config, analysis, stat, summary, m)
        call t%check('no directory: the run fails', .not. stat%ok())
        if (stat%ok()) return
        call t%check('no directory: the message names the input and &output directory', &
                     index(stat%message, 'single_element: &output directory') == 1)
    end subroutine an_unmakeable_directory_fails

    !> The thresholds of the single element: summary.json and the stdout summary, rendered
    !> from one record, quote the same lambda- (the closed form -(L + 3G)/(L + G) = -1.8 to
    !> 1e-13: a 1 x 1 pencil), the same absence of lambda+, the same boundary point and
    !> interval, and the text its headline mu as the JSON writes it.
    subroutine threshold_summary_says_one_thing(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(mesh_t) :: m
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary, report, minus
        logical :: ran
        call single_element_scene(OUT//'/threshold', config, m)
        config%analysis%kind = 'threshold'
        call run_checked(t, 'threshold', config, analysis, summary, ran, m, report)
        if (.not. ran) return
        minus = json_value(summary, 'lambda_critical_minus')
        call t%check_close('threshold: lambda- is the closed form', &
                           json_real(summary, 'lambda_critical_minus'), &
                           single_element_lambda_minus(0.3_wp), 1.0e-13_wp)
        call t%check('threshold: no lambda+ in either', &
                     json_value(summary, 'lambda_critical_plus') == 'null' .and. &
                     index(report, '  lambda+     none (no real eigenvalue') > 0)
        call t%check('threshold: the text quotes lambda- as the JSON', &
                     index(report, '  lambda-     '//minus//' ') > 0)
        call t%check('threshold: the boundary point is lambda- in both', &
                     json_value(summary, 'boundary_lambda') == '['//minus//']' .and. &
                     index(report, '              lambda = '//minus//' ') > 0)
        call t%check('threshold: the interval with a positive mu ends at lambda- in both', &
                     json_value(summary, 'positive_mu_intervals_upper') == '['//minus//']' &
                     .and. index(report, ', '//minus//']') > 0)
        call t%check('threshold: the headline mu as the JSON writes it', &
                     index(report, 'lowest positive mu = critical c_n = '// &
                           json_value(summary, 'lowest_positive_mu')) > 0)
    end subroutine threshold_summary_says_one_thing

    !> A point across which the count of positive mu does not change (0 and 0: not confirmed)
    !> neither appears nor vanishes: its line says the counts, not '(0 -> 0)' after
    !> 'positive mu vanishes'; a point from 1 to 0 keeps its wording.
    subroutine boundary_lines_say_the_counts(t)
        type(test_suite_t), intent(inout) :: t
        type(threshold_facts_t) :: set
        character(len=:), allocatable :: text
        set%lambda_min = -20.0_wp
        set%lambda_max = 20.0_wp
        allocate (set%points(2))
        set%points(1)%lambda = -2.0_wp
        set%points(1)%mechanism = 'pencil'
        set%points(1)%n_below = 1
        set%points(1)%n_above = 0
        set%points(1)%appears = .false.
        set%points(1)%confirmed = .true.
        set%points(2)%lambda = 3.0_wp
        set%points(2)%mechanism = 'complex_pair'
        set%points(2)%n_below = 0
        set%points(2)%n_above = 0
        set%points(2)%appears = .false.
        allocate (set%lower(0), set%upper(0))
        text = boundary_lines(set)
        call t%check('summary_record boundary lines: 0 and 0 are said as such, no "(0 -> 0)"', &
                     index(text, 'the count of positive mu is 0 on both sides, NOT confirmed') &
                     > 0 .and. index(text, '(0 -> 0)') == 0)
        call t%check('summary_record boundary lines: 1 -> 0 still vanishes', &
                     index(text, 'positive mu vanishes as lambda increases (1 -> 0), confirmed') &
                     > 0 .and. index(text, ': 2 points') > 0)
    end subroutine boundary_lines_say_the_counts
end program test_run_report
