! SPDX-License-Identifier: MIT
!> How much memory this machine can give the run: MemAvailable of /proc/meminfo (Linux),
!> the kernel's estimate of what can be allocated without swapping; MemTotal when the
!> kernel is too old to report it. MemAvailable rather than MemTotal: memory other processes
!> hold is not ours, and a run that overflows into swap (or the OOM killer) is no answer.
module system_memory
    use kinds, only: i8
    implicit none
    private
    public :: available_memory_bytes, MEMINFO_PATH

    character(len=*), parameter :: MEMINFO_PATH = '/proc/meminfo'

contains

    !> Bytes available to allocate (see above); -1 when /proc/meminfo cannot be read (not
    !> Linux), so that callers skip their check rather than refuse.
    function available_memory_bytes(path) result(bytes)
        character(len=*), intent(in), optional :: path   !! default MEMINFO_PATH (tests)
        integer(i8) :: bytes
        integer(i8) :: total, value
        integer :: unit, ios
        character(len=256) :: line
        character(len=:), allocatable :: file

        bytes = -1
        total = -1
        file = MEMINFO_PATH
        if (present(path)) file = path
        open (newunit=unit, file=file, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do
            read (unit, '(a)', iostat=ios) line
            if (ios /= 0) exit
            ! 'MemAvailable:   22846788 kB'
            if (index(line, 'MemAvailable:') == 1) then
                read (line(len('MemAvailable:') + 1:), *, iostat=ios) value
                if (ios == 0) bytes = 1024_i8*value
            else if (index(line, 'MemTotal:') == 1) then
                read (line(len('MemTotal:') + 1:), *, iostat=ios) value
                if (ios == 0) total = 1024_i8*value
            end if
        end do
        close (unit)
        if (bytes < 0) bytes = total
    end function available_memory_bytes
end module system_memory
