! SPDX-License-Identifier: MIT
!> Extremes suite (CTest label 'extremes'): the eigen analysis, run through the same
!> build_problem + solve_eigen path as the program, at extreme material constants, sizes,
!> lambdas, mesh sizes and cell shapes. It asserts scaling laws to tolerances derived from
!> the reported condition numbers, and that accuracy warnings appear exactly where expected.
program test_extremes_scaling
    use kinds, only: wp
    use fixtures, only: problem_of, eigen_of
    use reported_units, only: to_input_units
    use status, only: status_t
    use testing, only: test_suite_t
    use fixtures, only: has_warning
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use eigen_solve, only: eigen_result_t, solve_eigen
    use spectrum, only: KIND_COMPLEX
    use accuracy, only: BACKWARD_ERROR_BOUND, LOCKING_RATIO_BOUND, lame_ratio, &
                        forward_error_estimate, FORWARD_ERROR_BOUND
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_extremes_scaling'
    call reference_scene_has_no_warning(t)
    call young_modulus_scaling(t)
    call domain_size_scaling(t)
    call large_lambda_limit(t)
    call nearly_incompressible(t)
    call mesh_sizes(t)
    call elongated_cells(t)
    call t%report()

contains

    !> The reference scene (model.md section 10) on a small mesh: accurate and warning-free.
    subroutine reference_scene_has_no_warning(t)
        type(test_suite_t), intent(inout) :: t
        type(eigen_result_t) :: res
        call run(scene(), res)
        call t%check('reference scene: a positive mu', res%spec%lowest_positive() == 1)
        call t%check('reference scene: no warning', size(res%warnings) == 0)
    end subroutine reference_scene_has_no_warning

    !> K is proportional to E and B does not depend on it: mu(E) = E mu(1). K(E) differs
    !> from E K(1) by a few ulps per entry, which moves mu by about condition x eps; 100 x
    !> condition x eps covers that and dgeevx's own backward error constant.
    subroutine young_modulus_scaling(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: YOUNGS(6) = [1.0e-6_wp, 1.0e-3_wp, 1.0e3_wp, 1.0e6_wp, &
                                            1.0e9_wp, 1.0_wp]
        type(eigen_result_t) :: base, res
        type(config_t) :: c
        character(len=40) :: what
        integer :: i
        call run(scene(), base)
        do i = 1, size(YOUNGS)
            c = scene()
            c%material%young = YOUNGS(i)
            call run(c, res)
            write (what, '(a, es8.1)') 'E =', YOUNGS(i)
            call check_scaled(t, trim(what), base, res, YOUNGS(i))
        end do
    end subroutine young_modulus_scaling

    !> In 2D, K is invariant under x -> s x while M scales with s: mu(s) = mu(1) / s.
    subroutine domain_size_scaling(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: SIZES(5) = [1.0e-3_wp, 0.1_wp, 10.0_wp, 1.0e3_wp, 1.0_wp]
        type(eigen_result_t) :: base, res
        type(config_t) :: c
        character(len=40) :: what
        integer :: i
        c = scene()
        c%mesh%element = 'q1'
        call run(c, base)
        do i = 1, size(SIZES)
            c%mesh%width = SIZES(i)
            c%mesh%height = SIZES(i)
            call run(c, res)
            write (what, '(a, es8.1)') 'size =', SIZES(i)
            call check_scaled(t, trim(what), base, res, 1.0_wp/SIZES(i))
        end do
    end subroutine domain_size_scaling

    !> For |lambda| -> infinity, theta = 1/mu = lambda theta_t + theta_0 + O(1/lambda), so
    !> lambda mu tends to a limit with an error ~ 1/lambda: the change of lambda mu from
    !> 1e6 to 1e8 is 100 times smaller than from 1e4 to 1e6 (factor 2 for the higher terms,
    !> plus the round-off of the three mu, each condition x eps).
    subroutine large_lambda_limit(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: SIGNS(2) = [1.0_wp, -1.0_wp]
        type(eigen_result_t) :: res(3)
        type(config_t) :: c
        real(wp) :: limit(3), noise
        integer :: i, s
        do s = 1, 2
            do i = 1, 3
                c = scene()
                c%analysis%lambda = SIGNS(s)*10.0_wp**(2*i + 2)
                call run(c, res(i))
                call t%check('|lambda| = 1e'//achar(iachar('0') + 2*i + 2)// &
                             ': a positive mu, no warning', res(i)%spec%lowest_positive() == 1 &
                             .and. size(res(i)%warnings) == 0)
                if (res(i)%spec%lowest_positive() /= 1) return
                limit(i) = abs(c%analysis%lambda)*real(res(i)%spec%mu(1), wp)
            end do
            noise = 3.0_wp*maxval([(res(i)%spec%condition(1), i=1, 3)])*epsilon(1.0_wp)
            call t%check('lambda mu converges like 1/lambda, sign '// &
                         merge('+', '-', SIGNS(s) > 0.0_wp), abs(limit(3) - limit(2)) <= &
                         2.0e-2_wp*abs(limit(2) - limit(1)) + noise*abs(limit(3)))
        end do
    end subroutine large_lambda_limit

    !> nu up to 0.499999: the discrete problem stays well solved (backward error, condition),
    !> and the locking warning appears for p1/q1 exactly when L/G passes its bound.
    subroutine nearly_incompressible(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: POISSONS(4) = [0.0_wp, 0.49_wp, 0.4999_wp, 0.499999_wp]
        character(len=2), parameter :: ELEMENTS(4) = ['p1', 'q1', 'p2', 'q2']
        type(eigen_result_t) :: res
        type(config_t) :: c
        character(len=60) :: what
        logical :: locks
        integer :: i, e
        do i = 1, size(POISSONS)
            do e = 1, size(ELEMENTS)
                c = scene()
                c%material%poisson = POISSONS(i)
                c%mesh%element = ELEMENTS(e)
                call run(c, res)
                write (what, '(a, f9.6, a)') 'nu =', POISSONS(i), ', '//ELEMENTS(e)
                call t%check(trim(what)//': backward errors below bound', &
                             res%spec%max_residual() <= BACKWARD_ERROR_BOUND)
                if (res%spec%lowest_positive() == 1) call t%check(trim(what)// &
                    ': headline error estimate below bound', forward_error_estimate( &
                    res%spec%condition(1), res%spec%residual(1)) <= FORWARD_ERROR_BOUND)
                locks = (ELEMENTS(e) == 'p1' .or. ELEMENTS(e) == 'q1') .and. &
                        lame_ratio(POISSONS(i)) >= LOCKING_RATIO_BOUND
                call t%check(trim(what)//': locking warning iff linear element and L/G large', &
                             has_warning(res, 'incompressible') .eqv. locks)
                call t%check(trim(what)//': no other warning', &
                             size(res%warnings) == merge(1, 0, locks))
            end do
        end do
    end subroutine nearly_incompressible

    !> From one cell to the largest mesh a CI run affords (p1 and q2 at 64 x 64 cells, 33k
    !> dofs): accurate solves and no warning.
    subroutine mesh_sizes(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: CELLS(4) = [1, 2, 16, 64]
        character(len=2), parameter :: ELEMENTS(4) = ['p1', 'q1', 'p2', 'q2']
        type(eigen_result_t) :: res
        type(config_t) :: c
        character(len=40) :: what
        integer :: i, e
        do i = 1, size(CELLS)
            do e = 1, size(ELEMENTS)
                if (CELLS(i) == 64 .and. (ELEMENTS(e) == 'q1' .or. ELEMENTS(e) == 'p2')) cycle
                c = scene()
                c%mesh%nx = CELLS(i)
                c%mesh%ny = CELLS(i)
                c%mesh%element = ELEMENTS(e)
                call run(c, res)
                write (what, '(i0, a, i0, a)') CELLS(i), ' x ', CELLS(i), ' '//ELEMENTS(e)
                call t%check(trim(what)//': n_contact eigenvalues', res%spec%n() == &
                             count_nonzero(c))
                call t%check(trim(what)//': backward errors below bound, no warning', &
                             res%spec%max_residual() <= BACKWARD_ERROR_BOUND .and. &
                             size(res%warnings) == 0)
            end do
        end do
    end subroutine mesh_sizes

    !> Cells of aspect ratio up to 1000, both ways. The headline mu stays accurate (its
    !> error estimate is checked); the short-wave modes lose digits as K's condition grows,
    !> and the backward-error warning must appear exactly when a backward error passes its
    !> bound.
    subroutine elongated_cells(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: NX(5) = [1, 10, 100, 1000, 1000], NY(5) = [1000, 100, 10, 1, 1]
        character(len=2), parameter :: ELEMENTS(5) = ['p1', 'p1', 'q1', 'p1', 'q2']
        type(eigen_result_t) :: res
        type(config_t) :: c
        character(len=60) :: what
        integer :: i
        do i = 1, size(NX)
            c = scene()
            c%mesh%nx = NX(i)
            c%mesh%ny = NY(i)
            c%mesh%element = ELEMENTS(i)
            call run(c, res)
            write (what, '(a, i0, a, i0, a)') 'cells ', NX(i), ' x ', NY(i), ' '//ELEMENTS(i)
            if (res%spec%lowest_positive() == 1) call t%check(trim(what)// &
                ': headline error estimate below bound', forward_error_estimate( &
                res%spec%condition(1), res%spec%residual(1)) <= FORWARD_ERROR_BOUND)
            call t%check(trim(what)//': backward-error warning iff a residual above bound', &
                has_warning(res, 'backward error') .eqv. &
                res%spec%max_residual() > BACKWARD_ERROR_BOUND)
        end do
    end subroutine elongated_cells

    !> Every eigenvalue real-or-complex scaled by `factor`: the lowest positive to 100 x its
    !> condition x eps, the whole spectrum as a set, each to 100 x its own condition x eps.
    subroutine check_scaled(t, what, base, res, factor)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: what
        type(eigen_result_t), intent(in) :: base, res
        real(wp), intent(in) :: factor
        real(wp) :: worst
        integer :: i
        call t%check(what//': same count and kinds', base%spec%n() == res%spec%n() .and. &
                     all(base%spec%kind == res%spec%kind))
        if (base%spec%n() /= res%spec%n()) return
        worst = 0.0_wp
        do i = 1, base%spec%n()
            if (base%spec%kind(i) == KIND_COMPLEX) cycle   ! pairs may swap order
            worst = max(worst, abs(res%spec%mu(i) - factor*base%spec%mu(i))/ &
                        abs(factor*base%spec%mu(i))/(base%spec%condition(i)*epsilon(1.0_wp)))
        end do
        call t%check(what//': every real mu scales, within 100 condition eps', worst <= 100.0_wp)
        call t%check(what//': no warning', size(res%warnings) == 0)
    end subroutine check_scaled
    !> p = free contact nodes: bottom side nodes minus the two corners when the sides are
    !> fixed; here left and right are free, so every bottom node counts.
    integer function count_nonzero(c)
        type(config_t), intent(in) :: c
        count_nonzero = c%mesh%nx + 1
        if (c%mesh%element == 'p2' .or. c%mesh%element == 'q2') count_nonzero = 2*c%mesh%nx + 1
    end function count_nonzero

    !> The reference scene of model.md section 10 on 8 x 8 cells, no output.
    type(config_t) function scene() result(c)
        c%input_file = 'test_extremes_scaling'
        c%mesh%nx = 8
        c%mesh%ny = 8
        c%eigen%solver = 'dense'
    end function scene

    subroutine run(c, res)
        type(config_t), intent(in) :: c
        type(eigen_result_t), intent(out) :: res
        type(problem_t) :: prob
        type(timings_t) :: timings
        type(status_t) :: stat
        call problem_of(c, prob, stat)
        if (stat%ok()) call eigen_of(c, prob, c%analysis%lambda, res, timings, stat)
        ! the spectrum of the input problem, as the report gives it (reported_units)
        if (stat%ok()) call to_input_units(prob%units, res%spec%mu)
        if (.not. stat%ok()) then
            call t%check('run: '//stat%message, .false.)
            error stop 1
        end if
    end subroutine run
end program test_extremes_scaling
