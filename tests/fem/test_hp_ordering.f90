! SPDX-License-Identifier: MIT
!> The Cholesky ordering of an hp space with the contact functions last: a permutation of
!> the free dofs, each function's two dofs together, the chosen functions' dofs last in
!> their order (so the factor's trailing block is K's Schur complement onto them: checked
!> against K^-1 by a solve), and a clamped function refused.
program test_hp_ordering
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use mesh_structured, only: structured_rectangle
    use hp_space, only: hp_space_t, build_hp_space
    use hp_stiffness, only: assemble_hp_stiffness
    use hp_contact, only: build_hp_contact
    use hp_ordering, only: hp_cholesky_permutation
    use contact_boundary, only: contact_t
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t, ORDERING_GIVEN
    use fixtures, only: is_permutation
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t
    type(mesh_t) :: m
    type(hp_space_t) :: space
    type(contact_t) :: contact
    type(csr_matrix_t) :: k
    type(cholesky_t) :: chol
    type(status_t) :: stat
    integer, allocatable :: permutation(:), position(:), last(:), degree(:), rows(:)
    real(wp), allocatable :: l_tail(:, :), e(:, :), x(:, :), inverse(:, :)
    integer :: c, f, n_free, np, i
    logical :: together

    t%name = 'test_hp_ordering'
    call structured_rectangle(1.0_wp, 1.0_wp, 4, 4, ELEMENT_P1, 'right', m, stat)
    degree = [(1 + mod(c, 4), c=1, m%n_cells())]   ! degrees 1 to 4
    call build_hp_space(m, degree, [m%part_index('top')], space, stat)
    call build_hp_contact(m, space, m%part_index('bottom'), contact, stat)
    call hp_cholesky_permutation(m, space, contact%nodes, permutation, stat)
    n_free = space%n_free()
    call t%check('a permutation of the free dofs', stat%ok() .and. &
                 is_permutation(permutation, n_free))
    np = 2*contact%p()
    last = [(contact%dofs(:, c), c=1, contact%p())]
    call t%check('the contact functions'' dofs last, in their order', &
                 all(permutation(n_free - np + 1:) == last))
    allocate (position(n_free))
    position(permutation) = [(i, i=1, n_free)]
    together = .true.
    do f = 1, space%n_functions
        if (space%free_function(f) > 0) together = together .and. &
            position(2*space%free_function(f)) == position(2*space%free_function(f) - 1) + 1
    end do
    call t%check('each function''s dofs together, x then y', together)

    ! the trailing block L_c of the factor in this order: L_c^-T L_c^-1 = (K^-1) on them
    call assemble_hp_stiffness(m, space, 1.0_wp, 0.3_wp, k, stat)
    call chol%factor(k, stat, ordering=ORDERING_GIVEN, permutation=permutation, keep_last=np)
    call chol%trailing_block(np, l_tail, rows, stat)
    allocate (e(n_free, np), source=0.0_wp)
    allocate (x(n_free, np))
    do i = 1, np
        e(last(i), i) = 1.0_wp
    end do
    call chol%solve(e, x, stat)
    inverse = l_tail_inverse(l_tail)
    call t%check('the factor ends with them: its trailing block inverts to K^-1 there '// &
                 '(to 1e-10 of its largest entry)', stat%ok() .and. all(rows == last) .and. &
                 maxval(abs(inverse - x(last, :))) <= 1.0e-10_wp*maxval(abs(inverse)))
    call chol%free()

    call build_hp_space(m, degree, [m%part_index('top'), m%part_index('bottom')], space, stat)
    call hp_cholesky_permutation(m, space, contact%nodes, permutation, stat)
    call t%check('a clamped function to pivot last is refused', stat%code == STATUS_BAD_INPUT)
    ! (AddressSanitizer reports a main program's allocatables)
    deallocate (position, last, degree, rows, l_tail, e, x, inverse)
    if (allocated(permutation)) deallocate (permutation)
    call t%report()

contains

    !> (L L')^-1 of a lower triangle, densely.
    function l_tail_inverse(l) result(inverse)
        real(wp), intent(in) :: l(:, :)
        real(wp), allocatable :: inverse(:, :)
        real(wp), allocatable :: y(:, :)
        integer :: n, j
        n = size(l, 1)
        allocate (y(n, n), source=0.0_wp)
        do j = 1, n
            y(j, j) = 1.0_wp
        end do
        do j = 1, n   ! Y = L^-1 by forward substitution, row by row
            ! (no product with the empty row 1: UBSan flags gfortran's bounds of it)
            if (j > 1) y(j, :) = y(j, :) - matmul(l(j, 1:j - 1), y(1:j - 1, :))
            y(j, :) = y(j, :)/l(j, j)
        end do
        inverse = matmul(transpose(y), y)
    end function l_tail_inverse
end program test_hp_ordering
