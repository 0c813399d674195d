! SPDX-License-Identifier: MIT
!> The Cholesky ordering of K with chosen nodes last: a permutation of the free dofs, each
!> node's dofs together (x then y), the chosen nodes' dofs last in their order, the nodes
!> of higher-order cells eliminated just before the first-ordered corner of their side or
!> cell; and it reduces fill: the factor of K on a 32 x 32 grid has fewer entries in this
!> order than in the generator's row-by-row (banded) numbering.
program test_node_ordering
    use kinds, only: wp, i8
    use status, only: status_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P3, ELEMENT_Q2, element_name, &
                             element_corners, element_degree
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use csr_matrix, only: csr_matrix_t
    use contact_boundary, only: contact_t, build_contact
    use sparse_cholesky, only: cholesky_t, ORDERING_GIVEN, ORDERING_NATURAL
    use node_ordering, only: nested_dissection_last
    use fixtures, only: is_permutation
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_node_ordering'
    call check_ordering(ELEMENT_P1, 6)
    call check_ordering(ELEMENT_P3, 4)
    call check_ordering(ELEMENT_Q2, 4)
    call check_fill()
    call t%report()

contains

    !> The reference scene (top clamped, contact on the bottom) on n x n cells.
    subroutine scene(element, n, m, dofs, contact)
        integer, intent(in) :: element, n
        type(mesh_t), intent(out) :: m
        type(dof_map_t), intent(out) :: dofs
        type(contact_t), intent(out) :: contact
        type(status_t) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, n, n, element, 'right', m, stat)
        if (stat%ok()) call build_dof_map(m, [m%part_index('top')], dofs, stat)
        if (stat%ok()) call build_contact(m, m%part_index('bottom'), dofs, contact, stat)
    end subroutine scene

    subroutine check_ordering(element, n)
        integer, intent(in) :: element, n
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(status_t) :: stat
        integer, allocatable :: permutation(:), position(:), last(:)
        integer :: p, node, c, a, side, corners, inner, first
        logical :: together, before
        character(len=:), allocatable :: label
        label = ' ('//element_name(element)//')'
        call scene(element, n, m, dofs, contact)
        call nested_dissection_last(m, dofs, contact%nodes, permutation, stat)
        call t%check('a permutation of the free dofs'//label, stat%ok() .and. &
                     is_permutation(permutation, dofs%n_free))
        p = contact%p()
        allocate (last(2*p))   ! (gfortran 12 -O3 warns of an unallocated one)
        last = [(contact%dofs(:, a), a=1, p)]
        call t%check('the contact dofs last, in their order, x then y'//label, &
                     all(permutation(dofs%n_free - 2*p + 1:) == last))
        allocate (position(dofs%n_free))
        position(permutation) = [(a, a=1, dofs%n_free)]
        together = .true.
        do node = 1, m%n_nodes()
            if (all(dofs%free_dof(:, node) > 0)) together = together .and. &
                position(dofs%free_dof(2, node)) == position(dofs%free_dof(1, node)) + 1
        end do
        call t%check('each node''s dofs together'//label, together)
        ! a side or interior node before every free corner of its side or cell that is
        ! not forced last
        corners = element_corners(element)
        inner = element_degree(element) - 1
        before = .true.
        do c = 1, m%n_cells()
            do a = corners + 1, size(m%cells, 1)
                node = m%cells(a, c)
                if (dofs%free_dof(1, node) == 0 .or. any(contact%nodes == node)) cycle
                side = (a - corners - 1)/max(inner, 1) + 1
                if (side <= corners) then
                    first = earliest([m%cells(side, c), m%cells(mod(side, corners) + 1, c)], &
                                     dofs, contact, position)
                else
                    first = earliest(m%cells(1:corners, c), dofs, contact, position)
                end if
                before = before .and. position(dofs%free_dof(1, node)) < first
            end do
        end do
        call t%check('side and interior nodes just before the first of their corners'//label, &
                     before)

    end subroutine check_ordering

    !> The first position of the free, not-last corners among `nodes` (huge if none).
    integer function earliest(nodes, dofs, contact, position)
        integer, intent(in) :: nodes(:)
        type(dof_map_t), intent(in) :: dofs
        type(contact_t), intent(in) :: contact
        integer, intent(in) :: position(:)
        integer :: k
        earliest = huge(1)
        do k = 1, size(nodes)
            if (dofs%free_dof(1, nodes(k)) == 0 .or. any(contact%nodes == nodes(k))) cycle
            earliest = min(earliest, position(dofs%free_dof(1, nodes(k))))
        end do
    end function earliest

    !> nnz(L) with nested dissection against the banded numbering of the generator.
    subroutine check_fill()
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: k
        type(cholesky_t) :: chol
        type(status_t) :: stat
        integer, allocatable :: permutation(:)
        integer(i8) :: nested, banded
        call scene(ELEMENT_P1, 32, m, dofs, contact)
        call assemble_stiffness(m, dofs, 1.0_wp, 0.3_wp, k, stat)
        call nested_dissection_last(m, dofs, contact%nodes, permutation, stat)
        call chol%factor(k, stat, ordering=ORDERING_GIVEN, permutation=permutation, &
                         keep_last=2*contact%p())
        nested = chol%factor_nnz()
        call chol%factor(k, stat, ordering=ORDERING_NATURAL)
        banded = chol%factor_nnz()
        call chol%free()
        call t%check('32 x 32 P1: fewer factor entries than the banded numbering', &
                     stat%ok() .and. nested > 0 .and. nested < banded)
    end subroutine check_fill
end program test_node_ordering
