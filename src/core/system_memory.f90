! SPDX-License-Identifier: MIT
!> How much memory this machine can give the run: MemAvailable of /proc/meminfo (Linux),
!> the kernel's estimate of what can be allocated without swapping; MemTotal when the
!> kernel is too old to report it. MemAvailable rather than MemTotal: memory other processes
!> hold is not ours, and a run that overflows into swap (or the OOM killer) is no answer.
module system_memory
    use kinds, only: i8
    use iso_c_binding, only: c_long_long, c_int, c_double
    implicit none
    private
    public :: available_memory_bytes, MEMINFO_PATH, address_space_headroom_bytes, &
              threads_still_running

    character(len=*), parameter :: MEMINFO_PATH = '/proc/meminfo'
    !> The process's own mappings: 'VmSize:   123456 kB'.
    character(len=*), parameter :: STATUS_PATH = '/proc/self/status'

    interface
        function nceig_address_space_limit() bind(C, name='nceig_address_space_limit')
            import :: c_long_long
            integer(c_long_long) :: nceig_address_space_limit
        end function nceig_address_space_limit
        function nceig_wait_for_sleeping_threads(seconds) &
                bind(C, name='nceig_wait_for_sleeping_threads')
            import :: c_int, c_double
            real(c_double), value :: seconds
            integer(c_int) :: nceig_wait_for_sleeping_threads
        end function nceig_wait_for_sleeping_threads
    end interface

contains

    !> Bytes available to allocate (see above); -1 when /proc/meminfo cannot be read (not
    !> Linux), so that callers skip their check rather than refuse.
    function available_memory_bytes(path) result(bytes)
        character(len=*), intent(in), optional :: path   !! default MEMINFO_PATH (tests)
        integer(i8) :: bytes
        character(len=:), allocatable :: file

        file = MEMINFO_PATH
        if (present(path)) file = path
        bytes = kib_field(file, 'MemAvailable:')
        if (bytes < 0) bytes = kib_field(file, 'MemTotal:')
        if (bytes >= 0) bytes = 1024_i8*bytes
    end function available_memory_bytes

    !> Bytes of address space the process may still map under its limit (ulimit -v,
    !> RLIMIT_AS) beyond what it maps now (VmSize); -1 when there is no limit, or the size
    !> cannot be read (not Linux), so that callers skip their check rather than refuse.
    function address_space_headroom_bytes() result(bytes)
        integer(i8) :: bytes
        integer(i8) :: limit, mapped

        bytes = -1
        limit = int(nceig_address_space_limit(), i8)
        if (limit < 0) return
        mapped = kib_field(STATUS_PATH, 'VmSize:')
        if (mapped < 0) return
        bytes = max(0_i8, limit - 1024_i8*mapped)
    end function address_space_headroom_bytes

    !> The threads of this process other than the caller's that still run after waiting at
    !> most `seconds` for all to sleep (system_memory_c.c); -1 when /proc cannot tell.
    !> OpenBLAS's threads sleep once they hold their buffers; one whose mmap fails runs for
    !> ever, retrying it.
    integer function threads_still_running(seconds)
        real(c_double), intent(in) :: seconds
        threads_still_running = int(nceig_wait_for_sleeping_threads(seconds))
    end function threads_still_running

    !> The number after `key` on the first line of the /proc file `file` that starts with
    !> it ('MemAvailable:   22846788 kB': kB); -1 when the file, the line or the number
    !> cannot be read.
    function kib_field(file, key) result(value)
        character(len=*), intent(in) :: file, key
        integer(i8) :: value
        integer :: unit, ios
        character(len=256) :: line

        value = -1
        open (newunit=unit, file=file, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do
            read (unit, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (index(line, key) == 1) then
                read (line(len(key) + 1:), *, iostat=ios) value
                if (ios /= 0) value = -1
                exit
            end if
        end do
        close (unit)
    end function kib_field
end module system_memory
