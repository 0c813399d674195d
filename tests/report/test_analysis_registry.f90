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
    use eigen_run, only: eigen_run_t
    use adapt_run, only: adapt_run_t
    use hp_adapt_run, only: hp_adapt_run_t
    use threshold_run, only: threshold_run_t, sweep_run_t, adapt_threshold_run_t
    use hp_threshold_run, only: hp_threshold_run_t
    use branch_run, only: branch_run_t
    use solve_run, only: solve_run_t
    use filesystem, only: file_exists, remove_tree
    use fixtures, only: single_element_scene, single_element_mu, run_as_main, json_real, json_value, &
                        listed_files, write_text, all_present
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
    !> (absent: 'h'); K on all dofs only for 'branch' and 'solve'; an unknown kind: none.
    subroutine each_kind_has_its_type(t)
        type(test_suite_t), intent(inout) :: t
        class(analysis_t), allocatable :: a
        call new_analysis('eigen', .false., a)
        call t%check('eigen: eigen_run_t', is(a, 'eigen') .and. .not. a%needs_all_dofs)
        call new_analysis('eigen', .true., a)
        call t%check('eigen, adaptive, no strategy: adapt_run_t (h)', is(a, 'adapt'))
        call new_analysis('eigen', .true., a, 'h')
        call t%check('eigen, adaptive h: adapt_run_t', is(a, 'adapt'))
        call new_analysis('eigen', .true., a, 'hp')
        call t%check('eigen, adaptive hp: hp_adapt_run_t', is(a, 'hp_adapt'))
        call new_analysis('eigen', .false., a, 'hp')
        call t%check('eigen, hp but not adaptive: eigen_run_t', is(a, 'eigen'))
        call new_analysis('threshold', .false., a)
        call t%check('threshold: threshold_run_t', is(a, 'threshold'))
        call new_analysis('threshold', .true., a, 'h')
        call t%check('threshold, adaptive h: adapt_threshold_run_t', is(a, 'adapt_threshold'))
        call new_analysis('threshold', .true., a, 'hp')
        call t%check('threshold, adaptive hp: hp_threshold_run_t', is(a, 'hp_threshold'))
        call new_analysis('lambda_sweep', .false., a)
        call t%check('lambda_sweep: sweep_run_t', is(a, 'sweep'))
        call new_analysis('lambda_sweep', .true., a, 'hp')
        call t%check('lambda_sweep, adaptive hp: sweep_run_t (each point adapts)', is(a, 'sweep'))
        call new_analysis('branch', .false., a)
        call t%check('branch: branch_run_t on all dofs', is(a, 'branch') .and. a%needs_all_dofs)
        call new_analysis('solve', .false., a)
        call t%check('solve: solve_run_t on all dofs', is(a, 'solve') .and. a%needs_all_dofs)
        call new_analysis('nonsense', .false., a)
        call t%check('unknown kind: no analysis', .not. allocated(a))
    end subroutine each_kind_has_its_type

    !> Which of the registry's types `a` is, by name ('' when none).
    logical function is(a, name)
        class(analysis_t), allocatable, intent(in) :: a
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: found
        found = ''
        if (allocated(a)) then
            select type (a)
            type is (eigen_run_t); found = 'eigen'
            type is (adapt_run_t); found = 'adapt'
            type is (hp_adapt_run_t); found = 'hp_adapt'
            type is (threshold_run_t); found = 'threshold'
            type is (adapt_threshold_run_t); found = 'adapt_threshold'
            type is (hp_threshold_run_t); found = 'hp_threshold'
            type is (sweep_run_t); found = 'sweep'
            type is (branch_run_t); found = 'branch'
            type is (solve_run_t); found = 'solve'
            end select
        end if
        is = found == name
    end function is

    !> The eigen run of the single element at lambda = -5: the set in place, every file
    !> summary.json lists present and not empty, summary.json among them, its mu the
    !> closed form 105/208 (1e-13: a 2 x 2 solve and a 1 x 1 eigenproblem, a few ulps).
    subroutine a_run_commits_a_listed_set(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(mesh_t) :: m
        class(analysis_t), allocatable :: analysis
        type(status_t) :: stat
        character(len=:), allocatable :: summary, report
        character(len=255), allocatable :: names(:)
        call single_element_scene(OUT//'/first', config, m)
        call run_as_main(config, analysis, stat, summary, m, report)
        call t%check('run: ok, verdict ok', stat%ok() .and. analysis%verdict%ok())
        if (.not. stat%ok()) return
        names = listed_files(summary)
        call t%check('run: summary.json lists itself, eigenvalues.csv and mode_001.vtu', &
                     any(names == 'summary.json') .and. any(names == 'eigenvalues.csv') .and. &
                     any(names == 'mode_001.vtu'))
        call t%check('run: every listed file is in place and not empty', &
                     all_present(OUT//'/first', names))
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
        type(status_t) :: stat
        character(len=:), allocatable :: summary
        call single_element_scene(OUT//'/second', config, m)
        call run_as_main(config, analysis, stat, summary, m)
        if (.not. stat%ok()) then
            call t%check('replace: first run ok', .false.)
            return
        end if
        call write_text(OUT//'/second/notes.txt', 'mine')
        config%analysis%lambda = -3.0_wp
        config%output%vtk = .false.
        call run_as_main(config, analysis, stat, summary, m)
        call t%check('replace: second run ok', stat%ok())
        if (.not. stat%ok()) return
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

