! SPDX-License-Identifier: MIT
!> csr_matrix against brute-force dense equivalents on a small made-up connectivity.
program test_csr_matrix
    use kinds, only: wp
    use status, only: status_t, STATUS_INTERNAL
    use csr_matrix, only: csr_matrix_t, csr_from_element_dofs
    use testing, only: test_suite_t
    use fixtures, only: to_dense => csr_to_dense
    implicit none

    real(wp), parameter :: EPS = epsilon(1.0_wp)
    integer, parameter :: N = 8   ! dof 8 belongs to no element: its row stays empty
    ! Five 3-dof elements; 0 marks an eliminated (Dirichlet) dof and couples to nothing.
    integer, parameter :: ELEMENT_DOFS(3, 5) = reshape([1, 2, 0, &
                                                        2, 3, 4, &
                                                        0, 5, 6, &
                                                        6, 7, 1, &
                                                        3, 0, 0], [3, 5])
    type(test_suite_t) :: t
    type(csr_matrix_t) :: a, known
    type(status_t) :: stat
    logical :: pattern(N, N), sorted_unique, same_pattern, slots_ok
    real(wp) :: dense(N, N), block(3, 3), x(N), y(N), bound(N)
    integer :: e, i, j, k

    t%name = 'test_csr_matrix'

    ! Brute force: dofs i and j are coupled when some element holds both.
    pattern = .false.
    do e = 1, size(ELEMENT_DOFS, 2)
        do j = 1, 3
            do i = 1, 3
                if (ELEMENT_DOFS(i, e) > 0 .and. ELEMENT_DOFS(j, e) > 0) &
                    pattern(ELEMENT_DOFS(i, e), ELEMENT_DOFS(j, e)) = .true.
            end do
        end do
    end do

    call csr_from_element_dofs(N, ELEMENT_DOFS, a)
    call t%check('n is the number of dofs', a%n() == N)
    call t%check('nnz equals the dense pattern count', a%nnz() == count(pattern))
    sorted_unique = .true.
    same_pattern = .true.
    do i = 1, N
        associate (row => a%col(a%row_start(i):a%row_start(i + 1) - 1))
            if (size(row) > 1) &
                sorted_unique = sorted_unique .and. all(row(2:) > row(:size(row) - 1))
            same_pattern = same_pattern .and. size(row) == count(pattern(i, :))
            if (size(row) == count(pattern(i, :))) &
                same_pattern = same_pattern .and. all(row == pack([(j, j = 1, N)], pattern(i, :)))
        end associate
    end do
    call t%check('columns are sorted and unique in every row', sorted_unique)
    call t%check('the CSR pattern equals the brute-force dense pattern', same_pattern)
    call t%check('the unused dof has an empty row', a%row_start(N + 1) == a%row_start(N))
    call t%check('values start at zero', all(abs(a%val) <= 0.0_wp))

    slots_ok = .true.
    do j = 1, N
        do i = 1, N
            k = a%slot(i, j)
            if (pattern(i, j)) then
                slots_ok = slots_ok .and. k > 0
                if (k > 0) slots_ok = slots_ok .and. a%col(k) == j .and. &
                    k >= a%row_start(i) .and. k < a%row_start(i + 1)
            else
                slots_ok = slots_ok .and. k == 0
            end if
        end do
    end do
    call t%check('slot finds every pattern entry and returns 0 outside it', slots_ok)

    ! Assemble non-symmetric element blocks both ways.
    dense = 0.0_wp
    do e = 1, size(ELEMENT_DOFS, 2)
        block = reshape([((e + 0.1_wp*i + 0.01_wp*j, i = 1, 3), j = 1, 3)], [3, 3])
        call a%add_block(ELEMENT_DOFS(:, e), block, stat)
        do j = 1, 3
            do i = 1, 3
                if (ELEMENT_DOFS(i, e) > 0 .and. ELEMENT_DOFS(j, e) > 0) &
                    dense(ELEMENT_DOFS(i, e), ELEMENT_DOFS(j, e)) = &
                    dense(ELEMENT_DOFS(i, e), ELEMENT_DOFS(j, e)) + block(i, j)
            end do
        end do
    end do
    call t%check('add_block succeeds inside the pattern', stat%ok())
    ! Both assemblies add the same terms in the same order, so they agree to the last bit;
    ! a couple of ulps are allowed in case the compiler reassociates.
    call t%check('add_block equals the dense assembly', &
                 all(abs(to_dense(a) - dense) <= 2.0_wp*EPS*abs(dense)))

    x = [(0.5_wp*i - 1.0_wp, i = 1, N)]
    call a%matvec(x, y)
    ! A dot product of at most N terms: |error| <= N eps sum |a_ij x_j|.
    bound = N*EPS*matmul(abs(dense), abs(x))
    call t%check('matvec equals the dense product', all(abs(y - matmul(dense, x)) <= bound))

    call a%add_to(1, 5, 1.0_wp, stat)
    call t%check('add_to outside the pattern is an internal error', &
                 stat%code == STATUS_INTERNAL)

    ! [1 -2 0; 0 0 3; -4 0 5]: absolute row sums 3, 3, 9.
    known%row_start = [1, 3, 4, 6]
    known%col = [1, 2, 3, 1, 3]
    known%val = [1.0_wp, -2.0_wp, 3.0_wp, -4.0_wp, 5.0_wp]
    call t%check_close('norm_inf of a known matrix is 9', known%norm_inf(), 9.0_wp, 0.0_wp)
    call t%check('slot(2, 1) of the known matrix is 0', known%slot(2, 1) == 0)
    call t%check('slot(3, 3) of the known matrix is 5', known%slot(3, 3) == 5)
    call t%report()

contains
end program test_csr_matrix
