! SPDX-License-Identifier: MIT
!> The analyses by kind (analysis_registry): each &analysis kind, adaptive or not, with
!> either &adapt strategy (the refiner is the loop's, not the analysis's), gets its own type,
!> and only the analyses of the frictional problem work in the input's units.
program test_analysis_registry
    use kinds, only: wp
    use testing, only: test_suite_t
    use run_config, only: config_t
    use analysis_base, only: analysis_t
    use analysis_registry, only: new_analysis
    use eigen_run, only: eigen_run_t, adapt_eigen_run_t
    use threshold_run, only: threshold_run_t, sweep_run_t, adapt_threshold_run_t
    use compliance_run, only: branch_run_t, solve_run_t
    use run_inputs, only: run_inputs_t, translate_input
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_analysis_registry'
    call each_kind_has_its_type(t)
    call t%report()

contains

    !> The type new_analysis picks for every kind, adaptive or not, strategy 'h' or 'hp'
    !> (' ': the default, 'h'); the input's units (K on all dofs) only for 'branch' and
    !> 'solve'; an unknown kind: none.
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
end program test_analysis_registry
