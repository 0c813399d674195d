! SPDX-License-Identifier: MIT
!> Richardson extrapolation recovers limit, constant and order of f(h) = L + C h^p exactly
!> (to round-off) for any mesh ratios, agrees with the closed form for ratio 2, refuses
!> sequences that do not fit the model, and its error estimate bounds the true error of a
!> model with a higher-order term.
program test_extrapolation
    use kinds, only: wp
    use ieee_arithmetic, only: ieee_is_nan, ieee_value, ieee_quiet_nan
    use extrapolation, only: richardson_fit_t, richardson_fit, family_estimate_t, &
                             family_estimate, reference_index, fit_note, FIT_OK, FIT_BAD_H, &
                             FIT_NOT_FINITE, FIT_NOT_MONOTONE, FIT_NOT_CONVERGING, &
                             FIT_CONSTANT, FIT_TOO_FEW
    use testing, only: test_suite_t
    implicit none
    ! Data rounded to eps |f| ~ 1e-16 and differences d ~ 1e-3..1e-2: the ratio of differences
    ! carries ~1e-13 relative error, so p (through ln of the ratio, divided by ln of a mesh
    ! ratio >= ln 1.6) to ~2e-13 relative, C (through h^p and d) to ~1e-12. The limit
    ! L = f3 - d2 / ((h2/h3)^p - 1) loses only the rounding of f3 and d2: ~1e-15 relative.
    real(wp), parameter :: LIMIT_TOL = 1.0e-14_wp
    real(wp), parameter :: ORDER_TOL = 1.0e-11_wp
    real(wp), parameter :: CONSTANT_TOL = 1.0e-10_wp
    type(test_suite_t) :: t

    t%name = 'test_extrapolation'
    call check_exact_recovery()
    call check_closed_form_ratio_two()
    call check_refusals()
    call check_family()
    call check_reference()
    call t%report()

contains

    pure function model(h, limit, constant, order) result(f)
        real(wp), intent(in) :: h(:), limit, constant, order
        real(wp) :: f(size(h))
        f = limit + constant*h**order
    end function model

    subroutine check_exact_recovery()
        ! Ratios 2 (powers of two), uneven ratios 5/3 and 12/5 in scrambled order, a slow
        ! order below 1 and a fast one, converging from below and from above.
        call recover('ratio 2, p = 1.5, from below', [1.0_wp/8, 1.0_wp/16, 1.0_wp/32], &
                     0.75_wp, -0.3_wp, 1.5_wp)
        call recover('ratios 5/3 and 12/5 scrambled, p = 2.3, from above', &
                     [1.0_wp/20, 1.0_wp/12, 1.0_wp/48], 0.75_wp, 2.0_wp, 2.3_wp)
        call recover('ratios 3/2 and 4/3, p = 0.5', [1.0_wp/32, 1.0_wp/48, 1.0_wp/64], &
                     -1.25_wp, 0.1_wp, 0.5_wp)
        call recover('ratio 2, p = 4 (Q2 smooth)', [1.0_wp/4, 1.0_wp/8, 1.0_wp/16], &
                     3.0_wp, 50.0_wp, 4.0_wp)
    end subroutine check_exact_recovery

    subroutine recover(what, h, limit, constant, order)
        character(len=*), intent(in) :: what
        real(wp), intent(in) :: h(3), limit, constant, order
        type(richardson_fit_t) :: fit
        fit = richardson_fit(h, model(h, limit, constant, order))
        call t%check(what//': fit succeeds ('//fit_note(fit%code)//')', fit%code == FIT_OK)
        call t%check_close(what//': limit', fit%limit, limit, LIMIT_TOL)
        call t%check_close(what//': order', fit%order, order, ORDER_TOL)
        call t%check_close(what//': constant', fit%constant, constant, CONSTANT_TOL)
    end subroutine recover

    !> Equal ratios 2: p = log2(d1/d2) and L = f3 - d2/(2^p - 1), here on data that are no
    !> model output: f = 1, 0.5, 0.3 gives p = log2(2.5), L = 0.3 - 0.2/1.5 = 1/6.
    subroutine check_closed_form_ratio_two()
        type(richardson_fit_t) :: fit
        fit = richardson_fit([1.0_wp, 0.5_wp, 0.25_wp], [1.0_wp, 0.5_wp, 0.3_wp])
        call t%check('closed form: fit succeeds', fit%code == FIT_OK)
        call t%check_close('closed form: order log2(2.5)', fit%order, log(2.5_wp)/log(2.0_wp), &
                           ORDER_TOL)
        call t%check_close('closed form: limit 1/6', fit%limit, 1.0_wp/6.0_wp, LIMIT_TOL)
    end subroutine check_closed_form_ratio_two

    subroutine check_refusals()
        type(richardson_fit_t) :: fit
        real(wp), parameter :: h(3) = [0.5_wp, 0.25_wp, 0.125_wp]

        fit = richardson_fit(h, [1.0_wp, 1.2_wp, 1.1_wp])
        call t%check('up then down: not monotone, no limit', &
                     fit%code == FIT_NOT_MONOTONE .and. ieee_is_nan(fit%limit))
        fit = richardson_fit(h, [1.0_wp, 1.1_wp, 1.3_wp])
        call t%check('growing differences: not converging, no limit', &
                     fit%code == FIT_NOT_CONVERGING .and. ieee_is_nan(fit%limit))
        ! Uneven ratios: order 0 means d1/d2 = ln(h1/h2)/ln(h2/h3) = ln 2/ln 4 = 1/2; a
        ! ratio 0.4 below it would need p < 0.
        fit = richardson_fit([1.0_wp, 0.5_wp, 0.125_wp], [1.0_wp, 1.4_wp, 2.4_wp])
        call t%check('uneven ratios, d1/d2 below the p = 0 value: not converging', &
                     fit%code == FIT_NOT_CONVERGING)
        fit = richardson_fit([0.5_wp, 0.25_wp, 0.25_wp], [1.0_wp, 1.2_wp, 1.3_wp])
        call t%check('repeated h: refused', fit%code == FIT_BAD_H)
        fit = richardson_fit([0.5_wp, 0.25_wp, 0.0_wp], [1.0_wp, 1.2_wp, 1.3_wp])
        call t%check('h = 0: refused', fit%code == FIT_BAD_H)
        fit = richardson_fit(h, [1.0_wp, ieee_value(1.0_wp, ieee_quiet_nan), 1.3_wp])
        call t%check('NaN value: refused', fit%code == FIT_NOT_FINITE)
        fit = richardson_fit(h, [2.0_wp, 2.0_wp, 2.0_wp])
        call t%check('constant: limit is the value', fit%code == FIT_CONSTANT &
                     .and. abs(fit%limit - 2.0_wp) <= 0.0_wp)
    end subroutine check_refusals

    subroutine check_family()
        type(family_estimate_t) :: e
        real(wp), allocatable :: h(:), f(:)
        real(wp), parameter :: limit = 0.7528_wp
        integer :: i

        ! Five exact model values plus a failed run (NaN), coarse and fine mixed: the two
        ! triples give the same limit, so the estimate is round-off.
        allocate (h(0))   ! gfortran 12 -O3 falsely warns on a first assignment otherwise
        h = [1.0_wp/16, 1.0_wp/4, 1.0_wp/64, 1.0_wp/8, 1.0_wp/30, 1.0_wp/128]
        f = model(h, limit, 0.05_wp, 1.4_wp)
        f(5) = ieee_value(1.0_wp, ieee_quiet_nan)
        e = family_estimate(h, f)
        call t%check('family: NaN run ignored, 5 points', e%n_points == 5)
        call t%check('family: the finest three are 1/16, 1/64, 1/128', &
                     all(abs(e%h_used - [1.0_wp/16, 1.0_wp/64, 1.0_wp/128]) <= 0.0_wp))
        call t%check_close('family: exact limit', e%limit, limit, LIMIT_TOL)
        call t%check_close('family: exact order', e%order, 1.4_wp, ORDER_TOL)
        call t%check('family: error from two fits', e%from_two_fits)
        call t%check('family: error estimate at round-off', e%error_estimate <= 1.0e-14_wp)

        ! A second term: f = L + C h^p + D h^q, q > p, on ratios 2. The estimate must bound
        ! the true error of the finer limit.
        h = [(1.0_wp/2**i, i=2, 7)]
        f = model(h, limit, -0.4_wp, 1.3_wp) + 0.3_wp*h**2.1_wp
        e = family_estimate(h, f)
        call t%check('two terms: fit succeeds', e%code == FIT_OK)
        call t%check('two terms: error estimate bounds the true error', &
                     e%error_estimate >= abs(e%limit - limit))
        call t%check('two terms: extrapolating beats the finest mesh', &
                     abs(e%limit - limit) < abs(f(size(f)) - limit))

        ! Close meshes (ratio 4/3): the limits of successive triples differ by less than the
        ! error left in the finer one, so the plain change would claim too much; divided by
        ! rho^p - 1 the estimate still bounds the true error.
        h = [(0.75_wp**i/8, i=0, 7)]
        f = model(h, limit, 0.4_wp, 1.4_wp) + 0.5_wp*h**1.9_wp
        e = family_estimate(h, f)
        call t%check('ratio 4/3: the plain change of limits underestimates', &
                     abs(e%limit - e%previous_limit) < abs(e%limit - limit))
        call t%check('ratio 4/3: error estimate bounds the true error', &
                     e%error_estimate >= abs(e%limit - limit))

        ! Three meshes: the estimate falls back on the Richardson correction.
        e = family_estimate(h(4:6), f(4:6))
        call t%check('three meshes: not from two fits', .not. e%from_two_fits)
        call t%check_close('three meshes: error = |finest - limit|', e%error_estimate, &
                           abs(f(6) - e%limit), 1.0e-15_wp)

        e = family_estimate(h(1:2), f(1:2))
        call t%check('two meshes: too few, no limit', e%code == FIT_TOO_FEW .and. &
                     ieee_is_nan(e%limit))
        e = family_estimate([0.5_wp, 0.25_wp, 0.125_wp], [1.0_wp, 1.2_wp, 1.1_wp])
        call t%check('family not monotone: no limit', e%code == FIT_NOT_MONOTONE .and. &
                     ieee_is_nan(e%limit) .and. ieee_is_nan(e%error_estimate))
    end subroutine check_family

    subroutine check_reference()
        type(family_estimate_t) :: e(3)
        e(1)%code = FIT_OK
        e(1)%limit = 1.0_wp
        e(1)%error_estimate = 1.0e-4_wp
        e(2)%code = FIT_NOT_MONOTONE
        e(2)%limit = ieee_value(1.0_wp, ieee_quiet_nan)
        e(2)%error_estimate = ieee_value(1.0_wp, ieee_quiet_nan)
        e(3)%code = FIT_OK
        e(3)%limit = 2.0_wp
        e(3)%error_estimate = 1.5e-4_wp
        call t%check('reference: smallest relative error estimate (3: 7.5e-5 < 1e-4)', &
                     reference_index(e) == 3)
        call t%check('reference: none without a limit', reference_index(e(2:2)) == 0)
    end subroutine check_reference
end program test_extrapolation
