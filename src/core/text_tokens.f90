! SPDX-License-Identifier: MIT
!> Blank-separated tokens of a line of text: integers and decimal numbers read by hand and
!> checked strictly, for file readers whose input may be large or hostile (the Gmsh reader).
!> Positions `pos` index the line and move past what was read; blanks are space, tab and a
!> carriage return (of CRLF files).
module text_tokens
    use kinds, only: wp, i8
    implicit none
    private
    public :: integers_at, read_ints, read_int, read_reals, skip_tokens, skip_blanks
    public :: MAX_DECIMAL_EXPONENT

    !> Decimal numbers must be below 1e100 in magnitude: far beyond any physical quantity in
    !> SI units, and products of a few of them (Jacobians, squared diameters) stay finite.
    integer, parameter :: MAX_DECIMAL_EXPONENT = 99

contains

    !> True when `line` starts with size(values) integers, stored in `values`.
    logical function integers_at(line, values)
        character(len=*), intent(in) :: line
        integer, intent(out) :: values(:)
        integer :: pos
        pos = 1
        call read_ints(line, pos, values, integers_at)
    end function integers_at

    !> size(values) integers from `pos` on, as read_int reads each; not ok at the first miss.
    pure subroutine read_ints(line, pos, values, ok)
        character(len=*), intent(in) :: line
        integer, intent(inout) :: pos
        integer, intent(out) :: values(:)
        logical, intent(out) :: ok
        integer :: i
        ok = .true.
        values = 0
        do i = 1, size(values)
            call read_int(line, pos, values(i), ok)
            if (.not. ok) return
        end do
    end subroutine read_ints

    !> The integer starting at or after `pos` (blanks skipped); `pos` moves past it. Not ok
    !> when there is none, or it is followed by something other than a blank, or overflows.
    !> Hand-written because list-directed reads dominated the reading time of large files.
    pure subroutine read_int(line, pos, value, ok)
        character(len=*), intent(in) :: line
        integer, intent(inout) :: pos
        integer, intent(out) :: value
        logical, intent(out) :: ok
        integer(i8) :: accumulated
        integer :: digit, n_digits
        logical :: negative
        ok = .false.
        value = 0
        call skip_blanks(line, pos)
        if (pos > len(line)) return
        negative = line(pos:pos) == '-'
        if (negative .or. line(pos:pos) == '+') pos = pos + 1
        accumulated = 0
        n_digits = 0
        do while (pos <= len(line))
            digit = iachar(line(pos:pos)) - iachar('0')
            if (digit < 0 .or. digit > 9) exit
            accumulated = 10*accumulated + digit
            if (accumulated > huge(value)) return
            n_digits = n_digits + 1
            pos = pos + 1
        end do
        if (n_digits == 0) return
        if (pos <= len(line)) then
            if (.not. is_blank(line(pos:pos))) return
        end if
        value = int(accumulated)
        if (negative) value = -value
        ok = .true.
    end subroutine read_int

    !> size(values) reals from the blank-separated tokens at or after `pos` (moved past
    !> them); what follows on the line is not read (the parametric coordinates of MSH 4.1).
    !> Not ok unless each token is a decimal number ('-1.5', '2e-3') below 1e100 in
    !> magnitude: a list-directed read alone would accept NaN and Infinity, leave values
    !> unset on ',' and '/', repeat them on '3*1', and trap on an overflowing '1e999'.
    subroutine read_reals(line, pos, values, ok)
        character(len=*), intent(in) :: line
        integer, intent(inout) :: pos
        real(wp), intent(out) :: values(:)
        logical, intent(out) :: ok
        integer :: first, i, ios
        values = 0.0_wp
        call skip_blanks(line, pos)
        first = pos
        do i = 1, size(values)
            call skip_decimal(line, pos, ok)
            if (.not. ok) return
        end do
        ! The tokens are checked: one list-directed read of them all is safe, and fast.
        read (line(first:pos - 1), *, iostat=ios) values
        ok = ios == 0
    end subroutine read_reals

    !> Move `pos` past one token [+-]digits[.digits][(e|E|d|D)[+-]digits] (the mantissa may
    !> also be '.digits' or 'digits.') whose value is below 10**(MAX_DECIMAL_EXPONENT + 1)
    !> in magnitude; not ok otherwise.
    pure subroutine skip_decimal(line, pos, ok)
        character(len=*), intent(in) :: line
        integer, intent(inout) :: pos
        logical, intent(out) :: ok
        integer, parameter :: NONE = huge(1), EXPONENT_CAP = 100000
        integer :: n_digits, n_integer, leading, exponent, n_exponent_digits
        logical :: negative_exponent

        ok = .false.
        call skip_blanks(line, pos)
        if (pos > len(line)) return
        if (line(pos:pos) == '-' .or. line(pos:pos) == '+') pos = pos + 1
        ! leading: decimal exponent of the first non-zero digit, counted from the end of
        ! the integer part while in it (NONE while only zeros were seen).
        leading = NONE
        n_digits = 0
        do while (pos <= len(line))
            if (.not. is_digit(line(pos:pos))) exit
            n_digits = n_digits + 1
            if (leading == NONE .and. line(pos:pos) /= '0') leading = -n_digits
            pos = pos + 1
        end do
        n_integer = n_digits
        if (leading /= NONE) leading = leading + n_integer   ! 0 for '5', 1 for '12'
        if (pos <= len(line)) then
            if (line(pos:pos) == '.') then
                pos = pos + 1
                do while (pos <= len(line))
                    if (.not. is_digit(line(pos:pos))) exit
                    n_digits = n_digits + 1
                    if (leading == NONE .and. line(pos:pos) /= '0') &
                        leading = n_integer - n_digits             ! -1 for '0.5'
                    pos = pos + 1
                end do
            end if
        end if
        if (n_digits == 0) return
        exponent = 0
        if (pos <= len(line)) then
            if (index('eEdD', line(pos:pos)) > 0) then
                pos = pos + 1
                if (pos > len(line)) return
                negative_exponent = line(pos:pos) == '-'
                if (negative_exponent .or. line(pos:pos) == '+') pos = pos + 1
                n_exponent_digits = 0
                do while (pos <= len(line))
                    if (.not. is_digit(line(pos:pos))) exit
                    ! Capped: only whether it passes the bound matters.
                    exponent = min(10*exponent + iachar(line(pos:pos)) - iachar('0'), &
                                   EXPONENT_CAP)
                    n_exponent_digits = n_exponent_digits + 1
                    pos = pos + 1
                end do
                if (n_exponent_digits == 0) return
                if (negative_exponent) exponent = -exponent
            end if
        end if
        if (pos <= len(line)) then
            if (.not. is_blank(line(pos:pos))) return
        end if
        ok = leading == NONE
        if (.not. ok) ok = leading + exponent <= MAX_DECIMAL_EXPONENT
    end subroutine skip_decimal

    elemental logical function is_digit(c)
        character, intent(in) :: c
        is_digit = c >= '0' .and. c <= '9'
    end function is_digit

    !> Move `pos` past `n` blank-separated tokens of any kind.
    pure subroutine skip_tokens(line, pos, n, ok)
        character(len=*), intent(in) :: line
        integer, intent(inout) :: pos
        integer, intent(in) :: n
        logical, intent(out) :: ok
        integer :: i
        ok = .true.
        do i = 1, n
            call skip_blanks(line, pos)
            if (pos > len(line)) then
                ok = .false.
                return
            end if
            do while (pos <= len(line))
                if (is_blank(line(pos:pos))) exit
                pos = pos + 1
            end do
        end do
    end subroutine skip_tokens

    !> Move `pos` to the next non-blank character, or past the end of the line.
    pure subroutine skip_blanks(line, pos)
        character(len=*), intent(in) :: line
        integer, intent(inout) :: pos
        do while (pos <= len(line))
            if (.not. is_blank(line(pos:pos))) exit
            pos = pos + 1
        end do
    end subroutine skip_blanks

    elemental logical function is_blank(c)
        character, intent(in) :: c
        is_blank = c == ' ' .or. c == achar(9) .or. c == achar(13)
    end function is_blank
end module text_tokens
