! SPDX-License-Identifier: MIT
!> summary.json's writer: exact text, null for non-finite reals, exact round trip of reals,
!> arrays and objects as members.
program test_json_writer
    use kinds, only: wp, i8
    use status, only: status_t
    use json_writer, only: json_object_t
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
    use testing, only: test_suite_t
    use fixtures, only: file_text
    implicit none
    type(test_suite_t) :: t
    type(json_object_t) :: object, numbers, arrays, inner, empty, nested
    type(status_t) :: stat
    character(len=:), allocatable :: text, expected
    character(len=*), parameter :: NL = new_line('a')
    real(wp), parameter :: SAMPLES(*) = [0.1_wp, 1.0_wp/3.0_wp, -2.5e-300_wp, 6.02214076e23_wp, &
                                         huge(1.0_wp), tiny(1.0_wp), 1.0_wp + epsilon(1.0_wp), &
                                         123456.789_wp, -0.0_wp, 1.0e-5_wp, 1.0e16_wp]
    real(wp) :: back
    integer :: i, ios

    t%name = 'test_json_writer'

    call object%add_string('analysis', 'eigen')
    call object%add_integer('n_nodes', 81)
    call object%add_integer('nnz', 3000000000_i8)
    call object%add_real('lambda', 5.0_wp)
    call object%add_real('tol', 0.25_wp)
    call object%add_null('critical_c_t')
    call object%add_logical('converged', .true.)
    call object%add_real_or_null('lowest_positive_mu', 1.5_wp, .false.)
    call object%add_real_or_null('max_residual', 1.0e-15_wp, .true.)
    call object%add_real('nan', ieee_value(1.0_wp, ieee_quiet_nan))
    call object%add_real('inf', ieee_value(1.0_wp, ieee_positive_inf))
    call object%add_string('note', 'say "hi"\ tab'//achar(9)//'line'//NL//'bell'//achar(7))
    call object%add_integer('n_nodes', 82)   ! a repeated key replaces the value in place

    expected = '{'//NL &
               //'  "analysis": "eigen",'//NL &
               //'  "n_nodes": 82,'//NL &
               //'  "nnz": 3000000000,'//NL &
               //'  "lambda": 5.0,'//NL &
               //'  "tol": 0.25,'//NL &
               //'  "critical_c_t": null,'//NL &
               //'  "converged": true,'//NL &
               //'  "lowest_positive_mu": null,'//NL &
               //'  "max_residual": 1.0e-15,'//NL &
               //'  "nan": null,'//NL &
               //'  "inf": null,'//NL &
               //'  "note": "say \"hi\"\\ tab\tline\nbell\u0007"'//NL &
               //'}'
    call object%write('object.json', stat)
    call t%check('write succeeds', stat%ok())
    text = file_text('object.json', NL)
    call t%check('exact text of a small object', text == expected//NL)
    if (text /= expected//NL) print '(a)', text

    call t%check('empty object', numbers%to_text() == '{}')

    ! Every number written must read back to exactly the same bits.
    do i = 1, size(SAMPLES)
        call numbers%add_real('x', SAMPLES(i))
        text = numbers%to_text()
        text = text(index(text, ':') + 1:index(text, NL, back=.true.) - 1)
        read (text, *, iostat=ios) back
        call t%check('round trip of '//trim(adjustl(text)), &
                     ios == 0 .and. transfer(back, 0_i8) == transfer(SAMPLES(i), 0_i8))
        call t%check('valid JSON number '//trim(adjustl(text)), json_number(trim(adjustl(text))))
    end do

    call object%write('no_such_dir/object.json', stat)
    call t%check('unwritable path fails', .not. stat%ok())

    ! Arrays: each element as its scalar form, ', ' between, [] when empty.
    call arrays%add_real_array('r', [-1.5_wp, ieee_value(1.0_wp, ieee_quiet_nan), 2.0_wp])
    call arrays%add_integer_array('i', [2, 0, -7])
    call arrays%add_logical_array('l', [.true., .false.])
    call arrays%add_string_array('s', [character(len=6) :: 'pencil', 'a"b'])
    call arrays%add_real_array('none', [real(wp) ::])
    call t%check('arrays of reals, integers, logicals, strings, and an empty one', &
                 arrays%to_text() == '{'//NL//'  "r": [-1.5, null, 2.0],'//NL// &
                 '  "i": [2, 0, -7],'//NL//'  "l": [true, false],'//NL// &
                 '  "s": ["pencil", "a\"b"],'//NL//'  "none": []'//NL//'}')

    ! An object as a member: its members on one line, ', ' between, {} when empty.
    call inner%add_string('verdict', 'moving')
    call inner%add_real_array('point', [1.5_wp, 0.0_wp])
    call inner%add_null('limit')
    call nested%add_object('side', inner)
    call nested%add_object('empty', empty)
    call t%check('an object member on one line, and an empty one', nested%to_text() == &
                 '{'//NL//'  "side": {"verdict": "moving", "point": [1.5, 0.0], '// &
                 '"limit": null},'//NL//'  "empty": {}'//NL//'}')

    ! gfortran 12 keeps main-program allocatables in a frame gone before LeakSanitizer
    ! looks: free them here so a sanitizer build reports only real leaks.
    deallocate (text, expected)
    call t%report()

contains
    !> The JSON number grammar: -?(0|[1-9]d*)(.d+)?([eE][+-]?d+)?
    logical function json_number(s)
        character(len=*), intent(in) :: s
        integer :: i
        json_number = .false.
        i = 1
        if (s(i:i) == '-') i = i + 1
        if (i > len(s)) return
        if (s(i:i) == '0') then
            i = i + 1
        else if (is_digit(s, i)) then
            do while (is_digit(s, i))
                i = i + 1
            end do
        else
            return
        end if
        if (i <= len(s)) then
            if (s(i:i) == '.') then
                i = i + 1
                if (.not. is_digit(s, i)) return
                do while (is_digit(s, i))
                    i = i + 1
                end do
            end if
        end if
        if (i <= len(s)) then
            if (s(i:i) == 'e' .or. s(i:i) == 'E') then
                i = i + 1
                if (i > len(s)) return
                if (s(i:i) == '+' .or. s(i:i) == '-') i = i + 1
                if (.not. is_digit(s, i)) return
                do while (is_digit(s, i))
                    i = i + 1
                end do
            end if
        end if
        json_number = i > len(s)
    end function json_number

    logical function is_digit(s, k)
        character(len=*), intent(in) :: s
        integer, intent(in) :: k
        is_digit = .false.
        if (k <= len(s)) is_digit = index('0123456789', s(k:k)) > 0
    end function is_digit
end program test_json_writer
