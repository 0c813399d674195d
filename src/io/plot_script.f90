! SPDX-License-Identifier: MIT
!> The pictures drawn from an output folder's CSV files (lambda_sweep.png, adapt.png) by a
!> plot script (from the installed share/nceig/scripts or the source tree's scripts/) with
!> gnuplot into the staging folder, so that the picture joins the committed set. Plotting
!> is optional: without gnuplot, or when the script fails, the run still succeeds and the
!> caller prints the returned note.
module plot_script
    use executable, only: scripts_directory
    use filesystem, only: file_exists
    use gnuplot, only: gnuplot_available
    implicit none
    private
    public :: run_plot_script

contains

    !> Run the plot script `script` (a file name in the scripts folder) on `directory` with
    !> the summary.json `summary` when gnuplot is on the PATH: it draws its picture into
    !> `directory`. `drawn` tells whether it did; otherwise `note` says why, in one line.
    subroutine run_plot_script(script, directory, summary, drawn, note)
        character(len=*), intent(in) :: script, directory, summary
        logical, intent(out) :: drawn
        character(len=:), allocatable, intent(out) :: note
        integer :: exit_status, command_status
        character(len=:), allocatable :: plot_script

        drawn = .false.
        plot_script = scripts_directory()//'/'//script
        if (index(directory//summary, "'") > 0) then
            note = 'not drawn: the output path contains a quote; run '//plot_script//' by hand'
            return
        end if
        if (.not. file_exists(plot_script)) then
            note = 'not drawn: '//plot_script//' is missing'
            return
        end if
        if (.not. gnuplot_available()) then
            note = 'not drawn: gnuplot is not installed (the CSV holds the data)'
            return
        end if
        call execute_command_line("bash '"//plot_script//"' '"//directory//"' '"//summary// &
                                  "' >/dev/null 2>&1", exitstat=exit_status, &
                                  cmdstat=command_status)
        drawn = command_status == 0 .and. exit_status == 0
        note = ''
        if (.not. drawn) note = 'not drawn: the plot script failed; run bash '//plot_script// &
                                ' on the output directory to see why'
    end subroutine run_plot_script
end module plot_script
