! SPDX-License-Identifier: MIT
!> Reading formatted text files line by line, whatever the line length: the input file's
!> scanner and the CSV tables (results read back by nceig-extrapolate) share it.
module text_file
    use iso_fortran_env, only: iostat_end, iostat_eor
    implicit none
    private
    public :: read_line

    integer, parameter :: CHUNK_LEN = 256    !! pieces of a line of any length

contains

    !> One line of any length; the last line needs no line feed.
    subroutine read_line(unit, line, ios, msg)
        integer, intent(in) :: unit
        character(len=:), allocatable, intent(out) :: line
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        character(len=CHUNK_LEN) :: chunk
        integer :: n_read

        line = ''
        do
            read (unit, '(a)', advance='no', size=n_read, iostat=ios, iomsg=msg) chunk
            line = line//chunk(:n_read)
            if (ios == iostat_eor) then
                ios = 0
                return
            end if
            if (ios == iostat_end .and. len(line) > 0) ios = 0
            if (ios /= 0 .or. n_read < CHUNK_LEN) return
        end do
    end subroutine read_line
end module text_file
