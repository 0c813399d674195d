! SPDX-License-Identifier: MIT
!> Structured meshes of the rectangle [0, width] x [0, height]: nx x ny squares, each a
!> quadrilateral or split into two triangles along one diagonal.
module mesh_structured
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_SOLVER
    use strings, only: to_string, short_real_text
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, MAX_ELEMENT, element_nodes_per_cell, &
                             element_nodes_per_edge, element_name, element_degree, &
                             triangle_lattice
    implicit none
    private
    public :: structured_rectangle
    public :: PART_BOTTOM, PART_RIGHT, PART_TOP, PART_LEFT

    !> Index of each side in `part_names` of a structured mesh.
    integer, parameter :: PART_BOTTOM = 1, PART_RIGHT = 2, PART_TOP = 3, PART_LEFT = 4
    !> Dofs are numbered with default integers.
    integer, parameter :: MAX_DOFS = huge(1)
    !> Nonzeros of K per node in the interior of a grid (P1, Q1, P2, Q2, P3, P4): 4 per
    !> neighbour, self included (P1 7, Q1 9; P2 vertex 19 and mid-edge 9, i.e. 11.5 per node;
    !> Q2 vertex 25, mid-edge 15, centre 9, i.e. 16; P3 vertex 37, edge 16, centre 10, i.e. 17
    !> over the 9 nodes of a square; P4 vertex 61, edge 25, interior 15, i.e. 23.5 over 16).
    integer(i8), parameter :: NNZ_PER_NODE(MAX_ELEMENT) = [28_i8, 36_i8, 46_i8, 64_i8, 68_i8, &
                                                           94_i8]
    character(len=*), parameter :: SIDE_NAMES(4) = ['bottom', 'right ', 'top   ', 'left  ']

contains

    !> Mesh of [0, width] x [0, height] with nx x ny cells of type `element` (ELEMENT_*).
    !> `diagonal` is 'right' (squares split from lower-left to upper-right) or 'left' (from
    !> lower-right to upper-left); quadrilateral meshes ignore it. Nodes lie on a grid of
    !> (s nx + 1) x (s ny + 1) points, s the degree of the element (1 to 4), numbered row by
    !> row from the bottom so that the bandwidth stays near 2 s nx. Boundary edges go
    !> anticlockwise round the rectangle (body on their left) and belong to the parts
    !> 'bottom', 'right', 'top', 'left' (PART_* indices).
    subroutine structured_rectangle(width, height, nx, ny, element, diagonal, m, stat)
        real(wp), intent(in) :: width, height   !! metres, > 0
        integer, intent(in) :: nx, ny           !! cells along x and y, >= 1
        integer, intent(in) :: element          !! ELEMENT_P1, _Q1, _P2, _Q2, _P3 or _P4
        character(len=*), intent(in) :: diagonal
        type(mesh_t), intent(out) :: m
        type(status_t), intent(out) :: stat
        integer :: step, n_grid_x, n_grid_y, i, j, e, cell, ierr
        logical :: triangles, quadratic, right_diagonal
        integer(i8) :: n_nodes_wide

        if (.not. (width > 0.0_wp .and. width <= huge(width))) then
            call stat%fail(STATUS_BAD_INPUT, 'structured mesh: width must be a positive '// &
                           'finite number, got '//short_real_text(width, 5))
            return
        end if
        if (.not. (height > 0.0_wp .and. height <= huge(height))) then
            call stat%fail(STATUS_BAD_INPUT, 'structured mesh: height must be a positive '// &
                           'finite number, got '//short_real_text(height, 5))
            return
        end if
        if (nx < 1 .or. ny < 1) then
            call stat%fail(STATUS_BAD_INPUT, 'structured mesh: nx and ny must be >= 1, got '// &
                           to_string(nx)//' and '//to_string(ny))
            return
        end if
        select case (element)
        case (ELEMENT_P1, ELEMENT_P2, ELEMENT_P3, ELEMENT_P4); triangles = .true.
        case (ELEMENT_Q1, ELEMENT_Q2); triangles = .false.
        case default
            call stat%fail(STATUS_BAD_INPUT, 'structured mesh: unknown element code '// &
                           to_string(element))
            return
        end select
        right_diagonal = .true.
        if (triangles) then
            select case (trim(diagonal))
            case ('right'); right_diagonal = .true.
            case ('left'); right_diagonal = .false.
            case default
                call stat%fail(STATUS_BAD_INPUT, "structured mesh: diagonal must be 'right' "// &
                               "or 'left', got '"//trim(diagonal)//"'")
                return
            end select
        end if
        step = element_degree(element)
        quadratic = step > 1
        ! Node numbers are default integers: refuse grids whose count would overflow them
        ! (or whose dof count, twice as large, would) before any arithmetic wraps round.
        ! No file name here: the caller puts the input file and &mesh in front.
        n_nodes_wide = (step*int(nx, i8) + 1)*(step*int(ny, i8) + 1)
        if (2*n_nodes_wide > int(MAX_DOFS, i8)) then
            call stat%fail(STATUS_BAD_INPUT, 'nx = '//to_string(nx)//', ny = '// &
                to_string(ny)//': the '//trim(grid_name(step))// &
                ' grid has '//to_string(n_nodes_wide)//' nodes, '//to_string(2*n_nodes_wide) &
                //' dofs; expected at most '//to_string(MAX_DOFS)//' dofs (default ' &
                //'integers), i.e. '//trim(grid_size(step))//' <= '// &
                to_string(ishft(MAX_DOFS, -1)))
            return
        end if
        ! The positions in K (CSR row starts) are default integers too: 4 entries per pair of
        ! nodes sharing a cell, NNZ_PER_NODE on average in the interior (an upper bound).
        if (NNZ_PER_NODE(element)*n_nodes_wide > int(MAX_DOFS, i8)) then
            call stat%fail(STATUS_BAD_INPUT, 'nx = '//to_string(nx)//', ny = '// &
                to_string(ny)//': the stiffness matrix of this '//element_name(element)// &
                ' grid of '//to_string(n_nodes_wide)//' nodes would have about '// &
                to_string(NNZ_PER_NODE(element)*n_nodes_wide)//' nonzeros; expected at most ' &
                //to_string(MAX_DOFS)//' (default integers), i.e. at most '// &
                to_string(int(MAX_DOFS, i8)/NNZ_PER_NODE(element))//' nodes')
            return
        end if
        n_grid_x = step*nx + 1
        n_grid_y = step*ny + 1

        m%element = element
        allocate (m%coords(m%dim(), n_grid_x*n_grid_y), &
                  m%cells(element_nodes_per_cell(element), merge(2, 1, triangles)*nx*ny), &
                  m%edges(element_nodes_per_edge(element), 2*(nx + ny)), &
                  m%edge_part(2*(nx + ny)), stat=ierr)
        if (ierr /= 0) then
            call stat%fail(STATUS_SOLVER, 'nx = '//to_string(nx)//', ny = '// &
                to_string(ny)//': cannot allocate the mesh of '//to_string(n_nodes_wide)// &
                ' nodes: out of memory; expected a smaller grid')
            return
        end if
        do j = 0, n_grid_y - 1
            do i = 0, n_grid_x - 1
                ! width*(i/n) is exactly width at i = n, so the sides are straight lines.
                m%coords(1, node(i, j)) = width*(real(i, wp)/real(n_grid_x - 1, wp))
                m%coords(2, node(i, j)) = height*(real(j, wp)/real(n_grid_y - 1, wp))
            end do
        end do

        cell = 0
        do j = 0, ny - 1
            do i = 0, nx - 1
                call fill_square(step*i, step*j)
            end do
        end do

        allocate (m%part_names(size(SIDE_NAMES)))
        m%part_names = SIDE_NAMES
        e = 0
        do i = 0, nx - 1
            call add_edge(step*i, 0, step*(i + 1), 0, PART_BOTTOM)
        end do
        do j = 0, ny - 1
            call add_edge(n_grid_x - 1, step*j, n_grid_x - 1, step*(j + 1), PART_RIGHT)
        end do
        do i = nx, 1, -1
            call add_edge(step*i, n_grid_y - 1, step*(i - 1), n_grid_y - 1, PART_TOP)
        end do
        do j = ny, 1, -1
            call add_edge(0, step*j, 0, step*(j - 1), PART_LEFT)
        end do

    contains

        !> Node number of grid point (i, j), both counted from 0.
        pure integer function node(i, j)
            integer, intent(in) :: i, j
            node = j*n_grid_x + i + 1
        end function node

        !> Cells of the square whose lower-left grid point is (i0, j0).
        subroutine fill_square(i0, j0)
            integer, intent(in) :: i0, j0
            integer :: corner(2, 4)   ! grid points, anticlockwise from lower-left
            corner(:, 1) = [i0, j0]
            corner(:, 2) = [i0 + step, j0]
            corner(:, 3) = [i0 + step, j0 + step]
            corner(:, 4) = [i0, j0 + step]
            if (.not. triangles) then
                call add_cell(corner)
            else if (right_diagonal) then
                call add_cell(corner(:, [1, 2, 3]))
                call add_cell(corner(:, [1, 3, 4]))
            else
                call add_cell(corner(:, [1, 2, 4]))
                call add_cell(corner(:, [2, 3, 4]))
            end if
        end subroutine fill_square

        !> Append a cell given its corner grid points; mid-edge and centre nodes of quadratic
        !> elements are the grid points halfway between, in Gmsh order; the other nodes of a
        !> cubic or quartic triangle are the grid points at its barycentric lattice.
        subroutine add_cell(corner)
            integer, intent(in) :: corner(:, :)
            integer :: k, n_corners, middle(2), lattice(3, 15), point(2)
            n_corners = size(corner, 2)
            cell = cell + 1
            if (element == ELEMENT_P3 .or. element == ELEMENT_P4) then
                ! corner coordinates are multiples of step: the lattice points are integers
                call triangle_lattice(element, lattice)
                do k = 1, element_nodes_per_cell(element)
                    point = matmul(corner, lattice(:, k))/step
                    m%cells(k, cell) = node(point(1), point(2))
                end do
                return
            end if
            do k = 1, n_corners
                m%cells(k, cell) = node(corner(1, k), corner(2, k))
            end do
            if (.not. quadratic) return
            do k = 1, n_corners
                middle = (corner(:, k) + corner(:, modulo(k, n_corners) + 1))/2
                m%cells(n_corners + k, cell) = node(middle(1), middle(2))
            end do
            if (element == ELEMENT_Q2) then
                middle = (corner(:, 1) + corner(:, 3))/2
                m%cells(2*n_corners + 1, cell) = node(middle(1), middle(2))
            end if
        end subroutine add_cell

        subroutine add_edge(i1, j1, i2, j2, part)
            integer, intent(in) :: i1, j1, i2, j2, part
            integer :: t
            e = e + 1
            m%edges(1, e) = node(i1, j1)
            m%edges(2, e) = node(i2, j2)
            ! inner nodes from the first end, at t/step of the edge
            do t = 1, step - 1
                m%edges(2 + t, e) = node(((step - t)*i1 + t*i2)/step, ((step - t)*j1 + t*j2)/step)
            end do
            m%edge_part(e) = part
        end subroutine add_edge
    end subroutine structured_rectangle

    !> 'linear', 'quadratic', ... grid of an element of degree p, for messages.
    pure function grid_name(p) result(name)
        integer, intent(in) :: p
        character(len=9) :: name
        character(len=9), parameter :: NAMES(4) = ['linear   ', 'quadratic', 'cubic    ', &
                                                   'quartic  ']
        name = NAMES(max(1, min(p, 4)))
    end function grid_name

    !> The node count of the grid of an element of degree p, as a formula, for messages.
    pure function grid_size(p) result(text)
        integer, intent(in) :: p
        character(len=:), allocatable :: text
        if (p == 1) then
            text = '(nx + 1) (ny + 1)'
        else
            text = '('//to_string(p)//' nx + 1) ('//to_string(p)//' ny + 1)'
        end if
    end function grid_size
end module mesh_structured
