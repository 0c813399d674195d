! SPDX-License-Identifier: MIT
!> Warnings for results that lost accuracy, each with its reason, for summary.json
!> (`warnings`) and the stdout summary (`warning:` lines). The bounds and their
!> justification are in docs/accuracy.md, "Warnings".
module accuracy
    use kinds, only: wp
    use strings, only: to_string, short => short_real_text
    use real_format, only: real_to_text
    use spectrum, only: spectrum_t
    use unit_scaling, only: units_t
    use elasticity, only: lame_ratio
    implicit none
    private
    public :: accuracy_warnings, forward_error_estimate, lame_ratio, roundoff_warnings
    public :: WARNING_LEN, MU_VANISHED, FORWARD_ERROR_BOUND, BACKWARD_ERROR_BOUND, &
              LOCKING_RATIO_BOUND, LAMBDA_SENSITIVITY_BOUND

    !> the longest warning kept whole (a moving side's, with its place and wedge, runs to
    !> about 450 characters); every writer trims the blanks
    integer, parameter :: WARNING_LEN = 1000
    !> Why an adaptive loop ends where a positive mu of its earlier levels is gone: such a mu
    !> moves with the mesh (grows like 1/h at nu = 0), a grid-scale mode with no continuum
    !> value; the run exits with the status of a tolerance not met.
    character(len=*), parameter :: MU_VANISHED = 'the positive mu of the coarser levels is '// &
        'gone: a mode the mesh does not resolve, no converged value at this resolution'

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

contains

    !> The warning, if any, on the round-off bound `roundoff` of a critical value (< 0:
    !> unknown), `subject` (default: the lowest positive mu), against the discretisation
    !> part of its error bar (< 0: none): no correct digit (bound >= 1, the run exits with
    !> STATUS_NO_DIGIT), fewer than 6 correct digits (above FORWARD_ERROR_BOUND), or
    !> round-off the larger part of the bar.
    function roundoff_warnings(roundoff, discretisation, subject) result(warnings)
        real(wp), intent(in) :: roundoff, discretisation
        character(len=*), intent(in), optional :: subject
        character(len=WARNING_LEN), allocatable :: warnings(:)
        character(len=*), parameter :: WHY = ' (the bound grows with a nearly incompressible ' &
            //'material, stretched or sliver cells, and lambda near a critical value)'
        character(len=:), allocatable :: what
        allocate (warnings(0))
        if (.not. roundoff >= 0.0_wp) return
        what = 'the lowest positive mu'
        if (present(subject)) what = subject
        if (roundoff >= 1.0_wp) then
            warnings = [character(len=WARNING_LEN) :: 'round-off leaves no correct digit of ' &
                //what//': its bound is '//short(roundoff)//' relative'//WHY]
        else if (roundoff > FORWARD_ERROR_BOUND) then
            warnings = [character(len=WARNING_LEN) :: 'round-off bound of '//what//' is ' &
                //short(roundoff)//' relative: '//digits_text(floor(-log10(roundoff)))//WHY]
        else if (discretisation >= 0.0_wp .and. roundoff > discretisation) then
            warnings = [character(len=WARNING_LEN) :: 'round-off dominates the error bar of ' &
                //what//': '//short(roundoff)//' relative against '// &
                short(discretisation)//' from the discretisation, which refining the mesh ' &
                //'does not reduce'//WHY]
        end if

    contains

        function digits_text(n) result(text)
            integer, intent(in) :: n
            character(len=:), allocatable :: text
            text = 'only its sign is certain'
            if (n > 0) text = 'about '//to_string(n)//' correct digits'
        end function digits_text
    end function roundoff_warnings

    !> condition x max(backward error, eps): first-order bound of the relative error of mu.
    elemental real(wp) function forward_error_estimate(condition, residual)
        real(wp), intent(in) :: condition, residual
        forward_error_estimate = condition*max(residual, epsilon(1.0_wp))
    end function forward_error_estimate

    !> Every reason to distrust the result of an eigen run, one sentence each; none for a
    !> well-posed, well-resolved problem such as the reference scene.
    !> `roundoff`: the round-off bound of the lowest positive mu (module roundoff; < 0:
    !> unknown), which replaces the condition x backward error of the reduced problem where
    !> it is known.
    function accuracy_warnings(spec, units, element, poisson, roundoff) result(warnings)
        type(spectrum_t), intent(in) :: spec
        type(units_t), intent(in) :: units   !! of spec%mu: the warnings quote mu in the input's
        character(len=*), intent(in) :: element   !! 'p1', 'q1', 'p2', 'q2'
        real(wp), intent(in) :: poisson, roundoff
        character(len=WARNING_LEN), allocatable :: warnings(:)
        integer :: lowest, n_bad, i, worst

        allocate (warnings(0))
        lowest = spec%lowest_positive()
        if (lowest > 0 .and. .not. roundoff >= 0.0_wp) then
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
            ' (largest '//short(spec%residual(worst))//' at |mu| = '// &
            short(units%mu_to_input(abs(spec%mu(worst)))) &
            //'): the largest |mu| (short-wave contact modes) suffer first from a badly ' &
            //'conditioned K, e.g. with elongated cells')

        if ((element == 'p1' .or. element == 'q1') .and. &
            lame_ratio(poisson) >= LOCKING_RATIO_BOUND) call add('nearly incompressible ' &
            //'material (poisson = '//real_to_text(poisson)//', L/G = '// &
            short(lame_ratio(poisson))//'): '//trim(element)//' elements lock, so mu is ' &
            //'the accurate eigenvalue of a discrete problem that converges slowly to the ' &
            //'continuous one; use p2 or q2 or refine much further')

        if (roundoff > FORWARD_ERROR_BOUND) warnings = [character(len=WARNING_LEN) :: &
            warnings, roundoff_warnings(roundoff, -1.0_wp)]

        if (allocated(spec%lambda_sensitivity)) then
            do i = 1, spec%n()
                if (spec%lambda_sensitivity(i) <= LAMBDA_SENSITIVITY_BOUND) cycle
                call add('lambda is near a critical value: mu = '// &
                    short(units%mu_to_input(real(spec%mu(i), wp))) &
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
