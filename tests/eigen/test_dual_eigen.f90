! SPDX-License-Identifier: MIT
!> The left eigenvector by inverse iteration against closed forms: a 2 x 2 triangular
!> matrix, a shift that is an eigenvalue to the last bit, and a shift far from the wanted
!> eigenvalue with a second one close behind it (where a fixed shift gains a factor 0.83
!> per step and the shift must move).
program test_dual_eigen
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use dual_eigen, only: reduced_left_eigenvector
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_dual_eigen'
    call triangular_closed_form(t)
    call shift_on_an_eigenvalue(t)
    call far_shift_near_a_pair(t)
    call t%report()

contains

    !> A = [1 1; 0 2]: A' w = w for w = (1, -1) / sqrt(2), up to sign.
    subroutine triangular_closed_form(t)
        type(test_suite_t), intent(inout) :: t
        real(wp) :: a(2, 2), theta
        real(wp), allocatable :: w(:)
        type(status_t) :: stat
        a = reshape([1.0_wp, 0.0_wp, 1.0_wp, 2.0_wp], [2, 2])
        call reduced_left_eigenvector(a, 0.9_wp, w, theta, stat)
        call t%check('triangular: converged', stat%ok())
        call t%check_close('triangular: theta = 1', theta, 1.0_wp, rel_tol=1.0e-14_wp)
        call t%check_close('triangular: |w1 + w2| = 0', abs(w(1) + w(2)), 0.0_wp, &
                           rel_tol=0.0_wp, abs_tol=1.0e-14_wp)
        call t%check_close('triangular: |w1| = 1/sqrt(2)', abs(w(1)), 1.0_wp/sqrt(2.0_wp), &
                           rel_tol=1.0e-14_wp)
    end subroutine triangular_closed_form

    !> diag(3, -1, 7) with shift -1 exactly: the LU is singular to the last bit, the shift
    !> moves by a few ulps, and w is the second unit vector.
    subroutine shift_on_an_eigenvalue(t)
        type(test_suite_t), intent(inout) :: t
        real(wp) :: a(3, 3), theta
        real(wp), allocatable :: w(:)
        type(status_t) :: stat
        a = 0.0_wp
        a(1, 1) = 3.0_wp
        a(2, 2) = -1.0_wp
        a(3, 3) = 7.0_wp
        call reduced_left_eigenvector(a, -1.0_wp, w, theta, stat)
        call t%check('exact shift: converged', stat%ok())
        call t%check_close('exact shift: theta = -1', theta, -1.0_wp, rel_tol=1.0e-15_wp)
        call t%check_close('exact shift: |w2| = 1', abs(w(2)), 1.0_wp, rel_tol=1.0e-15_wp)
    end subroutine shift_on_an_eigenvalue

    !> A = S T S^-1 with T lower triangular, eigenvalues 1, 1.2, 5, and shift 0: the
    !> eigenvalue nearest the shift is 1, the next 1.2 (a fixed shift gains 1 / 1.2 per step,
    !> 1e-4 in 50 steps: not converged). Then A' w = w for w = S^-T e_1 (normalised), up to
    !> sign: e_1' T = e_1', so (e_1' S^-1) A = e_1' T S^-1 = e_1' S^-1.
    subroutine far_shift_near_a_pair(t)
        type(test_suite_t), intent(inout) :: t
        real(wp) :: a(3, 3), s(3, 3), s_inv(3, 3), tri(3, 3), expected(3), theta
        real(wp), allocatable :: w(:)
        type(status_t) :: stat
        tri = reshape([1.0_wp, 0.7_wp, -0.4_wp, 0.0_wp, 1.2_wp, 0.9_wp, 0.0_wp, 0.0_wp, &
                       5.0_wp], [3, 3])
        ! S unit upper triangular: its inverse in closed form
        s = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.5_wp, 1.0_wp, 0.0_wp, -0.25_wp, 0.75_wp, &
                     1.0_wp], [3, 3])
        s_inv = reshape([1.0_wp, 0.0_wp, 0.0_wp, -0.5_wp, 1.0_wp, 0.0_wp, 0.625_wp, &
                         -0.75_wp, 1.0_wp], [3, 3])
        call t%check_close('far shift: S S^-1 = I', maxval(abs(matmul(s, s_inv) - &
            reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
                     1.0_wp], [3, 3]))), 0.0_wp, rel_tol=0.0_wp, abs_tol=1.0e-15_wp)
        a = matmul(s, matmul(tri, s_inv))
        call reduced_left_eigenvector(a, 0.0_wp, w, theta, stat)
        call t%check('far shift: converged', stat%ok())
        call t%check_close('far shift: theta = 1', theta, 1.0_wp, rel_tol=1.0e-13_wp)
        expected = s_inv(1, :)/norm2(s_inv(1, :))
        call t%check_close('far shift: w = S^-T e_1', &
                           min(maxval(abs(w - expected)), maxval(abs(w + expected))), 0.0_wp, &
                           rel_tol=0.0_wp, abs_tol=1.0e-13_wp)
    end subroutine far_shift_near_a_pair

end program test_dual_eigen
