! SPDX-License-Identifier: MIT
!> Working precision and the few constants every module shares.
module kinds
    use iso_fortran_env, only: real64, int64
    implicit none
    private
    public :: wp, i8, PI

    integer, parameter :: wp = real64   !! all floating-point work is double precision
    integer, parameter :: i8 = int64    !! counts that can exceed 2**31 (nnz of factors, bytes)
    real(wp), parameter :: PI = 3.14159265358979323846264338327950288_wp
end module kinds
