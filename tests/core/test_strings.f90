! SPDX-License-Identifier: MIT
!> The text conversions every message uses: integers of both kinds round-trip exactly
!> (extremes included), reals to the digits they promise, and the name lists split, join
!> and normalise as the input file and the mesh reader expect; given_real_text gives the
!> fewest digits, three at least, that read back to the value given (a tolerance of
!> 0.999999 was printed 1.00E+00, which reads back as 1): read back and compared bit for bit.
program test_strings
    use kinds, only: wp, i8
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use iso_c_binding, only: c_char
    use strings, only: to_string, zero_padded, short_real_text, given_real_text, seconds_text, &
                       lowercase, &
                       split_names, split_words, count_names, normalized_list, quoted, &
                       one_of, joined, from_c_chars, printable, append_text, text_t, &
                       NAME_LEN, LIST_LEN, SHOWN_LEN
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_strings'
    call check_integers()
    call check_reals()
    call check_names()
    call check_lists()
    call check_texts()
    call three_digits_where_they_suffice()
    call more_digits_where_three_round()
    call every_text_reads_back()
    call t%report()

contains

    !> to_string of default and 64-bit integers reads back exactly, extremes included.
    subroutine check_integers()
        integer :: values(7), i, back
        integer(i8) :: long_values(5), long_back
        character(len=:), allocatable :: text
        logical :: ok
        values = [0, 1, -1, 42, -2147483647 - 1, 2147483647, 123456789]
        ok = .true.
        do i = 1, size(values)
            text = to_string(values(i))
            read (text, *) back
            ok = ok .and. back == values(i) .and. index(text, ' ') == 0
        end do
        call t%check('to_string(integer) reads back, no blanks, extremes included', ok)
        long_values = [huge(1_i8), -huge(1_i8) - 1_i8, 2147483648_i8, -1_i8, 0_i8]
        ok = .true.
        do i = 1, size(long_values)
            text = to_string(long_values(i))
            read (text, *) long_back
            ok = ok .and. long_back == long_values(i)
        end do
        call t%check('to_string(int64) reads back: counts past 2^31', ok .and. &
                     to_string(huge(1_i8)) == '9223372036854775807')
        call t%check('zero_padded: mode_001', zero_padded(1, 3) == '001' .and. &
                     zero_padded(42, 3) == '042' .and. zero_padded(123, 3) == '123')
    end subroutine check_integers

    !> to_string(real) holds 10 significant digits; short_real_text the digits asked for
    !> and a three-digit exponent where one is needed; seconds_text milliseconds.
    subroutine check_reals()
        real(wp) :: values(6), back
        integer :: i
        logical :: ok
        character(len=:), allocatable :: text
        values = [0.1_wp, -1.0_wp/3.0_wp, 6.02214076e23_wp, 1.0e-300_wp, 123456.789_wp, &
                  1.0e307_wp]
        ok = .true.
        do i = 1, size(values)
            text = to_string(values(i))
            read (text, *) back
            ! 10 significant digits: relative error at most half a unit of the 10th
            ok = ok .and. abs(back - values(i)) <= 5.0e-10_wp*abs(values(i))
        end do
        call t%check('to_string(real): 10 significant digits', ok)
        ok = .true.
        do i = 1, size(values)
            text = short_real_text(values(i))
            read (text, *) back
            ok = ok .and. abs(back - values(i)) <= 5.0e-3_wp*abs(values(i)) .and. &
                 index(text, 'E') > 0 .and. index(text, ' ') == 0
        end do
        call t%check('short_real_text: 3 significant digits, an exponent, no blanks', ok)
        call t%check('short_real_text: 1.23E-05 and 2.00000E+11', &
                     short_real_text(1.234e-5_wp) == '1.23E-05' .and. &
                     short_real_text(2.0e11_wp, 5) == '2.00000E+11')
        call t%check('short_real_text: three-digit exponents keep their E', &
                     short_real_text(1.0e-300_wp) == '1.00E-300' .and. &
                     short_real_text(1.5e284_wp) == '1.50E+284')
        call t%check('short_real_text: NaN is named', &
                     index(short_real_text(ieee_value(1.0_wp, ieee_quiet_nan)), 'NaN') > 0)
        call t%check('seconds_text: three decimals, a leading zero', &
                     seconds_text(0.0423_wp) == '0.042' .and. seconds_text(12.5_wp) == '12.500')
    end subroutine check_reals

    !> Names: case folded, blank-separated lists split, counted and normalised.
    subroutine check_names()
        character(len=NAME_LEN), allocatable :: names(:)
        character(len=LIST_LEN), allocatable :: words(:)
        character(len=:), allocatable :: tab_list
        tab_list = ' Left'//achar(9)//'RIGHT  top '
        call t%check('lowercase: ASCII capitals only', lowercase('Bottom_Side-2 '// &
                     char(196)//'B') == 'bottom_side-2 '//char(196)//'b')
        ! (allocated first: gfortran 12 -O3 warns of an unallocated one, see split_names)
        allocate (names(0))
        names = split_names(tab_list)
        call t%check('split_names: blanks and tabs separate, order kept', size(names) == 3 &
                     .and. names(1) == 'Left' .and. names(2) == 'RIGHT' .and. names(3) == 'top')
        names = split_names('  ')
        call t%check('split_names: an empty list has no names', size(names) == 0)
        names = split_names(repeat('x', NAME_LEN + 5))
        call t%check('split_names: a name longer than NAME_LEN is cut to it', &
                     size(names) == 1 .and. len_trim(names(1)) == NAME_LEN)
        call split_words(' a '//repeat('y', NAME_LEN + 5)//' b', words)
        call t%check('split_words: words are not cut', size(words) == 3 .and. &
                     len_trim(words(2)) == NAME_LEN + 5)
        call t%check('count_names', count_names(tab_list) == 3 .and. count_names('') == 0)
        call t%check('normalized_list: lowercase, single blanks', &
                     normalized_list(tab_list) == 'left right top')
    end subroutine check_names

    !> Quoting and joining for messages and help.
    subroutine check_lists()
        call t%check('quoted: trimmed, in single quotes', quoted('top  ') == "'top'")
        call t%check('one_of: the accepted values', &
                     one_of([character(len=5) :: 'p1', 'q1', 'p2']) == "'p1', 'q1', 'p2'")
        call t%check('joined: plain and bracketed', &
                     joined([character(len=3) :: 'a', 'bc']) == 'a, bc' .and. &
                     joined([character(len=3) :: 'a', 'bc'], before='<', after='>') == &
                     '<a>, <bc>')
        call t%check('joined: an empty list gives an empty text', &
                     joined([character(len=3) ::]) == '')
    end subroutine check_lists

    !> C strings, control characters, growing lists of texts.
    subroutine check_texts()
        character(kind=c_char) :: chars(8)
        type(text_t), allocatable :: texts(:)
        character(len=:), allocatable :: shown
        chars = ['n', 'c', 'e', 'i', 'g', achar(0), 'x', 'y']
        call t%check('from_c_chars: the first n characters', from_c_chars(chars, 5) == 'nceig' &
                     .and. len(from_c_chars(chars, 0)) == 0)
        call t%check('printable: control bytes become ?', &
                     printable('a'//achar(10)//'b'//achar(27)//'c'//achar(127)) == 'a?b?c?')
        shown = printable(repeat('z', 200))
        call t%check('printable: a long text is cut to SHOWN_LEN, ending in ...', &
                     len(shown) == SHOWN_LEN .and. shown(SHOWN_LEN - 2:) == '...')
        call t%check('printable: max_len', printable('abcdefghij', 6) == 'abc...')
        allocate (texts(0))
        call append_text(texts, 'first')
        call append_text(texts, '')
        call append_text(texts, 'third one')
        call t%check('append_text: texts of different lengths, in order', size(texts) == 3 &
                     .and. texts(1)%text == 'first' .and. len(texts(2)%text) == 0 .and. &
                     texts(3)%text == 'third one')
    end subroutine check_texts

    subroutine three_digits_where_they_suffice()
        call t%check('1e-8, 0.25 and 1e-300 keep the three digits of short_real_text', &
                     given_real_text(1.0e-8_wp) == '1.00E-08' .and. &
                     given_real_text(0.25_wp) == short_real_text(0.25_wp) .and. &
                     given_real_text(1.0e-300_wp) == '1.00E-300')
    end subroutine three_digits_where_they_suffice

    subroutine more_digits_where_three_round()
        call t%check('0.999999 is 9.99999E-01, not 1.00E+00; 1.23456789e-5 all nine digits', &
                     given_real_text(0.999999_wp) == '9.99999E-01' .and. &
                     given_real_text(1.23456789e-5_wp) == '1.23456789E-05')
    end subroutine more_digits_where_three_round

    subroutine every_text_reads_back()
        real(wp), parameter :: VALUES(5) = [0.1_wp, 1.0_wp/3.0_wp, 0.999999_wp, 7.0e-13_wp, &
                                            huge(1.0_wp)]
        character(len=:), allocatable :: text
        real(wp) :: back
        logical :: ok
        integer :: i, ios
        ok = .true.
        do i = 1, size(VALUES)
            text = given_real_text(VALUES(i))
            read (text, *, iostat=ios) back
            ok = ok .and. ios == 0 .and. abs(back - VALUES(i)) <= 0.0_wp
        end do
        call t%check('the text of 0.1, 1/3, 0.999999, 7e-13 and huge reads back exactly', ok)
    end subroutine every_text_reads_back
end program test_strings
