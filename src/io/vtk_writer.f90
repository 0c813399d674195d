! SPDX-License-Identifier: MIT
!> The mesh and nodal vector fields (mode shapes) as a VTK XML UnstructuredGrid (.vtu),
!> ASCII and Float64, for ParaView ('Warp By Vector' needs 3 components: z is 0).
module vtk_writer
    use kinds, only: wp, i8, N_DIM
    use status, only: status_t, STATUS_IO, STATUS_INTERNAL
    use mesh, only: mesh_t, element_nodes_per_cell, ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, &
                    ELEMENT_Q2
    implicit none
    private
    public :: write_vtu, vtk_cell_type, vtk_node_order
    public :: VTK_TRIANGLE, VTK_QUAD, VTK_QUADRATIC_TRIANGLE, VTK_BIQUADRATIC_QUAD

    integer, parameter :: VTK_TRIANGLE = 5
    integer, parameter :: VTK_QUAD = 9
    integer, parameter :: VTK_QUADRATIC_TRIANGLE = 22
    integer, parameter :: VTK_BIQUADRATIC_QUAD = 28
    integer, parameter :: VALUES_PER_LINE = 16   !! offsets and types, to keep lines short
    character(len=*), parameter :: REAL_FORMAT = '(*(1x, es24.16e3))'   !! round-trips binary64
    character(len=*), parameter :: INT_FORMAT = '(*(1x, i0))'

contains

    !> Write mesh `m` with the nodal vector fields `vectors(:, :, k)` called `names(k)` to
    !> the .vtu file `path` (replaced). The first field is marked as the active vectors.
    !> Inconsistent sizes give STATUS_INTERNAL, a failed write STATUS_IO naming the file.
    subroutine write_vtu(path, m, names, vectors, stat)
        character(len=*), intent(in) :: path
        type(mesh_t), intent(in) :: m
        character(len=*), intent(in) :: names(:)          !! e.g. 'displacement'
        real(wp), intent(in) :: vectors(:, :, :)          !! (N_DIM, n_nodes, size(names))
        type(status_t), intent(out) :: stat
        character(len=1024) :: msg
        integer :: unit, ios, ignored

        call check_arguments(m, names, vectors, stat)
        if (.not. stat%ok()) return
        open (newunit=unit, file=path, status='replace', action='write', iostat=ios, &
              iomsg=msg)
        if (ios == 0) then
            call write_grid(unit, m, names, vectors, ios, msg)
            if (ios /= 0) then
                close (unit, iostat=ignored)
            else
                close (unit, iostat=ios, iomsg=msg)
            end if
        end if
        ! A partial file is left for the output stage (or the caller) to remove.
        if (ios /= 0) call stat%fail(STATUS_IO, trim(path)//': cannot write VTK file: ' &
                                     //trim(msg))
    end subroutine write_vtu

    !> The XML itself; returns at the first failed write with its iostat and message.
    subroutine write_grid(unit, m, names, vectors, ios, msg)
        integer, intent(in) :: unit
        type(mesh_t), intent(in) :: m
        character(len=*), intent(in) :: names(:)
        real(wp), intent(in) :: vectors(:, :, :)
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, allocatable :: order(:)
        integer(i8), allocatable :: offsets(:)
        integer :: e, i, k

        write (unit, '(a)', iostat=ios, iomsg=msg) '<?xml version="1.0"?>', &
            '<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" ' &
            //'header_type="UInt64">', '  <UnstructuredGrid>', &
            '    <Piece NumberOfPoints="'//int_text(m%n_nodes())//'" NumberOfCells="' &
            //int_text(m%n_cells())//'">'
        if (ios /= 0) return

        if (size(names) > 0) then
            write (unit, '(a)', iostat=ios, iomsg=msg) &
                '      <PointData Vectors="'//xml_escaped(trim(names(1)))//'">'
            if (ios /= 0) return
            do k = 1, size(names)
                write (unit, '(a)', iostat=ios, iomsg=msg) '        <DataArray type="Float64" ' &
                    //'Name="'//xml_escaped(trim(names(k)))//'" NumberOfComponents="3" ' &
                    //'format="ascii">'
                if (ios /= 0) return
                do i = 1, m%n_nodes()
                    write (unit, REAL_FORMAT, iostat=ios, iomsg=msg) vectors(:, i, k), 0.0_wp
                    if (ios /= 0) return
                end do
                write (unit, '(a)', iostat=ios, iomsg=msg) '        </DataArray>'
                if (ios /= 0) return
            end do
            write (unit, '(a)', iostat=ios, iomsg=msg) '      </PointData>'
            if (ios /= 0) return
        end if

        write (unit, '(a)', iostat=ios, iomsg=msg) '      <Points>', &
            '        <DataArray type="Float64" NumberOfComponents="3" format="ascii">'
        if (ios /= 0) return
        do i = 1, m%n_nodes()
            write (unit, REAL_FORMAT, iostat=ios, iomsg=msg) m%coords(:, i), 0.0_wp
            if (ios /= 0) return
        end do
        write (unit, '(a)', iostat=ios, iomsg=msg) '        </DataArray>', '      </Points>', &
            '      <Cells>', '        <DataArray type="Int64" Name="connectivity" format="ascii">'
        if (ios /= 0) return
        order = vtk_node_order(m%element)
        do e = 1, m%n_cells()
            ! VTK counts points from 0.
            write (unit, INT_FORMAT, iostat=ios, iomsg=msg) m%cells(order, e) - 1
            if (ios /= 0) return
        end do
        write (unit, '(a)', iostat=ios, iomsg=msg) '        </DataArray>', &
            '        <DataArray type="Int64" Name="offsets" format="ascii">'
        if (ios /= 0) return
        ! Offsets mark where each cell ends in connectivity: the running node count.
        offsets = [(int(size(m%cells, 1), i8)*e, e=1, m%n_cells())]
        call write_in_lines(unit, offsets, ios, msg)
        if (ios /= 0) return
        write (unit, '(a)', iostat=ios, iomsg=msg) '        </DataArray>', &
            '        <DataArray type="UInt8" Name="types" format="ascii">'
        if (ios /= 0) return
        call write_in_lines(unit, spread(int(vtk_cell_type(m%element), i8), 1, m%n_cells()), &
                            ios, msg)
        if (ios /= 0) return
        write (unit, '(a)', iostat=ios, iomsg=msg) '        </DataArray>', '      </Cells>', &
            '    </Piece>', '  </UnstructuredGrid>', '</VTKFile>'
    end subroutine write_grid

    !> VTK cell type of an ELEMENT_* code; 0 for an unknown code.
    pure integer function vtk_cell_type(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_P1); vtk_cell_type = VTK_TRIANGLE
        case (ELEMENT_Q1); vtk_cell_type = VTK_QUAD
        case (ELEMENT_P2); vtk_cell_type = VTK_QUADRATIC_TRIANGLE
        case (ELEMENT_Q2); vtk_cell_type = VTK_BIQUADRATIC_QUAD
        case default; vtk_cell_type = 0
        end select
    end function vtk_cell_type

    !> Position in our (Gmsh) cell of each VTK cell node. Both number corners anticlockwise,
    !> then mid-edge nodes with edge k from corner k to corner k+1, then the Q2 centre; so
    !> the orders coincide, and this is where a difference would go.
    pure function vtk_node_order(element) result(order)
        integer, intent(in) :: element
        integer, allocatable :: order(:)
        integer :: i
        order = [(i, i=1, element_nodes_per_cell(element))]
    end function vtk_node_order

    subroutine check_arguments(m, names, vectors, stat)
        type(mesh_t), intent(in) :: m
        character(len=*), intent(in) :: names(:)
        real(wp), intent(in) :: vectors(:, :, :)
        type(status_t), intent(out) :: stat

        if (.not. allocated(m%coords) .or. .not. allocated(m%cells)) then
            call stat%fail(STATUS_INTERNAL, 'write_vtu: the mesh has no nodes or cells')
        else if (vtk_cell_type(m%element) == 0) then
            call stat%fail(STATUS_INTERNAL, 'write_vtu: unknown element code ' &
                           //int_text(m%element))
        else if (size(m%cells, 1) /= element_nodes_per_cell(m%element)) then
            call stat%fail(STATUS_INTERNAL, 'write_vtu: cells have ' &
                           //int_text(size(m%cells, 1))//' nodes, the element needs ' &
                           //int_text(element_nodes_per_cell(m%element)))
        else if (size(m%coords, 1) /= N_DIM) then
            call stat%fail(STATUS_INTERNAL, 'write_vtu: coordinates must be (2, n_nodes)')
        else if (m%n_cells() > 0) then
            if (minval(m%cells) < 1 .or. maxval(m%cells) > m%n_nodes()) then
                call stat%fail(STATUS_INTERNAL, 'write_vtu: a cell refers to a missing node')
            end if
        end if
        if (.not. stat%ok()) return
        if (size(vectors, 3) /= size(names) .or. size(vectors, 1) /= N_DIM .or. &
            (size(names) > 0 .and. size(vectors, 2) /= m%n_nodes())) then
            call stat%fail(STATUS_INTERNAL, 'write_vtu: fields must be (2, n_nodes, n_names)')
        end if
    end subroutine check_arguments

    subroutine write_in_lines(unit, values, ios, msg)
        integer, intent(in) :: unit
        integer(i8), intent(in) :: values(:)
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer :: first
        ios = 0
        do first = 1, size(values), VALUES_PER_LINE
            write (unit, INT_FORMAT, iostat=ios, iomsg=msg) &
                values(first:min(first + VALUES_PER_LINE - 1, size(values)))
            if (ios /= 0) return
        end do
    end subroutine write_in_lines

    pure function int_text(n) result(text)
        integer, intent(in) :: n
        character(len=:), allocatable :: text
        character(len=16) :: buffer
        write (buffer, '(i0)') n
        text = trim(buffer)
    end function int_text

    !> `text` safe inside an XML attribute.
    pure function xml_escaped(text) result(xml)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: xml
        integer :: i
        xml = ''
        do i = 1, len(text)
            select case (text(i:i))
            case ('&'); xml = xml//'&amp;'
            case ('<'); xml = xml//'&lt;'
            case ('>'); xml = xml//'&gt;'
            case ('"'); xml = xml//'&quot;'
            case default; xml = xml//text(i:i)
            end select
        end do
    end function xml_escaped
end module vtk_writer
