! SPDX-License-Identifier: MIT
!> The pictures drawn from an output folder's CSV files (lambda_sweep.png, adapt.png) by a
!> plot script (from the installed share/nceig/scripts or the source tree's scripts/) with
!> gnuplot into the staging folder, so that the picture joins the committed set. Plotting
!> is optional: without gnuplot, or when the script fails, the run still succeeds and the
!> caller prints the returned note.
module plot_script
    use executable, only: scripts_directory
    use filesystem, only: file_exists
    use strings, only: text_t
    use process, only: run_program
    use gnuplot, only: gnuplot_available, quotable, path_argument, not_run_note
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
        integer :: exit_status
        character(len=:), allocatable :: plot_script, reason
        type(text_t) :: arguments(4)

        drawn = .false.
        plot_script = scripts_directory()//'/'//script
        if (.not. file_exists(plot_script)) then
            note = 'not drawn: '//plot_script//' is missing'
            return
        end if
        if (.not. quotable(directory//summary)) then
            note = 'not drawn: the output path holds a control character'
            return
        end if
        if (.not. gnuplot_available()) then
            note = 'not drawn: gnuplot is not installed (the CSV holds the data)'
            return
        end if
        ! Paths as arguments: no shell parses them (the script quotes them for gnuplot).
        ! Set one by one: gfortran 12 garbles [text_t(f(x)), ...] (an argument got another's
        ! bytes) when f returns an allocatable string.
        arguments(1)%text = 'bash'
        arguments(2)%text = path_argument(plot_script)
        arguments(3)%text = path_argument(directory)
        arguments(4)%text = path_argument(summary)
        call run_program(arguments, exit_status, reason)
        drawn = exit_status == 0
        note = not_run_note('bash', exit_status, reason)
        if (.not. drawn .and. note == '') &
            note = 'not drawn: the plot script failed; run bash '//plot_script// &
                   ' on the output directory to see why'
    end subroutine run_plot_script
end module plot_script
