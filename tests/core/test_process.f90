! SPDX-License-Identifier: MIT
!> process: programs run with an argument vector and no shell. Exit statuses come back as
!> they are; a missing program and one that cannot be started get different codes (and the
!> latter the system's reason); an argument with blanks, quotes and `;` reaches the program
!> as one argument, byte for byte; stdout goes to the file asked for.
program test_process
    use process, only: run_program, program_on_path, ignore_broken_pipe, PROGRAM_NOT_FOUND, &
                       PROGRAM_NOT_STARTED
    use strings, only: text_t
    use filesystem, only: remove_file, file_exists
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t
    integer :: exit_status, unit, ios
    character(len=:), allocatable :: reason
    character(len=256) :: line
    character(len=*), parameter :: TRICKY = "a b'c;touch INJECTED_BY_TEST;'$(id)"""
    character(len=*), parameter :: OUTPUT = 'test_process.out', NOT_EXECUTABLE = &
                                   './test_process.not-executable'

    t%name = 'test_process'

    call run(exit_status, reason, 'true')
    call t%check('true: exit status 0', exit_status == 0 .and. reason == '')

    call run(exit_status, reason, 'false')
    call t%check('false: exit status 1', exit_status == 1)

    call run(exit_status, reason, 'sh', '-c', 'exit 42')
    call t%check('sh -c "exit 42": exit status 42', exit_status == 42)

    call run(exit_status, reason, 'sh', '-c', 'kill -TERM $$')
    call t%check('a program ended by SIGTERM: 128 + 15', exit_status == 128 + 15)

    call run(exit_status, reason, 'nceig-no-such-program-here')
    call t%check('a missing program: PROGRAM_NOT_FOUND with a reason', &
                 exit_status == PROGRAM_NOT_FOUND .and. len(reason) > 0)

    ! A file that exists but may not be executed: EACCES, not "not found"
    open (newunit=unit, file=NOT_EXECUTABLE, status='replace', action='write')
    write (unit, '(a)') 'exit 0'
    close (unit)
    call run(exit_status, reason, NOT_EXECUTABLE)
    call t%check('a file without execute permission: PROGRAM_NOT_STARTED, "Permission '// &
                 'denied"', exit_status == PROGRAM_NOT_STARTED .and. reason == 'Permission denied')
    call remove_file(NOT_EXECUTABLE)

    ! The test's own shell text: $1 must arrive whole, and nothing in it may run
    call run(exit_status, reason, 'sh', '-c', 'test "$1" = "$2"', 'sh', TRICKY, TRICKY)
    call t%check('an argument with blanks, quotes, ; and $( ) arrives as one, intact', &
                 exit_status == 0)
    call run(exit_status, reason, 'sh', '-c', 'test "$1" = "a b''c"', 'sh', "a b'c")
    call t%check("the argument a b'c compares equal to the shell's own literal", &
                 exit_status == 0)
    call t%check('no command inside an argument ran', .not. file_exists('INJECTED_BY_TEST'))
    call run(exit_status, reason, 'sh', '-c', 'test "$1" = "a  "', 'sh', 'a  ')
    call t%check('trailing blanks of an argument are kept', exit_status == 0)

    call remove_file(OUTPUT)
    call run(exit_status, reason, 'sh', '-c', 'echo "$1"; echo err >&2; cat', 'sh', &
             'to the file', output=OUTPUT)
    line = ''
    open (newunit=unit, file=OUTPUT, status='old', action='read', iostat=ios)
    if (ios == 0) read (unit, '(a)', iostat=ios) line
    call t%check('stdout into the file asked for; stdin is empty (cat ends)', &
                 exit_status == 0 .and. ios == 0 .and. line == 'to the file')
    if (ios == 0) read (unit, '(a)', iostat=ios) line
    call t%check('stderr into the same file', ios == 0 .and. line == 'err')
    close (unit, iostat=ios)
    call remove_file(OUTPUT)

    call run(exit_status, reason, 'true', output='no-such-folder/x.out')
    call t%check('an output file that cannot be opened: PROGRAM_NOT_STARTED, its reason', &
                 exit_status == PROGRAM_NOT_STARTED .and. reason == 'No such file or directory')

    ! As in nceig: ignored here, yet the default in the program (exec keeps an ignored
    ! signal ignored, and a non-interactive shell cannot undo that)
    call ignore_broken_pipe()
    call run(exit_status, reason, 'sh', '-c', 'kill -PIPE $$')
    call t%check('SIGPIPE ignored by the caller has its default action in the program', &
                 exit_status == 128 + 13)

    call t%check('sh is on the PATH', program_on_path('sh'))
    call t%check('a missing program is not on the PATH', &
                 .not. program_on_path('nceig-no-such-program-here'))
    call t%check('a path with / is checked as it is: /bin/sh', program_on_path('/bin/sh'))
    call t%check('a path with / is checked as it is: /nonexistent/sh', &
                 .not. program_on_path('/nonexistent/sh'))

    ! gfortran 12 keeps main-program allocatables in a frame gone before LeakSanitizer looks
    if (allocated(reason)) deallocate (reason)
    call t%report()

contains

    !> run_program on the arguments given (up to six), the vector filled element by element:
    !> an array constructor of text_t makes temporaries whose allocatable components
    !> gfortran 12 does not free in a main program (LeakSanitizer reported them).
    subroutine run(status, why, a1, a2, a3, a4, a5, a6, output)
        integer, intent(out) :: status
        character(len=:), allocatable, intent(out) :: why
        character(len=*), intent(in) :: a1
        character(len=*), intent(in), optional :: a2, a3, a4, a5, a6, output
        type(text_t), allocatable :: argv(:)
        integer :: n
        n = 1 + count([present(a2), present(a3), present(a4), present(a5), present(a6)])
        allocate (argv(n))
        argv(1)%text = a1
        if (present(a2)) argv(2)%text = a2
        if (present(a3)) argv(3)%text = a3
        if (present(a4)) argv(4)%text = a4
        if (present(a5)) argv(5)%text = a5
        if (present(a6)) argv(6)%text = a6
        if (present(output)) then
            call run_program(argv, status, why, output)
        else
            call run_program(argv, status, why)
        end if
    end subroutine run
end program test_process
