! SPDX-License-Identifier: MIT
!> Every operator ARPACK runs on, applied to vectors and compared with the same operator
!> formed densely and independently (dense K^-1 by LAPACK, A = (lambda N K^-1 T' - N K^-1
!> N') M, B) on the reference scene of 3 x 3 P2 squares at lambda = 5 (lambda_scale 4):
!> the reduced operator A y / 4 and (I - sigma A)^-1 A y / 4, the full operator
!> (K - sigma B)^-1 B y / 4 at sigma = 0 (CHOLMOD) and sigma = 0.3 (UMFPACK), each with its
!> transpose; the explicit operator; mu of an eigenvalue of the shifted operator; the norm
!> estimate and the target's range check.
program test_contact_operator
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use dof_map, only: dof_map_t
    use csr_matrix, only: csr_matrix_t
    use contact_boundary, only: contact_t
    use sparse_cholesky, only: cholesky_t
    use timer, only: timings_t
    use unit_scaling, only: units_t
    use lapack_interfaces, only: dgeev
    use contact_reduction, only: factor_stiffness
    use contact_operator, only: reduced_operator_t, full_operator_t, explicit_operator_t, &
                                TARGET_RANGE
    use dense_reference, only: dense_inverse, dense_solve, dense_reduced_matrix, tiny_scene
    use fixtures, only: csr_to_dense
    use testing, only: test_suite_t
    implicit none

    real(wp), parameter :: LAMBDA = 5.0_wp, SCALE = 4.0_wp, SIGMA = 0.3_wp
    !> K and K - sigma B are below 1e3 conditioned here
    real(wp), parameter :: TOL = 1.0e-12_wp
    type(test_suite_t) :: t
    type(mesh_t) :: m
    type(dof_map_t) :: dofs
    type(contact_t) :: contact
    type(csr_matrix_t) :: k, b
    type(cholesky_t) :: chol
    type(units_t) :: units
    type(timings_t) :: timings
    type(status_t) :: stat
    real(wp), allocatable :: a(:, :), k_dense(:, :), b_dense(:, :), k_inverse(:, :)
    real(wp), allocatable :: y_small(:), y_full(:)
    integer :: i, p, n

    t%name = 'test_contact_operator'
    call tiny_scene(LAMBDA, m, dofs, contact, k, b, stat)
    call factor_stiffness(k, m, dofs, contact, chol, timings, stat)
    k_dense = csr_to_dense(k)
    b_dense = csr_to_dense(b)
    k_inverse = dense_inverse(k_dense)
    a = dense_reduced_matrix(contact, k_inverse, LAMBDA)
    p = contact%p()
    n = dofs%n_free
    y_small = [(sin(real(3*i, wp)), i=1, p)]
    y_full = [(cos(real(7*i, wp)), i=1, n)]

    call check_reduced()
    call check_full()
    call check_explicit()
    call chol%free()
    ! (AddressSanitizer reports a main program's allocatables)
    deallocate (a, k_dense, b_dense, k_inverse, y_small, y_full)
    call t%report()

contains

    !> |x - expected| <= TOL max|expected|
    logical function matches(x, expected)
        real(wp), intent(in) :: x(:), expected(:)
        matches = size(x) == size(expected) .and. &
                maxval(abs(x - expected)) <= TOL*maxval(abs(expected))
    end function matches

    subroutine check_reduced()
        type(reduced_operator_t) :: op, shifted
        real(wp), allocatable :: out(:), expected(:, :), dense(:, :), shift_matrix(:, :), &
                                 wr(:), wi(:), work(:), unused(:, :), unused_right(:, :)
        complex(wp) :: nu
        integer :: j, info
        call op%setup(chol, contact, LAMBDA, 0.0_wp, stat, 0.0_wp, units)
        call t%check('reduced setup: p = n = the contact nodes, lambda_scale 4', stat%ok() &
                     .and. op%p == p .and. op%n == p .and. abs(op%lambda_scale - SCALE) &
                     <= 0.0_wp)
        allocate (out(p))
        call op%apply(chol, y_small, out, .false., stat)
        call t%check('reduced: A y / 4', stat%ok() .and. matches(out, matmul(a, y_small)/SCALE))
        call op%apply(chol, y_small, out, .true., stat)
        call t%check('reduced, transposed: A'' y / 4', stat%ok() .and. &
                     matches(out, matmul(transpose(a), y_small)/SCALE))
        call op%dense_a(dense, stat)
        call t%check('dense_a: A / 4', stat%ok() .and. maxval(abs(dense - a/SCALE)) <= &
                     TOL*maxval(abs(a)))

        call shifted%setup(chol, contact, LAMBDA, SIGMA, stat, SIGMA, units)
        shift_matrix = -SIGMA*a
        do j = 1, p
            shift_matrix(j, j) = shift_matrix(j, j) + 1.0_wp
        end do
        allocate (expected(p, 1))
        expected(:, 1) = matmul(a, y_small)/SCALE
        call dense_solve(shift_matrix, expected, .false.)
        call shifted%apply(chol, y_small, out, .false., stat)
        call t%check('reduced, sigma = 0.3: (I - sigma A)^-1 A y / 4', stat%ok() .and. &
                     matches(out, expected(:, 1)))
        expected(:, 1) = y_small
        call dense_solve(shift_matrix, expected, .true.)
        call shifted%apply(chol, y_small, out, .true., stat)
        call t%check('reduced, sigma = 0.3, transposed: A'' (I - sigma A)^-T y / 4', &
                     stat%ok() .and. matches(out, matmul(transpose(a), expected(:, 1))/SCALE))

        ! an eigenvalue theta of A is nu = (theta / 4)/(1 - sigma theta) of the shifted
        ! operator, and mu_of(nu) = 1 / theta
        dense = a
        allocate (wr(p), wi(p), work(8*p), unused(1, 1), unused_right(1, 1))
        call dgeev('N', 'N', p, dense, p, wr, wi, unused, 1, unused_right, 1, work, &
                   size(work), info)
        nu = (cmplx(wr(1), wi(1), wp)/SCALE)/(1.0_wp - SIGMA*cmplx(wr(1), wi(1), wp))
        call t%check('mu_of: sigma + 1/(4 nu) is 1/theta', &
                     abs(shifted%mu_of(nu) - 1.0_wp/cmplx(wr(1), wi(1), wp)) <= &
                     TOL*abs(1.0_wp/cmplx(wr(1), wi(1), wp)))

        call shifted%setup(chol, contact, LAMBDA, 2.0_wp*TARGET_RANGE/norm_inf(a), stat, &
                           123.0_wp, units)
        call t%check('check_target: |sigma| ||A|| beyond TARGET_RANGE is bad input naming '// &
                     '&eigen target', stat%code == STATUS_BAD_INPUT .and. &
                     index(stat%message, '&eigen: target = 123.0') == 1)
    end subroutine check_reduced

    subroutine check_full()
        type(full_operator_t) :: op, shifted
        real(wp), allocatable :: out(:), expected(:, :), shifted_k(:, :)
        real(wp) :: estimate, exact
        call op%setup(k, b, chol, contact, LAMBDA, 0.0_wp, stat, 0.0_wp, units)
        allocate (out(n), expected(n, 1))
        call op%apply(chol, y_full, out, .false., stat)
        call t%check('full, sigma = 0: K^-1 B y / 4', stat%ok() .and. op%n == n .and. &
                     matches(out, matmul(k_inverse, matmul(b_dense, y_full))/SCALE))
        call op%apply(chol, y_full, out, .true., stat)
        call t%check('full, sigma = 0, transposed: K^-1 B'' y / 4', stat%ok() .and. &
                     matches(out, matmul(k_inverse, matmul(transpose(b_dense), y_full))/SCALE))

        call shifted%setup(k, b, chol, contact, LAMBDA, SIGMA, stat, SIGMA, units)
        shifted_k = k_dense - SIGMA*b_dense
        expected(:, 1) = matmul(b_dense, y_full)/SCALE
        call dense_solve(shifted_k, expected, .false.)
        call shifted%apply(chol, y_full, out, .false., stat)
        call t%check('full, sigma = 0.3 (UMFPACK): (K - sigma B)^-1 B y / 4', stat%ok() &
                     .and. matches(out, expected(:, 1)))
        expected(:, 1) = matmul(transpose(b_dense), y_full)/SCALE
        call dense_solve(shifted_k, expected, .true.)
        call shifted%apply(chol, y_full, out, .true., stat)
        call t%check('full, sigma = 0.3, transposed: (K - sigma B)^-T B'' y / 4', &
                     stat%ok() .and. matches(out, expected(:, 1)))

        ! ||A / 4||_inf: Higham's estimator gives a lower bound, exact on small matrices
        call op%norm_estimate(chol, estimate, stat)
        exact = norm_inf(a)/SCALE
        call t%check('norm_estimate: a lower bound of ||A / 4||_inf within a factor 3', &
                     stat%ok() .and. estimate <= exact*(1.0_wp + TOL) .and. &
                     estimate >= exact/3.0_wp)
        call shifted%setup(k, b, chol, contact, LAMBDA, 2.0_wp*TARGET_RANGE/norm_inf(a), &
                           stat, 7.0_wp, units)
        call t%check('full: a target out of range is bad input', &
                     stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'target = 7.0') > 0)
    end subroutine check_full

    subroutine check_explicit()
        type(explicit_operator_t) :: op
        real(wp) :: out(3)
        real(wp), parameter :: M3(3, 3) = reshape([1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp, 5.0_wp, &
                                                   6.0_wp, 7.0_wp, 8.0_wp, 10.0_wp], [3, 3])
        call op%setup(M3)
        call op%apply(chol, [1.0_wp, -1.0_wp, 2.0_wp], out, .false., stat)
        call t%check('explicit: A y by one product (small integers: exact)', &
                     all(abs(out - matmul(M3, [1.0_wp, -1.0_wp, 2.0_wp])) <= 0.0_wp) .and. &
                     op%p == 3 .and. abs(op%sigma) <= 0.0_wp)
        call op%apply(chol, [1.0_wp, -1.0_wp, 2.0_wp], out, .true., stat)
        call t%check('explicit, transposed: A'' y', &
                     all(abs(out - matmul(transpose(M3), [1.0_wp, -1.0_wp, 2.0_wp])) <= 0.0_wp))
    end subroutine check_explicit

    pure real(wp) function norm_inf(x)
        real(wp), intent(in) :: x(:, :)
        norm_inf = maxval(sum(abs(x), dim=2))
    end function norm_inf
end program test_contact_operator
