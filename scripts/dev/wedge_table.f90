! SPDX-License-Identifier: MIT
!> wedge_table: the tables of docs/thresholds.md from wedge_exponents. Built on demand:
!> cmake --build build --target wedge_table && build/wedge_table
!> 1. the lambda at which a real exponent of an end of Gamma_C crosses 0 (contact-free: any
!>    nu; contact-clamped: per nu), by opening angle;
!> 2. for the corners of the bodies of issue 34, the real exponent that crosses 0, at local
!>    lambdas around its crossing.
program wedge_table
    use iso_fortran_env, only: output_unit
    use kinds, only: wp
    use wedge_exponents, only: wedge_roots, contact_free_crossing, &
                               contact_clamped_crossing, &
                               WEDGE_CONTACT, WEDGE_FREE, WEDGE_CLAMPED
    implicit none
    real(wp), parameter :: PI = acos(-1.0_wp)
    real(wp), parameter :: ANGLES(8) = [30.0_wp, 45.0_wp, 60.0_wp, 90.0_wp, 120.0_wp, &
                                        135.0_wp, 150.0_wp, 180.0_wp]
    real(wp), parameter :: NUS(4) = [0.1_wp, 0.2_wp, 0.3_wp, 0.45_wp]
    real(wp), parameter :: OFFSETS(9) = [-4.0_wp, -3.0_wp, -2.0_wp, -1.0_wp, -0.5_wp, 0.0_wp, &
                                         0.5_wp, 1.0_wp, 2.0_wp]
    integer :: i, j

    write (output_unit, '(a)') '| angle | contact-free | contact-clamped, nu = 0.1 | 0.2 | 0.3 '// &
        '| 0.45 |'
    write (output_unit, '(a)') '|---|---|---|---|---|---|'
    do i = 1, size(ANGLES)
        write (output_unit, '(a, f5.0, a, a, 4(a, a), a)') '| ', ANGLES(i), ' | ', &
            text(contact_free_crossing(ANGLES(i)*PI/180.0_wp)), &
            (' | ', text(contact_clamped_crossing(ANGLES(i)*PI/180.0_wp, NUS(j))), j=1, 4), ' |'
    end do
    write (output_unit, '(a)') ''
    call exponent_table('contact-free 90', WEDGE_FREE, 90.0_wp, [0.1_wp, 0.3_wp])
    call exponent_table('contact-free 135', WEDGE_FREE, 135.0_wp, [0.1_wp, 0.3_wp])
    call exponent_table('contact-free 45', WEDGE_FREE, 45.0_wp, [0.3_wp])
    call exponent_table('contact-clamped 90', WEDGE_CLAMPED, 90.0_wp, [0.1_wp, 0.3_wp])
    call exponent_table('contact-clamped 60', WEDGE_CLAMPED, 60.0_wp, [0.3_wp])

contains

    function text(x) result(s)
        real(wp), intent(in) :: x
        character(len=12) :: s
        if (abs(x) >= huge(1.0_wp)) then
            s = 'none'
        else
            write (s, '(f8.4)') x
        end if
    end function text

    !> One row per nu: at local lambdas around the crossing, the real exponent nearest 0 in
    !> (-1, 1) (the one that crosses; '-' where there is none).
    subroutine exponent_table(name, far, angle, nus_here)
        character(len=*), intent(in) :: name
        integer, intent(in) :: far
        real(wp), intent(in) :: angle, nus_here(:)
        complex(wp), allocatable :: r(:)
        logical :: complete
        real(wp) :: crossing, lambda
        integer :: k, l, best
        write (output_unit, '(a, *(a, f5.1))', advance='no') '| '//name// &
            ', nu \ lambda - crossing', (' | ', OFFSETS(l), l=1, size(OFFSETS))
        write (output_unit, '(a)') ' | crossing |'
        write (output_unit, '(*(a))') '|---', ('|---', l=1, size(OFFSETS)), '|---|'
        do k = 1, size(nus_here)
            if (far == WEDGE_FREE) then
                crossing = contact_free_crossing(angle*PI/180.0_wp)
            else
                crossing = contact_clamped_crossing(angle*PI/180.0_wp, nus_here(k))
            end if
            write (output_unit, '(a, f4.2)', advance='no') '| ', nus_here(k)
            do l = 1, size(OFFSETS)
                lambda = crossing + OFFSETS(l)
                call wedge_roots(WEDGE_CONTACT, far, angle*PI/180.0_wp, nus_here(k), lambda, &
                                 -0.999_wp, 0.999_wp, 0.5_wp, r, complete)
                r = pack(r, abs(aimag(r)) <= 1.0e-9_wp)
                if (size(r) == 0) then
                    write (output_unit, '(a)', advance='no') ' | -'
                else
                    best = minloc(abs(real(r)), dim=1)
                    write (output_unit, '(a, f7.3)', advance='no') ' | ', real(r(best))
                end if
            end do
            write (output_unit, '(a, f8.4, a)') ' | ', crossing, ' |'
        end do
        write (output_unit, '(a)') ''
    end subroutine exponent_table
end program wedge_table
