! SPDX-License-Identifier: MIT
!> Gmsh meshes: MSH 4.1 and MSH 2.2 ASCII files into a `mesh_t`.
!>
!> Body cells are all 2D elements (3-, 6-, 10- and 15-node triangles, 4- and 9-node
!> quadrangles, one type per mesh); boundary parts are the 1D physical groups, named by
!> $PhysicalNames (lowercased, as the input file's names are) or, when unnamed, by their
!> number; each 2- to 5-node line element of a group becomes a boundary edge of that part
!> (an element in several
!> groups is an edge of each). Points and lines outside physical groups are ignored; 3D
!> elements are rejected. The reader checks what the assembly cannot report with a file
!> line: undefined nodes, mixed element orders or shapes, inverted and degenerate cells. A
!> surface whose cells are all clockwise (as Gmsh writes a surface whose normal points to
!> -z) is reoriented; a clockwise cell among anticlockwise ones is an error. Nodes used by no
!> cell are dropped, and the rest renumbered by reverse Cuthill-McKee for locality.
!>
!> The text handling is msh_text's, the sections' parsing msh_parser's; this module checks
!> across sections and builds the mesh.
module mesh_gmsh
    use kinds, only: wp
    use status, only: status_t, STATUS_MESH
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, element_nodes_per_cell, element_nodes_per_edge, &
                             triangle_lattice
    use mesh_renumber, only: renumber_nodes, RENUMBER_RCM
    use cell_geometry, only: cell_orientation, CELL_DEGENERATE, CELL_FOLDED
    use strings, only: to_string
    use sorting, only: sort_index, sorted_position
    use msh_text, only: text_file_t, load_file
    use msh_parser, only: raw_mesh_t, parse_sections, gmsh_type_name, element_of_type, &
                          order_of, MAX_CELL_NODES, MAX_LINE_NODES
    implicit none
    private
    public :: read_gmsh, gmsh_type_name

    ! z of a 2D mesh is written as 0 by Gmsh; allow round-off of a rotated plane geometry.
    real(wp), parameter :: PLANAR_TOL = 1.0e-10_wp

contains

    !> Read the Gmsh ASCII mesh `path` (MSH 4.1 or 2.2) into `m`. Every failure is
    !> STATUS_MESH with a message 'path:line: problem; expected ...'. `n_reoriented` is the
    !> number of clockwise cells turned anticlockwise. `renumber` (RENUMBER_*, default
    !> RENUMBER_RCM) is for benchmarks: RENUMBER_NONE keeps the file's node order.
    subroutine read_gmsh(path, m, stat, n_reoriented, renumber)
        character(len=*), intent(in) :: path
        type(mesh_t), intent(out) :: m
        type(status_t), intent(out) :: stat
        integer, intent(out), optional :: n_reoriented
        integer, intent(in), optional :: renumber
        type(text_file_t) :: f
        type(raw_mesh_t) :: raw
        integer :: reoriented, method

        if (present(n_reoriented)) n_reoriented = 0
        call load_file(path, f, stat)
        if (.not. stat%ok()) return
        call parse_sections(f, raw, stat)
        if (.not. stat%ok()) return
        call build_mesh(f, raw, m, reoriented, stat)
        if (.not. stat%ok()) return
        if (present(n_reoriented)) n_reoriented = reoriented
        ! RCM rather than METIS: see docs/meshes.md (Gmsh input) for the measurements.
        method = RENUMBER_RCM
        if (present(renumber)) method = renumber
        call renumber_nodes(m, method, stat)
        if (.not. stat%ok()) stat%message = path//': '//stat%message
    end subroutine read_gmsh

    !> The checked mesh from what the file said.
    subroutine build_mesh(f, raw, m, n_reoriented, stat)
        type(text_file_t), intent(in) :: f
        type(raw_mesh_t), intent(in) :: raw
        type(mesh_t), intent(out) :: m
        integer, intent(out) :: n_reoriented
        type(status_t), intent(inout) :: stat
        integer, allocatable :: sorted_tags(:), index_of_sorted(:), node_of(:), new_node(:)
        integer, allocatable :: cells(:, :), edges(:, :), edge_part(:), edge_line(:)
        integer, allocatable :: part_tag(:)
        integer :: n_cell_nodes, n_edge_nodes, c, e, a, node, n_used, i, part, element, n_kept
        integer :: line_nodes(MAX_LINE_NODES)
        logical :: tags_are_positions
        logical, allocatable :: in_part(:)
        character(len=:), allocatable :: place

        n_reoriented = 0
        if (raw%n_cells == 0) then
            call stat%fail(STATUS_MESH, f%path//': no triangles or quadrangles in $Elements; ' &
                //'expected a 2D mesh (with physical groups, Gmsh saves only their elements: ' &
                //'define a Physical Surface)')
            return
        end if

        ! One cell type: the first cell's.
        element = element_of_type(raw%cell_type(1))
        n_cell_nodes = element_nodes_per_cell(element)
        n_edge_nodes = element_nodes_per_edge(element)
        do c = 2, raw%n_cells
            if (raw%cell_type(c) == raw%cell_type(1)) cycle
            place = f%path//':'//to_string(raw%cell_line(c))//': '
            if (order_of(raw%cell_type(c)) /= order_of(raw%cell_type(1))) then
                call stat%fail(STATUS_MESH, place//'mixed element orders: a '// &
                    gmsh_type_name(raw%cell_type(c))//' after '// &
                    gmsh_type_name(raw%cell_type(1))//'s (line '// &
                    to_string(raw%cell_line(1))//'); expected one order (gmsh -order 1 to 4)')
            else
                call stat%fail(STATUS_MESH, place//'mixed cell shapes: a '// &
                    gmsh_type_name(raw%cell_type(c))//' after '// &
                    gmsh_type_name(raw%cell_type(1))//'s (line '// &
                    to_string(raw%cell_line(1))//'); expected only triangles or only ' &
                    //'quadrangles')
            end if
            return
        end do
        do e = 1, raw%n_edges
            if (order_of(raw%edge_type(e)) == order_of(raw%cell_type(1))) cycle
            call stat%fail(STATUS_MESH, f%path//':'//to_string(raw%edge_line(e))// &
                ': mixed element orders: a '//gmsh_type_name(raw%edge_type(e))//' with '// &
                gmsh_type_name(raw%cell_type(1))//' cells (line '// &
                to_string(raw%cell_line(1))//'); expected '//to_string(n_edge_nodes)// &
                '-node lines')
            return
        end do

        ! Node tags -> positions in the file, by binary search in the sorted tags (a direct
        ! table when the tags are 1, 2, ..., n, as Gmsh writes them).
        tags_are_positions = all(raw%node_tag(:raw%n_nodes) == [(i, i=1, raw%n_nodes)])
        if (.not. tags_are_positions) then
            index_of_sorted = sort_index(raw%node_tag(:raw%n_nodes))
            sorted_tags = raw%node_tag(index_of_sorted)
            do i = 2, size(sorted_tags)
                if (sorted_tags(i) == sorted_tags(i - 1)) then
                    call stat%fail(STATUS_MESH, f%path//': node tag '// &
                        to_string(sorted_tags(i))//' is defined twice in $Nodes; expected ' &
                        //'distinct tags')
                    return
                end if
            end do
        end if

        allocate (cells(n_cell_nodes, raw%n_cells))
        allocate (node_of(raw%n_nodes), source=0)   ! 1: used by a cell
        do c = 1, raw%n_cells
            do a = 1, n_cell_nodes
                call locate(raw%cell_nodes(a, c), raw%cell_line(c), node)
                if (node == 0) return
                cells(a, c) = node
                node_of(node) = 1
            end do
        end do

        ! Boundary parts: 1D physical groups, named or not; edges of each.
        call collect_parts(part_tag, stat)
        if (.not. stat%ok()) return
        n_kept = 0
        do e = 1, raw%n_edges
            do a = 1, n_edge_nodes
                call locate(raw%edge_nodes(a, e), raw%edge_line(e), node)
                if (node == 0) return
            end do
            n_kept = n_kept + count(edge_parts(e))
        end do
        allocate (edges(n_edge_nodes, n_kept), edge_part(n_kept), edge_line(n_kept))
        n_kept = 0
        do e = 1, raw%n_edges
            in_part = edge_parts(e)
            if (.not. any(in_part)) cycle
            do a = 1, n_edge_nodes
                node = find_node(raw%edge_nodes(a, e))
                if (node_of(node) == 0) then
                    call stat%fail(STATUS_MESH, f%path//':'//to_string(raw%edge_line(e))// &
                        ': node '//to_string(raw%edge_nodes(a, e))//' of this line element ' &
                        //'is on no triangle or quadrangle; expected boundary lines of the body')
                    return
                end if
                line_nodes(a) = node
            end do
            do part = 1, size(part_tag)
                if (.not. in_part(part)) cycle
                n_kept = n_kept + 1
                edges(:, n_kept) = line_nodes(:n_edge_nodes)
                edge_part(n_kept) = part
                edge_line(n_kept) = raw%edge_line(e)
            end do
        end do

        ! Keep the nodes of cells only, in file order.
        allocate (new_node(raw%n_nodes), source=0)
        n_used = 0
        do node = 1, raw%n_nodes
            if (node_of(node) == 0) cycle
            n_used = n_used + 1
            new_node(node) = n_used
        end do
        m%element = element
        allocate (m%coords(m%dim(), n_used))
        do node = 1, raw%n_nodes
            if (new_node(node) > 0) m%coords(:, new_node(node)) = raw%node_xyz(1:m%dim(), node)
        end do
        call check_planar(stat)
        if (.not. stat%ok()) return
        m%cells = reshape(new_node(reshape(cells, [size(cells)])), shape(cells))
        m%edges = reshape(new_node(reshape(edges, [size(edges)])), shape(edges))
        m%edge_part = edge_part
        m%file = f%path
        m%cell_line = raw%cell_line(:raw%n_cells)
        m%edge_line = edge_line
        call orient_cells(f%path, raw%cell_entity(:raw%n_cells), m, n_reoriented, stat)

    contains

        integer function find_node(tag)
            integer, intent(in) :: tag
            integer :: position
            find_node = 0
            if (tags_are_positions) then
                if (tag >= 1 .and. tag <= raw%n_nodes) find_node = tag
                return
            end if
            position = sorted_position(sorted_tags, tag)
            if (position > 0) find_node = index_of_sorted(position)
        end function find_node

        !> find_node(tag) of the element at file line `line`; 0, and the failure in stat, when
        !> $Nodes does not define the tag.
        subroutine locate(tag, line, node)
            integer, intent(in) :: tag, line
            integer, intent(out) :: node
            node = find_node(tag)
            if (node == 0) call stat%fail(STATUS_MESH, f%path//':'//to_string(line)// &
                ': this element refers to node '//to_string(tag)//', which $Nodes does not '// &
                'define; expected tags of defined nodes')
        end subroutine locate

        !> Physical tags of the 1D groups (named in $PhysicalNames or used by a line
        !> element) and m%part_names, lowercased; two names equal but for case are an error.
        subroutine collect_parts(tags, stat)
            integer, allocatable, intent(out) :: tags(:)
            type(status_t), intent(inout) :: stat
            integer :: k, j, group
            allocate (tags(0))
            do k = 1, raw%n_names
                if (raw%name_dim(k) == 1 .and. .not. any(tags == raw%name_tag(k))) &
                    tags = [tags, raw%name_tag(k)]
            end do
            do k = 1, raw%n_edges
                if (raw%version == 2) then
                    group = raw%edge_group(k)
                    if (group /= 0 .and. .not. any(tags == group)) tags = [tags, group]
                end if
            end do
            if (raw%version == 4) then
                do k = 1, raw%n_pairs
                    if (.not. any(tags == raw%pair_physical(k))) &
                        tags = [tags, raw%pair_physical(k)]
                end do
            end if
            allocate (m%part_names(size(tags)))
            do k = 1, size(tags)
                m%part_names(k) = to_string(tags(k))
                do j = 1, raw%n_names
                    if (raw%name_dim(j) == 1 .and. raw%name_tag(j) == tags(k)) &
                        m%part_names(k) = raw%name_text(j)
                end do
            end do
            do k = 2, size(tags)
                do j = 1, k - 1
                    if (m%part_names(k) /= m%part_names(j)) cycle
                    call stat%fail(STATUS_MESH, f%path//': two 1D physical groups are ' &
                        //'named '''//trim(m%part_names(k))//''' (names are compared ' &
                        //'ignoring case); expected distinct names')
                    return
                end do
            end do
        end subroutine collect_parts

        !> Which parts (entries of part_tag) raw line element `e` belongs to.
        function edge_parts(e) result(member)
            integer, intent(in) :: e
            logical :: member(size(part_tag))
            integer :: k
            if (raw%version == 2) then
                member = part_tag == raw%edge_group(e)
                return
            end if
            member = .false.
            do k = 1, raw%n_pairs
                if (raw%pair_curve(k) == raw%edge_group(e)) &
                    member = member .or. part_tag == raw%pair_physical(k)
            end do
        end function edge_parts

        !> The mesh must lie in a plane z = constant.
        subroutine check_planar(stat)
            type(status_t), intent(inout) :: stat
            real(wp) :: extent, z0
            integer :: k
            extent = max(maxval(m%coords(1, :)) - minval(m%coords(1, :)), &
                         maxval(m%coords(2, :)) - minval(m%coords(2, :)))
            z0 = raw%node_xyz(3, cells(1, 1))
            do k = 1, raw%n_nodes
                if (node_of(k) == 0) cycle
                if (abs(raw%node_xyz(3, k) - z0) > PLANAR_TOL*extent) then
                    call stat%fail(STATUS_MESH, f%path//': node '// &
                        to_string(raw%node_tag(k))//' has z = '// &
                        to_string(raw%node_xyz(3, k))//'; expected a plane 2D mesh (all z ' &
                        //'equal)')
                    return
                end if
            end do
        end subroutine check_planar
    end subroutine build_mesh

    !> Check every cell's Jacobian at its nodes (cell_geometry: the test element_stiffness
    !> applies, so that a cell accepted here is accepted there) and orient the cells
    !> anticlockwise: a surface (entity) whose cells are all clockwise is reoriented; a cell
    !> whose orientation differs from the others of its surface is inverted, one with a
    !> vanishing or sign-changing Jacobian degenerate or folded.
    subroutine orient_cells(path, entity, m, n_reoriented, stat)
        character(len=*), intent(in) :: path
        integer, intent(in) :: entity(:)
        type(mesh_t), intent(inout) :: m
        integer, intent(out) :: n_reoriented
        type(status_t), intent(inout) :: stat
        integer, allocatable :: orientation(:), surfaces(:), surface_of(:), n_positive(:), &
                                n_negative(:)
        integer :: c, s, flip(MAX_CELL_NODES), n
        character(len=:), allocatable :: problem

        n_reoriented = 0
        n = size(m%cells, 1)
        allocate (orientation(m%n_cells()), surface_of(m%n_cells()))
        allocate (surfaces(0))
        s = 0
        do c = 1, m%n_cells()
            orientation(c) = cell_orientation(m%element, m%coords(:, m%cells(:, c)))
            if (orientation(c) == CELL_DEGENERATE .or. orientation(c) == CELL_FOLDED) then
                problem = 'degenerate: zero area (its corners are collinear or coincide)'
                if (orientation(c) == CELL_FOLDED) then
                    problem = 'inverted or degenerate: its Jacobian determinant vanishes or ' &
                              //'changes sign at a node (a folded or flat cell'
                    if (n > 4) problem = problem//', or misplaced mid-edge nodes'
                    problem = problem//')'
                end if
                call stat%fail(STATUS_MESH, path//':'//to_string(m%cell_line(c))// &
                               ': this cell is '//problem)
                return
            end if
            ! Cells of a surface are consecutive in Gmsh files: look further only on change.
            if (s > 0) then
                if (surfaces(s) == entity(c)) then
                    surface_of(c) = s
                    cycle
                end if
            end if
            s = findloc(surfaces, entity(c), dim=1)
            if (s == 0) then
                surfaces = [surfaces, entity(c)]
                s = size(surfaces)
            end if
            surface_of(c) = s
        end do
        allocate (n_positive(size(surfaces)), n_negative(size(surfaces)), source=0)
        do c = 1, m%n_cells()
            if (orientation(c) > 0) n_positive(surface_of(c)) = n_positive(surface_of(c)) + 1
            if (orientation(c) < 0) n_negative(surface_of(c)) = n_negative(surface_of(c)) + 1
        end do
        do c = 1, m%n_cells()
            s = surface_of(c)
            ! The minority orientation of a surface is the inverted one (ties: clockwise).
            if (n_positive(s) > 0 .and. n_negative(s) > 0) then
                if ((orientation(c) < 0) .eqv. (n_negative(s) <= n_positive(s))) then
                    call stat%fail(STATUS_MESH, path//':'//to_string(m%cell_line(c))// &
                        ': inverted cell: it is '//trim(merge('clockwise    ', &
                        'anticlockwise', orientation(c) < 0))//' while '// &
                        to_string(max(n_positive(s), n_negative(s)))//' other cells of ' &
                        //'surface '//to_string(surfaces(s))//' are not; expected ' &
                        //'consistently oriented cells')
                    return
                end if
            end if
        end do
        flip(:n) = reoriented_order(m%element)
        do c = 1, m%n_cells()
            if (orientation(c) > 0) cycle
            m%cells(:, c) = m%cells(flip(:n), c)
            n_reoriented = n_reoriented + 1
        end do
    end subroutine orient_cells

    !> Node order that turns a clockwise cell anticlockwise: corners reversed after the
    !> first, mid-edge nodes following their edges. For cubic and quartic triangles, the node
    !> at lattice index (i1, i3, i2) takes the place of the one at (i1, i2, i3).
    pure function reoriented_order(element) result(order)
        integer, intent(in) :: element
        integer :: order(element_nodes_per_cell(element))
        integer :: lattice(3, MAX_CELL_NODES), a, b
        select case (element)
        case (ELEMENT_P3, ELEMENT_P4)
            call triangle_lattice(element, lattice)
            do a = 1, size(order)
                do b = 1, size(order)
                    if (all(lattice(:, b) == lattice([1, 3, 2], a))) order(a) = b
                end do
            end do
        case (ELEMENT_P1); order = [1, 3, 2]
        case (ELEMENT_Q1); order = [1, 4, 3, 2]
        case (ELEMENT_P2); order = [1, 3, 2, 6, 5, 4]
        case (ELEMENT_Q2); order = [1, 4, 3, 2, 8, 7, 6, 5, 9]
        end select
    end function reoriented_order
end module mesh_gmsh
