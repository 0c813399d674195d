! SPDX-License-Identifier: MIT
!> The strict token readers: integers and decimals are taken only when the whole token is
!> one, a real only below 10**(MAX_DECIMAL_EXPONENT + 1), and positions move past them.
program test_text_tokens
    use kinds, only: wp
    use text_tokens, only: integers_at, read_ints, read_int, read_reals, skip_tokens, &
                           skip_blanks, MAX_DECIMAL_EXPONENT
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t
    integer :: values(3), value, pos
    real(wp) :: reals(2)
    logical :: ok
    character(len=16) :: beyond

    t%name = 'test_text_tokens'

    ok = integers_at('4 -5 +6 tail', values)
    call t%check('integers_at: the leading integers of a line', ok .and. &
                 all(values == [4, -5, 6]))
    ok = integers_at('4 x 6', values)
    call t%check('integers_at: not with a word among them', .not. ok)

    pos = 3
    call read_ints('9 10 11 12', pos, values(:2), ok)
    call t%check('read_ints: from pos on, pos moved past them', &
                 ok .and. all(values(:2) == [10, 11]) .and. pos == 8)

    pos = 1
    call read_int('  2147483648', pos, value, ok)
    call t%check('read_int: an overflowing integer is refused', .not. ok)
    pos = 1
    call read_int('12a', pos, value, ok)
    call t%check('read_int: digits followed by a letter are refused', .not. ok)

    pos = 1
    call read_reals(' -1.5 2e-3 0.0 rest', pos, reals, ok)
    call t%check_close('read_reals: decimals read, the rest left', reals(2), 2.0e-3_wp, &
                       1.0e-15_wp)
    call t%check_close('read_reals: the first value', reals(1), -1.5_wp, 0.0_wp)
    call t%check('read_reals: ok, pos past the values', ok .and. pos == 11)
    pos = 1
    write (beyond, '(a, i0, a)') '1e', MAX_DECIMAL_EXPONENT + 1, ' 1'
    call read_reals(trim(beyond), pos, reals, ok)
    call t%check('read_reals: 1e100 is beyond the bound', .not. ok)
    pos = 1
    call read_reals('NaN 1', pos, reals, ok)
    call t%check('read_reals: NaN is not a decimal number', .not. ok)

    pos = 1
    call skip_tokens('"a b" c d', pos, 2, ok)
    call t%check('skip_tokens: blank-separated, quotes group nothing', ok .and. pos == 6)
    call skip_tokens('x', pos, 2, ok)
    call t%check('skip_tokens: not ok past the end', .not. ok)

    pos = 1
    call skip_blanks('  '//achar(9)//'x', pos)
    call t%check('skip_blanks: spaces and tabs', pos == 4)
    call t%report()
end program test_text_tokens
