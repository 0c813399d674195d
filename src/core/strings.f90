! SPDX-License-Identifier: MIT
!> Number-to-text conversions for messages, file names and the stdout summaries. Every
!> module uses these rather than a local twin, so a count or a time reads the same everywhere.
module strings
    use kinds, only: wp, i8
    use ieee_arithmetic, only: ieee_is_nan
    implicit none
    private
    public :: to_string, zero_padded, short_real_text, seconds_text

    interface to_string
        module procedure integer_to_string, long_integer_to_string, real_to_string
    end interface to_string

contains

    pure function integer_to_string(i) result(text)
        integer, intent(in) :: i
        character(len=:), allocatable :: text
        character(len=24) :: buffer
        write (buffer, '(i0)') i
        text = trim(buffer)
    end function integer_to_string

    !> Counts that can pass 2**31: byte offsets, nnz of factors.
    pure function long_integer_to_string(i) result(text)
        integer(i8), intent(in) :: i
        character(len=:), allocatable :: text
        character(len=24) :: buffer
        write (buffer, '(i0)') i
        text = trim(buffer)
    end function long_integer_to_string

    !> Shortest readable form that still round-trips in messages: g0 with 17 digits is noisy,
    !> so use 10 significant digits, enough to name the offending value.
    pure function real_to_string(x) result(text)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: buffer
        write (buffer, '(g0.10)') x
        text = trim(adjustl(buffer))
    end function real_to_string

    !> `i` with leading zeros to `width` digits (mode_001.vtu).
    pure function zero_padded(i, width) result(text)
        integer, intent(in) :: i, width
        character(len=width) :: text
        character(len=16) :: fmt
        write (fmt, '(a, i0, a, i0, a)') '(i', width, '.', width, ')'
        write (text, fmt) i
    end function zero_padded

    !> `x` in scientific notation with `digits` decimals (2 unless given), no blanks:
    !> '1.23E-05' for backward errors, times and rcond in messages; digits = 5 names an
    !> offending input value ('2.00000E+11').
    pure function short_real_text(x, digits) result(text)
        real(wp), intent(in) :: x
        integer, intent(in), optional :: digits
        character(len=:), allocatable :: text
        character(len=48) :: buffer
        character(len=16) :: edit
        integer :: d
        logical :: wide
        d = 2
        if (present(digits)) d = digits
        ! es(d+7).d is the narrowest field that holds a sign and a 2-digit exponent; a
        ! 3-digit exponent needs e3, or the 'E' is dropped ('1.49+284')
        ! (NaN first: an ordered comparison with it traps in debug builds)
        wide = .false.
        if (.not. ieee_is_nan(x)) wide = abs(x) >= 1.0e98_wp .or. &
                                         (abs(x) > 0.0_wp .and. abs(x) < 1.0e-98_wp)
        if (wide) then
            write (edit, '(a, i0, a, i0, a)') '(es', d + 8, '.', d, 'e3)'
        else
            write (edit, '(a, i0, a, i0, a)') '(es', d + 7, '.', d, ')'
        end if
        write (buffer, edit) x
        text = trim(adjustl(buffer))
    end function short_real_text

    !> Seconds with three decimals and a leading zero ('0.042', '12.500') for the summaries.
    pure function seconds_text(t) result(text)
        real(wp), intent(in) :: t
        character(len=:), allocatable :: text
        character(len=16) :: buffer
        write (buffer, '(f0.3)') t
        text = trim(buffer)
        if (text(1:1) == '.') text = '0'//text
    end function seconds_text
end module strings
