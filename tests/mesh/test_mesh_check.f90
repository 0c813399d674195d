! SPDX-License-Identifier: MIT
!> The mesh checks: the structured meshes (P1 both diagonals, Q1, P2, Q2, P3, P4) and the
!> meshes of input/meshes pass; Gmsh files written from altered grids are refused with the
!> file, the line and what is wrong: a duplicated cell, an overlapping cell, a contact group
!> on an interior line, a zero-length contact edge, a group edge that is no side of a cell, a
!> crack (duplicated nodes: two pieces); a generated mesh with an unused node is refused too,
!> and non-conforming P3 edge nodes.
program test_mesh_check
    use kinds, only: wp
    use status, only: status_t, STATUS_MESH
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P3, MAX_ELEMENT, element_name
    use mesh_structured, only: structured_rectangle, PART_BOTTOM, PART_TOP
    use filesystem, only: remove_file
    use mesh_gmsh, only: read_gmsh
    use mesh_check, only: check_mesh
    use strings, only: to_string
    use testing, only: test_suite_t
    use msh_writer, only: write_msh22
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_mesh_check'
    call check_reference_meshes()
    call check_duplicated_cell()
    call check_overlapping_cell()
    call check_interior_contact()
    call check_zero_length_contact()
    call check_edge_of_no_cell()
    call check_crack()
    call check_unused_node()
    call check_nonconforming_cubic()
    call t%report()

contains

    !> P3: a cell whose inner node on a shared side is a copy of its neighbour's (same place,
    !> another number) is not conforming; a boundary edge listing another inner node than its
    !> cell is refused too.
    subroutine check_nonconforming_cubic()
        type(mesh_t) :: m
        type(status_t) :: stat
        real(wp), allocatable :: coords(:, :)
        integer :: n
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P3, 'right', m, stat)
        n = m%n_nodes()
        ! Cell 1 (corners 1, 2, 3 of the first square) meets cell 2 along its diagonal, its
        ! side 3 from corner 3 to corner 1: nodes 8 and 9.
        call move_alloc(m%coords, coords)
        allocate (m%coords(2, n + 1))
        m%coords(:, 1:n) = coords
        m%coords(:, n + 1) = coords(:, m%cells(8, 1))
        m%cells(8, 1) = n + 1
        call check_mesh(m, [PART_TOP], [2, 4], [PART_BOTTOM], stat)
        call t%check('P3: a copied inner node on a shared side is refused', &
                     stat%code == STATUS_MESH .and. index(stat%message, 'edge nodes') > 0)
        if (stat%ok()) return
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P3, 'right', m, stat)
        m%edges(3, 1) = m%cells(10, 1)
        call check_mesh(m, [PART_TOP], [2, 4], [PART_BOTTOM], stat)
        call t%check('P3: a boundary edge with another inner node than its cell is refused', &
                     stat%code == STATUS_MESH .and. index(stat%message, 'inner nodes') > 0)
    end subroutine check_nonconforming_cubic

    subroutine check_reference_meshes()
        type(mesh_t) :: m
        type(status_t) :: stat
        integer :: element
        character(len=*), parameter :: FILES(2) = ['single_element.msh', 'square_16.msh     ']
        character(len=:), allocatable :: source_dir
        integer :: i, length

        do element = ELEMENT_P1, MAX_ELEMENT
            call structured_rectangle(1.5_wp, 1.0_wp, 5, 3, element, 'right', m, stat)
            call check_mesh(m, [PART_TOP], [2, 4], [PART_BOTTOM], stat)
            call t%check('structured '//element_name(element)//' passes', stat%ok())
            if (.not. stat%ok()) print '(a)', stat%message
        end do
        call structured_rectangle(1.0_wp, 1.0_wp, 4, 4, ELEMENT_P1, 'left', m, stat)
        call check_mesh(m, [PART_TOP], [2, 4], [PART_BOTTOM], stat)
        call t%check('structured p1 (left diagonal) passes', stat%ok())

        call get_environment_variable('NCEIG_SOURCE_DIR', length=length)
        allocate (character(len=length) :: source_dir)
        call get_environment_variable('NCEIG_SOURCE_DIR', source_dir)
        if (length == 0) source_dir = '..'
        do i = 1, size(FILES)
            call read_gmsh(source_dir//'/input/meshes/'//trim(FILES(i)), m, stat)
            call t%check(trim(FILES(i))//' reads', stat%ok())
            if (.not. stat%ok()) cycle
            call check_mesh(m, [(i, i=1, size(m%part_names))], [integer ::], [integer ::], stat)
            call t%check(trim(FILES(i))//' passes with every 1D group named', stat%ok())
            if (.not. stat%ok()) print '(a)', stat%message
        end do
    end subroutine check_reference_meshes

    !> The last cell repeated: its edges belong to 2 cells on the same side, or to 3 cells.
    subroutine check_duplicated_cell()
        type(mesh_t) :: m
        call grid(ELEMENT_P1, 4, 4, m)
        m%cells = reshape([m%cells, m%cells(:, m%n_cells())], [3, m%n_cells() + 1])
        call expect_refusal('duplicated cell', m, cell_line(m, m%n_cells()), &
                            'overlapping or duplicated cells', [PART_BOTTOM])
    end subroutine check_duplicated_cell

    !> A quadrangle over two cells of a Q1 grid: the edges it shares with them run the same way.
    subroutine check_overlapping_cell()
        type(mesh_t) :: m
        call grid(ELEMENT_Q1, 2, 2, m)
        ! grid nodes 1 2 3 / 4 5 6 / 7 8 9; the cell (1, 3, 6, 4) covers the two lower cells
        m%cells = reshape([m%cells, 1, 3, 6, 4], [4, m%n_cells() + 1])
        call expect_refusal('overlapping cell', m, cell_line(m, m%n_cells()), &
                            'both lie on the same side of their common edge', [PART_BOTTOM])
    end subroutine check_overlapping_cell

    !> The contact group moved onto the line y = 0.5 of a 2 x 2 grid.
    subroutine check_interior_contact()
        type(mesh_t) :: m
        integer :: e
        call grid(ELEMENT_P1, 2, 2, m)
        do e = 1, size(m%edge_part)
            if (m%edge_part(e) /= PART_BOTTOM) cycle
            m%edges(:, e) = m%edges(:, e) + 3   ! one grid row up
        end do
        call expect_refusal('contact group on an interior line', m, edge_line(m, 1), &
                            'lies inside the body', [PART_BOTTOM])
    end subroutine check_interior_contact

    !> A contact group that is one edge from a node to itself.
    subroutine check_zero_length_contact()
        type(mesh_t) :: m
        logical, allocatable :: keep(:)
        call grid(ELEMENT_P1, 2, 2, m)
        keep = m%edge_part /= PART_BOTTOM
        keep(1) = .true.
        call drop_edges(m, keep)
        m%edges(:, 1) = [2, 2]
        call expect_refusal('zero-length contact edge', m, edge_line(m, 1), &
                            'is degenerate: its ends', [PART_BOTTOM])
    end subroutine check_zero_length_contact

    !> A contact edge across a quadrangle, from corner to opposite corner.
    subroutine check_edge_of_no_cell()
        type(mesh_t) :: m
        call grid(ELEMENT_Q1, 2, 2, m)
        m%edges(:, 1) = [1, 5]
        call expect_refusal('contact edge across a cell', m, edge_line(m, 1), &
                            'is the side of no cell', [PART_BOTTOM])
    end subroutine check_edge_of_no_cell

    !> A 2 x 2 Q1 grid cut along x = 0.5: the right cells get copies of the middle nodes.
    subroutine check_crack()
        type(mesh_t) :: m
        integer :: c, e, a, copy(9), n
        call grid(ELEMENT_Q1, 2, 2, m)
        n = m%n_nodes()
        copy = [(a, a=1, 9)]
        copy([2, 5, 8]) = [n + 1, n + 2, n + 3]
        m%coords = reshape([m%coords, m%coords(:, 2), m%coords(:, 5), m%coords(:, 8)], [2, n + 3])
        do c = 1, m%n_cells()
            if (sum(m%coords(1, m%cells(:, c)))/4 > 0.5_wp) m%cells(:, c) = copy(m%cells(:, c))
        end do
        do e = 1, size(m%edge_part)
            if (sum(m%coords(1, m%edges(:, e)))/2 > 0.5_wp) m%edges(:, e) = copy(m%edges(:, e))
        end do
        call expect_refusal('crack along x = 0.5', m, cell_line(m, 2), &
                            'the mesh is not connected: it falls into 2 pieces', [PART_BOTTOM])
    end subroutine check_crack

    !> A node on no cell (the Gmsh reader drops such nodes: a generated mesh).
    subroutine check_unused_node()
        type(mesh_t) :: m
        type(status_t) :: stat
        call grid(ELEMENT_P1, 2, 2, m)
        m%coords = reshape([m%coords, 2.0_wp, 2.0_wp], [2, m%n_nodes() + 1])
        call check_mesh(m, [PART_TOP], [integer ::], [PART_BOTTOM], stat)
        call t%check('unused node refused', stat%code == STATUS_MESH)
        if (stat%ok()) return
        call t%check('unused node: message names it', &
                     index(stat%message, 'node 10 at (2.0') > 0)
        print '(a)', '      '//stat%message
    end subroutine check_unused_node

    ! ------------------------------------------------------------------------ helpers

    subroutine grid(element, nx, ny, m)
        integer, intent(in) :: element, nx, ny
        type(mesh_t), intent(out) :: m
        type(status_t) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, nx, ny, element, 'right', m, stat)
    end subroutine grid

    subroutine drop_edges(m, keep)
        type(mesh_t), intent(inout) :: m
        logical, intent(in) :: keep(:)
        integer :: e
        integer, allocatable :: kept(:)
        kept = pack([(e, e=1, size(keep))], keep)
        m%edges = m%edges(:, kept)
        m%edge_part = m%edge_part(kept)
    end subroutine drop_edges

    !> Line of cell c in the MSH 2.2 file write_msh22 writes: 13 header lines, the nodes,
    !> $EndNodes, $Elements, the count, the edges part by part, then the cells.
    integer function cell_line(m, c)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: c
        cell_line = 16 + m%n_nodes() + size(m%edge_part) + c
    end function cell_line

    !> Line of the first edge of part `part` in that file.
    integer function edge_line(m, part)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: part
        edge_line = 17 + m%n_nodes() + count(m%edge_part < part)
    end function edge_line

    !> Write m as MSH 2.2 (a scratch file in the working folder), read it back, check with `contact` the contact group: STATUS_MESH,
    !> and a message 'file:line: ...' containing `words`.
    subroutine expect_refusal(what, m, line, words, contact)
        character(len=*), intent(in) :: what, words
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: line, contact(:)
        type(mesh_t) :: from_file
        type(status_t) :: stat
        character(len=:), allocatable :: path
        path = 'check_'//to_string(line)//'_'//element_name(m%element)//'.msh'
        call write_msh22(path, m)
        call read_gmsh(path, from_file, stat)
        call remove_file(path)
        call t%check(what//': the reader accepts the file', stat%ok())
        if (.not. stat%ok()) then
            print '(a)', '      '//stat%message
            return
        end if
        call check_mesh(from_file, [PART_TOP], [integer ::], contact, stat)
        call t%check(what//': refused', stat%code == STATUS_MESH)
        if (stat%ok()) return
        call t%check(what//': names the file and line', &
                     index(stat%message, path//':'//to_string(line)//': ') == 1)
        call t%check(what//': says what is wrong', index(stat%message, words) > 0)
        print '(a)', '      '//stat%message
    end subroutine expect_refusal
end program test_mesh_check
