! SPDX-License-Identifier: MIT
!> The listener of test_timer, outside the program: a procedure pointer to an internal
!> procedure needs a trampoline on an executable stack.
module timer_listener
    implicit none
    private
    public :: listen, HEARD_PATH

    character(len=*), parameter :: HEARD_PATH = 'test_timer.heard'

contains

    !> The listener: each line appended to HEARD_PATH.
    subroutine listen(line)
        character(len=*), intent(in) :: line
        integer :: unit
        open (newunit=unit, file=HEARD_PATH, position='append', action='write')
        write (unit, '(a)') line
        close (unit)
    end subroutine listen
end module timer_listener

!> Phase timings add up per phase, the listener hears each phase as one formatted line, and
!> a loop's steps are told at most once per TICK second (never by a fast loop). No wall
!> time is asserted: the clock is moved by hand where a step must be due. The listener
!> writes what it hears to a file, which the program reads back.
program test_timer
    use kinds, only: wp
    use timer, only: wall_time, timings_t, PHASE_ASSEMBLY, PHASE_ORDERING, PHASE_FACTOR, &
                     PHASE_REDUCTION, PHASE_EIGEN, PHASE_OUTPUT
    use strings, only: text_t, append_text
    use text_file, only: read_line
    use timer_listener, only: listen, HEARD_PATH
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t
    type(timings_t) :: timings
    type(text_t), allocatable :: heard(:)
    real(wp) :: first, second
    integer :: i, status

    t%name = 'test_timer'
    open (newunit=i, file=HEARD_PATH, status='replace')
    close (i, status='delete')
    allocate (heard(0))

    first = wall_time()
    second = wall_time()
    call t%check('wall_time never goes back', second >= first)

    ! without a listener: sums only
    call timings%add(PHASE_FACTOR, 0.25_wp)
    call timings%add(PHASE_FACTOR, 0.5_wp)
    call timings%add(PHASE_ASSEMBLY, 1.0_wp)
    call timings%add(PHASE_ORDERING, 2.0_wp)
    call timings%add(PHASE_REDUCTION, 3.0_wp)
    call timings%add(PHASE_EIGEN, 4.0_wp)
    call timings%add(PHASE_OUTPUT, 5.0_wp)
    call t%check('add: each phase sums its own times (0.25 + 0.5 = 0.75 exactly)', &
                 all(abs([timings%factor, timings%assembly, timings%ordering, &
                          timings%reduction, timings%eigen, timings%output] - &
                         [0.75_wp, 1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp, 5.0_wp]) <= 0.0_wp))
    call timings%note('silent')
    call hear()
    call t%check('note: nothing heard without a listener', size(heard) == 0)

    timings%listener => listen
    call timings%add(PHASE_EIGEN, 0.0421_wp, ': arpack')
    call timings%add(PHASE_OUTPUT, 1.5_wp)
    call hear()
    call t%check('add: the listener hears the phase, its time and the detail', &
                 size(heard) == 2 .and. heard(1)%text == '  .. eigen      0.042 s: arpack' &
                 .and. heard(2)%text == '  .. output     1.500 s')
    call timings%note('sweep point 3')
    call hear()
    call t%check('note: one line', heard(size(heard))%text == '  .. sweep point 3')

    ! a loop faster than a tick says nothing
    do i = 1, 50
        call timings%tick('level', i, 50)
    end do
    call hear()
    call t%check('tick: a fast loop prints no step', size(heard) == 3)
    ! a step due: the last tick a second and more ago
    call timings%tick('level', 1, 4)
    timings%last_tick = timings%last_tick - 2.0_wp
    call timings%tick('level', 2, 4)
    call timings%tick('level', 3, 4)
    call timings%tick('level', 4, 4)
    call hear()
    call t%check('tick: a step due is told, then the last one', size(heard) == 5 .and. &
                 heard(4)%text == '  .. level 2/4' .and. heard(5)%text == '  .. level 4/4')
    open (newunit=i, file=HEARD_PATH, status='old', iostat=status)
    if (status == 0) close (i, status='delete')
    deallocate (heard)   ! (AddressSanitizer reports a main program's allocatables)
    call t%report()

contains

    !> heard = the lines of HEARD_PATH so far.
    subroutine hear()
        character(len=:), allocatable :: line
        character(len=256) :: msg
        integer :: unit, ios
        deallocate (heard)
        allocate (heard(0))
        open (newunit=unit, file=HEARD_PATH, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do
            call read_line(unit, line, ios, msg)
            if (ios /= 0) exit
            call append_text(heard, line)
        end do
        close (unit)
    end subroutine hear
end program test_timer
