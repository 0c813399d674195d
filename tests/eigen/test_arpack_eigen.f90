! SPDX-License-Identifier: MIT
!> The ARPACK solver against the dense solver (LAPACK dgeevx on the whole reduced matrix;
!> both read K^-1 on the contact dofs off the same factor, which test_dense_eigen checks
!> against forward solves and dense inverses) over many scenes, and its parts
!> against mathematics: the trailing block of the factor is K^-1 on the contact dofs, the
!> node ordering puts the contact dofs last, the certificate logic, the info sentences.
program test_arpack_eigen
    use kinds, only: wp
    use fixtures, only: problem_of, eigen_of
    use status, only: status_t
    use testing, only: test_suite_t
    use fixtures, only: square_scene
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use timer, only: timings_t
    use eigen_solve, only: eigen_result_t, solve_eigen
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness
    use node_ordering, only: nested_dissection_last
    use metis_c, only: metis_status_message
    use arpack_eigen, only: certify_lowest, is_real_ritz, CERTIFIED_FOUND, CERTIFIED_NONE, &
                            UNDECIDED
    use arpack_interfaces, only: arpack_info_message
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_arpack_eigen'
    call ordering_puts_contact_last(t)
    call trailing_block_is_contact_compliance(t)
    call certificate_logic(t)
    call real_or_complex_ritz(t)
    call info_sentences(t)
    call agrees_with_dense_over_scenes(t)
    call agrees_near_the_threshold(t)
    call target_finds_the_same_lowest(t)
    call too_few_contact_nodes(t)
    call left_vector_from_the_certificate(t)
    call reference_scene_converges(t, 'p3')
    call reference_scene_converges(t, 'p4')
    call t%report()

contains

    !> The reference scene at lambda = 5 with P3 or P4 on N x N squares, N = 4, 8, 16: mu
    !> rises towards the mesh limit 0.7528436 (Richardson from the P1/P2 sweeps) and the
    !> error falls by more than 2.5 per halving of h (about 3: the corner singularities at
    !> the ends of the contact side, not the degree, set the rate); N = 16 is within 4e-5.
    !> Measured: P3 0.7525593, 0.7527432, 0.7528130; P4 0.7527148, 0.7528063, 0.7528320.
    subroutine reference_scene_converges(t, element)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: element
        real(wp), parameter :: LIMIT = 0.7528436_wp
        integer, parameter :: SIZES(3) = [4, 8, 16]
        type(config_t) :: config
        real(wp) :: mu(3), r
        character(len=:), allocatable :: warning
        logical :: ok, all_ok
        integer :: s
        all_ok = .true.
        do s = 1, size(SIZES)
            call square_scene(SIZES(s), element, 'right', config)
            call lowest(config, 'auto', 5.0_wp, mu(s), r, warning, ok)
            all_ok = all_ok .and. ok
        end do
        write (*, '(a, 3f14.10)') '      '//element//' reference scene, N = 4, 8, 16: mu =', mu
        call t%check(element//' reference scene: solves succeed', all_ok)
        call t%check(element//' reference scene: mu rises towards the limit from below', &
                     all(mu < LIMIT) .and. mu(2) > mu(1) .and. mu(3) > mu(2))
        call t%check(element//' reference scene: error falls by > 2.5 per halving of h', &
                     (LIMIT - mu(1)) > 2.5_wp*(LIMIT - mu(2)) .and. &
                     (LIMIT - mu(2)) > 2.5_wp*(LIMIT - mu(3)))
        call t%check(element//' reference scene: N = 16 within 4e-5 of the limit', &
                     LIMIT - mu(3) < 4.0e-5_wp)
    end subroutine reference_scene_converges

    !> Lowest positive mu (0 when none), backward error and warning of one solver.
    subroutine lowest(config, solver, lambda, mu, residual, warning, ok)
        type(config_t), intent(inout) :: config
        character(len=*), intent(in) :: solver
        real(wp), intent(in) :: lambda
        real(wp), intent(out) :: mu, residual
        character(len=:), allocatable, intent(out) :: warning
        logical, intent(out) :: ok
        type(problem_t) :: prob
        type(eigen_result_t) :: res
        type(timings_t) :: timings
        type(status_t) :: stat
        integer :: i
        config%eigen%solver = solver
        call problem_of(config, prob, stat)
        if (stat%ok()) call eigen_of(config, prob, lambda, res, timings, stat)
        ok = stat%ok()
        mu = 0.0_wp
        residual = 0.0_wp
        warning = ''
        if (.not. ok) return
        ! the certificate's own warning; accuracy warnings are tested elsewhere
        do i = 1, size(res%warnings)
            if (index(res%warnings(i), 'not certified') > 0) warning = trim(res%warnings(i))
        end do
        residual = res%spec%max_residual()
        i = res%spec%lowest_positive()
        if (i > 0) mu = real(res%spec%mu(i), wp)
    end subroutine lowest

    !> Every free dof exactly once, and the 2p contact dofs in the last 2p places.
    subroutine ordering_puts_contact_last(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(problem_t) :: prob
        type(status_t) :: stat
        integer, allocatable :: perm(:), seen(:)
        integer :: n, p
        call square_scene(12, 'q1', 'right', config)
        call problem_of(config, prob, stat)
        call nested_dissection_last(prob%mesh, prob%dofs, prob%contact%nodes, perm, stat)
        call t%check('node ordering succeeds', stat%ok())
        if (.not. stat%ok()) return
        n = prob%dofs%n_free
        p = prob%contact%p()
        allocate (seen(n), source=0)
        seen(perm) = seen(perm) + 1
        call t%check('node ordering is a permutation of the free dofs', &
                     size(perm) == n .and. all(seen == 1))
        seen = 0
        seen(perm(n - 2*p + 1:n)) = 1
        call t%check('contact dofs are the last 2p', &
                     all(seen(pack(prob%contact%dofs, .true.)) == 1))
    end subroutine ordering_puts_contact_last

    !> With the contact dofs last, L_c L_c' is the Schur complement, so L_c^-T L_c^-1 must
    !> equal K^-1 on the contact dofs as full solves give it. Both are backward-stable
    !> solves with K (condition ~1e3 on this mesh): agreement to 1e-10 relative.
    subroutine trailing_block_is_contact_compliance(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(problem_t) :: prob
        type(status_t) :: stat
        type(cholesky_t) :: chol
        type(timings_t) :: timings
        integer, allocatable :: perm(:), rows(:)
        real(wp), allocatable :: l_tail(:, :), rhs(:, :), x(:, :), inverse(:, :)
        integer :: m, j, n
        call square_scene(10, 'p1', 'left', config)
        call problem_of(config, prob, stat)
        call nested_dissection_last(prob%mesh, prob%dofs, prob%contact%nodes, perm, stat)
        call factor_stiffness(prob%k, prob%mesh, prob%dofs, prob%contact, chol, timings, stat)
        call t%check('factor with the contact dofs last', stat%ok())
        if (.not. stat%ok()) return
        m = 2*prob%contact%p()
        n = prob%dofs%n_free
        call chol%trailing_block(m, l_tail, rows, stat)
        call t%check('trailing block extracted', stat%ok())
        call t%check('trailing rows are the contact dofs', &
                     all(rows == perm(n - m + 1:n)))
        allocate (rhs(n, m), x(n, m), source=0.0_wp)
        do j = 1, m
            rhs(rows(j), j) = 1.0_wp
        end do
        call chol%solve(rhs, x, stat)
        inverse = matmul(transpose(lower_inverse(l_tail)), lower_inverse(l_tail))
        call t%check_close('L_c^-T L_c^-1 = K^-1 on the contact dofs', &
            maxval(abs(inverse - x(rows, :))), 0.0_wp, 0.0_wp, &
            1.0e-10_wp*maxval(abs(x(rows, :))))
        call t%check('trailing block is lower triangular', &
                     all([(maxval(abs(l_tail(1:j - 1, j))) <= 0.0_wp, j=2, m)]))
    end subroutine trailing_block_is_contact_compliance

    pure function lower_inverse(l) result(inv)
        real(wp), intent(in) :: l(:, :)
        real(wp) :: inv(size(l, 1), size(l, 1))
        integer :: i, j
        inv = 0.0_wp
        do j = 1, size(l, 1)
            inv(j, j) = 1.0_wp/l(j, j)
            do i = j + 1, size(l, 1)
                inv(i, j) = -dot_product(l(i, j:i - 1), inv(j:i - 1, j))/l(i, i)
            end do
        end do
    end function lower_inverse

    !> The disc argument of certify_lowest on hand-made sets.
    subroutine certificate_logic(t)
        type(test_suite_t), intent(inout) :: t
        integer :: outcome, low
        ! sigma = 0: the set of smallest |mu| holds 0.75 -> it is the lowest positive
        call certify_lowest([(-0.3_wp, 0.0_wp), (0.75_wp, 0.0_wp), (-2.0_wp, 2.0_wp)], &
                            [.true., .true., .false.], 0.0_wp, .false., outcome, low)
        call t%check('sigma = 0, positive in the set: found', &
                     outcome == CERTIFIED_FOUND .and. low == 2)
        ! no positive in an incomplete set: undecided, never 'none'
        call certify_lowest([(-0.3_wp, 0.0_wp), (-2.0_wp, 2.0_wp)], [.true., .false.], &
                            0.0_wp, .false., outcome, low)
        call t%check('no positive in a partial set: undecided', outcome == UNDECIDED)
        call certify_lowest([(-0.3_wp, 0.0_wp), (-2.0_wp, 2.0_wp)], [.true., .false.], &
                            0.0_wp, .true., outcome, low)
        call t%check('no positive in the whole spectrum: none', outcome == CERTIFIED_NONE)
        ! sigma = 10, set {9, 11}: radius 1 leaves ]0, 9[ unsearched
        call certify_lowest([(9.0_wp, 0.0_wp), (11.0_wp, 0.0_wp)], [.true., .true.], &
                            10.0_wp, .false., outcome, low)
        call t%check('target far from 0: disc does not reach 0, undecided', outcome == UNDECIDED)
        ! sigma = 1, set {0.5, 3}: radius 2 covers ]0, 0.5]
        call certify_lowest([(0.5_wp, 0.0_wp), (3.0_wp, 0.0_wp)], [.true., .true.], &
                            1.0_wp, .false., outcome, low)
        call t%check('disc covers ]0, mu+]: found', outcome == CERTIFIED_FOUND .and. low == 1)
        ! a complex value never counts as the positive one
        call certify_lowest([(0.5_wp, 0.1_wp)], [.false.], 0.0_wp, .false., outcome, low)
        call t%check('complex is not positive real', outcome == UNDECIDED .and. low == 0)
    end subroutine certificate_logic

    !> The sqrt(tol) rule: exact zero imaginary parts are real, splits below sqrt(tol) are
    !> rounding, clearly complex pairs stay complex.
    subroutine real_or_complex_ritz(t)
        type(test_suite_t), intent(inout) :: t
        real(wp) :: eps
        eps = epsilon(1.0_wp)
        call t%check('zero imaginary part is real', is_real_ritz((2.0_wp, 0.0_wp), eps))
        call t%check('split 1e-10 at tol = eps is real', is_real_ritz((2.0_wp, 2.0e-10_wp), eps))
        call t%check('split 1e-6 at tol = eps is complex', &
                     .not. is_real_ritz((2.0_wp, 2.0e-6_wp), eps))
        call t%check('split 1e-6 at tol = 1e-10 is complex', &
                     .not. is_real_ritz((2.0_wp, 2.0e-4_wp), 1.0e-10_wp))
    end subroutine real_or_complex_ritz

    subroutine info_sentences(t)
        type(test_suite_t), intent(inout) :: t
        integer :: code
        logical :: all_named
        all_named = .true.
        do code = -15, 3
            if (code == 2) cycle
            if (index(arpack_info_message('dnaupd', code), 'undocumented') > 0) &
                all_named = .false.
        end do
        call t%check('every documented ARPACK info has a sentence', all_named)
        call t%check('-9999 explained', index(arpack_info_message('dnaupd', -9999), &
                                               'Arnoldi') > 0)
        call t%check('dneupd -8 is about the Schur form', &
                     index(arpack_info_message('dneupd', -8), 'Schur') > 0)
        call t%check('METIS memory error explained', &
                     index(metis_status_message(-3), 'memory') > 0)
    end subroutine info_sentences

    !> ARPACK and dense agree on the lowest positive mu (or on its absence) on both
    !> diagonals and Q1, for lambda from 2.5 to 100 and negative lambda. Both solvers are
    !> backward stable (residuals ~1e-14) and these eigenvalues have condition numbers below
    !> 1e4 (dgeevx), so 1e-9 relative is a safe bound on their difference; a wrong eigenvalue
    !> (the next one is at least 10x away) or a missed one fails by orders of magnitude.
    subroutine agrees_with_dense_over_scenes(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: LAMBDAS(9) = [2.5_wp, 3.0_wp, 5.0_wp, 10.0_wp, 30.0_wp, &
                                             100.0_wp, -2.5_wp, -5.0_wp, -100.0_wp]
        character(len=*), parameter :: ELEMENTS(5) = ['p1', 'p1', 'q1', 'p3', 'p4']
        character(len=*), parameter :: DIAGONALS(5) = [character(len=5) :: 'right', 'left', &
                                                       'right', 'left', 'right']
        integer, parameter :: SIZES(3) = [4, 8, 20]   ! p = 5 is nearly the smallest ARPACK takes
        type(config_t) :: config
        real(wp) :: mu_dense, mu_arpack, r_dense, r_arpack
        character(len=:), allocatable :: warning
        character(len=96) :: what
        logical :: ok_dense, ok_arpack
        integer :: e, i, s
        do s = 1, size(SIZES)
            do e = 1, size(ELEMENTS)
                do i = 1, size(LAMBDAS)
                    call square_scene(SIZES(s), ELEMENTS(e), DIAGONALS(e), config)
                    call lowest(config, 'dense', LAMBDAS(i), mu_dense, r_dense, warning, ok_dense)
                    call lowest(config, 'arpack', LAMBDAS(i), mu_arpack, r_arpack, warning, &
                                ok_arpack)
                    write (what, '(a, i0, 1x, a, 1x, a, a, f7.1)') 'N = ', SIZES(s), &
                        ELEMENTS(e), trim(DIAGONALS(e)), ', lambda =', LAMBDAS(i)
                    call t%check(trim(what)//': both solvers succeed', ok_dense .and. ok_arpack)
                    call t%check(trim(what)//': certified (no warning)', len(warning) == 0)
                    call t%check(trim(what)//': same existence', &
                                 (mu_dense > 0.0_wp) .eqv. (mu_arpack > 0.0_wp))
                    call t%check_close(trim(what)//': lowest positive mu', mu_arpack, mu_dense, &
                                       1.0e-9_wp)
                    call t%check(trim(what)//': ARPACK backward errors <= 1e-12', &
                                 r_arpack <= 1.0e-12_wp)
                end do
            end do
        end do
    end subroutine agrees_with_dense_over_scenes

    !> Near the critical lambda the positive mu comes in from +infinity, deep among the
    !> eigenvalues of large modulus: the hardest case for a Krylov search. Bracket the
    !> threshold with the dense solver by bisection (existence is monotone near it) to
    !> 5/2^14 = 3e-4, where mu is about 1e4 to 1e5, then ARPACK must agree just above it and
    !> find nothing just below it. theta = 1/mu is then tiny beside ||A|| ~ 1, so both solvers
    !> get mu to about eps ||A|| mu ~ 1e-11 relative (measured: 2e-5 at mu = 2e9, i.e. with
    !> a constant of 50); 1e-7 leaves a factor 100 over that.
    subroutine agrees_near_the_threshold(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: ELEMENTS(3) = ['p1', 'p1', 'q1']
        character(len=*), parameter :: DIAGONALS(3) = [character(len=5) :: 'right', 'left', &
                                                                            'right']
        real(wp), parameter :: SIDES(2) = [1.0_wp, -1.0_wp]
        type(config_t) :: config
        real(wp) :: below, above, middle, mu_dense, mu_arpack, r
        character(len=:), allocatable :: warning
        character(len=96) :: what
        logical :: ok
        integer :: e, i, side
        do e = 1, size(ELEMENTS)
            do side = 1, size(SIDES)
                call square_scene(16, ELEMENTS(e), DIAGONALS(e), config)
                below = 0.0_wp
                above = 5.0_wp
                do i = 1, 14
                    middle = 0.5_wp*(below + above)
                    call lowest(config, 'dense', SIDES(side)*middle, mu_dense, r, warning, ok)
                    if (mu_dense > 0.0_wp) then
                        above = middle
                    else
                        below = middle
                    end if
                end do
                write (what, '(a, 1x, a, a, es12.5)') ELEMENTS(e), trim(DIAGONALS(e)), &
                    ', near threshold lambda =', SIDES(side)*above
                call lowest(config, 'dense', SIDES(side)*above, mu_dense, r, warning, ok)
                call lowest(config, 'arpack', SIDES(side)*above, mu_arpack, r, warning, ok)
                call t%check(trim(what)//': above, mu is large (> 1e3)', mu_dense > 1.0e3_wp)
                call t%check(trim(what)//': above, certified', ok .and. len(warning) == 0)
                call t%check_close(trim(what)//': above, same mu', mu_arpack, mu_dense, 1.0e-7_wp)
                call lowest(config, 'arpack', SIDES(side)*below, mu_arpack, r, warning, ok)
                call t%check(trim(what)//': below, none and certified', &
                             ok .and. mu_arpack <= 0.0_wp .and. len(warning) == 0)
            end do
        end do
    end subroutine agrees_near_the_threshold

    !> With a target the shift-inverted operator (I - sigma A)^-1 A is used; a target
    !> between 0 and twice the lowest mu has a disc reaching 0, so the answer is certified and
    !> equal to the unshifted one (same 1e-9 argument as above).
    subroutine target_finds_the_same_lowest(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        real(wp) :: mu_plain, mu_shifted, r
        character(len=:), allocatable :: warning
        logical :: ok
        call square_scene(16, 'p1', 'right', config)
        call lowest(config, 'arpack', 5.0_wp, mu_plain, r, warning, ok)
        config%eigen%target = 0.5_wp
        call lowest(config, 'arpack', 5.0_wp, mu_shifted, r, warning, ok)
        call t%check('target 0.5: succeeds and certified', ok .and. len(warning) == 0)
        call t%check_close('target 0.5: same lowest positive mu', mu_shifted, mu_plain, 1.0e-9_wp)
        call t%check('target 0.5: residuals <= 1e-12', r <= 1.0e-12_wp)
    end subroutine target_finds_the_same_lowest

    !> ARPACK needs nev + 2 <= ncv <= p: with p = 2 the message must say what to do.
    subroutine too_few_contact_nodes(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(problem_t) :: prob
        type(eigen_result_t) :: res
        type(timings_t) :: timings
        type(status_t) :: stat
        call square_scene(1, 'p1', 'right', config)
        config%eigen%solver = 'arpack'
        call problem_of(config, prob, stat)
        call eigen_of(config, prob, 5.0_wp, res, timings, stat)
        call t%check('p = 2 with arpack fails', .not. stat%ok())
        if (stat%ok()) return
        call t%check('p = 2: the message points to the dense solver', &
                     index(stat%message, 'dense') > 0)
    end subroutine too_few_contact_nodes

    !> The certified search's first run is on the transposed reduced operator (same
    !> eigenvalues, so it counts as one of the two agreeing runs), and its vector of the
    !> lowest positive mu is then that mu's left eigenvector, which the round-off bound needs.
    !> So the left vector y the ARPACK solver returns must satisfy K y = mu B' y: its
    !> residual, relative to (||K|| + |mu| ||B||) ||y|| (infinity norms), is at the level of
    !> ARPACK's tolerance (eps) times the condition of the reduced problem's left vector
    !> mapped through K^-1 (measured 7e-17 to 1e-16 here); 1e-12 leaves room. A right
    !> vector in its place (B is not symmetric: X' M N with X = lambda T - N) leaves 1.6e-2
    !> to 2.7e-2, another eigenvalue's left vector 2.1e-2 to 4.5e-2 (both measured by
    !> breaking the search that way). mu agrees with
    !> the dense solver's (as in agrees_with_dense_over_scenes), on P1 and Q1, both signs of
    !> lambda.
    subroutine left_vector_from_the_certificate(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: ELEMENTS(2) = ['p1', 'q1']
        real(wp), parameter :: LAMBDAS(2) = [5.0_wp, -10.0_wp]
        type(config_t) :: config
        type(problem_t) :: prob
        type(eigen_result_t) :: res
        type(timings_t) :: timings
        type(status_t) :: stat
        real(wp), allocatable :: ky(:), bty(:)
        real(wp) :: mu, mu_dense, r_dense, residual
        character(len=:), allocatable :: warning
        character(len=64) :: what
        logical :: ok_dense
        integer :: e, i, k
        do e = 1, size(ELEMENTS)
            do i = 1, size(LAMBDAS)
                write (what, '(a, f6.1)') ELEMENTS(e)//' 12 x 12, lambda =', LAMBDAS(i)
                call square_scene(12, ELEMENTS(e), 'right', config)
                call lowest(config, 'dense', LAMBDAS(i), mu_dense, r_dense, warning, ok_dense)
                config%eigen%solver = 'arpack'
                call problem_of(config, prob, stat)
                if (stat%ok()) call eigen_of(config, prob, LAMBDAS(i), res, timings, stat)
                call t%check(trim(what)//': left vector: solves succeed', &
                             stat%ok() .and. ok_dense)
                if (.not. stat%ok()) cycle
                k = res%spec%lowest_positive()
                call t%check(trim(what)//': left vector: lowest positive mu first', k == 1)
                call t%check(trim(what)//': left vector returned', allocated(res%spec%left))
                if (k /= 1 .or. .not. allocated(res%spec%left)) cycle
                mu = real(res%spec%mu(1), wp)
                call t%check_close(trim(what)//': left vector: mu as the dense solver', mu, &
                                   mu_dense, 1.0e-9_wp)
                allocate (ky(size(res%spec%left)))
                call prob%k%matvec(res%spec%left, ky)
                bty = transposed_product(res%b, res%spec%left)
                residual = maxval(abs(ky - mu*bty))/((prob%k%norm_inf() + &
                    abs(mu)*res%b%norm_inf())*maxval(abs(res%spec%left)))
                write (*, '(a, es10.2)') '      '//trim(what)//': left residual', residual
                call t%check(trim(what)//': K y = mu B'' y to 1e-12', residual <= 1.0e-12_wp)
                call t%check(trim(what)//': round-off bound computed', &
                             res%spec%roundoff(1) >= 0.0_wp)
                deallocate (ky)
            end do
        end do
    end subroutine left_vector_from_the_certificate

    !> B' y for a CSR matrix B.
    function transposed_product(b, y) result(bty)
        type(csr_matrix_t), intent(in) :: b
        real(wp), intent(in) :: y(:)
        real(wp), allocatable :: bty(:)
        integer :: i, j
        allocate (bty(size(y)), source=0.0_wp)
        do i = 1, b%n()
            do j = b%row_start(i), b%row_start(i + 1) - 1
                bty(b%col(j)) = bty(b%col(j)) + b%val(j)*y(i)
            end do
        end do
    end function transposed_product
end program test_arpack_eigen
