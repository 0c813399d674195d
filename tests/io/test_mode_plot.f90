! SPDX-License-Identifier: MIT
!> mode_001.png (mode_plot): a mode on two triangles is drawn as a PNG file (its 8-byte
!> signature) when gnuplot is installed, the scratch script removed afterwards, also for a
!> zero mode (no deformation to scale); not drawn, with a note saying why and no file left,
!> above MAX_PLOT_CELLS cells, when the script cannot be written, or for a path gnuplot
!> cannot quote.
program test_mode_plot
    use kinds, only: wp
    use testing, only: test_suite_t
    use mode_plot, only: plot_mode, MAX_PLOT_CELLS
    use gnuplot, only: gnuplot_available
    use filesystem, only: file_exists, remove_file
    use fixtures, only: read_text
    implicit none

    character(len=*), parameter :: PNG = 'test_mode_plot.png', SCRIPT = 'test_mode_plot.gp'
    !> The unit square as two triangles, corners anticlockwise.
    real(wp), parameter :: COORDS(2, 4) = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, &
                                                   1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
    integer, parameter :: CELLS(3, 2) = reshape([1, 2, 3, 1, 3, 4], [3, 2])
    type(test_suite_t) :: t

    t%name = 'test_mode_plot'
    call a_mode_is_drawn(t)
    call too_many_cells(t)
    call path_cases(t)
    call t%report()

contains

    subroutine a_mode_is_drawn(t)
        type(test_suite_t), intent(inout) :: t
        real(wp) :: u(2, 4)
        logical :: drawn, removed
        character(len=:), allocatable :: note, bytes
        integer :: trial
        if (.not. gnuplot_available()) then
            u = 0.0_wp
            call plot_mode(PNG, SCRIPT, 'mode 1', COORDS, CELLS, 3, u, drawn, note)
            call t%check('no gnuplot: not drawn, the note says so', .not. drawn .and. &
                         index(note, 'gnuplot is not installed') > 0)
            return
        end if
        do trial = 1, 2
            ! a shear of the top, then the zero mode (scale 0)
            u = 0.0_wp
            if (trial == 1) u(1, 3:4) = 0.5_wp
            call remove_file(PNG)
            call plot_mode(PNG, SCRIPT, 'mode 1', COORDS, CELLS, 3, u, drawn, note)
            call t%check(trim(merge('mode     ', 'zero mode', trial == 1))// &
                         ': drawn, no note', drawn .and. len(note) == 0)
            removed = .not. file_exists(SCRIPT)
            call t%check(trim(merge('mode     ', 'zero mode', trial == 1))// &
                         ': the script is removed', removed)
            bytes = ''
            if (file_exists(PNG)) call read_text(PNG, bytes)
            call t%check(trim(merge('mode     ', 'zero mode', trial == 1))// &
                         ': a PNG file', len(bytes) > 8 .and. bytes(1:min(8, len(bytes))) == &
                         char(137)//'PNG'//achar(13)//achar(10)//achar(26)//achar(10))
        end do
        call remove_file(PNG)
    end subroutine a_mode_is_drawn

    !> One cell more than MAX_PLOT_CELLS: no picture, no script, the note gives the count.
    subroutine too_many_cells(t)
        type(test_suite_t), intent(inout) :: t
        integer, allocatable :: many(:, :)
        real(wp) :: u(2, 4)
        logical :: drawn, written
        character(len=:), allocatable :: note
        allocate (many(3, MAX_PLOT_CELLS + 1), source=1)
        u = 1.0_wp
        call plot_mode(PNG, SCRIPT, 'big', COORDS, many, 3, u, drawn, note)
        written = file_exists(PNG)
        if (file_exists(SCRIPT)) written = .true.
        call t%check('too many cells: not drawn, nothing written', .not. (drawn .or. written))
        call t%check('too many cells: the note counts them', index(note, 'not drawn: ') == 1 &
                     .and. index(note, ' cells (more than ') > 0)
    end subroutine too_many_cells

    !> A script in a missing folder (with gnuplot), a picture path with a line feed: not
    !> drawn, neither file left, the note naming the script or the control character.
    subroutine path_cases(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: PICTURES(2) = [character(len=18) :: PNG, &
                                                      'a'//achar(10)//'b.png']
        character(len=*), parameter :: SCRIPTS(2) = [character(len=19) :: &
                                                     'no_such_folder/x.gp', SCRIPT]
        character(len=*), parameter :: NOTES(2) = [character(len=30) :: &
            'not drawn: no_such_folder/x.gp', 'control character']
        real(wp) :: u(2, 4)
        logical :: drawn, written
        character(len=:), allocatable :: note
        integer :: i
        u = 1.0_wp
        do i = 1, 2
            ! without gnuplot the first is not drawn for that reason
            if (i == 1) then
                if (.not. gnuplot_available()) cycle
            end if
            call plot_mode(trim(PICTURES(i)), trim(SCRIPTS(i)), 'mode 1', COORDS, CELLS, 3, u, &
                           drawn, note)
            written = file_exists(trim(PICTURES(i)))
            if (file_exists(trim(SCRIPTS(i)))) written = .true.
            call t%check('not drawn, nothing written, the note says: '//trim(NOTES(i)), &
                         .not. (drawn .or. written) .and. index(note, trim(NOTES(i))) > 0)
        end do
    end subroutine path_cases
end program test_mode_plot
