! SPDX-License-Identifier: MIT
!> The mesh and nodal vector fields (mode shapes) as a VTK XML UnstructuredGrid (.vtu) for
!> ParaView ('Warp By Vector' needs 3 components: z is 0). Two encodings of the same grid:
!> 'binary' (default) puts every array, raw, in one <AppendedData encoding="raw"> element
!> written with Fortran stream access; 'ascii' writes every value as text (es24.16), for
!> reading by eye or by scripts, at several times the size and the writing time.
module vtk_writer
    use iso_fortran_env, only: int8, int32, int64, file_storage_size, character_storage_size
    use ieee_arithmetic, only: ieee_support_datatype
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_IO, STATUS_INTERNAL
    use strings, only: to_string
    use filesystem, only: end_output
    use mesh, only: mesh_t
    use element_types, only: element_nodes_per_cell, ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, &
                             ELEMENT_Q2, ELEMENT_P3, ELEMENT_P4
    implicit none
    private
    public :: write_vtu, vtk_cell_type, vtk_node_order, machine_byte_order
    public :: VTK_TRIANGLE, VTK_QUAD, VTK_QUADRATIC_TRIANGLE, VTK_BIQUADRATIC_QUAD
    public :: VTK_LAGRANGE_TRIANGLE
    public :: VTK_BINARY, VTK_ASCII

    integer, parameter :: VTK_TRIANGLE = 5
    integer, parameter :: VTK_QUAD = 9
    integer, parameter :: VTK_QUADRATIC_TRIANGLE = 22
    integer, parameter :: VTK_BIQUADRATIC_QUAD = 28
    !> Arbitrary-order Lagrange triangle (VTK 8.1, ParaView 5.5 on); its order follows from its
    !> node count (10: cubic, 15: quartic). Written as one cell, not split into linear
    !> sub-triangles, so that ParaView interpolates (and tessellates) the field as computed.
    integer, parameter :: VTK_LAGRANGE_TRIANGLE = 69
    character(len=*), parameter :: VTK_BINARY = 'binary'   !! raw appended data
    character(len=*), parameter :: VTK_ASCII = 'ascii'     !! every value as text
    integer, parameter :: VALUES_PER_LINE = 16   !! offsets and types, to keep lines short
    character(len=*), parameter :: REAL_FORMAT = '(*(1x, es24.16e3))'   !! round-trips binary64
    character(len=*), parameter :: INT_FORMAT = '(*(1x, i0))'
    character(len=*), parameter :: LF = achar(10)
    !> Nodes or cells per write statement of the binary writer: enough that the cost of a
    !> statement vanishes, few enough that the buffers stay small (96 kB of reals).
    integer, parameter :: CHUNK = 4096
    integer(i8), parameter :: HEADER_BYTES = 8   !! the UInt64 byte count before each array
    integer(i8), parameter :: REAL_BYTES = 8     !! Float64
    integer(i8), parameter :: INLINE = -1        !! data_array_tag: data follow in the text

contains

    !> Write mesh `m` with the nodal vector fields `vectors(:, :, k)` called `names(k)` to
    !> the .vtu file `path` (replaced), encoded as `format` (VTK_BINARY or VTK_ASCII). The
    !> first field is marked as the active vectors. Inconsistent sizes or an unknown format
    !> give STATUS_INTERNAL, a failed write STATUS_IO naming the file. Optional scalar cell
    !> fields `cell_values(:, k)` called `cell_names(k)` go to CellData (both or neither),
    !> optional numbers `field_values(k)` called `field_names(k)` to FieldData.
    subroutine write_vtu(path, m, names, vectors, format, stat, cell_names, cell_values, &
                         field_names, field_values)
        character(len=*), intent(in) :: path
        type(mesh_t), intent(in) :: m
        character(len=*), intent(in) :: names(:)          !! e.g. 'displacement'
        real(wp), intent(in) :: vectors(:, :, :)          !! (m%dim(), n_nodes, size(names))
        character(len=*), intent(in) :: format            !! VTK_BINARY or VTK_ASCII
        type(status_t), intent(out) :: stat
        character(len=*), intent(in), optional :: cell_names(:)    !! e.g. 'error_indicator'
        real(wp), intent(in), optional :: cell_values(:, :)        !! (n_cells, size(cell_names))
        !> one number each for the whole data set (VTK field data: mu, lambda, nu of a mode)
        character(len=*), intent(in), optional :: field_names(:)
        real(wp), intent(in), optional :: field_values(:)
        character(len=:), allocatable :: fields_xml
        character(len=1024) :: msg
        character(len=128), allocatable :: scalar_names(:)
        real(wp), allocatable :: scalars(:, :)
        integer :: unit, ios

        call check_arguments(m, names, vectors, stat)
        if (.not. stat%ok()) return
        if (present(cell_names) .and. present(cell_values)) then
            if (size(cell_values, 1) /= m%n_cells() .or. &
                size(cell_values, 2) /= size(cell_names)) then
                call stat%fail(STATUS_INTERNAL, 'write_vtu: cell fields must be (n_cells, '// &
                               'number of names)')
                return
            end if
            scalar_names = cell_names
            scalars = cell_values
        else
            allocate (scalar_names(0))
            allocate (scalars(m%n_cells(), 0))
        end if
        fields_xml = ''
        if (present(field_names) .and. present(field_values)) &
            fields_xml = field_data_xml(field_names, field_values)
        select case (format)
        case (VTK_BINARY)
            call check_binary_support(stat)
            if (.not. stat%ok()) return
            open (newunit=unit, file=path, status='replace', action='write', access='stream', &
                  form='unformatted', iostat=ios, iomsg=msg)
        case (VTK_ASCII)
            open (newunit=unit, file=path, status='replace', action='write', iostat=ios, &
                  iomsg=msg)
        case default
            call stat%fail(STATUS_INTERNAL, "write_vtu: unknown format '"//trim(format) &
                           //"', expected '"//VTK_BINARY//"' or '"//VTK_ASCII//"'")
            return
        end select
        if (ios == 0) then
            if (format == VTK_BINARY) then
                call write_binary_grid(unit, m, names, vectors, scalar_names, scalars, &
                                       fields_xml, ios, msg)
            else
                call write_ascii_grid(unit, m, names, vectors, scalar_names, scalars, &
                                      fields_xml, ios, msg)
            end if
            call end_output(unit, path, ios, msg)
        end if
        ! A partial file is left for the output stage (or the caller) to remove.
        if (ios /= 0) call stat%fail(STATUS_IO, trim(path)//': cannot write VTK file: ' &
                                     //trim(msg))
    end subroutine write_vtu

    !> 'LittleEndian' or 'BigEndian': the order in which this machine stores the bytes of a
    !> number, hence of everything the binary writer copies from memory to the file.
    pure function machine_byte_order() result(order)
        character(len=:), allocatable :: order
        ! The first byte in memory of the integer 1 is 1 exactly when the least significant
        ! byte comes first.
        if (transfer(1_int32, 0_int8) == 1_int8) then
            order = 'LittleEndian'
        else
            order = 'BigEndian'
        end if
    end function machine_byte_order

    !> The binary writer copies memory as it is: that is VTK's Float64 only for IEEE binary64
    !> reals, and the offsets count bytes only when a file storage unit is one 8-bit byte.
    subroutine check_binary_support(stat)
        type(status_t), intent(out) :: stat
        if (file_storage_size /= 8 .or. character_storage_size /= 8) then
            call stat%fail(STATUS_INTERNAL, 'write_vtu: binary VTK needs 8-bit file storage' &
                           //" units; use &output vtk_format = 'ascii'")
        else if (.not. ieee_support_datatype(1.0_wp) .or. storage_size(1.0_wp) /= 64) then
            call stat%fail(STATUS_INTERNAL, 'write_vtu: binary VTK needs IEEE binary64 reals;' &
                           //" use &output vtk_format = 'ascii'")
        end if
    end subroutine check_binary_support

    !> First two lines of the file; the byte order is the machine's, found at run time.
    pure function xml_prolog() result(xml)
        character(len=:), allocatable :: xml
        xml = '<?xml version="1.0"?>'//LF//'<VTKFile type="UnstructuredGrid" version="1.0" ' &
              //'byte_order="'//machine_byte_order()//'" header_type="UInt64">'
    end function xml_prolog

    !> The FieldData block (before the Piece: it belongs to the whole data set) of one
    !> Float64 value per name, inline text in either encoding (VTK reads a mix of inline and
    !> appended arrays); '' when there is none. Each line ends with LF.
    pure function field_data_xml(names, values) result(xml)
        character(len=*), intent(in) :: names(:)
        real(wp), intent(in) :: values(:)
        character(len=:), allocatable :: xml
        character(len=40) :: number
        integer :: k
        xml = ''
        if (size(names) == 0) return
        xml = '    <FieldData>'//LF
        do k = 1, min(size(names), size(values))
            write (number, REAL_FORMAT) values(k)
            xml = xml//'      <DataArray type="Float64" Name="'//xml_escaped(trim(names(k)))// &
                  '" NumberOfTuples="1" format="ascii">'//trim(number)//' </DataArray>'//LF
        end do
        xml = xml//'    </FieldData>'//LF
    end function field_data_xml

    pure function piece_tag(m) result(tag)
        type(mesh_t), intent(in) :: m
        character(len=:), allocatable :: tag
        tag = '    <Piece NumberOfPoints="'//to_string(m%n_nodes())//'" NumberOfCells="' &
              //to_string(m%n_cells())//'">'
    end function piece_tag

    !> A DataArray start tag: its data follow in the text when `offset` is INLINE; otherwise
    !> they start `offset` bytes after the '_' of the AppendedData, and the tag closes itself.
    pure function data_array_tag(type, name, components, offset) result(tag)
        character(len=*), intent(in) :: type, name   !! name '' for the Points array
        integer, intent(in) :: components            !! 0: leave it out (VTK reads 1)
        integer(i8), intent(in) :: offset
        character(len=:), allocatable :: tag
        tag = '        <DataArray type="'//type//'"'
        if (len(name) > 0) tag = tag//' Name="'//xml_escaped(name)//'"'
        if (components > 0) tag = tag//' NumberOfComponents="'//to_string(components)//'"'
        if (offset == INLINE) then
            tag = tag//' format="ascii">'
        else
            tag = tag//' format="appended" offset="'//to_string(offset)//'"/>'
        end if
    end function data_array_tag

    !> The XML with every array in the appended section, laid out as
    !> `_ n1 data1 n2 data2 ...`, each n a UInt64 byte count in the machine's byte order.
    !> Returns at the first failed write with its iostat and message.
    subroutine write_binary_grid(unit, m, names, vectors, cell_names, cell_values, fields_xml, &
                                 ios, msg)
        integer, intent(in) :: unit
        type(mesh_t), intent(in) :: m
        character(len=*), intent(in) :: names(:), cell_names(:)
        real(wp), intent(in) :: vectors(:, :, :), cell_values(:, :)
        character(len=*), intent(in) :: fields_xml   !! field_data_xml's block, or ''
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer(i8) :: bytes(size(names) + size(cell_names) + 4)
        integer(i8) :: offset(size(names) + size(cell_names) + 5)
        integer(i8) :: n_nodes, n_cells, n_entries, index_bytes, data_start, position
        character(len=:), allocatable :: xml, index_type
        logical :: wide
        integer :: k, n_fields, n_all

        n_fields = size(names)
        n_all = n_fields + size(cell_names)   ! the nodal fields, then the cell fields
        n_nodes = m%n_nodes()
        n_cells = m%n_cells()
        n_entries = int(size(m%cells, 1), i8)*n_cells
        ! Int32 halves connectivity and offsets; Int64 only when the largest offset (the
        ! length of connectivity) does not fit. Both arrays get one type, as VTK stores them.
        wide = n_entries > huge(1_int32)
        if (wide) then
            index_type = 'Int64'
            index_bytes = 8
        else
            index_type = 'Int32'
            index_bytes = 4
        end if
        ! Arrays in file order: the fields, cell fields, points, connectivity, offsets, types.
        bytes(1:n_fields) = 3*REAL_BYTES*n_nodes
        bytes(n_fields + 1:n_all) = REAL_BYTES*n_cells
        bytes(n_all + 1) = 3*REAL_BYTES*n_nodes
        bytes(n_all + 2) = index_bytes*n_entries
        bytes(n_all + 3) = index_bytes*n_cells
        bytes(n_all + 4) = n_cells
        offset(1) = 0
        do k = 1, size(bytes)
            offset(k + 1) = offset(k) + HEADER_BYTES + bytes(k)
        end do

        xml = xml_prolog()//LF//'  <UnstructuredGrid>'//LF//fields_xml//piece_tag(m)//LF
        if (n_fields > 0) then
            xml = xml//'      <PointData Vectors="'//xml_escaped(trim(names(1)))//'">'//LF
            do k = 1, n_fields
                xml = xml//data_array_tag('Float64', trim(names(k)), 3, offset(k))//LF
            end do
            xml = xml//'      </PointData>'//LF
        end if
        if (n_all > n_fields) then
            xml = xml//'      <CellData Scalars="'//xml_escaped(trim(cell_names(1)))//'">'//LF
            do k = n_fields + 1, n_all
                xml = xml//data_array_tag('Float64', trim(cell_names(k - n_fields)), 0, &
                                          offset(k))//LF
            end do
            xml = xml//'      </CellData>'//LF
        end if
        xml = xml//'      <Points>'//LF//data_array_tag('Float64', '', 3, offset(n_all + 1)) &
              //LF//'      </Points>'//LF//'      <Cells>'//LF &
              //data_array_tag(index_type, 'connectivity', 0, offset(n_all + 2))//LF &
              //data_array_tag(index_type, 'offsets', 0, offset(n_all + 3))//LF &
              //data_array_tag('UInt8', 'types', 0, offset(n_all + 4))//LF &
              //'      </Cells>'//LF//'    </Piece>'//LF//'  </UnstructuredGrid>'//LF &
              //'  <AppendedData encoding="raw">'//LF//'   _'
        write (unit, iostat=ios, iomsg=msg) xml
        if (ios /= 0) return
        inquire (unit, pos=data_start, iostat=ios, iomsg=msg)
        if (ios /= 0) return

        do k = 1, size(bytes)
            write (unit, iostat=ios, iomsg=msg) bytes(k)
            if (ios /= 0) return
            if (k <= n_fields) then
                call write_vector_block(unit, vectors(:, :, k), ios, msg)
            else if (k <= n_all) then
                write (unit, iostat=ios, iomsg=msg) cell_values(:, k - n_fields)
            else if (k == n_all + 1) then
                call write_vector_block(unit, m%coords, ios, msg)
            else if (k == n_all + 2) then
                call write_connectivity_block(unit, m, wide, ios, msg)
            else if (k == n_all + 3) then
                call write_offsets_block(unit, size(m%cells, 1), m%n_cells(), wide, ios, msg)
            else
                call write_types_block(unit, vtk_cell_type(m%element), m%n_cells(), ios, msg)
            end if
            if (ios /= 0) return
            ! The offsets in the XML are promises about these positions: keep each one.
            inquire (unit, pos=position, iostat=ios, iomsg=msg)
            if (ios /= 0) return
            if (position /= data_start + offset(k + 1)) then
                ios = -1
                msg = 'internal error: array '//to_string(k)//' ends at byte ' &
                      //to_string(position - data_start)//', not '//to_string(offset(k + 1))
                return
            end if
        end do
        write (unit, iostat=ios, iomsg=msg) LF//'  </AppendedData>'//LF//'</VTKFile>'//LF
    end subroutine write_binary_grid

    !> A (dim, n) nodal array as n Float64 triples (a plane one with z = 0), a chunk of nodes
    !> at a time.
    subroutine write_vector_block(unit, xy, ios, msg)
        integer, intent(in) :: unit
        real(wp), intent(in) :: xy(:, :)
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        real(wp), allocatable :: buffer(:, :)
        integer :: first, last

        ios = 0
        allocate (buffer(3, min(CHUNK, size(xy, 2))))
        buffer(size(xy, 1) + 1:, :) = 0.0_wp
        do first = 1, size(xy, 2), CHUNK
            last = min(first + CHUNK - 1, size(xy, 2))
            buffer(1:size(xy, 1), 1:last - first + 1) = xy(:, first:last)
            write (unit, iostat=ios, iomsg=msg) buffer(:, 1:last - first + 1)
            if (ios /= 0) return
        end do
    end subroutine write_vector_block

    !> Cell nodes in VTK order, counted from 0, as Int32 or (wide) Int64.
    subroutine write_connectivity_block(unit, m, wide, ios, msg)
        integer, intent(in) :: unit
        type(mesh_t), intent(in) :: m
        logical, intent(in) :: wide
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer :: order(size(m%cells, 1)), first, last

        ios = 0
        order = vtk_node_order(m%element)
        do first = 1, m%n_cells(), CHUNK
            last = min(first + CHUNK - 1, m%n_cells())
            if (wide) then
                write (unit, iostat=ios, iomsg=msg) int(m%cells(order, first:last) - 1, int64)
            else
                write (unit, iostat=ios, iomsg=msg) int(m%cells(order, first:last) - 1, int32)
            end if
            if (ios /= 0) return
        end do
    end subroutine write_connectivity_block

    !> Where each cell ends in connectivity: the running node count.
    subroutine write_offsets_block(unit, nodes_per_cell, n_cells, wide, ios, msg)
        integer, intent(in) :: unit, nodes_per_cell, n_cells
        logical, intent(in) :: wide
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer :: first, last, e

        ios = 0
        do first = 1, n_cells, CHUNK
            last = min(first + CHUNK - 1, n_cells)
            if (wide) then
                write (unit, iostat=ios, iomsg=msg) &
                    [(int(nodes_per_cell, int64)*e, e=first, last)]
            else
                write (unit, iostat=ios, iomsg=msg) &
                    [(int(nodes_per_cell, int32)*int(e, int32), e=first, last)]
            end if
            if (ios /= 0) return
        end do
    end subroutine write_offsets_block

    !> One UInt8 cell type per cell (every code used is below 128).
    subroutine write_types_block(unit, cell_type, n_cells, ios, msg)
        integer, intent(in) :: unit, cell_type, n_cells
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer :: first, last

        ios = 0
        do first = 1, n_cells, CHUNK
            last = min(first + CHUNK - 1, n_cells)
            write (unit, iostat=ios, iomsg=msg) spread(int(cell_type, int8), 1, last - first + 1)
            if (ios /= 0) return
        end do
    end subroutine write_types_block

    !> The XML with every value as text; returns at the first failed write with its iostat
    !> and message.
    subroutine write_ascii_grid(unit, m, names, vectors, cell_names, cell_values, fields_xml, &
                                ios, msg)
        integer, intent(in) :: unit
        type(mesh_t), intent(in) :: m
        character(len=*), intent(in) :: names(:), cell_names(:)
        real(wp), intent(in) :: vectors(:, :, :), cell_values(:, :)
        character(len=*), intent(in) :: fields_xml   !! field_data_xml's block, or ''
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, allocatable :: order(:)
        integer(i8), allocatable :: offsets(:)
        integer :: e, k

        write (unit, '(a)', iostat=ios, iomsg=msg) xml_prolog(), '  <UnstructuredGrid>'
        if (ios /= 0) return
        if (len(fields_xml) > 0) &
            write (unit, '(a)', iostat=ios, iomsg=msg, advance='no') fields_xml
        if (ios /= 0) return
        write (unit, '(a)', iostat=ios, iomsg=msg) piece_tag(m)
        if (ios /= 0) return

        if (size(names) > 0) then
            write (unit, '(a)', iostat=ios, iomsg=msg) &
                '      <PointData Vectors="'//xml_escaped(trim(names(1)))//'">'
            if (ios /= 0) return
            do k = 1, size(names)
                call write_ascii_reals(unit, trim(names(k)), vectors(:, :, k), ios, msg)
                if (ios /= 0) return
            end do
            write (unit, '(a)', iostat=ios, iomsg=msg) '      </PointData>'
            if (ios /= 0) return
        end if
        if (size(cell_names) > 0) then
            write (unit, '(a)', iostat=ios, iomsg=msg) &
                '      <CellData Scalars="'//xml_escaped(trim(cell_names(1)))//'">'
            if (ios /= 0) return
            do k = 1, size(cell_names)
                call write_ascii_reals(unit, trim(cell_names(k)), &
                                       reshape(cell_values(:, k), [1, m%n_cells()]), ios, msg)
                if (ios /= 0) return
            end do
            write (unit, '(a)', iostat=ios, iomsg=msg) '      </CellData>'
            if (ios /= 0) return
        end if

        write (unit, '(a)', iostat=ios, iomsg=msg) '      <Points>'
        if (ios /= 0) return
        call write_ascii_reals(unit, '', m%coords, ios, msg)
        if (ios /= 0) return
        write (unit, '(a)', iostat=ios, iomsg=msg) '      </Points>', &
            '      <Cells>', data_array_tag('Int64', 'connectivity', 0, INLINE)
        if (ios /= 0) return
        order = vtk_node_order(m%element)
        do e = 1, m%n_cells()
            ! VTK counts points from 0.
            write (unit, INT_FORMAT, iostat=ios, iomsg=msg) m%cells(order, e) - 1
            if (ios /= 0) return
        end do
        write (unit, '(a)', iostat=ios, iomsg=msg) '        </DataArray>', &
            data_array_tag('Int64', 'offsets', 0, INLINE)
        if (ios /= 0) return
        ! Offsets mark where each cell ends in connectivity: the running node count.
        offsets = [(int(size(m%cells, 1), i8)*e, e=1, m%n_cells())]
        call write_in_lines(unit, offsets, ios, msg)
        if (ios /= 0) return
        write (unit, '(a)', iostat=ios, iomsg=msg) '        </DataArray>', &
            data_array_tag('UInt8', 'types', 0, INLINE)
        if (ios /= 0) return
        call write_in_lines(unit, spread(int(vtk_cell_type(m%element), i8), 1, m%n_cells()), &
                            ios, msg)
        if (ios /= 0) return
        write (unit, '(a)', iostat=ios, iomsg=msg) '        </DataArray>', '      </Cells>', &
            '    </Piece>', '  </UnstructuredGrid>', '</VTKFile>'
    end subroutine write_ascii_grid

    !> One inline Float64 DataArray `name` of `columns` (components x n), a line per column:
    !> a plane vector gets a zero z (VTK's vectors have three components), a scalar stays one.
    subroutine write_ascii_reals(unit, name, columns, ios, msg)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: columns(:, :)
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        real(wp), parameter :: PADDING(2) = 0.0_wp
        logical :: vector
        integer :: i
        vector = size(columns, 1) > 1
        write (unit, '(a)', iostat=ios, iomsg=msg) &
            data_array_tag('Float64', name, merge(3, 0, vector), INLINE)
        if (ios /= 0) return
        do i = 1, size(columns, 2)
            if (vector) then
                write (unit, REAL_FORMAT, iostat=ios, iomsg=msg) columns(:, i), &
                    PADDING(:3 - size(columns, 1))
            else
                write (unit, REAL_FORMAT, iostat=ios, iomsg=msg) columns(:, i)
            end if
            if (ios /= 0) return
        end do
        write (unit, '(a)', iostat=ios, iomsg=msg) '        </DataArray>'
    end subroutine write_ascii_reals

    !> VTK cell type of an ELEMENT_* code; 0 for an unknown code.
    pure integer function vtk_cell_type(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_P1); vtk_cell_type = VTK_TRIANGLE
        case (ELEMENT_Q1); vtk_cell_type = VTK_QUAD
        case (ELEMENT_P2); vtk_cell_type = VTK_QUADRATIC_TRIANGLE
        case (ELEMENT_Q2); vtk_cell_type = VTK_BIQUADRATIC_QUAD
        case (ELEMENT_P3, ELEMENT_P4); vtk_cell_type = VTK_LAGRANGE_TRIANGLE
        case default; vtk_cell_type = 0
        end select
    end function vtk_cell_type

    !> Position in our (Gmsh) cell of each VTK cell node. Both number corners anticlockwise,
    !> then mid-edge nodes with edge k from corner k to corner k+1, then the Q2 centre; so
    !> the orders coincide, and this is where a difference would go. The VTK Lagrange
    !> triangle too lists corners, then the edge nodes edge by edge from corner k towards
    !> corner k+1, then the interior nodes as a triangle of degree p - 3 (P3: the centre;
    !> P4: three nodes, next to corners 1, 2, 3; vtkHigherOrderTriangle's parametric
    !> coordinates): Gmsh's order up to degree 4.
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
                           //to_string(m%element))
        else if (size(m%cells, 1) /= element_nodes_per_cell(m%element)) then
            call stat%fail(STATUS_INTERNAL, 'write_vtu: cells have ' &
                           //to_string(size(m%cells, 1))//' nodes, the element needs ' &
                           //to_string(element_nodes_per_cell(m%element)))
        else if (size(m%coords, 1) /= m%dim() .or. m%dim() > 3) then
            call stat%fail(STATUS_INTERNAL, 'write_vtu: coordinates must be ('// &
                           to_string(m%dim())//', n_nodes), at most 3 components')
        else if (m%n_cells() > 0) then
            if (minval(m%cells) < 1 .or. maxval(m%cells) > m%n_nodes()) then
                call stat%fail(STATUS_INTERNAL, 'write_vtu: a cell refers to a missing node')
            end if
        end if
        if (.not. stat%ok()) return
        if (size(vectors, 3) /= size(names) .or. size(vectors, 1) /= m%dim() .or. &
            (size(names) > 0 .and. size(vectors, 2) /= m%n_nodes())) then
            call stat%fail(STATUS_INTERNAL, 'write_vtu: fields must be ('// &
                           to_string(m%dim())//', n_nodes, n_names)')
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
