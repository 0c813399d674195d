! SPDX-License-Identifier: MIT
!> The Gmsh MSH 4.1 writer: structured meshes of every element type and refined P1/P2 meshes
!> read back by the Gmsh reader to exactly the same nodes, cells, boundary edges (grouped by
!> part) and part names; no partial file is left behind; bad meshes and unwritable paths fail
!> with their status.
program test_gmsh_writer
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_IO
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P2, ELEMENT_P3, MAX_ELEMENT, element_name
    use mesh_structured, only: structured_rectangle
    use mesh_refine, only: refinable_mesh_t, build_refinable_mesh
    use mesh_gmsh, only: read_gmsh
    use mesh_renumber, only: RENUMBER_NONE
    use gmsh_writer, only: write_gmsh
    use filesystem, only: file_exists, remove_file
    use sorting, only: sort_index
    use testing, only: test_suite_t
    use iso_fortran_env, only: output_unit
    implicit none

    type(test_suite_t) :: t
    integer :: element

    t%name = 'test_gmsh_writer'
    do element = ELEMENT_P1, MAX_ELEMENT
        call check_structured(element)
    end do
    call check_refined(ELEMENT_P1)
    call check_refined(ELEMENT_P2)
    call check_refined(ELEMENT_P3)
    call check_errors()
    call t%report()

contains

    subroutine check_structured(element)
        integer, intent(in) :: element
        type(mesh_t) :: m
        type(status_t) :: stat
        call structured_rectangle(1.5_wp, 1.0_wp, 4, 3, element, 'left', m, stat)
        call check_round_trip(m, 'grid_'//element_name(element)//'.msh', &
                              ' (structured '//element_name(element)//')')
    end subroutine check_structured

    !> A graded refined mesh, whose boundary edges are not in the generator's order.
    subroutine check_refined(element)
        integer, intent(in) :: element
        type(mesh_t) :: m, fine
        type(refinable_mesh_t) :: r
        type(status_t) :: stat
        integer :: step
        call structured_rectangle(2.0_wp, 1.5_wp, 3, 2, ELEMENT_P1, 'right', m, stat)
        call build_refinable_mesh(m, r, stat)
        do step = 1, 6
            call r%refine([1, r%n_cells()], stat)
        end do
        call r%to_mesh(element, fine, stat)
        call check_round_trip(fine, 'refined_'//element_name(element)//'.msh', &
                              ' (refined '//element_name(element)//')')
    end subroutine check_refined

    !> Write, read back without renumbering, compare exactly.
    subroutine check_round_trip(m, path, label)
        type(mesh_t), intent(in) :: m
        character(len=*), intent(in) :: path, label
        type(mesh_t) :: back
        type(status_t) :: stat
        integer, allocatable :: by_part(:)

        call write_gmsh(path, m, stat)
        call t%check('write succeeds'//label, stat%ok())
        call t%check('no partial file left'//label, .not. file_exists(path//'.partial'))
        call read_gmsh(path, back, stat, renumber=RENUMBER_NONE)
        call t%check('the reader reads it'//label, stat%ok())
        if (.not. stat%ok()) then
            write (output_unit, '(a)') '      '//stat%message
            return
        end if
        call t%check('same element and sizes'//label, back%element == m%element .and. &
                     all(shape(back%coords) == shape(m%coords)) .and. &
                     all(shape(back%cells) == shape(m%cells)) .and. &
                     all(shape(back%edges) == shape(m%edges)))
        if (.not. all(shape(back%coords) == shape(m%coords))) return
        call t%check('same coordinates, bit for bit'//label, &
                     maxval(abs(back%coords - m%coords)) <= 0.0_wp)
        call t%check('same cells'//label, all(back%cells == m%cells))
        by_part = sort_index(m%edge_part)
        call t%check('same boundary edges and parts, grouped by part'//label, &
                     all(back%edges == m%edges(:, by_part)) .and. &
                     all(back%edge_part == m%edge_part(by_part)))
        call t%check('same part names'//label, size(back%part_names) == size(m%part_names) &
                     .and. all(back%part_names == m%part_names))
        call remove_file(path)
    end subroutine check_round_trip

    subroutine check_errors()
        type(mesh_t) :: m
        type(status_t) :: stat
        logical :: written
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        call write_gmsh('no_such_directory/mesh.msh', m, stat)
        call t%check('unwritable path: STATUS_IO naming the file', stat%code == STATUS_IO &
                     .and. index(stat%message, 'no_such_directory/mesh.msh') > 0)
        m%part_names(2) = 'say "right"'
        call write_gmsh('quoted.msh', m, stat)
        written = file_exists('quoted.msh')
        call t%check('part name with a double quote: STATUS_BAD_INPUT, no file', &
                     stat%code == STATUS_BAD_INPUT .and. .not. written)
        m%part_names(2) = 'right'
        m%edge_part(3) = 5
        call write_gmsh('bad_part.msh', m, stat)
        call t%check('part index out of range: STATUS_BAD_INPUT', &
                     stat%code == STATUS_BAD_INPUT)
    end subroutine check_errors
end program test_gmsh_writer
