! SPDX-License-Identifier: MIT
!> The contact boundary: geometry (outward normal, t = (n2, -n1)), the free nodes on it, the
!> boundary mass matrix and B = (lambda T^T - N^T) M N, against hand-computed values.
program test_contact_boundary
    use kinds, only: wp
    use status, only: status_t, STATUS_MESH
    use testing, only: test_suite_t
    use fixtures, only: single_triangle
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, element_degree
    use mesh_structured, only: structured_rectangle
    use mesh_geometric, only: geometric_mesh
    use dof_map, only: dof_map_t, build_dof_map
    use contact_boundary, only: contact_t, build_contact, assemble_b, edge_mass
    use csr_matrix, only: csr_matrix_t
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_contact_boundary'
    call single_element_mass_and_b(t)
    call normals_point_out_of_every_side(t)
    call mass_integrates_constants_and_linears(t)
    call quadratic_edges_count_mid_nodes(t)
    call bent_contact_is_rejected(t)
    call graded_slanted_contact_is_straight(t)
    call t%report()

contains

    !> model.md section 8: with B, C fixed only A is free on Gamma_C = [A, B]; M = l/3, n = (0,-1),
    !> t = (-1,0), and B has the single column of u_n: B(x, y) = (lambda t_x - n_x) M n_y.
    subroutine single_element_mass_and_b(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: L_SIDE = 0.25_wp, LAMBDA = 3.0_wp
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: b
        type(status_t) :: stat
        real(wp) :: bd(2, 2)
        integer :: i, k
        call single_triangle(L_SIDE, m)
        call build_dof_map(m, [2], dofs, stat)
        call build_contact(m, 1, dofs, contact, stat)
        call t%check('single element: contact built', stat%ok())
        call t%check('single element: p = 1, the node A', contact%p() == 1 .and. &
                     contact%nodes(1) == 1)
        call t%check_close('single element: M = l/3', contact%mass%val(1), L_SIDE/3.0_wp, &
                           1.0e-15_wp)
        call t%check('single element: n = (0,-1), t = (-1,0)', &
            all(abs(contact%normal - [0.0_wp, -1.0_wp]) < 1.0e-15_wp) .and. &
            all(abs(contact%tangent - [-1.0_wp, 0.0_wp]) < 1.0e-15_wp))
        call assemble_b(contact, dofs%n_free, LAMBDA, b, stat)
        bd = 0.0_wp
        do i = 1, 2
            do k = b%row_start(i), b%row_start(i + 1) - 1
                bd(i, b%col(k)) = b%val(k)
            end do
        end do
        ! rows: test dofs (x, y); columns: trial dofs. Only the y column (u_n = -u_y) is nonzero.
        call t%check_close('single element: B(x, y) = -lambda l/3 ... times n_y', bd(1, 2), &
                           (LAMBDA*(-1.0_wp) - 0.0_wp)*L_SIDE/3.0_wp*(-1.0_wp), 1.0e-15_wp)
        call t%check_close('single element: B(y, y) = (0 + 1) l/3 (-1)', bd(2, 2), &
                           (LAMBDA*0.0_wp + 1.0_wp)*L_SIDE/3.0_wp*(-1.0_wp), 1.0e-15_wp)
        call t%check('single element: x column of B is zero', all(abs(bd(:, 1)) < tiny(1.0_wp)))
    end subroutine single_element_mass_and_b

    !> The outward normal of each side of a rectangle, whatever side is in contact.
    subroutine normals_point_out_of_every_side(t)
        type(test_suite_t), intent(inout) :: t
        character(len=6), parameter :: SIDES(4) = ['bottom', 'right ', 'top   ', 'left  ']
        character(len=6), parameter :: OPPOSITE(4) = ['top   ', 'left  ', 'bottom', 'right ']
        real(wp), parameter :: NORMALS(2, 4) = reshape([0.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, &
                                                        0.0_wp, 1.0_wp, -1.0_wp, 0.0_wp], [2, 4])
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(status_t) :: stat
        integer :: s
        call structured_rectangle(2.0_wp, 1.0_wp, 4, 3, ELEMENT_Q1, 'right', m, stat)
        do s = 1, 4
            call build_dof_map(m, [m%part_index(trim(OPPOSITE(s)))], dofs, stat)
            call build_contact(m, m%part_index(trim(SIDES(s))), dofs, contact, stat)
            call t%check('outward normal of '//trim(SIDES(s)), stat%ok() .and. &
                all(abs(contact%normal - NORMALS(:, s)) < 1.0e-15_wp))
            call t%check('t = (n2, -n1) on '//trim(SIDES(s)), &
                all(abs(contact%tangent - [contact%normal(2), -contact%normal(1)]) < tiny(1.0_wp)))
        end do
    end subroutine normals_point_out_of_every_side

    !> The consistent mass matrix integrates products of the edge shape functions exactly:
    !> 1^T M 1 = length and x^T M 1 = int x ds, for edges of every degree, and for cubic and
    !> quartic edges (x^p)^T M (x^p) = int x^(2p) ds, the highest degree M must integrate.
    subroutine mass_integrates_constants_and_linears(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: ELEMENTS(6) = [ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, &
                                             ELEMENT_P3, ELEMENT_P4]
        real(wp), parameter :: WIDTH = 3.0_wp
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(status_t) :: stat
        real(wp), allocatable :: ones(:), x(:), m_ones(:)
        integer :: e, p
        do e = 1, size(ELEMENTS)
            call structured_rectangle(WIDTH, 1.0_wp, 5, 2, ELEMENTS(e), 'left', m, stat)
            call build_dof_map(m, [m%part_index('top')], dofs, stat)
            call build_contact(m, m%part_index('bottom'), dofs, contact, stat)
            allocate (ones(contact%p()), m_ones(contact%p()))
            ones = 1.0_wp
            x = m%coords(1, contact%nodes)
            call contact%mass%matvec(ones, m_ones)
            call t%check_close('1^T M 1 = length, element '//char(48 + e), sum(m_ones), WIDTH, &
                               1.0e-14_wp)
            call t%check_close('x^T M 1 = int x ds, element '//char(48 + e), &
                               dot_product(x, m_ones), WIDTH**2/2.0_wp, 1.0e-14_wp)
            call t%check('nodes ordered along t, element '//char(48 + e), &
                all(dot_product(contact%tangent, [1.0_wp, 0.0_wp])* &
                    (x(2:) - x(:size(x) - 1)) > 0.0_wp))
            p = element_degree(ELEMENTS(e))
            if (p >= 3) then
                call contact%mass%matvec(x**p, m_ones)
                call t%check_close('(x^p)^T M x^p = int x^(2p) ds, element '//char(48 + e), &
                    dot_product(x**p, m_ones), WIDTH**(2*p + 1)/(2*p + 1), 1.0e-13_wp)
                call t%check('p = degree nx + 1, element '//char(48 + e), &
                             contact%p() == p*5 + 1)
            end if
            deallocate (ones, m_ones)
        end do
        call t%check_close('quadratic edge mass: total h', sum(edge_mass(3, 2.0_wp)), 2.0_wp, &
                           1.0e-15_wp)
    end subroutine mass_integrates_constants_and_linears

    !> Quadratic elements put a mid node on every contact edge: p = 2 nx + 1.
    subroutine quadratic_edges_count_mid_nodes(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(status_t) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, 4, 4, ELEMENT_P2, 'right', m, stat)
        call build_dof_map(m, [m%part_index('top')], dofs, stat)
        call build_contact(m, m%part_index('bottom'), dofs, contact, stat)
        call t%check('P2: p = 2 nx + 1', contact%p() == 9)
    end subroutine quadratic_edges_count_mid_nodes

    !> Gamma_C must be one straight segment: two sides of a corner are refused, naming why.
    subroutine bent_contact_is_rejected(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(status_t) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        where (m%edge_part == m%part_index('right')) m%edge_part = m%part_index('bottom')
        call build_dof_map(m, [m%part_index('top')], dofs, stat)
        call build_contact(m, m%part_index('bottom'), dofs, contact, stat)
        call t%check('bent contact: STATUS_MESH', stat%code == STATUS_MESH)
        if (.not. stat%ok()) call t%check('bent contact: message says straight', &
                                          index(stat%message, 'straight') > 0)
    end subroutine bent_contact_is_rejected

    !> A slanted Gamma_C graded toward one end by newest-vertex bisection (30 halvings: its
    !> edges from 1e-9 to 0.5 long, as on hp levels): every node is on the segment to
    !> round-off, and the segment is accepted with its normal. The direction of the 1e-9 edge
    !> alone is good only to about 1e-16 / 1e-9 = 1e-7, a thousand times the straightness
    !> tolerance (1e-10 of the length): taken from it, the far nodes looked off the line.
    subroutine graded_slanted_contact_is_straight(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: ANGLE = 0.3_wp
        type(mesh_t) :: m, graded
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(status_t) :: stat
        real(wp) :: h_min, xy(2)
        integer :: i, first
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        do i = 1, m%n_nodes()
            xy = m%coords(:, i)
            ! rotated, and moved off the origin: rounding of O(1) coordinates is 1e-16
            m%coords(:, i) = [cos(ANGLE)*xy(1) - sin(ANGLE)*xy(2) + 0.7_wp, &
                              sin(ANGLE)*xy(1) + cos(ANGLE)*xy(2) + 0.4_wp]
        end do
        ! grade toward both ends of the first edge listed on Gamma_C: its remains stay first
        first = findloc(m%edge_part, m%part_index('bottom'), dim=1)
        call geometric_mesh(m, m%coords(:, m%edges(1:2, first)), 0.5_wp, 30, graded, h_min, &
                            stat)
        first = findloc(graded%edge_part, graded%part_index('bottom'), dim=1)
        call t%check('graded slanted contact: first edge on Gamma_C below 1e-8', norm2( &
            graded%coords(:, graded%edges(2, first)) - graded%coords(:, graded%edges(1, first))) &
            < 1.0e-8_wp)
        call t%check('graded slanted contact: mesh built, smallest cells below 1e-8', &
                     stat%ok() .and. h_min < 1.0e-8_wp)
        call build_dof_map(graded, [graded%part_index('top')], dofs, stat)
        call build_contact(graded, graded%part_index('bottom'), dofs, contact, stat)
        call t%check('graded slanted contact: accepted as one straight segment', stat%ok())
        if (stat%ok()) call t%check('graded slanted contact: outward normal (sin a, -cos a)', &
            all(abs(contact%normal - [sin(ANGLE), -cos(ANGLE)]) < 1.0e-12_wp))
    end subroutine graded_slanted_contact_is_straight
end program test_contact_boundary
