! SPDX-License-Identifier: MIT
!> Progress lines on stdout, written and flushed at once: a run of minutes must not look
!> hung, and a log file shows how far a killed run got. A module procedure (not one internal
!> to the main program) so that pointing timings%listener at it needs no stack trampoline.
module console
    use iso_fortran_env, only: output_unit
    implicit none
    private
    public :: print_progress

contains

    !> A line that cannot be written (stdout a closed pipe) is dropped: the run goes on.
    subroutine print_progress(line)
        character(len=*), intent(in) :: line
        integer :: ios
        write (output_unit, '(a)', iostat=ios) line
        flush (output_unit, iostat=ios)
    end subroutine print_progress
end module console
