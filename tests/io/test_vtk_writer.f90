! SPDX-License-Identifier: MIT
!> The .vtu writer in both encodings. Two P1 triangles with two vector fields are written
!> as 'ascii' and as 'binary'; the text file is parsed as numbers, the binary one is read
!> back the way VTK does (the XML gives each array's type and offset, the appended block
!> gives a UInt64 byte count and the raw values), and both must give exactly the values
!> written: es24.16 has 17 significant digits, which round-trip binary64, and raw bytes are
!> the values themselves, so any difference at all is a bug. Then the cell types, offsets
!> and connectivity of P1, Q1, P2 and Q2 rectangles, and the errors.
program test_vtk_writer
    use iso_fortran_env, only: int8, int32, int64
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_INTERNAL, STATUS_IO
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4
    use mesh_structured, only: structured_rectangle
    use vtk_writer, only: write_vtu, vtk_cell_type, vtk_node_order, machine_byte_order, &
                          VTK_BINARY, VTK_ASCII
    use strings, only: to_string
    use testing, only: test_suite_t
    use fixtures, only: file_text
    implicit none
    type(test_suite_t) :: t
    type(mesh_t) :: m
    type(status_t) :: stat
    real(wp) :: fields(2, 4, 2), text_values(12), binary_values(12), expected(12)
    integer(i8), allocatable :: text_ints(:), binary_ints(:)
    character(len=:), allocatable :: text, xml
    character(len=17), parameter :: NAMES(2) = [character(len=17) :: 'displacement', &
                                                 'displacement_imag']
    integer, parameter :: ELEMENTS(6) = [ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, &
                                         ELEMENT_P3, ELEMENT_P4]
    !> VTK's vtkCellType.h: P3 and P4 as VTK_LAGRANGE_TRIANGLE
    integer, parameter :: VTK_CODES(6) = [5, 9, 22, 28, 69, 69]
    character(len=*), parameter :: REAL_ARRAYS(3) = [character(len=19) :: &
        'Name="displacement"', 'Name="displacement_', '<Points>']
    character(len=*), parameter :: INT_ARRAYS(3) = [character(len=19) :: &
        'Name="connectivity"', 'Name="offsets"', 'Name="types"']
    integer, parameter :: INT_LENGTHS(3) = [6, 2, 2]
    integer :: i, k, n_cells, n_per_cell

    t%name = 'test_vtk_writer'

    ! Unit square cut by the diagonal from node 1 (0,0) to node 3 (1,1); nodes 2 (1,0) and
    ! 4 (0,1); both cells anticlockwise. VTK wants nodes 1..4 as 0..3. Field values with
    ! 17 significant digits, a tiny and a large magnitude, and both signs.
    m%element = ELEMENT_P1
    m%coords = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
    m%cells = reshape([1, 2, 3, 1, 3, 4], [3, 2])
    fields(:, :, 1) = reshape([0.0_wp, 0.0_wp, 0.5_wp, 0.0_wp, 0.5_wp, -0.25_wp, &
                               0.0_wp, -0.25_wp], [2, 4])
    fields(:, :, 2) = reshape([1.0_wp/3.0_wp, -2.0_wp/7.0_wp, 1.0e-300_wp, -1.0e300_wp, &
                               sqrt(2.0_wp), -12345.678901234567_wp, 0.1_wp, -0.0_wp], [2, 4])

    call write_vtu('two_triangles.vtu', m, NAMES, fields, VTK_ASCII, stat)
    call t%check('ascii write succeeds', stat%ok())
    call write_vtu('two_triangles_binary.vtu', m, NAMES, fields, VTK_BINARY, stat)
    call t%check('binary write succeeds', stat%ok())

    text = file_text('two_triangles.vtu', ' ')
    call t%check('ascii: XML declaration first', index(text, '<?xml version="1.0"?>') == 1)
    call t%check('ascii: an UnstructuredGrid', index(text, '<VTKFile type="UnstructuredGrid"') > 0)
    call t%check('ascii: NumberOfPoints = 4', index(text, 'NumberOfPoints="4"') > 0)
    call t%check('ascii: NumberOfCells = 2', index(text, 'NumberOfCells="2"') > 0)
    call t%check('ascii: field named and 3-component', index(text, 'Name="displacement" ' &
                 //'NumberOfComponents="3" format="ascii"') > 0)
    call t%check('ascii: first field is the active vector', &
                 index(text, 'Vectors="displacement"') > 0)
    call t%check('ascii: file is complete', index(text, '</VTKFile>') > 0)

    xml = binary_xml('two_triangles_binary.vtu')
    call t%check('binary: XML declaration first', index(xml, '<?xml version="1.0"?>') == 1)
    call t%check('binary: version 1.0 with UInt64 headers', index(xml, 'version="1.0" ' &
                 //'byte_order="'//machine_byte_order()//'" header_type="UInt64"') > 0)
    call t%check('binary: raw appended data', index(xml, '<AppendedData encoding="raw">') > 0)
    call t%check('binary: same piece sizes', &
                 index(xml, 'NumberOfPoints="4" NumberOfCells="2"') > 0)
    call t%check('binary: first field is the active vector', &
                 index(xml, 'Vectors="displacement"') > 0)
    call t%check('binary: small mesh gets Int32 indices', &
                 index(xml, 'type="Int32" Name="connectivity"') > 0)
    call t%check('binary: types are UInt8', index(xml, 'type="UInt8" Name="types"') > 0)
    call t%check('binary: appended block and file end right after the last array', &
                 ends_after_last_array('two_triangles_binary.vtu'))

    ! Every real array: binary = text = the values written (z = 0), exactly.
    do k = 1, 3
        call read_text_reals(trim(REAL_ARRAYS(k)), text_values)
        call read_binary_reals('two_triangles_binary.vtu', trim(REAL_ARRAYS(k)), binary_values)
        if (k <= size(NAMES)) then
            expected = [(fields(:, i, min(k, size(NAMES))), 0.0_wp, i=1, 4)]
        else
            expected = [(m%coords(:, i), 0.0_wp, i=1, 4)]
        end if
        call t%check('text = written: '//trim(REAL_ARRAYS(k)), &
                     all(abs(text_values - expected) <= 0.0_wp))
        call t%check('binary = text: '//trim(REAL_ARRAYS(k)), &
                     all(abs(binary_values - text_values) <= 0.0_wp))
        ! == cannot tell -0.0 from 0.0; the bytes must.
        if (k == 2) call t%check('binary keeps the sign of -0.0', &
                                 sign(1.0_wp, binary_values(11)) < 0.0_wp)
    end do

    ! Every integer array: binary = text = what VTK needs.
    do k = 1, 3
        call read_text_ints(trim(INT_ARRAYS(k)), INT_LENGTHS(k), text_ints)
        call read_binary_ints('two_triangles_binary.vtu', trim(INT_ARRAYS(k)), binary_ints)
        select case (k)
        case (1); call t%check('connectivity is 0-based', all(text_ints == [0, 1, 2, 0, 2, 3]))
        case (2); call t%check('offsets end each cell', all(text_ints == [3, 6]))
        case (3); call t%check('types are VTK_TRIANGLE = 5', all(text_ints == 5))
        end select
        call t%check('binary = text: '//trim(INT_ARRAYS(k)), &
                     size(binary_ints) == size(text_ints))
        if (size(binary_ints) == size(text_ints)) call t%check('binary = text: ' &
            //trim(INT_ARRAYS(k)), all(binary_ints == text_ints))
    end do

    ! VTK's numbers for the four elements, node orders that match Gmsh's, and a 2 x 1
    ! rectangle of each written both ways: types, offsets n_per_cell * (1..n_cells), and
    ! connectivity = cells - 1 in both files.
    call t%check('Q2 node order is Gmsh order', all(vtk_node_order(ELEMENT_Q2) == &
                 [1, 2, 3, 4, 5, 6, 7, 8, 9]))
    do k = 1, size(ELEMENTS)
        call t%check('cell type code '//to_string(VTK_CODES(k)), &
                     vtk_cell_type(ELEMENTS(k)) == VTK_CODES(k))
        call check_element(ELEMENTS(k), VTK_CODES(k))
    end do

    ! Cell data (the error indicators): both encodings give back the values written, and
    ! the point arrays after them still read right.
    call write_vtu('cells.vtu', m, NAMES(1:1), fields(:, :, 1:1), VTK_ASCII, stat, &
                   ['error_indicator'], reshape([0.125_wp, 1.0e-300_wp], [2, 1]))
    call t%check('ascii write with cell data succeeds', stat%ok())
    text = file_text('cells.vtu', ' ')
    call t%check('ascii: CellData marks the scalars', &
                 index(text, '<CellData Scalars="error_indicator">') > 0)
    call read_text_reals('Name="error_indicator"', text_values(1:2))
    call t%check('ascii: cell values as written', &
                 all(abs(text_values(1:2) - [0.125_wp, 1.0e-300_wp]) <= 0.0_wp))
    call write_vtu('cells_binary.vtu', m, NAMES(1:1), fields(:, :, 1:1), VTK_BINARY, stat, &
                   ['error_indicator'], reshape([0.125_wp, 1.0e-300_wp], [2, 1]))
    call t%check('binary write with cell data succeeds', stat%ok())
    call read_binary_reals('cells_binary.vtu', 'Name="error_indicator"', binary_values(1:2))
    call t%check('binary: cell values as written', &
                 all(abs(binary_values(1:2) - [0.125_wp, 1.0e-300_wp]) <= 0.0_wp))
    call read_binary_reals('cells_binary.vtu', '<Points>', binary_values)
    call t%check('binary: points after the cell data', &
                 all(abs(binary_values - [(m%coords(:, i), 0.0_wp, i=1, 4)]) <= 0.0_wp))
    call t%check('binary: file ends right after the last array', &
                 ends_after_last_array('cells_binary.vtu'))
    call write_vtu('bad.vtu', m, NAMES(1:1), fields(:, :, 1:1), VTK_BINARY, stat, &
                   ['error_indicator'], reshape([1.0_wp, 2.0_wp, 3.0_wp], [3, 1]))
    call t%check('cell fields must have one value per cell', stat%code == STATUS_INTERNAL)

    call write_vtu('bad.vtu', m, ['a', 'b'], fields(:, :, 1:1), VTK_BINARY, stat)
    call t%check('names and fields must match', stat%code == STATUS_INTERNAL)
    call write_vtu('bad.vtu', m, NAMES, fields, 'base64', stat)
    call t%check('unknown format is an internal error', stat%code == STATUS_INTERNAL .and. &
                 index(stat%message, "'base64'") > 0)
    call write_vtu('no_such_dir/x.vtu', m, NAMES, fields, VTK_BINARY, stat)
    call t%check('unwritable path fails (binary)', stat%code == STATUS_IO .and. &
                 index(stat%message, 'no_such_dir/x.vtu') > 0)
    call write_vtu('no_such_dir/x.vtu', m, NAMES, fields, VTK_ASCII, stat)
    call t%check('unwritable path fails (ascii)', stat%code == STATUS_IO)

    ! gfortran 12 keeps main-program allocatables in a frame gone before LeakSanitizer
    ! looks: free them here so a sanitizer build reports only real leaks.
    deallocate (text, xml, text_ints, binary_ints)
    call field_data_in_both_encodings()
    call t%report()

contains

    subroutine check_element(element, code)
        integer, intent(in) :: element, code
        type(mesh_t) :: r
        character(len=:), allocatable :: name, saved_text
        integer(i8), allocatable :: from_text(:), from_binary(:)
        integer :: e

        name = 'element_'//to_string(code)
        call structured_rectangle(2.0_wp, 1.0_wp, 2, 1, element, 'right', r, stat)
        call t%check(name//': mesh', stat%ok())
        if (.not. stat%ok()) return
        call write_vtu(name//'.vtu', r, NAMES(1:1), reshape(r%coords, [2, r%n_nodes(), 1]), &
                       VTK_ASCII, stat)
        call t%check(name//': ascii write', stat%ok())
        call write_vtu(name//'_binary.vtu', r, NAMES(1:1), &
                       reshape(r%coords, [2, r%n_nodes(), 1]), VTK_BINARY, stat)
        call t%check(name//': binary write', stat%ok())
        saved_text = text
        text = file_text(name//'.vtu', ' ')
        n_cells = r%n_cells()
        n_per_cell = size(r%cells, 1)

        call read_text_ints('Name="types"', n_cells, from_text)
        call read_binary_ints(name//'_binary.vtu', 'Name="types"', from_binary)
        call t%check(name//': ascii types', all(from_text == code))
        call t%check(name//': binary types', size(from_binary) == n_cells .and. &
                     all(from_binary == code))
        call read_text_ints('Name="offsets"', n_cells, from_text)
        call read_binary_ints(name//'_binary.vtu', 'Name="offsets"', from_binary)
        call t%check(name//': ascii offsets', all(from_text == [(n_per_cell*e, e=1, n_cells)]))
        call t%check(name//': binary offsets', size(from_binary) == n_cells .and. &
                     all(from_binary == [(n_per_cell*e, e=1, n_cells)]))
        call read_text_ints('Name="connectivity"', n_per_cell*n_cells, from_text)
        call read_binary_ints(name//'_binary.vtu', 'Name="connectivity"', from_binary)
        call t%check(name//': ascii connectivity', all(from_text == &
                     reshape(r%cells(vtk_node_order(element), :) - 1, [n_per_cell*n_cells])))
        call t%check(name//': binary connectivity', size(from_binary) == size(from_text))
        if (size(from_binary) == size(from_text)) &
            call t%check(name//': binary connectivity', all(from_binary == from_text))
        text = saved_text
    end subroutine check_element
    !> The `n` integers of the text DataArray found by `marker`.
    subroutine read_text_ints(marker, n, values)
        character(len=*), intent(in) :: marker
        integer, intent(in) :: n
        integer(i8), allocatable, intent(out) :: values(:)
        character(len=:), allocatable :: body
        integer :: ios
        allocate (values(n))
        values = -1
        body = data_after(marker)
        read (body, *, iostat=ios) values
        call t%check('read text '//marker, ios == 0)
    end subroutine read_text_ints

    subroutine read_text_reals(marker, values)
        character(len=*), intent(in) :: marker
        real(wp), intent(out) :: values(:)
        character(len=:), allocatable :: body
        integer :: ios
        values = -1.0_wp
        body = data_after(marker)
        read (body, *, iostat=ios) values
        call t%check('read text '//marker, ios == 0)
    end subroutine read_text_reals

    !> Content of the text DataArray whose tag contains `marker`, or of the first DataArray
    !> after the element `marker` ('<Points>').
    function data_after(marker) result(body)
        character(len=*), intent(in) :: marker
        character(len=:), allocatable :: body
        integer :: first, last
        first = index(text, marker)
        body = ''
        if (first == 0) return
        if (marker(1:1) == '<') first = first + index(text(first + 1:), '<DataArray')
        first = first + index(text(first:), '>')
        last = first + index(text(first:), '<') - 2
        body = text(first:last)
    end function data_after

    !> The XML part of a binary .vtu: everything up to and including the '_' that starts
    !> the appended data (which may hold any byte, '<' included).
    function binary_xml(path) result(xml)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: xml
        character(len=:), allocatable :: bytes
        integer :: unit, n, start
        open (newunit=unit, file=path, status='old', action='read', access='stream', &
              form='unformatted')
        inquire (unit, size=n)
        allocate (character(len=n) :: bytes)
        read (unit) bytes
        close (unit)
        start = index(bytes, '<AppendedData encoding="raw">')
        xml = ''
        if (start == 0) return
        xml = bytes(:start + index(bytes(start:), '_') - 1)
    end function binary_xml

    !> Attribute `name` of the DataArray tag that `marker` finds in `xml` (for '<Points>', the
    !> first DataArray after it).
    function attribute(xml, marker, name) result(value)
        character(len=*), intent(in) :: xml, marker, name
        character(len=:), allocatable :: value
        integer :: first, last, at
        value = ''
        first = index(xml, marker)
        if (first == 0) return
        if (marker(1:1) == '<') then
            first = first + index(xml(first + 1:), '<DataArray')
        else
            first = index(xml(:first), '<', back=.true.)
        end if
        last = first + index(xml(first:), '>') - 1
        at = index(xml(first:last), ' '//name//'="')
        if (at == 0) return
        at = first + at + len(name) + 2
        value = xml(at:at + index(xml(at:last), '"') - 2)
    end function attribute

    !> Open `path` as a stream, position on the array that `marker` finds and read its UInt64
    !> byte count, decoding the 8 bytes by the file's byte_order attribute (so a wrong
    !> attribute shows here, independently of the writer's machine_byte_order). A count
    !> beyond the end of the file is reported and returned as -1.
    subroutine open_array(path, marker, unit, type, n_bytes)
        character(len=*), intent(in) :: path, marker
        integer, intent(out) :: unit
        character(len=:), allocatable, intent(out) :: type
        integer(i8), intent(out) :: n_bytes
        character(len=:), allocatable :: xml, offset_text
        integer(int8) :: header(8)
        integer(i8) :: offset
        integer :: i, ios, file_bytes
        logical :: little

        xml = binary_xml(path)
        type = attribute(xml, marker, 'type')
        call t%check('binary '//marker//' is appended', &
                     attribute(xml, marker, 'format') == 'appended')
        offset_text = attribute(xml, marker, 'offset')
        read (offset_text, *, iostat=ios) offset
        call t%check('binary '//marker//' has an offset', ios == 0)
        little = index(xml, 'byte_order="LittleEndian"') > 0
        open (newunit=unit, file=path, status='old', action='read', access='stream', &
              form='unformatted')
        ! Stream positions count from 1, offsets from the byte after the '_'.
        read (unit, pos=len(xml) + 1 + offset) header
        n_bytes = 0
        do i = 1, 8
            if (little) then
                n_bytes = n_bytes + int(iand(int(header(i), i8), 255_i8), i8)*256_i8**(i - 1)
            else
                n_bytes = n_bytes + int(iand(int(header(i), i8), 255_i8), i8)*256_i8**(8 - i)
            end if
        end do
        inquire (unit, size=file_bytes)
        if (n_bytes < 0 .or. len(xml) + offset + 8 + n_bytes > file_bytes) then
            call t%check('binary '//marker//' byte count within the file', .false.)
            n_bytes = -1
        end if
    end subroutine open_array

    subroutine read_binary_reals(path, marker, values)
        character(len=*), intent(in) :: path, marker
        real(wp), intent(out) :: values(:)
        character(len=:), allocatable :: type
        integer(i8) :: n_bytes
        integer :: unit
        call open_array(path, marker, unit, type, n_bytes)
        call t%check('binary '//marker//' is Float64', type == 'Float64')
        call t%check('binary '//marker//' byte count', n_bytes == 8*size(values))
        values = -1.0_wp
        if (n_bytes == 8*size(values)) read (unit) values
        close (unit)
    end subroutine read_binary_reals

    subroutine read_binary_ints(path, marker, values)
        character(len=*), intent(in) :: path, marker
        integer(i8), allocatable, intent(out) :: values(:)
        character(len=:), allocatable :: type
        integer(int8), allocatable :: bytes(:)
        integer(int32), allocatable :: words(:)
        integer(int64), allocatable :: longs(:)
        integer(i8) :: n_bytes
        integer :: unit
        call open_array(path, marker, unit, type, n_bytes)
        if (n_bytes < 0) type = 'unreadable'
        select case (type)
        case ('UInt8')
            allocate (bytes(n_bytes))
            read (unit) bytes
            values = iand(int(bytes, i8), 255_i8)
        case ('Int32')
            allocate (words(n_bytes/4))
            read (unit) words
            values = int(words, i8)
        case ('Int64')
            allocate (longs(n_bytes/8))
            read (unit) longs
            values = int(longs, i8)
        case default
            call t%check('binary '//marker//': known integer type, not '//type, .false.)
            allocate (values(0))
        end select
        close (unit)
    end subroutine read_binary_ints

    !> The last array (types, 2 bytes) ends where '</AppendedData>' and '</VTKFile>' follow.
    logical function ends_after_last_array(path)
        character(len=*), intent(in) :: path
        character(len=*), parameter :: TAIL = achar(10)//'  </AppendedData>'//achar(10) &
                                               //'</VTKFile>'//achar(10)
        character(len=:), allocatable :: type, rest
        integer(i8) :: n_bytes, position
        integer :: unit, size_bytes
        call open_array(path, 'Name="types"', unit, type, n_bytes)
        inquire (unit, pos=position, size=size_bytes)
        close (unit)
        ends_after_last_array = .false.
        if (size_bytes - (position - 1 + n_bytes) /= len(TAIL)) return
        allocate (character(len=len(TAIL)) :: rest)
        open (newunit=unit, file=path, status='old', action='read', access='stream', &
              form='unformatted')
        read (unit, pos=position + n_bytes) rest
        close (unit)
        ends_after_last_array = rest == TAIL
    end function ends_after_last_array

    !> Field data (a mode's mu, lambda, nu): one FieldData block inside UnstructuredGrid and
    !> before the Piece (VTK's place for data of the whole set), a Float64 DataArray per
    !> name with NumberOfTuples="1", whose text reads back to the value written, bit for bit
    !> (es24.16 round-trips binary64), in both encodings.
    subroutine field_data_in_both_encodings()
        character(len=*), parameter :: FILES(2) = [character(len=20) :: 'fields_ascii.vtu', &
                                                   'fields_binary.vtu']
        character(len=*), parameter :: FORMATS(2) = [character(len=6) :: VTK_ASCII, VTK_BINARY]
        character(len=7), parameter :: FIELD_NAMES(3) = [character(len=7) :: 'mu', &
                                                         'lambda', 'nu']
        real(wp), parameter :: VALUES(3) = [0.7516698639178927_wp, -1.0e-300_wp, 0.3_wp]
        character(len=:), allocatable :: header
        real(wp) :: back
        integer :: f, k, at, close_at, ios
        logical :: placed, values_ok
        do f = 1, 2
            call write_vtu(trim(FILES(f)), m, NAMES(1:1), fields(:, :, 1:1), trim(FORMATS(f)), &
                           stat, field_names=FIELD_NAMES, field_values=VALUES)
            header = file_text(trim(FILES(f)), ' ')
            at = index(header, '<AppendedData')
            if (at > 0) header = header(:at)
            placed = stat%ok() .and. index(header, '<FieldData>') > &
                     index(header, '<UnstructuredGrid>') .and. &
                     index(header, '</FieldData>') < index(header, '<Piece ') .and. &
                     index(header, '<FieldData>') == index(header, '<FieldData', back=.true.)
            values_ok = .true.
            do k = 1, size(FIELD_NAMES)
                at = index(header, 'Name="'//trim(FIELD_NAMES(k))//'" NumberOfTuples="1" ' &
                           //'format="ascii">')
                values_ok = values_ok .and. at > 0
                if (.not. values_ok) exit
                at = at + index(header(at:), '>')
                close_at = at + index(header(at:), '</DataArray>') - 2
                read (header(at:close_at), *, iostat=ios) back
                values_ok = values_ok .and. ios == 0 .and. abs(back - VALUES(k)) <= 0.0_wp
            end do
            call t%check('field data ('//trim(FORMATS(f))//'): one block before the Piece', &
                         placed)
            call t%check('field data ('//trim(FORMATS(f))//'): mu, lambda, nu read back '// &
                         'exactly', values_ok)
        end do
    end subroutine field_data_in_both_encodings
end program test_vtk_writer
