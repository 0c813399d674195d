! SPDX-License-Identifier: MIT
!> The CSV writer writes the header and the rows as given, line by line, and reports the
!> first failure once, at close, naming the file; the numbers nceig writes (shortest
!> round-trip text) come back bit for bit through csv_table, the reader of its own tables.
program test_csv_writer
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_IO
    use real_format, only: real_to_text
    use csv_writer, only: csv_writer_t
    use csv_table, only: csv_table_t, read_csv_table
    use fixtures, only: read_text
    use testing, only: test_suite_t
    implicit none

    character(len=*), parameter :: PATH = 'test_csv_writer.csv'
    real(wp), parameter :: VALUES(5) = [0.1_wp, -1.0_wp/3.0_wp, 6.02214076e23_wp, &
                                        transfer(1_i8, 1.0_wp), 1.0e-5_wp]
    type(test_suite_t) :: t
    type(csv_writer_t) :: writer
    type(csv_table_t) :: table
    type(status_t) :: stat
    character(len=:), allocatable :: text
    real(wp) :: back
    integer :: i, unit
    logical :: same

    t%name = 'test_csv_writer'
    call writer%open(PATH, 'index,value')
    do i = 1, size(VALUES)
        call writer%row(char(iachar('0') + i)//','//real_to_text(VALUES(i)))
    end do
    call writer%close(stat)
    call read_text(PATH, text)
    call t%check('open, row, close: the header and one line per row, nothing else', &
                 stat%ok() .and. index(text, 'index,value'//new_line('a')//'1,0.1'// &
                 new_line('a')) == 1 .and. count_lines(text) == 1 + size(VALUES))
    call read_csv_table(PATH, table, stat)
    same = stat%ok() .and. table%n_rows() == size(VALUES)
    do i = 1, size(VALUES)
        back = table%number(i, table%column('value'))
        same = same .and. transfer(back, 0_i8) == transfer(VALUES(i), 0_i8)
    end do
    call t%check('written numbers read back bit for bit (the smallest subnormal too)', same)

    call writer%open('no_such_folder/'//PATH, 'a,b')
    call writer%row('1,2')
    call writer%close(stat)
    call t%check('a file that cannot be made: one failure at close, naming it', &
                 stat%code == STATUS_IO .and. &
                 index(stat%message, 'no_such_folder/'//PATH//': cannot write:') == 1)
    call writer%open(PATH, 'replaced')
    call writer%close(stat)
    call read_text(PATH, text)
    call t%check('open replaces an existing file', stat%ok() .and. text == &
                 'replaced'//new_line('a'))
    open (newunit=unit, file=PATH, status='old')
    close (unit, status='delete')
    deallocate (text)   ! (AddressSanitizer reports a main program's allocatables)
    call t%report()

contains

    pure integer function count_lines(text)
        character(len=*), intent(in) :: text
        integer :: i
        count_lines = 0
        do i = 1, len(text)
            if (text(i:i) == new_line('a')) count_lines = count_lines + 1
        end do
    end function count_lines
end program test_csv_writer
