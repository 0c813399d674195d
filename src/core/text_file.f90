! SPDX-License-Identifier: MIT
!> Reading formatted text files line by line, whatever the line length: the input file's
!> scanner and the CSV tables (results read back by nceig-extrapolate) share it.
module text_file
    use iso_fortran_env, only: iostat_end, iostat_eor
    implicit none
    private
    public :: read_line, TOO_LONG

    integer, parameter :: CHUNK_LEN = 4096   !! pieces of a line of any length
    !> ios of read_line when the line has more than `max_len` characters (unread beyond).
    integer, parameter :: TOO_LONG = -12345

contains

    !> One line of any length; the last line needs no line feed. In time linear in its
    !> length (the buffer doubles, it is not regrown by each piece). With `max_len`, a
    !> longer line stops the reading after max_len + 1 characters with ios = TOO_LONG, so
    !> that an endless line (/dev/zero) cannot take all memory.
    subroutine read_line(unit, line, ios, msg, max_len)
        integer, intent(in) :: unit
        character(len=:), allocatable, intent(out) :: line
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: max_len
        character(len=CHUNK_LEN) :: chunk
        character(len=:), allocatable :: buffer
        integer :: n_read, n

        allocate (character(len=CHUNK_LEN) :: buffer)
        n = 0
        do
            read (unit, '(a)', advance='no', size=n_read, iostat=ios, iomsg=msg) chunk
            if (n + n_read > len(buffer)) call grow(buffer, max(2*len(buffer), n + n_read))
            buffer(n + 1:n + n_read) = chunk(:n_read)
            n = n + n_read
            if (ios == iostat_eor) then
                ios = 0
                exit
            end if
            if (ios == iostat_end .and. n > 0) ios = 0
            if (ios /= 0 .or. n_read < CHUNK_LEN) exit
            if (present(max_len)) then
                if (n > max_len) then
                    ios = TOO_LONG
                    exit
                end if
            end if
        end do
        if (present(max_len) .and. ios == 0) then
            if (n > max_len) ios = TOO_LONG
        end if
        line = buffer(:n)
    end subroutine read_line

    !> `buffer` with room for `length` characters, its text kept.
    subroutine grow(buffer, length)
        character(len=:), allocatable, intent(inout) :: buffer
        integer, intent(in) :: length
        character(len=:), allocatable :: larger
        allocate (character(len=length) :: larger)
        larger(:len(buffer)) = buffer
        call move_alloc(larger, buffer)
    end subroutine grow
end module text_file
