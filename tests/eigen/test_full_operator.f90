! SPDX-License-Identifier: MIT
!> ARPACK on the full operator (K - sigma B)^-1 B (&eigen operator = 'full') against ARPACK
!> on the reduced p x p operator and against the dense solver's complete spectrum: the same
!> lowest positive mu, the same certified list up to cn_max, over elements, both signs of
!> lambda, near the thresholds and for targets from 0 to the edge of the accepted range;
!> and the shifted UMFPACK factorization it rests on.
!>
!> Why 1e-10 between the operators: both are backward stable (backward errors ~1e-16 on
!> (K, B), checked below), the lowest positive eigenvalues here have condition numbers
!> below 1e4 (test_dense_eigen, dgeevx), so each is within ~1e-12 of the exact discrete mu;
!> a shift adds a small multiple of eps |sigma| ||A|| to each (arpack_eigen, TARGET_RANGE;
!> ||A|| = 15.6 on P1 16 x 16 at lambda = 5, whose |mu| reach 1027): under 1e-11 up to
!> |sigma| = 2e3, twice the largest |mu|. Further out the test allows 10 eps |sigma| ||A||
!> (3.5e-10 at 1e4; measured 2.9e-11 in Release, 1.4e-10 in Debug, where the rounding of
!> the LU differs). Measured without shift: 1e-15 to 2e-14. A wrong or missed eigenvalue
!> differs by more than 1e-3 relative (the neighbours are at least 10x away).
program test_full_operator
    use kinds, only: wp
    use fixtures, only: problem_of, eigen_of
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_SINGULAR
    use testing, only: test_suite_t
    use fixtures, only: square_scene
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use timer, only: timings_t
    use eigen_solve, only: eigen_result_t
    use reported_units, only: critical_cn
    use method_options, only: operator_name, SOLVER_ARPACK, SOLVER_DENSE, OPERATOR_FULL
    use input_validation, only: validate_config
    use csr_matrix, only: csr_matrix_t
    use sparse_lu, only: lu_t
    use arpack_eigen, only: certify_lowest, wanted_values, CERTIFIED_FOUND, UNDECIDED
    implicit none

    !> The agreement bound between the two operators (see the header).
    real(wp), parameter :: AGREE = 1.0e-10_wp
    !> Largest backward error accepted for an eigenpair of the full operator without a far
    !> shift: ARPACK converges to tol = eps on OP, and one sparse LU solve is backward
    !> stable, so ~1e-15 is expected (measured 1e-16 to 6e-16); 1e-12 flags a lost digit
    !> budget, not round-off. A shift sigma solves with K - sigma B, whose rounding is
    !> eps (||K|| + |sigma| ||B||): relative to the pair's own scale that is up to
    !> eps |sigma| ||A|| (3.5e-12 at 1e4; the Prescott kernel on one thread exceeded 1e-12
    !> there), so far shifts are allowed the agreement bound below, 10 eps |sigma| ||A||.
    real(wp), parameter :: BACKWARD_MAX = 1.0e-12_wp

    type(test_suite_t) :: t
    t%name = 'test_full_operator'
    call shifted_lu_solves_the_shifted_system(t)
    call shifted_lu_refuses_a_wider_pattern(t)
    call disc_must_reach_cn_max(t)
    call wanted_values_are_the_lowest_and_those_up_to_cn_max(t)
    call full_needs_an_arpack_solver(t)
    call full_agrees_with_reduced_over_elements(t)
    call full_agrees_near_the_thresholds(t)
    call full_agrees_for_targets_near_and_far(t)
    call full_refuses_targets_beyond_the_range(t)
    call cn_max_lists_match_the_dense_list(t)
    call t%report()

contains

    !> (A - sigma B) x = b with A the 1D Laplacian (tridiagonal) and B a non-symmetric
    !> matrix inside its pattern: the residual of the computed x is round-off (LU with
    !> partial pivoting on a well-conditioned 5 x 5 matrix: ~1e-15; 1e-12 leaves room).
    subroutine shifted_lu_solves_the_shifted_system(t)
        type(test_suite_t), intent(inout) :: t
        type(csr_matrix_t) :: a, b
        type(lu_t) :: lu
        type(status_t) :: stat
        real(wp) :: x(5), rhs(5), ax(5), bx(5)
        real(wp), parameter :: SIGMA = 0.7_wp
        call tridiagonal(5, [-1.0_wp, 2.0_wp, -1.0_wp], a)
        call tridiagonal(5, [0.0_wp, 1.0_wp, 3.0_wp], b)
        rhs = [1.0_wp, -2.0_wp, 0.5_wp, 4.0_wp, 1.0_wp]
        call lu%factor_shifted(a, b, SIGMA, stat)
        if (stat%ok()) call lu%solve(rhs, x, stat)
        call t%check('shifted LU: factor and solve succeed', stat%ok())
        call a%matvec(x, ax)
        call b%matvec(x, bx)
        call t%check('shifted LU: (A - sigma B) x = b to round-off', &
                     maxval(abs(ax - SIGMA*bx - rhs)) <= 1.0e-12_wp*maxval(abs(rhs)))
        ! A - 1 A is the zero matrix: UMFPACK's zero pivot must come back as singular
        call lu%factor_shifted(a, a, 1.0_wp, stat)
        call t%check('shifted LU: A - 1 A (zero) is singular', stat%code == STATUS_SINGULAR)
    end subroutine shifted_lu_solves_the_shifted_system

    !> An entry of B outside A's pattern is an error, never silently dropped.
    subroutine shifted_lu_refuses_a_wider_pattern(t)
        type(test_suite_t), intent(inout) :: t
        type(csr_matrix_t) :: a, b
        type(lu_t) :: lu
        type(status_t) :: stat
        call tridiagonal(4, [0.0_wp, 1.0_wp, 0.0_wp], a)
        call tridiagonal(4, [-1.0_wp, 2.0_wp, -1.0_wp], b)
        a%row_start = [1, 2, 3, 4, 5]   ! diagonal only
        a%col = [1, 2, 3, 4]
        a%val = [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp]
        call lu%factor_shifted(a, b, 0.5_wp, stat)
        call t%check('shifted LU: B wider than A is refused', &
                     stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'pattern') > 0)
    end subroutine shifted_lu_refuses_a_wider_pattern

    !> The disc |mu - sigma| <= r must cover (0, cn_max] for a partial set to be complete.
    subroutine disc_must_reach_cn_max(t)
        type(test_suite_t), intent(inout) :: t
        integer :: outcome, low
        ! sigma = 0, set {0.5, -2}: radius 2 covers (0, 2] but not (0, 3]
        call certify_lowest([(0.5_wp, 0.0_wp), (-2.0_wp, 0.0_wp)], [.true., .true.], 0.0_wp, &
                            .false., outcome, low, 1.5_wp)
        call t%check('cn_max inside the disc: found', outcome == CERTIFIED_FOUND .and. low == 1)
        call certify_lowest([(0.5_wp, 0.0_wp), (-2.0_wp, 0.0_wp)], [.true., .true.], 0.0_wp, &
                            .false., outcome, low, 3.0_wp)
        call t%check('cn_max beyond the disc: undecided', outcome == UNDECIDED)
    end subroutine disc_must_reach_cn_max

    subroutine wanted_values_are_the_lowest_and_those_up_to_cn_max(t)
        type(test_suite_t), intent(inout) :: t
        complex(wp), parameter :: MU(5) = [(7.0_wp, 0.0_wp), (0.5_wp, 0.0_wp), &
            (2.0_wp, 0.0_wp), (-1.0_wp, 0.0_wp), (1.0_wp, 1.0_wp)]
        logical, parameter :: IS_REAL(5) = [.true., .true., .true., .true., .false.]
        real(wp), allocatable :: values(:)
        allocate (values(0))   ! defined bounds before reallocation (gfortran warns otherwise)
        values = wanted_values(MU, IS_REAL, 0.0_wp)
        call t%check('wanted: cn_max = 0 gives the lowest alone', size(values) == 1)
        if (size(values) == 1) call t%check('wanted: the lowest is 0.5', &
                                               abs(values(1) - 0.5_wp) <= 0.0_wp)
        values = wanted_values(MU, IS_REAL, 3.0_wp)
        call t%check('wanted: up to 3, ascending, no negative or complex', &
                     size(values) == 2)
        if (size(values) == 2) call t%check('wanted: 0.5 then 2', &
                                            all(abs(values - [0.5_wp, 2.0_wp]) <= 0.0_wp))
    end subroutine wanted_values_are_the_lowest_and_those_up_to_cn_max

    !> 'full' is an ARPACK operator: with solver = 'dense' it is bad input; 'auto' then
    !> means ARPACK, and summary.json names the operator that ran.
    subroutine full_needs_an_arpack_solver(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(status_t) :: dense_full, auto_full, unknown, negative
        config%eigen%operator = 'full'
        config%eigen%solver = 'dense'
        call validate_config(config, 'in.nml', dense_full)
        call t%check('full with dense: refused naming &eigen operator', &
                     .not. dense_full%ok() .and. index(dense_full%message, 'operator') > 0)
        config%eigen%solver = 'auto'
        call validate_config(config, 'in.nml', auto_full)
        call t%check('full with auto: accepted', auto_full%ok())
        config%eigen%operator = 'fill'
        call validate_config(config, 'in.nml', unknown)
        call t%check('unknown operator: refused', .not. unknown%ok())
        config%eigen%operator = 'reduced'
        config%eigen%cn_max = -1.0_wp
        call validate_config(config, 'in.nml', negative)
        call t%check('negative cn_max: refused', .not. negative%ok() .and. &
                     index(negative%message, 'cn_max') > 0)
        call t%check('operator name: arpack + full is full', &
                     operator_name(SOLVER_ARPACK, OPERATOR_FULL) == 'full')
        call t%check('operator name: dense is always reduced', &
                     operator_name(SOLVER_DENSE, OPERATOR_FULL) == 'reduced')
    end subroutine full_needs_an_arpack_solver

    !> P1 (both diagonals), Q1, P2, Q2, P3 on 8 x 8, lambda of both signs: the full and the
    !> reduced operator give the same lowest positive mu, both certified, with backward
    !> errors of every pair of the full operator at round-off.
    subroutine full_agrees_with_reduced_over_elements(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: ELEMENTS(6) = ['p1', 'p1', 'q1', 'p2', 'q2', 'p3']
        character(len=*), parameter :: DIAGONALS(6) = [character(len=5) :: 'right', 'left', &
                                                       'right', 'right', 'right', 'left']
        real(wp), parameter :: LAMBDAS(4) = [5.0_wp, 30.0_wp, -5.0_wp, -30.0_wp]
        type(config_t) :: config
        type(eigen_result_t) :: full, reduced
        character(len=64) :: what
        logical :: ok, ok_full
        integer :: e, i
        do e = 1, size(ELEMENTS)
            do i = 1, size(LAMBDAS)
                write (what, '(a, 1x, a, a, f6.1)') ELEMENTS(e), trim(DIAGONALS(e)), &
                    ', lambda =', LAMBDAS(i)
                call scene(8, ELEMENTS(e), DIAGONALS(e), config)
                call solve(config, 'full', LAMBDAS(i), full, ok_full)
                call solve(config, 'reduced', LAMBDAS(i), reduced, ok)
                call compare(t, trim(what), full, reduced, ok .and. ok_full, .true.)
            end do
        end do
    end subroutine full_agrees_with_reduced_over_elements

    !> Just beyond a threshold lambda_c the positive mu is large (it comes in from infinity):
    !> bisect lambda_c with the dense solver to 5/2^10 (mu ~ 1e2 to 1e3), then both operators
    !> must agree there; just short of it the full one finds no positive mu. So close, mu is
    !> among the largest |mu| and only the dense decision can certify it (for both operators
    !> alike); at 1.2 lambda_c (mu ~ 10) ARPACK on the full operator must certify it itself.
    subroutine full_agrees_near_the_thresholds(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: ELEMENTS(2) = ['p1', 'q2']
        real(wp), parameter :: SIDES(2) = [1.0_wp, -1.0_wp]
        type(config_t) :: config
        type(eigen_result_t) :: full, reduced, dense
        real(wp) :: below, above, middle
        character(len=64) :: what
        logical :: ok, ok_full
        integer :: e, side, i
        do e = 1, size(ELEMENTS)
            do side = 1, size(SIDES)
                call scene(16, ELEMENTS(e), 'right', config)
                below = 0.0_wp
                above = 5.0_wp
                do i = 1, 10
                    middle = 0.5_wp*(below + above)
                    config%eigen%solver = 'dense'
                    call solve(config, 'reduced', SIDES(side)*middle, dense, ok)
                    if (dense%spec%lowest_positive() > 0) then
                        above = middle
                    else
                        below = middle
                    end if
                end do
                config%eigen%solver = 'arpack'
                write (what, '(a, a, es11.4)') ELEMENTS(e), ', near lambda_c =', &
                    SIDES(side)*above
                call solve(config, 'full', SIDES(side)*above, full, ok_full)
                call solve(config, 'reduced', SIDES(side)*above, reduced, ok)
                call compare(t, trim(what)//' above', full, reduced, ok .and. ok_full, .false.)
                call solve(config, 'full', 1.2_wp*SIDES(side)*above, full, ok_full)
                call solve(config, 'reduced', 1.2_wp*SIDES(side)*above, reduced, ok)
                call compare(t, trim(what)//' x 1.2', full, reduced, ok .and. ok_full, .true.)
                call solve(config, 'full', SIDES(side)*below, full, ok_full)
                call t%check(trim(what)//' below: full finds no positive mu', ok_full .and. &
                             full%spec%lowest_positive() == 0)
            end do
        end do
    end subroutine full_agrees_near_the_thresholds

    !> Targets inside the spectrum, next to the lowest positive mu (0.749), and beyond every
    !> eigenvalue (|mu| <= 1027 here; 1e4 with ||A|| = 15.6 is still within |target| ||A||
    !> <= 1e6): the same lowest positive mu as the reduced operator, certified by ARPACK
    !> (-2e3, -1e4: a disc around them reaching past 0.749 holds the whole spectrum, so
    !> the dense decision certifies, alike for both operators).
    subroutine full_agrees_for_targets_near_and_far(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: TARGETS(9) = [0.0_wp, 0.5_wp, 0.76_wp, 3.0_wp, -3.0_wp, &
                                             1.0e3_wp, -2.0e3_wp, 1.0e4_wp, -1.0e4_wp]
        real(wp), parameter :: A_NORM = 15.6_wp   !! ||A||_inf of this scene (the range message)
        real(wp) :: tolerance
        type(config_t) :: config
        type(eigen_result_t) :: full, reduced
        character(len=64) :: what
        logical :: ok, ok_full
        integer :: i
        do i = 1, size(TARGETS)
            write (what, '(a, es10.2)') 'p1 16 x 16, lambda = 5, target =', TARGETS(i)
            call scene(16, 'p1', 'right', config)
            config%eigen%target = TARGETS(i)
            call solve(config, 'full', 5.0_wp, full, ok_full)
            call solve(config, 'reduced', 5.0_wp, reduced, ok)
            tolerance = max(AGREE, 10.0_wp*epsilon(1.0_wp)*abs(TARGETS(i))*A_NORM)
            call compare(t, trim(what), full, reduced, ok .and. ok_full, &
                         TARGETS(i) >= -3.0_wp, tolerance)
        end do
    end subroutine full_agrees_for_targets_near_and_far

    !> Past |target| ||A|| = 1e6 both operators refuse the target as bad input naming it.
    subroutine full_refuses_targets_beyond_the_range(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(eigen_result_t) :: res
        type(problem_t) :: prob
        type(timings_t) :: timings
        type(status_t) :: stat
        call scene(8, 'p1', 'right', config)
        config%eigen%target = 1.0e9_wp
        config%eigen%solver = 'arpack'
        config%eigen%operator = 'full'
        call problem_of(config, prob, stat)
        if (stat%ok()) call eigen_of(config, prob, 5.0_wp, res, timings, stat)
        call t%check('target 1e9: full refuses it as bad input naming target', &
                     stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'target') > 0)
    end subroutine full_refuses_targets_beyond_the_range

    !> lambda = 20 and 100 on P1 16 x 16 have four positive eigenvalues each (0.13 to 47 and
    !> 0.02 to 4.7): with cn_max between two of them and beyond the largest, both operators
    !> list exactly the dense solver's positive eigenvalues up to cn_max.
    subroutine cn_max_lists_match_the_dense_list(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: LAMBDAS(2) = [20.0_wp, 100.0_wp]
        real(wp), parameter :: CN_MAX(3) = [1.0_wp, 10.0_wp, 100.0_wp]
        character(len=*), parameter :: OPERATORS(2) = [character(len=7) :: 'full', 'reduced']
        type(config_t) :: config
        type(eigen_result_t) :: dense, sparse
        real(wp), allocatable :: expected(:), listed(:)
        character(len=80) :: what
        logical :: ok, ok_dense
        integer :: i, c, o
        do i = 1, size(LAMBDAS)
            do c = 1, size(CN_MAX)
                call scene(16, 'p1', 'right', config)
                config%eigen%cn_max = CN_MAX(c)
                config%eigen%solver = 'dense'
                call solve(config, 'reduced', LAMBDAS(i), dense, ok_dense)
                expected = critical_cn(dense%spec, CN_MAX(c))
                do o = 1, size(OPERATORS)
                    write (what, '(a, a, f6.1, a, f6.1)') trim(OPERATORS(o)), ', lambda =', &
                        LAMBDAS(i), ', cn_max =', CN_MAX(c)
                    config%eigen%solver = 'arpack'
                    call solve(config, OPERATORS(o), LAMBDAS(i), sparse, ok)
                    listed = critical_cn(sparse%spec, CN_MAX(c))
                    call t%check(trim(what)//': solves succeed, none uncertified', ok .and. &
                                 ok_dense .and. .not. uncertified(sparse))
                    call t%check(trim(what)//': as many as the dense list ('// &
                                 trim(count_text(size(expected)))//')', &
                                 size(listed) == size(expected) .and. size(expected) > 0)
                    if (size(listed) == size(expected)) call t%check(trim(what)// &
                        ': each within 1e-10 of the dense one', &
                        all(abs(listed - expected) <= AGREE*abs(expected)))
                end do
            end do
        end do
    end subroutine cn_max_lists_match_the_dense_list

    function count_text(n) result(text)
        integer, intent(in) :: n
        character(len=12) :: text
        write (text, '(i0)') n
    end function count_text

    !> Same certified lowest positive mu (or none) from both operators, within AGREE, and
    !> the full operator's backward errors at round-off. `by_arpack`: the full operator's
    !> ARPACK runs must certify it themselves; else (a positive mu among the largest, where
    !> no partial set can) both operators must fall back alike.
    subroutine compare(t, what, full, reduced, ok, by_arpack, tolerance)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: what
        type(eigen_result_t), intent(in) :: full, reduced
        logical, intent(in) :: ok, by_arpack
        real(wp), intent(in), optional :: tolerance   !! relative; default AGREE
        real(wp) :: bound, backward
        integer :: lf, lr
        bound = AGREE
        backward = BACKWARD_MAX
        if (present(tolerance)) then
            bound = tolerance
            ! a far shift's rounding (above): its bound exceeds AGREE from |sigma| ~ 3e3
            if (tolerance > AGREE) backward = tolerance
        end if
        call t%check(what//': both operators succeed', ok)
        if (.not. ok) return
        call t%check(what//': both by ARPACK', full%solver == SOLVER_ARPACK .and. &
                     reduced%solver == SOLVER_ARPACK)
        call t%check(what//': both certified', .not. (uncertified(full) .or. &
                                                      uncertified(reduced)))
        lf = full%spec%lowest_positive()
        lr = reduced%spec%lowest_positive()
        call t%check(what//': same existence of a positive mu', (lf > 0) .eqv. (lr > 0))
        if (lf > 0 .and. lr > 0) call t%check_close(what//': lowest positive mu', &
            real(full%spec%mu(lf), wp), real(reduced%spec%mu(lr), wp), bound)
        call t%check(what//': full backward errors at round-off (1e-12, or the shift''s bound)', &
                     full%spec%max_residual() <= backward)
        if (by_arpack) then
            call t%check(what//': certified by ARPACK on the full operator, not densely', &
                         .not. full%spec%dense_decision)
        else
            call t%check(what//': both operators decide the same way', &
                         full%spec%dense_decision .eqv. reduced%spec%dense_decision)
        end if
    end subroutine compare

    logical function uncertified(res)
        type(eigen_result_t), intent(in) :: res
        integer :: i
        uncertified = .false.
        if (.not. allocated(res%warnings)) return
        do i = 1, size(res%warnings)
            if (index(res%warnings(i), 'not certified') > 0) uncertified = .true.
        end do
    end function uncertified

    !> The reference scene with ARPACK (test_arpack_eigen compares it with the dense solver).
    subroutine scene(n, element, diagonal, config)
        integer, intent(in) :: n
        character(len=*), intent(in) :: element, diagonal
        type(config_t), intent(out) :: config
        call square_scene(n, element, diagonal, config)
        config%eigen%solver = 'arpack'
    end subroutine scene

    !> The eigen solve of `config` with &eigen operator = `operator` at `lambda`.
    subroutine solve(config, operator, lambda, res, ok)
        type(config_t), intent(inout) :: config
        character(len=*), intent(in) :: operator
        real(wp), intent(in) :: lambda
        type(eigen_result_t), intent(out) :: res
        logical, intent(out) :: ok
        type(problem_t) :: prob
        type(timings_t) :: timings
        type(status_t) :: stat
        config%eigen%operator = operator
        call problem_of(config, prob, stat)
        if (stat%ok()) call eigen_of(config, prob, lambda, res, timings, stat)
        ok = stat%ok()
    end subroutine solve

    !> n x n tridiagonal CSR matrix with constant stencil (below, diagonal, above).
    subroutine tridiagonal(n, stencil, a)
        integer, intent(in) :: n
        real(wp), intent(in) :: stencil(3)
        type(csr_matrix_t), intent(out) :: a
        integer :: i, j, k
        allocate (a%row_start(n + 1), a%col(3*n - 2), a%val(3*n - 2))
        k = 0
        a%row_start(1) = 1
        do i = 1, n
            do j = max(1, i - 1), min(n, i + 1)
                k = k + 1
                a%col(k) = j
                a%val(k) = stencil(j - i + 2)
            end do
            a%row_start(i + 1) = k + 1
        end do
    end subroutine tridiagonal
end program test_full_operator
