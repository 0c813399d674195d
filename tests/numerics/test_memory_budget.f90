! SPDX-License-Identifier: MIT
!> The memory guard of the dense contact blocks: the estimate (10 or 8 p^2 doubles), the refusal
!> naming nx and ny (or the mesh file), the estimate and the memory available, and the
!> reading of MemAvailable (else MemTotal) from a meminfo file.
program test_memory_budget
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_SOLVER
    use scene, only: scene_t, MESH_RECTANGLE, MESH_GMSH
    use memory_budget, only: contact_blocks_bytes, check_contact_memory, contact_peak_blocks, &
                             check_address_space
    use system_memory, only: available_memory_bytes
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t
    type(scene_t) :: strip
    type(status_t) :: stat
    integer(i8) :: here

    t%name = 'test_memory_budget'
    call t%check('10 blocks when Kt_nn and Kt_nt are formed, 8 for ARPACK unshifted', &
                 contact_peak_blocks(.false.) == 10 .and. contact_peak_blocks(.true.) == 8)
    call t%check_close('estimate: 80 p^2 bytes', contact_blocks_bytes(10001, 10), &
                       80.0_wp*10001.0_wp**2, 1.0e-15_wp)

    ! ulimit -v: OpenBLAS hung retrying its 128 MiB buffer under 100 MB of address space.
    call check_address_space(stat, headroom=35_i8*1000000_i8, blas_threads=2, running=0)
    call t%check('address space: 35 MB of headroom is refused, exit 5, naming ulimit -v', &
                 stat%code == STATUS_SOLVER .and. index(stat%message, 'ulimit -v') > 0 .and. &
                 index(stat%message, 'leaves 35 MB') > 0)
    call check_address_space(stat, headroom=1024_i8**3)
    call t%check('address space: 1 GiB of headroom, or no limit, passes', stat%ok())
    call check_address_space(stat, headroom=-1_i8)
    call t%check('address space: no limit (-1) passes', stat%ok())
    call check_address_space_accounting()

    strip%name = 'strip.nml'
    strip%source = MESH_RECTANGLE
    strip%nx = 20000
    strip%ny = 1
    call check_contact_memory(strip, 20001, 10, stat, available=16_i8*1024_i8**3)
    call t%check('thin strip over the budget: bad input', stat%code == STATUS_BAD_INPUT)
    if (.not. stat%ok()) then
        print '(a)', '      '//stat%message
        call t%check('names the input, &mesh, nx and ny', &
                     index(stat%message, 'strip.nml: &mesh: nx = 20000, ny = 1: ') == 1)
        call t%check('gives p, the estimate and the memory available', &
                     index(stat%message, 'p = 20001') > 0 .and. &
                     index(stat%message, 'estimated 32.0 GB') > 0 .and. &
                     index(stat%message, 'than the 17.2 GB') > 0)
    end if
    call check_contact_memory(strip, 2001, 10, stat, available=16_i8*1024_i8**3)
    call t%check('p = 2001 (320 MB) fits in 16 GiB', stat%ok())
    call check_contact_memory(strip, 20001, 10, stat, available=-1_i8)
    call t%check('no memory figure (not Linux): no check', stat%ok())

    strip%source = MESH_GMSH
    strip%file = 'meshes/long.msh'
    call check_contact_memory(strip, 50000, 8, stat, available=1024_i8**3)
    call t%check('a Gmsh mesh: names the file', &
                 index(stat%message, 'strip.nml: &mesh: file = ''meshes/long.msh'': ') == 1)

    call write_meminfo('meminfo_new', [character(len=40) :: 'MemTotal:       32000000 kB', &
                       'MemFree:         1000000 kB', 'MemAvailable:   20000000 kB'])
    call t%check('MemAvailable read, in bytes', &
                 available_memory_bytes('meminfo_new') == 20000000_i8*1024)
    call write_meminfo('meminfo_old', [character(len=40) :: 'MemTotal:       32000000 kB', &
                       'MemFree:         1000000 kB'])
    call t%check('without MemAvailable: MemTotal', &
                 available_memory_bytes('meminfo_old') == 32000000_i8*1024)
    call t%check('no such file: -1', available_memory_bytes('no/such/meminfo') == -1)
    here = available_memory_bytes()
    call t%check('this machine reports a positive figure or none', here > 0 .or. here == -1)
    call t%report()

contains

    !> The buffers still to map: 128 MiB and a page (BLAS_BUFFER = 134221824 bytes) for the
    !> calling thread and for each OpenBLAS thread still running (retrying), and 64 MiB
    !> (67108864 bytes) to spare. The rise asked for is need - room, in MB rounded up.
    subroutine check_address_space_accounting()
        integer(i8), parameter :: BUFFER = 134221824_i8, SPARE = 67108864_i8
        integer(i8) :: room
        character(len=:), allocatable :: mapped, late

        call check_address_space(stat, headroom=300000000_i8, blas_threads=2, running=0)
        call t%check('address space: 300 MB hold the calling thread''s buffer and the spare', &
                     stat%ok())
        call check_address_space(stat, headroom=150000000_i8, blas_threads=2, running=0)
        ! 134221824 + 67108864 - 150000000 = 51330688 bytes: 52 MB
        call t%check('address space: 150 MB are 52 MB short of one buffer and the spare', &
                     index(stat%message, 'at least 52 MB higher') > 0)
        call check_address_space(stat, headroom=150000000_i8, blas_threads=2, running=1)
        ! 2 buffers + spare - 150000000 = 185552512 bytes: 186 MB
        call t%check('address space: a thread still retrying needs its buffer too: 186 MB', &
                     index(stat%message, 'at least 186 MB higher') > 0)
        call check_address_space(stat, headroom=2*BUFFER + SPARE, blas_threads=2, running=1)
        call t%check('address space: room for every buffer passes without waiting', stat%ok())
        call check_address_space(stat, headroom=500000000_i8, blas_threads=4, running=3)
        ! 4 buffers + spare - 500000000 = 103996160 bytes: 104 MB
        call t%check('address space: 4 threads, 3 retrying: 104 MB short', &
                     index(stat%message, 'at least 104 MB higher') > 0)
        ! The same process with OpenBLAS's thread's buffer mapped, or not mapped (its mmap
        ! failed and it retries): the room differs by that buffer, the limit asked does not.
        room = 120000000_i8
        call check_address_space(stat, headroom=room, blas_threads=2, running=0)
        mapped = stat%message(index(stat%message, 'at least'):)
        call check_address_space(stat, headroom=room + BUFFER, blas_threads=2, running=1)
        late = stat%message(index(stat%message, 'at least'):)
        call t%check('address space: the rise asked for does not depend on the thread''s state', &
                     mapped == late .and. index(mapped, 'at least 82 MB higher') == 1)
    end subroutine check_address_space_accounting

    subroutine write_meminfo(path, lines)
        character(len=*), intent(in) :: path, lines(:)
        integer :: unit, i
        open (newunit=unit, file=path, status='replace', action='write')
        do i = 1, size(lines)
            write (unit, '(a)') trim(lines(i))
        end do
        close (unit)
    end subroutine write_meminfo
end program test_memory_budget
