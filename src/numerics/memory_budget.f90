! SPDX-License-Identifier: MIT
!> Refuse, before any of it is allocated, a run whose dense contact blocks exceed the memory
!> of the machine: thin strips with many contact nodes asked for tens of GB, then failed
!> inside the allocator with a backtrace, or swapped for minutes.
module memory_budget
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_SOLVER
    use strings, only: to_string
    use scene, only: scene_t
    use system_memory, only: available_memory_bytes, address_space_headroom_bytes
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
    !> Address space a BLAS call needs beyond what the process maps: OpenBLAS's buffer
    !> (BUFFER_SIZE, 128 MiB on x86_64) and room to spare (64 MiB, a glibc malloc arena).
    !> Under less, OpenBLAS retries its failed mmap for ever (blas_memory_alloc, inside
    !> CHOLMOD). Measured (P1 64 x 64, 2 threads): hangs with 168 MB of headroom, runs with
    !> 189 MB; its worker threads' buffers are mapped when the library loads, so the number
    !> of threads does not change it.
    integer(i8), parameter :: BLAS_HEADROOM_BYTES = 192_i8*1048576_i8

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
    !> a BLAS call needs: checked before any library call, since OpenBLAS would hang
    !> retrying its allocation. `headroom` defaults to this process's
    !> (address_space_headroom_bytes); a negative headroom (no limit) skips the check.
    subroutine check_address_space(stat, headroom)
        type(status_t), intent(out) :: stat
        integer(i8), intent(in), optional :: headroom   !! bytes
        integer(i8) :: room

        if (present(headroom)) then
            room = headroom
        else
            room = address_space_headroom_bytes()
        end if
        if (room < 0 .or. room >= BLAS_HEADROOM_BYTES) return
        call stat%fail(STATUS_SOLVER, 'the address-space limit (ulimit -v) leaves '// &
            megabytes(room)//' MB to map, less than the '//megabytes(BLAS_HEADROOM_BYTES)// &
            ' MB a BLAS call needs (OpenBLAS would retry its 128 MiB buffer for ever); '// &
            'expected a limit at least '//megabytes(BLAS_HEADROOM_BYTES - room)//' MB higher')

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
