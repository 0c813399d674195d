! SPDX-License-Identifier: MIT
!> A mesh file held in memory and read line by line, with the one-line failures of the MSH
!> reader: 'path:line: problem; expected ...', quoting at most 60 printable characters of
!> the offending line (a binary or garbage file must not drive the terminal).
module msh_text
    use kinds, only: i8
    use status, only: status_t, STATUS_MESH
    use strings, only: to_string
    use text_tokens, only: integers_at
    implicit none
    private
    public :: text_file_t, load_file, next_line, require_line, truncated, fail_here, &
              check_announced, read_counts, shortened, printable

    !> The file in memory, read line by line; `line` counts the lines handed out.
    type :: text_file_t
        character(len=:), allocatable :: path
        character(len=:), allocatable :: text
        integer(i8) :: next = 1
        integer :: line = 0
    end type text_file_t

contains

    !> The whole file `path` into `f`, or a failure naming it.
    subroutine load_file(path, f, stat)
        character(len=*), intent(in) :: path
        type(text_file_t), intent(out) :: f
        type(status_t), intent(out) :: stat
        character(len=512) :: msg
        integer :: unit, ios
        integer(i8) :: file_size

        f%path = path
        open (newunit=unit, file=path, access='stream', form='unformatted', status='old', &
              action='read', iostat=ios, iomsg=msg)
        if (ios /= 0) then
            call stat%fail(STATUS_MESH, path//': cannot open mesh file: '//trim(msg)// &
                           '; expected a readable Gmsh .msh file')
            return
        end if
        inquire (unit=unit, size=file_size)
        allocate (character(len=max(file_size, 0_i8)) :: f%text)
        if (file_size > 0) read (unit, iostat=ios, iomsg=msg) f%text
        close (unit)
        if (ios /= 0) call stat%fail(STATUS_MESH, path//': cannot read mesh file: '// &
                                     trim(msg)//'; expected a readable Gmsh .msh file')
    end subroutine load_file

    !> The next line without its end-of-line characters; .false. at the end of the file.
    logical function next_line(f, line)
        type(text_file_t), intent(inout) :: f
        character(len=:), allocatable, intent(out) :: line
        integer(i8) :: finish
        next_line = f%next <= len(f%text, kind=i8)
        if (.not. next_line) then
            line = ''
            return
        end if
        finish = index(f%text(f%next:), new_line('a'), kind=i8)
        if (finish == 0) then
            finish = len(f%text, kind=i8)
        else
            finish = f%next + finish - 2
        end if
        line = f%text(f%next:finish)
        f%next = finish + 2
        f%line = f%line + 1
        if (len(line) > 0) then
            if (line(len(line):) == achar(13)) line = line(:len(line) - 1)   ! CRLF files
        end if
    end function next_line

    !> The next line, or a failure 'unexpected end of file' saying what was expected.
    subroutine require_line(f, line, expected, stat)
        type(text_file_t), intent(inout) :: f
        character(len=:), allocatable, intent(out) :: line
        character(len=*), intent(in) :: expected
        type(status_t), intent(inout) :: stat
        if (.not. next_line(f, line)) call truncated(f, expected, stat)
    end subroutine require_line

    subroutine truncated(f, expected, stat)
        type(text_file_t), intent(in) :: f
        character(len=*), intent(in) :: expected
        type(status_t), intent(inout) :: stat
        call stat%fail(STATUS_MESH, f%path//':'//to_string(f%line)// &
            ': unexpected end of file (truncated?); expected '//printable(expected))
    end subroutine truncated

    !> Fail with 'path:line: message' at the line last read.
    subroutine fail_here(f, stat, message)
        type(text_file_t), intent(in) :: f
        type(status_t), intent(inout) :: stat
        character(len=*), intent(in) :: message
        call stat%fail(STATUS_MESH, f%path//':'//to_string(f%line)//': '//printable(message))
    end subroutine fail_here

    !> A section header's count `n` of entries taking `lines_each` lines must fit in the
    !> rest of the file: a mangled count then fails here, not as a huge allocation.
    subroutine check_announced(f, n, lines_each, what, stat)
        type(text_file_t), intent(in) :: f
        integer, intent(in) :: n, lines_each
        character(len=*), intent(in) :: what
        type(status_t), intent(inout) :: stat
        integer(i8) :: n_lines, start, finish
        n_lines = 0
        start = f%next
        do while (start <= len(f%text, kind=i8))
            finish = index(f%text(start:), new_line('a'), kind=i8)
            n_lines = n_lines + 1
            if (finish == 0) exit
            start = start + finish
        end do
        if (int(n, i8)*lines_each <= n_lines) return
        call fail_here(f, stat, 'the header announces '//to_string(n)//' '//what// &
                       ', but the file ends '//to_string(int(n_lines))//' lines later ' &
                       //'(truncated?); expected a count that the section holds')
    end subroutine check_announced

    !> A line of `n` non-negative integers (counts of a section header).
    subroutine read_counts(f, n, expected, values, stat)
        type(text_file_t), intent(inout) :: f
        integer, intent(in) :: n
        character(len=*), intent(in) :: expected
        integer, intent(out) :: values(n)
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        values = 0
        call require_line(f, line, expected, stat)
        if (.not. stat%ok()) return
        if (.not. integers_at(line, values)) then
            call fail_here(f, stat, 'expected '//expected//', found '''//shortened(line)//'''')
        else if (any(values < 0) .and. n > 1) then
            call fail_here(f, stat, 'expected '//expected//', found negative counts in '''// &
                           shortened(line)//'''')
        else if (n == 1 .and. values(1) < 0) then
            call fail_here(f, stat, 'expected '//expected//', found '''//shortened(line)//'''')
        end if
    end subroutine read_counts

    !> At most 60 characters of a line, for messages, in printable ASCII: a stray carriage
    !> return would break the one-line message, and bytes of a binary or garbage file
    !> (C1 controls among them) could drive the terminal.
    pure function shortened(text) result(short)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: short
        integer :: i
        if (len(text) <= 60) then
            short = printable(text)
        else
            short = printable(text(:57))//'...'
        end if
        do i = 1, len(short)
            if (iachar(short(i:i)) > 127) short(i:i) = '?'
        end do
    end function shortened

    !> `text` with control characters (line breaks, NUL, escape, ...) replaced by '?'.
    pure function printable(text) result(clean)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: clean
        integer :: i
        clean = text
        do i = 1, len(clean)
            if (iachar(clean(i:i)) < 32 .or. iachar(clean(i:i)) == 127) clean(i:i) = '?'
        end do
    end function printable
end module msh_text
