! SPDX-License-Identifier: MIT
!> Wall-clock phase timings of a run, as reported in summary.json and on stdout, and the
!> progress line each phase gives as it ends (to whoever listens: the program prints them).
module timer
    use kinds, only: wp, i8
    use strings, only: seconds_text
    implicit none
    private
    public :: wall_time, progress_listener
    public :: PHASE_ASSEMBLY, PHASE_ORDERING, PHASE_FACTOR, PHASE_REDUCTION, PHASE_EIGEN, &
              PHASE_OUTPUT

    integer, parameter :: PHASE_ASSEMBLY = 1, PHASE_ORDERING = 2, PHASE_FACTOR = 3, &
                          PHASE_REDUCTION = 4, PHASE_EIGEN = 5, PHASE_OUTPUT = 6
    character(len=*), parameter :: PHASE_NAMES(6) = [character(len=10) :: 'assembly', &
        'ordering', 'factor', 'reduction', 'eigen', 'output']
    !> Loops report at most this often (s), so a fast run prints no step lines at all.
    real(wp), parameter :: TICK_SECONDS = 1.0_wp

    abstract interface
        !> Receives one line of progress, already formatted.
        subroutine progress_listener(line)
            character(len=*), intent(in) :: line
        end subroutine progress_listener
    end interface

    type, public :: timings_t
        real(wp) :: assembly = 0.0_wp   !! mesh, dof map, K, M, B
        real(wp) :: factor = 0.0_wp     !! sparse factorization(s)
        real(wp) :: ordering = 0.0_wp   !! fill-reducing ordering computed by nceig (METIS)
        real(wp) :: reduction = 0.0_wp  !! contact blocks Kt_nn, Kt_nt and the reduced matrix
        real(wp) :: eigen = 0.0_wp      !! eigen-solve, eigenvectors and residuals
        real(wp) :: output = 0.0_wp     !! files
        real(wp) :: total = 0.0_wp
        !> Hears of each phase as it ends and of long loops; none: silent.
        procedure(progress_listener), pointer, nopass :: listener => null()
        real(wp) :: last_tick = 0.0_wp     !! wall_time() of the loop's start or last line
        logical :: ticked = .false.        !! a step line of the current loop was told
    contains
        procedure :: add => timings_add
        procedure :: tick => timings_tick
        procedure :: note => timings_note
    end type timings_t

contains

    !> Seconds since an arbitrary origin, from the 64-bit system clock. A build configured
    !> with -DNCEIG_CPU_TIMERS=ON (CMakeLists.txt) reads the process's CPU time instead, all
    !> threads summed: its phase lines then say where the CPU goes on a machine whose load
    !> stretches the wall clock (docs/thresholds.md, "The boundary searched once").
    real(wp) function wall_time()
#ifdef NCEIG_CPU_TIMERS
        call cpu_time(wall_time)
#else
        integer(i8) :: count, rate
        call system_clock(count, rate)
        wall_time = real(count, wp)/real(rate, wp)
#endif
    end function wall_time

    !> Add `seconds` to phase `phase` (PHASE_*) and tell the listener, with `detail` (what
    !> was done: sizes, the solver) after the time.
    subroutine timings_add(this, phase, seconds, detail)
        class(timings_t), intent(inout) :: this
        integer, intent(in) :: phase
        real(wp), intent(in) :: seconds
        character(len=*), intent(in), optional :: detail
        select case (phase)
        case (PHASE_ASSEMBLY); this%assembly = this%assembly + seconds
        case (PHASE_ORDERING); this%ordering = this%ordering + seconds
        case (PHASE_FACTOR); this%factor = this%factor + seconds
        case (PHASE_REDUCTION); this%reduction = this%reduction + seconds
        case (PHASE_EIGEN); this%eigen = this%eigen + seconds
        case (PHASE_OUTPUT); this%output = this%output + seconds
        end select
        if (.not. associated(this%listener)) return
        if (present(detail)) then
            call this%listener('  .. '//PHASE_NAMES(phase)//' '//seconds_text(seconds)//' s'// &
                               detail)
        else
            call this%listener('  .. '//PHASE_NAMES(phase)//' '//seconds_text(seconds)//' s')
        end if
    end subroutine timings_add

    !> A progress line outside the phases (e.g. the thresholds of a sweep run).
    subroutine timings_note(this, text)
        class(timings_t), intent(inout) :: this
        character(len=*), intent(in) :: text
        if (associated(this%listener)) call this%listener('  .. '//text)
    end subroutine timings_note

    !> Step `i` of `n` of a loop (`what` names it), told at most every TICK_SECONDS, and the
    !> last step too once any was told: a loop shorter than TICK_SECONDS prints nothing.
    subroutine timings_tick(this, what, i, n)
        class(timings_t), intent(inout) :: this
        character(len=*), intent(in) :: what
        integer, intent(in) :: i, n
        character(len=24) :: counts
        real(wp) :: now
        if (.not. associated(this%listener)) return
        now = wall_time()
        if (i <= 1) then
            this%last_tick = now
            this%ticked = .false.
            return
        end if
        if (now - this%last_tick < TICK_SECONDS .and. .not. (i == n .and. this%ticked)) return
        this%last_tick = now
        this%ticked = .true.
        write (counts, '(i0, "/", i0)') i, n
        call this%listener('  .. '//what//' '//trim(counts))
    end subroutine timings_tick
end module timer
