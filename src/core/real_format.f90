! SPDX-License-Identifier: MIT
!> Shortest decimal text of a real that reads back to the same value. Messages, the help
!> text and JSON show 0.3 rather than 0.29999999999999999, and lose nothing.
module real_format
    use kinds, only: wp, i8
    use ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
    implicit none
    private
    public :: real_to_text, known_text

    integer, parameter :: MAX_DIGITS = 17          !! always enough for a binary64 round trip
    integer, parameter :: MIN_POSITIONAL_EXP = -5  !! 1.0e-5 is written 0.00001, 1.0e-6 is not
    integer, parameter :: MAX_POSITIONAL_EXP = 15  !! beyond, positional text gets unreadable

contains

    !> real_to_text(x) where `known`, else `missing` (default '': the empty field of a table
    !> row for a value that does not exist, such as no mu or a negative 'none' bar).
    function known_text(known, x, missing) result(text)
        logical, intent(in) :: known
        real(wp), intent(in) :: x
        character(len=*), intent(in), optional :: missing
        character(len=:), allocatable :: text
        if (known) then
            text = real_to_text(x)
        else if (present(missing)) then
            text = missing
        else
            text = ''
        end if
    end function known_text

    !> Shortest decimal text of `x` that reads back exactly with a Fortran list-directed
    !> read: positional for moderate magnitudes ('0.3', '200.0', '-0.0'), otherwise
    !> scientific ('1.0e-7', '2.5e20'). Finite results are valid JSON numbers; non-finite
    !> values give 'NaN', 'Infinity' or '-Infinity'.
    function real_to_text(x) result(text)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=48) :: buffer
        character(len=16) :: edit
        character(len=:), allocatable :: digits
        real(wp) :: back
        integer :: n_digits, exponent10, e_pos, ios, i

        if (ieee_is_nan(x)) then
            text = 'NaN'
            return
        else if (.not. ieee_is_finite(x)) then
            text = 'Infinity'
            if (x < 0.0_wp) text = '-Infinity'
            return
        else if (same_bits(abs(x), 0.0_wp)) then
            text = '0.0'
            if (sign(1.0_wp, x) < 0.0_wp) text = '-0.0'
            return
        end if

        ! Fewest significant digits that survive the round trip through text. Near huge()
        ! a short candidate can round up past it, and reading that back overflows (a trap
        ! in debug builds): there, take all digits at once.
        n_digits = 1
        if (abs(x) > 1.0e308_wp) n_digits = MAX_DIGITS + 1
        do while (n_digits <= MAX_DIGITS)
            write (edit, '(a, i0, a)') '(es48.', n_digits - 1, 'e3)'
            write (buffer, edit) x
            read (buffer, *, iostat=ios) back
            if (ios == 0 .and. same_bits(back, x)) exit
            n_digits = n_digits + 1
        end do
        if (n_digits > MAX_DIGITS) then
            write (edit, '(a, i0, a)') '(es48.', MAX_DIGITS - 1, 'e3)'
            write (buffer, edit) x
        end if

        ! buffer holds e.g. '  -3.25E-007': split into the digit string and the exponent.
        buffer = adjustl(buffer)
        e_pos = index(buffer, 'E')
        read (buffer(e_pos + 1:), *) exponent10
        digits = ''
        do i = 1, e_pos - 1
            if (index('0123456789', buffer(i:i)) > 0) digits = digits//buffer(i:i)
        end do
        do while (len(digits) > 1 .and. digits(len(digits):) == '0')
            digits = digits(:len(digits) - 1)
        end do

        if (exponent10 >= 0 .and. exponent10 <= MAX_POSITIONAL_EXP) then
            if (len(digits) <= exponent10 + 1) then
                text = digits//repeat('0', exponent10 + 1 - len(digits))//'.0'
            else
                text = digits(:exponent10 + 1)//'.'//digits(exponent10 + 2:)
            end if
        else if (exponent10 < 0 .and. exponent10 >= MIN_POSITIONAL_EXP) then
            text = '0.'//repeat('0', -exponent10 - 1)//digits
        else
            write (edit, '(i0)') exponent10
            if (len(digits) == 1) then
                text = digits//'.0e'//trim(edit)
            else
                text = digits(:1)//'.'//digits(2:)//'e'//trim(edit)
            end if
        end if
        if (buffer(1:1) == '-') text = '-'//text
    end function real_to_text

    !> Exact equality, stated as such (comparing reals with == draws a warning).
    elemental logical function same_bits(a, b)
        real(wp), intent(in) :: a, b
        same_bits = transfer(a, 0_i8) == transfer(b, 0_i8)
    end function same_bits
end module real_format
