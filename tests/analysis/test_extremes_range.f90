! SPDX-License-Identifier: MIT
!> Extremes suite (CTest label 'extremes'), the far ends of binary64: E and the domain size
!> from 1e-307 to 1e307, |lambda| up to 1.7e308, ARPACK targets from 0 to 1e300, and the
!> inputs that make K numerically singular. Each valid input must give the right answer with
!> honest (finite, relative, round-off sized) backward errors, or fail with STATUS_BAD_INPUT
!> and one line naming the input variable: never a wrong value with success. Runs in-process,
!> so the Debug build's floating-point traps watch every case.
program test_extremes_range
    use kinds, only: wp
    use fixtures, only: problem_of, eigen_of
    use reported_units, only: to_input_units
    use status, only: status_t, STATUS_BAD_INPUT
    use testing, only: test_suite_t
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use eigen_solve, only: eigen_result_t, solve_eigen
    use spectrum, only: KIND_COMPLEX
    use accuracy, only: BACKWARD_ERROR_BOUND
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness, contact_flexibility
    use lapack_interfaces, only: dgeev
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_extremes_range'
    call young_modulus_over_the_range(t)
    call domain_size_over_the_range(t)
    call young_and_size_cancel(t)
    call huge_lambda(t)
    call limit_pencil_directly(t)
    call arpack_targets(t)
    call singular_looking_inputs(t)
    call t%report()

contains

    !> mu(E) = E mu(1): bit for bit at powers of two (the problem is solved in units of E, a
    !> change of unit by a power of two is exact), to 100 condition eps at decimal E; refused
    !> naming young where the spectrum leaves the normal range (largest |mu| ~ 838 E).
    subroutine young_modulus_over_the_range(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: DECIMAL(5) = [1.0e-307_wp, 1.0e-200_wp, 1.0e-6_wp, &
                                             1.0e200_wp, 1.0e305_wp]
        real(wp), parameter :: REFUSED(4) = [1.0e-310_wp, 1.0e306_wp, 2.0e307_wp, 1.0e308_wp]
        integer, parameter :: POWERS(4) = [-1000, -500, 500, 1000]
        type(eigen_result_t) :: base, res
        type(config_t) :: c
        type(status_t) :: stat
        character(len=40) :: what
        integer :: i
        call run(scene(), base, stat)
        do i = 1, size(POWERS)
            c = scene()
            c%material%young = scale(1.0_wp, POWERS(i))
            call run(c, res, stat)
            write (what, '(a, i0)') 'E = 2^', POWERS(i)
            call check_exact(t, trim(what), base, res, POWERS(i), stat)
        end do
        do i = 1, size(DECIMAL)
            c = scene()
            c%material%young = DECIMAL(i)
            call run(c, res, stat)
            write (what, '(a, es9.1e3)') 'E =', DECIMAL(i)
            call check_scaled(t, trim(what), base, res, DECIMAL(i), stat)
        end do
        do i = 1, size(REFUSED)
            c = scene()
            c%material%young = REFUSED(i)
            call run(c, res, stat)
            write (what, '(a, es9.1e3)') 'E =', REFUSED(i)
            call check_refused(t, trim(what), stat, '&material: young = ')
        end do
    end subroutine young_modulus_over_the_range

    !> In 2D K does not change with the size s while M grows like s: mu(s) = mu(1) / s.
    subroutine domain_size_over_the_range(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: DECIMAL(5) = [1.0e-300_wp, 1.0e-160_wp, 1.0e-12_wp, &
                                             1.0e160_wp, 1.0e300_wp]
        integer, parameter :: POWERS(2) = [-900, 1000]
        type(eigen_result_t) :: base, res
        type(config_t) :: c
        type(status_t) :: stat
        character(len=40) :: what
        integer :: i
        call run(scene(), base, stat)
        do i = 1, size(POWERS)
            c = scene()
            c%mesh%width = scale(1.0_wp, POWERS(i))
            c%mesh%height = c%mesh%width
            call run(c, res, stat)
            write (what, '(a, i0)') 'size = 2^', POWERS(i)
            call check_exact(t, trim(what), base, res, -POWERS(i), stat)
        end do
        do i = 1, size(DECIMAL)
            c = scene()
            c%mesh%width = DECIMAL(i)
            c%mesh%height = DECIMAL(i)
            call run(c, res, stat)
            write (what, '(a, es9.1e3)') 'size =', DECIMAL(i)
            call check_scaled(t, trim(what), base, res, 1.0_wp/DECIMAL(i), stat)
        end do
        c = scene()
        c%mesh%width = 1.0e-307_wp
        c%mesh%height = 1.0e-307_wp
        call run(c, res, stat)
        call check_refused(t, 'size = 1e-307', stat, '&mesh: width = ')
    end subroutine domain_size_over_the_range

    !> Neither E nor the size alone decides: E = size = 1e-300 is the reference spectrum.
    subroutine young_and_size_cancel(t)
        type(test_suite_t), intent(inout) :: t
        type(eigen_result_t) :: base, res
        type(config_t) :: c
        type(status_t) :: stat
        call run(scene(), base, stat)
        c = scene()
        c%material%young = 1.0e-300_wp
        c%mesh%width = 1.0e-300_wp
        c%mesh%height = 1.0e-300_wp
        call run(c, res, stat)
        call check_scaled(t, 'E = size = 1e-300', base, res, 1.0_wp, stat)
    end subroutine young_and_size_cancel

    !> lambda mu tends to a limit as |lambda| grows (error ~ 1/lambda): from 1e155 on it is
    !> that limit to round-off, with finite, round-off sized backward errors (they were
    !> Infinity from 1e155), by both solvers; lambda = 1.7e308 puts mu below the normal range.
    subroutine huge_lambda(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: LAMBDAS(4) = [1.0e155_wp, 1.0e160_wp, 1.0e300_wp, 1.0e307_wp]
        character(len=6), parameter :: SOLVERS(2) = ['dense ', 'arpack']
        type(eigen_result_t) :: res
        type(config_t) :: c
        type(status_t) :: stat
        character(len=60) :: what
        real(wp) :: limit(2, 2)
        integer :: i, s, sgn
        do s = 1, size(SOLVERS)
            do sgn = 1, 2
                do i = 1, size(LAMBDAS)
                    c = scene()
                    c%eigen%solver = SOLVERS(s)
                    c%mesh%nx = 40
                    c%analysis%lambda = merge(1.0_wp, -1.0_wp, sgn == 1)*LAMBDAS(i)
                    call run(c, res, stat)
                    write (what, '(a, es10.1e3)') trim(SOLVERS(s))//', lambda =', &
                        c%analysis%lambda
                    call t%check(trim(what)//': solved', stat%ok())
                    if (.not. stat%ok()) cycle
                    call t%check(trim(what)//': a positive mu, honest residuals, no warning', &
                                 res%spec%lowest_positive() == 1 .and. &
                                 res%spec%max_residual() <= BACKWARD_ERROR_BOUND .and. &
                                 size(res%warnings) == 0)
                    if (res%spec%lowest_positive() /= 1) cycle
                    if (i == 1) limit(s, sgn) = LAMBDAS(i)*real(res%spec%mu(1), wp)
                    call t%check_close(trim(what)//': lambda mu at its limit', &
                                       LAMBDAS(i)*real(res%spec%mu(1), wp), limit(s, sgn), &
                                       rel_tol=1.0e-12_wp)
                end do
            end do
        end do
        c = scene()
        c%analysis%lambda = 1.7e308_wp
        call run(c, res, stat)
        call check_refused(t, 'lambda = 1.7e308', stat, '&analysis: lambda = ')
    end subroutine huge_lambda

    !> The limit lambda -> +-infinity is its own eigenproblem, K phi = nu B_inf phi with
    !> B_inf = T' M N (B / lambda -> B_inf; docs/model.md, section 5), and c_t = |lambda| mu
    !> tends to |nu|: the nu > 0 of least modulus for +infinity, the nu < 0 for -infinity.
    !> Computed here independently, by dgeev on its reduced matrix Kt_nt M (eigenvalues
    !> 1 / nu), against the run at lambda = +-1e300 (where the -N' term of B is 1e-300 of
    !> the other): equal to 1e-12.
    subroutine limit_pencil_directly(t)
        type(test_suite_t), intent(inout) :: t
        type(eigen_result_t) :: res
        type(config_t) :: c
        type(problem_t) :: prob
        type(cholesky_t) :: chol
        type(timings_t) :: timings
        type(status_t) :: stat
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), a(:, :), wr(:), wi(:), work(:)
        real(wp) :: vl(1, 1), vr(1, 1), nu(2), query(1)
        integer :: p, info, sgn
        c = scene()
        call problem_of(c, prob, stat)
        if (stat%ok()) call factor_stiffness(prob%k, prob%mesh, prob%dofs, prob%contact, chol, &
                                             timings, stat)
        if (stat%ok()) call contact_flexibility(chol, prob%contact, kt_nn, kt_nt, stat)
        call chol%free()
        call t%check('limit pencil: reduced blocks', stat%ok())
        if (.not. stat%ok()) return
        p = prob%contact%p()
        a = matmul(kt_nt, prob%contact%mass_dense())
        allocate (wr(p), wi(p))
        call dgeev('N', 'N', p, a, p, wr, wi, vl, 1, vr, 1, query, -1, info)
        allocate (work(int(query(1))))
        call dgeev('N', 'N', p, a, p, wr, wi, vl, 1, vr, 1, work, size(work), info)
        call t%check('limit pencil: dgeev', info == 0)
        ! nu = 1 / theta over the real theta: the smallest positive nu is 1 / the largest theta
        nu(1) = 1.0_wp/maxval(wr, mask=.not. abs(wi) > 0.0_wp .and. wr > 0.0_wp)
        nu(2) = 1.0_wp/minval(wr, mask=.not. abs(wi) > 0.0_wp .and. wr < 0.0_wp)
        do sgn = 1, 2
            c = scene()
            c%analysis%lambda = merge(1.0e300_wp, -1.0e300_wp, sgn == 1)
            call run(c, res, stat)
            call t%check('limit pencil: lambda = +-1e300 solved', stat%ok() .and. &
                         res%spec%lowest_positive() == 1)
            if (res%spec%lowest_positive() /= 1) cycle
            ! mu is in the units of E (1 here): lambda mu is nu itself
            call t%check_close('limit pencil: lambda mu at '// &
                               trim(merge('+1e300', '-1e300', sgn == 1))//' = nu of K phi = '// &
                               'nu B_inf phi', 1.0e300_wp*real(res%spec%mu(1), wp), &
                               abs(nu(sgn)), rel_tol=1.0e-12_wp)
        end do
    end subroutine limit_pencil_directly

    !> ARPACK with a target sigma: the lowest positive mu agrees with the dense solver's
    !> (to the certificate's 1e-8) and is certified, or the run is refused naming &eigen
    !> target; the refusal starts at |sigma| ||A|| = 1e6 (about 6.5e4 on this mesh), where
    !> mu = sigma + 1/nu cancels. Before, 1e10 to 1e300 returned wrong values with success.
    subroutine arpack_targets(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: ACCEPTED(7) = [0.0_wp, 1.0_wp, 0.76_wp, 1.0e3_wp, 1.0e4_wp, &
                                              -1.0e4_wp, -1.0_wp]
        real(wp), parameter :: REFUSED(8) = [1.0e5_wp, 1.0e10_wp, 1.0e15_wp, 1.0e20_wp, &
                                             1.0e50_wp, 1.0e300_wp, -1.0e15_wp, -1.0e300_wp]
        type(eigen_result_t) :: dense, res
        type(config_t) :: c
        type(status_t) :: stat
        character(len=40) :: what
        integer :: i
        c = scene()
        c%mesh%nx = 40
        call run(c, dense, stat)
        c%eigen%solver = 'arpack'
        do i = 1, size(ACCEPTED)
            c%eigen%target = ACCEPTED(i)
            call run(c, res, stat)
            write (what, '(a, es9.1e3)') 'target =', ACCEPTED(i)
            call t%check(trim(what)//': solved', stat%ok())
            if (.not. stat%ok()) cycle
            call t%check(trim(what)//': certified, no warning', size(res%warnings) == 0)
            call t%check(trim(what)//': a positive mu', res%spec%lowest_positive() == 1)
            if (res%spec%lowest_positive() /= 1) cycle
            call t%check_close(trim(what)//': the dense lowest positive mu', &
                               real(res%spec%mu(1), wp), real(dense%spec%mu(1), wp), &
                               rel_tol=1.0e-8_wp)
        end do
        do i = 1, size(REFUSED)
            c%eigen%target = REFUSED(i)
            call run(c, res, stat)
            write (what, '(a, es9.1e3)') 'target =', REFUSED(i)
            call check_refused(t, trim(what), stat, '&eigen: target = ')
        end do
        ! the range scales with the spectrum: E = 1e-300 moves it to 6.5e-296
        c%material%young = 1.0e-300_wp
        c%eigen%target = 1.0e-296_wp
        call run(c, res, stat)
        call t%check('E = 1e-300, target = 1e-296: solved, certified', stat%ok())
        if (stat%ok()) call t%check_close('E = 1e-300, target = 1e-296: 1e-300 x dense mu', &
            real(res%spec%mu(1), wp), 1.0e-300_wp*real(dense%spec%mu(1), wp), rel_tol=1.0e-8_wp)
        c%eigen%target = 1.0e10_wp   ! 1e10 / 2^-997 overflows: clamped, then refused
        call run(c, res, stat)
        call check_refused(t, 'E = 1e-300, target = 1e10', stat, '&eigen: target = ')
    end subroutine arpack_targets

    !> K singular in binary64 only because of one input: that input is named, not the
    !> Dirichlet boundary. young = 1e308 is not singular at all (solved in units of E): its
    !> spectrum leaves the range, which names young.
    subroutine singular_looking_inputs(t)
        type(test_suite_t), intent(inout) :: t
        type(eigen_result_t) :: res
        type(config_t) :: c
        type(status_t) :: stat
        c = scene()
        c%material%poisson = 0.49999999999999_wp
        call run(c, res, stat)
        call check_refused(t, 'poisson = 0.49999999999999', stat, '&material: poisson = ')
        c = scene()
        c%mesh%width = 1.0e-12_wp
        call run(c, res, stat)
        call check_refused(t, 'width = 1e-12', stat, '&mesh: width = ')
        c = scene()
        c%mesh%width = 1.0e-6_wp
        call run(c, res, stat)
        call check_refused(t, 'width = 1e-6', stat, '&mesh: width = ')
        call t%check('width = 1e-6: blames the aspect ratio', &
                     index(stat%message, 'aspect ratio') > 0)
        c = scene()
        c%mesh%width = 1.0e-300_wp
        c%mesh%height = 1.0e300_wp
        call run(c, res, stat)
        call check_refused(t, 'width = 1e-300, height = 1e300', stat, '&mesh: coordinates ')
        c = scene()
        c%material%young = 1.0e308_wp
        call run(c, res, stat)
        call check_refused(t, 'young = 1e308', stat, '&material: young = ')
        call t%check('young = 1e308: not called singular', index(stat%message, 'singular') == 0)
        ! still solved: just below the bounds
        c = scene()
        c%material%poisson = 0.499999999999_wp
        call run(c, res, stat)
        call t%check('poisson = 0.499999999999: solved to round-off', stat%ok())
        if (stat%ok()) call t%check('poisson = 0.499999999999: residuals below bound', &
                                    res%spec%max_residual() <= BACKWARD_ERROR_BOUND)
    end subroutine singular_looking_inputs

    !> Every eigenvalue of `res` is exactly 2^power times that of `base`, residuals equal.
    subroutine check_exact(t, what, base, res, power, stat)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: what
        type(eigen_result_t), intent(in) :: base, res
        integer, intent(in) :: power
        type(status_t), intent(in) :: stat
        integer :: i
        logical :: same
        call t%check(what//': solved', stat%ok())
        if (.not. stat%ok()) return
        same = base%spec%n() == res%spec%n()
        if (same) then
            do i = 1, base%spec%n()
                same = same .and. abs(res%spec%mu(i) - cmplx(scale(real(base%spec%mu(i), wp), &
                    power), scale(aimag(base%spec%mu(i)), power), wp)) <= 0.0_wp
            end do
            same = same .and. all(abs(res%spec%residual - base%spec%residual) <= 0.0_wp)
        end if
        call t%check(what//': mu = 2^k mu(1) bit for bit, same residuals', same)
        call t%check(what//': no warning', size(res%warnings) == 0)
    end subroutine check_exact

    !> Every real mu scaled by `factor` to 100 x its condition x eps; honest residuals.
    subroutine check_scaled(t, what, base, res, factor, stat)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: what
        type(eigen_result_t), intent(in) :: base, res
        real(wp), intent(in) :: factor
        type(status_t), intent(in) :: stat
        real(wp) :: worst
        integer :: i
        call t%check(what//': solved', stat%ok())
        if (.not. stat%ok()) return
        call t%check(what//': same count and kinds', base%spec%n() == res%spec%n() .and. &
                     all(base%spec%kind == res%spec%kind))
        if (base%spec%n() /= res%spec%n()) return
        worst = 0.0_wp
        do i = 1, base%spec%n()
            if (base%spec%kind(i) == KIND_COMPLEX) cycle
            worst = max(worst, abs(real(res%spec%mu(i), wp)/factor - &
                                   real(base%spec%mu(i), wp))/abs(base%spec%mu(i))/ &
                        (base%spec%condition(i)*epsilon(1.0_wp)))
        end do
        call t%check(what//': every real mu scales, within 100 condition eps', worst <= 100.0_wp)
        call t%check(what//': residuals finite and below bound', &
                     res%spec%max_residual() <= BACKWARD_ERROR_BOUND .and. &
                     minval(res%spec%residual) > 0.0_wp)
        call t%check(what//': no warning', size(res%warnings) == 0)
    end subroutine check_scaled

    !> A one-line STATUS_BAD_INPUT message naming the input file and `names`.
    subroutine check_refused(t, what, stat, names)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: what, names
        type(status_t), intent(in) :: stat
        call t%check(what//': refused as bad input', stat%code == STATUS_BAD_INPUT)
        if (stat%ok()) return
        call t%check(what//': the message names the file and '//names//' ('//stat%message// &
                     ')', index(stat%message, 'test_extremes_range: '//names) == 1 .and. &
                     index(stat%message, new_line('a')) == 0)
    end subroutine check_refused

    !> The reference scene of model.md section 10 on 8 x 8 cells, dense solver, no output.
    type(config_t) function scene() result(c)
        c%input_file = 'test_extremes_range'
        c%mesh%nx = 8
        c%mesh%ny = 8
        c%eigen%solver = 'dense'
    end function scene

    subroutine run(c, res, stat)
        type(config_t), intent(in) :: c
        type(eigen_result_t), intent(out) :: res
        type(status_t), intent(out) :: stat
        type(problem_t) :: prob
        type(timings_t) :: timings
        call problem_of(c, prob, stat)
        if (stat%ok()) call eigen_of(c, prob, c%analysis%lambda, res, timings, stat)
        ! the spectrum of the input problem, as the report gives it (reported_units)
        if (stat%ok()) call to_input_units(prob%units, res%spec%mu)
    end subroutine run
end program test_extremes_range
