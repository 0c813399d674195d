! SPDX-License-Identifier: MIT
!> The CSV reader of nceig's own tables: columns by name, blanks around fields and blank
!> lines ignored, numbers read exactly and every other field as NaN, a row of the wrong
!> width refused naming the file and its line.
program test_csv_table
    use kinds, only: wp
    use ieee_arithmetic, only: ieee_is_nan
    use status, only: status_t, STATUS_BAD_INPUT
    use csv_table, only: csv_table_t, csv_field_t, read_csv_table, split_fields
    use fixtures, only: write_text
    use testing, only: test_suite_t
    implicit none

    character(len=*), parameter :: PATH = 'test_csv_table.csv', LF = new_line('a')
    type(test_suite_t) :: t
    type(csv_table_t) :: table
    type(csv_field_t), allocatable :: fields(:)
    type(status_t) :: stat
    real(wp) :: numbers(3)
    integer :: n, v, unit

    t%name = 'test_csv_table'
    allocate (fields(0))   ! (gfortran 12 -O3 warns of an unallocated one)
    fields = split_fields(' a , b,,c ')
    call t%check('split_fields: commas separate, blanks trimmed, empty fields kept', &
                 size(fields) == 4 .and. fields(1)%text == 'a' .and. fields(2)%text == 'b' &
                 .and. len(fields(3)%text) == 0 .and. fields(4)%text == 'c')
    fields = split_fields('')
    call t%check('split_fields: an empty line is one empty field', size(fields) == 1 .and. &
                 len(fields(1)%text) == 0)

    call write_text(PATH, LF//' n , value ,note'//LF//'1, 0.25 ,first'//LF//LF// &
                    '2,-1.5e-3,'//LF//'3,null,x'//LF//'4,abc,y'//LF//'5,inf,z'//LF)
    call read_csv_table(PATH, table, stat)
    n = table%column('n')
    v = table%column('value')
    call t%check('read_csv_table: the header after a blank line, blank rows skipped', &
                 stat%ok() .and. size(table%header) == 3 .and. table%n_rows() == 5)
    call t%check('column: by name, trimmed; 0 for a missing one', n == 1 .and. v == 2 .and. &
                 table%column('note') == 3 .and. table%column('missing') == 0)
    call t%check('text: the trimmed field; empty for column 0', table%text(1, 3) == 'first' &
                 .and. len(table%text(2, 3)) == 0 .and. len(table%text(1, 0)) == 0)
    numbers = [table%number(1, v), table%number(2, v), table%number(4, n)]
    call t%check('number: decimal fields exactly (0.25, -1.5e-3)', &
                 all(abs(numbers - [0.25_wp, -1.5e-3_wp, 4.0_wp]) <= 0.0_wp))
    numbers = [table%number(3, v), table%number(4, v), table%number(5, v)]
    call t%check('number: NaN for null, text and inf', all(ieee_is_nan(numbers)))
    numbers(1:2) = [table%number(2, 3), table%number(1, 0)]
    call t%check('number: NaN for an empty field and column 0', &
                 all(ieee_is_nan(numbers(1:2))))

    call write_text(PATH, 'a,b'//LF//'1,2'//LF//LF//'3'//LF)
    call read_csv_table(PATH, table, stat)
    call t%check('a row of the wrong width: refused at its line (4)', &
                 stat%code == STATUS_BAD_INPUT .and. stat%message == &
                 PATH//':4: expected 2 fields as in the header, found 1')
    call write_text(PATH, LF//'   '//LF)
    call read_csv_table(PATH, table, stat)
    call t%check('only blank lines: an empty file', stat%code == STATUS_BAD_INPUT .and. &
                 index(stat%message, 'empty file') > 0)
    open (newunit=unit, file=PATH, status='old')
    close (unit, status='delete')
    call read_csv_table(PATH, table, stat)
    call t%check('a missing file: cannot open, named', stat%code == STATUS_BAD_INPUT .and. &
                 index(stat%message, PATH//': cannot open') == 1)
    deallocate (fields)   ! (AddressSanitizer reports a main program's allocatables)
    call t%report()
end program test_csv_table
