! SPDX-License-Identifier: MIT
!> mode_001.png: the deformed mesh coloured by |u| of a mode, drawn by gnuplot into the staging
!> folder so that it joins the run's set of files, for a look at the shape without ParaView.
!> Optional: without gnuplot, on a mesh too large to draw cell by cell, or when gnuplot fails,
!> the run still succeeds and `note` says why there is no picture.
module mode_plot
    use kinds, only: wp
    use strings, only: to_string, short_real_text
    use filesystem, only: remove_file
    use gnuplot, only: not_drawable_note, gnuplot_string, path_argument, run_gnuplot
    implicit none
    private
    public :: plot_mode, MAX_PLOT_CELLS

    !> Above this many cells gnuplot takes many seconds and the picture is a blur: the VTU is
    !> the way to look at such a mode.
    integer, parameter :: MAX_PLOT_CELLS = 40000
    !> The largest displacement is drawn as this fraction of the mesh's diameter (the
    !> diagonal of its bounding box).
    real(wp), parameter :: DEFORMATION_FRACTION = 0.1_wp

contains

    !> Draw `png` from the corners (n_corners per cell, anticlockwise first in `cells`) moved
    !> by `u` (2, n_nodes), scaled for display, each cell coloured by its mean |u|. `script`
    !> is a scratch file, removed afterwards. `drawn` tells whether `png` was written.
    subroutine plot_mode(png, script, title, coords, cells, n_corners, u, drawn, note)
        character(len=*), intent(in) :: png, script, title
        real(wp), intent(in) :: coords(:, :), u(:, :)
        integer, intent(in) :: cells(:, :), n_corners
        logical, intent(out) :: drawn
        character(len=:), allocatable, intent(out) :: note
        real(wp) :: scale, diameter, u_max, magnitude
        integer :: unit, ios, cell, a
        character(len=512) :: msg

        drawn = .false.
        if (size(cells, 2) > MAX_PLOT_CELLS) then
            note = 'not drawn: '//to_string(size(cells, 2))//' cells (more than '// &
                   to_string(MAX_PLOT_CELLS)//'); open the mode''s VTU file in ParaView'
            return
        end if
        note = not_drawable_note(png, 'the VTU files hold the modes')
        if (len(note) > 0) return
        diameter = norm2(maxval(coords, dim=2) - minval(coords, dim=2))
        u_max = maxval(norm2(u, dim=1))
        scale = 0.0_wp
        if (u_max > 0.0_wp) scale = DEFORMATION_FRACTION*diameter/u_max

        open (newunit=unit, file=script, status='replace', action='write', iostat=ios, &
              iomsg=msg)
        if (ios /= 0) then
            note = 'not drawn: '//script//': '//trim(msg)
            return
        end if
        write (unit, '(a)', iostat=ios) 'set terminal pngcairo size 900,800 noenhanced', &
            'set output '//gnuplot_string(path_argument(png)), 'set size ratio -1', &
            'set palette rgb 33,13,10', 'set title '//gnuplot_string(title), &
            "set xlabel 'x + "//short_real_text(scale)// &
            " u_x  [length]  (deformed: largest |u| drawn as 1/10 of the body''s diagonal)'", &
            "set ylabel 'y + "//short_real_text(scale)//" u_y  [length]'", &
            "set cblabel '|u| (mode normalised to largest entry 1)'", '$cells << EOD'
        do cell = 1, size(cells, 2)
            if (ios /= 0) exit
            magnitude = sum(norm2(u(:, cells(1:n_corners, cell)), dim=1))/real(n_corners, wp)
            do a = 1, n_corners
                associate (node => cells(a, cell))
                    write (unit, '(3(es16.8e3, 1x))', iostat=ios) &
                        coords(:, node) + scale*u(:, node), magnitude
                end associate
            end do
            write (unit, '(a)', iostat=ios) ''
        end do
        write (unit, '(a)', iostat=ios) 'EOD', 'plot $cells using 1:2:3 with polygons '// &
            'fillcolor palette z fillstyle solid 1.0 border lc rgb ''#404040'' notitle'
        close (unit, iostat=ios)
        if (ios /= 0) then
            call remove_file(script)
            note = 'not drawn: the gnuplot script could not be written'
            return
        end if
        call run_gnuplot(script, png, drawn, note)
    end subroutine plot_mode
end module mode_plot
