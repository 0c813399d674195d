! SPDX-License-Identifier: MIT
!> The command line: the one-argument forms as before, --set options around one input file,
!> and each misuse refused with STATUS_BAD_INPUT.
program test_command_line
    use status, only: status_t, STATUS_BAD_INPUT
    use namelist_scan, only: text_t
    use command_line, only: command_t, read_command_line, parse_arguments
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t
    type(command_t) :: command
    type(status_t) :: stat

    t%name = 'test_command_line'

    ! ctest runs this program without arguments: the usage error of the program.
    call read_command_line(command, stat)
    call t%check('read_command_line: no argument is refused', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'one argument') > 0)

    call parse([character(len=9) :: '--help'])
    call t%check('parse_arguments: --help', stat%ok() .and. command%action == 'help')
    call parse([character(len=9) :: '-V'])
    call t%check('parse_arguments: -V', stat%ok() .and. command%action == 'version')
    call parse([character(len=9) :: 'a.nml'])
    call t%check('parse_arguments: an input file alone', stat%ok() .and. &
                 command%action == 'run' .and. command%input == 'a.nml' .and. &
                 size(command%settings) == 0)
    call parse([character(len=9) :: 'a.nml', 'b.nml'])
    call t%check('parse_arguments: two files without --set keep the old message', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'one argument') > 0)
    call parse([character(len=17) :: '--set', 'mesh%nx=3', 'a.nml', '--set', &
                'analysis%lambda=2'])
    call t%check('parse_arguments: settings in order, the file among them', stat%ok() .and. &
                 command%input == 'a.nml' .and. size(command%settings) == 2)
    if (size(command%settings) == 2) call t%check('parse_arguments: setting values', &
        command%settings(1)%text == 'mesh%nx=3' .and. &
        command%settings(2)%text == 'analysis%lambda=2')
    call parse([character(len=9) :: 'a.nml', '--set'])
    call t%check('parse_arguments: --set without a value', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'needs a value') > 0)
    call parse([character(len=9) :: '--set', 'mesh%nx=3'])
    call t%check('parse_arguments: --set without a file', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'input file') > 0)
    call parse([character(len=9) :: 'a.nml', '--sett', '--set', 'mesh%nx=3'])
    call t%check('parse_arguments: an unknown option with --set', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, '--sett') > 0)
    call parse([character(len=9) :: 'a.nml', '--set', 'mesh%nx=3', '-'//achar(27)//'[2J'])
    call t%check('parse_arguments: control bytes of an argument are not echoed', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, '-?[2J') > 0 .and. &
                 scan(stat%message, achar(27)) == 0)
    ! gfortran 12 never frees main-program allocatables: LeakSanitizer would report them.
    deallocate (command%action, command%input, command%settings)
    call t%report()

contains

    !> parse_arguments on `words` (trimmed), an array built one element at a time: an array
    !> constructor of text_t leaks its temporaries in gfortran 12 (LeakSanitizer).
    subroutine parse(words)
        character(len=*), intent(in) :: words(:)
        type(text_t), allocatable :: arguments(:)
        integer :: i
        allocate (arguments(size(words)))
        do i = 1, size(words)
            arguments(i)%text = trim(words(i))
        end do
        call parse_arguments(arguments, command, stat)
    end subroutine parse
end program test_command_line
