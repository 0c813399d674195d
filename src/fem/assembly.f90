! SPDX-License-Identifier: MIT
!> Global matrices on the free dofs, assembled cell by cell into a CSR pattern built once
!> from the connectivity.
module assembly
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_MESH, STATUS_INTERNAL
    use mesh, only: mesh_t
    use element_types, only: element_nodes_per_cell
    use dof_map, only: dof_map_t, cell_dofs
    use csr_matrix, only: csr_matrix_t, csr_from_element_dofs
    use strings, only: to_string, short_real_text
    use sorting, only: sort_by_key
    use elasticity, only: element_stiffness, ELEMENT_OK, ELEMENT_INVERTED, stiffness_tables_t, &
                          stiffness_tables
    implicit none
    private
    public :: assemble_stiffness

contains

    !> Stiffness matrix K of a(u, v) = int sigma(u) : eps(v) on the free dofs of `dofs`
    !> (prescribed dofs are eliminated: their rows and columns are left out). Fails with
    !> STATUS_MESH naming the first inverted or degenerate cell.
    subroutine assemble_stiffness(m, dofs, young, poisson, k, stat)
        type(mesh_t), intent(in) :: m
        type(dof_map_t), intent(in) :: dofs
        real(wp), intent(in) :: young, poisson   !! Pa, dimensionless
        type(csr_matrix_t), intent(out) :: k
        type(status_t), intent(out) :: stat
        integer, allocatable :: local_dofs(:)
        real(wp), allocatable :: ke(:, :), xy(:, :)
        real(wp) :: min_det
        type(stiffness_tables_t) :: tables
        integer :: n_nodes, n_dim, cell, info, i

        if (.not. (young > 0.0_wp .and. young <= huge(young))) then
            call stat%fail(STATUS_BAD_INPUT, 'assembly: Young''s modulus must be positive '// &
                           'and finite, got '//short_real_text(young, 5))
            return
        end if
        if (.not. (poisson > -1.0_wp .and. poisson < 0.5_wp)) then
            call stat%fail(STATUS_BAD_INPUT, 'assembly: Poisson''s ratio must lie in '// &
                           '(-1, 1/2), got '//short_real_text(poisson, 5))
            return
        end if
        if (.not. (allocated(m%cells) .and. allocated(m%coords))) then
            call stat%fail(STATUS_INTERNAL, 'assembly: the mesh has no cells')
            return
        end if
        n_nodes = element_nodes_per_cell(m%element)
        if (n_nodes == 0 .or. n_nodes /= size(m%cells, 1)) then
            call stat%fail(STATUS_INTERNAL, 'assembly: the mesh cells do not match its '// &
                           'element type')
            return
        end if
        if (.not. allocated(dofs%free_dof)) then
            call stat%fail(STATUS_INTERNAL, 'assembly: the dof map is not built')
            return
        end if
        n_dim = m%dim()
        if (size(m%coords, 1) /= n_dim .or. dofs%dim() /= n_dim) then
            call stat%fail(STATUS_INTERNAL, 'assembly: the coordinates or the dof map do '// &
                           'not have the mesh''s dimension '//to_string(n_dim))
            return
        end if

        call stiffness_pattern(m, dofs, k)
        tables = stiffness_tables(m%element)

        ! Work arrays outlive the loop: a temporary per cell costs as much as a P1 matrix.
        allocate (ke(n_dim*n_nodes, n_dim*n_nodes), local_dofs(n_dim*n_nodes))
        allocate (xy(n_dim, n_nodes))
        do cell = 1, m%n_cells()
            do i = 1, n_nodes
                xy(:, i) = m%coords(:, m%cells(i, cell))
                local_dofs(n_dim*(i - 1) + 1:n_dim*i) = dofs%free_dof(:, m%cells(i, cell))
            end do
            call element_stiffness(m%element, xy, young, poisson, ke, info, min_det, tables)
            if (info /= ELEMENT_OK) then
                if (info == ELEMENT_INVERTED) then
                    call stat%fail(STATUS_MESH, 'mesh: cell '//to_string(cell)// &
                                   ' is inverted or degenerate (Jacobian determinant '// &
                                   short_real_text(min_det, 5)//')')
                    ! A mesh read from a file: name the file and the line of the cell.
                    if (allocated(m%file) .and. allocated(m%cell_line)) then
                        stat%message = m%file//':'//to_string(m%cell_line(cell))//': '// &
                                       stat%message
                    end if
                else
                    call stat%fail(STATUS_INTERNAL, 'assembly: element_stiffness rejected '// &
                                   'the arguments for cell '//to_string(cell))
                end if
                return
            end if
            call scatter_block(k, local_dofs, ke, info)
            if (info /= 0) then
                call stat%fail(STATUS_INTERNAL, 'assembly: an entry of a cell matrix falls '// &
                               'outside the sparsity pattern')
                return
            end if
        end do
    end subroutine assemble_stiffness

    !> Empty CSR matrix coupling every pair of free dofs whose nodes share a cell. With the
    !> node-major numbering of build_dof_map, the pattern is that of the node graph with
    !> each node expanded to its free components: a quarter of the work of building it from
    !> the dofs directly, which dominated the assembly of large meshes.
    subroutine stiffness_pattern(m, dofs, k)
        type(mesh_t), intent(in) :: m
        type(dof_map_t), intent(in) :: dofs
        type(csr_matrix_t), intent(out) :: k
        type(csr_matrix_t) :: node_graph
        integer, allocatable :: free_count(:), all_dofs(:, :)
        integer :: node, neighbour, component, column_component, row, pos, slot, row_length
        integer :: cell

        if (.not. node_major(dofs)) then
            allocate (all_dofs(dofs%dim()*size(m%cells, 1), m%n_cells()))
            do cell = 1, m%n_cells()
                all_dofs(:, cell) = cell_dofs(dofs, m, cell)
            end do
            call csr_from_element_dofs(dofs%n_free, all_dofs, k)
            return
        end if
        call csr_from_element_dofs(m%n_nodes(), m%cells, node_graph)
        free_count = count(dofs%free_dof > 0, dim=1)

        ! Rows come node by node, components in order, which is the free numbering itself.
        allocate (k%row_start(dofs%n_free + 1))
        k%row_start(1) = 1
        row = 0
        do node = 1, m%n_nodes()
            row_length = 0
            do slot = node_graph%row_start(node), node_graph%row_start(node + 1) - 1
                row_length = row_length + free_count(node_graph%col(slot))
            end do
            do component = 1, free_count(node)
                row = row + 1
                k%row_start(row + 1) = k%row_start(row) + row_length
            end do
        end do
        allocate (k%col(k%row_start(dofs%n_free + 1) - 1))
        do node = 1, m%n_nodes()
            do component = 1, dofs%dim()
                row = dofs%free_dof(component, node)
                if (row == 0) cycle
                pos = k%row_start(row)
                ! Neighbours are sorted and numbering is node-major: columns come out sorted.
                do slot = node_graph%row_start(node), node_graph%row_start(node + 1) - 1
                    neighbour = node_graph%col(slot)
                    do column_component = 1, dofs%dim()
                        if (dofs%free_dof(column_component, neighbour) == 0) cycle
                        k%col(pos) = dofs%free_dof(column_component, neighbour)
                        pos = pos + 1
                    end do
                end do
            end do
        end do
        allocate (k%val(size(k%col)), source=0.0_wp)
    end subroutine stiffness_pattern

    !> k(dofs(i), dofs(j)) += block(i, j), skipping zero dofs; `info` /= 0 when an entry is
    !> missing from the pattern. Same result as csr_matrix_t%add_block, but each row is
    !> walked once against the cell's dofs in increasing order instead of binary-searched
    !> for every entry: the scatter was a third of the assembly time of a million cells.
    pure subroutine scatter_block(k, dofs, block, info)
        type(csr_matrix_t), intent(inout) :: k
        integer, intent(in) :: dofs(:)
        real(wp), intent(in) :: block(:, :)
        integer, intent(out) :: info
        integer :: order(size(dofs)), n_order, i, j, row, pos, last

        ! Positions of the free dofs, sorted by dof number.
        n_order = 0
        do i = 1, size(dofs)
            if (dofs(i) == 0) cycle
            n_order = n_order + 1
            order(n_order) = i
        end do
        call sort_by_key(order(:n_order), dofs)

        info = 0
        do i = 1, size(dofs)
            row = dofs(i)
            if (row == 0) cycle
            pos = k%row_start(row)
            last = k%row_start(row + 1) - 1
            do j = 1, n_order
                do while (pos < last .and. k%col(pos) < dofs(order(j)))
                    pos = pos + 1
                end do
                if (k%col(pos) /= dofs(order(j))) then
                    info = 1
                    return
                end if
                k%val(pos) = k%val(pos) + block(i, order(j))
            end do
        end do
    end subroutine scatter_block

    !> True when the free dofs are numbered 1, 2, ... node by node, components in order
    !> (as build_dof_map does), the ordering stiffness_pattern's shortcut relies on.
    pure logical function node_major(dofs)
        type(dof_map_t), intent(in) :: dofs
        integer :: node, component, expected
        node_major = .false.
        expected = 0
        do node = 1, size(dofs%free_dof, 2)
            do component = 1, size(dofs%free_dof, 1)
                if (dofs%free_dof(component, node) == 0) cycle
                expected = expected + 1
                if (dofs%free_dof(component, node) /= expected) return
            end do
        end do
        node_major = expected == dofs%n_free
    end function node_major
end module assembly
