! SPDX-License-Identifier: MIT
!> Free-dof numbering: Dirichlet parts fix whole nodes, the rest are numbered node by node.
program test_dof_map
    use status, only: status_t, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q2
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map, cell_dofs
    use kinds, only: wp
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t
    type(mesh_t) :: m
    type(dof_map_t) :: dofs
    type(status_t) :: stat
    integer :: node

    t%name = 'test_dof_map'
    ! 2 x 2 P1 squares: 3 x 3 nodes, numbered row by row from the bottom.
    call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
    call build_dof_map(m, [m%part_index('top')], dofs, stat)
    call t%check('top clamped: ok', stat%ok())
    call t%check('one dof per component of the mesh''s dimension at each node', &
                 dofs%dim() == m%dim() .and. size(dofs%free_dof, 1) == 2)
    call t%check('top clamped: the top row (nodes 7-9) fixed', all(dofs%free_dof(:, 7:9) == 0))
    call t%check('top clamped: 12 free dofs numbered node by node, x then y', &
                 dofs%n_free == 12 .and. all(reshape(dofs%free_dof(:, 1:6), [12]) == &
                                             [(node, node=1, 12)]))
    ! Cell 1 of the 'right' mesh is nodes 1, 2, 5.
    call t%check('cell_dofs in element order (u_x1, u_y1, ...)', &
                 all(cell_dofs(dofs, m, 1) == [1, 2, 3, 4, 9, 10]))
    ! Cell 8 is nodes 5, 9, 8: the last two are on the top side.
    call t%check('cell_dofs gives 0 for fixed dofs', &
                 all(cell_dofs(dofs, m, 8) == [9, 10, 0, 0, 0, 0]))

    call build_dof_map(m, [m%part_index('bottom'), m%part_index('left')], dofs, stat)
    call t%check('bottom + left clamped: 5 nodes fixed, corner counted once', &
                 stat%ok() .and. dofs%n_free == 2*(9 - 5))

    ! Q2: the mid node of each clamped edge is fixed too.
    call structured_rectangle(1.0_wp, 1.0_wp, 1, 1, ELEMENT_Q2, 'right', m, stat)
    call build_dof_map(m, [m%part_index('right')], dofs, stat)
    call t%check('Q2 right side clamped: nodes 3, 6, 9 fixed', &
                 all(dofs%free_dof(:, [3, 6, 9]) == 0) .and. dofs%n_free == 12)

    call build_dof_map(m, [0], dofs, stat)
    call t%check('part index 0 is bad input', stat%code == STATUS_BAD_INPUT)
    call build_dof_map(m, [5], dofs, stat)
    call t%check('part index 5 of 4 is bad input, named', stat%code == STATUS_BAD_INPUT &
                 .and. index(stat%message, '5') > 0)
    call t%report()
end program test_dof_map
