! SPDX-License-Identifier: MIT
!> mesh_t's own procedures: its counts from its arrays, its dimension from its element,
!> its parts found by name, and the completeness a writer or a refinement requires (every
!> array there, the coordinates of the mesh's dimension).
program test_mesh
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q2, MAX_ELEMENT, element_dimension
    use mesh_structured, only: structured_rectangle
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t
    type(mesh_t) :: m, empty
    type(status_t) :: stat
    integer :: element
    logical :: dims

    t%name = 'test_mesh'
    call t%check('an empty mesh: no nodes, no cells, part 0 for any name', &
                 empty%n_nodes() == 0 .and. empty%n_cells() == 0 .and. &
                 empty%part_index('bottom') == 0)
    call empty%require_complete('writer', stat)
    call t%check('require_complete: an empty mesh is bad input of the caller named', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'writer:') == 1)

    ! 3 x 2 Q2 squares: (2*3 + 1) x (2*2 + 1) nodes
    call structured_rectangle(1.5_wp, 1.0_wp, 3, 2, ELEMENT_Q2, 'right', m, stat)
    call t%check('counts from the arrays: 35 nodes, 6 cells', m%n_nodes() == 35 .and. &
                 m%n_cells() == 6)
    call t%check('part_index: the four sides by name, 0 for another', &
                 m%part_index('bottom') > 0 .and. m%part_index('top') > 0 .and. &
                 m%part_index('left') > 0 .and. m%part_index('right') > 0 .and. &
                 m%part_index('middle') == 0 .and. m%part_index('bottom') /= m%part_index('top'))
    call m%require_complete('writer', stat)
    call t%check('require_complete: a generated mesh is complete', stat%ok())

    dims = .true.
    do element = ELEMENT_P1, MAX_ELEMENT
        m%element = element
        dims = dims .and. m%dim() == element_dimension(element) .and. m%dim() == 2
    end do
    call t%check('dim: the dimension of its element, 2 for every element', dims)

    call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
    m%coords = reshape([m%coords, m%coords(1, :)], [3, m%n_nodes()])
    call m%require_complete('writer', stat)
    call t%check('require_complete: three coordinates for a plane element are refused, '// &
                 'naming both counts', stat%code == STATUS_BAD_INPUT .and. &
                 index(stat%message, '3 coordinates') > 0 .and. index(stat%message, 'p1') > 0)
    call t%report()
end program test_mesh
