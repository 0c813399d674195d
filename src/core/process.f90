! SPDX-License-Identifier: MIT
!> Running a helper program (gnuplot) with an argument vector, through no
!> shell: a path holding a quote or `;` is one argument, never a command. Also whether a
!> program is on the PATH, and SIGPIPE. The C side is process_c.c (posix_spawnp, waitpid).
module process
    use iso_c_binding, only: c_char, c_int, c_null_char
    use strings, only: text_t, from_c_chars
    implicit none
    private
    public :: run_program, program_on_path, ignore_broken_pipe
    !> run_program's exit status when the program could not be run at all; other values are
    !> the program's exit status, or 128 + n when signal n ended it.
    integer, parameter, public :: PROGRAM_NOT_FOUND = -1    !! no such program (ENOENT)
    integer, parameter, public :: PROGRAM_NOT_STARTED = -2  !! EMFILE, EAGAIN, ENOMEM, ...

    integer, parameter :: ERROR_TEXT_CAPACITY = 256

    interface
        function c_run_program(args, count, output, error) bind(C, name='nceig_run_program') &
                result(status)
            import :: c_char, c_int
            character(kind=c_char), intent(in) :: args(*), output(*)
            integer(c_int), value :: count
            integer(c_int), intent(out) :: error
            integer(c_int) :: status
        end function c_run_program

        function c_find_program(name) bind(C, name='nceig_find_program') result(found)
            import :: c_char, c_int
            character(kind=c_char), intent(in) :: name(*)
            integer(c_int) :: found
        end function c_find_program

        function c_error_text(errnum, buffer, capacity) bind(C, name='nceig_error_text') &
                result(length)
            import :: c_char, c_int
            integer(c_int), value :: errnum, capacity
            character(kind=c_char), intent(out) :: buffer(*)
            integer(c_int) :: length
        end function c_error_text

        function c_ignore_broken_pipe() bind(C, name='nceig_ignore_broken_pipe') result(status)
            import :: c_int
            integer(c_int) :: status
        end function c_ignore_broken_pipe
    end interface

contains

    !> Run `arguments` (the program first, searched on the PATH unless it holds a '/'; each
    !> element one argument, exactly as given, trailing blanks included) with stdin from
    !> /dev/null and stdout and stderr into file `output` (to /dev/null without it), and
    !> wait for it. `exit_status` is its exit status, 128 + n for signal n, or
    !> PROGRAM_NOT_FOUND or PROGRAM_NOT_STARTED, for which `reason` is the system's
    !> sentence ('Too many open files'); it is '' otherwise.
    subroutine run_program(arguments, exit_status, reason, output)
        type(text_t), intent(in) :: arguments(:)
        integer, intent(out) :: exit_status
        character(len=:), allocatable, intent(out) :: reason
        character(len=*), intent(in), optional :: output
        character(kind=c_char, len=:), allocatable :: packed, output_path
        character(kind=c_char) :: buffer(ERROR_TEXT_CAPACITY)
        integer(c_int) :: error
        integer :: i

        packed = ''
        do i = 1, size(arguments)
            packed = packed//arguments(i)%text//c_null_char
        end do
        output_path = c_null_char
        if (present(output)) output_path = output//c_null_char
        exit_status = c_run_program(packed, int(size(arguments), c_int), output_path, error)
        reason = ''
        if (exit_status == PROGRAM_NOT_FOUND .or. exit_status == PROGRAM_NOT_STARTED) &
            reason = from_c_chars(buffer, int(c_error_text(error, buffer, ERROR_TEXT_CAPACITY)))
    end subroutine run_program

    !> Whether `name` is an executable file in a folder of the PATH (searched as exec does;
    !> no program, and no shell, is run).
    logical function program_on_path(name)
        character(len=*), intent(in) :: name
        program_on_path = c_find_program(name//c_null_char) /= 0
    end function program_on_path

    !> Make a write to a closed pipe fail (EPIPE) instead of ending the process by SIGPIPE.
    !> Programs run by run_program get the default action back.
    subroutine ignore_broken_pipe()
        integer(c_int) :: status
        status = c_ignore_broken_pipe()   ! fails only for an invalid signal number
    end subroutine ignore_broken_pipe
end module process
