! SPDX-License-Identifier: MIT
!> The dense reduced solver against mathematics: the single element of model.md section 8 in
!> closed form, an independent dense QZ solve of the full pencil, scaling laws and residuals.
program test_dense_eigen
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use fixtures, only: single_triangle, csr_to_dense
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_P3
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use contact_boundary, only: contact_t, build_contact, assemble_b
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use spectrum, only: spectrum_t, KIND_POSITIVE, KIND_NEGATIVE, KIND_COMPLEX
    use dense_eigen, only: dense_spectrum, contact_flexibility
    use contact_reduction, only: factor_stiffness, lift_block_columns, lift_share_t, lift_share
    use roundoff, only: left_from_reduced
    use timer, only: timings_t
    use lapack_interfaces, only: dggev
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_dense_eigen'
    call single_element_closed_form(t)
    call reduced_problem_matches_full_pencil(t)
    call eigenvalues_scale_with_young_modulus(t)
    call eigenvalues_scale_with_inverse_size(t)
    call output_order_and_residuals(t)
    call trailing_block_matches_forward_solves(t)
    call many_blocks_of_eigenvectors(t)
    call lowest_only_matches_full_spectrum(t)
    call left_lift_matches_full_solve(t)
    call t%report()

contains

    !> model.md section 8: mu = -6 G (L + 2G) / ((L (lambda + 1) + G (lambda + 3)) l) for the one
    !> triangle A, B, C with B, C fixed and Gamma_C = [A, B]. The reduction is exact algebra on
    !> a 2 x 2 system, so round-off is the only error: 1e-12 relative.
    subroutine single_element_closed_form(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: LAMBDAS(6) = [-100.0_wp, -10.0_wp, -3.0_wp, -2.5_wp, 0.0_wp, &
                                             5.0_wp]
        real(wp), parameter :: SIZES(3) = [1.0_wp, 0.01_wp, 100.0_wp]
        real(wp), parameter :: YOUNG = 1.0_wp, POISSON = 0.3_wp
        real(wp) :: lame_l, shear_g, expected, l
        type(spectrum_t) :: spec
        type(mesh_t) :: m
        character(len=80) :: what
        integer :: i, s

        lame_l = YOUNG*POISSON/((1.0_wp + POISSON)*(1.0_wp - 2.0_wp*POISSON))
        shear_g = YOUNG/(2.0_wp*(1.0_wp + POISSON))
        do s = 1, size(SIZES)
            l = SIZES(s)
            call single_triangle(l, m)
            do i = 1, size(LAMBDAS)
                call solve_scene(m, [2], 1, YOUNG, POISSON, LAMBDAS(i), spec)
                expected = -6.0_wp*shear_g*(lame_l + 2.0_wp*shear_g)/ &
                           ((lame_l*(LAMBDAS(i) + 1.0_wp) + shear_g*(LAMBDAS(i) + 3.0_wp))*l)
                write (what, '(a, f7.1, a, es8.1)') 'single element mu, lambda =', LAMBDAS(i), &
                    ', l =', l
                call t%check(trim(what)//': one eigenvalue', spec%n() == 1)
                if (spec%n() /= 1) cycle
                call t%check_close(trim(what), real(spec%mu(1), wp), expected, 1.0e-12_wp)
                call t%check(trim(what)//': sign decides the kind', &
                    (expected > 0.0_wp .eqv. spec%kind(1) == KIND_POSITIVE))
            end do
        end do
    end subroutine single_element_closed_form

    !> The p nonzero theta = 1/mu of the reduced problem are the nonzero eigenvalues of the
    !> full pencil (B, K), computed independently by LAPACK's QZ on dense n x n copies. The
    !> other n - p are zero (B has rank p). Both computations are backward stable, so each mu
    !> must agree within its reported relative condition number times eps, up to a factor
    !> 1e3 for the dimension and the reference's own error: this also checks the condition
    !> numbers themselves.
    subroutine reduced_problem_matches_full_pencil(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: ELEMENTS(3) = [ELEMENT_P1, ELEMENT_P1, ELEMENT_Q1]
        character(len=5), parameter :: DIAGONALS(3) = ['right', 'left ', 'right']
        real(wp), parameter :: LAMBDAS(3) = [5.0_wp, -7.0_wp, 0.5_wp]
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: k, b
        type(spectrum_t) :: spec
        type(status_t) :: stat
        real(wp), allocatable :: kd(:, :), bd(:, :), alphar(:), alphai(:), beta(:), work(:), &
                                 vl(:, :), vr(:, :)
        complex(wp), allocatable :: theta(:), reference(:)
        real(wp) :: query(1), worst
        integer :: c, j, n, p, info, order(1), i
        logical, allocatable :: used(:)
        character(len=60) :: what

        do c = 1, size(ELEMENTS)
            call structured_rectangle(1.0_wp, 1.0_wp, 4, 4, ELEMENTS(c), trim(DIAGONALS(c)), &
                                      m, stat)
            call build_dof_map(m, [m%part_index('top')], dofs, stat)
            call build_contact(m, m%part_index('bottom'), dofs, contact, stat)
            call assemble_stiffness(m, dofs, 1.0_wp, 0.3_wp, k, stat)
            call assemble_b(contact, dofs%n_free, LAMBDAS(c), b, stat)
            call solve_scene(m, [m%part_index('top')], m%part_index('bottom'), 1.0_wp, 0.3_wp, &
                             LAMBDAS(c), spec)
            n = dofs%n_free
            p = contact%p()
            kd = csr_to_dense(k)
            bd = csr_to_dense(b)
            allocate (alphar(n), alphai(n), beta(n), vl(1, 1), vr(1, 1))
            call dggev('N', 'N', n, bd, n, kd, n, alphar, alphai, beta, vl, 1, vr, 1, query, &
                       -1, info)
            allocate (work(int(query(1))))
            call dggev('N', 'N', n, bd, n, kd, n, alphar, alphai, beta, vl, 1, vr, 1, work, &
                       size(work), info)
            theta = cmplx(alphar, alphai, wp)/beta
            ! the p largest |theta| are the nonzero ones; match each computed mu to one
            allocate (used(n), source=.false.)
            allocate (reference(p))
            do j = 1, p
                order = maxloc(abs(theta), mask=.not. used)
                used(order(1)) = .true.
                reference(j) = 1.0_wp/theta(order(1))
            end do
            write (what, '(a, i0, a, f5.1)') 'reduced = full pencil, case ', c, ', lambda ', &
                LAMBDAS(c)
            call t%check(trim(what)//': p eigenvalues', spec%n() == p)
            worst = 0.0_wp
            do i = 1, spec%n()
                worst = max(worst, minval(abs(reference - spec%mu(i)))/abs(spec%mu(i))/ &
                            (spec%condition(i)*epsilon(1.0_wp)))
            end do
            call t%check(trim(what)//': every mu matches to 1e3 eps condition', worst <= 1.0e3_wp)
            call t%check(trim(what)//': the rest of the full spectrum is zero', &
                maxval(abs(theta), mask=.not. used) <= 1.0e-10_wp*maxval(abs(theta)))
            deallocate (alphar, alphai, beta, vl, vr, work, used, reference)
        end do
    end subroutine reduced_problem_matches_full_pencil

    !> K is proportional to E and B does not depend on it, so mu is exactly proportional to E.
    subroutine eigenvalues_scale_with_young_modulus(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(spectrum_t) :: base, scaled
        type(status_t) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, 6, 6, ELEMENT_P1, 'right', m, stat)
        call solve_scene(m, [m%part_index('top')], m%part_index('bottom'), 1.0_wp, 0.3_wp, &
                         5.0_wp, base)
        call solve_scene(m, [m%part_index('top')], m%part_index('bottom'), 1.0e3_wp, 0.3_wp, &
                         5.0_wp, scaled)
        call t%check('scaling with E: same count', base%n() == scaled%n())
        call t%check_close('scaling with E: lowest positive mu x 1000', &
                           real(scaled%mu(1), wp), 1.0e3_wp*real(base%mu(1), wp), 1.0e-11_wp)
        ! the largest |mu| is the worst conditioned: allow 1e2 eps times its condition
        call t%check_close('scaling with E: largest |mu| x 1000', maxval(abs(scaled%mu)), &
            1.0e3_wp*maxval(abs(base%mu)), 1.0e2_wp*epsilon(1.0_wp)*maxval(base%condition))
    end subroutine eigenvalues_scale_with_young_modulus

    !> In 2D, K is invariant under x -> s x while M (a length) scales with s: mu -> mu / s.
    subroutine eigenvalues_scale_with_inverse_size(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(spectrum_t) :: base, scaled
        type(status_t) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, 6, 6, ELEMENT_Q1, 'right', m, stat)
        call solve_scene(m, [m%part_index('top')], m%part_index('bottom'), 1.0_wp, 0.3_wp, &
                         5.0_wp, base)
        call structured_rectangle(25.0_wp, 25.0_wp, 6, 6, ELEMENT_Q1, 'right', m, stat)
        call solve_scene(m, [m%part_index('top')], m%part_index('bottom'), 1.0_wp, 0.3_wp, &
                         5.0_wp, scaled)
        call t%check_close('scaling with size: lowest positive mu / 25', &
                           real(scaled%mu(1), wp), real(base%mu(1), wp)/25.0_wp, 1.0e-11_wp)
    end subroutine eigenvalues_scale_with_inverse_size

    !> Output order of docs/outputs.md, and backward errors at round-off level: the chain
    !> (Cholesky, dgeevx, one more solve) is backward stable, so eta ~ n eps; 1e-12 allows it.
    subroutine output_order_and_residuals(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(spectrum_t) :: spec
        type(status_t) :: stat
        integer :: i
        logical :: ordered
        call structured_rectangle(1.0_wp, 1.0_wp, 8, 8, ELEMENT_P1, 'right', m, stat)
        call solve_scene(m, [m%part_index('top')], m%part_index('bottom'), 1.0_wp, 0.3_wp, &
                         5.0_wp, spec)
        call t%check('reference scene N=8 has a positive eigenvalue', &
                     spec%lowest_positive() == 1)
        ordered = .true.
        do i = 2, spec%n()
            if (spec%kind(i) < spec%kind(i - 1)) ordered = .false.
            if (spec%kind(i) == spec%kind(i - 1) .and. spec%kind(i) /= KIND_COMPLEX) then
                if (abs(spec%mu(i)) < abs(spec%mu(i - 1))) ordered = .false.
            end if
            if (spec%kind(i) == KIND_COMPLEX .and. spec%kind(i - 1) == KIND_COMPLEX) then
                if (abs(spec%mu(i)) < abs(spec%mu(i - 1))*(1.0_wp - 1.0e-12_wp)) &
                    ordered = .false.
            end if
        end do
        call t%check('output order: positive ascending, negative, complex by modulus', ordered)
        call t%check('real kinds have zero imaginary part', &
            all(.not. (abs(aimag(spec%mu)) > 0.0_wp) .or. spec%kind == KIND_COMPLEX))
        call t%check('negative kinds are negative', all(real(spec%mu, wp) < 0.0_wp .or. &
                     spec%kind /= KIND_NEGATIVE))
        call t%check('every backward error below 1e-12', spec%max_residual() < 1.0e-12_wp)
    end subroutine output_order_and_residuals

    !> Kt_nn and Kt_nt as the solvers form them (dpotri on the trailing block of a factor with
    !> the contact dofs last) against the identity X' K^-1 Y = (L^-1 P X)' (L^-1 P Y) with
    !> forward solves through a factor in CHOLMOD's own ordering: the same matrices by two
    !> different factorizations and two different algorithms. Both are backward stable with
    !> K (condition about 1e3 on these 6 x 6 meshes), so they agree to about cond eps = 2e-13
    !> relative to the largest entry (seen: 1e-15 to 1e-14); 1e-12 leaves a factor 5.
    subroutine trailing_block_matches_forward_solves(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: ELEMENTS(5) = [ELEMENT_P1, ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, &
                                             ELEMENT_P3]
        character(len=5), parameter :: DIAGONALS(5) = ['right', 'left ', 'right', 'right', &
                                                       'right']
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: k
        type(cholesky_t) :: contact_last, own_order
        type(timings_t) :: timings
        type(status_t) :: stat
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), rhs(:, :), w_n(:, :), w_t(:, :)
        integer :: c, a, p, n
        character(len=40) :: what

        do c = 1, size(ELEMENTS)
            call structured_rectangle(1.0_wp, 1.0_wp, 6, 6, ELEMENTS(c), trim(DIAGONALS(c)), &
                                      m, stat)
            call build_dof_map(m, [m%part_index('top')], dofs, stat)
            call build_contact(m, m%part_index('bottom'), dofs, contact, stat)
            call assemble_stiffness(m, dofs, 1.0_wp, 0.3_wp, k, stat)
            write (what, '(a, i0)') 'contact blocks, case ', c
            call factor_stiffness(k, m, dofs, contact, contact_last, timings, stat)
            if (stat%ok()) call contact_flexibility(contact_last, contact, kt_nn, kt_nt, stat)
            call t%check(trim(what)//': formed from the trailing block', stat%ok())
            if (.not. stat%ok()) cycle
            n = dofs%n_free
            p = contact%p()
            call own_order%factor(k, stat)
            allocate (rhs(n, p), w_n(n, p), w_t(n, p), source=0.0_wp)
            do a = 1, p
                rhs(contact%dofs(:, a), a) = contact%normal
            end do
            call own_order%forward(rhs, w_n, stat)
            rhs = 0.0_wp
            do a = 1, p
                rhs(contact%dofs(:, a), a) = contact%tangent
            end do
            if (stat%ok()) call own_order%forward(rhs, w_t, stat)
            call t%check(trim(what)//': forward solves', stat%ok())
            call t%check_close(trim(what)//': Kt_nn = W_n'' W_n', maxval(abs(kt_nn - &
                matmul(transpose(w_n), w_n))), 0.0_wp, 0.0_wp, 1.0e-12_wp*maxval(abs(kt_nn)))
            call t%check_close(trim(what)//': Kt_nt = W_n'' W_t', maxval(abs(kt_nt - &
                matmul(transpose(w_n), w_t))), 0.0_wp, 0.0_wp, 1.0e-12_wp*maxval(abs(kt_nt)))
            call t%check(trim(what)//': Kt_nn exactly symmetric', &
                         maxval(abs(kt_nn - transpose(kt_nn))) <= 0.0_wp)
            call own_order%free()
            call contact_last%free()
            deallocate (rhs, w_n, w_t)
        end do
    end subroutine trailing_block_matches_forward_solves

    !> More eigenvectors than one block of the lift holds (p = 97 > 64 columns, complex pairs
    !> taking two): every pair still gets its own eigenvector, which its backward error shows
    !> (a vector of another eigenvalue would give an O(1) residual); round-off level as in
    !> output_order_and_residuals. The kept modes are normalised to largest entry 1.
    subroutine many_blocks_of_eigenvectors(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(spectrum_t) :: spec
        type(status_t) :: stat
        integer :: i
        call structured_rectangle(4.0_wp, 1.0_wp, 96, 6, ELEMENT_P1, 'left', m, stat)
        call solve_scene(m, [m%part_index('top')], m%part_index('bottom'), 1.0_wp, 0.3_wp, &
                         -7.0_wp, spec, n_keep=3)
        call t%check('p = 97 exceeds one block', spec%n() == 97 .and. &
                     lift_block_columns(2*97*6) < 97)
        call t%check('complex pairs present', count(spec%kind == KIND_COMPLEX) >= 2)
        call t%check('several blocks: every backward error below 1e-12', &
                     spec%max_residual() < 1.0e-12_wp)
        call t%check('three modes kept', size(spec%vectors, 2) == 3)
        do i = 1, size(spec%vectors, 2)
            call t%check_close('kept mode normalised', maxval(abs(spec%vectors(:, i))), &
                               1.0_wp, 1.0e-15_wp)
        end do
    end subroutine many_blocks_of_eigenvectors

    !> Assemble and solve one scene with the dense solver (n_keep full modes, default 1).
    !> The path of an hp sweep's points (lowest_only, with the level's blocks and the lifts'
    !> data made once: contact_flexibility with `share`) against the full dense spectrum
    !> without them, on the reference scene (N = 8, P1, p = 9) at lambdas with and without a
    !> positive mu. The same matrix and the same LAPACK calls: every mu and the lowest's mode
    !> agree to round-off (1e-12 relative: the lift solves one column where the full path
    !> solves a block, which BLAS rounds differently). The backward error is round-off noise
    !> (|K phi - mu B phi| at ~eps, seen 4e-17 to 9e-17 on both paths, ratios 0.7 to 1.4):
    !> below 1e-14 and within a factor 10 of the full path's, which a wrong ||K|| in the shared
    !> data would leave. The round-off bound is mostly its eps |y|'(|K| + |mu B|)|x| part,
    !> which depends on the vectors to first order (seen: 6e-4 relative apart): 5 %. Only the
    !> other backward errors are left unknown (-1), and nothing is lifted where no positive
    !> mu exists.
    subroutine lowest_only_matches_full_spectrum(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: LAMBDAS(4) = [-12.0_wp, -0.5_wp, 3.0_wp, 12.0_wp]
        real(wp), parameter :: TOL = 1.0e-12_wp
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: k, b
        type(cholesky_t) :: chol
        type(timings_t) :: timings
        type(status_t) :: stat
        type(spectrum_t) :: full, fast
        type(lift_share_t) :: share
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :)
        character(len=40) :: what
        integer :: i, n_without

        call structured_rectangle(1.0_wp, 1.0_wp, 8, 8, ELEMENT_P1, 'right', m, stat)
        if (stat%ok()) call build_dof_map(m, [m%part_index('top')], dofs, stat)
        if (stat%ok()) call build_contact(m, m%part_index('bottom'), dofs, contact, stat)
        if (stat%ok()) call assemble_stiffness(m, dofs, 1.0_wp, 0.3_wp, k, stat)
        if (stat%ok()) call factor_stiffness(k, m, dofs, contact, chol, timings, stat)
        if (stat%ok()) call contact_flexibility(chol, contact, kt_nn, kt_nt, stat, k, share)
        call t%check('lowest_only: blocks and shared lift data', stat%ok() .and. &
                     allocated(share%l_tail) .and. share%k_norm > 0.0_wp)
        if (.not. stat%ok()) return
        n_without = 0
        do i = 1, size(LAMBDAS)
            write (what, '(a, f6.1, a)') 'lowest_only, lambda =', LAMBDAS(i), ':'
            call assemble_b(contact, dofs%n_free, LAMBDAS(i), b, stat)
            if (stat%ok()) call dense_spectrum(k, b, chol, contact, LAMBDAS(i), 1, full, stat)
            if (stat%ok()) call dense_spectrum(k, b, chol, contact, LAMBDAS(i), 1, fast, stat, &
                kt_nn_given=kt_nn, kt_nt_given=kt_nt, lowest_only=.true., share=share)
            call t%check(trim(what)//' both run', stat%ok())
            if (.not. stat%ok()) cycle
            call t%check(trim(what)//' the same eigenvalues', full%n() == fast%n() .and. &
                         full%n() == contact%p())
            if (full%n() /= fast%n()) cycle
            call t%check(trim(what)//' every mu to round-off', &
                         all(abs(fast%mu - full%mu) <= TOL*abs(full%mu)))
            call t%check(trim(what)//' the others'' backward errors unknown', &
                         all(fast%residual(2:) < 0.0_wp) .and. all(full%residual >= 0.0_wp))
            if (full%lowest_positive() == 0) then
                n_without = n_without + 1
                call t%check(trim(what)//' no positive mu: nothing lifted', &
                             fast%lowest_positive() == 0 .and. size(fast%vectors, 2) == 0 &
                             .and. fast%residual(1) < 0.0_wp)
                cycle
            end if
            call t%check(trim(what)//' the lowest''s mode', size(fast%vectors, 2) == 1 .and. &
                maxval(abs(fast%vectors(:, 1) - full%vectors(:, 1))) <= &
                TOL*maxval(abs(full%vectors(:, 1))))
            call t%check(trim(what)//' its backward error', fast%residual(1) <= 1.0e-14_wp &
                         .and. fast%residual(1) <= 10.0_wp*full%residual(1) .and. &
                         full%residual(1) <= 10.0_wp*fast%residual(1))
            call t%check(trim(what)//' its round-off bound', full%roundoff(1) >= 0.0_wp .and. &
                         abs(fast%roundoff(1) - full%roundoff(1)) <= 0.05_wp*full%roundoff(1))
        end do
        call t%check('lowest_only: a lambda without a positive mu was seen', n_without > 0)
        call chol%free()
    end subroutine lowest_only_matches_full_spectrum

    !> The pencil's left vector y = K^-1 N' w of a reduced left vector w, from the lifts'
    !> shared data (the trailing block of the factor, then its backward half: what an hp
    !> sweep's points use) against the full solve with the factor, on the reference scene
    !> (N = 8, P2 on Gamma_C: p = 17) for a w with every entry nonzero. Both solve K y = N' w
    !> with the same factor, in another order of the same operations: they agree to
    !> round-off, cond(K) eps ~ 1e-13 here (1e-11 leaves room), and y solves the system:
    !> ||K y - N' w||_inf <= 1e-12 ||K||_inf ||y||_inf (a backward stable solve leaves ~eps).
    subroutine left_lift_matches_full_solve(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: k
        type(cholesky_t) :: chol
        type(timings_t) :: timings
        type(status_t) :: stat
        type(lift_share_t) :: share
        real(wp), allocatable :: w(:), y_full(:), y_share(:), rhs(:), ky(:)
        integer :: a

        call structured_rectangle(1.0_wp, 1.0_wp, 8, 8, ELEMENT_P2, 'right', m, stat)
        if (stat%ok()) call build_dof_map(m, [m%part_index('top')], dofs, stat)
        if (stat%ok()) call build_contact(m, m%part_index('bottom'), dofs, contact, stat)
        if (stat%ok()) call assemble_stiffness(m, dofs, 1.0_wp, 0.3_wp, k, stat)
        if (stat%ok()) call factor_stiffness(k, m, dofs, contact, chol, timings, stat)
        if (stat%ok()) call lift_share(k, chol, contact, share, stat)
        allocate (w(contact%p()))
        w = [(1.0_wp + 0.25_wp*sin(real(a, wp)), a=1, contact%p())]
        if (stat%ok()) call left_from_reduced(chol, contact, dofs%n_free, w, y_full, stat)
        if (stat%ok()) call left_from_reduced(chol, contact, dofs%n_free, w, y_share, stat, &
                                              share)
        call t%check('left lift: both paths run', stat%ok() .and. allocated(y_full) .and. &
                     allocated(y_share))
        if (.not. stat%ok()) return
        call t%check('left lift: the shared data''s y is the full solve''s to round-off', &
                     maxval(abs(y_share - y_full)) <= 1.0e-11_wp*maxval(abs(y_full)))
        allocate (rhs(dofs%n_free), source=0.0_wp)
        allocate (ky(dofs%n_free))
        call contact%scatter(contact%normal, w, rhs)
        call k%matvec(y_share, ky)
        call t%check('left lift: K y = N'' w', maxval(abs(ky - rhs)) <= &
                     1.0e-12_wp*k%norm_inf()*maxval(abs(y_share)))
        call chol%free()
    end subroutine left_lift_matches_full_solve

    subroutine solve_scene(m, dirichlet_parts, contact_part, young, poisson, lambda, spec, &
                           n_keep)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: dirichlet_parts(:), contact_part
        real(wp), intent(in) :: young, poisson, lambda
        type(spectrum_t), intent(out) :: spec
        integer, intent(in), optional :: n_keep
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: k, b
        type(cholesky_t) :: chol
        type(timings_t) :: timings
        type(status_t) :: stat
        call build_dof_map(m, dirichlet_parts, dofs, stat)
        if (stat%ok()) call build_contact(m, contact_part, dofs, contact, stat)
        if (stat%ok()) call assemble_stiffness(m, dofs, young, poisson, k, stat)
        if (stat%ok()) call assemble_b(contact, dofs%n_free, lambda, b, stat)
        if (stat%ok()) call factor_stiffness(k, m, dofs, contact, chol, timings, stat)
        if (stat%ok()) then
            if (present(n_keep)) then
                call dense_spectrum(k, b, chol, contact, lambda, n_keep, spec, stat)
            else
                call dense_spectrum(k, b, chol, contact, lambda, 1, spec, stat)
            end if
        end if
        call chol%free()
        if (.not. stat%ok()) then
            call t%check('solve_scene: '//stat%message, .false.)
            allocate (spec%mu(0), spec%kind(0), spec%residual(0), spec%condition(0))
        end if
    end subroutine solve_scene
end program test_dense_eigen
