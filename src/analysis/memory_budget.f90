! SPDX-License-Identifier: MIT
!> Refuse, before any of it is allocated, a run whose dense contact blocks exceed the memory
!> of the machine: thin strips with many contact nodes asked for tens of GB, then failed
!> inside the allocator with a backtrace, or swapped for minutes.
module memory_budget
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: to_string
    use run_config, only: config_t
    use system_memory, only: available_memory_bytes
    implicit none
    private
    public :: contact_blocks_bytes, check_contact_memory

    !> Dense p x p arrays alive at once at the peak of every eigen analysis (contact_reduction:
    !> flexibility_blocks): the trailing 2p x 2p block L_c of the factor of K (4) and its
    !> inverse S^-1 (4), then Kt_nn and Kt_nt (1 each). ARPACK keeps L_c while forming them
    !> (same peak); later stages (dgeevx: A, VL, VR and Kt_nt; dggev for the thresholds: two
    !> copies of the blocks and VR) hold at most 7.
    integer, parameter :: PEAK_DENSE_BLOCKS = 10

contains

    !> Bytes of the dense contact blocks for p contact nodes: PEAK_DENSE_BLOCKS p^2 doubles
    !> (real: 80 p^2 overflows 64-bit integers from p = 3.4e8).
    pure real(wp) function contact_blocks_bytes(p)
        integer, intent(in) :: p
        contact_blocks_bytes = PEAK_DENSE_BLOCKS*8.0_wp*real(p, wp)**2
    end function contact_blocks_bytes

    !> STATUS_BAD_INPUT when the contact blocks of the problem's p contact nodes need more
    !> than `available` bytes (default: available_memory_bytes(); a negative value skips the
    !> check), naming nx and ny or the mesh file, the estimate and the memory available.
    subroutine check_contact_memory(config, p, stat, available)
        type(config_t), intent(in) :: config
        integer, intent(in) :: p                       !! contact nodes
        type(status_t), intent(out) :: stat
        integer(i8), intent(in), optional :: available   !! bytes
        integer(i8) :: limit
        real(wp) :: needed
        character(len=:), allocatable :: source

        if (present(available)) then
            limit = available
        else
            limit = available_memory_bytes()
        end if
        if (limit < 0) return
        needed = contact_blocks_bytes(p)
        if (needed <= real(limit, wp)) return
        if (trim(config%mesh%source) == 'gmsh') then
            source = 'file = '''//trim(config%mesh%file)//''''
        else
            source = 'nx = '//to_string(config%mesh%nx)//', ny = '//to_string(config%mesh%ny)
        end if
        call stat%fail(STATUS_BAD_INPUT, config%input_file//': &mesh: '//source// &
            ': the contact boundary has p = '//to_string(p)//' nodes; its dense blocks ('// &
            to_string(PEAK_DENSE_BLOCKS)//' p x p doubles) need an estimated '// &
            gigabytes(needed)//' GB, more than the '//gigabytes(real(limit, wp))// &
            ' GB this machine has available (MemAvailable, /proc/meminfo); expected fewer ' &
            //'nodes on the contact boundary (at most about '//to_string(largest_p(limit))//')')
    end subroutine check_contact_memory

    !> The largest p whose blocks fit in `bytes`.
    pure integer function largest_p(bytes)
        integer(i8), intent(in) :: bytes
        largest_p = int(sqrt(real(bytes, wp)/(8.0_wp*PEAK_DENSE_BLOCKS)))
    end function largest_p

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
