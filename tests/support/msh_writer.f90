! SPDX-License-Identifier: MIT
!> MSH 4.1 and MSH 2.2 files of a structured mesh, for the tests of the Gmsh reader (the
!> reader's round trip and the seeds of its fuzz test).
module msh_writer
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4
    use strings, only: to_string
    implicit none
    private
    public :: write_msh41, write_msh22

    ! Gmsh element type codes and the body's physical tag, as the files written here use.
    integer, parameter :: GMSH_TYPES(6) = [2, 3, 9, 10, 21, 23]   !! P1, Q1, P2, Q2, P3, P4
    !> Line types by nodes per edge: 2, 3, 4, 5.
    integer, parameter :: GMSH_LINE_TYPES(2:5) = [1, 8, 26, 27]
    integer, parameter :: BODY_TAG = 5
    ! Node tags in the written files: sparse and not in node order, so that the reader's
    ! tag lookup (not a shortcut for 1..n) is exercised.
    integer, parameter :: TAG_STRIDE = 7, TAG_OFFSET = 1000

contains

    !> Tag of node `node` in the written files.
    elemental integer function node_tag(node)
        integer, intent(in) :: node
        node_tag = TAG_OFFSET + TAG_STRIDE*node
    end function node_tag

    !> Node order of a cell written clockwise (the inverse of the reader's reorientation).
    pure function clockwise_order(element) result(order)
        integer, intent(in) :: element
        integer, allocatable :: order(:)
        select case (element)
        case (ELEMENT_P1); order = [1, 3, 2]
        case (ELEMENT_Q1); order = [1, 4, 3, 2]
        case (ELEMENT_P2); order = [1, 3, 2, 6, 5, 4]
        case (ELEMENT_Q2); order = [1, 4, 3, 2, 8, 7, 6, 5, 9]
        ! Edges reversed and in reverse order; the interior nodes next to corners 2 and 3
        ! swap places (P4).
        case (ELEMENT_P3); order = [1, 3, 2, 9, 8, 7, 6, 5, 4, 10]
        case (ELEMENT_P4); order = [1, 3, 2, 12, 11, 10, 9, 8, 7, 6, 5, 4, 13, 15, 14]
        end select
    end function clockwise_order

    !> MSH 4.1 of a structured mesh: nodes in reverse order in one surface block, the four
    !> sides as curves 1-4 in physical groups 1-4, the body surface in group 5.
    subroutine write_msh41(path, m, clockwise)
        character(len=*), intent(in) :: path
        type(mesh_t), intent(in) :: m
        logical, intent(in) :: clockwise
        integer :: unit, i, part, n_edges, line_type, tag
        integer, allocatable :: order(:)
        allocate (order(0))   ! avoids a false -Wuninitialized at -O3 (see split_names)
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') '$MeshFormat', '4.1 0 8', '$EndMeshFormat', '$PhysicalNames', '5'
        do part = 1, 4
            write (unit, '(a)') '1 '//to_string(part)//' "'//trim(m%part_names(part))//'"'
        end do
        write (unit, '(a)') '2 5 "body"', '$EndPhysicalNames', '$Entities', '0 4 1 0'
        do part = 1, 4
            write (unit, '(a)') to_string(part)//' 0 0 0 1.5 1 0 1 '//to_string(part)//' 0'
        end do
        write (unit, '(a)') '1 0 0 0 1.5 1 0 1 '//to_string(BODY_TAG)//' 0', '$EndEntities'
        write (unit, '(a)') '$Nodes', '1 '//to_string(m%n_nodes())//' '// &
            to_string(node_tag(1))//' '//to_string(node_tag(m%n_nodes())), &
            '2 1 0 '//to_string(m%n_nodes())
        do i = m%n_nodes(), 1, -1
            write (unit, '(i0)') node_tag(i)
        end do
        do i = m%n_nodes(), 1, -1
            write (unit, '(2(es25.17, 1x), a)') m%coords(:, i), '0'
        end do
        write (unit, '(a)') '$EndNodes', '$Elements'
        n_edges = size(m%edges, 2)
        write (unit, '(a)') '5 '//to_string(n_edges + m%n_cells())//' 1 '// &
            to_string(n_edges + m%n_cells())
        line_type = GMSH_LINE_TYPES(size(m%edges, 1))
        tag = 0
        do part = 1, 4
            write (unit, '(a)') '1 '//to_string(part)//' '//to_string(line_type)//' '// &
                to_string(count(m%edge_part == part))
            do i = 1, n_edges
                if (m%edge_part(i) /= part) cycle
                tag = tag + 1
                write (unit, '(*(i0, 1x))') tag, node_tag(m%edges(:, i))
            end do
        end do
        write (unit, '(a)') '2 1 '//to_string(GMSH_TYPES(m%element))//' '// &
            to_string(m%n_cells())
        order = [(i, i=1, size(m%cells, 1))]
        if (clockwise) order = clockwise_order(m%element)
        do i = 1, m%n_cells()
            tag = tag + 1
            write (unit, '(*(i0, 1x))') tag, node_tag(m%cells(order, i))
        end do
        write (unit, '(a)') '$EndElements'
        close (unit)
    end subroutine write_msh41

    !> The same mesh as MSH 2.2 (elements: tag type 2 physical elementary nodes...).
    subroutine write_msh22(path, m)
        character(len=*), intent(in) :: path
        type(mesh_t), intent(in) :: m
        integer :: unit, i, part, n_edges, line_type, tag
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') '$MeshFormat', '2.2 0 8', '$EndMeshFormat', '$PhysicalNames', '5'
        do part = 1, 4
            write (unit, '(a)') '1 '//to_string(part)//' "'//trim(m%part_names(part))//'"'
        end do
        write (unit, '(a)') '2 5 "body"', '$EndPhysicalNames', '$Nodes', to_string(m%n_nodes())
        do i = m%n_nodes(), 1, -1
            write (unit, '(i0, 1x, 2(es25.17, 1x), a)') node_tag(i), m%coords(:, i), '0'
        end do
        n_edges = size(m%edges, 2)
        write (unit, '(a)') '$EndNodes', '$Elements', to_string(n_edges + m%n_cells())
        line_type = GMSH_LINE_TYPES(size(m%edges, 1))
        tag = 0
        do part = 1, 4
            do i = 1, n_edges
                if (m%edge_part(i) /= part) cycle
                tag = tag + 1
                write (unit, '(*(i0, 1x))') tag, line_type, 2, part, part, node_tag(m%edges(:, i))
            end do
        end do
        do i = 1, m%n_cells()
            tag = tag + 1
            write (unit, '(*(i0, 1x))') tag, GMSH_TYPES(m%element), 2, BODY_TAG, 1, &
                node_tag(m%cells(:, i))
        end do
        write (unit, '(a)') '$EndElements'
        close (unit)
    end subroutine write_msh22
end module msh_writer
