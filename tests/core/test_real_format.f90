! SPDX-License-Identifier: MIT
!> real_to_text is the shortest decimal that reads back to the same binary64: checked on
!> random bit patterns (a fixed-seed xorshift stream, so every run sees the same ones), on
!> subnormals, on the extremes (huge, tiny, their neighbours) and on the layout the JSON
!> and the messages rely on (positional from 1e-5 to below 1e16, scientific beyond).
program test_real_format
    use kinds, only: wp, i8
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, &
                               ieee_negative_inf, ieee_is_finite
    use real_format, only: real_to_text, known_text
    use testing, only: test_suite_t
    implicit none

    integer, parameter :: N_RANDOM = 4000   !! patterns; about 0.5 s in Debug
    type(test_suite_t) :: t

    t%name = 'test_real_format'
    call check_random_patterns()
    call check_extremes()
    call check_layout()
    call check_known_text()
    call t%report()

contains

    !> Random 64-bit patterns, each as a real: every finite one prints shortest and reads
    !> back bit for bit; the others print as JSON's words for them.
    subroutine check_random_patterns()
        integer(i8) :: state
        real(wp) :: x
        integer :: i, n_finite, n_exact, n_shortest
        state = 88172645463325252_i8
        n_finite = 0
        n_exact = 0
        n_shortest = 0
        do i = 1, N_RANDOM
            state = ieor(state, ishft(state, 13))
            state = ieor(state, ishft(state, -7))
            state = ieor(state, ishft(state, 17))
            x = transfer(state, x)
            if (.not. ieee_is_finite(x)) cycle
            n_finite = n_finite + 1
            if (reads_back(x)) n_exact = n_exact + 1
            if (significant_digits(real_to_text(x)) == shortest_digits(x)) &
                n_shortest = n_shortest + 1
        end do
        ! random exponents: nearly all patterns are finite, most far outside 1e+-16
        call t%check('random bit patterns: most are finite numbers', n_finite > N_RANDOM*9/10)
        call t%check('random bit patterns: every finite one reads back exactly', &
                     n_exact == n_finite)
        call t%check('random bit patterns: every one with the fewest digits that do', &
                     n_shortest == n_finite)
    end subroutine check_random_patterns

    !> Subnormals, the extremes and their neighbours, powers of two and ten.
    subroutine check_extremes()
        real(wp) :: values(16)
        integer :: i
        logical :: all_back
        values = [transfer(1_i8, 1.0_wp), transfer(2_i8, 1.0_wp), &
                  transfer(4503599627370495_i8, 1.0_wp), &     ! largest subnormal
                  0.5_wp*tiny(1.0_wp), tiny(1.0_wp), nearest(tiny(1.0_wp), 1.0_wp), &
                  huge(1.0_wp), nearest(huge(1.0_wp), -1.0_wp), -huge(1.0_wp), &
                  epsilon(1.0_wp), 1.0_wp + epsilon(1.0_wp), nearest(1.0_wp, -1.0_wp), &
                  2.0_wp**(-1074 + 60), 1.0e-300_wp, 1.0e300_wp, 0.1_wp]
        all_back = .true.
        do i = 1, size(values)
            if (.not. reads_back(values(i))) all_back = .false.
            if (significant_digits(real_to_text(values(i))) /= shortest_digits(values(i))) &
                all_back = .false.
        end do
        call t%check('subnormals, tiny, huge and neighbours: shortest, read back exactly', &
                     all_back)
        call t%check('smallest subnormal is 5.0e-324', &
                     real_to_text(transfer(1_i8, 1.0_wp)) == '5.0e-324')
        call t%check('huge is 1.7976931348623157e308', &
                     real_to_text(huge(1.0_wp)) == '1.7976931348623157e308')
        call t%check('tiny is 2.2250738585072014e-308', &
                     real_to_text(tiny(1.0_wp)) == '2.2250738585072014e-308')
        call t%check('signed zeros: 0.0 and -0.0', all([real_to_text(0.0_wp) == '0.0', &
                     real_to_text(-0.0_wp) == '-0.0']))
        call t%check('non-finite values: NaN, Infinity, -Infinity', &
                     all([real_to_text(ieee_value(1.0_wp, ieee_quiet_nan)) == 'NaN', &
                     real_to_text(ieee_value(1.0_wp, ieee_positive_inf)) == 'Infinity', &
                     real_to_text(ieee_value(1.0_wp, ieee_negative_inf)) == '-Infinity']))
    end subroutine check_extremes

    !> Positional text from 1e-5 up to below 1e16, scientific outside; never an 'E' or a
    !> '+', so that every finite text is a JSON number.
    subroutine check_layout()
        call t%check('0.3 is 0.3, not 0.29999999999999999', real_to_text(0.3_wp) == '0.3')
        call t%check('200 is 200.0', real_to_text(200.0_wp) == '200.0')
        call t%check('-3.25e-7 is scientific', real_to_text(-3.25e-7_wp) == '-3.25e-7')
        call t%check('1e-5 is 0.00001, 1e-6 is 1.0e-6', all([real_to_text(1.0e-5_wp) == &
                     '0.00001', real_to_text(1.0e-6_wp) == '1.0e-6']))
        call t%check('1e15 is positional, 1e16 scientific', &
                     all([real_to_text(1.0e15_wp) == '1000000000000000.0', &
                     real_to_text(1.0e16_wp) == '1.0e16']))
        call t%check('2.5e20 is 2.5e20', real_to_text(2.5e20_wp) == '2.5e20')
        call t%check('1/3 needs 16 digits', real_to_text(1.0_wp/3.0_wp) == &
                     '0.3333333333333333')
    end subroutine check_layout

    subroutine check_known_text()
        call t%check('known_text: the value when known', known_text(.true., 0.5_wp) == '0.5')
        call t%check('known_text: empty when unknown', known_text(.false., 0.5_wp) == '')
        call t%check('known_text: the given word when unknown', &
                     known_text(.false., 0.5_wp, 'null') == 'null')
    end subroutine check_known_text

    !> The text of x read back by a list-directed read is x, bit for bit.
    logical function reads_back(x)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        real(wp) :: back
        integer :: ios
        text = real_to_text(x)
        read (text, *, iostat=ios) back
        reads_back = ios == 0 .and. transfer(back, 0_i8) == transfer(x, 0_i8) .and. &
                     index(text, 'E') == 0 .and. index(text, '+') == 0 .and. &
                     index(text, ' ') == 0
    end function reads_back

    !> The fewest significant digits d whose correctly rounded decimal (es format, d digits)
    !> reads back to x: if any d-digit decimal lies in x's rounding interval, the nearest
    !> one does. A candidate beyond huge's rounding interval (huge + half an ulp =
    !> 1.797693134862315807...e308) is not read: it would overflow (a trap in Debug).
    integer function shortest_digits(x)
        real(wp), intent(in) :: x
        character(len=*), parameter :: BEYOND_HUGE = '1.797693134862315807'
        character(len=40) :: buffer, edit
        character(len=len(BEYOND_HUGE)) :: mantissa
        real(wp) :: back
        integer :: ios, e_pos, first
        do shortest_digits = 1, 17
            write (edit, '(a, i0, a)') '(es40.', shortest_digits - 1, 'e3)'
            write (buffer, edit) x
            buffer = adjustl(buffer)
            first = merge(2, 1, buffer(1:1) == '-')
            e_pos = index(buffer, 'E')
            mantissa = buffer(first:e_pos - 1)//repeat('0', len(mantissa))
            if (buffer(e_pos:) == 'E+308' .and. lgt(mantissa, BEYOND_HUGE)) cycle
            read (buffer, *, iostat=ios) back
            if (ios == 0 .and. transfer(back, 0_i8) == transfer(x, 0_i8)) return
        end do
    end function shortest_digits

    !> Significant digits of a decimal text: its digits before the exponent, without the
    !> leading and trailing zeros.
    pure integer function significant_digits(text)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: digits
        integer :: i, last, first
        last = index(text, 'e') - 1
        if (last < 0) last = len(text)
        digits = ''
        do i = 1, last
            if (index('0123456789', text(i:i)) > 0) digits = digits//text(i:i)
        end do
        first = verify(digits, '0')
        last = verify(digits, '0', back=.true.)
        significant_digits = 0
        if (first > 0) significant_digits = last - first + 1
    end function significant_digits
end program test_real_format
