! SPDX-License-Identifier: MIT
!> A `mesh_t` as a Gmsh MSH 4.1 ASCII file, so that a generated or refined mesh can be looked
!> at in Gmsh and read back by `read_gmsh` (mesh_gmsh.f90) unchanged.
!>
!> Boundary part k becomes curve entity k in 1D physical group k named part_names(k), the
!> cells one surface in 2D physical group n_parts + 1 named 'body'. Nodes get tags 1..n in
!> node order, and elements are written part by part, then the cells, so that the reader
!> returns the same nodes (with RENUMBER_NONE), the same cells, the same part names and the
!> boundary edges stably sorted by part (unchanged when they were grouped by part already).
!> Reals are written with 17 significant digits, which round-trip binary64 exactly.
module gmsh_writer
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_IO
    use strings, only: to_string
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, element_nodes_per_cell, element_nodes_per_edge
    use filesystem, only: rename_file, remove_file, end_output
    implicit none
    private
    public :: write_gmsh

    ! Gmsh element type numbers (MSH file format documentation, section "Node ordering").
    integer, parameter :: GMSH_LINE2 = 1, GMSH_TRIANGLE3 = 2, GMSH_QUAD4 = 3, &
                          GMSH_LINE3 = 8, GMSH_TRIANGLE6 = 9, GMSH_QUAD9 = 10, &
                          GMSH_TRIANGLE10 = 21, GMSH_TRIANGLE15 = 23, GMSH_LINE4 = 26, &
                          GMSH_LINE5 = 27
    !> Line type by nodes per edge (2 to 5).
    integer, parameter :: GMSH_LINE(2:5) = [GMSH_LINE2, GMSH_LINE3, GMSH_LINE4, GMSH_LINE5]
    integer, parameter :: CURVE_DIM = 1, SURFACE_DIM = 2
    integer, parameter :: SURFACE_TAG = 1            !! the one surface entity
    character(len=*), parameter :: BODY_NAME = 'body'
    character(len=*), parameter :: REAL_FORMAT = '(2(es24.16e3, 1x), a)'   !! x y 0
    character(len=*), parameter :: INT_FORMAT = '(*(i0, :, 1x))'
    !> Suffix of the file written before it is renamed to its name: a reader never sees half a
    !> mesh, and a failed write leaves the previous file (if any) in place.
    character(len=*), parameter :: PARTIAL_SUFFIX = '.partial'

contains

    !> Write `m` (P1, Q1, P2 or Q2 cells) to the MSH 4.1 ASCII file `path` (replaced whole or
    !> not at all). An inconsistent mesh (unknown element, a part index out of range, a part
    !> name that is empty or holds a double quote) gives STATUS_BAD_INPUT; a failed write
    !> STATUS_IO naming the file.
    subroutine write_gmsh(path, m, stat)
        character(len=*), intent(in) :: path
        type(mesh_t), intent(in) :: m
        type(status_t), intent(out) :: stat
        character(len=512) :: msg
        character(len=:), allocatable :: partial
        integer :: unit, ios

        call check_mesh(m, stat)
        if (.not. stat%ok()) return
        partial = path//PARTIAL_SUFFIX
        open (newunit=unit, file=partial, status='replace', action='write', iostat=ios, &
              iomsg=msg)
        if (ios == 0) then
            call write_sections(unit, m, ios, msg)
            call end_output(unit, partial, ios, msg)
        end if
        if (ios /= 0) then
            call remove_file(partial)
            call stat%fail(STATUS_IO, trim(path)//': cannot write Gmsh mesh file: '//trim(msg))
            return
        end if
        call rename_file(partial, path, stat)
        if (.not. stat%ok()) call remove_file(partial)
    end subroutine write_gmsh

    subroutine check_mesh(m, stat)
        type(mesh_t), intent(in) :: m
        type(status_t), intent(out) :: stat
        integer :: k
        if (element_nodes_per_cell(m%element) == 0) then
            call stat%fail(STATUS_BAD_INPUT, 'write_gmsh: unknown element code '// &
                           to_string(m%element))
            return
        end if
        call m%require_complete('write_gmsh', stat)
        if (.not. stat%ok()) return
        ! the entities below are a plane's: boundary curves around one surface
        if (m%dim() /= SURFACE_DIM) then
            call stat%fail(STATUS_BAD_INPUT, 'write_gmsh: the mesh has dimension '// &
                           to_string(m%dim())//'; expected a plane mesh (dimension 2)')
            return
        end if
        if (m%n_cells() == 0) then
            call stat%fail(STATUS_BAD_INPUT, 'write_gmsh: the mesh has no cells')
            return
        end if
        if (size(m%edge_part) > 0) then
            if (minval(m%edge_part) < 1 .or. maxval(m%edge_part) > size(m%part_names)) then
                call stat%fail(STATUS_BAD_INPUT, 'write_gmsh: a boundary edge has part index ' &
                    //to_string(merge(minval(m%edge_part), maxval(m%edge_part), &
                                      minval(m%edge_part) < 1))//'; expected 1 to '// &
                    to_string(size(m%part_names)))
                return
            end if
        end if
        do k = 1, size(m%part_names)
            ! A quote would end the name early in $PhysicalNames; an empty name reads back as
            ! the group's number.
            if (len_trim(m%part_names(k)) == 0 .or. index(m%part_names(k), '"') > 0) then
                call stat%fail(STATUS_BAD_INPUT, 'write_gmsh: boundary part '//to_string(k)// &
                    ' is named '''//trim(m%part_names(k))//'''; expected a non-empty name ' &
                    //'without double quotes')
                return
            end if
        end do
    end subroutine check_mesh

    !> All sections; stops at the first failed write, with `ios` and `msg` set.
    subroutine write_sections(unit, m, ios, msg)
        integer, intent(in) :: unit
        type(mesh_t), intent(in) :: m
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer :: n_parts, k, i, n_edges, n_elements, n_blocks, tag, cell_type, edge_type
        real(wp) :: low(2), high(2)

        n_parts = size(m%part_names)
        n_edges = size(m%edges, 2)
        n_elements = n_edges + m%n_cells()
        select case (m%element)
        case (ELEMENT_P1); cell_type = GMSH_TRIANGLE3
        case (ELEMENT_Q1); cell_type = GMSH_QUAD4
        case (ELEMENT_P2); cell_type = GMSH_TRIANGLE6
        case (ELEMENT_Q2); cell_type = GMSH_QUAD9
        case (ELEMENT_P3); cell_type = GMSH_TRIANGLE10
        case (ELEMENT_P4); cell_type = GMSH_TRIANGLE15
        end select
        edge_type = GMSH_LINE(element_nodes_per_edge(m%element))

        write (unit, '(a)', iostat=ios, iomsg=msg) '$MeshFormat', '4.1 0 8', '$EndMeshFormat', &
            '$PhysicalNames', to_string(n_parts + 1)
        do k = 1, n_parts
            if (ios /= 0) return
            write (unit, '(a)', iostat=ios, iomsg=msg) to_string(CURVE_DIM)//' '// &
                to_string(k)//' "'//trim(m%part_names(k))//'"'
        end do
        if (ios /= 0) return
        write (unit, '(a)', iostat=ios, iomsg=msg) to_string(SURFACE_DIM)//' '// &
            to_string(n_parts + 1)//' "'//BODY_NAME//'"', '$EndPhysicalNames'
        if (ios /= 0) return

        ! $Entities: numPoints numCurves numSurfaces numVolumes; each curve with its bounding
        ! box, one physical tag and no bounding points; the surface with no bounding curves.
        write (unit, '(a)', iostat=ios, iomsg=msg) '$Entities', &
            '0 '//to_string(n_parts)//' 1 0'
        do k = 1, n_parts
            if (ios /= 0) return
            call part_box(k, low, high)
            write (unit, '(a)', iostat=ios, iomsg=msg) to_string(k)//' '// &
                box_text(low, high)//' 1 '//to_string(k)//' 0'
        end do
        if (ios /= 0) return
        write (unit, '(a)', iostat=ios, iomsg=msg) to_string(SURFACE_TAG)//' '// &
            box_text(minval(m%coords, dim=2), maxval(m%coords, dim=2))//' 1 '// &
            to_string(n_parts + 1)//' 0', '$EndEntities'
        if (ios /= 0) return

        ! $Nodes: one block on the surface, tags 1..n, then the coordinates.
        write (unit, '(a)', iostat=ios, iomsg=msg) '$Nodes', '1 '//to_string(m%n_nodes())// &
            ' 1 '//to_string(m%n_nodes()), to_string(SURFACE_DIM)//' '// &
            to_string(SURFACE_TAG)//' 0 '//to_string(m%n_nodes())
        if (ios /= 0) return
        write (unit, '(i0)', iostat=ios, iomsg=msg) (i, i=1, m%n_nodes())
        if (ios /= 0) return
        do i = 1, m%n_nodes()
            write (unit, REAL_FORMAT, iostat=ios, iomsg=msg) m%coords(:, i), '0'
            if (ios /= 0) return
        end do
        write (unit, '(a)', iostat=ios, iomsg=msg) '$EndNodes', '$Elements'
        if (ios /= 0) return

        ! $Elements: a block per part that has edges (the reader's edge order is the file's),
        ! then the cells.
        n_blocks = 1
        do k = 1, n_parts
            if (any(m%edge_part == k)) n_blocks = n_blocks + 1
        end do
        write (unit, '(a)', iostat=ios, iomsg=msg) to_string(n_blocks)//' '// &
            to_string(n_elements)//' 1 '//to_string(n_elements)
        if (ios /= 0) return
        tag = 0
        do k = 1, n_parts
            if (.not. any(m%edge_part == k)) cycle
            write (unit, '(a)', iostat=ios, iomsg=msg) to_string(CURVE_DIM)//' '// &
                to_string(k)//' '//to_string(edge_type)//' '// &
                to_string(count(m%edge_part == k))
            if (ios /= 0) return
            do i = 1, n_edges
                if (m%edge_part(i) /= k) cycle
                tag = tag + 1
                write (unit, INT_FORMAT, iostat=ios, iomsg=msg) tag, m%edges(:, i)
                if (ios /= 0) return
            end do
        end do
        write (unit, '(a)', iostat=ios, iomsg=msg) to_string(SURFACE_DIM)//' '// &
            to_string(SURFACE_TAG)//' '//to_string(cell_type)//' '//to_string(m%n_cells())
        if (ios /= 0) return
        do i = 1, m%n_cells()
            tag = tag + 1
            write (unit, INT_FORMAT, iostat=ios, iomsg=msg) tag, m%cells(:, i)
            if (ios /= 0) return
        end do
        write (unit, '(a)', iostat=ios, iomsg=msg) '$EndElements'

    contains

        !> Bounding box of the nodes of part k's edges (of the whole mesh when it has none).
        subroutine part_box(part, low, high)
            integer, intent(in) :: part
            real(wp), intent(out) :: low(2), high(2)
            integer :: e, a
            low = huge(1.0_wp)
            high = -huge(1.0_wp)
            do e = 1, n_edges
                if (m%edge_part(e) /= part) cycle
                do a = 1, size(m%edges, 1)
                    low = min(low, m%coords(:, m%edges(a, e)))
                    high = max(high, m%coords(:, m%edges(a, e)))
                end do
            end do
            if (low(1) > high(1)) then
                low = minval(m%coords, dim=2)
                high = maxval(m%coords, dim=2)
            end if
        end subroutine part_box
    end subroutine write_sections

    !> 'minX minY minZ maxX maxY maxZ' of a box in the plane z = 0.
    function box_text(low, high) result(text)
        real(wp), intent(in) :: low(2), high(2)
        character(len=:), allocatable :: text
        character(len=160) :: buffer
        write (buffer, '(2(es24.16e3, 1x), a, 2(1x, es24.16e3), a)') low, '0', high, ' 0'
        text = trim(adjustl(buffer))
    end function box_text
end module gmsh_writer
