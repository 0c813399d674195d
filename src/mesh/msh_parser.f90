! SPDX-License-Identifier: MIT
!> The MSH 4.1 and 2.2 ASCII sections ($MeshFormat, $PhysicalNames, $Entities, $Nodes,
!> $Elements) into a `raw_mesh_t`: what the file says, each entry with its file line, checked
!> only within its section (counts, numbers, supported element types). The checks across
!> sections and the conversion to a mesh are mesh_gmsh's.
module msh_parser
    use kinds, only: wp
    use status, only: status_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4
    use strings, only: to_string, lowercase, NAME_LEN
    use text_tokens, only: integers_at, read_ints, read_int, read_reals, skip_tokens, &
                           skip_blanks
    use msh_text, only: text_file_t, next_line, require_line, truncated, fail_here, &
                        check_announced, read_counts, shortened, printable
    implicit none
    private
    public :: raw_mesh_t, parse_sections, gmsh_type_name, element_of_type, order_of
    public :: MAX_CELL_NODES, MAX_LINE_NODES

    ! Gmsh element type numbers (MSH file format documentation, section "Node ordering").
    integer, parameter :: GMSH_LINE2 = 1, GMSH_TRIANGLE3 = 2, GMSH_QUAD4 = 3, &
                          GMSH_LINE3 = 8, GMSH_TRIANGLE6 = 9, GMSH_QUAD9 = 10, GMSH_POINT = 15, &
                          GMSH_TRIANGLE10 = 21, GMSH_TRIANGLE15 = 23, GMSH_LINE4 = 26, &
                          GMSH_LINE5 = 27
    integer, parameter :: MAX_CELL_NODES = 15, MAX_LINE_NODES = 5
    ! Coordinates are below 1e100 in magnitude (text_tokens' MAX_DECIMAL_EXPONENT): far beyond
    ! any length in metres, and products of coordinate differences (Jacobians) stay finite.
    character(len=*), parameter :: REAL_HINT = '(decimal numbers below 1e100 in magnitude)'
    character(len=*), parameter :: FORMAT_HINT = 'write ASCII with gmsh -format msh41 ' &
                                                 //'(or -format msh22)'

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
            call check_block_fits(f, block(4), raw%n_nodes, n, 'node', stat)
            if (.not. stat%ok()) return
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
        call check_blocks_hold(f, raw%n_nodes, n, 'node', stat)
        if (stat%ok()) call expect_end(f, '$EndNodes', stat)
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
            call check_block_fits(f, block(4), n_done, header(2), 'element', stat)
            if (.not. stat%ok()) return
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
        call check_blocks_hold(f, n_done, header(2), 'element', stat)
        if (stat%ok()) call expect_end(f, '$EndElements', stat)
    end subroutine parse_elements_4

    !> MSH 4.1: a block of `block_size` nodes or elements (`noun`) after `done` of them must
    !> fit in the `announced` of the section header ($Nodes, $Elements).
    subroutine check_block_fits(f, block_size, done, announced, noun, stat)
        type(text_file_t), intent(in) :: f
        integer, intent(in) :: block_size, done, announced
        character(len=*), intent(in) :: noun   !! 'node' or 'element'
        type(status_t), intent(inout) :: stat
        ! Compared so, not as done + block_size > announced, which can overflow.
        if (block_size > announced - done) call fail_here(f, stat, 'more '//noun//'s than the ' &
            //to_string(announced)//' of the '//section_of(noun)//' header')
    end subroutine check_block_fits

    !> MSH 4.1: the blocks of a section hold the `announced` nodes or elements (`noun`).
    subroutine check_blocks_hold(f, done, announced, noun, stat)
        type(text_file_t), intent(in) :: f
        integer, intent(in) :: done, announced
        character(len=*), intent(in) :: noun   !! 'node' or 'element'
        type(status_t), intent(inout) :: stat
        if (done /= announced) call fail_here(f, stat, 'the '//noun//' blocks hold '// &
            to_string(done)//' '//noun//'s, the '//section_of(noun)//' header announced '// &
            to_string(announced))
    end subroutine check_blocks_hold

    !> '$Nodes' or '$Elements' for 'node' or 'element'.
    pure function section_of(noun) result(section)
        character(len=*), intent(in) :: noun
        character(len=:), allocatable :: section
        section = trim(merge('$Nodes   ', '$Elements', noun == 'node'))
    end function section_of

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

    subroutine allocate_nodes(f, raw, n, stat)
        type(text_file_t), intent(in) :: f
        type(raw_mesh_t), intent(inout) :: raw
        integer, intent(in) :: n
        type(status_t), intent(inout) :: stat
        integer :: alloc_status
        allocate (raw%node_tag(n), raw%node_xyz(3, n), stat=alloc_status)
        call check_allocated(f, alloc_status, n, 'node', stat)
    end subroutine allocate_nodes

    !> An allocation for the `n` nodes or elements (`noun`) announced at the current line.
    subroutine check_allocated(f, alloc_status, n, noun, stat)
        type(text_file_t), intent(in) :: f
        integer, intent(in) :: alloc_status, n
        character(len=*), intent(in) :: noun
        type(status_t), intent(inout) :: stat
        if (alloc_status /= 0) call fail_here(f, stat, 'out of memory for the '// &
                                              to_string(n)//' '//noun//'s announced here')
    end subroutine check_allocated

    subroutine allocate_elements(f, raw, n, stat)
        type(text_file_t), intent(in) :: f
        type(raw_mesh_t), intent(inout) :: raw
        integer, intent(in) :: n
        type(status_t), intent(inout) :: stat
        integer :: alloc_status
        allocate (raw%cell_type(n), raw%cell_nodes(MAX_CELL_NODES, n), raw%cell_entity(n), &
                  raw%cell_line(n), raw%edge_type(n), raw%edge_nodes(MAX_LINE_NODES, n), &
                  raw%edge_group(n), raw%edge_line(n), stat=alloc_status)
        call check_allocated(f, alloc_status, n, 'element', stat)
        if (.not. stat%ok()) return
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

    !> The nceig element (ELEMENT_*) of a Gmsh cell type; 0 for a line or point.
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

    !> Polynomial order of a Gmsh element type.
    pure integer function order_of(type)
        integer, intent(in) :: type
        select case (type)
        case (GMSH_LINE3, GMSH_TRIANGLE6, GMSH_QUAD9); order_of = 2
        case (GMSH_LINE4, GMSH_TRIANGLE10); order_of = 3
        case (GMSH_LINE5, GMSH_TRIANGLE15); order_of = 4
        case default; order_of = 1
        end select
    end function order_of
end module msh_parser
