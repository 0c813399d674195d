! SPDX-License-Identifier: MIT
!> Leave the program with an exit status and nothing else on standard error: gfortran's
!> `error stop n` prints "ERROR STOP n" and a backtrace after our one-line message.
module process_exit
    use iso_c_binding, only: c_int
    use iso_fortran_env, only: error_unit, output_unit
    use status, only: status_t
    implicit none
    private
    public :: exit_with, exit_now, stop_with, stop_on_failure

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
    !> one way to end on an error that travelled up as a status).
    subroutine stop_on_failure(program, stat)
        character(len=*), intent(in) :: program
        type(status_t), intent(in) :: stat
        if (.not. stat%ok()) call stop_with(program, stat%message, stat%code)
    end subroutine stop_on_failure
end module process_exit
