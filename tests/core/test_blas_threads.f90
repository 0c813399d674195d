! SPDX-License-Identifier: MIT
!> policy_threads against its documented rule (docs/performance.md, "BLAS threads"): one
!> thread per THREAD_DOFS rows of the factor, at most the cores less the load of other
!> processes (to the nearest core, an unknown load as none), at least one. Each check names
!> the rule's clause it tests; all are integer logic, no timing and no BLAS involved.
program test_blas_threads
    use kinds, only: wp
    use blas_threads, only: policy_threads, THREAD_DOFS
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_blas_threads'
    call small_factor_one_thread(t)
    call one_thread_per_thread_dofs(t)
    call at_most_the_cores(t)
    call others_load_takes_cores(t)
    call unknown_load_is_none(t)
    call monotone(t)
    call t%report()

contains

    !> Below two THREAD_DOFS rows a factor has one thread, on any number of idle cores.
    subroutine small_factor_one_thread(t)
        type(test_suite_t), intent(inout) :: t
        integer :: order
        logical :: ok
        ok = .true.
        do order = 1, 2*THREAD_DOFS - 1, 997
            ok = ok .and. policy_threads(order, 64, 0.0_wp) == 1
        end do
        ok = ok .and. policy_threads(2*THREAD_DOFS - 1, 64, 0.0_wp) == 1
        call t%check('a factor below 2 THREAD_DOFS rows: one thread on 64 idle cores', ok)
    end subroutine small_factor_one_thread

    !> On many idle cores, k THREAD_DOFS rows (and up to one row less than k + 1) get k.
    subroutine one_thread_per_thread_dofs(t)
        type(test_suite_t), intent(inout) :: t
        integer :: k
        logical :: ok
        ok = .true.
        do k = 2, 16
            ok = ok .and. policy_threads(k*THREAD_DOFS, 64, 0.0_wp) == k .and. &
                 policy_threads((k + 1)*THREAD_DOFS - 1, 64, 0.0_wp) == k
        end do
        call t%check('k THREAD_DOFS rows on 64 idle cores: k threads (k = 2..16)', ok)
    end subroutine one_thread_per_thread_dofs

    !> A factor large enough for more: the cores, and one on one core.
    subroutine at_most_the_cores(t)
        type(test_suite_t), intent(inout) :: t
        integer :: cores
        logical :: ok
        ok = .true.
        do cores = 1, 8
            ok = ok .and. policy_threads(100*THREAD_DOFS, cores, 0.0_wp) == cores
        end do
        call t%check('100 THREAD_DOFS rows on 1..8 idle cores: one thread per core', ok)
    end subroutine at_most_the_cores

    !> Other processes' load takes cores, rounded to the nearest: on 8 cores a load of 2.4
    !> leaves 6, of 2.6 leaves 5; a load of the cores or more leaves one thread.
    subroutine others_load_takes_cores(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: BIG = 100*THREAD_DOFS
        call t%check('load 2.4 of others on 8 cores: 6 threads, 2.6: 5, 8: 1, 30: 1', &
                     policy_threads(BIG, 8, 2.4_wp) == 6 .and. &
                     policy_threads(BIG, 8, 2.6_wp) == 5 .and. &
                     policy_threads(BIG, 8, 8.0_wp) == 1 .and. &
                     policy_threads(BIG, 8, 30.0_wp) == 1 .and. &
                     policy_threads(BIG, 2, 0.4_wp) == 2 .and. &
                     policy_threads(BIG, 2, 0.6_wp) == 1)
    end subroutine others_load_takes_cores

    !> A negative load (the load average could not be read) counts as an idle machine.
    subroutine unknown_load_is_none(t)
        type(test_suite_t), intent(inout) :: t
        call t%check('unknown load (-1): as idle cores', &
                     policy_threads(100*THREAD_DOFS, 8, -1.0_wp) == 8 .and. &
                     policy_threads(3*THREAD_DOFS, 8, -1.0_wp) == 3)
    end subroutine unknown_load_is_none

    !> More rows never mean fewer threads, more load never more, and the count stays within
    !> 1 and the cores, over a grid of orders, cores and loads.
    subroutine monotone(t)
        type(test_suite_t), intent(inout) :: t
        integer :: cores, i, j, now, bigger, busier
        real(wp) :: load
        logical :: ok
        ok = .true.
        do cores = 1, 6
            do i = 0, 40
                do j = 0, 16
                    load = 0.5_wp*j
                    now = policy_threads(i*THREAD_DOFS/2 + 1, cores, load)
                    bigger = policy_threads((i + 1)*THREAD_DOFS/2 + 1, cores, load)
                    busier = policy_threads(i*THREAD_DOFS/2 + 1, cores, load + 0.5_wp)
                    ok = ok .and. now >= 1 .and. now <= cores .and. bigger >= now .and. &
                         busier <= now
                end do
            end do
        end do
        call t%check('non-decreasing in the order, non-increasing in the load, in [1, cores]', &
                     ok)
    end subroutine monotone

end program test_blas_threads
