! SPDX-License-Identifier: MIT
!> The command line of nceig: `INPUT.nml`, `--help` or `--version` alone, or an input file
!> with `--set group%variable=value` options. Parsed here, away from the program, so that
!> its rules are tested; the program only acts on the result.
module command_line
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: text_t, append_text, printable
    implicit none
    private
    public :: command_t, read_command_line, parse_arguments, command_argument

    !> What the command line asks for.
    type :: command_t
        character(len=:), allocatable :: action    !! 'run', 'help' or 'version'
        character(len=:), allocatable :: input     !! the namelist file of a run
        type(text_t), allocatable :: settings(:)   !! values of the --set options, in order
    end type command_t

    character(len=*), parameter :: SET_USAGE = &
        'nceig INPUT.nml [--set group%variable=value]...'

contains

    !> parse_arguments on the arguments of this process.
    subroutine read_command_line(command, stat)
        type(command_t), intent(out) :: command
        type(status_t), intent(out) :: stat
        type(text_t), allocatable :: arguments(:)
        integer :: i, length
        allocate (arguments(command_argument_count()))
        do i = 1, size(arguments)
            call get_command_argument(i, length=length)
            allocate (character(len=length) :: arguments(i)%text)
            call get_command_argument(i, arguments(i)%text)
        end do
        call parse_arguments(arguments, command, stat)
    end subroutine read_command_line

    !> The command of `arguments`. Without --set, exactly one argument: the input file,
    !> --help (-h) or --version (-V). With it, one input file anywhere among the options.
    !> A misuse is STATUS_BAD_INPUT with a one-line message.
    subroutine parse_arguments(arguments, command, stat)
        type(text_t), intent(in) :: arguments(:)
        type(command_t), intent(out) :: command
        type(status_t), intent(out) :: stat
        integer :: i

        command%action = 'run'
        command%input = ''
        allocate (command%settings(0))
        if (.not. any([(arguments(i)%text == '--set', i=1, size(arguments))])) then
            if (size(arguments) /= 1) then
                call stat%fail(STATUS_BAD_INPUT, 'expected one argument: nceig INPUT.nml | ' &
                               //'--help | --version')
                return
            end if
            select case (arguments(1)%text)
            case ('--help', '-h')
                command%action = 'help'
            case ('--version', '-V')
                command%action = 'version'
            case default
                command%input = arguments(1)%text
            end select
            return
        end if

        i = 1
        do while (i <= size(arguments))
            associate (argument => arguments(i)%text)
                if (argument == '--set') then
                    if (i == size(arguments)) then
                        call stat%fail(STATUS_BAD_INPUT, '--set needs a value: '//SET_USAGE)
                        return
                    end if
                    call append_text(command%settings, arguments(i + 1)%text)
                    i = i + 2
                    cycle
                else if (argument(1:min(1, len(argument))) == '-') then
                    call stat%fail(STATUS_BAD_INPUT, 'unexpected option '''//printable(argument) &
                                   //''' with --set: expected '//SET_USAGE)
                    return
                else if (len(command%input) > 0) then
                    call stat%fail(STATUS_BAD_INPUT, 'two input files, ''' &
                                   //printable(command%input)//''' and ''' &
                                   //printable(argument)//''': expected '//SET_USAGE)
                    return
                end if
                command%input = argument
            end associate
            i = i + 1
        end do
        if (len(command%input) == 0) then
            call stat%fail(STATUS_BAD_INPUT, '--set without an input file: expected ' &
                           //SET_USAGE)
        end if
    end subroutine parse_arguments

    !> Argument `i` of this process, whole (any length).
    function command_argument(i) result(text)
        integer, intent(in) :: i
        character(len=:), allocatable :: text
        integer :: length
        call get_command_argument(i, length=length)
        allocate (character(len=length) :: text)
        if (length > 0) call get_command_argument(i, text)
    end function command_argument
end module command_line
