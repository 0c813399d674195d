! SPDX-License-Identifier: MIT
!> The .vtu of two P1 triangles on the unit square with one vector field: sizes,
!> 0-based connectivity, offsets, cell types and the field, read back from the text.
program test_vtk_writer
    use kinds, only: wp
    use status, only: status_t, STATUS_INTERNAL
    use mesh, only: mesh_t, ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2
    use vtk_writer, only: write_vtu, vtk_cell_type, vtk_node_order
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t
    type(mesh_t) :: m
    type(status_t) :: stat
    real(wp) :: field(2, 4, 1), values(12)
    integer :: connectivity(6), offsets(2), types(2)
    character(len=:), allocatable :: text

    t%name = 'test_vtk_writer'

    ! Unit square cut by the diagonal from node 1 (0,0) to node 3 (1,1); nodes 2 (1,0) and
    ! 4 (0,1); both cells anticlockwise. VTK wants nodes 1..4 as 0..3.
    m%element = ELEMENT_P1
    m%coords = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
    m%cells = reshape([1, 2, 3, 1, 3, 4], [3, 2])
    field(:, :, 1) = reshape([0.0_wp, 0.0_wp, 0.5_wp, 0.0_wp, 0.5_wp, -0.25_wp, &
                              0.0_wp, -0.25_wp], [2, 4])

    call write_vtu('two_triangles.vtu', m, ['displacement'], field, stat)
    call t%check('write succeeds', stat%ok())
    text = file_text('two_triangles.vtu')
    call t%check('XML declaration first', index(text, '<?xml version="1.0"?>') == 1)
    call t%check('an UnstructuredGrid', index(text, '<VTKFile type="UnstructuredGrid"') > 0)
    call t%check('NumberOfPoints = 4', index(text, 'NumberOfPoints="4"') > 0)
    call t%check('NumberOfCells = 2', index(text, 'NumberOfCells="2"') > 0)
    call t%check('field named and 3-component', index(text, 'Name="displacement" ' &
                 //'NumberOfComponents="3" format="ascii"') > 0)
    call t%check('field is the active vector', index(text, 'Vectors="displacement"') > 0)
    call t%check('file is complete', index(text, '</VTKFile>') > 0)

    call read_array('Name="connectivity"', connectivity)
    call t%check('connectivity is 0-based', all(connectivity == [0, 1, 2, 0, 2, 3]))
    call read_array('Name="offsets"', offsets)
    call t%check('offsets end each cell', all(offsets == [3, 6]))
    call read_array('Name="types"', types)
    call t%check('types are VTK_TRIANGLE = 5', all(types == 5))
    call read_reals('Name="displacement"', values)
    call t%check('field values with z = 0', all(abs(values - [0.0_wp, 0.0_wp, 0.0_wp, &
                 0.5_wp, 0.0_wp, 0.0_wp, 0.5_wp, -0.25_wp, 0.0_wp, 0.0_wp, -0.25_wp, &
                 0.0_wp]) <= 0.0_wp))
    call read_reals('<Points>', values)
    call t%check('points with z = 0', all(abs(values - [0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
                 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp]) <= 0.0_wp))

    ! VTK's numbers for the four elements, and node orders that match Gmsh's.
    call t%check('P1 is VTK_TRIANGLE', vtk_cell_type(ELEMENT_P1) == 5)
    call t%check('Q1 is VTK_QUAD', vtk_cell_type(ELEMENT_Q1) == 9)
    call t%check('P2 is VTK_QUADRATIC_TRIANGLE', vtk_cell_type(ELEMENT_P2) == 22)
    call t%check('Q2 is VTK_BIQUADRATIC_QUAD', vtk_cell_type(ELEMENT_Q2) == 28)
    call t%check('Q2 node order is Gmsh order', all(vtk_node_order(ELEMENT_Q2) == &
                 [1, 2, 3, 4, 5, 6, 7, 8, 9]))

    call write_vtu('bad.vtu', m, ['a', 'b'], field, stat)
    call t%check('names and fields must match', stat%code == STATUS_INTERNAL)
    call write_vtu('no_such_dir/x.vtu', m, ['displacement'], field, stat)
    call t%check('unwritable path fails', .not. stat%ok())

    ! gfortran 12 keeps main-program allocatables in a frame gone before LeakSanitizer
    ! looks: free them here so a sanitizer build reports only real leaks.
    deallocate (text)
    call t%report()

contains

    function file_text(path) result(text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text
        character(len=1000) :: line
        integer :: unit, ios
        text = ''
        open (newunit=unit, file=path, status='old', action='read')
        do
            read (unit, '(a)', iostat=ios) line
            if (ios /= 0) exit
            text = text//trim(line)//' '
        end do
        close (unit)
    end function file_text

    !> The integers that follow the first '>' after `marker`, up to the next '<'.
    subroutine read_array(marker, array)
        character(len=*), intent(in) :: marker
        integer, intent(out) :: array(:)
        character(len=:), allocatable :: body
        integer :: ios
        body = data_after(marker)
        array = -1
        read (body, *, iostat=ios) array
        call t%check('read '//marker, ios == 0)
    end subroutine read_array

    subroutine read_reals(marker, array)
        character(len=*), intent(in) :: marker
        real(wp), intent(out) :: array(:)
        character(len=:), allocatable :: body
        integer :: ios
        body = data_after(marker)
        array = -1.0_wp
        read (body, *, iostat=ios) array
        call t%check('read '//marker, ios == 0)
    end subroutine read_reals

    !> Content of the DataArray whose tag contains `marker`, or of the first DataArray
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
end program test_vtk_writer
