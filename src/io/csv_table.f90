! SPDX-License-Identifier: MIT
!> A small CSV table read whole: a header of column names and rows of text fields, as the
!> sweep's results.csv is written (commas separate fields; no quoting, no commas in fields).
!> Columns are looked up by name, so tables may gain columns without breaking readers.
module csv_table
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: to_string
    use text_file, only: read_line
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use iso_fortran_env, only: iostat_end
    implicit none
    private
    public :: read_csv_table, split_fields

    integer, parameter :: MSG_LEN = 512

    type, public :: csv_field_t
        character(len=:), allocatable :: text
    end type csv_field_t

    type, public :: csv_table_t
        type(csv_field_t), allocatable :: header(:)     !! (n_columns) names, blanks trimmed
        type(csv_field_t), allocatable :: fields(:, :)  !! (n_columns, n_rows), blanks trimmed
    contains
        procedure :: n_rows => csv_table_n_rows
        procedure :: column => csv_table_column
        procedure :: text => csv_table_text
        procedure :: number => csv_table_number
    end type csv_table_t

contains

    !> Read `path`: its first line names the columns; blank lines are skipped; every other
    !> line must have as many fields as the header.
    subroutine read_csv_table(path, table, stat)
        character(len=*), intent(in) :: path
        type(csv_table_t), intent(out) :: table
        type(status_t), intent(out) :: stat
        type(csv_field_t), allocatable :: lines(:), grown(:), row(:)
        character(len=:), allocatable :: line
        character(len=MSG_LEN) :: msg
        integer :: unit, ios, n_lines, n_rows, first, i

        open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
        if (ios /= 0) then
            call stat%fail(STATUS_BAD_INPUT, path//': cannot open: '//trim(msg))
            return
        end if
        allocate (lines(64))
        n_lines = 0
        do
            call read_line(unit, line, ios, msg)
            if (ios == iostat_end) exit
            if (ios /= 0) then
                call stat%fail(STATUS_BAD_INPUT, path//': cannot read: '//trim(msg))
                close (unit)
                return
            end if
            if (n_lines == size(lines)) then
                allocate (grown(2*size(lines)))
                grown(:n_lines) = lines
                call move_alloc(grown, lines)
            end if
            n_lines = n_lines + 1
            lines(n_lines)%text = line
        end do
        close (unit)

        i = 1
        do while (i <= n_lines)
            if (len_trim(lines(i)%text) > 0) exit
            i = i + 1
        end do
        if (i > n_lines) then
            call stat%fail(STATUS_BAD_INPUT, path//': empty file, expected a header line')
            return
        end if
        first = i
        table%header = split_fields(lines(first)%text)
        ! Sized first, then filled row by row: reshaping arrays of derived types with
        ! allocatable components loses their contents with gfortran 12.
        allocate (table%fields(size(table%header), &
                               count([(len_trim(lines(i)%text) > 0, i=first + 1, n_lines)])))
        n_rows = 0
        do i = first + 1, n_lines
            if (len_trim(lines(i)%text) == 0) cycle
            row = split_fields(lines(i)%text)
            if (size(row) /= size(table%header)) then
                call stat%fail(STATUS_BAD_INPUT, path//':'//to_string(i)//': expected '// &
                               to_string(size(table%header))//' fields as in the header, found ' &
                               //to_string(size(row)))
                return
            end if
            n_rows = n_rows + 1
            table%fields(:, n_rows) = row
        end do
    end subroutine read_csv_table

    !> The comma-separated fields of `line`, leading and trailing blanks removed.
    pure function split_fields(line) result(fields)
        character(len=*), intent(in) :: line
        type(csv_field_t), allocatable :: fields(:)
        integer :: start, comma, n

        n = 1
        do start = 1, len(line)
            if (line(start:start) == ',') n = n + 1
        end do
        allocate (fields(n))
        start = 1
        do n = 1, size(fields)
            comma = index(line(start:), ',')
            if (comma == 0) then
                fields(n)%text = trim(adjustl(line(start:)))
            else
                fields(n)%text = trim(adjustl(line(start:start + comma - 2)))
                start = start + comma
            end if
        end do
    end function split_fields

    pure integer function csv_table_n_rows(this) result(n)
        class(csv_table_t), intent(in) :: this
        n = size(this%fields, 2)
    end function csv_table_n_rows

    !> Index of the column called `name`, 0 when there is none.
    pure integer function csv_table_column(this, name) result(column)
        class(csv_table_t), intent(in) :: this
        character(len=*), intent(in) :: name
        do column = 1, size(this%header)
            if (this%header(column)%text == name) return
        end do
        column = 0
    end function csv_table_column

    !> Field text of (row, column); '' for column 0 (an absent optional column).
    pure function csv_table_text(this, row, column) result(text)
        class(csv_table_t), intent(in) :: this
        integer, intent(in) :: row, column
        character(len=:), allocatable :: text
        text = ''
        if (column > 0) text = this%fields(column, row)%text
    end function csv_table_text

    !> Field of (row, column) as a real; NaN when empty, 'null', not a number, or column 0.
    function csv_table_number(this, row, column) result(x)
        class(csv_table_t), intent(in) :: this
        integer, intent(in) :: row, column
        real(wp) :: x
        integer :: ios
        character(len=:), allocatable :: text

        x = ieee_value(1.0_wp, ieee_quiet_nan)
        text = this%text(row, column)
        if (len(text) == 0 .or. text == 'null' .or. verify(text, '0123456789+-.eEdD') > 0) return
        read (text, *, iostat=ios) x
        if (ios /= 0) x = ieee_value(1.0_wp, ieee_quiet_nan)
    end function csv_table_number
end module csv_table
