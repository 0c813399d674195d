! SPDX-License-Identifier: MIT
!> Conforming, nested refinement of triangle meshes by newest-vertex bisection (NVB): the
!> refinement step of an adaptive loop.
!>
!> A `refinable_mesh_t` is the P1 vertex mesh of a triangle mesh (P2 mid-edge nodes are
!> dropped and regenerated on output) in which each cell knows its refinement edge. Bisecting
!> a cell splits that edge at its midpoint; the two children take the parent's other edges as
!> their refinement edges, so the new vertex is their newest one. Descendants of a cell then
!> fall into at most four similarity classes (Mitchell 1991; Sewell 1972), so angles stay
!> bounded away from 0 and 180 degrees however often a region is refined.
!>
!> `refine` closes the marking so that every cell with a bisected edge has its refinement
!> edge bisected too: a cell is then cut into 2, 3 or 4 children, each edge is cut in every
!> cell that shares it, and the mesh stays conforming (no hanging nodes). New vertices sit at
!> edge midpoints, so straight sides stay straight, and a boundary edge is replaced by its two
!> halves with its part index: boundary parts (physical groups), the contact segment among
!> them, carry over to the children unchanged. Every step costs O(cells): the edges are found
!> by bucketing the cell sides by their lower vertex, never by a search over all edges.
module mesh_refine
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_MESH
    use strings, only: to_string, short_real_text
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P2, ELEMENT_P3, ELEMENT_P4, element_name, &
                             element_corners, element_degree, element_nodes_per_cell, &
                             triangle_lattice
    implicit none
    private
    public :: refinable_mesh_t, build_refinable_mesh, edge_table_t, build_edge_table, edge_number

    integer, parameter :: NAME_LEN = 64   !! as mesh_t%part_names
    integer, parameter :: N_CORNERS = 3

    !> A triangle mesh that can be refined by newest-vertex bisection.
    type :: refinable_mesh_t
        real(wp), allocatable :: coords(:, :)   !! (2, n_vertices), metres
        !> (3, n_cells) vertices anticlockwise, the newest vertex first: the refinement edge
        !> is the one opposite it, from vertex 2 to vertex 3.
        integer, allocatable :: cells(:, :)
        integer, allocatable :: edges(:, :)     !! (2, n_edges) boundary edges, as in mesh_t
        integer, allocatable :: edge_part(:)    !! (n_edges) index into part_names
        character(len=NAME_LEN), allocatable :: part_names(:)
        !> (n_cells) the cell of the mesh before the last `refine` that contains each cell
        !> (the identity before any refinement): what an error estimator needs to compare a
        !> solution with its predecessor cell by cell.
        integer, allocatable :: parent(:)
    contains
        procedure :: n_vertices => refinable_mesh_n_vertices
        procedure :: n_cells => refinable_mesh_n_cells
        procedure :: refine => refinable_mesh_refine
        procedure :: to_mesh => refinable_mesh_to_mesh
    end type refinable_mesh_t

    !> The distinct edges of a triangulation. The 3 n_cells cell sides are bucketed by their
    !> lower vertex (a counting sort); sides with equal upper vertex in one bucket are one
    !> edge. Building costs O(n_cells + n_vertices); a lookup scans one vertex's bucket, whose
    !> length is about the vertex degree (bounded under NVB, whose angles are bounded).
    type :: edge_table_t
        integer, allocatable :: first(:)          !! (n_vertices + 1) bucket starts
        integer, allocatable :: upper(:)          !! (3 n_cells) upper vertex of each side
        integer, allocatable :: edge(:)           !! (3 n_cells) edge number of each side
        integer, allocatable :: cell_edge(:, :)   !! (3, n_cells) edge opposite vertex k
        integer, allocatable :: ends(:, :)        !! (2, n_edges) lower, upper vertex
        integer, allocatable :: cells_of(:, :)    !! (2, n_edges) cells sharing it, 0: none
        integer :: n_edges = 0
        integer :: overshared = 0                 !! an edge of 3 or more cells (0: none)
    end type edge_table_t

contains

    pure integer function refinable_mesh_n_vertices(this)
        class(refinable_mesh_t), intent(in) :: this
        refinable_mesh_n_vertices = 0
        if (allocated(this%coords)) refinable_mesh_n_vertices = size(this%coords, 2)
    end function refinable_mesh_n_vertices

    pure integer function refinable_mesh_n_cells(this)
        class(refinable_mesh_t), intent(in) :: this
        refinable_mesh_n_cells = 0
        if (allocated(this%cells)) refinable_mesh_n_cells = size(this%cells, 2)
    end function refinable_mesh_n_cells

    !> The refinable vertex mesh of the P1 to P4 triangle mesh `m`: its cell corners (in node
    !> order; other nodes are dropped, so curved edges become straight), its boundary
    !> edges and parts. Each cell's refinement edge is its longest edge (the first of equal
    !> ones), the usual initial choice: it makes neighbours across a longest edge bisect the
    !> same edge, which keeps the closure of the first steps short. Fails with
    !> STATUS_BAD_INPUT for quadrilaterals or an incomplete mesh, STATUS_MESH for a clockwise
    !> or flat cell, an edge of more than two cells or a boundary edge that is no cell side.
    subroutine build_refinable_mesh(m, r, stat, keep_corner_order)
        type(mesh_t), intent(in) :: m
        type(refinable_mesh_t), intent(out) :: r
        type(status_t), intent(out) :: stat
        !> keep each cell's corners in the order of `m` (default false: longest edge first).
        !> A mesh meant for `to_mesh` only, not for `refine`: the enriched space of an error
        !> estimate, whose cells must match those of `m` node by node.
        logical, intent(in), optional :: keep_corner_order
        integer, allocatable :: vertex_of(:)
        type(edge_table_t) :: table
        integer :: node, c, e, n_vertices, corners(N_CORNERS), longest
        real(wp) :: length2(N_CORNERS), twice_area

        if (element_corners(m%element) /= N_CORNERS .or. &
            element_nodes_per_cell(m%element) == 0) then
            call stat%fail(STATUS_BAD_INPUT, 'mesh refinement: needs triangles (p1 to p4), '// &
                           'got '//element_name(m%element)//' cells')
            return
        end if
        call m%require_complete('mesh refinement', stat)
        if (.not. stat%ok()) return

        ! Vertices are the cell corners, numbered in node order so that locality carries over.
        allocate (vertex_of(m%n_nodes()), source=0)
        do c = 1, m%n_cells()
            vertex_of(m%cells(1:N_CORNERS, c)) = 1
        end do
        n_vertices = 0
        do node = 1, size(vertex_of)
            if (vertex_of(node) == 0) cycle
            n_vertices = n_vertices + 1
            vertex_of(node) = n_vertices
        end do
        allocate (r%coords(size(m%coords, 1), n_vertices))
        do node = 1, size(vertex_of)
            if (vertex_of(node) > 0) r%coords(:, vertex_of(node)) = m%coords(:, node)
        end do

        allocate (r%cells(N_CORNERS, m%n_cells()))
        do c = 1, m%n_cells()
            corners = vertex_of(m%cells(1:N_CORNERS, c))
            twice_area = cross(r%coords(:, corners(2)) - r%coords(:, corners(1)), &
                               r%coords(:, corners(3)) - r%coords(:, corners(1)))
            if (.not. twice_area > 0.0_wp) then
                call stat%fail(STATUS_MESH, 'mesh refinement: cell '//to_string(c)// &
                    ' is clockwise or flat (twice its signed area is '// &
                    short_real_text(twice_area, 5)//'); expected anticlockwise cells')
                return
            end if
            length2(1) = sum((r%coords(:, corners(3)) - r%coords(:, corners(2)))**2)
            length2(2) = sum((r%coords(:, corners(1)) - r%coords(:, corners(3)))**2)
            length2(3) = sum((r%coords(:, corners(2)) - r%coords(:, corners(1)))**2)
            longest = maxloc(length2, dim=1)
            if (present(keep_corner_order)) then
                if (keep_corner_order) longest = 1
            end if
            ! A cyclic shift keeps the orientation and puts the longest edge opposite vertex 1.
            r%cells(:, c) = cshift(corners, longest - 1)
        end do

        allocate (r%edges(2, size(m%edges, 2)))
        do e = 1, size(m%edges, 2)
            r%edges(:, e) = vertex_of(m%edges(1:2, e))
            if (any(r%edges(:, e) == 0)) then
                call stat%fail(STATUS_MESH, 'mesh refinement: boundary edge '//to_string(e)// &
                    ' ends at a node that is no cell corner; expected edges along cell sides')
                return
            end if
        end do
        ! sourced allocation, not assignment, into the intent(out) record: gfortran 12's
        ! reallocation reads the unallocated component's stale bounds, which
        ! -fsanitize=undefined reports as an overflow (now and then, as the stack holds)
        allocate (r%edge_part, source=m%edge_part)
        allocate (r%part_names, source=m%part_names)
        allocate (r%parent(m%n_cells()))
        r%parent = [(c, c=1, m%n_cells())]

        call build_edge_table(r%cells, n_vertices, table)
        if (table%overshared > 0) then
            call stat%fail(STATUS_MESH, 'mesh refinement: the edge from vertex at ('// &
                coordinates_text(r%coords(:, table%ends(1, table%overshared)))//') to ('// &
                coordinates_text(r%coords(:, table%ends(2, table%overshared)))// &
                ') is a side of three or more cells; expected a conforming 2D mesh')
            return
        end if
        do e = 1, size(r%edges, 2)
            if (edge_number(table, r%edges(1, e), r%edges(2, e)) == 0) then
                call stat%fail(STATUS_MESH, 'mesh refinement: boundary edge '//to_string(e)// &
                    ' is not a side of any cell; expected edges along cell sides')
                return
            end if
        end do
    end subroutine build_refinable_mesh

    !> Bisect every cell listed in `marked` (indices into the current cells; repeats allowed)
    !> and as many others as conformity needs. Afterwards `parent` maps each new cell to the
    !> cell it came from (a cell left whole is its own child). Fails with STATUS_BAD_INPUT,
    !> leaving the mesh unchanged, when an index is out of range or a boundary edge (edited
    !> since the build) is no cell side.
    subroutine refinable_mesh_refine(this, marked, stat)
        class(refinable_mesh_t), intent(inout) :: this
        integer, intent(in) :: marked(:)
        type(status_t), intent(out) :: stat
        type(edge_table_t) :: table
        logical, allocatable :: bisected(:)
        integer, allocatable :: queue(:), midpoint(:), cells(:, :), parent(:), edges(:, :), &
                                edge_part(:), boundary_edge(:)
        real(wp), allocatable :: coords(:, :)
        integer :: i, c, e, side, head, tail, n_vertices, n_new, n_cells, n_edges, middle
        integer :: v(N_CORNERS), mid(N_CORNERS)

        do i = 1, size(marked)
            if (marked(i) < 1 .or. marked(i) > this%n_cells()) then
                call stat%fail(STATUS_BAD_INPUT, 'mesh refinement: marked cell '// &
                    to_string(marked(i))//' is not a cell of the mesh (1 to '// &
                    to_string(this%n_cells())//')')
                return
            end if
        end do
        n_vertices = this%n_vertices()
        call build_edge_table(this%cells, n_vertices, table)
        ! The components are public: check that the boundary still lies on cell sides.
        allocate (boundary_edge(size(this%edges, 2)))
        do e = 1, size(this%edges, 2)
            boundary_edge(e) = edge_number(table, this%edges(1, e), this%edges(2, e))
            if (boundary_edge(e) == 0) then
                call stat%fail(STATUS_BAD_INPUT, 'mesh refinement: boundary edge '// &
                    to_string(e)//' is not a side of any cell; expected edges along cell sides')
                return
            end if
        end do

        ! Closure: a cell with a bisected edge must bisect its refinement edge first; a newly
        ! bisected edge may in turn oblige the other cell that shares it. Each edge enters the
        ! queue at most once, so the closure is O(n_edges).
        allocate (bisected(table%n_edges), source=.false.)
        allocate (queue(table%n_edges))
        tail = 0
        do i = 1, size(marked)
            call bisect(table%cell_edge(1, marked(i)))
        end do
        head = 0
        do while (head < tail)
            head = head + 1
            do side = 1, 2
                c = table%cells_of(side, queue(head))
                if (c > 0) call bisect(table%cell_edge(1, c))
            end do
        end do

        ! A new vertex at the midpoint of each bisected edge, in edge order.
        allocate (midpoint(table%n_edges), source=0)
        allocate (coords(size(this%coords, 1), n_vertices + tail))
        coords(:, :n_vertices) = this%coords
        do e = 1, table%n_edges
            if (.not. bisected(e)) cycle
            n_vertices = n_vertices + 1
            midpoint(e) = n_vertices
            coords(:, n_vertices) = 0.5_wp*(this%coords(:, table%ends(1, e)) + &
                                            this%coords(:, table%ends(2, e)))
        end do

        ! Children replace their parent in place, so cells keep their locality.
        n_new = 0
        do c = 1, this%n_cells()
            n_new = n_new + n_children(c)
        end do
        allocate (cells(N_CORNERS, n_new), parent(n_new))
        n_cells = 0
        do c = 1, this%n_cells()
            v = this%cells(:, c)
            mid = midpoint(table%cell_edge(:, c))
            if (mid(1) == 0) then
                call add_cell(v, c)
                cycle
            end if
            ! Newest vertex mid(1) on the refinement edge v2-v3: children (m, v1, v2) and
            ! (m, v3, v1), whose refinement edges v1-v2 and v3-v1 may be bisected in turn.
            call add_child(mid(1), v(1), v(2), mid(3), c)
            call add_child(mid(1), v(3), v(1), mid(2), c)
        end do

        ! A bisected boundary edge becomes its two halves, in order along it, same part.
        n_edges = size(this%edges, 2)
        n_edges = n_edges + count(bisected(boundary_edge))
        allocate (edges(2, n_edges), edge_part(n_edges))
        n_edges = 0
        do e = 1, size(this%edges, 2)
            middle = midpoint(boundary_edge(e))
            if (middle == 0) then
                n_edges = n_edges + 1
                edges(:, n_edges) = this%edges(:, e)
            else
                n_edges = n_edges + 2
                edges(:, n_edges - 1) = [this%edges(1, e), middle]
                edges(:, n_edges) = [middle, this%edges(2, e)]
                edge_part(n_edges - 1) = this%edge_part(e)
            end if
            edge_part(n_edges) = this%edge_part(e)
        end do

        call move_alloc(coords, this%coords)
        call move_alloc(cells, this%cells)
        call move_alloc(parent, this%parent)
        call move_alloc(edges, this%edges)
        call move_alloc(edge_part, this%edge_part)

    contains

        subroutine bisect(edge)
            integer, intent(in) :: edge
            if (bisected(edge)) return
            bisected(edge) = .true.
            tail = tail + 1
            queue(tail) = edge
        end subroutine bisect

        pure integer function n_children(cell)
            integer, intent(in) :: cell
            n_children = 1
            if (.not. bisected(table%cell_edge(1, cell))) return
            n_children = 2 + count(bisected(table%cell_edge(2:3, cell)))
        end function n_children

        subroutine add_cell(vertices, from)
            integer, intent(in) :: vertices(N_CORNERS), from
            n_cells = n_cells + 1
            cells(:, n_cells) = vertices
            parent(n_cells) = from
        end subroutine add_cell

        !> The child (newest, a, b) of cell `from`, or, when its refinement edge a-b is
        !> bisected at `middle` (0: not), the two halves of it with `middle` as newest vertex.
        subroutine add_child(newest, a, b, middle, from)
            integer, intent(in) :: newest, a, b, middle, from
            if (middle == 0) then
                call add_cell([newest, a, b], from)
            else
                call add_cell([middle, newest, a], from)
                call add_cell([middle, b, newest], from)
            end if
        end subroutine add_child
    end subroutine refinable_mesh_refine

    !> The mesh as a `mesh_t` of `element` ELEMENT_P1 to ELEMENT_P4 (degree p): vertices
    !> first, then p - 1 nodes per edge equally spaced from the edge's first end (P2: its
    !> exact midpoint), numbered in the edge table's order, then (P3, P4) the interior nodes of
    !> each cell at their lattice points. Boundary edges keep their order and parts and list
    !> their inner nodes after the ends, from the first end on, as mesh_t does. Fails with
    !> STATUS_BAD_INPUT for any other element.
    subroutine refinable_mesh_to_mesh(this, element, m, stat)
        class(refinable_mesh_t), intent(in) :: this
        integer, intent(in) :: element
        type(mesh_t), intent(out) :: m
        type(status_t), intent(out) :: stat
        type(edge_table_t) :: table
        integer :: e, c, k, t, a, n_vertices, p, inner, n_inner, first_inner, lattice(3, 15)
        integer :: from, to
        ! Gmsh order: side k joins corners k and k+1, the side opposite corner k+2.
        integer, parameter :: OPPOSITE(N_CORNERS) = [3, 1, 2]

        if (element /= ELEMENT_P1 .and. element /= ELEMENT_P2 .and. element /= ELEMENT_P3 &
            .and. element /= ELEMENT_P4) then
            call stat%fail(STATUS_BAD_INPUT, 'mesh refinement: output element must be p1 to ' &
                           //'p4, got '//element_name(element))
            return
        end if
        m%element = element
        ! sourced allocation, not assignment: gfortran 12's reallocation of the unallocated
        ! component reads an extent that -fsanitize=undefined reports as an overflow
        allocate (m%part_names, source=this%part_names)
        allocate (m%edge_part, source=this%edge_part)
        if (element == ELEMENT_P1) then
            allocate (m%coords, source=this%coords)
            allocate (m%cells, source=this%cells)
            allocate (m%edges, source=this%edges)
            return
        end if

        p = element_degree(element)
        inner = p - 1                              ! nodes inside an edge
        n_inner = (p - 1)*(p - 2)/2                ! nodes inside a cell
        n_vertices = this%n_vertices()
        call build_edge_table(this%cells, n_vertices, table)
        first_inner = n_vertices + inner*table%n_edges
        allocate (m%coords(size(this%coords, 1), first_inner + n_inner*this%n_cells()))
        m%coords(:, :n_vertices) = this%coords
        do e = 1, table%n_edges
            do t = 1, inner
                m%coords(:, n_vertices + inner*(e - 1) + t) = &
                    (real(p - t, wp)*this%coords(:, table%ends(1, e)) + &
                     real(t, wp)*this%coords(:, table%ends(2, e)))/real(p, wp)
            end do
        end do
        call triangle_lattice(element, lattice)
        allocate (m%cells(element_nodes_per_cell(element), this%n_cells()))
        do c = 1, this%n_cells()
            m%cells(1:N_CORNERS, c) = this%cells(:, c)
            do k = 1, N_CORNERS
                e = table%cell_edge(OPPOSITE(k), c)
                do t = 1, inner
                    m%cells(N_CORNERS + inner*(k - 1) + t, c) = &
                        edge_node(e, this%cells(k, c), t)
                end do
            end do
            do a = 1, n_inner
                m%cells(N_CORNERS + 3*inner + a, c) = first_inner + n_inner*(c - 1) + a
                m%coords(:, first_inner + n_inner*(c - 1) + a) = &
                    matmul(this%coords(:, this%cells(:, c)), &
                           real(lattice(:, N_CORNERS + 3*inner + a), wp))/real(p, wp)
            end do
        end do
        allocate (m%edges(p + 1, size(this%edges, 2)))
        do e = 1, size(this%edges, 2)
            from = this%edges(1, e)
            to = this%edges(2, e)
            m%edges(1:2, e) = [from, to]
            do t = 1, inner
                m%edges(2 + t, e) = edge_node(edge_number(table, from, to), from, t)
            end do
        end do

    contains

        !> Node t of the inner nodes of table edge `edge`, counted from its end `start`.
        integer function edge_node(edge, start, t)
            integer, intent(in) :: edge, start, t
            if (table%ends(1, edge) == start) then
                edge_node = n_vertices + inner*(edge - 1) + t
            else
                edge_node = n_vertices + inner*(edge - 1) + (p - t)
            end if
        end function edge_node
    end subroutine refinable_mesh_to_mesh

    ! ------------------------------------------------------------------------ edge table

    !> The edge table of the triangles `cells` on vertices 1..n_vertices.
    pure subroutine build_edge_table(cells, n_vertices, table)
        integer, intent(in) :: cells(:, :)
        integer, intent(in) :: n_vertices
        type(edge_table_t), intent(out) :: table
        integer, allocatable :: next(:), side_of(:)
        integer :: c, k, i, j, low, high, pos, e, n_sides

        n_sides = N_CORNERS*size(cells, 2)
        allocate (table%first(n_vertices + 1), source=0)
        do c = 1, size(cells, 2)
            do k = 1, N_CORNERS
                low = min(cells(next_corner(k), c), cells(next_corner(next_corner(k)), c))
                table%first(low + 1) = table%first(low + 1) + 1
            end do
        end do
        table%first(1) = 1
        do i = 1, n_vertices
            table%first(i + 1) = table%first(i + 1) + table%first(i)
        end do

        allocate (table%upper(n_sides), table%edge(n_sides), side_of(n_sides))
        next = table%first(:n_vertices)
        do c = 1, size(cells, 2)
            do k = 1, N_CORNERS
                low = cells(next_corner(k), c)
                high = cells(next_corner(next_corner(k)), c)
                if (low > high) then
                    low = high
                    high = cells(next_corner(k), c)
                end if
                pos = next(low)
                next(low) = pos + 1
                table%upper(pos) = high
                side_of(pos) = N_CORNERS*(c - 1) + k   ! side k of cell c, opposite corner k
            end do
        end do

        ! Within a bucket, the first side with a given upper vertex opens the edge.
        allocate (table%ends(2, n_sides), table%cells_of(2, n_sides), source=0)
        allocate (table%cell_edge(N_CORNERS, size(cells, 2)))
        table%n_edges = 0
        do low = 1, n_vertices
            do i = table%first(low), table%first(low + 1) - 1
                e = 0
                do j = table%first(low), i - 1
                    if (table%upper(j) == table%upper(i)) then
                        e = table%edge(j)
                        exit
                    end if
                end do
                if (e == 0) then
                    table%n_edges = table%n_edges + 1
                    e = table%n_edges
                    table%ends(:, e) = [low, table%upper(i)]
                end if
                table%edge(i) = e
                c = (side_of(i) - 1)/N_CORNERS + 1
                k = side_of(i) - N_CORNERS*(c - 1)
                table%cell_edge(k, c) = e
                if (table%cells_of(1, e) == 0) then
                    table%cells_of(1, e) = c
                else if (table%cells_of(2, e) == 0) then
                    table%cells_of(2, e) = c
                else if (table%overshared == 0) then
                    table%overshared = e
                end if
            end do
        end do
        table%ends = table%ends(:, :table%n_edges)
        table%cells_of = table%cells_of(:, :table%n_edges)
    end subroutine build_edge_table

    !> Number of the edge joining vertices a and b, 0 when no cell has that side (or a vertex
    !> number is out of range).
    pure integer function edge_number(table, a, b)
        type(edge_table_t), intent(in) :: table
        integer, intent(in) :: a, b
        integer :: i, low, high
        low = min(a, b)
        high = max(a, b)
        edge_number = 0
        if (low < 1 .or. high >= size(table%first)) return
        do i = table%first(low), table%first(low + 1) - 1
            if (table%upper(i) == high) then
                edge_number = table%edge(i)
                return
            end if
        end do
    end function edge_number

    !> Corner after corner k, anticlockwise: side k of a cell joins next_corner(k) and
    !> next_corner(next_corner(k)), opposite corner k.
    elemental integer function next_corner(k)
        integer, intent(in) :: k
        next_corner = modulo(k, N_CORNERS) + 1
    end function next_corner

    pure real(wp) function cross(a, b)
        real(wp), intent(in) :: a(2), b(2)
        cross = a(1)*b(2) - a(2)*b(1)
    end function cross

    pure function coordinates_text(xy) result(text)
        real(wp), intent(in) :: xy(2)
        character(len=:), allocatable :: text
        text = short_real_text(xy(1), 6)//', '//short_real_text(xy(2), 6)
    end function coordinates_text
end module mesh_refine
