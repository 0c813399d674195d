! SPDX-License-Identifier: MIT
!> gnuplot draws the pictures (mode_001.png, lambda_sweep.png) when it is installed; it is
!> optional at run time, so every picture first asks whether it is there.
module gnuplot
    implicit none
    private
    public :: gnuplot_available

contains

    !> Whether `gnuplot` is on the PATH.
    logical function gnuplot_available()
        integer :: exit_status, command_status
        call execute_command_line('command -v gnuplot >/dev/null 2>&1', &
                                  exitstat=exit_status, cmdstat=command_status)
        gnuplot_available = command_status == 0 .and. exit_status == 0
    end function gnuplot_available
end module gnuplot
