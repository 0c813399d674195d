! SPDX-License-Identifier: MIT
!> lambda_sweep.png, drawn by plot_lambda_sweep.sh (from the installed share/nceig/scripts or
!> the source tree's scripts/) with gnuplot after the outputs are committed. Plotting is optional: without gnuplot, or when the script fails, the run still
!> succeeds and the caller prints the returned note.
module sweep_plot
    use executable, only: scripts_directory
    use filesystem, only: file_exists
    implicit none
    private
    public :: plot_lambda_sweep

contains

    !> Run the plot script on the output folder `directory` when gnuplot is on the PATH;
    !> `note` says what happened, in one line.
    subroutine plot_lambda_sweep(directory, note)
        character(len=*), intent(in) :: directory
        character(len=:), allocatable, intent(out) :: note
        integer :: exit_status, command_status
        character(len=:), allocatable :: plot_script

        plot_script = scripts_directory()//'/plot_lambda_sweep.sh'
        if (index(directory, "'") > 0) then
            note = 'not drawn: the output path contains a quote; run '//plot_script//' by hand'
            return
        end if
        if (.not. file_exists(plot_script)) then
            note = 'not drawn: '//plot_script//' is missing'
            return
        end if
        call execute_command_line('command -v gnuplot >/dev/null 2>&1', &
                                  exitstat=exit_status, cmdstat=command_status)
        if (command_status /= 0 .or. exit_status /= 0) then
            note = 'not drawn: gnuplot is not installed (the CSV holds the curve)'
            return
        end if
        call execute_command_line("bash '"//plot_script//"' '"//directory// &
                                  "' >/dev/null 2>&1", exitstat=exit_status, &
                                  cmdstat=command_status)
        if (command_status /= 0 .or. exit_status /= 0) then
            note = 'not drawn: the plot script failed; run bash '//plot_script//' '// &
                   directory//' to see why'
        else
            note = directory//'/lambda_sweep.png'
        end if
    end subroutine plot_lambda_sweep
end module sweep_plot
