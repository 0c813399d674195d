! SPDX-License-Identifier: MIT
!> The element table against the counting formulas of Lagrange elements of degree p: a
!> triangle has (p + 1)(p + 2)/2 nodes, a tensor quadrilateral (p + 1)^2, an edge p + 1;
!> the triangle's lattice holds every barycentric index (i1, i2, i3) with sum p exactly
!> once, corners first, then p - 1 nodes per edge from corner k towards corner k + 1.
program test_element_types
    use element_types, only: element_nodes_per_cell, element_nodes_per_edge, &
                             element_from_name, element_name, element_corners, &
                             element_degree, element_dimension, triangle_lattice, &
                             ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, MAX_ELEMENT
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t
    integer :: element

    t%name = 'test_element_types'
    do element = 1, MAX_ELEMENT
        call check_counts(element)
    end do
    do element = ELEMENT_P1, MAX_ELEMENT
        if (element_corners(element) == 3) call check_lattice(element)
    end do
    call t%check('unknown codes: 0 nodes, degree 0, dimension 0, name ??', &
                 element_nodes_per_cell(0) == 0 .and. element_nodes_per_cell(MAX_ELEMENT + 1) &
                 == 0 .and. element_degree(0) == 0 .and. element_nodes_per_edge(0) == 0 .and. &
                 element_dimension(0) == 0 .and. element_name(MAX_ELEMENT + 1) == '??')
    call t%check('element_from_name: unknown names give 0', element_from_name('p5') == 0 &
                 .and. element_from_name('P1') == 0 .and. element_from_name('') == 0)
    call t%check('the codes are 1 to MAX_ELEMENT', all([ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, &
                 ELEMENT_Q2, ELEMENT_P3, ELEMENT_P4] == [1, 2, 3, 4, 5, 6]) .and. MAX_ELEMENT == 6)
    call t%report()

contains

    subroutine check_counts(element)
        integer, intent(in) :: element
        integer :: p, corners, expected
        character(len=2) :: name
        character(len=:), allocatable :: label
        name = element_name(element)
        label = ' ('//name//')'
        p = element_degree(element)
        corners = element_corners(element)
        if (corners == 3) then
            expected = (p + 1)*(p + 2)/2
        else
            expected = (p + 1)**2
        end if
        call t%check('nodes per cell from the degree'//label, p >= 1 .and. p <= 4 .and. &
                     element_nodes_per_cell(element) == expected)
        call t%check('nodes per edge p + 1'//label, element_nodes_per_edge(element) == p + 1)
        call t%check('name and code round-trip'//label, &
                     element_from_name(element_name(element)) == element)
        call t%check('a plane element: dimension 2, 3 or 4 corners'//label, &
                     element_dimension(element) == 2 .and. (corners == 3 .or. corners == 4) &
                     .and. ((corners == 4) .eqv. (name(1:1) == 'q')))
    end subroutine check_counts

    subroutine check_lattice(element)
        integer, intent(in) :: element
        integer :: lattice(3, 20), p, n, a, b, k, i
        logical :: distinct, on_edges
        character(len=:), allocatable :: label
        label = ' ('//element_name(element)//')'
        p = element_degree(element)
        n = element_nodes_per_cell(element)
        lattice = -1
        call triangle_lattice(element, lattice)
        call t%check('lattice indices are >= 0 and sum to p'//label, &
                     all(lattice(:, 1:n) >= 0) .and. all(sum(lattice(:, 1:n), dim=1) == p))
        distinct = .true.
        do a = 1, n
            do b = a + 1, n
                distinct = distinct .and. any(lattice(:, a) /= lattice(:, b))
            end do
        end do
        call t%check('lattice nodes distinct: all (p+1)(p+2)/2 of them'//label, distinct)
        call t%check('columns beyond the nodes are zero'//label, all(lattice(:, n + 1:) == 0))
        call t%check('corners first, anticlockwise: p e_1, p e_2, p e_3'//label, &
                     all(lattice(:, 1) == [p, 0, 0]) .and. all(lattice(:, 2) == [0, p, 0]) &
                     .and. all(lattice(:, 3) == [0, 0, p]))
        ! edge k (corner k to k + 1): index of corner k falls by one per node, k + 1's rises
        on_edges = .true.
        do k = 1, 3
            do i = 1, p - 1
                a = 3 + (k - 1)*(p - 1) + i
                on_edges = on_edges .and. lattice(k, a) == p - i .and. &
                           lattice(mod(k, 3) + 1, a) == i
            end do
        end do
        call t%check('p - 1 nodes per edge, from corner k towards corner k + 1'//label, on_edges)
        call t%check('interior nodes have every index >= 1'//label, &
                     all(lattice(:, 3*p + 1:n) >= 1))
    end subroutine check_lattice
end program test_element_types
