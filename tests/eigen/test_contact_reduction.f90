! SPDX-License-Identifier: MIT
!> The reduction to the contact nodes against a dense inverse of K on a tiny mesh (the
!> reference scene on 3 x 3 P2 squares, lambda = 5): the contact blocks Kt_nn = N K^-1 N'
!> and Kt_nt = N K^-1 T' read off the trailing block of the contact-last factor; A and its
!> scaled form; the lift of the reduced eigenvectors y (LAPACK's, of the dense A) to
!> phi = K^-1 (lambda T' - N') M y, which are eigenvectors of K phi = mu B phi to round-off.
program test_contact_reduction
    use kinds, only: wp
    use status, only: status_t
    use mesh, only: mesh_t
    use dof_map, only: dof_map_t
    use csr_matrix, only: csr_matrix_t
    use contact_boundary, only: contact_t
    use sparse_cholesky, only: cholesky_t, ORDERING_GIVEN
    use node_ordering, only: nested_dissection_last
    use timer, only: timings_t
    use lapack_interfaces, only: dgeev, lapack_eigenvector
    use spectrum, only: normalise_mode
    use contact_reduction, only: factor_stiffness, factor_permuted, factor_contact_blocks, &
                                 contact_tail, flexibility_blocks, contact_flexibility, &
                                 lift_eigenvectors, lift_block_columns, reduced_matrix, &
                                 scaled_reduced_matrix, lambda_unit, mu_of_theta, &
                                 reduced_blocks_t
    use dense_reference, only: dense_inverse, contact_rows, dense_reduced_matrix, tiny_scene
    use fixtures, only: csr_to_dense
    use testing, only: test_suite_t
    implicit none

    real(wp), parameter :: LAMBDA = 5.0_wp
    !> K is 3e2 conditioned here: the factor and the dense inverse agree to a few hundred eps
    real(wp), parameter :: TOL = 1.0e-12_wp
    type(test_suite_t) :: t
    type(mesh_t) :: m
    type(dof_map_t) :: dofs
    type(contact_t) :: contact
    type(csr_matrix_t) :: k, b
    type(status_t) :: stat
    type(timings_t) :: timings
    type(cholesky_t) :: chol
    real(wp), allocatable :: k_inverse(:, :), normal_rows(:, :), tangent_rows(:, :), &
                             kt_nn(:, :), kt_nt(:, :), kt_nn_ref(:, :), kt_nt_ref(:, :)

    t%name = 'test_contact_reduction'
    call tiny_scene(LAMBDA, m, dofs, contact, k, b, stat)
    k_inverse = dense_inverse(csr_to_dense(k))
    call contact_rows(contact, dofs%n_free, normal_rows, tangent_rows)
    kt_nn_ref = matmul(matmul(normal_rows, k_inverse), transpose(normal_rows))
    kt_nt_ref = matmul(matmul(normal_rows, k_inverse), transpose(tangent_rows))

    call check_blocks()
    call check_tail()
    call check_matrices()
    call check_lift()
    call check_scalars()
    call chol%free()
    ! (AddressSanitizer reports a main program's allocatables)
    deallocate (k_inverse, normal_rows, tangent_rows, kt_nn, kt_nt, kt_nn_ref, kt_nt_ref)
    call t%report()

contains

    subroutine check_blocks()
        type(cholesky_t) :: other
        real(wp), allocatable :: nn(:, :), nt(:, :)
        integer, allocatable :: permutation(:)
        logical :: factored, same
        call factor_stiffness(k, m, dofs, contact, chol, timings, stat)
        call t%check('factor_stiffness: factored, contact-last order given to CHOLMOD', &
                     stat%ok() .and. chol%is_factored() .and. chol%ordering_used() == &
                     ORDERING_GIVEN)
        call contact_flexibility(chol, contact, kt_nn, kt_nt, stat)
        call t%check('contact_flexibility: N K^-1 N'' of the dense inverse', stat%ok() .and. &
                     maxval(abs(kt_nn - kt_nn_ref)) <= TOL*maxval(abs(kt_nn_ref)))
        call t%check('contact_flexibility: N K^-1 T'' of the dense inverse', &
                     maxval(abs(kt_nt - kt_nt_ref)) <= TOL*maxval(abs(kt_nn_ref)))
        call t%check('Kt_nn exactly symmetric', all(abs(kt_nn - transpose(kt_nn)) <= 0.0_wp))
        call factor_contact_blocks(k, m, dofs, contact, other, nn, nt, timings, stat)
        call t%check('factor_contact_blocks: the same blocks, the factor kept', stat%ok() &
                     .and. other%is_factored() .and. all(abs(nn - kt_nn) <= 0.0_wp) .and. &
                     all(abs(nt - kt_nt) <= 0.0_wp))
        call other%free()
        call nested_dissection_last(m, dofs, contact%nodes, permutation, stat)
        call factor_permuted(k, permutation, contact, 'test order', '', 0.0_wp, other, &
                             timings, stat)
        call contact_flexibility(other, contact, nn, nt, stat)
        call t%check('factor_permuted: a given contact-last order, the same blocks', &
                     stat%ok() .and. maxval(abs(nn - kt_nn_ref)) <= TOL*maxval(abs(kt_nn_ref)))
        call other%free()
        call factor_stiffness(k, m, dofs, contact, other, timings, stat, contact_last=.false.)
        factored = stat%ok() .and. other%is_factored()
        call contact_flexibility(other, contact, nn, nt, stat)
        if (stat%ok()) then   ! CHOLMOD's order happened to end with them
            same = maxval(abs(nn - kt_nn_ref)) <= TOL*maxval(abs(kt_nn_ref))
        else
            same = index(stat%message, 'does not end with the contact dofs') > 0
        end if
        call t%check('contact_last = .false.: CHOLMOD''s own order, which contact_tail '// &
                     'refuses unless it ends with the contact dofs', factored .and. same)
        call other%free()
    end subroutine check_blocks

    !> L_c L_c' is the Schur complement S of K onto the contact dofs: S^-1 = K^-1 there.
    subroutine check_tail()
        real(wp), allocatable :: l_tail(:, :), s_inverse(:, :), kt_nn_small(:, :), &
                                 kt_nt_small(:, :)
        integer, allocatable :: slot(:, :), rows(:)
        integer :: a, c
        logical :: covers
        call contact_tail(chol, contact, l_tail, slot, stat)
        covers = size(slot, 2) == contact%p() .and. all(slot >= 1 .and. &
                 slot <= 2*contact%p())
        call t%check('contact_tail: every contact dof has its row of L_c', stat%ok() .and. &
                     covers)
        s_inverse = dense_inverse(matmul(l_tail, transpose(l_tail)))
        rows = [(contact%dofs(:, a), a=1, contact%p())]
        call t%check('contact_tail: (L_c L_c'')^-1 is K^-1 on the contact dofs', &
                     maxval(abs(s_inverse([((slot(c, a), c=1, 2), a=1, contact%p())], &
                     [((slot(c, a), c=1, 2), a=1, contact%p())]) - k_inverse(rows, rows))) &
                     <= TOL*maxval(abs(k_inverse)))
        ! a hand-made block: S = [4 2; 2 5], L = [2 0; 1 2], n = (0, -1), t = (-1, 0):
        ! S^-1 = [5 -2; -2 4]/16, so n' S^-1 n = 1/4 and n' S^-1 t = -1/8
        call flexibility_blocks(reshape([2.0_wp, 1.0_wp, 0.0_wp, 2.0_wp], [2, 2]), &
                                reshape([1, 2], [2, 1]), [0.0_wp, -1.0_wp], [-1.0_wp, 0.0_wp], &
                                kt_nn_small, kt_nt_small, stat)
        call t%check('flexibility_blocks: n'' S^-1 n = 1/4, n'' S^-1 t = -1/8 in closed form', &
                     stat%ok() .and. abs(kt_nn_small(1, 1) - 0.25_wp) <= 1.0e-16_wp .and. &
                     abs(kt_nt_small(1, 1) + 0.125_wp) <= 1.0e-16_wp)
    end subroutine check_tail

    subroutine check_matrices()
        real(wp), allocatable :: a(:, :), scaled(:, :), a_ref(:, :)
        type(reduced_blocks_t) :: blocks
        allocate (a, source=reduced_matrix(kt_nn, kt_nt, contact%mass, LAMBDA))
        allocate (a_ref, source=dense_reduced_matrix(contact, k_inverse, LAMBDA))
        call t%check('reduced_matrix: (lambda Kt_nt - Kt_nn) M of the dense inverse', &
                     maxval(abs(a - a_ref)) <= TOL*maxval(abs(a_ref)))
        allocate (scaled, source=scaled_reduced_matrix(kt_nn, kt_nt, contact%mass, LAMBDA))
        call t%check('scaled_reduced_matrix: A / lambda_unit exactly (a power of two)', &
                     all(abs(scaled*lambda_unit(LAMBDA) - a) <= 0.0_wp))
        blocks%kt_nn = kt_nn
        blocks%kt_nt = kt_nt
        blocks%mass = contact%mass
        call t%check('reduced_blocks_t%matrix: the scaled matrix', &
                     all(abs(blocks%matrix(LAMBDA) - scaled) <= 0.0_wp))
    end subroutine check_matrices

    !> The dense A's eigenpairs (theta, y) lifted: mu = 1/theta with phi solving the pencil.
    subroutine check_lift()
        real(wp), allocatable :: a(:, :), wr(:), wi(:), vr(:, :), work(:), left(:, :), &
                                 residual(:)
        complex(wp), allocatable :: mu(:), y(:, :), vectors(:, :), phi(:)
        integer :: p, info, j
        real(wp) :: worst_direction
        p = contact%p()
        allocate (a, source=reduced_matrix(kt_nn, kt_nt, contact%mass, LAMBDA))
        allocate (wr(p), wi(p), vr(p, p), work(8*p), left(1, 1), mu(p), y(p, p))
        call dgeev('N', 'V', p, a, p, wr, wi, left, 1, vr, p, work, size(work), info)
        do j = 1, p
            mu(j) = 1.0_wp/cmplx(wr(j), wi(j), wp)
            y(:, j) = lapack_eigenvector(vr, wi, j)
        end do
        call lift_eigenvectors(k, b, chol, contact, LAMBDA, mu, y, 3, residual, vectors, stat)
        call t%check('lift_eigenvectors: every pair (real and complex) solves K phi = mu '// &
                     'B phi to 1e-12', stat%ok() .and. size(residual) == p .and. &
                     maxval(residual) <= 1.0e-12_wp .and. any(abs(wi) > 0.0_wp))
        ! the kept modes: phi = K^-1 (lambda T' - N') M y up to the normalisation
        worst_direction = 0.0_wp
        do j = 1, 3
            allocate (phi(dofs%n_free))
            phi = cmplx(matmul(k_inverse, matmul(transpose(LAMBDA*tangent_rows - &
                  normal_rows), matmul(contact%mass_dense(), real(y(:, j), wp)))), &
                  matmul(k_inverse, matmul(transpose(LAMBDA*tangent_rows - normal_rows), &
                  matmul(contact%mass_dense(), aimag(y(:, j))))), wp)
            call normalise_mode(phi)
            worst_direction = max(worst_direction, maxval(abs(vectors(:, j) - phi)))
            deallocate (phi)
        end do
        call t%check('lift_eigenvectors: the first 3 kept, each the dense K^-1 (lambda T'' '// &
                     '- N'') M y normalised', size(vectors, 2) == 3 .and. &
                     worst_direction <= 1.0e-10_wp)
        mu(1) = mu(1)*1.5_wp
        call lift_eigenvectors(k, b, chol, contact, LAMBDA, mu(1:1), y(:, 1:1), 1, residual, &
                               vectors, stat)
        call t%check('lift_eigenvectors: a wrong mu has a large backward error', &
                     residual(1) > 1.0e-3_wp)
    end subroutine check_lift

    subroutine check_scalars()
        call t%check('lambda_unit: a power of two 2^c with |lambda|/2^c in [1, 2), else 1', &
                     abs(lambda_unit(5.0_wp) - 4.0_wp) <= 0.0_wp .and. &
                     abs(lambda_unit(-5.0_wp) - 4.0_wp) <= 0.0_wp .and. &
                     abs(lambda_unit(0.3_wp) - 1.0_wp) <= 0.0_wp .and. &
                     abs(lambda_unit(1.0e300_wp) - 2.0_wp**996) <= 0.0_wp)
        call t%check('mu_of_theta: (1/theta)/unit, real and complex', &
                     abs(mu_of_theta(0.25_wp, 4.0_wp) - 1.0_wp) <= 0.0_wp .and. &
                     abs(mu_of_theta((0.0_wp, 0.5_wp), 2.0_wp) - (0.0_wp, -1.0_wp)) <= 0.0_wp)
        ! 256 MiB of columns: 64 of 2e5 dofs, 15 of 2.1e6, never fewer than 8
        call t%check('lift_block_columns: 64 at most, BLOCK_BYTES / (8 n), 8 at least', &
                     lift_block_columns(10) == 64 .and. lift_block_columns(2100000) == 15 &
                     .and. lift_block_columns(100000000) == 8)
    end subroutine check_scalars
end program test_contact_reduction
