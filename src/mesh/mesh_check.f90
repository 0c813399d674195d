! SPDX-License-Identifier: MIT
!> Checks of a built mesh that no single cell can fail: how the cells fit together and where
!> the named boundary groups lie. Every edge of a cell (pair of corners) belongs to one cell
!> (a boundary edge) or to two cells on opposite sides of it (an interior edge: anticlockwise
!> cells run through it in opposite directions). An edge of 3 or more cells, or of 2 cells
!> running through it in the same direction, is an overlapping or duplicated cell. The cells
!> must form one piece, joined through shared edges (a crack made of duplicated nodes leaves
!> two pieces), and every node must belong to a cell. The edges of the groups named by
!> &mesh dirichlet, neumann and contact must be boundary edges of positive length.
!> The edge-to-cell incidence is a bucket sort of the cell edges by their lower corner, then
!> by the higher one within each bucket: O(n) for meshes of bounded node degree.
module mesh_check
    use kinds, only: wp
    use status, only: status_t, STATUS_MESH, STATUS_SOLVER
    use strings, only: to_string
    use sorting, only: sort_by_key
    use mesh, only: mesh_t
    use element_types, only: element_nodes_per_edge, element_corners
    implicit none
    private
    public :: check_mesh

    !> An edge is degenerate when its ends coincide to rounding: each coordinate difference
    !> within this many ulps of the larger coordinate. Not relative to the mesh's extent: a
    !> thin strip or a tiny body has short edges that are no defect.
    real(wp), parameter :: COINCIDE_ULPS = 4.0_wp

    !> The edges of the cells, grouped by corner pair: the cell edges of corner pair g are
    !> item(first(g):first(g + 1) - 1); a cell edge k is side side_of(k) of cell cell_of(k).
    type :: incidence_t
        integer, allocatable :: cell_of(:), side_of(:), low(:), high(:)
        integer, allocatable :: item(:)        !! cell edges, sorted by (low, high)
        integer, allocatable :: bucket(:)      !! (n_nodes + 1) start in item of each low node
    end type incidence_t

contains

    !> Refuse a mesh whose cells overlap, are duplicated, do not fit together, form several
    !> pieces or leave nodes unused, or whose named boundary groups (indices into
    !> m%part_names, by the &mesh variable that names them) are not boundary edges of
    !> positive length. STATUS_MESH; the message names 'file:line: ' for a mesh read from a
    !> file, else the cell or edge number (the caller adds the input file).
    subroutine check_mesh(m, dirichlet, neumann, contact, stat)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: dirichlet(:), neumann(:), contact(:)
        type(status_t), intent(out) :: stat
        type(incidence_t) :: inc
        integer, allocatable :: parent(:)

        call check_nodes_used(m, stat)
        if (.not. stat%ok()) return
        call build_incidence(m, inc, stat)
        if (.not. stat%ok()) return
        call check_edges(m, inc, parent, stat)
        if (.not. stat%ok()) return
        call check_groups(m, inc, dirichlet, 'dirichlet', stat)
        if (.not. stat%ok()) return
        call check_groups(m, inc, neumann, 'neumann', stat)
        if (.not. stat%ok()) return
        call check_groups(m, inc, contact, 'contact', stat)
        if (.not. stat%ok()) return
        call check_connected(m, parent, stat)
    end subroutine check_mesh

    !> Every node on a cell (the Gmsh reader drops the others; a generator must not make any).
    subroutine check_nodes_used(m, stat)
        type(mesh_t), intent(in) :: m
        type(status_t), intent(inout) :: stat
        logical, allocatable :: used(:)
        integer :: node, c, ierr
        allocate (used(m%n_nodes()), source=.false., stat=ierr)
        if (ierr /= 0) then
            call out_of_memory(stat, m%n_nodes())
            return
        end if
        do c = 1, m%n_cells()
            used(m%cells(:, c)) = .true.
        end do
        node = findloc(used, .false., dim=1)
        if (node == 0) return
        call stat%fail(STATUS_MESH, file_prefix(m)//'node '//to_string(node)//' at '// &
            point_text(m, node)//' belongs to no cell; expected every node on a cell')
    end subroutine check_nodes_used

    !> The cell edges, bucketed by lower corner, each bucket sorted by the higher corner.
    subroutine build_incidence(m, inc, stat)
        type(mesh_t), intent(in) :: m
        type(incidence_t), intent(out) :: inc
        type(status_t), intent(inout) :: stat
        integer, allocatable :: fill(:)
        integer :: corners, n_cell_edges, c, s, k, a, b, node, ierr

        corners = n_corners(m)
        n_cell_edges = corners*m%n_cells()
        allocate (inc%cell_of(n_cell_edges), inc%side_of(n_cell_edges), &
                  inc%low(n_cell_edges), inc%high(n_cell_edges), inc%item(n_cell_edges), &
                  inc%bucket(m%n_nodes() + 1), fill(m%n_nodes()), stat=ierr)
        if (ierr /= 0) then
            call out_of_memory(stat, n_cell_edges)
            return
        end if
        k = 0
        do c = 1, m%n_cells()
            do s = 1, corners
                k = k + 1
                a = m%cells(s, c)
                b = m%cells(modulo(s, corners) + 1, c)
                inc%cell_of(k) = c
                inc%side_of(k) = s
                inc%low(k) = min(a, b)
                inc%high(k) = max(a, b)
            end do
        end do
        ! Counting sort by the lower corner, then each (short) bucket by the higher one.
        inc%bucket = 0
        do k = 1, n_cell_edges
            inc%bucket(inc%low(k) + 1) = inc%bucket(inc%low(k) + 1) + 1
        end do
        inc%bucket(1) = 1
        do node = 1, m%n_nodes()
            inc%bucket(node + 1) = inc%bucket(node + 1) + inc%bucket(node)
        end do
        fill = inc%bucket(1:m%n_nodes())
        do k = 1, n_cell_edges
            inc%item(fill(inc%low(k))) = k
            fill(inc%low(k)) = fill(inc%low(k)) + 1
        end do
        do node = 1, m%n_nodes()
            associate (first => inc%bucket(node), last => inc%bucket(node + 1) - 1)
                if (last > first) call sort_by_key(inc%item(first:last), inc%high)
            end associate
        end do
    end subroutine build_incidence

    !> Each corner pair: one cell, or two on opposite sides with the same mid node. `parent`
    !> returns the union-find forest of the cells joined through interior edges.
    subroutine check_edges(m, inc, parent, stat)
        type(mesh_t), intent(in) :: m
        type(incidence_t), intent(in) :: inc
        integer, allocatable, intent(out) :: parent(:)
        type(status_t), intent(inout) :: stat
        integer :: first, last, k1, k2, c1, c2, i, ierr
        character(len=:), allocatable :: lines

        allocate (parent(m%n_cells()), stat=ierr)
        if (ierr /= 0) then
            call out_of_memory(stat, m%n_cells())
            return
        end if
        parent = [(i, i=1, m%n_cells())]
        first = 1
        do while (first <= size(inc%item))
            last = pair_end(inc, first)
            if (last - first >= 2) then
                lines = ''
                do i = first, last
                    lines = lines//cell_name(m, inc%cell_of(inc%item(i)))
                    if (i < last) lines = lines//', '
                end do
                call stat%fail(STATUS_MESH, cell_place(m, inc%cell_of(inc%item(last)))// &
                    'overlapping or duplicated cells: the edge from '// &
                    point_text(m, inc%low(inc%item(first)))//' to '// &
                    point_text(m, inc%high(inc%item(first)))//' belongs to '// &
                    to_string(last - first + 1)//' cells ('//lines//'); expected at most 2')
                return
            end if
            if (last == first + 1) then
                k1 = inc%item(first)
                k2 = inc%item(last)
                c1 = inc%cell_of(k1)
                c2 = inc%cell_of(k2)
                if (c1 == c2) then
                    call stat%fail(STATUS_MESH, cell_place(m, c1)//'this cell has the edge '// &
                        'from '//point_text(m, inc%low(k1))//' to '// &
                        point_text(m, inc%high(k1))//' twice; expected distinct corners')
                    return
                end if
                if (m%cells(inc%side_of(k1), c1) == m%cells(inc%side_of(k2), c2)) then
                    call stat%fail(STATUS_MESH, cell_place(m, c2)//'this cell overlaps '// &
                        cell_name(m, c1)//': '//trim(same_corners_text(c1, c2))// &
                        'both lie on the same side of their common edge from '// &
                        point_text(m, inc%low(k1))//' to '//point_text(m, inc%high(k1))// &
                        '; expected the two cells of an edge on opposite sides of it')
                    return
                end if
                if (.not. same_side_nodes(m, k1, k2, inc)) then
                    call stat%fail(STATUS_MESH, cell_place(m, c2)//'this cell and '// &
                        cell_name(m, c1)//' share the corners of the edge from '// &
                        point_text(m, inc%low(k1))//' to '//point_text(m, inc%high(k1))// &
                        ' but not its '//trim(merge('mid node  ', 'edge nodes', &
                        size(m%edges, 1) <= 3))//'; expected conforming cells')
                    return
                end if
                call join(parent, c1, c2)
            end if
            first = last + 1
        end do

    contains

        !> 'it duplicates it (same corners): ' when c1 and c2 have the same corner set.
        function same_corners_text(c1, c2) result(text)
            integer, intent(in) :: c1, c2
            character(len=48) :: text
            integer :: corners
            corners = n_corners(m)
            text = ''
            if (all([(any(m%cells(1:corners, c1) == m%cells(i, c2)), i=1, corners)])) &
                text = 'it duplicates it (same corners); '
        end function same_corners_text
    end subroutine check_edges

    !> The edges of each named group: positive length, and each a side of exactly one cell.
    subroutine check_groups(m, inc, parts, variable, stat)
        type(mesh_t), intent(in) :: m
        type(incidence_t), intent(in) :: inc
        integer, intent(in) :: parts(:)
        character(len=*), intent(in) :: variable
        type(status_t), intent(inout) :: stat
        integer :: e, first, last, a, b, per_edge

        if (.not. allocated(m%edge_part) .or. size(parts) == 0) return
        per_edge = element_nodes_per_edge(m%element)
        do e = 1, size(m%edge_part)
            if (.not. any(parts == m%edge_part(e))) cycle
            a = m%edges(1, e)
            b = m%edges(2, e)
            if (a == b .or. all(abs(m%coords(:, b) - m%coords(:, a)) <= COINCIDE_ULPS* &
                epsilon(1.0_wp)*max(abs(m%coords(:, a)), abs(m%coords(:, b))))) then
                call stat%fail(STATUS_MESH, what(e)//'is degenerate: its ends '// &
                    point_text(m, a)//' and '//point_text(m, b)//' coincide; expected an ' &
                    //'edge of positive length')
                return
            end if
            first = find_pair(inc, min(a, b), max(a, b))
            if (first == 0) then
                call stat%fail(STATUS_MESH, what(e)//'from '//point_text(m, a)//' to '// &
                    point_text(m, b)//' is the side of no cell; expected a boundary edge ' &
                    //'of the mesh')
                return
            end if
            last = pair_end(inc, first)
            if (last > first) then
                call stat%fail(STATUS_MESH, what(e)//'from '//point_text(m, a)//' to '// &
                    point_text(m, b)//' lies inside the body, between '// &
                    cell_name(m, inc%cell_of(inc%item(first)))//' and '// &
                    cell_name(m, inc%cell_of(inc%item(last)))//'; expected a boundary edge')
                return
            end if
            if (per_edge > 3) then
                if (.not. same_inner_nodes(m, e, inc%item(first), inc)) then
                    call unlike_cell('other inner nodes', 'edge nodes')
                    return
                end if
            else if (per_edge == 3) then
                if (m%edges(3, e) /= mid_node(m, inc%item(first), inc)) then
                    call unlike_cell('another mid node', 'mid-edge node')
                    return
                end if
            end if
        end do

    contains

        !> Edge e's inner nodes (`has`) are not those of its cell (`expected` the cell's).
        subroutine unlike_cell(has, expected)
            character(len=*), intent(in) :: has, expected
            call stat%fail(STATUS_MESH, what(e)//'from '//point_text(m, a)//' to '// &
                point_text(m, b)//' has '//has//' than its cell ('// &
                cell_name(m, inc%cell_of(inc%item(first)))//'); expected the cell''s '//expected)
        end subroutine unlike_cell

        !> 'file:line: this edge of the boundary group 'name' (&mesh variable) '
        function what(e) result(text)
            integer, intent(in) :: e
            character(len=:), allocatable :: text
            text = edge_place(m, e)//'this edge of the boundary group '''// &
                trim(m%part_names(m%edge_part(e)))//''' (&mesh '//variable//') '
        end function what
    end subroutine check_groups

    !> One piece: all cells in one tree of the union-find forest.
    subroutine check_connected(m, parent, stat)
        type(mesh_t), intent(in) :: m
        integer, intent(inout) :: parent(:)
        type(status_t), intent(inout) :: stat
        integer :: c, root, other, n_pieces
        if (m%n_cells() == 0) return
        root = find_root(parent, 1)
        other = 0
        n_pieces = 0
        do c = 1, m%n_cells()
            if (find_root(parent, c) /= c) cycle
            n_pieces = n_pieces + 1
            if (c /= root .and. other == 0) other = c
        end do
        if (n_pieces == 1) return
        call stat%fail(STATUS_MESH, cell_place(m, other)//'the mesh is not connected: it '// &
            'falls into '//to_string(n_pieces)//' pieces that share no edge (this cell and '// &
            cell_name(m, 1)//' are in different pieces; duplicated nodes along a line cut '// &
            'the body there); expected one body')
    end subroutine check_connected

    ! ------------------------------------------------------------------------ helpers

    pure integer function n_corners(m)
        type(mesh_t), intent(in) :: m
        n_corners = element_corners(m%element)
    end function n_corners

    !> Mid node of cell edge k (0 for linear elements).
    pure integer function mid_node(m, k, inc)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: k
        type(incidence_t), intent(in) :: inc
        mid_node = 0
        if (size(m%cells, 1) > n_corners(m)) &
            mid_node = m%cells(n_corners(m) + inc%side_of(k), inc%cell_of(k))
    end function mid_node

    !> Whether cell edges k1 and k2 have the same nodes inside (in either order).
    pure logical function same_side_nodes(m, k1, k2, inc)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: k1, k2
        type(incidence_t), intent(in) :: inc
        integer :: inner, first1, first2, t
        inner = element_nodes_per_edge(m%element) - 2
        same_side_nodes = .true.
        if (inner < 1) return
        first1 = n_corners(m) + (inc%side_of(k1) - 1)*inner
        first2 = n_corners(m) + (inc%side_of(k2) - 1)*inner
        do t = 1, inner
            same_side_nodes = same_side_nodes .and. &
                any(m%cells(first1 + 1:first1 + inner, inc%cell_of(k1)) == &
                    m%cells(first2 + t, inc%cell_of(k2)))
        end do
    end function same_side_nodes

    !> Whether boundary edge `e` has the inner nodes (in either order) of cell edge k, for
    !> elements with p - 1 > 1 nodes inside each edge.
    pure logical function same_inner_nodes(m, e, k, inc)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: e, k
        type(incidence_t), intent(in) :: inc
        integer :: inner, first, t
        inner = size(m%edges, 1) - 2
        first = n_corners(m) + (inc%side_of(k) - 1)*inner
        same_inner_nodes = .true.
        do t = 1, inner
            same_inner_nodes = same_inner_nodes .and. &
                any(m%cells(first + 1:first + inner, inc%cell_of(k)) == m%edges(2 + t, e))
        end do
    end function same_inner_nodes

    !> Last position in inc%item of the corner pair that starts at position `first`.
    pure integer function pair_end(inc, first)
        type(incidence_t), intent(in) :: inc
        integer, intent(in) :: first
        integer :: k0
        k0 = inc%item(first)
        pair_end = first
        do while (pair_end < size(inc%item))
            if (inc%low(inc%item(pair_end + 1)) /= inc%low(k0) .or. &
                inc%high(inc%item(pair_end + 1)) /= inc%high(k0)) exit
            pair_end = pair_end + 1
        end do
    end function pair_end

    !> First position in inc%item of the corner pair (low, high), 0 if no cell has it.
    pure integer function find_pair(inc, low, high)
        type(incidence_t), intent(in) :: inc
        integer, intent(in) :: low, high
        integer :: i
        find_pair = 0
        do i = inc%bucket(low), inc%bucket(low + 1) - 1
            if (inc%high(inc%item(i)) == high) then
                find_pair = i
                return
            end if
        end do
    end function find_pair

    !> Root of c in the union-find forest, halving the path on the way.
    integer function find_root(parent, c)
        integer, intent(inout) :: parent(:)
        integer, intent(in) :: c
        find_root = c
        do while (parent(find_root) /= find_root)
            parent(find_root) = parent(parent(find_root))
            find_root = parent(find_root)
        end do
    end function find_root

    subroutine join(parent, c1, c2)
        integer, intent(inout) :: parent(:)
        integer, intent(in) :: c1, c2
        integer :: r1, r2
        r1 = find_root(parent, c1)
        r2 = find_root(parent, c2)
        if (r1 /= r2) parent(max(r1, r2)) = min(r1, r2)
    end subroutine join

    !> 'file: ' for a mesh read from a file, else ''.
    function file_prefix(m) result(text)
        type(mesh_t), intent(in) :: m
        character(len=:), allocatable :: text
        text = ''
        if (allocated(m%file)) text = m%file//': '
    end function file_prefix

    !> 'file:line: ' of cell c for a mesh read from a file, else 'cell c: '.
    function cell_place(m, c) result(text)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: c
        character(len=:), allocatable :: text
        text = cell_name(m, c)//': '
        if (allocated(m%file) .and. allocated(m%cell_line)) &
            text = m%file//':'//to_string(m%cell_line(c))//': '
    end function cell_place

    !> 'the cell at line L' for a mesh read from a file, else 'cell c'.
    function cell_name(m, c) result(text)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: c
        character(len=:), allocatable :: text
        text = 'cell '//to_string(c)
        if (allocated(m%cell_line)) text = 'the cell at line '//to_string(m%cell_line(c))
    end function cell_name

    !> 'file:line: ' of boundary edge e for a mesh read from a file, else 'boundary edge e: '.
    function edge_place(m, e) result(text)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: e
        character(len=:), allocatable :: text
        text = 'boundary edge '//to_string(e)//': '
        if (allocated(m%file) .and. allocated(m%edge_line)) &
            text = m%file//':'//to_string(m%edge_line(e))//': '
    end function edge_place

    function point_text(m, node) result(text)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: node
        character(len=:), allocatable :: text
        text = '('//to_string(m%coords(1, node))//', '//to_string(m%coords(2, node))//')'
    end function point_text

    subroutine out_of_memory(stat, n)
        type(status_t), intent(inout) :: stat
        integer, intent(in) :: n
        call stat%fail(STATUS_SOLVER, 'mesh check: cannot allocate arrays of '// &
            to_string(n)//' entries: out of memory')
    end subroutine out_of_memory
end module mesh_check
