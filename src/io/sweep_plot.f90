! SPDX-License-Identifier: MIT
!> lambda_sweep.png, drawn by plot_lambda_sweep.sh (from the installed share/nceig/scripts or
!> the source tree's scripts/) with gnuplot into the staging folder, so that the picture
!> joins the committed set. Plotting is optional: without gnuplot, or when the script fails,
!> the run still succeeds and the caller prints the returned note.
module sweep_plot
    use executable, only: scripts_directory
    use filesystem, only: file_exists
    use gnuplot, only: gnuplot_available
    implicit none
    private
    public :: plot_lambda_sweep

contains

    !> Run the plot script on `directory` (holding lambda_sweep.csv) with the summary.json
    !> `summary` when gnuplot is on the PATH: it draws directory/lambda_sweep.png. `drawn`
    !> tells whether it did; otherwise `note` says why, in one line.
    subroutine plot_lambda_sweep(directory, summary, drawn, note)
        character(len=*), intent(in) :: directory, summary
        logical, intent(out) :: drawn
        character(len=:), allocatable, intent(out) :: note
        integer :: exit_status, command_status
        character(len=:), allocatable :: plot_script

        drawn = .false.
        plot_script = scripts_directory()//'/plot_lambda_sweep.sh'
        if (index(directory//summary, "'") > 0) then
            note = 'not drawn: the output path contains a quote; run '//plot_script//' by hand'
            return
        end if
        if (.not. file_exists(plot_script)) then
            note = 'not drawn: '//plot_script//' is missing'
            return
        end if
        if (.not. gnuplot_available()) then
            note = 'not drawn: gnuplot is not installed (the CSV holds the curve)'
            return
        end if
        call execute_command_line("bash '"//plot_script//"' '"//directory//"' '"//summary// &
                                  "' >/dev/null 2>&1", exitstat=exit_status, &
                                  cmdstat=command_status)
        drawn = command_status == 0 .and. exit_status == 0
        note = ''
        if (.not. drawn) note = 'not drawn: the plot script failed; run bash '//plot_script// &
                                ' on the output directory to see why'
    end subroutine plot_lambda_sweep
end module sweep_plot
