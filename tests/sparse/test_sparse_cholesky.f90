! SPDX-License-Identifier: MIT
!> sparse_cholesky on the 5-point Laplacian of an m x m grid, whose spectrum is known:
!> with Dirichlet boundaries its eigenvalues are 4 - 2 cos(i pi/(m+1)) - 2 cos(j pi/(m+1)).
program test_sparse_cholesky
    use, intrinsic :: iso_fortran_env, only: output_unit
    use kinds, only: wp, i8, PI
    use status, only: status_t, STATUS_SINGULAR, STATUS_BAD_INPUT
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t, cholmod_status_message, ORDERING_DEFAULT, &
                               ORDERING_AMD, ORDERING_METIS, ORDERING_NATURAL, ORDERING_GIVEN
    use testing, only: test_suite_t
    use fixtures, only: to_dense => csr_to_dense, five_point_matrix
    implicit none

    interface
        subroutine dposv(uplo, n, nrhs, a, lda, b, ldb, info)
            import :: wp
            character, intent(in) :: uplo
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(inout) :: a(lda, *), b(ldb, *)
            integer, intent(out) :: info
        end subroutine dposv
    end interface

    integer, parameter :: M = 30, N = M*M, NRHS = 4
    real(wp), parameter :: EPS = epsilon(1.0_wp)
    ! Normwise backward error of a Cholesky solve: |dA| <= gamma_(k+1) |L||L'| with k the
    ! largest column count of L (below 2m + 1 = 61 here for every ordering but the natural
    ! one, whose band is m + 1), and |L||L'| is of the size of A for this diagonally dominant
    ! matrix: about 60 eps. We allow 1e3 eps, so an ordering or transpose bug (an O(1)
    ! residual) fails while rounding never does.
    real(wp), parameter :: BACKWARD_TOL = 1.0e3_wp*EPS
    integer, parameter :: ORDERINGS(5) = [ORDERING_DEFAULT, ORDERING_AMD, ORDERING_METIS, &
                                          ORDERING_NATURAL, ORDERING_GIVEN]
    character(len=*), parameter :: NAMES(5) = [character(len=7) :: 'default', 'AMD', 'METIS', &
                                               'natural', 'given']

    call run()

contains

    !> All checks, in a procedure so that its allocatables are freed on return and a
    !> sanitizer build reports only real leaks.
    subroutine run()
        type(test_suite_t) :: t
        type(csr_matrix_t) :: a, shifted, neumann, tiny_pivot
        type(cholesky_t) :: chol
        type(status_t) :: stat
        real(wp), allocatable :: b(:, :), x(:, :), x_default(:, :), x_lapack(:, :), dense(:, :)
        real(wp), allocatable :: b1(:, :), b2(:, :), w1(:, :), w2(:, :), x2(:, :), gram(:, :), &
                                 x_back(:, :)
        integer, allocatable :: reversed(:)
        real(wp) :: lambda_min, lambda_max, cond, forward_tol
        integer :: i, k, info
        integer(i8) :: band_nnz

        t%name = 'test_sparse_cholesky'
        call laplacian(M, .true., a)
        lambda_min = 4.0_wp - 4.0_wp*cos(PI/(M + 1))
        lambda_max = 4.0_wp + 4.0_wp*cos(PI/(M + 1))
        cond = lambda_max/lambda_min
        ! Each of two backward stable solvers has forward error <= cond * backward error.
        forward_tol = 2.0_wp*cond*BACKWARD_TOL

        allocate (b(N, NRHS), x(N, NRHS))
        do k = 1, NRHS
            do i = 1, N
                b(i, k) = sin(0.37_wp*i*k) + 0.5_wp*cos(0.11_wp*i) + real(k, wp)
            end do
        end do

        ! --- default ordering against the residual and LAPACK on the dense copy ---
        call chol%factor(a, stat)
        call t%check('factor the Dirichlet Laplacian', stat%ok())
        call t%check('is_factored after factor', chol%is_factored())
        call chol%solve(b, x, stat)
        call t%check('solve with 4 right-hand sides', stat%ok())
        call t%check('backward error of the solve <= 1e3 eps', &
                     backward_error(a, x, b) <= BACKWARD_TOL)
        x_default = x

        dense = to_dense(a)
        x_lapack = b
        call dposv('U', N, NRHS, dense, N, x_lapack, N, info)
        call t%check('dposv succeeds', info == 0)
        call t%check('CHOLMOD and dposv agree within 2 cond * 1e3 eps', &
                     maxval(abs(x - x_lapack)) <= forward_tol*maxval(abs(x_lapack)))
        call t%check('nnz(L) and flops are reported', &
                     chol%factor_nnz() >= N .and. chol%flops() > 0)
        call t%check('rcond estimate lies in (1/cond, 1]', chol%rcond() >= 1.0_wp/cond .and. &
                     chol%rcond() <= 1.0_wp)

        ! --- every ordering gives the same solution ---
        reversed = [(N + 1 - i, i = 1, N)]
        do k = 1, size(ORDERINGS)
            call chol%factor(a, stat, ordering=ORDERINGS(k), permutation=reversed)
            call t%check('factor with ordering '//trim(NAMES(k)), stat%ok())
            if (.not. stat%ok()) cycle
            if (ORDERINGS(k) /= ORDERING_DEFAULT) &
                call t%check('ordering used is '//trim(NAMES(k)), &
                             chol%ordering_used() == ORDERINGS(k))
            call chol%solve(b, x, stat)
            call t%check('solve with ordering '//trim(NAMES(k)), stat%ok())
            call t%check('ordering '//trim(NAMES(k))//' agrees with the default', &
                         maxval(abs(x - x_default)) <= forward_tol*maxval(abs(x_default)))
            if (ORDERINGS(k) == ORDERING_NATURAL .or. ORDERINGS(k) == ORDERING_GIVEN) then
                ! In natural order (and reversed, which maps the grid onto itself) L fills the
                ! envelope of A: row p of L spans p - 1..p in the first grid line (p <= m),
                ! p - m..p after it. The elimination tree is a path, so postordering keeps this.
                band_nnz = 1_i8 + 2_i8*(M - 1) + int(N - M, i8)*(M + 1)
                call t%check('nnz(L) in '//trim(NAMES(k))//' order fills the envelope exactly', &
                             chol%factor_nnz() == band_nnz)
            end if
        end do

        ! --- forward: B1' A^{-1} B2 = W1' W2 ---
        call chol%factor(a, stat)
        b1 = b(:, 1:3)
        b2 = b(:, 2:4)*0.5_wp - 1.0_wp
        allocate (w1(N, 3), w2(N, 3), x2(N, 3))
        call chol%forward(b1, w1, stat)
        call t%check('forward solve of B1', stat%ok())
        call chol%forward(b2, w2, stat)
        call chol%solve(b2, x2, stat)
        gram = matmul(transpose(w1), w2)
        ! Both sides are B1' A^{-1} B2 up to rounding amplified by ||A^{-1}|| = 1/lambda_min.
        call t%check('W1''W2 equals B1''A^{-1}B2 within 1e3 eps ||B1|| ||B2|| / lambda_min', &
                     maxval(abs(gram - matmul(transpose(b1), x2))) <= &
                     BACKWARD_TOL*norm2(b1)*norm2(b2)/lambda_min)
        ! backward undoes the rest of a solve: P' L^-T (L^-1 P B) = A^-1 B, the same rounding
        ! bound as above with ||B2|| for the other factor
        allocate (x_back(N, 3))
        call chol%backward(w2, x_back, stat)
        call t%check('backward solve of W2', stat%ok())
        call t%check('backward(forward(B2)) = A^{-1} B2 within 1e3 eps ||B2|| / lambda_min', &
                     maxval(abs(x_back - x2)) <= BACKWARD_TOL*norm2(b2)/lambda_min)

        ! --- errors are statuses, not crashes ---
        call chol%factor(a, stat, ordering=ORDERING_GIVEN)
        call t%check('ORDERING_GIVEN without permutation is bad input', &
                     stat%code == STATUS_BAD_INPUT)
        call t%check('a failed factor leaves nothing to solve with', .not. chol%is_factored())
        call chol%solve(b, x, stat)
        call t%check('solve before factor fails', stat%code == STATUS_BAD_INPUT)
        reversed(1) = reversed(2)
        call chol%factor(a, stat, ordering=ORDERING_GIVEN, permutation=reversed)
        call t%check('a permutation with a repeated entry is bad input', &
                     stat%code == STATUS_BAD_INPUT)
        call chol%factor(a, stat)
        call chol%solve(b(1:N - 1, :), x(1:N - 1, :), stat)
        call t%check('a right-hand side of the wrong size is bad input', &
                     stat%code == STATUS_BAD_INPUT)

        ! A - 4 I has eigenvalues of both signs; in natural order its first pivot is 0.
        shifted = a
        do i = 1, N
            k = shifted%slot(i, i)
            shifted%val(k) = shifted%val(k) - 4.0_wp
        end do
        call chol%factor(shifted, stat, ordering=ORDERING_NATURAL)
        call t%check('indefinite A - 4I is reported as STATUS_SINGULAR', &
                     stat%code == STATUS_SINGULAR)
        call t%check('indefinite A - 4I: a message', allocated(stat%message))
        if (allocated(stat%message)) then
            write (output_unit, '(a)') '      message: '//stat%message
            call t%check('the message names the first column', stat%message == &
                'CHOLMOD: the matrix is not positive definite: a pivot <= 0 at row/column 1')
        end if
        call chol%factor(shifted, stat)
        call t%check('indefinite A - 4I fails with the default ordering too', &
                     stat%code == STATUS_SINGULAR)

        ! Pure Neumann: constants span the kernel. The last pivot is rounding noise of either
        ! sign, caught as a breakdown or as a pivot ratio far below any sane one.
        call laplacian(M, .false., neumann)
        do k = 1, size(ORDERINGS) - 1
            call chol%factor(neumann, stat, ordering=ORDERINGS(k))
            call t%check('singular Neumann Laplacian fails ('//trim(NAMES(k))//')', &
                         stat%code == STATUS_SINGULAR)
            if (allocated(stat%message)) write (output_unit, '(a)') '      message: '//stat%message
        end do

        ! [1 1; 1 1+d]: exact pivots 1 and d, so CHOLMOD's pivot ratio is d (up to rounding of
        ! 1 + d). d = 1e-15 (about 4.5 eps) lies below the 1e3 eps threshold of the shim and
        ! must be refused as singular; d = 1e-10 is ill-conditioned but a valid factorization.
        call two_by_two(1.0e-15_wp, tiny_pivot)
        call chol%factor(tiny_pivot, stat, ordering=ORDERING_NATURAL)
        call t%check('pivot ratio 1e-15 is numerically singular', stat%code == STATUS_SINGULAR)
        call t%check('pivot ratio 1e-15: a message', allocated(stat%message))
        if (allocated(stat%message)) then
            write (output_unit, '(a)') '      message: '//stat%message
            call t%check('the message says numerically singular', &
                         index(stat%message, 'numerically singular') > 0)
        end if
        call two_by_two(1.0e-10_wp, tiny_pivot)
        call chol%factor(tiny_pivot, stat, ordering=ORDERING_NATURAL)
        call t%check('pivot ratio 1e-10 is accepted', stat%ok())
        call t%check_close('its rcond estimate is the pivot ratio 1e-10', chol%rcond(), &
                           1.0e-10_wp, 1.0e-5_wp)

        call chol%free()
        call chol%free()
        call t%check('free twice is harmless', .not. chol%is_factored())
        call t%check('messages exist for every code', &
                     all([(len(cholmod_status_message(k)) > 10, k = 0, 8)]))
        call factor_in_a_scope(a, t)
        call t%report()

    end subroutine run

    !> 5-point Laplacian of an m x m grid of unknowns. Dirichlet: a zero boundary outside
    !> the grid, diagonal 4. Neumann: the diagonal is the number of neighbours (rows sum to 0).
    subroutine laplacian(m, dirichlet, a)
        integer, intent(in) :: m
        logical, intent(in) :: dirichlet
        type(csr_matrix_t), intent(out) :: a
        integer :: row, k
        call five_point_matrix(m, [-1.0_wp, -1.0_wp, 4.0_wp, -1.0_wp, -1.0_wp], a)
        if (dirichlet) return
        do row = 1, m*m
            do k = a%row_start(row), a%row_start(row + 1) - 1
                if (a%col(k) == row) a%val(k) = a%row_start(row + 1) - a%row_start(row) - 1
            end do
        end do
    end subroutine laplacian

    !> The SPD matrix [1 1; 1 1 + d] in CSR.
    subroutine two_by_two(d, a)
        real(wp), intent(in) :: d
        type(csr_matrix_t), intent(out) :: a
        a%row_start = [1, 3, 5]
        a%col = [1, 2, 1, 2]
        a%val = [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp + d]
    end subroutine two_by_two

    !> ||B - A X||_max / (||A||_inf ||X||_max + ||B||_max), the normwise backward error.
    real(wp) function backward_error(a, x, b)
        type(csr_matrix_t), intent(in) :: a
        real(wp), intent(in) :: x(:, :), b(:, :)
        real(wp) :: ax(size(x, 1))
        integer :: k
        backward_error = 0.0_wp
        do k = 1, size(x, 2)
            call a%matvec(x(:, k), ax)
            backward_error = max(backward_error, maxval(abs(b(:, k) - ax)) &
                /(a%norm_inf()*maxval(abs(x(:, k))) + maxval(abs(b(:, k)))))
        end do
    end function backward_error
    !> A local factor is finalized on return; doing it repeatedly must neither crash nor
    !> leave the caller's matrix changed.
    subroutine factor_in_a_scope(a, t)
        type(csr_matrix_t), intent(in) :: a
        type(test_suite_t), intent(inout) :: t
        type(csr_matrix_t) :: copy
        integer :: round
        logical :: all_ok
        copy = a
        all_ok = .true.
        do round = 1, 3
            call factor_and_drop(a, all_ok)
        end do
        call t%check('local factors are finalized cleanly', all_ok)
        call t%check('factor leaves the caller''s CSR untouched', &
            all(copy%row_start == a%row_start) .and. all(copy%col == a%col) .and. &
            all(transfer(copy%val, [0_i8]) == transfer(a%val, [0_i8])))
    end subroutine factor_in_a_scope

    subroutine factor_and_drop(a, all_ok)
        type(csr_matrix_t), intent(in) :: a
        logical, intent(inout) :: all_ok
        type(cholesky_t) :: local
        type(status_t) :: stat
        call local%factor(a, stat, ordering=ORDERING_METIS)
        all_ok = all_ok .and. stat%ok()
    end subroutine factor_and_drop
end program test_sparse_cholesky
