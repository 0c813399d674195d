! SPDX-License-Identifier: MIT
!> The analyses by kind (analysis_registry) and the run skeleton every one shares
!> (analysis_base's run_analysis), in process: each &analysis kind, adaptive or not, with
!> either &adapt strategy, gets its own type; a run commits a complete set whose
!> summary.json lists every file, replaces the set of an earlier run, and fails without a
!> set where the output directory cannot be made. The runs are of the single element
!> (docs/model.md section 8), whose one eigenvalue has a closed form.
program test_analysis_registry
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use run_config, only: config_t
    use mesh, only: mesh_t
    use analysis_base, only: analysis_t
    use analysis_registry, only: new_analysis
    use eigen_run, only: eigen_run_t, adapt_eigen_run_t
    use threshold_run, only: threshold_run_t, sweep_run_t, adapt_threshold_run_t
    use compliance_run, only: branch_run_t, solve_run_t
    use run_inputs, only: run_inputs_t, translate_input
    use filesystem, only: file_exists, remove_tree
    use fixtures, only: single_element_scene, single_element_mu, run_as_main, run_checked, &
                        json_real, json_value, listed_files, write_text
    implicit none

    character(len=*), parameter :: OUT = 'test_analysis_registry.out'
    type(test_suite_t) :: t

    t%name = 'test_analysis_registry'
    call remove_tree(OUT)
    call each_kind_has_its_type(t)
    call a_run_commits_a_listed_set(t)
    call a_second_run_replaces_the_set(t)
    call an_unmakeable_directory_fails(t)
    call remove_tree(OUT)
    call t%report()

contains

    !> The type new_analysis picks for every kind, adaptive or not, strategy 'h' or 'hp'
    !> (' ': absent, which is 'h'); K on all dofs only for 'branch' and 'solve'; an unknown
    !> kind: none.
    subroutine each_kind_has_its_type(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: KINDS(13) = [character(len=12) :: 'eigen', 'eigen', &
            'eigen', 'eigen', 'eigen', 'threshold', 'threshold', 'threshold', 'lambda_sweep', &
            'lambda_sweep', 'branch', 'solve', 'nonsense']
        logical, parameter :: ADAPTIVE(13) = [.false., .true., .true., .true., .false., &
            .false., .true., .true., .false., .true., .false., .false., .false.]
        character(len=*), parameter :: STRATEGIES(13) = [character(len=2) :: ' ', ' ', 'h', &
            'hp', 'hp', ' ', 'h', 'hp', ' ', 'hp', ' ', ' ', ' ']
        character(len=*), parameter :: EXPECTED(13) = [character(len=15) :: 'eigen', &
            'adapt_eigen', 'adapt_eigen', 'adapt_eigen', 'eigen', 'threshold', &
            'adapt_threshold', 'adapt_threshold', 'sweep', 'sweep', 'branch', 'solve', '']
        class(analysis_t), allocatable :: a
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        character(len=100) :: what
        integer :: i
        logical :: all_dofs
        do i = 1, size(KINDS)
            config%analysis%kind = KINDS(i)
            config%adapt%tolerance = merge(1.0e-6_wp, 0.0_wp, ADAPTIVE(i))
            config%adapt%strategy = 'h'
            if (STRATEGIES(i) /= ' ') config%adapt%strategy = STRATEGIES(i)
            call translate_input(config, inputs)
            call new_analysis(inputs, a)
            write (what, '(a, l1, 4a)') trim(KINDS(i))//', adaptive ', ADAPTIVE(i), &
                ', strategy "', trim(STRATEGIES(i)), '": ', trim(EXPECTED(i))
            all_dofs = .false.
            if (allocated(a)) all_dofs = a%in_input_units()
            call t%check(trim(what)//', all dofs only for branch and solve', &
                         type_name(a) == trim(EXPECTED(i)) .and. (all_dofs .eqv. &
                         any(KINDS(i) == [character(len=12) :: 'branch', 'solve'])))
        end do
    end subroutine each_kind_has_its_type

    !> Which of the registry's types `a` is, without _run_t ('' when none).
    function type_name(a) result(found)
        class(analysis_t), allocatable, intent(in) :: a
        character(len=:), allocatable :: found
        found = ''
        if (allocated(a)) then
            select type (a)
            type is (eigen_run_t); found = 'eigen'
            type is (adapt_eigen_run_t); found = 'adapt_eigen'
            type is (threshold_run_t); found = 'threshold'
            type is (adapt_threshold_run_t); found = 'adapt_threshold'
            type is (sweep_run_t); found = 'sweep'
            type is (branch_run_t); found = 'branch'
            type is (solve_run_t); found = 'solve'
            end select
        end if
    end function type_name

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

end program test_analysis_registry

