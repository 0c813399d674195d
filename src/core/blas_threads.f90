! SPDX-License-Identifier: MIT
!> How many threads the BLAS gets for a sparse factorization (docs/performance.md, "BLAS
!> threads"). Threads pay only on a large factor and on cores nobody else uses: on a small
!> factor, or beside other busy processes, OpenBLAS's threads wait for each other and a run
!> took several times longer for the same CPU time. So each factorization sets the count for
!> its own order, and everything that works on that factor (its solves, the dense contact
!> blocks formed from it) runs on that count. A count the user gives in the environment
!> (OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS, OMP_NUM_THREADS) always wins; a BLAS without
!> openblas_set_num_threads (the reference BLAS) keeps its own.
module blas_threads
    use iso_c_binding, only: c_int, c_double
    use kinds, only: wp
    implicit none
    private
    public :: policy_threads, blas_threads_for, blas_threads_source, environment_threads
    public :: THREAD_DOFS

    !> Rows of the factor per thread: a factor of order n gets n / THREAD_DOFS threads, so
    !> two from 2 THREAD_DOFS rows on: on idle cores two threads gained from 33024 rows on
    !> and nothing below (docs/performance.md, "BLAS threads";
    !> scripts/bench/bench_blas_threads.sh --crossover measures it on other cores).
    integer, parameter :: THREAD_DOFS = 20000

    interface
        integer(c_int) function nceig_blas_environment_threads() &
                bind(C, name='nceig_blas_environment_threads')
            import :: c_int
        end function nceig_blas_environment_threads
        subroutine nceig_blas_set_threads(threads) bind(C, name='nceig_blas_set_threads')
            import :: c_int
            integer(c_int), value :: threads
        end subroutine nceig_blas_set_threads
        integer(c_int) function nceig_cpu_count() bind(C, name='nceig_cpu_count')
            import :: c_int
        end function nceig_cpu_count
        real(c_double) function nceig_load_of_others() bind(C, name='nceig_load_of_others')
            import :: c_double
        end function nceig_load_of_others
        integer(c_int) function nceig_blas_largest_threads_set() &
                bind(C, name='nceig_blas_largest_threads_set')
            import :: c_int
        end function nceig_blas_largest_threads_set
    end interface

contains

    !> The rule: one thread per THREAD_DOFS rows of a factor of order `order`, at most the
    !> `cores` this process may use less the load `others_load` of other processes (rounded
    !> to the nearest core; a negative load is unknown and counts as none), at least one.
    pure integer function policy_threads(order, cores, others_load)
        integer, intent(in) :: order, cores
        real(wp), intent(in) :: others_load
        integer :: idle
        idle = cores - nint(max(0.0_wp, min(others_load, real(cores, wp))))
        policy_threads = max(1, min(order/THREAD_DOFS, idle, cores))
    end function policy_threads

    !> Give the BLAS the policy's count for a factorization of order `order`, unless the
    !> environment set one. A small factor gets one thread without reading the load.
    subroutine blas_threads_for(order)
        integer, intent(in) :: order
        integer :: threads
        if (environment_threads() > 0) return
        threads = 1
        if (order/THREAD_DOFS > 1) threads = policy_threads(order, int(nceig_cpu_count()), &
                                                            real(nceig_load_of_others(), wp))
        call nceig_blas_set_threads(int(threads, c_int))
    end subroutine blas_threads_for

    !> The count the environment gives OpenBLAS (as OpenBLAS reads it), 0 if none.
    integer function environment_threads()
        environment_threads = int(nceig_blas_environment_threads())
    end function environment_threads

    !> Who chose the run's BLAS threads: 'environment' (the user's variable), 'nceig' (this
    !> policy; `largest` is then the largest count a factorization had) or 'blas' (a BLAS
    !> nceig cannot set, or no factorization yet; `largest` 0).
    subroutine blas_threads_source(source, largest)
        character(len=:), allocatable, intent(out) :: source
        integer, intent(out) :: largest
        largest = int(nceig_blas_largest_threads_set())
        if (environment_threads() > 0) then
            source = 'environment'
        else if (largest > 0) then
            source = 'nceig'
        else
            source = 'blas'
        end if
    end subroutine blas_threads_source

end module blas_threads
