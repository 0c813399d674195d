! SPDX-License-Identifier: MIT
!> Warnings for results that lost accuracy, each with its reason, for summary.json
!> (`warnings`) and the stdout summary (`warning:` lines). The bounds and their
!> justification are in docs/accuracy.md, "Warnings".
module accuracy
    use kinds, only: wp
    use strings, only: to_string, short => short_real_text
    use real_format, only: real_to_text
    use spectrum, only: spectrum_t
    use elasticity, only: lame_ratio
    implicit none
    private
    public :: accuracy_warnings, forward_error_estimate, lame_ratio
    public :: WARNING_LEN, FORWARD_ERROR_BOUND, BACKWARD_ERROR_BOUND, LOCKING_RATIO_BOUND, &
              LAMBDA_SENSITIVITY_BOUND

    integer, parameter :: WARNING_LEN = 400

    !> Relative error of the headline mu above which it is reported: six significant digits,
    !> more than any convergence study of c_n needs, far fewer than the 15 of a well
    !> conditioned solve.
    real(wp), parameter :: FORWARD_ERROR_BOUND = 1.0e-6_wp
    !> Backward error above which an eigenpair is reported: a backward stable chain
    !> (Cholesky, dgeevx, one more solve) gives about n eps, below 1e-11 for the n <= 1e5
    !> the dense solver meets; 1e-10 is well above that and well below where digits of mu go.
    real(wp), parameter :: BACKWARD_ERROR_BOUND = 1.0e-10_wp
    !> L/G = 2 nu/(1 - 2 nu) from which linear elements lock: 40 is nu = 0.488; at nu = 0.49
    !> (L/G = 49) the lowest mu of Q1 on 8 x 8 cells is 20% off the converged value, at
    !> nu = 0.45 (L/G = 9) 5%, as at nu = 0.3.
    real(wp), parameter :: LOCKING_RATIO_BOUND = 40.0_wp
    !> |lambda dmu/dlambda / mu| above which lambda counts as near a threshold: about
    !> |lambda / (lambda - lambda_c)|, so 1e4 is lambda within 1e-4 relative of lambda_c, where
    !> a change of lambda in its 6th digit moves mu by 1% or more.
    real(wp), parameter :: LAMBDA_SENSITIVITY_BOUND = 1.0e4_wp
    !> Relative round-off error of mu per eps x L/G: K's condition grows like L/G as nu ->
    !> 0.5, in any element. Measured (P2, 8 x 8 and 16 x 16, errors against the values at
    !> nu = 0.4999999): 35 to 67 eps L/G on 8 x 8, 108 to 180 on 16 x 16 (it grows with
    !> refinement); 100 makes the warning fire from L/G = 4.5e7 (nu = 0.49999999, error
    !> 3.9e-7 measured), where the error estimate, which sees only the discretisation, does not.
    real(wp), parameter :: ROUNDOFF_PER_LAME_RATIO = 100.0_wp

contains

    !> condition x max(backward error, eps): first-order bound of the relative error of mu.
    elemental real(wp) function forward_error_estimate(condition, residual)
        real(wp), intent(in) :: condition, residual
        forward_error_estimate = condition*max(residual, epsilon(1.0_wp))
    end function forward_error_estimate

    !> Every reason to distrust the result of an eigen run, one sentence each; none for a
    !> well-posed, well-resolved problem such as the reference scene.
    function accuracy_warnings(spec, element, poisson) result(warnings)
        type(spectrum_t), intent(in) :: spec
        character(len=*), intent(in) :: element   !! 'p1', 'q1', 'p2', 'q2'
        real(wp), intent(in) :: poisson
        character(len=WARNING_LEN), allocatable :: warnings(:)
        integer :: lowest, n_bad, i, worst

        allocate (warnings(0))
        lowest = spec%lowest_positive()
        if (lowest > 0) then
            if (spec%condition(lowest) >= 0.0_wp) then
                if (forward_error_estimate(spec%condition(lowest), spec%residual(lowest)) > &
                    FORWARD_ERROR_BOUND) call add('lowest positive mu may be inaccurate: ' &
                    //'condition number '//short(spec%condition(lowest))//' x backward error ' &
                    //short(max(spec%residual(lowest), epsilon(1.0_wp)))// &
                    ' gives a relative error up to '//short(forward_error_estimate( &
                    spec%condition(lowest), spec%residual(lowest)))//' (bound ' &
                    //short(FORWARD_ERROR_BOUND)//')')
            end if
        end if

        n_bad = 0
        worst = 0
        do i = 1, spec%n()
            if (spec%residual(i) > BACKWARD_ERROR_BOUND) then
                n_bad = n_bad + 1
                if (worst == 0) worst = i
                if (spec%residual(i) > spec%residual(worst)) worst = i
            end if
        end do
        if (n_bad > 0) call add(to_string(n_bad)//' of '//to_string(spec%n())// &
            ' eigenpairs have a backward error above '//short(BACKWARD_ERROR_BOUND)// &
            ' (largest '//short(spec%residual(worst))//' at |mu| = '//short(abs(spec%mu(worst))) &
            //'): the largest |mu| (short-wave contact modes) suffer first from a badly ' &
            //'conditioned K, e.g. with elongated cells')

        if ((element == 'p1' .or. element == 'q1') .and. &
            lame_ratio(poisson) >= LOCKING_RATIO_BOUND) call add('nearly incompressible ' &
            //'material (poisson = '//real_to_text(poisson)//', L/G = '// &
            short(lame_ratio(poisson))//'): '//trim(element)//' elements lock, so mu is ' &
            //'the accurate eigenvalue of a discrete problem that converges slowly to the ' &
            //'continuous one; use p2 or q2 or refine much further')

        associate (roundoff => ROUNDOFF_PER_LAME_RATIO*epsilon(1.0_wp)*lame_ratio(poisson))
            if (roundoff > FORWARD_ERROR_BOUND) call add('nearly incompressible material ' &
                //'(poisson = '//real_to_text(poisson)//', L/G = '// &
                short(lame_ratio(poisson))//'): the condition of K grows like L/G, so mu has a ' &
                //'round-off error of about '//short(roundoff)//' relative ('// &
                to_string(nint(log10(roundoff/epsilon(1.0_wp))))//' of 16 digits lost; more on ' &
                //'finer meshes), which the error estimate does not see; keep L/G below ' &
                //short(FORWARD_ERROR_BOUND/(ROUNDOFF_PER_LAME_RATIO*epsilon(1.0_wp))))
        end associate

        if (allocated(spec%lambda_sensitivity)) then
            do i = 1, spec%n()
                if (spec%lambda_sensitivity(i) <= LAMBDA_SENSITIVITY_BOUND) cycle
                call add('lambda is near a critical value: mu = '//short(real(spec%mu(i), wp)) &
                    //' changes '//short(spec%lambda_sensitivity(i))//' times faster than ' &
                    //'lambda (relative), i.e. lambda is within about '// &
                    short(1.0_wp/spec%lambda_sensitivity(i))//' relative of a threshold, ' &
                    //'where mu passes through infinity')
                exit
            end do
        end if

    contains

        subroutine add(text)
            character(len=*), intent(in) :: text
            warnings = [character(len=WARNING_LEN) :: warnings, text]
        end subroutine add
    end function accuracy_warnings
end module accuracy
