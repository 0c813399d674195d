! SPDX-License-Identifier: MIT
!> gnuplot draws the pictures (mode_001.png, adapt.png, lambda_sweep.png) when it is
!> installed; it is optional at run time, so every picture first asks whether it is there.
!> Paths reach it as program arguments or as gnuplot strings, never through a shell.
module gnuplot
    use process, only: program_on_path, run_program, PROGRAM_NOT_FOUND, PROGRAM_NOT_STARTED
    use filesystem, only: remove_file
    use strings, only: text_t
    implicit none
    private
    public :: gnuplot_available, gnuplot_string, quotable, path_argument, not_run_note, &
              not_drawable_note
    public :: run_gnuplot

contains

    !> Whether `gnuplot` is on the PATH (looked up in C: no shell is run).
    logical function gnuplot_available()
        gnuplot_available = program_on_path('gnuplot')
    end function gnuplot_available

    !> Why a picture at `png` cannot be drawn, '' when it can: a path gnuplot cannot quote,
    !> or no gnuplot (`data_note` then says where the data are instead).
    function not_drawable_note(png, data_note) result(note)
        character(len=*), intent(in) :: png, data_note
        character(len=:), allocatable :: note
        note = ''
        if (.not. quotable(png)) then
            note = 'not drawn: the output path holds a control character'
        else if (.not. gnuplot_available()) then
            note = 'not drawn: gnuplot is not installed ('//data_note//')'
        end if
    end function not_drawable_note

    !> `text` as a gnuplot single-quoted string: a quote is written twice, the one escape
    !> such strings have (backslashes are not escapes there).
    pure function gnuplot_string(text) result(quoted)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: quoted
        integer :: i
        quoted = "'"
        do i = 1, len(text)
            if (text(i:i) == "'") then
                quoted = quoted//"''"
            else
                quoted = quoted//text(i:i)
            end if
        end do
        quoted = quoted//"'"
    end function gnuplot_string

    !> Whether gnuplot_string can hold `text`: a line feed or another control byte cannot be
    !> inside a single-quoted string, and would end the command there.
    pure logical function quotable(text)
        character(len=*), intent(in) :: text
        integer :: i
        quotable = .true.
        do i = 1, len(text)
            if (iachar(text(i:i)) < 32 .or. iachar(text(i:i)) == 127) quotable = .false.
        end do
    end function quotable

    !> `path` as a program argument or gnuplot file name: a relative path starting with '-'
    !> (taken for an option) or '~' (expanded by gnuplot) gets './' in front.
    pure function path_argument(path) result(argument)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: argument
        argument = path
        if (len(path) > 0) then
            if (path(1:1) == '-' .or. path(1:1) == '~') argument = './'//path
        end if
    end function path_argument

    !> The note for a `program` that run_program could not run (`exit_status` from it, with
    !> its `reason`): missing, or the system's reason it did not start ('Too many open
    !> files'), which is not the same thing. '' for a program that ran.
    function not_run_note(program, exit_status, reason) result(note)
        character(len=*), intent(in) :: program, reason
        integer, intent(in) :: exit_status
        character(len=:), allocatable :: note
        note = ''
        if (exit_status == PROGRAM_NOT_FOUND) then
            note = 'not drawn: '//program//' is not installed'
        else if (exit_status == PROGRAM_NOT_STARTED) then
            note = 'not drawn: '//program//' could not be started: '//reason
        end if
    end function not_run_note

    !> Run gnuplot on the file `script` (removed afterwards), which draws `picture`.
    !> `drawn` tells whether it did; otherwise `note` says why, and a partial picture is
    !> removed.
    subroutine run_gnuplot(script, picture, drawn, note)
        character(len=*), intent(in) :: script, picture
        logical, intent(out) :: drawn
        character(len=:), allocatable, intent(out) :: note
        character(len=:), allocatable :: reason
        type(text_t) :: arguments(2)
        integer :: exit_status
        ! gnuplot reads the script named by its argument; no shell parses the path. Set one
        ! by one: gfortran 12 garbles [text_t(f(x)), ...] when f returns an allocatable string.
        arguments(1)%text = 'gnuplot'
        arguments(2)%text = path_argument(script)
        call run_program(arguments, exit_status, reason)
        call remove_file(script)
        drawn = exit_status == 0
        note = not_run_note('gnuplot', exit_status, reason)
        if (drawn) return
        call remove_file(picture)
        if (note == '') note = 'not drawn: gnuplot failed on '//picture
    end subroutine run_gnuplot
end module gnuplot
