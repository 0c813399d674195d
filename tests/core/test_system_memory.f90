! SPDX-License-Identifier: MIT
!> available_memory_bytes reads MemAvailable (else MemTotal) of a meminfo file in KiB, and
!> -1 when it cannot; address_space_headroom_bytes is -1 without a limit and, under
!> `ulimit -v`, what remains of the limit: checked in a child run of this program.
program test_system_memory
    use kinds, only: i8
    use system_memory, only: available_memory_bytes, address_space_headroom_bytes, MEMINFO_PATH
    use testing, only: test_suite_t
    implicit none

    character(len=*), parameter :: FAKE = 'test_system_memory.meminfo'
    character(len=*), parameter :: CHILD_OUT = 'test_system_memory.child'
    character(len=*), parameter :: CHILD_ERR = 'test_system_memory.child_err'
    !> the limit of the child, KiB: more than it maps (libraries, OpenBLAS's buffers)
    integer(i8), parameter :: LIMIT_KIB = 8000000_i8
    type(test_suite_t) :: t
    character(len=4096) :: self
    character(len=16) :: mode
    integer(i8) :: bytes, headroom
    integer :: unit, ios, status

    call get_command_argument(1, mode)
    if (mode == '--headroom') then   ! the child: print what it sees, nothing else
        print '(i0)', address_space_headroom_bytes()
        stop
    end if
    t%name = 'test_system_memory'

    call write_fake('MemTotal:       16000000 kB'//new_line('a')// &
                    'MemFree:         1000000 kB'//new_line('a')// &
                    'MemAvailable:    12345678 kB'//new_line('a'))
    call t%check('MemAvailable in KiB, as bytes', available_memory_bytes(FAKE) == &
                 1024_i8*12345678_i8)
    call write_fake('MemTotal:       16000000 kB'//new_line('a')// &
                    'MemFree:         1000000 kB'//new_line('a'))
    call t%check('no MemAvailable (an old kernel): MemTotal', available_memory_bytes(FAKE) &
                 == 1024_i8*16000000_i8)
    call write_fake('MemAvailable:    lots kB'//new_line('a'))
    call t%check('no number: -1, a check skipped', available_memory_bytes(FAKE) == -1_i8)
    open (newunit=unit, file=FAKE, status='old')
    close (unit, status='delete')
    call t%check('no file: -1', available_memory_bytes(FAKE) == -1_i8)
    bytes = available_memory_bytes()
    call t%check('this machine ('//MEMINFO_PATH//'): some memory, below 2^50 bytes', &
                 bytes > 0_i8 .and. bytes < 2_i8**50)

    ! here, under ctest, no address-space limit
    headroom = address_space_headroom_bytes()
    call get_command_argument(0, self)
    call execute_command_line('ulimit -v '//trim(int_text(LIMIT_KIB))//' && '// &
                              trim(self)//' --headroom > '//CHILD_OUT//' 2> '//CHILD_ERR, &
                              exitstat=status)
    open (newunit=unit, file=CHILD_OUT, status='old', action='read', iostat=ios)
    if (ios == 0) read (unit, *, iostat=ios) bytes
    if (ios == 0) close (unit, status='delete')
    if (under_sanitizer()) then
        ! AddressSanitizer reserves terabytes of shadow memory at start: under any
        ! ulimit -v the child cannot even start; Release and Debug check it
        print '(a)', 'SKIP  address_space_headroom_bytes under ulimit -v: AddressSanitizer'
        call t%check('address_space_headroom_bytes: -1 without a limit', headroom == -1_i8)
    else
        call t%check('address_space_headroom_bytes: -1 without a limit, under ulimit -v L '// &
                     'the part of L not mapped yet (0 < headroom < L)', headroom == -1_i8 .and. &
                     status == 0 .and. ios == 0 .and. bytes > 0_i8 .and. &
                     bytes < 1024_i8*LIMIT_KIB)
    end if
    open (newunit=unit, file=CHILD_ERR, status='old', iostat=ios)
    if (ios == 0) close (unit, status='delete')
    call t%report()

contains

    !> Whether the child failed because AddressSanitizer could not start under the limit.
    logical function under_sanitizer()
        character(len=512) :: line
        integer :: unit, ios
        under_sanitizer = .false.
        open (newunit=unit, file=CHILD_ERR, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do
            read (unit, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (index(line, 'AddressSanitizer') > 0) under_sanitizer = .true.
        end do
        close (unit)
    end function under_sanitizer

    subroutine write_fake(text)
        character(len=*), intent(in) :: text
        integer :: unit
        open (newunit=unit, file=FAKE, access='stream', form='unformatted', status='replace')
        write (unit) text
        close (unit)
    end subroutine write_fake

    pure function int_text(i) result(text)
        integer(i8), intent(in) :: i
        character(len=24) :: text
        write (text, '(i0)') i
    end function int_text
end program test_system_memory
