! SPDX-License-Identifier: MIT
!> read_line returns each line whole whatever its length (across the 4096-character chunks
!> it reads in), the last one without a line feed too, and stops a line longer than
!> max_len with TOO_LONG after reading no more than max_len + 1 characters of it.
program test_text_file
    use iso_fortran_env, only: iostat_end
    use text_file, only: read_line, TOO_LONG
    use testing, only: test_suite_t
    implicit none

    character(len=*), parameter :: PATH = 'test_text_file.txt'
    !> lengths around the chunk size, an empty line and a long one
    integer, parameter :: LENGTHS(8) = [0, 1, 4095, 4096, 4097, 8192, 12289, 3]
    type(test_suite_t) :: t
    character(len=:), allocatable :: line
    character(len=256) :: msg
    integer :: unit, ios, i
    logical :: same

    t%name = 'test_text_file'
    ! every line of its own letter, the last without a line feed
    open (newunit=unit, file=PATH, access='stream', form='unformatted', status='replace')
    do i = 1, size(LENGTHS)
        write (unit) repeat(achar(iachar('a') + i - 1), LENGTHS(i))
        if (i < size(LENGTHS)) write (unit) new_line('a')
    end do
    close (unit)

    open (newunit=unit, file=PATH, status='old', action='read')
    same = .true.
    do i = 1, size(LENGTHS)
        call read_line(unit, line, ios, msg)
        same = same .and. ios == 0 .and. len(line) == LENGTHS(i) .and. &
               line == repeat(achar(iachar('a') + i - 1), LENGTHS(i))
    end do
    call t%check('every line whole, across chunks, the last without a line feed', same)
    call read_line(unit, line, ios, msg)
    call t%check('after the last line: end of file, an empty line', ios == iostat_end .and. &
                 len(line) == 0)
    close (unit)

    ! max_len: the 4097- and 8192-character lines are too long for 5000, the others not
    open (newunit=unit, file=PATH, status='old', action='read')
    same = .true.
    do i = 1, 5
        call read_line(unit, line, ios, msg, max_len=5000)
        same = same .and. ios == 0 .and. len(line) == LENGTHS(i)
    end do
    call t%check('max_len: lines up to it are read', same)
    call read_line(unit, line, ios, msg, max_len=5000)
    call t%check('max_len: a longer line stops with TOO_LONG after max_len + 1 or a chunk '// &
                 'more, never the whole of an endless line', ios == TOO_LONG .and. &
                 len(line) > 5000 .and. len(line) <= 5000 + 4096)
    close (unit, status='delete')
    deallocate (line)   ! (AddressSanitizer reports a main program's allocatables)
    call t%report()
end program test_text_file
