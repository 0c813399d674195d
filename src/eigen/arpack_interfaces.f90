! SPDX-License-Identifier: MIT
!> Explicit interfaces of ARPACK-ng's real non-symmetric reverse-communication driver
!> (dnaupd, dneupd), and a pure function that turns their `info` into a sentence.
!>
!> ARPACK keeps `save`d variables between the calls of one reverse-communication loop, so
!> one ARPACK solve at a time per process: never interleave two loops.
module arpack_interfaces
    use kinds, only: wp
    use strings, only: to_string
    implicit none
    private
    public :: dnaupd, dneupd, arpack_info_message

    interface
        subroutine dnaupd(ido, bmat, n, which, nev, tol, resid, ncv, v, ldv, iparam, ipntr, &
                          workd, workl, lworkl, info)
            import :: wp
            integer, intent(inout) :: ido, info
            character(len=1), intent(in) :: bmat
            character(len=2), intent(in) :: which
            integer, intent(in) :: n, nev, ncv, ldv, lworkl
            real(wp), intent(in) :: tol
            real(wp), intent(inout) :: resid(*), v(ldv, *), workd(*), workl(*)
            integer, intent(inout) :: iparam(11), ipntr(14)
        end subroutine dnaupd

        subroutine dneupd(rvec, howmny, select, dr, di, z, ldz, sigmar, sigmai, workev, bmat, &
                          n, which, nev, tol, resid, ncv, v, ldv, iparam, ipntr, workd, &
                          workl, lworkl, info)
            import :: wp
            logical, intent(in) :: rvec
            character(len=1), intent(in) :: howmny, bmat
            integer, intent(in) :: ldz, n, nev, ncv, ldv, lworkl
            logical, intent(inout) :: select(*)
            real(wp), intent(out) :: dr(*), di(*), z(ldz, *), workev(*)
            real(wp), intent(in) :: sigmar, sigmai, tol
            character(len=2), intent(in) :: which
            real(wp), intent(inout) :: resid(*), v(ldv, *), workd(*), workl(*)
            integer, intent(inout) :: iparam(11), ipntr(14), info
        end subroutine dneupd
    end interface

contains

    !> A sentence for ARPACK's `info` from dnaupd (`routine` = 'dnaupd') or dneupd.
    pure function arpack_info_message(routine, info) result(text)
        character(len=*), intent(in) :: routine
        integer, intent(in) :: info
        character(len=:), allocatable :: text
        character(len=:), allocatable :: what
        select case (info)
        case (0)
            what = 'normal exit'
        case (1)
            what = 'the maximum number of restarts (maxit) was reached before all wanted '// &
                   'Ritz values converged'
        case (2)
            what = 'no longer an informational error (ARPACK-ng)'
        case (3)
            what = 'no shifts could be applied during a restart; increase ncv relative to nev'
        case (-1)
            what = 'n must be positive'
        case (-2)
            what = 'nev must be positive'
        case (-3)
            what = 'ncv must satisfy nev + 2 <= ncv <= n'
        case (-4)
            what = 'maxit must be positive'
        case (-5)
            what = 'which must be one of LM, SM, LR, SR, LI, SI'
        case (-6)
            what = 'bmat must be I or G'
        case (-7)
            what = 'the private work array workl is too short'
        case (-8)
            if (routine == 'dneupd') then
                what = 'the Schur form of the Hessenberg matrix could not be computed '// &
                       '(LAPACK dlahqr failed)'
            else
                what = 'the eigenvalues of the Hessenberg matrix could not be computed '// &
                       '(LAPACK dlahqr failed)'
            end if
        case (-9)
            if (routine == 'dneupd') then
                what = 'the eigenvectors of the Schur form could not be computed (dtrevc)'
            else
                what = 'the starting vector is zero'
            end if
        case (-10)
            what = 'iparam(7) (mode) must be 1 to 4'
        case (-11)
            what = 'mode 1 needs bmat = I'
        case (-12)
            what = 'iparam(1) (shift strategy) must be 0 or 1'
        case (-13)
            what = 'howmny = S is not implemented'
        case (-14)
            what = 'dnaupd did not find any eigenvalue to sufficient accuracy'
        case (-15)
            what = 'dneupd received a different count of converged Ritz values than dnaupd'
        case (-9999)
            what = 'the Arnoldi factorization could not be built (the Krylov subspace '// &
                   'is invariant or breakdown occurred: its size is in iparam(5))'
        case default
            what = 'undocumented code'
        end select
        text = 'ARPACK '//routine//' info = '//to_string(info)//': '//what
    end function arpack_info_message
end module arpack_interfaces
