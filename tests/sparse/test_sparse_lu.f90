! SPDX-License-Identifier: MIT
!> sparse_lu: a small non-symmetric system with a known integer solution (which tells A
!> from A'), a convection-diffusion stencil against LAPACK dgesv, and singular matrices.
program test_sparse_lu
    use, intrinsic :: iso_fortran_env, only: output_unit
    use kinds, only: wp
    use status, only: status_t, STATUS_SINGULAR, STATUS_BAD_INPUT
    use csr_matrix, only: csr_matrix_t
    use sparse_lu, only: lu_t, LU_ORDERING_DEFAULT, &
                         LU_ORDERING_METIS, LU_ORDERING_NATURAL, LU_ORDERING_CHOLMOD
    use umfpack_c, only: umfpack_status_message
    use testing, only: test_suite_t
    use fixtures, only: to_dense => csr_to_dense, five_point_matrix
    implicit none

    interface
        subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: wp
            integer, intent(in) :: m, n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgetrf
        subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            character, intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb, ipiv(*)
            real(wp), intent(in) :: a(lda, *)
            real(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dgetrs
        subroutine dgecon(norm, n, a, lda, anorm, rcond, work, iwork, info)
            import :: wp
            character, intent(in) :: norm
            integer, intent(in) :: n, lda
            real(wp), intent(in) :: a(lda, *), anorm
            real(wp), intent(out) :: rcond, work(*)
            integer, intent(out) :: iwork(*), info
        end subroutine dgecon
    end interface

    integer, parameter :: M = 20, N = M*M
    real(wp), parameter :: EPS = epsilon(1.0_wp)
    ! Normwise backward error of sparse LU with threshold partial pivoting, after UMFPACK's
    ! iterative refinement: a few eps in practice; 1e3 eps still exposes any wrong solve.
    real(wp), parameter :: BACKWARD_TOL = 1.0e3_wp*EPS
    integer, parameter :: ORDERINGS(4) = [LU_ORDERING_DEFAULT, LU_ORDERING_METIS, &
                                          LU_ORDERING_NATURAL, LU_ORDERING_CHOLMOD]
    integer, parameter :: DOCUMENTED(16) = [0, 1, 2, 3, -1, -3, -4, -5, -6, -8, -11, -13, &
                                            -15, -911, -17, -18]   ! umfpack.h, SuiteSparse 5
    character(len=*), parameter :: NAMES(4) = [character(len=7) :: 'default', 'METIS', &
                                               'natural', 'CHOLMOD']

    call run()

contains

    !> All checks, in a procedure so that its allocatables are freed on return and a
    !> sanitizer build reports only real leaks.
    subroutine run()
        type(test_suite_t) :: t
        type(csr_matrix_t) :: small, a, singular
        type(lu_t) :: lu
        type(status_t) :: stat
        real(wp), allocatable :: b(:), x(:), x_lapack(:), dense(:, :), work(:)
        integer, allocatable :: pivots(:), iwork(:)
        real(wp) :: rcond_1, forward_tol
        integer :: i, k, info

        t%name = 'test_sparse_lu'

        ! [2 1 0; 0 3 1; 1 0 4] x = [4 9 13] has x = [1 2 3]; the transposed system has not.
        small%row_start = [1, 3, 5, 7]
        small%col = [1, 2, 2, 3, 1, 3]
        small%val = [2.0_wp, 1.0_wp, 3.0_wp, 1.0_wp, 1.0_wp, 4.0_wp]
        call lu%factor(small, stat)
        call t%check('factor a 3 x 3 non-symmetric matrix', stat%ok())
        allocate (x(3))
        call lu%solve([4.0_wp, 9.0_wp, 13.0_wp], x, stat)
        call t%check('solve it', stat%ok())
        ! cond_inf of this matrix is below 10, so x is exact to a few ulps of 3.
        call t%check('A x = b, not A''x = b: x = (1, 2, 3)', &
                     maxval(abs(x - [1.0_wp, 2.0_wp, 3.0_wp])) <= 30.0_wp*EPS)
        deallocate (x)

        ! Convection-diffusion, central differences: 4 on the diagonal, -1 -+ 0.3 west/east,
        ! -1 -+ 0.2 south/north. Non-symmetric, diagonally dominant, so non-singular.
        call convection_diffusion(M, 0.3_wp, 0.2_wp, a)
        allocate (b(N), x(N))
        b = [(sin(0.1_wp*i) + 1.0_wp, i = 1, N)]
        dense = to_dense(a)
        allocate (pivots(N), work(4*N), iwork(N))
        call dgetrf(N, N, dense, N, pivots, info)
        call t%check('dgetrf succeeds', info == 0)
        call dgecon('1', N, dense, N, maxval(column_sums(a)), rcond_1, work, iwork, info)
        x_lapack = b
        call dgetrs('N', N, 1, dense, N, pivots, x_lapack, N, info)
        ! Two backward stable solves differ by at most 2 cond_1 * backward error (1-norm).
        forward_tol = 2.0_wp*BACKWARD_TOL/rcond_1
        write (output_unit, '(a, es10.3)') '      cond_1 estimate ', 1.0_wp/rcond_1
        do k = 1, size(ORDERINGS)
            call lu%factor(a, stat, ordering=ORDERINGS(k))
            call t%check('factor convection-diffusion, ordering '//trim(NAMES(k)), stat%ok())
            call lu%solve(b, x, stat)
            call t%check('solve, ordering '//trim(NAMES(k)), stat%ok())
            call t%check('backward error <= 1e3 eps, ordering '//trim(NAMES(k)), &
                         backward_error(a, x, b) <= BACKWARD_TOL)
            call t%check('agrees with dgesv within 2 cond_1 1e3 eps, ordering '//trim(NAMES(k)), &
                         sum(abs(x - x_lapack)) <= forward_tol*sum(abs(x_lapack)))
        end do
        call t%check('factor nnz is reported', lu%factor_nnz() >= N)
        call t%check('rcond estimate lies in (0, 1]', lu%rcond() > 0 .and. lu%rcond() <= 1)

        ! --- failures are statuses ---
        call lu%factor(a, stat, ordering=99)
        call t%check('an unknown ordering is bad input', stat%code == STATUS_BAD_INPUT)
        call lu%solve(b, x, stat)
        call t%check('solve before factor is bad input', stat%code == STATUS_BAD_INPUT)
        call lu%factor(a, stat)
        call lu%solve(b(1:N - 1), x(1:N - 1), stat)
        call t%check('a right-hand side of the wrong size is bad input', &
                     stat%code == STATUS_BAD_INPUT)

        ! Structurally singular: row 2 of [1 1 0; 0 0 0; 0 1 1] stores no entry at all.
        singular%row_start = [1, 3, 3, 5]
        singular%col = [1, 2, 2, 3]
        singular%val = [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp]
        call lu%factor(singular, stat)
        call t%check('an empty row is reported as STATUS_SINGULAR', stat%code == STATUS_SINGULAR)
        if (allocated(stat%message)) write (output_unit, '(a)') '      message: '//stat%message
        call t%check('a singular factor is not kept', .not. lu%is_factored())

        ! Numerically singular: row 2 of [1 2; 2 4] is twice row 1. After UMFPACK's row scaling
        ! by the row sums both rows are [1/3 2/3] exactly, so elimination leaves an exact 0.
        singular%row_start = [1, 3, 5]
        singular%col = [1, 2, 1, 2]
        singular%val = [1.0_wp, 2.0_wp, 2.0_wp, 4.0_wp]
        call lu%factor(singular, stat)
        call t%check('dependent rows are reported as STATUS_SINGULAR', &
                     stat%code == STATUS_SINGULAR)
        if (allocated(stat%message)) write (output_unit, '(a)') '      message: '//stat%message

        call lu%free()
        call lu%free()
        call t%check('free twice is harmless', .not. lu%is_factored())
        call t%check('every documented status has its own sentence', &
                     all([(index(umfpack_status_message(DOCUMENTED(k)), 'unknown') == 0, &
                           k = 1, size(DOCUMENTED))]))
        call t%check('an undocumented status says unknown', &
                     index(umfpack_status_message(-2), 'unknown status -2') > 0)
        call t%report()

    end subroutine run

    subroutine convection_diffusion(m, east_west, north_south, a)
        integer, intent(in) :: m
        real(wp), intent(in) :: east_west, north_south
        type(csr_matrix_t), intent(out) :: a
        call five_point_matrix(m, [-1.0_wp - north_south, -1.0_wp - east_west, 4.0_wp, &
                                   -1.0_wp + east_west, -1.0_wp + north_south], a)
    end subroutine convection_diffusion

    !> Absolute column sums: their maximum is the 1-norm dgecon needs.
    function column_sums(a) result(sums)
        type(csr_matrix_t), intent(in) :: a
        real(wp) :: sums(a%n())
        integer :: k
        sums = 0.0_wp
        do k = 1, size(a%col)
            sums(a%col(k)) = sums(a%col(k)) + abs(a%val(k))
        end do
    end function column_sums

    !> ||b - A x||_inf / (||A||_inf ||x||_inf + ||b||_inf)
    real(wp) function backward_error(a, x, b)
        type(csr_matrix_t), intent(in) :: a
        real(wp), intent(in) :: x(:), b(:)
        real(wp) :: ax(size(x))
        call a%matvec(x, ax)
        backward_error = maxval(abs(b - ax))/(a%norm_inf()*maxval(abs(x)) + maxval(abs(b)))
    end function backward_error
end program test_sparse_lu
