! SPDX-License-Identifier: MIT
!> The hp space counts its functions as the closed formula says: on a triangle mesh of V
!> vertices, E edges and T cells with degree p everywhere, V + E (p - 1) vertex and edge
!> functions and T (p - 1)(p - 2)/2 interior ones, together the (p n + 1)^2 nodes of the
!> P_p grid of the same n x n squares; a clamped side removes its vertices' and edges'
!> functions; an edge takes the smaller degree of its two cells (the minimum rule).
program test_hp_space
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P2, ELEMENT_P3, ELEMENT_P4
    use mesh_structured, only: structured_rectangle
    use hp_basis, only: hp_bubble_count, MAX_HP_DEGREE
    use hp_space, only: hp_space_t, build_hp_space
    use testing, only: test_suite_t
    implicit none

    integer, parameter :: N = 3   !! 3 x 3 squares, each two triangles
    integer, parameter :: LAGRANGE_TRIANGLES(4) = [ELEMENT_P1, ELEMENT_P2, ELEMENT_P3, ELEMENT_P4]
    type(test_suite_t) :: t
    type(mesh_t) :: m
    type(status_t) :: stat
    integer :: p

    t%name = 'test_hp_space'
    call structured_rectangle(1.0_wp, 1.0_wp, N, N, ELEMENT_P1, 'right', m, stat)
    do p = 1, 6
        call check_uniform(p)
    end do
    call check_mixed()
    call check_errors()
    call t%report()

contains

    subroutine check_uniform(p)
        integer, intent(in) :: p
        type(hp_space_t) :: space, clamped
        type(mesh_t) :: lagrange
        integer :: v, e, cells, c, k
        integer, allocatable :: functions(:), dofs(:)
        logical :: consistent
        character(len=8) :: label
        write (label, '(a, i0, a)') ' (p = ', p, ')'
        call build_hp_space(m, [(p, c=1, m%n_cells())], [integer ::], space, stat)
        v = (N + 1)**2
        cells = 2*N*N
        e = v + cells - 1   ! Euler's formula for a disc: V - E + T = 1
        call t%check('V + E (p - 1) vertex and edge functions, E = V + T - 1'//trim(label), &
                     stat%ok() .and. space%n_vertices == v .and. space%n_edges() == e .and. &
                     space%n_functions == v + e*(p - 1) .and. space%n_free() == &
                     2*space%n_functions)
        ! the same count as the nodes of the Lagrange grid of degree p (p <= 4 exists here)
        if (p <= 4) then
            call structured_rectangle(1.0_wp, 1.0_wp, N, N, LAGRANGE_TRIANGLES(p), 'right', &
                                      lagrange, stat)
            call t%check('with the T (p-1)(p-2)/2 interior ones: the (p n + 1)^2 nodes of '// &
                         'the P_p grid'//trim(label), space%n_functions + &
                         cells*hp_bubble_count(p) == (p*N + 1)**2 .and. &
                         lagrange%n_nodes() == (p*N + 1)**2)
        end if
        call build_hp_space(m, [(p, c=1, m%n_cells())], [m%part_index('top')], clamped, stat)
        call t%check('the top clamped: its N + 1 vertices and N (p - 1) edge functions '// &
                     'gone'//trim(label), stat%ok() .and. clamped%n_free() == &
                     2*(space%n_functions - (N + 1) - N*(p - 1)))
        call t%check('max_cell_dofs: 2 (3 + 3 (p - 1))'//trim(label), &
                     space%max_cell_dofs() == 2*(3 + 3*(p - 1)))
        consistent = .true.
        do c = 1, m%n_cells()
            functions = space%cell_functions(c, m%cells(1:3, c))
            dofs = clamped%cell_dofs(c, m%cells(1:3, c))
            consistent = consistent .and. size(functions) == 3 + 3*(p - 1) .and. &
                         all(functions(1:3) == m%cells(1:3, c)) .and. &
                         size(dofs) == 2*size(functions) .and. &
                         all(space%edge_degrees_of(c) == p)
            do k = 1, size(functions)
                if (clamped%free_function(functions(k)) == 0) then
                    consistent = consistent .and. all(dofs(2*k - 1:2*k) == 0)
                else
                    consistent = consistent .and. all(dofs(2*k - 1:2*k) == &
                        [2*clamped%free_function(functions(k)) - 1, &
                         2*clamped%free_function(functions(k))])
                end if
            end do
            ! edge k runs between corners k and k + 1, flipped when k + 1 is the lower
            do k = 1, 3
                consistent = consistent .and. all(space%edge_ends(:, space%cell_edge(k, c)) == &
                    [minval(m%cells([k, mod(k, 3) + 1], c)), &
                     maxval(m%cells([k, mod(k, 3) + 1], c))]) .and. &
                    (space%cell_flip(k, c) .eqv. m%cells(k, c) > m%cells(mod(k, 3) + 1, c))
            end do
        end do
        call t%check('cell_functions and cell_dofs: vertices first, (x, y) of each free '// &
                     'function, 0 where clamped; edges and their directions'//trim(label), &
                     consistent)
    end subroutine check_uniform

    !> Degrees 2 and 5 in alternate cells: every edge between them has degree 2.
    subroutine check_mixed()
        type(hp_space_t) :: space
        integer, allocatable :: degree(:)
        integer :: c, e, edge_cells, n_interior
        logical :: minimum
        allocate (degree(m%n_cells()))   ! (gfortran 12 -O3 warns of an unallocated one)
        degree = [(merge(2, 5, mod(c, 2) == 1), c=1, m%n_cells())]
        call build_hp_space(m, degree, [integer ::], space, stat)
        minimum = .true.
        n_interior = 0
        do e = 1, space%n_edges()
            edge_cells = 0
            do c = 1, m%n_cells()
                if (any(space%cell_edge(:, c) == e)) then
                    edge_cells = edge_cells + 1
                    minimum = minimum .and. space%edge_degree(e) <= degree(c)
                end if
            end do
            if (edge_cells == 2) n_interior = n_interior + 1
        end do
        call t%check('mixed degrees: each edge no higher than either of its cells', &
                     stat%ok() .and. minimum)
        call t%check('mixed degrees: the function count from the edge degrees', &
                     space%n_functions == space%n_vertices + sum(space%edge_degree - 1) .and. &
                     all(space%edge_degree == 2 .or. space%edge_degree == 5) .and. &
                     count(space%edge_degree == 5) > 0 .and. n_interior > 0)
    end subroutine check_mixed

    subroutine check_errors()
        type(hp_space_t) :: space
        type(mesh_t) :: quadratic
        integer :: c
        call structured_rectangle(1.0_wp, 1.0_wp, N, N, ELEMENT_P2, 'right', quadratic, stat)
        call build_hp_space(quadratic, [(2, c=1, quadratic%n_cells())], [integer ::], space, &
                            stat)
        call t%check('a P2 mesh is refused', stat%code == STATUS_BAD_INPUT)
        call build_hp_space(m, [(2, c=1, m%n_cells() - 1)], [integer ::], space, stat)
        call t%check('one degree too few is refused', stat%code == STATUS_BAD_INPUT)
        call build_hp_space(m, [(MAX_HP_DEGREE + 1, c=1, m%n_cells())], [integer ::], space, &
                            stat)
        call t%check('a degree above MAX_HP_DEGREE is refused', stat%code == STATUS_BAD_INPUT)
        call build_hp_space(m, [(0, c=1, m%n_cells())], [integer ::], space, stat)
        call t%check('degree 0 is refused', stat%code == STATUS_BAD_INPUT)
        call build_hp_space(m, [(2, c=1, m%n_cells())], [9], space, stat)
        call t%check('a Dirichlet part that is none is refused', stat%code == STATUS_BAD_INPUT)
    end subroutine check_errors
end program test_hp_space
