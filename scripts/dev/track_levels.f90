! SPDX-License-Identifier: MIT
!> track_levels: pencil_tracking applied to the output of pencil_probe --profile over levels
!> (docs/thresholds.md). Reads from stdin the probe's lines of several levels, each level
!> begun by a line starting '# hp level' or '# level'; per level and side, the value nceig
!> would report (the real pencil value nearest zero) is followed back through the levels by
!> its profile, and the chain classified. One line per level and side:
!>   side level value | chain length, verdict, fitted factor, bar, limit, where, end shares
!> Built on demand: cmake --build build --target track_levels.
program track_levels
    use iso_fortran_env, only: input_unit, output_unit
    use kinds, only: wp
    use pencil_tracking, only: N_PROFILE_BINS, pencil_value_t, level_values_t, &
                               track_verdict_t, track_chain, classify_chain, TRACK_NAMES
    implicit none
    type(level_values_t), allocatable :: plus(:), minus(:)
    type(pencil_value_t) :: v
    character(len=4096) :: line
    integer :: ios, bar_at, n_levels
    real(wp) :: lambda, resolution, length

    allocate (plus(0), minus(0))
    resolution = 0.0_wp
    length = 1.0_wp
    n_levels = 0
    do
        read (input_unit, '(a)', iostat=ios) line
        if (ios /= 0) exit
        if (index(line, '# hp level') == 1 .or. index(line, '# level') == 1) then
            n_levels = n_levels + 1
            plus = [plus, level_values_t(values=[pencil_value_t ::])]
            minus = [minus, level_values_t(values=[pencil_value_t ::])]
            cycle
        end if
        if (index(line, '# free dofs') == 1) then   ! the smallest contact cell, relative
            read (line(index(line, 'cell') + 4:), *) resolution
            resolution = resolution/length
            cycle
        end if
        if (index(line, '# segment length') == 1) then
            read (line(17:), *) length
            cycle
        end if
        if (index(line, 'real ') /= 1 .or. n_levels == 0) cycle
        bar_at = index(line, '|')
        if (bar_at == 0) cycle
        read (line(6:), *) lambda
        v%lambda = lambda
        v%resolution = resolution
        read (line(bar_at + 1:), *) v%profile
        if (lambda > 0.0_wp) then
            plus(n_levels)%values = [plus(n_levels)%values, v]
        else
            minus(n_levels)%values = [minus(n_levels)%values, v]
        end if
    end do
    call report('lambda+', plus, 1.0_wp)
    call report('lambda-', minus, -1.0_wp)

contains

    subroutine report(name, levels, sign)
        character(len=*), intent(in) :: name
        type(level_values_t), intent(in) :: levels(:)
        real(wp), intent(in) :: sign
        type(track_verdict_t) :: verdict
        integer, allocatable :: chain(:)
        real(wp), allocatable :: values(:), profiles(:, :)
        integer :: k, nearest, j, first
        do k = 1, size(levels)
            if (size(levels(k)%values) == 0) then
                write (output_unit, '(a, i3, a)') name, k, '  none'
                cycle
            end if
            nearest = minloc(sign*levels(k)%values%lambda, dim=1)
            chain = track_chain(levels(:k), nearest)
            first = k - size(chain) + 1
            allocate (values(size(chain)), profiles(N_PROFILE_BINS, size(chain)))
            do j = 1, size(chain)
                values(j) = levels(first + j - 1)%values(chain(j))%lambda
                profiles(:, j) = levels(first + j - 1)%values(chain(j))%profile
            end do
            verdict = classify_chain(values, profiles)
            write (output_unit, '(a, i3, es20.11, a, i3, 1x, a10, 3es11.3, es20.11, f8.4, 2f7.3)') &
                name, k, values(size(values)), ' |', verdict%length, &
                TRACK_NAMES(verdict%kind), verdict%rate, verdict%bar, &
                merge(1.0_wp, 0.0_wp, verdict%has_limit), verdict%limit, verdict%where, &
                verdict%end_share
            deallocate (values, profiles)
        end do
    end subroutine report
end program track_levels
