! SPDX-License-Identifier: MIT
!> Wall-clock phase timings of a run, as reported in summary.json and on stdout.
module timer
    use kinds, only: wp, i8
    implicit none
    private
    public :: wall_time

    type, public :: timings_t
        real(wp) :: assembly = 0.0_wp   !! mesh, dof map, K, M, B
        real(wp) :: factor = 0.0_wp     !! sparse factorization(s)
        real(wp) :: ordering = 0.0_wp   !! fill-reducing ordering computed by nceig (METIS)
        real(wp) :: reduction = 0.0_wp  !! contact blocks Kt_nn, Kt_nt and the reduced matrix
        real(wp) :: eigen = 0.0_wp      !! eigen-solve, eigenvectors and residuals
        real(wp) :: output = 0.0_wp     !! files
        real(wp) :: total = 0.0_wp
    end type timings_t

contains

    !> Seconds since an arbitrary origin, from the 64-bit system clock.
    real(wp) function wall_time()
        integer(i8) :: count, rate
        call system_clock(count, rate)
        wall_time = real(count, wp)/real(rate, wp)
    end function wall_time
end module timer
