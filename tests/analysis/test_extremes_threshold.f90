! SPDX-License-Identifier: MIT
!> Extremes suite (CTest label 'extremes'): lambda within 1e-6 relative of a threshold, on
!> both sides. Thresholds are the real eigenvalues nearest zero of Kt_nn x = lambda Kt_nt x
!> (model.md sections 4-7), computed here independently with contact_flexibility and LAPACK dggev;
!> for the single element of model.md section 8 in closed form, -(L + 3G)/(L + G).
program test_extremes_threshold
    use kinds, only: wp
    use fixtures, only: problem_of, eigen_of
    use status, only: status_t
    use testing, only: test_suite_t
    use fixtures, only: has_warning, single_triangle_mesh => single_triangle
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use eigen_solve, only: eigen_result_t, solve_eigen
    use dof_map, only: build_dof_map
    use contact_boundary, only: build_contact
    use assembly, only: assemble_stiffness
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness, contact_flexibility
    use lapack_interfaces, only: dggev
    use spectrum, only: KIND_COMPLEX
    use accuracy, only: LAMBDA_SENSITIVITY_BOUND
    implicit none

    real(wp), parameter :: OFFSET = 1.0e-6_wp   !! relative distance to the threshold
    type(test_suite_t) :: t
    t%name = 'test_extremes_threshold'
    call single_element_threshold(t)
    call reference_scene_thresholds(t)
    call t%report()

contains

    !> One P1 triangle: mu = -6 G (L + 2G) / ((L (lambda + 1) + G (lambda + 3)) l) = c /
    !> (lambda - lambda_c), so |lambda dmu/dlambda / mu| = |lambda / (lambda - lambda_c)|
    !> exactly. Evaluating the closed form cancels digits in its denominator: its relative
    !> error is about eps |lambda| (L + G) / |denominator| = eps x sensitivity, which with
    !> the solver's own (condition x eps) sets the tolerances: 100 x (both) x eps.
    subroutine single_element_threshold(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: YOUNG = 1.0_wp, POISSON = 0.3_wp, L_SIDE = 1.0_wp
        real(wp) :: lame_l, shear_g, critical, lambda, expected, sensitivity, tol
        real(wp) :: lambdas(4)
        type(eigen_result_t) :: res
        type(problem_t) :: prob
        type(config_t) :: c
        character(len=60) :: what
        integer :: i

        lame_l = YOUNG*POISSON/((1.0_wp + POISSON)*(1.0_wp - 2.0_wp*POISSON))
        shear_g = YOUNG/(2.0_wp*(1.0_wp + POISSON))
        critical = -(lame_l + 3.0_wp*shear_g)/(lame_l + shear_g)
        call single_triangle(L_SIDE, YOUNG, POISSON, prob)
        c%input_file = 'single element'
        c%eigen%solver = 'dense'
        lambdas = [critical*(1.0_wp + OFFSET), critical*(1.0_wp - OFFSET), -10.0_wp, 5.0_wp]
        do i = 1, size(lambdas)
            lambda = lambdas(i)
            call solve(c, prob, lambda, res)
            expected = -6.0_wp*shear_g*(lame_l + 2.0_wp*shear_g)/ &
                       ((lame_l*(lambda + 1.0_wp) + shear_g*(lambda + 3.0_wp))*L_SIDE)
            sensitivity = abs(lambda/(lambda - critical))
            write (what, '(a, es15.8)') 'single element, lambda =', lambda
            if (res%spec%n() /= 1) then
                call t%check(trim(what)//': one eigenvalue', .false.)
                cycle
            end if
            tol = 100.0_wp*(res%spec%condition(1) + sensitivity)*epsilon(1.0_wp)
            call t%check_close(trim(what)//': mu = closed form', real(res%spec%mu(1), wp), &
                               expected, tol)
            call t%check_close(trim(what)//': lambda sensitivity = |lambda/(lambda-lambda_c)|', &
                               res%spec%lambda_sensitivity(1), sensitivity, tol)
            call t%check(trim(what)//': near-threshold warning iff sensitivity > bound', &
                         has_warning(res, 'near a critical') .eqv. &
                         sensitivity > LAMBDA_SENSITIVITY_BOUND)
        end do
    end subroutine single_element_threshold

    !> The reference scene, 8 x 8 P1 and Q1: on each side of each threshold lambda_c, at
    !> lambda_c (1 -+ 1e-6) and lambda_c (1 -+ 2e-6). The eigenvalue through infinity
    !> behaves like C / (lambda - lambda_c) + O(1): halving the distance doubles it, to
    !> about 1e-6 relative (the O(1) term over C / 1e-6) plus the threshold's own error,
    !> condition x eps / 1e-6; 1e-4 is safe. It is positive beyond the threshold, negative
    !> before it, and the near-threshold warning is there on both sides.
    subroutine reference_scene_thresholds(t)
        type(test_suite_t), intent(inout) :: t
        character(len=2), parameter :: ELEMENTS(2) = ['p1', 'q1']
        type(config_t) :: c
        type(problem_t) :: prob
        type(eigen_result_t) :: near, nearer
        type(status_t) :: stat
        real(wp) :: thresholds(2), side, big_near, big_nearer
        character(len=80) :: what
        integer :: e, i, s

        do e = 1, size(ELEMENTS)
            c%input_file = 'reference scene'
            c%mesh%nx = 8
            c%mesh%ny = 8
            c%mesh%element = ELEMENTS(e)
            c%eigen%solver = 'dense'
            call problem_of(c, prob, stat)
            call pencil_thresholds(prob, thresholds)
            call t%check(ELEMENTS(e)//': thresholds on both sides of 0', &
                         thresholds(1) < 0.0_wp .and. thresholds(2) > 0.0_wp)
            do i = 1, 2
                do s = 1, 2
                    side = merge(1.0_wp, -1.0_wp, s == 1)   ! +1: beyond, -1: before
                    call solve(c, prob, thresholds(i)*(1.0_wp + side*2.0_wp*OFFSET), near)
                    call solve(c, prob, thresholds(i)*(1.0_wp + side*OFFSET), nearer)
                    big_near = largest_real(near)
                    big_nearer = largest_real(nearer)
                    write (what, '(a, es12.5, a)') ELEMENTS(e)//', lambda_c =', thresholds(i), &
                        merge(', beyond', ', before', s == 1)
                    call t%check_close(trim(what)//': mu ~ 1/(lambda - lambda_c)', &
                                       big_nearer, 2.0_wp*big_near, 1.0e-4_wp)
                    call t%check(trim(what)//': sign of the mu through infinity', &
                                 (big_nearer > 0.0_wp) .eqv. (s == 1))
                    if (s == 1) call t%check(trim(what)//': it is the lowest positive', &
                        abs(real(nearer%spec%mu(1), wp) - big_nearer) <= 0.0_wp)
                    call t%check(trim(what)//': near-threshold warning', &
                                 has_warning(nearer, 'near a critical'))
                    call t%check(trim(what)//': its relative error estimate stays small', &
                                 maxval(nearer%spec%residual) < 1.0e-10_wp)
                end do
            end do
        end do
    end subroutine reference_scene_thresholds

    !> The real eigenvalues of Kt_nn x = lambda Kt_nt x nearest zero: (negative, positive).
    subroutine pencil_thresholds(prob, thresholds)
        type(problem_t), intent(in) :: prob
        real(wp), intent(out) :: thresholds(2)
        type(cholesky_t) :: chol
        type(timings_t) :: timings
        type(status_t) :: stat
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), alphar(:), alphai(:), beta(:), &
                                 work(:), vl(:, :), vr(:, :)
        real(wp) :: query(1), value
        integer :: p, info, j
        call factor_stiffness(prob%k, prob%mesh, prob%dofs, prob%contact, chol, timings, stat)
        call contact_flexibility(chol, prob%contact, kt_nn, kt_nt, stat)
        call chol%free()
        p = prob%contact%p()
        allocate (alphar(p), alphai(p), beta(p), vl(1, 1), vr(1, 1))
        call dggev('N', 'N', p, kt_nn, p, kt_nt, p, alphar, alphai, beta, vl, 1, vr, 1, query, &
                   -1, info)
        allocate (work(int(query(1))))
        call dggev('N', 'N', p, kt_nn, p, kt_nt, p, alphar, alphai, beta, vl, 1, vr, 1, work, &
                   size(work), info)
        thresholds = [-huge(1.0_wp), huge(1.0_wp)]
        do j = 1, p
            if (abs(alphai(j)) > 0.0_wp .or. .not. abs(beta(j)) > 0.0_wp) cycle
            value = alphar(j)/beta(j)
            if (value < 0.0_wp) thresholds(1) = max(thresholds(1), value)
            if (value > 0.0_wp) thresholds(2) = min(thresholds(2), value)
        end do
    end subroutine pencil_thresholds

    !> The real mu of largest modulus.
    real(wp) function largest_real(res)
        type(eigen_result_t), intent(in) :: res
        integer :: i
        largest_real = 0.0_wp
        do i = 1, res%spec%n()
            if (res%spec%kind(i) == KIND_COMPLEX) cycle
            if (abs(res%spec%mu(i)) > abs(largest_real)) largest_real = real(res%spec%mu(i), wp)
        end do
    end function largest_real
    subroutine solve(c, prob, lambda, res)
        type(config_t), intent(in) :: c
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: lambda
        type(eigen_result_t), intent(out) :: res
        type(timings_t) :: timings
        type(status_t) :: stat
        call eigen_of(c, prob, lambda, res, timings, stat)
        if (.not. stat%ok()) then
            call t%check('solve: '//stat%message, .false.)
            error stop 1
        end if
    end subroutine solve

    !> model.md section 8: A = (0,0), B = (l,0), C = (0,l); [A,B] contact, [B,C] fixed.
    subroutine single_triangle(l, young, poisson, prob)
        real(wp), intent(in) :: l, young, poisson
        type(problem_t), intent(out) :: prob
        type(status_t) :: stat
        call single_triangle_mesh(l, prob%mesh)
        prob%young = young
        prob%poisson = poisson
        prob%dirichlet_parts = [2]
        prob%contact_part = 1
        call build_dof_map(prob%mesh, prob%dirichlet_parts, prob%dofs, stat)
        if (stat%ok()) call build_contact(prob%mesh, 1, prob%dofs, prob%contact, stat)
        if (stat%ok()) call assemble_stiffness(prob%mesh, prob%dofs, young, poisson, prob%k, stat)
        if (.not. stat%ok()) error stop 1
    end subroutine single_triangle
end program test_extremes_threshold
