! SPDX-License-Identifier: MIT
!> Leave the program with an exit status and nothing else on standard error: gfortran's
!> `error stop n` prints "ERROR STOP n" and a backtrace after our one-line message.
module process_exit
    use iso_c_binding, only: c_int
    use iso_fortran_env, only: error_unit, output_unit
    use status, only: status_t
    implicit none
    private
    public :: exit_with, exit_now, stop_with, stop_on_failure, naming_file

    interface
        subroutine c_exit(code) bind(C, name='exit')
            import :: c_int
            integer(c_int), value :: code
        end subroutine c_exit
        subroutine c_exit_now(code) bind(C, name='_exit')
            import :: c_int
            integer(c_int), value :: code
        end subroutine c_exit_now
    end interface

contains

    !> Flush the standard units and exit with `code` (libgfortran closes other units at exit).
    subroutine exit_with(code)
        integer, intent(in) :: code
        integer :: ios
        flush (output_unit, iostat=ios)   ! a closed pipe does not change the status
        flush (error_unit, iostat=ios)
        call c_exit(int(code, c_int))
    end subroutine exit_with

    !> exit_with without the exit handlers: for a process whose libraries cannot finish (an
    !> OpenBLAS thread retrying an allocation under ulimit -v, which blas_shutdown would
    !> join for ever). Only before any file of the run is open.
    subroutine exit_now(code)
        integer, intent(in) :: code
        flush (output_unit)
        flush (error_unit)
        call c_exit_now(int(code, c_int))
    end subroutine exit_now

    !> One line `program: message` on standard error, then exit_with(code).
    subroutine stop_with(program, message, code)
        character(len=*), intent(in) :: program, message
        integer, intent(in) :: code
        write (error_unit, '(a)') program//': '//message
        call exit_with(code)
    end subroutine stop_with

    !> Nothing when `stat` is ok; else its message and code through stop_with (the programs'
    !> one way to end on an error that travelled up as a status). With `file` (the input
    !> file), a message that names no file gets it in front (naming_file).
    subroutine stop_on_failure(program, stat, file)
        character(len=*), intent(in) :: program
        type(status_t), intent(in) :: stat
        character(len=*), intent(in), optional :: file
        if (stat%ok()) return
        if (present(file)) then
            call stop_with(program, naming_file(stat%message, file), stat%code)
        else
            call stop_with(program, stat%message, stat%code)
        end if
    end subroutine stop_on_failure

    !> `message` with 'file: ' in front, unless it starts with a file of its own: `file`
    !> itself, or a first field (up to ': ') that is a path (holds a '/' or a '.', as
    !> 'meshes/a.msh:27' or a staging file). A solver's or a generated mesh's failure
    !> ('left eigenvector: ...', 'mesh: cell 1 is inverted ...') then names the input.
    pure function naming_file(message, file) result(named)
        character(len=*), intent(in) :: message, file
        character(len=:), allocatable :: named
        integer :: colon
        named = message
        if (len(file) == 0) return
        if (index(message, file) == 1) return
        colon = index(message, ': ')
        if (colon > 1) then
            if (scan(message(:colon - 1), '/.') > 0 .and. index(message(:colon - 1), ' ') == 0) &
                return
        end if
        named = file//': '//message
    end function naming_file
end module process_exit
