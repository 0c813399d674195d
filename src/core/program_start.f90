! SPDX-License-Identifier: MIT
!> What the nceig program sets up before any library runs (program_start_c.c): its stop
!> signals (SIGTERM, SIGINT, SIGHUP, SIGXCPU) are blocked in every thread from the process's
!> start and taken by a thread of their own, so that no library's handler (METIS turns
!> SIGTERM into an error code) can swallow one: each ends the run by that signal, exit
!> status 128 + n, after one line on stderr. Used by main.f90 only: a test program that used
!> it would block the signals from its start.
module program_start
    use iso_c_binding, only: c_char, c_null_char
    implicit none
    private
    public :: start_signal_thread

    interface
        subroutine c_signal_thread_start(name) bind(C, name='nceig_signal_thread_start')
            import :: c_char
            character(kind=c_char), intent(in) :: name(*)
        end subroutine c_signal_thread_start
    end interface

contains

    !> Start the thread; `name` (the input file) is what the line of a stopped run names.
    subroutine start_signal_thread(name)
        character(len=*), intent(in) :: name
        call c_signal_thread_start(name//c_null_char)
    end subroutine start_signal_thread
end module program_start
