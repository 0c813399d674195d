! SPDX-License-Identifier: MIT
!> Explicit interfaces of the LAPACK and BLAS routines nceig calls, so that argument
!> mistakes are compile-time errors, a pure function that explains LAPACK's info codes, and
!> the one reading of LAPACK's real storage of complex eigenvectors.
module lapack_interfaces
    use kinds, only: wp
    use strings, only: to_string
    implicit none
    private
    public :: dgeevx, dggev, dgemm, dgemv, dsyrk, dgesvd, lapack_info_message
    public :: dgeev, dtrsv, dtrsm, dgetrf, dgetrs, dpotri, dpotrf, dlacn2, lapack_eigenvector

    interface
        subroutine dgeevx(balanc, jobvl, jobvr, sense, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, &
                          ilo, ihi, scale, abnrm, rconde, rcondv, work, lwork, iwork, info)
            import :: wp
            character(len=1), intent(in) :: balanc, jobvl, jobvr, sense
            integer, intent(in) :: n, lda, ldvl, ldvr, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), scale(*)
            real(wp), intent(out) :: abnrm, rconde(*), rcondv(*), work(*)
            integer, intent(out) :: ilo, ihi, iwork(*), info
        end subroutine dgeevx

        subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
            import :: wp
            character(len=1), intent(in) :: jobvl, jobvr
            integer, intent(in) :: n, lda, ldvl, ldvr, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
            integer, intent(out) :: info
        end subroutine dgeev

        subroutine dgesvd(jobu, jobvt, m, n, a, lda, s, u, ldu, vt, ldvt, work, lwork, info)
            import :: wp
            character(len=1), intent(in) :: jobu, jobvt
            integer, intent(in) :: m, n, lda, ldu, ldvt, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: s(*), u(ldu, *), vt(ldvt, *), work(*)
            integer, intent(out) :: info
        end subroutine dgesvd

        subroutine dggev(jobvl, jobvr, n, a, lda, b, ldb, alphar, alphai, beta, vl, ldvl, &
                         vr, ldvr, work, lwork, info)
            import :: wp
            character(len=1), intent(in) :: jobvl, jobvr
            integer, intent(in) :: n, lda, ldb, ldvl, ldvr, lwork
            real(wp), intent(inout) :: a(lda, *), b(ldb, *)
            real(wp), intent(out) :: alphar(*), alphai(*), beta(*), vl(ldvl, *), vr(ldvr, *)
            real(wp), intent(out) :: work(*)
            integer, intent(out) :: info
        end subroutine dggev

        subroutine dgemm(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc)
            import :: wp
            character(len=1), intent(in) :: transa, transb
            integer, intent(in) :: m, n, k, lda, ldb, ldc
            real(wp), intent(in) :: alpha, beta, a(lda, *), b(ldb, *)
            real(wp), intent(inout) :: c(ldc, *)
        end subroutine dgemm

        subroutine dgemv(trans, m, n, alpha, a, lda, x, incx, beta, y, incy)
            import :: wp
            character(len=1), intent(in) :: trans
            integer, intent(in) :: m, n, lda, incx, incy
            real(wp), intent(in) :: alpha, beta, a(lda, *), x(*)
            real(wp), intent(inout) :: y(*)
        end subroutine dgemv

        subroutine dsyrk(uplo, trans, n, k, alpha, a, lda, beta, c, ldc)
            import :: wp
            character(len=1), intent(in) :: uplo, trans
            integer, intent(in) :: n, k, lda, ldc
            real(wp), intent(in) :: alpha, beta, a(lda, *)
            real(wp), intent(inout) :: c(ldc, *)
        end subroutine dsyrk

        subroutine dtrsv(uplo, trans, diag, n, a, lda, x, incx)
            import :: wp
            character(len=1), intent(in) :: uplo, trans, diag
            integer, intent(in) :: n, lda, incx
            real(wp), intent(in) :: a(lda, *)
            real(wp), intent(inout) :: x(*)
        end subroutine dtrsv

        subroutine dtrsm(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb)
            import :: wp
            character(len=1), intent(in) :: side, uplo, transa, diag
            integer, intent(in) :: m, n, lda, ldb
            real(wp), intent(in) :: alpha, a(lda, *)
            real(wp), intent(inout) :: b(ldb, *)
        end subroutine dtrsm

        subroutine dpotrf(uplo, n, a, lda, info)
            import :: wp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotrf

        subroutine dpotri(uplo, n, a, lda, info)
            import :: wp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotri

        subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: wp
            integer, intent(in) :: m, n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgetrf

        subroutine dlacn2(n, v, x, isgn, est, kase, isave)
            import :: wp
            integer, intent(in) :: n
            real(wp), intent(out) :: v(*)
            real(wp), intent(inout) :: x(*), est
            integer, intent(out) :: isgn(*)
            integer, intent(inout) :: kase, isave(3)
        end subroutine dlacn2

        subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            character(len=1), intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb, ipiv(*)
            real(wp), intent(in) :: a(lda, *)
            real(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dgetrs
    end interface

contains

    !> A sentence for a nonzero LAPACK info from routine `routine`.
    pure function lapack_info_message(routine, info) result(text)
        character(len=*), intent(in) :: routine
        integer, intent(in) :: info
        character(len=:), allocatable :: text
        if (info < 0) then
            text = routine//': argument '//to_string(-info)//' had an illegal value (a bug)'
        else
            text = routine//': the QR/QZ iteration failed to converge (info = '// &
                   to_string(info)//'); no eigenvalues are reliable'
        end if
    end function lapack_info_message

    !> Eigenvector j of dgeev/dgeevx as a complex vector: a real eigenvalue (wi(j) = 0) has
    !> column j; a complex pair (j, j+1) with wi(j) > 0 stores the real part in column j and
    !> the imaginary part in column j + 1, the partner being the conjugate.
    pure function lapack_eigenvector(vr, wi, j) result(y)
        real(wp), intent(in) :: vr(:, :), wi(:)
        integer, intent(in) :: j
        complex(wp) :: y(size(vr, 1))
        if (.not. (abs(wi(j)) > 0.0_wp)) then
            y = cmplx(vr(:, j), 0.0_wp, wp)
        else if (wi(j) > 0.0_wp) then
            y = cmplx(vr(:, j), vr(:, j + 1), wp)
        else
            y = cmplx(vr(:, j - 1), -vr(:, j), wp)
        end if
    end function lapack_eigenvector
end module lapack_interfaces
