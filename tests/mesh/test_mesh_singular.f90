! SPDX-License-Identifier: MIT
!> singular_vertices finds, from geometry and parts alone, where a solution on a triangle
!> mesh can be singular: the corners of a rectangle (not the nodes along its straight
!> sides, nor the edge nodes of higher-order cells), a point where one side changes part
!> (the end of a contact segment), and where a side in no part meets one in a part.
program test_mesh_singular
    use kinds, only: wp
    use status, only: status_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, MAX_ELEMENT, element_corners, element_name
    use mesh_structured, only: structured_rectangle
    use mesh_singular, only: singular_vertices
    use testing, only: test_suite_t
    implicit none

    real(wp), parameter :: CORNERS(2, 4) = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, &
                                                    2.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
    type(test_suite_t) :: t
    type(mesh_t) :: m
    type(status_t) :: stat
    integer :: element
    integer, allocatable :: vertices(:), keep(:)
    integer :: e, bottom

    t%name = 'test_mesh_singular'
    do element = ELEMENT_P1, MAX_ELEMENT
        if (element_corners(element) /= 3) cycle   ! triangle meshes
        call structured_rectangle(2.0_wp, 1.0_wp, 4, 2, element, 'right', m, stat)
        vertices = singular_vertices(m)
        call t%check('a rectangle: its four corners, ascending ('//element_name(element)// &
                     ')', stat%ok() .and. &
                     size(vertices) == 4 .and. all(vertices(2:) > vertices(:3)) .and. &
                     holds_points(m, vertices, CORNERS))
    end do

    ! the bottom's right half a part of its own: (1, 0) joins the corners
    call structured_rectangle(2.0_wp, 1.0_wp, 4, 2, ELEMENT_P1, 'right', m, stat)
    bottom = m%part_index('bottom')
    m%part_names = [m%part_names, m%part_names(1)]
    m%part_names(size(m%part_names)) = 'contact'
    do e = 1, size(m%edge_part)
        if (m%edge_part(e) == bottom .and. minval(m%coords(1, m%edges(:, e))) >= 1.0_wp) &
            m%edge_part(e) = size(m%part_names)
    end do
    vertices = singular_vertices(m)
    call t%check('a part changing along a straight side: the point of change too', &
                 size(vertices) == 5 .and. holds_points(m, vertices, &
                 reshape([CORNERS, 1.0_wp, 0.0_wp], [2, 5])))

    ! the bottom's right half in no part (its edges dropped): the same five points
    call structured_rectangle(2.0_wp, 1.0_wp, 4, 2, ELEMENT_P1, 'right', m, stat)
    bottom = m%part_index('bottom')
    allocate (keep(0))
    do e = 1, size(m%edge_part)
        if (m%edge_part(e) == bottom .and. minval(m%coords(1, m%edges(:, e))) >= 1.0_wp) cycle
        keep = [keep, e]
    end do
    m%edges = m%edges(:, keep)
    m%edge_part = m%edge_part(keep)
    vertices = singular_vertices(m)
    call t%check('a side in no part meeting one in a part: the meeting point', &
                 size(vertices) == 5 .and. holds_points(m, vertices, &
                 reshape([CORNERS, 1.0_wp, 0.0_wp], [2, 5])))
    deallocate (vertices, keep)   ! (AddressSanitizer reports a main program's allocatables)
    call t%report()

contains

    !> Whether the nodes `vertices` of m sit exactly at the points, in any order.
    logical function holds_points(m, vertices, points)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: vertices(:)
        real(wp), intent(in) :: points(:, :)
        integer :: k
        holds_points = size(vertices) == size(points, 2)
        do k = 1, size(points, 2)
            holds_points = holds_points .and. &
                any(sum(abs(m%coords(:, vertices) - spread(points(:, k), 2, size(vertices))), &
                        dim=1) <= 1.0e-14_wp)
        end do
    end function holds_points
end program test_mesh_singular
