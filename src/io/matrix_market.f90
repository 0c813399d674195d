! SPDX-License-Identifier: MIT
!> Matrix Market coordinate files for CSR matrices, so K and B can be compared with other
!> tools (Octave, SciPy) and read back in tests.
module matrix_market
    use kinds, only: wp
    use status, only: status_t, STATUS_IO, STATUS_BAD_INPUT
    use csr_matrix, only: csr_matrix_t
    use strings, only: to_string, lowercase
    use sorting, only: sort_index
    use filesystem, only: close_output
    implicit none
    private
    public :: write_matrix_market, read_matrix_market

    integer, parameter :: LINE_LEN = 1024

contains

    !> Write `a` as `%%MatrixMarket matrix coordinate real general`, 1-based. Values get 17
    !> significant digits, enough for any double to read back to the same bits.
    subroutine write_matrix_market(path, a, stat)
        character(len=*), intent(in) :: path
        type(csr_matrix_t), intent(in) :: a
        type(status_t), intent(out) :: stat
        integer :: unit, io, row, k
        character(len=LINE_LEN) :: message

        open (newunit=unit, file=path, status='replace', action='write', form='formatted', &
              iostat=io, iomsg=message)
        if (io /= 0) then
            call stat%fail(STATUS_IO, 'matrix_market: cannot open '//path//' for writing: '// &
                           trim(message))
            return
        end if
        write (unit, '(a)', iostat=io, iomsg=message) &
            '%%MatrixMarket matrix coordinate real general'
        if (io == 0) write (unit, '(i0, 1x, i0, 1x, i0)', iostat=io, iomsg=message) &
            a%n(), a%n(), a%nnz()
        do row = 1, a%n()
            if (io /= 0) exit
            do k = a%row_start(row), a%row_start(row + 1) - 1
                write (unit, '(i0, 1x, i0, 1x, es24.16e3)', iostat=io, iomsg=message) &
                    row, a%col(k), a%val(k)
                if (io /= 0) exit
            end do
        end do
        if (io /= 0) then
            call stat%fail(STATUS_IO, 'matrix_market: cannot write '//path//': '//trim(message))
            close (unit, iostat=io)
            return
        end if
        call close_output(unit, path, io, message)
        if (io /= 0) call stat%fail(STATUS_IO, 'matrix_market: cannot write '//path//': '// &
                                    trim(message))
    end subroutine write_matrix_market

    !> Read a square `coordinate real|integer general|symmetric` Matrix Market file into CSR:
    !> columns sorted within each row, duplicates summed, a symmetric file mirrored.
    subroutine read_matrix_market(path, a, stat)
        character(len=*), intent(in) :: path
        type(csr_matrix_t), intent(out) :: a
        type(status_t), intent(out) :: stat
        integer :: unit, io, n_rows, n_cols, n_entries, k, line_number
        integer, allocatable :: rows(:), cols(:)
        real(wp), allocatable :: values(:)
        character(len=LINE_LEN) :: line, message
        character(len=32) :: words(5)
        logical :: symmetric

        open (newunit=unit, file=path, status='old', action='read', form='formatted', &
              iostat=io, iomsg=message)
        if (io /= 0) then
            call stat%fail(STATUS_IO, 'matrix_market: cannot open '//path//': '//trim(message))
            return
        end if

        read (unit, '(a)', iostat=io, iomsg=message) line
        if (io /= 0) then
            call fail_read('the header line')
            return
        end if
        words = ''
        read (line, *, iostat=io) words
        words = lowercase(words)
        if (words(1) /= '%%matrixmarket' .or. words(2) /= 'matrix' .or. &
            words(3) /= 'coordinate' .or. (words(4) /= 'real' .and. words(4) /= 'integer') &
            .or. (words(5) /= 'general' .and. words(5) /= 'symmetric')) then
            call stat%fail(STATUS_BAD_INPUT, 'matrix_market: '//path//': expected a '// &
                '"%%MatrixMarket matrix coordinate real general|symmetric" header, found "'// &
                trim(line)//'"')
            close (unit)
            return
        end if
        symmetric = words(5) == 'symmetric'

        ! Comment lines start with '%'; the first other line holds the sizes.
        line_number = 1
        do
            read (unit, '(a)', iostat=io, iomsg=message) line
            line_number = line_number + 1
            if (io /= 0) then
                call fail_read('the size line')
                return
            end if
            if (len_trim(line) > 0 .and. line(1:1) /= '%') exit
        end do
        read (line, *, iostat=io) n_rows, n_cols, n_entries
        if (io /= 0 .or. n_rows /= n_cols .or. n_rows < 0 .or. n_entries < 0) then
            call stat%fail(STATUS_BAD_INPUT, 'matrix_market: '//path//': line '// &
                to_string(line_number)//' should give the sizes of a square matrix, found "'// &
                trim(line)//'"')
            close (unit)
            return
        end if

        allocate (rows(n_entries), cols(n_entries), values(n_entries))
        do k = 1, n_entries
            read (unit, *, iostat=io, iomsg=message) rows(k), cols(k), values(k)
            if (io /= 0) then
                call fail_read('entry '//to_string(k)//' of '//to_string(n_entries))
                return
            end if
            if (min(rows(k), cols(k)) < 1 .or. max(rows(k), cols(k)) > n_rows) then
                call stat%fail(STATUS_BAD_INPUT, 'matrix_market: '//path//': entry '// &
                    to_string(k)//' at ('//to_string(rows(k))//', '//to_string(cols(k))// &
                    ') lies outside the '//to_string(n_rows)//' x '//to_string(n_rows)//' matrix')
                close (unit)
                return
            end if
        end do
        close (unit)

        if (symmetric) call mirror(rows, cols, values)
        call csr_from_triplets(n_rows, rows, cols, values, a)

    contains

        subroutine fail_read(what)
            character(len=*), intent(in) :: what
            if (is_iostat_end(io)) then
                call stat%fail(STATUS_BAD_INPUT, 'matrix_market: '//path// &
                               ': file ends before '//what)
            else
                call stat%fail(STATUS_IO, 'matrix_market: cannot read '//what//' of '// &
                               path//': '//trim(message))
            end if
            close (unit, iostat=io)
        end subroutine fail_read
    end subroutine read_matrix_market

    !> Append (j, i, v) for each off-diagonal (i, j, v) of a lower or upper triangle.
    pure subroutine mirror(rows, cols, values)
        integer, allocatable, intent(inout) :: rows(:), cols(:)
        real(wp), allocatable, intent(inout) :: values(:)
        integer, allocatable :: all_rows(:), all_cols(:)
        real(wp), allocatable :: all_values(:)
        integer :: k, pos
        pos = size(rows)
        allocate (all_rows(pos + count(rows /= cols)), all_cols(pos + count(rows /= cols)), &
                  all_values(pos + count(rows /= cols)))
        all_rows(1:pos) = rows
        all_cols(1:pos) = cols
        all_values(1:pos) = values
        do k = 1, size(rows)
            if (rows(k) == cols(k)) cycle
            pos = pos + 1
            all_rows(pos) = cols(k)
            all_cols(pos) = rows(k)
            all_values(pos) = values(k)
        end do
        call move_alloc(all_rows, rows)
        call move_alloc(all_cols, cols)
        call move_alloc(all_values, values)
    end subroutine mirror

    !> CSR from coordinate triplets in any order: counting sort by row, then sort and merge
    !> each row by column.
    pure subroutine csr_from_triplets(n, rows, cols, values, a)
        integer, intent(in) :: n
        integer, intent(in) :: rows(:), cols(:)
        real(wp), intent(in) :: values(:)
        type(csr_matrix_t), intent(out) :: a
        integer, allocatable :: start(:), fill(:), row_cols(:), order(:)
        real(wp), allocatable :: row_values(:)
        integer :: k, row, first, last, kept, i

        allocate (start(n + 1), source=0)
        do k = 1, size(rows)
            start(rows(k) + 1) = start(rows(k) + 1) + 1
        end do
        start(1) = 1
        do row = 1, n
            start(row + 1) = start(row + 1) + start(row)
        end do
        allocate (row_cols(size(rows)), row_values(size(rows)), fill(n))
        fill = start(1:n)
        do k = 1, size(rows)
            row_cols(fill(rows(k))) = cols(k)
            row_values(fill(rows(k))) = values(k)
            fill(rows(k)) = fill(rows(k)) + 1
        end do

        ! Sort each row in place, then compact it, summing duplicates.
        allocate (a%row_start(n + 1))
        a%row_start(1) = 1
        kept = 0
        do row = 1, n
            first = start(row)
            last = start(row + 1) - 1
            ! Stable, so duplicates are summed in file order, as before.
            order = first - 1 + sort_index(row_cols(first:last))
            row_cols(first:last) = row_cols(order)
            row_values(first:last) = row_values(order)
            do i = first, last
                if (i > first) then
                    if (row_cols(i) == row_cols(kept)) then
                        row_values(kept) = row_values(kept) + row_values(i)
                        cycle
                    end if
                end if
                kept = kept + 1
                row_cols(kept) = row_cols(i)
                row_values(kept) = row_values(i)
            end do
            a%row_start(row + 1) = kept + 1
        end do
        a%col = row_cols(1:kept)
        a%val = row_values(1:kept)
    end subroutine csr_from_triplets
end module matrix_market
