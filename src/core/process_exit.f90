! SPDX-License-Identifier: MIT
!> Leave the program with an exit status and nothing else on standard error: gfortran's
!> `error stop n` prints "ERROR STOP n" and a backtrace after our one-line message.
module process_exit
    use iso_c_binding, only: c_int
    use iso_fortran_env, only: error_unit, output_unit
    implicit none
    private
    public :: exit_with

    interface
        subroutine c_exit(code) bind(C, name='exit')
            import :: c_int
            integer(c_int), value :: code
        end subroutine c_exit
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
end module process_exit
