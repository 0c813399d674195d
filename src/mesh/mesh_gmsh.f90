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
module mesh_gmsh
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_MESH
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, element_nodes_per_cell, element_nodes_per_edge, &
                             triangle_lattice
    use mesh_renumber, only: renumber_nodes, RENUMBER_RCM
    use cell_geometry, only: cell_orientation, CELL_DEGENERATE, CELL_FOLDED
    use strings, only: to_string, lowercase, NAME_LEN
    use sorting, only: sort_index
    use text_tokens, only: integers_at, read_ints, read_int, read_reals, skip_tokens, &
                           skip_blanks
    implicit none
    private
    public :: read_gmsh, gmsh_type_name

    ! Gmsh element type numbers (MSH file format documentation, section "Node ordering").
    integer, parameter :: GMSH_LINE2 = 1, GMSH_TRIANGLE3 = 2, GMSH_QUAD4 = 3, &
                          GMSH_LINE3 = 8, GMSH_TRIANGLE6 = 9, GMSH_QUAD9 = 10, GMSH_POINT = 15, &
                          GMSH_TRIANGLE10 = 21, GMSH_TRIANGLE15 = 23, GMSH_LINE4 = 26, &
                          GMSH_LINE5 = 27
    integer, parameter :: MAX_CELL_NODES = 15, MAX_LINE_NODES = 5
    ! z of a 2D mesh is written as 0 by Gmsh; allow round-off of a rotated plane geometry.
    real(wp), parameter :: PLANAR_TOL = 1.0e-10_wp
    ! Coordinates are below 1e100 in magnitude (text_tokens' MAX_DECIMAL_EXPONENT): far beyond
    ! any length in metres, and products of coordinate differences (Jacobians) stay finite.
    character(len=*), parameter :: REAL_HINT = '(decimal numbers below 1e100 in magnitude)'
    character(len=*), parameter :: FORMAT_HINT = 'write ASCII with gmsh -format msh41 ' &
                                                 //'(or -format msh22)'

    !> The file in memory, read line by line; `line` counts the lines handed out.
    type :: text_file_t
        character(len=:), allocatable :: path
        character(len=:), allocatable :: text
        integer(i8) :: next = 1
        integer :: line = 0
    end type text_file_t

    !> What the file says, before any check across sections.
    type :: raw_mesh_t
        integer :: version = 0                         !! 2 or 4
        integer :: n_nodes = 0, n_cells = 0, n_edges = 0, n_pairs = 0, n_names = 0
        integer, allocatable :: node_tag(:)
        real(wp), allocatable :: node_xyz(:, :)        !! (3, n_nodes)
        integer, allocatable :: cell_type(:), cell_nodes(:, :), cell_entity(:), cell_line(:)
        integer, allocatable :: edge_type(:), edge_nodes(:, :), edge_line(:)
        !> MSH 4: the curve (entity) tag; MSH 2: the physical tag (0: none).
        integer, allocatable :: edge_group(:)
        integer, allocatable :: pair_curve(:), pair_physical(:)   !! MSH 4 $Entities
        integer, allocatable :: name_dim(:), name_tag(:), name_line(:)
        character(len=:), allocatable :: name_text(:)
    end type raw_mesh_t

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

    ! ------------------------------------------------------------------------ the file

    subroutine load_file(path, f, stat)
        character(len=*), intent(in) :: path
        type(text_file_t), intent(out) :: f
        type(status_t), intent(out) :: stat
        character(len=512) :: msg
        integer :: unit, ios
        integer(i8) :: file_size

        f%path = path
        open (newunit=unit, file=path, access='stream', form='unformatted', status='old', &
              action='read', iostat=ios, iomsg=msg)
        if (ios /= 0) then
            call stat%fail(STATUS_MESH, path//': cannot open mesh file: '//trim(msg)// &
                           '; expected a readable Gmsh .msh file')
            return
        end if
        inquire (unit=unit, size=file_size)
        allocate (character(len=max(file_size, 0_i8)) :: f%text)
        if (file_size > 0) read (unit, iostat=ios, iomsg=msg) f%text
        close (unit)
        if (ios /= 0) call stat%fail(STATUS_MESH, path//': cannot read mesh file: '// &
                                     trim(msg)//'; expected a readable Gmsh .msh file')
    end subroutine load_file

    !> The next line without its end-of-line characters; .false. at the end of the file.
    logical function next_line(f, line)
        type(text_file_t), intent(inout) :: f
        character(len=:), allocatable, intent(out) :: line
        integer(i8) :: finish
        next_line = f%next <= len(f%text, kind=i8)
        if (.not. next_line) then
            line = ''
            return
        end if
        finish = index(f%text(f%next:), new_line('a'), kind=i8)
        if (finish == 0) then
            finish = len(f%text, kind=i8)
        else
            finish = f%next + finish - 2
        end if
        line = f%text(f%next:finish)
        f%next = finish + 2
        f%line = f%line + 1
        if (len(line) > 0) then
            if (line(len(line):) == achar(13)) line = line(:len(line) - 1)   ! CRLF files
        end if
    end function next_line

    !> The next line, or a failure 'unexpected end of file' saying what was expected.
    subroutine require_line(f, line, expected, stat)
        type(text_file_t), intent(inout) :: f
        character(len=:), allocatable, intent(out) :: line
        character(len=*), intent(in) :: expected
        type(status_t), intent(inout) :: stat
        if (.not. next_line(f, line)) call truncated(f, expected, stat)
    end subroutine require_line

    subroutine truncated(f, expected, stat)
        type(text_file_t), intent(in) :: f
        character(len=*), intent(in) :: expected
        type(status_t), intent(inout) :: stat
        call stat%fail(STATUS_MESH, f%path//':'//to_string(f%line)// &
            ': unexpected end of file (truncated?); expected '//printable(expected))
    end subroutine truncated

    !> Fail with 'path:line: message' at the line last read.
    subroutine fail_here(f, stat, message)
        type(text_file_t), intent(in) :: f
        type(status_t), intent(inout) :: stat
        character(len=*), intent(in) :: message
        call stat%fail(STATUS_MESH, f%path//':'//to_string(f%line)//': '//printable(message))
    end subroutine fail_here

    ! -------------------------------------------------------------------- the sections

    subroutine parse_sections(f, raw, stat)
        type(text_file_t), intent(inout) :: f
        type(raw_mesh_t), intent(inout) :: raw
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line, header
        integer, parameter :: NAMES = 1, ENTITIES = 2, NODES = 3, ELEMENTS = 4
        integer :: first_line(4)   !! where each parsed section began; 0: not yet

        call parse_format(f, raw, stat)
        if (.not. stat%ok()) return
        first_line = 0
        allocate (raw%pair_curve(0), raw%pair_physical(0))
        allocate (raw%name_dim(0), raw%name_tag(0), raw%name_line(0))
        allocate (character(len=NAME_LEN + 1) :: raw%name_text(0))
        do while (next_line(f, line))
            header = trim(adjustl(line))
            select case (header)
            case ('')
                cycle
            case ('$PhysicalNames')
                call first_time(NAMES)
                if (stat%ok()) call parse_physical_names(f, raw, stat)
            case ('$Entities')
                call first_time(ENTITIES)
                if (raw%version == 4 .and. stat%ok()) call parse_entities(f, raw, stat)
                if (raw%version /= 4 .and. stat%ok()) call skip_section(f, header, stat)
            case ('$PartitionedEntities')
                call fail_here(f, stat, 'partitioned meshes are not supported; expected a ' &
                               //'mesh saved without partitions')
            case ('$Nodes')
                call first_time(NODES)
                if (raw%version == 4 .and. stat%ok()) call parse_nodes_4(f, raw, stat)
                if (raw%version == 2 .and. stat%ok()) call parse_nodes_2(f, raw, stat)
            case ('$Elements')
                call first_time(ELEMENTS)
                if (raw%version == 4 .and. stat%ok()) call parse_elements_4(f, raw, stat)
                if (raw%version == 2 .and. stat%ok()) call parse_elements_2(f, raw, stat)
            case default
                if (header(1:1) /= '$' .or. header(1:min(4, len(header))) == '$End') then
                    call fail_here(f, stat, 'unexpected text '''//shortened(header)// &
                                   '''; expected a section header such as $Nodes')
                else
                    call skip_section(f, header, stat)
                end if
            end select
            if (.not. stat%ok()) return
        end do
        if (first_line(NODES) == 0) then
            call fail_here(f, stat, 'no $Nodes section (truncated file?)')
        else if (first_line(ELEMENTS) == 0) then
            call fail_here(f, stat, 'no $Elements section (truncated file?)')
        end if

    contains

        !> A section the reader parses may appear once (the MSH formats allow one).
        subroutine first_time(section)
            integer, intent(in) :: section
            if (first_line(section) == 0) then
                first_line(section) = f%line
            else
                call fail_here(f, stat, 'a second '//header//' section (the first began ' &
                               //'at line '//to_string(first_line(section))//'); expected one')
            end if
        end subroutine first_time
    end subroutine parse_sections

    !> $MeshFormat: version 4.1 or 2.x, ASCII.
    subroutine parse_format(f, raw, stat)
        type(text_file_t), intent(inout) :: f
        type(raw_mesh_t), intent(inout) :: raw
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        character(len=16) :: version
        integer :: file_type, sizes(2), pos, first
        logical :: ok

        do
            call require_line(f, line, '$MeshFormat', stat)
            if (.not. stat%ok()) return
            if (len_trim(line) > 0) exit
        end do
        if (trim(adjustl(line)) /= '$MeshFormat') then
            call fail_here(f, stat, 'not a Gmsh mesh file: expected $MeshFormat, found '''// &
                           shortened(trim(adjustl(line)))//'''')
            return
        end if
        call require_line(f, line, 'the version line ''4.1 0 8'' of $MeshFormat', stat)
        if (.not. stat%ok()) return
        ! Token by token: a list-directed read would leave file_type unset on '4.1 , 8'.
        pos = 1
        call skip_blanks(line, pos)
        first = pos
        call skip_tokens(line, pos, 1, ok)
        version = line(first:pos - 1)
        if (ok) call read_ints(line, pos, sizes, ok)
        file_type = sizes(1)
        if (.not. ok) then
            call fail_here(f, stat, 'expected ''version file-type data-size'' (such as ' &
                           //'''4.1 0 8''), found '''//shortened(line)//'''')
            return
        end if
        if (file_type /= 0) then
            call fail_here(f, stat, 'binary MSH files are not supported; '//FORMAT_HINT)
            return
        end if
        if (trim(version) == '4.1') then
            raw%version = 4
        else if (version(1:2) == '2.') then
            raw%version = 2
        else
            call fail_here(f, stat, 'MSH version '//shortened(trim(version))// &
                           ' is not supported (expected 4.1 or 2.2); '//FORMAT_HINT)
            return
        end if
        call expect_end(f, '$EndMeshFormat', stat)
    end subroutine parse_format

    !> The next non-blank line must be `marker`.
    subroutine expect_end(f, marker, stat)
        type(text_file_t), intent(inout) :: f
        character(len=*), intent(in) :: marker
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        do
            call require_line(f, line, marker, stat)
            if (.not. stat%ok()) return
            if (len_trim(line) > 0) exit
        end do
        if (trim(adjustl(line)) /= marker) then
            call fail_here(f, stat, 'expected '//marker//', found '''// &
                           shortened(trim(adjustl(line)))//''' (more entries than announced?)')
        end if
    end subroutine expect_end

    !> Skip an unused section ($Periodic, $NodeData, $Comments, ...) up to its end marker.
    subroutine skip_section(f, header, stat)
        type(text_file_t), intent(inout) :: f
        character(len=*), intent(in) :: header
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        do
            call require_line(f, line, '$End'//header(2:), stat)
            if (.not. stat%ok()) return
            if (trim(adjustl(line)) == '$End'//header(2:)) return
        end do
    end subroutine skip_section

    !> $PhysicalNames: count, then 'dimension tag "name"' per line.
    subroutine parse_physical_names(f, raw, stat)
        type(text_file_t), intent(inout) :: f
        type(raw_mesh_t), intent(inout) :: raw
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        integer :: values(2), n, i, first, last
        character(len=NAME_LEN + 1) :: name

        call read_counts(f, 1, 'the number of physical names', values, stat)
        if (stat%ok()) call check_announced(f, values(1), 1, 'names (a line each)', stat)
        if (.not. stat%ok()) return
        n = values(1)
        do i = 1, n
            ! The message is built only on failure: this runs once per line of the file.
            if (.not. next_line(f, line)) then
                call truncated(f, 'physical name '//to_string(i)//' of '// &
                    to_string(n)//' (''dimension tag "name"'')', stat)
                return
            end if
            if (.not. integers_at(line, values)) then
                call fail_here(f, stat, 'expected ''dimension tag "name"'', found '''// &
                               shortened(line)//'''')
                return
            end if
            first = index(line, '"')
            last = index(line, '"', back=.true.)
            if (first == 0 .or. last <= first) then
                call fail_here(f, stat, 'expected the name in double quotes, found '''// &
                               shortened(line)//'''')
                return
            end if
            if (printable(line(first:last)) /= line(first:last)) then
                call fail_here(f, stat, 'control characters in the physical name '// &
                               shortened(line(first:last))//'; expected printable text')
                return
            end if
            if (last - first - 1 > NAME_LEN) then
                call fail_here(f, stat, 'physical name longer than '//to_string(NAME_LEN)// &
                               ' characters: '//shortened(line(first:last)))
                return
            end if
            name = lowercase(line(first + 1:last - 1))
            raw%name_dim = [raw%name_dim, values(1)]
            raw%name_tag = [raw%name_tag, values(2)]
            raw%name_line = [raw%name_line, f%line]
            raw%name_text = [character(len=NAME_LEN + 1) :: raw%name_text, name]
        end do
        raw%n_names = n
        call expect_end(f, '$EndPhysicalNames', stat)
    end subroutine parse_physical_names

    !> MSH 4.1 $Entities: the physical tags of each curve (points, surfaces and volumes are
    !> only skipped: cells belong to the body whatever their surface).
    subroutine parse_entities(f, raw, stat)
        type(text_file_t), intent(inout) :: f
        type(raw_mesh_t), intent(inout) :: raw
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        integer :: counts(4), i, pos, tag, n_physical, physical, k
        logical :: ok

        n_physical = 0

        call read_counts(f, 4, '$Entities (numPoints numCurves numSurfaces numVolumes)', &
                         counts, stat)
        if (.not. stat%ok()) return
        call check_announced(f, maxval(counts), 1, 'entities of one kind (a line each)', stat)
        if (.not. stat%ok()) return
        do i = 1, counts(1)
            call require_line(f, line, 'a point entity of $Entities', stat)
            if (.not. stat%ok()) return
        end do
        do i = 1, counts(2)
            call require_line(f, line, 'a curve entity of $Entities', stat)
            if (.not. stat%ok()) return
            ! curveTag minX minY minZ maxX maxY maxZ numPhysicalTags physicalTag ...
            pos = 1
            call read_int(line, pos, tag, ok)
            if (ok) call skip_tokens(line, pos, 6, ok)
            if (ok) call read_int(line, pos, n_physical, ok)
            do k = 1, n_physical
                if (.not. ok) exit
                call read_int(line, pos, physical, ok)
                if (ok) then
                    raw%pair_curve = [raw%pair_curve, tag]
                    raw%pair_physical = [raw%pair_physical, abs(physical)]
                end if
            end do
            if (.not. ok) then
                call fail_here(f, stat, 'expected ''curveTag minX minY minZ maxX maxY maxZ ' &
                               //'numPhysicalTags physicalTag ...'', found '''// &
                               shortened(line)//'''')
                return
            end if
        end do
        raw%n_pairs = size(raw%pair_curve)
        do i = 1, counts(3)   ! two loops: counts(3) + counts(4) can overflow
            call require_line(f, line, 'a surface entity of $Entities', stat)
            if (.not. stat%ok()) return
        end do
        do i = 1, counts(4)
            call require_line(f, line, 'a volume entity of $Entities', stat)
            if (.not. stat%ok()) return
        end do
        call expect_end(f, '$EndEntities', stat)
    end subroutine parse_entities

    !> MSH 4.1 $Nodes: blocks of node tags, then their coordinates.
    subroutine parse_nodes_4(f, raw, stat)
        type(text_file_t), intent(inout) :: f
        type(raw_mesh_t), intent(inout) :: raw
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        integer :: header(4), block(4), b, i, n, pos
        logical :: ok

        call read_counts(f, 4, '$Nodes header (numEntityBlocks numNodes minNodeTag ' &
                         //'maxNodeTag)', header, stat)
        if (.not. stat%ok()) return
        n = header(2)
        call check_announced(f, n, 2, 'nodes (a tag line and a coordinate line each)', stat)
        if (stat%ok()) call allocate_nodes(f, raw, n, stat)
        if (.not. stat%ok()) return
        do b = 1, header(1)
            call read_counts(f, 4, 'node block '//to_string(b)//' of '//to_string(header(1)) &
                             //' (entityDim entityTag parametric numNodesInBlock)', block, stat)
            if (.not. stat%ok()) return
            ! Compared so, not as n_nodes + block(4) > n, which can overflow.
            if (block(4) > n - raw%n_nodes) then
                call fail_here(f, stat, 'more nodes than the '//to_string(n)// &
                               ' of the $Nodes header')
                return
            end if
            do i = 1, block(4)
                ! The message is built only on failure: this runs once per line of the file.
                if (.not. next_line(f, line)) then
                    call truncated(f, 'a node tag (node '//to_string(raw%n_nodes + i)// &
                        ' of '//to_string(n)//')', stat)
                    return
                end if
                pos = 1
                call read_int(line, pos, raw%node_tag(raw%n_nodes + i), ok)
                if (.not. ok) then
                    call fail_here(f, stat, 'expected a node tag, found '''// &
                                   shortened(line)//'''')
                    return
                end if
            end do
            do i = 1, block(4)
                ! The message is built only on failure: this runs once per line of the file.
                if (.not. next_line(f, line)) then
                    call truncated(f, 'coordinates x y z (node '// &
                        to_string(raw%n_nodes + i)//' of '//to_string(n)//')', stat)
                    return
                end if
                pos = 1
                call read_reals(line, pos, raw%node_xyz(:, raw%n_nodes + i), ok)
                if (.not. ok) then
                    call fail_here(f, stat, 'expected coordinates x y z '//REAL_HINT// &
                                   ', found '''//shortened(line)//'''')
                    return
                end if
            end do
            raw%n_nodes = raw%n_nodes + block(4)
        end do
        if (raw%n_nodes /= n) then
            call fail_here(f, stat, 'the node blocks hold '//to_string(raw%n_nodes)// &
                           ' nodes, the $Nodes header announced '//to_string(n))
            return
        end if
        call expect_end(f, '$EndNodes', stat)
    end subroutine parse_nodes_4

    !> MSH 2.2 $Nodes: count, then 'tag x y z' per line.
    subroutine parse_nodes_2(f, raw, stat)
        type(text_file_t), intent(inout) :: f
        type(raw_mesh_t), intent(inout) :: raw
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        integer :: header(1), i, n, pos
        logical :: ok

        call read_counts(f, 1, 'the number of nodes', header, stat)
        if (.not. stat%ok()) return
        n = header(1)
        call check_announced(f, n, 1, 'nodes (a line each)', stat)
        if (stat%ok()) call allocate_nodes(f, raw, n, stat)
        if (.not. stat%ok()) return
        do i = 1, n
            ! The message is built only on failure: this runs once per line of the file.
            if (.not. next_line(f, line)) then
                call truncated(f, 'node '//to_string(i)//' of '//to_string(n)// &
                    ' (''tag x y z'')', stat)
                return
            end if
            pos = 1
            call read_int(line, pos, raw%node_tag(i), ok)
            if (ok) call read_reals(line, pos, raw%node_xyz(:, i), ok)
            if (.not. ok) then
                call fail_here(f, stat, 'expected ''tag x y z'' '//REAL_HINT//', found ''' &
                               //shortened(line)//'''')
                return
            end if
        end do
        raw%n_nodes = n
        call expect_end(f, '$EndNodes', stat)
    end subroutine parse_nodes_2

    !> MSH 4.1 $Elements: blocks 'entityDim entityTag elementType numElementsInBlock', then
    !> 'elementTag nodeTag ...' per element.
    subroutine parse_elements_4(f, raw, stat)
        type(text_file_t), intent(inout) :: f
        type(raw_mesh_t), intent(inout) :: raw
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        integer :: header(4), block(4), b, i, k, pos, tag, nodes(MAX_CELL_NODES), dim, n_done
        logical :: ok

        call read_counts(f, 4, '$Elements header (numEntityBlocks numElements ' &
                         //'minElementTag maxElementTag)', header, stat)
        if (.not. stat%ok()) return
        call check_announced(f, header(2), 1, 'elements (a line each)', stat)
        if (stat%ok()) call allocate_elements(f, raw, header(2), stat)
        if (.not. stat%ok()) return
        n_done = 0
        do b = 1, header(1)
            call read_counts(f, 4, 'element block '//to_string(b)//' of '// &
                             to_string(header(1))//' (entityDim entityTag elementType ' &
                             //'numElementsInBlock)', block, stat)
            if (.not. stat%ok()) return
            call check_type(f, block(3), dim, k, stat)
            if (.not. stat%ok()) return
            ! Compared so, not as n_done + block(4) > header(2), which can overflow.
            if (block(4) > header(2) - n_done) then
                call fail_here(f, stat, 'more elements than the '//to_string(header(2))// &
                               ' of the $Elements header')
                return
            end if
            do i = 1, block(4)
                ! The message is built only on failure: this runs once per line of the file.
                if (.not. next_line(f, line)) then
                    call truncated(f, 'element '//to_string(n_done + i)//' of '// &
                        to_string(header(2))//' (''elementTag'' and '// &
                        to_string(k)//' node tags)', stat)
                    return
                end if
                pos = 1
                call read_int(line, pos, tag, ok)
                if (ok) call read_ints(line, pos, nodes(:k), ok)
                if (.not. ok) then
                    call fail_here(f, stat, 'expected an element tag and '//to_string(k)// &
                                   ' node tags ('//gmsh_type_name(block(3))//'), found '''// &
                                   shortened(line)//'''')
                    return
                end if
                call add_element(raw, dim, block(3), nodes(:k), block(2), f%line)
            end do
            n_done = n_done + block(4)
        end do
        if (n_done /= header(2)) then
            call fail_here(f, stat, 'the element blocks hold '//to_string(n_done)// &
                           ' elements, the $Elements header announced '//to_string(header(2)))
            return
        end if
        call expect_end(f, '$EndElements', stat)
    end subroutine parse_elements_4

    !> MSH 2.2 $Elements: count, then 'tag type numTags tag... node...' per line; the first
    !> tag is the physical group, the second the elementary entity.
    subroutine parse_elements_2(f, raw, stat)
        type(text_file_t), intent(inout) :: f
        type(raw_mesh_t), intent(inout) :: raw
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        integer :: header(1), i, k, pos, first(3), n_tags, tags(2), nodes(MAX_CELL_NODES), dim
        integer :: skipped
        logical :: ok

        call read_counts(f, 1, 'the number of elements', header, stat)
        if (.not. stat%ok()) return
        call check_announced(f, header(1), 1, 'elements (a line each)', stat)
        if (stat%ok()) call allocate_elements(f, raw, header(1), stat)
        if (.not. stat%ok()) return
        do i = 1, header(1)
            ! The message is built only on failure: this runs once per line of the file.
            if (.not. next_line(f, line)) then
                call truncated(f, 'element '//to_string(i)//' of '// &
                    to_string(header(1))//' (''tag type numTags tags nodes'')', stat)
                return
            end if
            pos = 1
            call read_ints(line, pos, first, ok)
            if (.not. ok) then
                call fail_here(f, stat, 'expected ''tag type numTags tags nodes'', found ''' &
                               //shortened(line)//'''')
                return
            end if
            call check_type(f, first(2), dim, k, stat)
            if (.not. stat%ok()) return
            n_tags = first(3)
            tags = 0
            call read_ints(line, pos, tags(:min(2, max(n_tags, 0))), ok)
            skipped = max(n_tags - 2, 0)
            if (ok) call skip_tokens(line, pos, skipped, ok)
            if (ok) call read_ints(line, pos, nodes(:k), ok)
            if (.not. ok .or. n_tags < 0) then
                call fail_here(f, stat, 'expected '//to_string(max(n_tags, 0))//' tags and ' &
                               //to_string(k)//' node tags ('//gmsh_type_name(first(2))// &
                               '), found '''//shortened(line)//'''')
                return
            end if
            if (dim == 1) then
                call add_element(raw, dim, first(2), nodes(:k), tags(1), f%line)
            else
                call add_element(raw, dim, first(2), nodes(:k), tags(2), f%line)
            end if
        end do
        call expect_end(f, '$EndElements', stat)
    end subroutine parse_elements_2

    !> Dimension and node count of a supported element type; anything else fails here.
    subroutine check_type(f, type, dim, n_nodes, stat)
        type(text_file_t), intent(in) :: f
        integer, intent(in) :: type
        integer, intent(out) :: dim, n_nodes
        type(status_t), intent(inout) :: stat
        dim = 0
        n_nodes = 0
        select case (type)
        case (GMSH_POINT); dim = 0; n_nodes = 1
        case (GMSH_LINE2); dim = 1; n_nodes = 2
        case (GMSH_LINE3); dim = 1; n_nodes = 3
        case (GMSH_TRIANGLE3); dim = 2; n_nodes = 3
        case (GMSH_TRIANGLE6); dim = 2; n_nodes = 6
        case (GMSH_QUAD4); dim = 2; n_nodes = 4
        case (GMSH_QUAD9); dim = 2; n_nodes = 9
        case (GMSH_LINE4); dim = 1; n_nodes = 4
        case (GMSH_LINE5); dim = 1; n_nodes = 5
        case (GMSH_TRIANGLE10); dim = 2; n_nodes = 10
        case (GMSH_TRIANGLE15); dim = 2; n_nodes = 15
        case default
            call fail_here(f, stat, 'unsupported element type '//to_string(type)//' ('// &
                gmsh_type_name(type)//'); expected 3-, 6-, 10- or 15-node triangles, 4- or ' &
                //'9-node quadrangles, 2- to 5-node lines, points')
        end select
    end subroutine check_type

    !> Name of a Gmsh element type, for messages.
    pure function gmsh_type_name(type) result(name)
        integer, intent(in) :: type
        character(len=:), allocatable :: name
        select case (type)
        case (GMSH_LINE2); name = '2-node line'
        case (GMSH_TRIANGLE3); name = '3-node triangle'
        case (GMSH_QUAD4); name = '4-node quadrangle'
        case (4); name = '4-node tetrahedron: a 3D mesh'
        case (5); name = '8-node hexahedron: a 3D mesh'
        case (6); name = '6-node prism: a 3D mesh'
        case (7); name = '5-node pyramid: a 3D mesh'
        case (GMSH_LINE3); name = '3-node line'
        case (GMSH_TRIANGLE6); name = '6-node triangle'
        case (GMSH_QUAD9); name = '9-node quadrangle'
        case (11); name = '10-node tetrahedron: a 3D mesh'
        case (GMSH_POINT); name = 'point'
        case (16); name = '8-node serendipity quadrangle: set Mesh.SecondOrderIncomplete = 0'
        case (20); name = '9-node cubic triangle: set Mesh.SecondOrderIncomplete = 0'
        case (GMSH_TRIANGLE10); name = '10-node triangle'
        case (GMSH_TRIANGLE15); name = '15-node triangle'
        case (GMSH_LINE4); name = '4-node line'
        case (GMSH_LINE5); name = '5-node line'
        case (22); name = '12-node quartic triangle: set Mesh.SecondOrderIncomplete = 0'
        case (36); name = 'cubic quadrangle: use -order 1 or 2 for quadrangles'
        case (37); name = 'quartic quadrangle: use -order 1 or 2 for quadrangles'
        case default; name = 'not a 2D element of order 1 to 4'
        end select
    end function gmsh_type_name

    !> A section header's count `n` of entries taking `lines_each` lines must fit in the
    !> rest of the file: a mangled count then fails here, not as a huge allocation.
    subroutine check_announced(f, n, lines_each, what, stat)
        type(text_file_t), intent(in) :: f
        integer, intent(in) :: n, lines_each
        character(len=*), intent(in) :: what
        type(status_t), intent(inout) :: stat
        integer(i8) :: n_lines, start, finish
        n_lines = 0
        start = f%next
        do while (start <= len(f%text, kind=i8))
            finish = index(f%text(start:), new_line('a'), kind=i8)
            n_lines = n_lines + 1
            if (finish == 0) exit
            start = start + finish
        end do
        if (int(n, i8)*lines_each <= n_lines) return
        call fail_here(f, stat, 'the header announces '//to_string(n)//' '//what// &
                       ', but the file ends '//to_string(int(n_lines))//' lines later ' &
                       //'(truncated?); expected a count that the section holds')
    end subroutine check_announced

    subroutine allocate_nodes(f, raw, n, stat)
        type(text_file_t), intent(in) :: f
        type(raw_mesh_t), intent(inout) :: raw
        integer, intent(in) :: n
        type(status_t), intent(inout) :: stat
        integer :: alloc_status
        allocate (raw%node_tag(n), raw%node_xyz(3, n), stat=alloc_status)
        if (alloc_status /= 0) call fail_here(f, stat, 'out of memory for the '// &
                                              to_string(n)//' nodes announced here')
    end subroutine allocate_nodes

    subroutine allocate_elements(f, raw, n, stat)
        type(text_file_t), intent(in) :: f
        type(raw_mesh_t), intent(inout) :: raw
        integer, intent(in) :: n
        type(status_t), intent(inout) :: stat
        integer :: alloc_status
        allocate (raw%cell_type(n), raw%cell_nodes(MAX_CELL_NODES, n), raw%cell_entity(n), &
                  raw%cell_line(n), raw%edge_type(n), raw%edge_nodes(MAX_LINE_NODES, n), &
                  raw%edge_group(n), raw%edge_line(n), stat=alloc_status)
        if (alloc_status /= 0) then
            call fail_here(f, stat, 'out of memory for the '//to_string(n)// &
                           ' elements announced here')
            return
        end if
        raw%cell_nodes = 0
        raw%edge_nodes = 0
    end subroutine allocate_elements

    subroutine add_element(raw, dim, type, nodes, group, line)
        type(raw_mesh_t), intent(inout) :: raw
        integer, intent(in) :: dim, type, nodes(:), group, line
        select case (dim)
        case (1)
            raw%n_edges = raw%n_edges + 1
            raw%edge_type(raw%n_edges) = type
            raw%edge_nodes(:size(nodes), raw%n_edges) = nodes
            raw%edge_group(raw%n_edges) = group
            raw%edge_line(raw%n_edges) = line
        case (2)
            raw%n_cells = raw%n_cells + 1
            raw%cell_type(raw%n_cells) = type
            raw%cell_nodes(:size(nodes), raw%n_cells) = nodes
            raw%cell_entity(raw%n_cells) = group
            raw%cell_line(raw%n_cells) = line
        end select
    end subroutine add_element

    !> A line of `n` non-negative integers (counts of a section header).
    subroutine read_counts(f, n, expected, values, stat)
        type(text_file_t), intent(inout) :: f
        integer, intent(in) :: n
        character(len=*), intent(in) :: expected
        integer, intent(out) :: values(n)
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: line
        values = 0
        call require_line(f, line, expected, stat)
        if (.not. stat%ok()) return
        if (.not. integers_at(line, values)) then
            call fail_here(f, stat, 'expected '//expected//', found '''//shortened(line)//'''')
        else if (any(values < 0) .and. n > 1) then
            call fail_here(f, stat, 'expected '//expected//', found negative counts in '''// &
                           shortened(line)//'''')
        else if (n == 1 .and. values(1) < 0) then
            call fail_here(f, stat, 'expected '//expected//', found '''//shortened(line)//'''')
        end if
    end subroutine read_counts

    ! ------------------------------------------------------------------ checks and mesh

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
                node = find_node(raw%cell_nodes(a, c))
                if (node == 0) then
                    call undefined(raw%cell_line(c), raw%cell_nodes(a, c))
                    return
                end if
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
                node = find_node(raw%edge_nodes(a, e))
                if (node == 0) then
                    call undefined(raw%edge_line(e), raw%edge_nodes(a, e))
                    return
                end if
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
        allocate (m%coords(2, n_used))
        do node = 1, raw%n_nodes
            if (new_node(node) > 0) m%coords(:, new_node(node)) = raw%node_xyz(1:2, node)
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
            integer :: low, high, middle
            find_node = 0
            if (tags_are_positions) then
                if (tag >= 1 .and. tag <= raw%n_nodes) find_node = tag
                return
            end if
            low = 1
            high = size(sorted_tags)
            do while (low <= high)
                middle = (low + high)/2
                if (sorted_tags(middle) == tag) then
                    find_node = index_of_sorted(middle)
                    return
                else if (sorted_tags(middle) < tag) then
                    low = middle + 1
                else
                    high = middle - 1
                end if
            end do
        end function find_node

        subroutine undefined(line, tag)
            integer, intent(in) :: line, tag
            call stat%fail(STATUS_MESH, f%path//':'//to_string(line)//': this element ' &
                //'refers to node '//to_string(tag)//', which $Nodes does not define; ' &
                //'expected tags of defined nodes')
        end subroutine undefined

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

    pure integer function element_of_type(type)
        integer, intent(in) :: type
        select case (type)
        case (GMSH_TRIANGLE3); element_of_type = ELEMENT_P1
        case (GMSH_QUAD4); element_of_type = ELEMENT_Q1
        case (GMSH_TRIANGLE6); element_of_type = ELEMENT_P2
        case (GMSH_QUAD9); element_of_type = ELEMENT_Q2
        case (GMSH_TRIANGLE10); element_of_type = ELEMENT_P3
        case (GMSH_TRIANGLE15); element_of_type = ELEMENT_P4
        case default; element_of_type = 0
        end select
    end function element_of_type

    pure integer function order_of(type)
        integer, intent(in) :: type
        select case (type)
        case (GMSH_LINE3, GMSH_TRIANGLE6, GMSH_QUAD9); order_of = 2
        case (GMSH_LINE4, GMSH_TRIANGLE10); order_of = 3
        case (GMSH_LINE5, GMSH_TRIANGLE15); order_of = 4
        case default; order_of = 1
        end select
    end function order_of

    !> At most 60 characters of a line, for messages, in printable ASCII: a stray carriage
    !> return would break the one-line message, and bytes of a binary or garbage file
    !> (C1 controls among them) could drive the terminal.
    pure function shortened(text) result(short)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: short
        integer :: i
        if (len(text) <= 60) then
            short = printable(text)
        else
            short = printable(text(:57))//'...'
        end if
        do i = 1, len(short)
            if (iachar(short(i:i)) > 127) short(i:i) = '?'
        end do
    end function shortened

    !> `text` with control characters (line breaks, NUL, escape, ...) replaced by '?'.
    pure function printable(text) result(clean)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: clean
        integer :: i
        clean = text
        do i = 1, len(clean)
            if (iachar(clean(i:i)) < 32 .or. iachar(clean(i:i)) == 127) clean(i:i) = '?'
        end do
    end function printable
end module mesh_gmsh
