! SPDX-License-Identifier: MIT
!> Refuse, before any of it is allocated, a run whose dense contact blocks exceed the memory
!> of the machine: thin strips with many contact nodes asked for tens of GB, then failed
!> inside the allocator with a backtrace, or swapped for minutes.
module memory_budget
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_SOLVER
    use strings, only: to_string
    use scene, only: scene_t
    use system_memory, only: available_memory_bytes, address_space_headroom_bytes, &
                             threads_still_running
    use blas_info, only: blas_in_use
    use iso_c_binding, only: c_double
    implicit none
    private
    public :: contact_blocks_bytes, check_contact_memory, contact_peak_blocks, &
              check_address_space

    !> Dense p x p arrays alive at once at the peak (the trailing block of the factor is
    !> zeroed in full by the shim, so all of it is resident). Forming Kt_nn and Kt_nt
    !> (contact_reduction: flexibility_blocks): the 2p x 2p trailing block L_c of the factor
    !> of K (4), its inverse S^-1 (4), Kt_nn and Kt_nt (1 each); ARPACK with a shift forms
    !> them too, while holding its own L_c (which flexibility_blocks borrows: same 10). Later
    !> stages hold less (dgeevx: A, VL, VR and Kt_nt; dggev for the thresholds: the blocks,
    !> two copies and VR; lifting: a second L_c).
    integer, parameter :: PEAK_BLOCKS_FORMED = 10
    !> ARPACK without a shift never forms them: its operator's L_c (4) and the second L_c of
    !> lift_eigenvectors (4). (Its dense fallback forms them, but only for p <= 4000, where
    !> 10 p^2 doubles are 1.3 GB.) Measured: nx = 10000, ny = 1, p = 10001: peak RSS 6.28 GB
    !> against 6.40 GB estimated.
    integer, parameter :: PEAK_BLOCKS_ARPACK = 8
    !> OpenBLAS's buffer: BUFFER_SIZE (128 MiB on x86_64) and a page. Each of its threads
    !> maps one: its own threads as they start (at the library's load, before main), the
    !> calling thread at its first BLAS call (dpotrf inside CHOLMOD). A failed mmap is
    !> retried for ever (driver/others/memory.c, blas_memory_alloc), so the run must know
    !> before its first call that every buffer still to come fits.
    integer(i8), parameter :: BLAS_BUFFER_BYTES = 128_i8*1048576_i8 + 4096_i8
    !> Room beyond the buffers: a glibc malloc arena (64 MiB), for the libraries' threads.
    integer(i8), parameter :: SPARE_BYTES = 64_i8*1048576_i8
    !> How long to wait for OpenBLAS's threads to hold their buffers and sleep (they spin for
    !> at most about 0.4 s after their mmap); one still running then retries for ever.
    real(wp), parameter :: THREAD_WAIT_SECONDS = 2.0_wp

contains

    !> Dense p x p arrays at the peak: 8 for ARPACK without a shift, else 10 (see above).
    pure integer function contact_peak_blocks(arpack_unshifted)
        logical, intent(in) :: arpack_unshifted
        contact_peak_blocks = merge(PEAK_BLOCKS_ARPACK, PEAK_BLOCKS_FORMED, arpack_unshifted)
    end function contact_peak_blocks

    !> Bytes of `blocks` dense p x p arrays of doubles (real: 80 p^2 overflows 64-bit
    !> integers from p = 3.4e8).
    pure real(wp) function contact_blocks_bytes(p, blocks)
        integer, intent(in) :: p, blocks
        contact_blocks_bytes = blocks*8.0_wp*real(p, wp)**2
    end function contact_blocks_bytes

    !> STATUS_BAD_INPUT when `blocks` (contact_peak_blocks) dense p x p arrays of the
    !> problem's p contact nodes need more than `available` bytes (default:
    !> available_memory_bytes(); a negative value skips the check), naming the scene's nx and
    !> ny or mesh file, the estimate and the memory available.
    subroutine check_contact_memory(scn, p, blocks, stat, available)
        type(scene_t), intent(in) :: scn
        integer, intent(in) :: p                       !! contact nodes
        integer, intent(in) :: blocks
        type(status_t), intent(out) :: stat
        integer(i8), intent(in), optional :: available   !! bytes
        integer(i8) :: limit
        real(wp) :: needed

        if (present(available)) then
            limit = available
        else
            limit = available_memory_bytes()
        end if
        if (limit < 0) return
        needed = contact_blocks_bytes(p, blocks)
        if (needed <= real(limit, wp)) return
        call stat%fail(STATUS_BAD_INPUT, scn%name//': &mesh: '//scn%mesh_words()// &
            ': the contact boundary has p = '//to_string(p)//' nodes; its dense blocks ('// &
            to_string(blocks)//' p x p doubles) need an estimated '// &
            gigabytes(needed)//' GB, more than the '//gigabytes(real(limit, wp))// &
            ' GB this machine has available (MemAvailable, /proc/meminfo); expected fewer ' &
            //'nodes on the contact boundary (at most about '//to_string(largest_p())//')')

    contains

        !> The largest p whose blocks fit in the memory available.
        integer function largest_p()
            largest_p = int(sqrt(real(limit, wp)/(8.0_wp*blocks)))
        end function largest_p
    end subroutine check_contact_memory

    !> STATUS_SOLVER (exit 5) when the address-space limit (ulimit -v) leaves less room than
    !> OpenBLAS's buffers still to be mapped need (BLAS_BUFFER_BYTES each) with SPARE_BYTES:
    !> checked before any BLAS call, since OpenBLAS would hang retrying. Its threads map
    !> their buffers as they start, which may not have happened yet: when the room does not
    !> hold a buffer for every thread, the check waits (THREAD_WAIT_SECONDS at most) for
    !> them to sleep, and counts a buffer for each still running (retrying its mmap) and one
    !> for the calling thread. So the limit asked for is the same in every run: the process
    !> without its buffers, plus all of them and the spare. Arguments for the tests:
    !> `headroom` (default address_space_headroom_bytes(); negative: no limit, no check),
    !> `blas_threads` (default OpenBLAS's count, the calling thread included) and `running`
    !> (the threads found running after the wait; given, no wait).
    subroutine check_address_space(stat, headroom, blas_threads, running)
        type(status_t), intent(out) :: stat
        integer(i8), intent(in), optional :: headroom   !! bytes
        integer, intent(in), optional :: blas_threads, running
        integer(i8) :: room, need
        integer :: threads, still, unmapped
        character(len=:), allocatable :: library, blas_config

        if (present(headroom)) then
            room = headroom
        else
            room = address_space_headroom_bytes()
        end if
        if (room < 0) return
        if (present(blas_threads)) then
            threads = max(1, blas_threads)
        else
            call blas_in_use(library, blas_config, threads)
            threads = max(1, threads)
        end if
        ! Room for every buffer, whichever the threads have mapped already: nothing to wait for.
        if (room >= threads*BLAS_BUFFER_BYTES + SPARE_BYTES) return
        if (present(running)) then
            still = running
        else
            still = threads_still_running(real(THREAD_WAIT_SECONDS, c_double))
            if (.not. present(headroom)) room = address_space_headroom_bytes()
        end if
        if (still < 0) still = threads - 1   ! /proc cannot tell: count every buffer
        unmapped = min(threads, 1 + still)
        need = unmapped*BLAS_BUFFER_BYTES + SPARE_BYTES
        if (room >= need) return
        call stat%fail(STATUS_SOLVER, 'the address-space limit (ulimit -v) leaves '// &
            megabytes(room)//' MB to map, less than the '//megabytes(need)// &
            ' MB OpenBLAS still needs (a 128 MiB buffer for '//to_string(unmapped)//' of its '// &
            to_string(threads)//' threads and 64 MiB to spare; it would retry its buffer for '// &
            'ever); expected a limit at least '//megabytes(need - room)//' MB higher')

    contains

        function megabytes(bytes) result(text)
            integer(i8), intent(in) :: bytes
            character(len=:), allocatable :: text
            text = to_string(int((bytes + 999999_i8)/1000000_i8))
        end function megabytes
    end subroutine check_address_space

    !> Bytes as GB (1e9) with one decimal: '32.0'.
    function gigabytes(bytes) result(text)
        real(wp), intent(in) :: bytes
        character(len=:), allocatable :: text
        character(len=32) :: buffer
        write (buffer, '(f0.1)') bytes/1.0e9_wp
        text = trim(buffer)
        if (text(1:1) == '.') text = '0'//text
    end function gigabytes
end module memory_budget
