! SPDX-License-Identifier: MIT
!> Richardson extrapolation of a mesh refinement sequence f(h) -> limit as h -> 0, for the
!> lowest positive eigenvalue against the mesh size. The model is f(h) = limit + C h^p with
!> unknown limit, C and order p, fitted exactly through three meshes of any sizes (the ratios
!> h1/h2 and h2/h3 need not be equal nor 2). Sequences that do not behave like that model
!> (differences changing sign, differences not shrinking) get no limit and a reason, never a
!> number extrapolated from noise.
module extrapolation
    use kinds, only: wp
    use sorting, only: sort_index
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
    implicit none
    private
    public :: richardson_fit_t, richardson_fit, family_estimate_t, family_estimate, &
              reference_index, fit_note
    public :: FIT_OK, FIT_TOO_FEW, FIT_BAD_H, FIT_NOT_FINITE, FIT_NOT_MONOTONE, &
              FIT_NOT_CONVERGING, FIT_ORDER_TOO_HIGH, FIT_CONSTANT

    integer, parameter :: FIT_OK = 0              !! limit, constant and order are set
    integer, parameter :: FIT_TOO_FEW = 1         !! fewer than three meshes with a value
    integer, parameter :: FIT_BAD_H = 2           !! a repeated or non-positive mesh size
    integer, parameter :: FIT_NOT_FINITE = 3      !! a value or size is NaN or infinite
    integer, parameter :: FIT_NOT_MONOTONE = 4    !! the two differences have opposite signs
    integer, parameter :: FIT_NOT_CONVERGING = 5  !! differences do not shrink: order <= 0
    integer, parameter :: FIT_ORDER_TOO_HIGH = 6  !! order beyond MAX_ORDER: no trust in it
    integer, parameter :: FIT_CONSTANT = 7        !! equal values: limit known, order not

    !> Beyond this observed order the three values agree to round-off and p means nothing.
    real(wp), parameter :: MAX_ORDER = 64.0_wp

    !> f(h) = limit + constant h^order through three meshes.
    type :: richardson_fit_t
        integer :: code = FIT_TOO_FEW
        real(wp) :: limit = 0.0_wp
        real(wp) :: constant = 0.0_wp
        real(wp) :: order = 0.0_wp
    end type richardson_fit_t

    !> The extrapolation of one family of meshes from its finest three, with an error estimate.
    type :: family_estimate_t
        integer :: code = FIT_TOO_FEW       !! of the fit on the finest three meshes
        integer :: previous_code = FIT_TOO_FEW  !! of the fit on the three before the finest
        integer :: n_points = 0             !! meshes with a finite value
        real(wp) :: h_used(3) = 0.0_wp      !! sizes of the finest three, coarse to fine
        real(wp) :: finest = 0.0_wp         !! value on the finest mesh
        real(wp) :: limit = 0.0_wp
        real(wp) :: constant = 0.0_wp
        real(wp) :: order = 0.0_wp
        real(wp) :: previous_limit = 0.0_wp !! limit of the previous triple (NaN if none)
        real(wp) :: previous_order = 0.0_wp
        real(wp) :: error_estimate = 0.0_wp !! estimated |limit - exact limit|
        logical :: from_two_fits = .false.  !! error_estimate = |limit - previous_limit|
    end type family_estimate_t

contains

    !> Fit f = limit + C h^p exactly through three points (h(i), f(i)), in any order.
    !> With h1 > h2 > h3 and differences d1 = f1 - f2, d2 = f2 - f3 of one sign, p solves
    !> d1/d2 = (h1^p - h2^p)/(h2^p - h3^p); the right side increases strictly with p (from
    !> ln(h1/h2)/ln(h2/h3) at p = 0+ to infinity), so bisection finds the one root.
    pure function richardson_fit(h, f) result(fit)
        real(wp), intent(in) :: h(3), f(3)
        type(richardson_fit_t) :: fit
        real(wp) :: hs(3), fs(3), d1, d2, ratio, s, t, lo, hi, mid
        integer :: i

        fit%limit = nan()
        fit%constant = nan()
        fit%order = nan()
        if (.not. all(ieee_is_finite(h)) .or. .not. all(ieee_is_finite(f))) then
            fit%code = FIT_NOT_FINITE
            return
        end if
        hs = h
        fs = f
        call coarsest_first(hs, fs)
        if (.not. (hs(3) > 0.0_wp .and. hs(2) > hs(3) .and. hs(1) > hs(2))) then
            fit%code = FIT_BAD_H
            return
        end if
        d1 = fs(1) - fs(2)
        d2 = fs(2) - fs(3)
        if (.not. (abs(d1) > 0.0_wp) .and. .not. (abs(d2) > 0.0_wp)) then
            fit%code = FIT_CONSTANT
            fit%limit = fs(3)
            fit%constant = 0.0_wp
            return
        end if
        if (.not. (d1*d2 > 0.0_wp)) then
            fit%code = FIT_NOT_MONOTONE
            return
        end if
        ratio = d1/d2
        s = log(hs(1)/hs(2))
        t = log(hs(2)/hs(3))
        if (.not. (log(ratio) > log_ratio_of_differences(0.0_wp, s, t))) then
            fit%code = FIT_NOT_CONVERGING
            return
        end if

        ! Bracket the root in ]0, hi], then bisect down to adjacent floating-point numbers.
        lo = 0.0_wp
        hi = 1.0_wp
        do while (log_ratio_of_differences(hi, s, t) < log(ratio))
            lo = hi
            hi = 2.0_wp*hi
            if (hi > MAX_ORDER) then
                fit%code = FIT_ORDER_TOO_HIGH
                return
            end if
        end do
        do i = 1, 200
            mid = 0.5_wp*(lo + hi)
            if (mid <= lo .or. mid >= hi) exit
            if (log_ratio_of_differences(mid, s, t) < log(ratio)) then
                lo = mid
            else
                hi = mid
            end if
        end do
        fit%code = FIT_OK
        fit%order = 0.5_wp*(lo + hi)
        ! f3 - limit = C h3^p = d2/((h2/h3)^p - 1): no power of h itself, so no overflow.
        fit%limit = fs(3) - d2/expm1(fit%order*t)
        fit%constant = d2/(expm1(fit%order*t)*hs(3)**fit%order)
    end function richardson_fit

    !> Extrapolate one family: the fit on its finest three meshes gives limit and order p.
    !> Its error is estimated from the change from the fit on the three meshes before: what
    !> the fits miss (higher-order terms, h^q with q > p) makes the limits themselves converge
    !> like h^q, so with rho = h(n-1)/h(n) the finer limit's error is about
    !> |limit - previous| / (rho^q - 1) <= |limit - previous| / (rho^p - 1). The division
    !> matters for close meshes: at rho = 4/3 and p = 1.5 it doubles the plain change. With
    !> three meshes only, or when that earlier fit fails, the estimate is the whole Richardson
    !> correction |finest - limit|, cautious as long as extrapolating improves on the finest
    !> value. Points with a non-finite value (failed runs, no positive eigenvalue) are ignored.
    pure function family_estimate(h, f) result(est)
        real(wp), intent(in) :: h(:), f(:)
        type(family_estimate_t) :: est
        type(richardson_fit_t) :: fit, previous
        real(wp), allocatable :: hs(:), fs(:)
        integer :: n

        est%limit = nan()
        est%constant = nan()
        est%order = nan()
        est%previous_limit = nan()
        est%previous_order = nan()
        est%error_estimate = nan()
        est%finest = nan()
        est%h_used = nan()
        hs = pack(h, ieee_is_finite(f) .and. ieee_is_finite(h))
        fs = pack(f, ieee_is_finite(f) .and. ieee_is_finite(h))
        n = size(hs)
        est%n_points = n
        if (n < 3) then
            est%code = FIT_TOO_FEW
            return
        end if
        call coarsest_first(hs, fs)
        est%h_used = hs(n - 2:n)
        est%finest = fs(n)
        fit = richardson_fit(hs(n - 2:n), fs(n - 2:n))
        est%code = fit%code
        if (fit%code /= FIT_OK .and. fit%code /= FIT_CONSTANT) return
        est%limit = fit%limit
        est%constant = fit%constant
        est%order = fit%order
        est%error_estimate = abs(est%finest - est%limit)
        if (n >= 4) then
            previous = richardson_fit(hs(n - 3:n - 1), fs(n - 3:n - 1))
            est%previous_code = previous%code
            est%previous_limit = previous%limit
            est%previous_order = previous%order
            if (previous%code == FIT_OK .or. previous%code == FIT_CONSTANT) then
                est%error_estimate = abs(est%limit - previous%limit)
                if (fit%code == FIT_OK) est%error_estimate = est%error_estimate &
                    /expm1(fit%order*log(hs(n - 1)/hs(n)))
                est%from_two_fits = .true.
            end if
        end if
    end function family_estimate

    !> The family whose limit is known best (smallest relative error estimate) among the
    !> estimates with a limit; 0 when there is none.
    pure integer function reference_index(estimates) result(best)
        type(family_estimate_t), intent(in) :: estimates(:)
        real(wp) :: relative, best_relative
        integer :: i

        best = 0
        best_relative = huge(1.0_wp)
        do i = 1, size(estimates)
            if (estimates(i)%code /= FIT_OK .and. estimates(i)%code /= FIT_CONSTANT) cycle
            if (.not. (ieee_is_finite(estimates(i)%error_estimate) .and. &
                       ieee_is_finite(estimates(i)%limit))) cycle
            if (.not. (abs(estimates(i)%limit) > 0.0_wp)) cycle
            relative = estimates(i)%error_estimate/abs(estimates(i)%limit)
            if (best == 0 .or. relative < best_relative) then
                best = i
                best_relative = relative
            end if
        end do
    end function reference_index

    !> Reorder the points (h(i), f(i)) by decreasing h: the coarsest mesh first.
    pure subroutine coarsest_first(h, f)
        real(wp), intent(inout) :: h(:), f(:)
        integer :: order(size(h))
        order = sort_index(-h)
        h = h(order)
        f = f(order)
    end subroutine coarsest_first

    !> A short reason for a fit code, fit for a CSV field (no commas).
    pure function fit_note(code) result(note)
        integer, intent(in) :: code
        character(len=:), allocatable :: note
        select case (code)
        case (FIT_OK)
            note = 'ok'
        case (FIT_TOO_FEW)
            note = 'fewer than 3 meshes with a value'
        case (FIT_BAD_H)
            note = 'repeated or non-positive mesh size'
        case (FIT_NOT_FINITE)
            note = 'non-finite value'
        case (FIT_NOT_MONOTONE)
            note = 'not monotone on these meshes'
        case (FIT_NOT_CONVERGING)
            note = 'differences do not shrink'
        case (FIT_ORDER_TOO_HIGH)
            note = 'observed order too high to trust'
        case (FIT_CONSTANT)
            note = 'constant on these meshes'
        case default
            note = 'unknown fit status'
        end select
    end function fit_note

    !> ln((h1^p - h2^p)/(h2^p - h3^p)) for s = ln(h1/h2) > 0, t = ln(h2/h3) > 0, written
    !> with ratios only: p s + ln(1 - e^(-p s)) - ln(1 - e^(-p t)), its limit ln(s/t) at p = 0.
    pure real(wp) function log_ratio_of_differences(p, s, t) result(value)
        real(wp), intent(in) :: p, s, t
        if (.not. (p > 0.0_wp)) then
            value = log(s/t)
        else
            value = p*s + log(-expm1(-p*s)) - log(-expm1(-p*t))
        end if
    end function log_ratio_of_differences

    !> e^x - 1 without cancellation for small |x| (Fortran 2008 has no expm1):
    !> e^x - 1 = 2 e^(x/2) sinh(x/2), and sinh is accurate near 0.
    elemental real(wp) function expm1(x)
        real(wp), intent(in) :: x
        if (abs(x) < 1.0_wp) then
            expm1 = 2.0_wp*exp(0.5_wp*x)*sinh(0.5_wp*x)
        else
            expm1 = exp(x) - 1.0_wp
        end if
    end function expm1

    pure real(wp) function nan()
        nan = ieee_value(1.0_wp, ieee_quiet_nan)
    end function nan
end module extrapolation
