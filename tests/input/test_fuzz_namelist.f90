! SPDX-License-Identifier: MIT
!> Fuzzing the input reader: a few thousand mutated copies of the example inputs
!> (input/*.nml), each read by read_input in this process, so that the Debug build
!> (-fcheck=all, FPE traps) and the sanitizer build watch every read. Each mutant must end
!> either in a config that validate_config accepts again, or in STATUS_BAD_INPUT with a
!> message of one line (no line feed, no control byte, at most MAX_MESSAGE characters)
!> naming the file; a crash or a hang fails the test (CTest TIMEOUT, see CMakeLists.txt).
!> Mutations: byte changes (any of the 256), deleted, duplicated and truncated text, long
!> values (past every buffer), control bytes, and tokens the namelist read used to get
!> silently wrong ('.trash.', '1.0e', a repeated variable, 1001 lambdas). The generator is
!> seeded per seed file, so every run reads the same mutants. After a crash,
!> fuzz_mutant.nml in the test's working directory is the input that crashed; a mutant
!> that fails a check is kept as fuzz_failure_<n>.nml.
program test_fuzz_namelist
    use kinds, only: i8
    use status, only: status_t, STATUS_BAD_INPUT
    use run_config, only: config_t
    use input_config, only: read_input
    use input_validation, only: validate_config
    use strings, only: to_string
    use testing, only: test_suite_t
    use fixtures, only: random_t, uniform, read_text, write_text
    implicit none

    integer, parameter :: MUTANTS_PER_SEED = 250    !! 13 seeds: 3250 mutants
    integer, parameter :: MAX_MUTATIONS = 3         !! per mutant, at least 1
    integer, parameter :: MAX_MESSAGE = 1000        !! characters of a message
    integer(i8), parameter :: BASE_SEED = 20261123_i8
    character(len=*), parameter :: MUTANT_PATH = 'fuzz_mutant.nml'
    character(len=*), parameter :: SEED_NAMES(*) = [character(len=24) :: 'branch.nml', &
        'delaunay.nml', 'eigen_p1_left.nml', 'eigen_p2.nml', 'eigen_q1.nml', 'eigen_q2.nml', &
        'lambda_sweep_fine.nml', 'single_element.nml', 'solve.nml', 'solve_branch.nml', &
        'square.nml', 'square_sweep.nml', 'threshold.nml']

    integer, parameter :: CHANGE_BYTE = 1, DELETE_TEXT = 2, DUPLICATE_TEXT = 3, &
                          TRUNCATE = 4, LONG_VALUE = 5, CONTROL_BYTE = 6, PUT_TOKEN = 7, &
                          N_KINDS = 7
    !> Tokens put into the text: wrong logicals, unreadable numbers, repeats, separators.
    character(len=*), parameter :: TOKENS(*) = [character(len=24) :: '.trash.', '1.0e', &
        '1.0x', ' nx = 4, nx = 6 ', "'", '"', '/', '&', '!', '&mesh', '&end', '$', ',', &
        '1001*1.0', '2*', '9999999999999', '1e999', '-1e999', 'NaN', '(', ')', '%', &
        ' lambdas(999) = 1, 2, 3 ', ' vtk = T ']

    !> Minimal standard generator (Park and Miller), as in test_fuzz_mesh_gmsh.
    type(test_suite_t) :: t
    integer :: s, n_ok, n_bad_input, n_failures
    character(len=4096) :: source_dir

    t%name = 'test_fuzz_namelist'
    call get_environment_variable('NCEIG_SOURCE_DIR', source_dir)
    n_ok = 0
    n_bad_input = 0
    n_failures = 0
    do s = 1, size(SEED_NAMES)
        call fuzz_seed(s, trim(source_dir)//'/input/'//trim(SEED_NAMES(s)))
    end do
    print '(a)', '      total: '//to_string(n_ok + n_bad_input + n_failures)//' mutants, ' &
        //to_string(n_ok)//' read OK (config valid), '//to_string(n_bad_input) &
        //' refused with one-line STATUS_BAD_INPUT, '//to_string(n_failures)//' failures'
    call t%check('every mutant read OK or refused with one clean line', n_failures == 0)
    call t%report()

contains

    subroutine fuzz_seed(index, path)
        integer, intent(in) :: index
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: original, text, problem
        type(random_t) :: rng
        type(config_t) :: config
        type(status_t) :: stat, check
        integer :: m, k, n_mutations

        call read_text(path, original)
        call t%check('seed '//trim(SEED_NAMES(index))//' is read', len(original) > 0)
        rng%state = BASE_SEED + 7919_i8*index
        do m = 1, MUTANTS_PER_SEED
            text = original
            n_mutations = uniform(rng, 1, MAX_MUTATIONS)
            do k = 1, n_mutations
                call mutate(text, uniform(rng, 1, N_KINDS), rng)
            end do
            call write_text(MUTANT_PATH, text)
            call read_input(MUTANT_PATH, config, stat)
            problem = ''
            if (stat%ok()) then
                call validate_config(config, MUTANT_PATH, check)
                if (.not. check%ok()) problem = 'accepted, but invalid: '//check%message
            else
                problem = message_problem(stat)
            end if
            if (len(problem) == 0) then
                if (stat%ok()) then
                    n_ok = n_ok + 1
                else
                    n_bad_input = n_bad_input + 1
                end if
            else
                n_failures = n_failures + 1
                call write_text('fuzz_failure_'//to_string(n_failures)//'.nml', text)
                print '(a)', 'FAIL  '//trim(SEED_NAMES(index))//' mutant '//to_string(m) &
                    //' (fuzz_failure_'//to_string(n_failures)//'.nml): '//problem
            end if
        end do
    end subroutine fuzz_seed

    !> What is wrong with the status of a refused mutant ('' when nothing).
    function message_problem(stat) result(problem)
        type(status_t), intent(in) :: stat
        character(len=:), allocatable :: problem
        integer :: i
        problem = ''
        if (stat%code /= STATUS_BAD_INPUT) then
            problem = 'status '//to_string(stat%code)//' instead of STATUS_BAD_INPUT'
        else if (.not. allocated(stat%message)) then
            problem = 'no message'
        else if (len(stat%message) == 0 .or. len(stat%message) > MAX_MESSAGE) then
            problem = 'message of '//to_string(len(stat%message))//' characters'
        else if (index(stat%message, MUTANT_PATH) /= 1) then
            problem = 'message does not start with the file: '//stat%message
        else
            do i = 1, len(stat%message)
                if (iachar(stat%message(i:i)) < 32 .or. iachar(stat%message(i:i)) == 127) then
                    problem = 'control byte '//to_string(iachar(stat%message(i:i))) &
                              //' in the message at '//to_string(i)
                    return
                end if
            end do
        end if
    end function message_problem

    ! -------------------------------------------------------------------- mutations

    subroutine mutate(text, kind, rng)
        character(len=:), allocatable, intent(inout) :: text
        integer, intent(in) :: kind
        type(random_t), intent(inout) :: rng
        integer :: at, length
        character(len=:), allocatable :: piece

        if (len(text) == 0) text = ' '
        at = uniform(rng, 1, len(text))
        select case (kind)
        case (CHANGE_BYTE)
            text(at:at) = achar(uniform(rng, 0, 255))
        case (DELETE_TEXT)
            length = uniform(rng, 1, min(40, len(text) - at + 1))
            text = text(:at - 1)//text(at + length:)
        case (DUPLICATE_TEXT)
            length = uniform(rng, 1, min(80, len(text) - at + 1))
            text = text(:at + length - 1)//text(at:)
        case (TRUNCATE)
            text = text(:at - 1)
        case (LONG_VALUE)
            ! Past the 64 of a name, the 512 of a list or the 4096 of a path, or far beyond.
            select case (uniform(rng, 1, 4))
            case (1); length = 70
            case (2); length = 600
            case (3); length = 4200
            case default; length = 200000
            end select
            allocate (character(len=length) :: piece)
            piece = repeat(achar(uniform(rng, 32, 126)), length)
            if (uniform(rng, 0, 1) == 0) piece(1:1) = 'x'   ! else often all blanks
            text = text(:at - 1)//piece//text(at:)
        case (CONTROL_BYTE)
            text = text(:at - 1)//achar(uniform(rng, 0, 31))//text(at:)
        case (PUT_TOKEN)
            piece = trim(TOKENS(uniform(rng, 1, size(TOKENS))))
            if (len(piece) == 0) piece = ' '
            text = text(:at - 1)//piece//text(at:)
        end select
    end subroutine mutate


    ! ------------------------------------------------------------------------ files

end program test_fuzz_namelist
