! SPDX-License-Identifier: MIT
!> Structured rectangle meshes: counts, orientation, boundary parts, area, the mirror
!> symmetry between the two diagonals, and rejected arguments.
program test_mesh_structured
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, MAX_ELEMENT, &
                             element_name, element_degree, element_corners, &
                             element_nodes_per_cell
    use shape_functions, only: reference_nodes, MAX_NODES
    use mesh_structured, only: structured_rectangle
    use testing, only: test_suite_t
    implicit none

    ! Non-square cells and unequal nx, ny so that x/y or nx/ny mix-ups show.
    real(wp), parameter :: WIDTH = 3.0_wp, HEIGHT = 1.25_wp
    integer, parameter :: NX = 4, NY = 3
    ! Coordinates are width*(i/n): a few ulps of the largest coordinate.
    real(wp), parameter :: GEOMETRY_TOL = 1.0e-14_wp
    type(test_suite_t) :: t
    integer :: element

    t%name = 'test_mesh_structured'
    do element = ELEMENT_P1, MAX_ELEMENT
        call check_mesh(element, 'right')
        if (element_corners(element) == 3) then
            call check_mesh(element, 'left')
            call check_mirror(element)
        end if
    end do
    call check_bad_input()
    call t%report()

contains

    subroutine check_mesh(element, diagonal)
        integer, intent(in) :: element
        character(len=*), intent(in) :: diagonal
        type(mesh_t) :: m
        type(status_t) :: stat
        character(len=:), allocatable :: label
        integer :: step, n_corners, expected_cells, cell, k, side, e
        real(wp) :: area, total_area, smallest_area, mid(2), x, y, ref_nodes(2, MAX_NODES)
        logical :: mids_ok, side_ok
        integer, parameter :: SIDE_COUNT(4) = [NX, NY, NX, NY]
        character(len=6), parameter :: NAMES(4) = ['bottom', 'right ', 'top   ', 'left  ']

        label = ' ('//element_name(element)//', '//diagonal//')'
        call structured_rectangle(WIDTH, HEIGHT, NX, NY, element, diagonal, m, stat)
        call t%check('generation succeeds'//label, stat%ok())
        if (.not. stat%ok()) return
        call t%check('element code recorded'//label, m%element == element)

        step = element_degree(element)
        n_corners = element_corners(element)
        expected_cells = merge(2, 1, n_corners == 3)*NX*NY
        call t%check('node count (s nx + 1)(s ny + 1)'//label, &
                     m%n_nodes() == (step*NX + 1)*(step*NY + 1))
        call t%check('cell count'//label, m%n_cells() == expected_cells)
        call t%check('edge count 2 (nx + ny)'//label, size(m%edges, 2) == 2*(NX + NY) &
                     .and. size(m%edge_part) == 2*(NX + NY))
        call t%check('nodes per edge'//label, size(m%edges, 1) == step + 1)

        ! Row-by-row numbering: node (i, j) of the grid is j (s nx + 1) + i + 1.
        call t%check('node 2 is the next grid point along x'//label, &
                     abs(m%coords(1, 2) - WIDTH/(step*NX)) <= GEOMETRY_TOL*WIDTH .and. &
                     abs(m%coords(2, 2)) <= 0.0_wp)
        call t%check('last node is the corner (width, height)'//label, &
                     abs(m%coords(1, m%n_nodes()) - WIDTH) <= 0.0_wp .and. &
                     abs(m%coords(2, m%n_nodes()) - HEIGHT) <= 0.0_wp)

        ! Corner polygon areas by the shoelace formula: positive = anticlockwise. For
        ! straight-sided cells the Jacobian determinant is a positive multiple of it
        ! (triangles) or, for rectangles, constant and equal to area/4.
        total_area = 0.0_wp
        smallest_area = huge(1.0_wp)
        mids_ok = .true.
        do cell = 1, m%n_cells()
            area = 0.0_wp
            do k = 1, n_corners
                associate (p => m%coords(:, m%cells(k, cell)), &
                           q => m%coords(:, m%cells(modulo(k, n_corners) + 1, cell)))
                    area = area + 0.5_wp*(p(1)*q(2) - q(1)*p(2))
                    if (step == 2) then
                        mid = m%coords(:, m%cells(n_corners + k, cell))
                        mids_ok = mids_ok .and. &
                            maxval(abs(mid - 0.5_wp*(p + q))) <= GEOMETRY_TOL*WIDTH
                    end if
                end associate
            end do
            if (element == ELEMENT_Q2) then
                mid = m%coords(:, m%cells(9, cell))
                mids_ok = mids_ok .and. maxval(abs(mid - 0.25_wp*sum(m%coords(:, &
                    m%cells(1:4, cell)), dim=2))) <= GEOMETRY_TOL*WIDTH
            end if
            if (step > 2) then
                ! Cubic and quartic triangles: every node at the affine image of its
                ! reference position.
                call reference_nodes(element, ref_nodes)
                associate (c1 => m%coords(:, m%cells(1, cell)), &
                           c2 => m%coords(:, m%cells(2, cell)), &
                           c3 => m%coords(:, m%cells(3, cell)))
                    do k = 4, element_nodes_per_cell(element)
                        mid = c1 + ref_nodes(1, k)*(c2 - c1) + ref_nodes(2, k)*(c3 - c1)
                        mids_ok = mids_ok .and. maxval(abs(m%coords(:, m%cells(k, cell)) - &
                                                           mid)) <= GEOMETRY_TOL*WIDTH
                    end do
                end associate
            end if
            total_area = total_area + area
            smallest_area = min(smallest_area, area)
        end do
        call t%check('every cell anticlockwise (positive Jacobian)'//label, smallest_area > 0.0_wp)
        call t%check('cell areas all equal the expected one'//label, abs(smallest_area - &
                     WIDTH*HEIGHT/expected_cells) <= GEOMETRY_TOL*WIDTH*HEIGHT)
        call t%check_close('total area = width height'//label, total_area, WIDTH*HEIGHT, &
                           GEOMETRY_TOL)
        if (step >= 2) call t%check('edge and interior nodes in place'//label, mids_ok)

        call t%check('four parts named bottom, right, top, left'//label, &
                     size(m%part_names) == 4 .and. all(m%part_names == NAMES))
        do side = 1, 4
            side_ok = count(m%edge_part == side) == SIDE_COUNT(side)
            do e = 1, size(m%edge_part)
                if (m%edge_part(e) /= side) cycle
                do k = 1, size(m%edges, 1)
                    x = m%coords(1, m%edges(k, e))
                    y = m%coords(2, m%edges(k, e))
                    select case (side)
                    case (1); side_ok = side_ok .and. abs(y) <= 0.0_wp
                    case (2); side_ok = side_ok .and. abs(x - WIDTH) <= 0.0_wp
                    case (3); side_ok = side_ok .and. abs(y - HEIGHT) <= 0.0_wp
                    case (4); side_ok = side_ok .and. abs(x) <= 0.0_wp
                    end select
                end do
                if (step == 2) side_ok = side_ok .and. maxval(abs(m%coords(:, m%edges(3, e)) &
                    - 0.5_wp*(m%coords(:, m%edges(1, e)) + m%coords(:, m%edges(2, e))))) &
                    <= GEOMETRY_TOL*WIDTH
            end do
            call t%check('side '//trim(NAMES(side))//': right edge count, all on the side'// &
                         label, side_ok)
        end do
        ! The boundary, walked edge by edge, is one closed anticlockwise loop, so every corner
        ! of the rectangle ends one side and starts the next.
        side_ok = all(m%edges(1, 2:) == m%edges(2, :size(m%edge_part) - 1)) .and. &
                  m%edges(1, 1) == m%edges(2, size(m%edge_part))
        call t%check('boundary edges form one closed loop'//label, side_ok)
        call t%check('corners: loop starts at (0,0), sides meet at the corners'//label, &
                     m%edges(1, 1) == 1 .and. &
                     m%edges(2, NX) == step*NX + 1 .and. &
                     m%edges(2, NX + NY) == m%n_nodes() .and. &
                     m%edges(2, 2*NX + NY) == m%n_nodes() - step*NX)
        ! Anticlockwise: the body is on the left of every edge, i.e. the shoelace sum over
        ! the boundary loop is the (positive) area.
        area = 0.0_wp
        do e = 1, size(m%edge_part)
            associate (p => m%coords(:, m%edges(1, e)), q => m%coords(:, m%edges(2, e)))
                area = area + 0.5_wp*(p(1)*q(2) - q(1)*p(2))
            end associate
        end do
        call t%check_close('boundary loop is anticlockwise (encloses +area)'//label, area, &
                           WIDTH*HEIGHT, GEOMETRY_TOL)
    end subroutine check_mesh

    !> x -> width - x maps the nodes of the 'left' mesh onto those of the 'right' one and its
    !> triangles onto the triangles of the other (as node sets: mirroring reverses order).
    subroutine check_mirror(element)
        integer, intent(in) :: element
        type(mesh_t) :: right, left
        type(status_t) :: stat
        integer, allocatable :: image(:), right_key(:, :), left_key(:, :)
        integer :: node, i, j, cell, n_grid_x, n_grid_y, step
        logical :: nodes_ok, cells_ok
        character(len=:), allocatable :: label

        label = ' ('//element_name(element)//')'
        call structured_rectangle(WIDTH, HEIGHT, NX, NY, element, 'right', right, stat)
        call structured_rectangle(WIDTH, HEIGHT, NX, NY, element, 'left', left, stat)
        step = element_degree(element)
        n_grid_x = step*NX + 1
        n_grid_y = step*NY + 1
        ! image(node of left) = node of right at the mirrored position, found from the
        ! coordinates by rounding to the grid, then checked against them.
        allocate (image(left%n_nodes()))
        nodes_ok = right%n_nodes() == left%n_nodes()
        do node = 1, left%n_nodes()
            i = nint((WIDTH - left%coords(1, node))/WIDTH*(n_grid_x - 1))
            j = nint(left%coords(2, node)/HEIGHT*(n_grid_y - 1))
            image(node) = j*n_grid_x + i + 1
            nodes_ok = nodes_ok .and. abs(right%coords(1, image(node)) - &
                (WIDTH - left%coords(1, node))) <= GEOMETRY_TOL*WIDTH .and. &
                abs(right%coords(2, image(node)) - left%coords(2, node)) <= 0.0_wp
        end do
        call t%check('mirror maps the node set onto itself'//label, nodes_ok .and. &
                     size(unique_sorted(image)) == left%n_nodes())

        ! Triangles as sorted node triples (corners), then the sets compared sorted.
        allocate (right_key(3, right%n_cells()), left_key(3, left%n_cells()))
        do cell = 1, right%n_cells()
            right_key(:, cell) = sort3(right%cells(1:3, cell))
            left_key(:, cell) = sort3(image(left%cells(1:3, cell)))
        end do
        call sort_columns(right_key)
        call sort_columns(left_key)
        cells_ok = all(right_key == left_key)
        call t%check('mirror maps the triangle set onto the other diagonal''s'//label, cells_ok)
    end subroutine check_mirror

    subroutine check_bad_input()
        type(mesh_t) :: m
        type(status_t) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, 0, 2, ELEMENT_P1, 'right', m, stat)
        call t%check('nx = 0 is bad input', stat%code == STATUS_BAD_INPUT .and. &
                     index(stat%message, 'nx') > 0)
        call structured_rectangle(-1.0_wp, 1.0_wp, 2, 2, ELEMENT_Q1, 'right', m, stat)
        call t%check('negative width is bad input', stat%code == STATUS_BAD_INPUT)
        call structured_rectangle(1.0_wp, 0.0_wp, 2, 2, ELEMENT_Q1, 'right', m, stat)
        call t%check('zero height is bad input', stat%code == STATUS_BAD_INPUT)
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, 7, 'right', m, stat)
        call t%check('element code 7 is bad input', stat%code == STATUS_BAD_INPUT)
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P2, 'up', m, stat)
        call t%check('diagonal ''up'' is bad input, named in the message', &
                     stat%code == STATUS_BAD_INPUT .and. index(stat%message, "'up'") > 0)
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_Q2, 'up', m, stat)
        call t%check('quadrilaterals ignore the diagonal', stat%ok())
        call structured_rectangle(1.0_wp, 1.0_wp, 100000, 100000, ELEMENT_Q2, 'right', m, stat)
        call t%check('a grid overflowing default integers is bad input', &
                     stat%code == STATUS_BAD_INPUT)
        call structured_rectangle(1.0_wp, 1.0_wp, 46341, 46341, ELEMENT_P1, 'right', m, stat)
        call t%check('46341 x 46341: names nx, ny and the limit', &
                     index(stat%message, 'nx = 46341, ny = 46341: ') == 1 .and. &
                     index(stat%message, '(nx + 1) (ny + 1) <= 1073741823') > 0)
        call structured_rectangle(1.0_wp, 1.0_wp, 8800, 8800, ELEMENT_P1, 'right', m, stat)
        call t%check('8800 x 8800 p1: nnz(K) would overflow default integers', &
                     stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'nonzeros') > 0)
    end subroutine check_bad_input

    pure function sort3(v) result(s)
        integer, intent(in) :: v(3)
        integer :: s(3)
        s = [minval(v), sum(v) - minval(v) - maxval(v), maxval(v)]
    end function sort3

    !> Lexicographic insertion sort of the columns (small meshes only).
    pure subroutine sort_columns(a)
        integer, intent(inout) :: a(:, :)
        integer :: i, j, key(size(a, 1))
        do i = 2, size(a, 2)
            key = a(:, i)
            j = i - 1
            do while (j >= 1)
                if (.not. lex_greater(a(:, j), key)) exit
                a(:, j + 1) = a(:, j)
                j = j - 1
            end do
            a(:, j + 1) = key
        end do
    end subroutine sort_columns

    pure logical function lex_greater(x, y)
        integer, intent(in) :: x(:), y(:)
        integer :: k
        lex_greater = .false.
        do k = 1, size(x)
            if (x(k) /= y(k)) then
                lex_greater = x(k) > y(k)
                return
            end if
        end do
    end function lex_greater

    pure function unique_sorted(v) result(u)
        integer, intent(in) :: v(:)
        integer, allocatable :: u(:)
        integer :: w(1, size(v))
        w(1, :) = v
        call sort_columns(w)
        u = pack(w(1, :), [.true., w(1, 2:) /= w(1, :size(v) - 1)])
    end function unique_sorted
end program test_mesh_structured
