! SPDX-License-Identifier: MIT
!> The MSH sections as written by hand: an MSH 4.1 and an MSH 2.2 fragment with every
!> section the parser reads ($MeshFormat, $PhysicalNames, $Entities, $Nodes, $Elements) and
!> one it skips, parsed into exactly what they say (tags, coordinates, types, groups, the
!> line of every entry); then every error path of the parser, each a one-line message
!> naming the file and the line at fault. Not reachable from a file, so not here: the
!> out-of-memory branches (a count larger than the file's lines fails before allocating)
!> and a truncation inside a section whose count check_announced has bounded.
program test_msh_parser
    use kinds, only: wp
    use status, only: status_t, STATUS_MESH
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, element_degree
    use strings, only: to_string
    use msh_text, only: text_file_t
    use msh_parser, only: raw_mesh_t, parse_sections, gmsh_type_name, element_of_type, &
                          order_of
    use testing, only: test_suite_t
    implicit none

    character(len=*), parameter :: PATH = 'fragment.msh'
    integer, parameter :: W = 72   !! longest line of a fragment
    character(len=W), parameter :: HEAD4(3) = [character(len=W) :: '$MeshFormat', &
                                                '4.1 0 8', '$EndMeshFormat']
    character(len=W), parameter :: HEAD2(3) = [character(len=W) :: '$MeshFormat', &
                                                '2.2 0 8', '$EndMeshFormat']
    !> a valid MSH 4.1 $Nodes section of one node (lines 4 to 8 after HEAD4)
    character(len=W), parameter :: NODES4(5) = [character(len=W) :: '$Nodes', '1 1 1 1', &
                                                 '0 1 0 1', '1', '0 0 0']
    type(test_suite_t) :: t

    t%name = 'test_msh_parser'
    call check_msh41()
    call check_msh22()
    call check_types()
    call check_format_errors()
    call check_section_errors()
    call check_name_errors()
    call check_entity_errors()
    call check_node_errors()
    call check_element_errors()
    call t%report()

contains

    !> The lines, trimmed, each ended by a line feed.
    function joined_lines(lines) result(text)
        character(len=*), intent(in) :: lines(:)
        character(len=:), allocatable :: text
        integer :: i
        text = ''
        do i = 1, size(lines)
            text = text//trim(lines(i))//new_line('a')
        end do
    end function joined_lines

    subroutine parse(lines, raw, stat)
        character(len=*), intent(in) :: lines(:)
        type(raw_mesh_t), intent(out) :: raw
        type(status_t), intent(out) :: stat
        type(text_file_t) :: f
        f%path = PATH
        f%text = joined_lines(lines)
        call parse_sections(f, raw, stat)
    end subroutine parse

    !> The file fails at `line` with a message holding `words`, on one printable line
    !> 'fragment.msh:line: ...'.
    subroutine expect_failure(label, lines, line, words)
        character(len=*), intent(in) :: label
        character(len=*), intent(in) :: lines(:)
        integer, intent(in) :: line
        character(len=*), intent(in) :: words
        type(raw_mesh_t) :: raw
        type(status_t) :: stat
        character(len=:), allocatable :: prefix
        logical :: printable
        integer :: i
        call parse(lines, raw, stat)
        prefix = PATH//':'//to_string(line)//': '
        printable = .false.
        if (allocated(stat%message)) then
            printable = .true.
            do i = 1, len(stat%message)
                printable = printable .and. iachar(stat%message(i:i)) >= 32 .and. &
                            iachar(stat%message(i:i)) < 127
            end do
        end if
        call t%check(label//': '//PATH//':'//to_string(line)//': ...'//words//'...', &
                     stat%code == STATUS_MESH .and. printable .and. &
                     index(stat%message, prefix) == 1 .and. index(stat%message, words) > 0)
        if (stat%code == STATUS_MESH .and. .not. (index(stat%message, prefix) == 1 .and. &
            index(stat%message, words) > 0)) print '(a)', '      got: '//stat%message
    end subroutine expect_failure

    !> Every section of MSH 4.1, a skipped one and blank lines between.
    subroutine check_msh41()
        type(raw_mesh_t) :: raw
        type(status_t) :: stat
        call parse([character(len=W) :: HEAD4, &          ! lines 1-3
                    '$PhysicalNames', '2', '1 7 "Bottom Side"', '2 9 "body"', &   ! 4-7
                    '$EndPhysicalNames', &                                       ! 8
                    '$Entities', '2 1 1 0', '1 0 0 0 0', '2 1 0 0 0', &           ! 9-12
                    '5 0 0 0 1 0 0 1 -7 2 1 -2', '3 0 0 0 1 1 0 1 9 1 5', &      ! 13-14
                    '$EndEntities', &                                            ! 15
                    '$Comments', 'anything here: $Nodes', '$EndComments', '', &  ! 16-19
                    '$Nodes', '2 4 1 4', '0 1 0 1', '1', '0 0 0', &              ! 20-24
                    '2 3 0 3', '2', '3', '4', '1 0 0', '1 1 0.5', '0 1 0', &     ! 25-31
                    '$EndNodes', &                                               ! 32
                    '$Elements', '2 3 1 3', '1 5 1 1', '1 1 2', &                ! 33-36
                    '2 3 2 2', '2 1 2 3', '3 1 3 4', '$EndElements'], raw, stat) ! 37-40
        call t%check('MSH 4.1: parsed, version 4', stat%ok() .and. raw%version == 4)
        call t%check('MSH 4.1 $PhysicalNames: dimension, tag, lowercased name, line', &
                     raw%n_names == 2 .and. all(raw%name_dim == [1, 2]) .and. &
                     all(raw%name_tag == [7, 9]) .and. all(raw%name_line == [6, 7]) .and. &
                     raw%name_text(1) == 'bottom side' .and. raw%name_text(2) == 'body')
        call t%check('MSH 4.1 $Entities: curve 5 in physical group 7 (sign dropped)', &
                     raw%n_pairs == 1 .and. all(raw%pair_curve == [5]) .and. &
                     all(raw%pair_physical == [7]))
        call t%check('MSH 4.1 $Nodes: two blocks, tags and coordinates', raw%n_nodes == 4 &
                     .and. all(raw%node_tag == [1, 2, 3, 4]) .and. &
                     all(abs(raw%node_xyz - reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
                     0.0_wp, 1.0_wp, 1.0_wp, 0.5_wp, 0.0_wp, 1.0_wp, 0.0_wp], [3, 4])) <= 0.0_wp))
        call t%check('MSH 4.1 $Elements: a line of curve 5 at line 36', raw%n_edges == 1 .and. &
                     raw%edge_type(1) == 1 .and. all(raw%edge_nodes(1:2, 1) == [1, 2]) .and. &
                     raw%edge_group(1) == 5 .and. raw%edge_line(1) == 36)
        call t%check('MSH 4.1 $Elements: two triangles of surface 3 at lines 38, 39', &
                     raw%n_cells == 2 .and. all(raw%cell_type(1:2) == 2) .and. &
                     all(raw%cell_nodes(1:3, 1) == [1, 2, 3]) .and. &
                     all(raw%cell_nodes(1:3, 2) == [1, 3, 4]) .and. &
                     all(raw%cell_entity(1:2) == 3) .and. all(raw%cell_line(1:2) == [38, 39]))
    end subroutine check_msh41

    !> MSH 2.2: $Entities skipped, lines in their physical group, cells in their entity,
    !> points dropped, any number of tags.
    subroutine check_msh22()
        type(raw_mesh_t) :: raw
        type(status_t) :: stat
        call parse([character(len=W) :: HEAD2, &
                    '$PhysicalNames', '1', '1 7 "contact"', '$EndPhysicalNames', &    ! 4-7
                    '$Entities', 'not read in 2.2', '$EndEntities', &                 ! 8-10
                    '$Nodes', '4', '1 0 0 0', '2 1 0 0', '3 1 1 0', '4 0 1 0', &      ! 11-16
                    '$EndNodes', &                                                   ! 17
                    '$Elements', '4', '1 1 2 7 5 1 2', '2 2 3 9 3 0 1 2 3', &         ! 18-21
                    '3 2 0 1 3 4', '4 15 2 0 0 4', '$EndElements'], raw, stat)        ! 22-24
        call t%check('MSH 2.2: parsed, version 2, $Entities skipped', stat%ok() .and. &
                     raw%version == 2 .and. raw%n_pairs == 0 .and. raw%n_names == 1)
        call t%check('MSH 2.2 $Nodes: tags and coordinates', raw%n_nodes == 4 .and. &
                     all(raw%node_tag == [1, 2, 3, 4]) .and. &
                     all(abs(raw%node_xyz(:, 3) - [1.0_wp, 1.0_wp, 0.0_wp]) <= 0.0_wp))
        call t%check('MSH 2.2 $Elements: the line in physical group 7, line 20', &
                     raw%n_edges == 1 .and. raw%edge_group(1) == 7 .and. raw%edge_line(1) == 20 &
                     .and. all(raw%edge_nodes(1:2, 1) == [1, 2]))
        call t%check('MSH 2.2 $Elements: triangles in entity 3 (3 tags) and 0 (no tags), '// &
                     'the point dropped', raw%n_cells == 2 .and. &
                     all(raw%cell_entity(1:2) == [3, 0]) .and. &
                     all(raw%cell_nodes(1:3, 1) == [1, 2, 3]) .and. &
                     all(raw%cell_nodes(1:3, 2) == [1, 3, 4]) .and. &
                     all(raw%cell_line(1:2) == [21, 22]))
    end subroutine check_msh22

    !> The supported Gmsh types: their element, order and name.
    subroutine check_types()
        integer, parameter :: CELLS(6) = [2, 3, 9, 10, 21, 23]
        integer, parameter :: ELEMENTS(6) = [ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, &
                                             ELEMENT_P3, ELEMENT_P4]
        integer, parameter :: LINES(4) = [1, 8, 26, 27]
        integer :: i
        logical :: orders
        orders = .true.
        do i = 1, size(CELLS)
            orders = orders .and. element_of_type(CELLS(i)) == ELEMENTS(i) .and. &
                     order_of(CELLS(i)) == element_degree(ELEMENTS(i))
        end do
        call t%check('element_of_type and order_of: the six cell types', orders)
        call t%check('order_of: lines of 2 to 5 nodes are of order 1 to 4', &
                     all([(order_of(LINES(i)), i=1, 4)] == [1, 2, 3, 4]) .and. &
                     all([(element_of_type(LINES(i)), i=1, 4)] == 0))
        call t%check('gmsh_type_name: supported types by node count', &
                     gmsh_type_name(2) == '3-node triangle' .and. &
                     gmsh_type_name(10) == '9-node quadrangle' .and. &
                     gmsh_type_name(27) == '5-node line' .and. gmsh_type_name(15) == 'point')
        call t%check('gmsh_type_name: a 3D element and an incomplete one say why', &
                     index(gmsh_type_name(4), '3D mesh') > 0 .and. &
                     index(gmsh_type_name(16), 'SecondOrderIncomplete') > 0 .and. &
                     gmsh_type_name(99) == 'not a 2D element of order 1 to 4')
    end subroutine check_types

    subroutine check_format_errors()
        call expect_failure('empty file', [character(len=W) ::], 0, &
                            'unexpected end of file (truncated?); expected $MeshFormat')
        call expect_failure('not a mesh', [character(len=W) :: '', 'hello'], 2, &
                            'not a Gmsh mesh file: expected $MeshFormat, found ''hello''')
        call expect_failure('no version line', [character(len=W) :: '$MeshFormat'], 1, &
                            'unexpected end of file (truncated?); expected the version line')
        call expect_failure('a bad version line', [character(len=W) :: '$MeshFormat', &
                            '4.1 , 8'], 2, 'expected ''version file-type data-size''')
        call expect_failure('binary', [character(len=W) :: '$MeshFormat', '4.1 1 8'], 2, &
                            'binary MSH files are not supported')
        call expect_failure('version 3', [character(len=W) :: '$MeshFormat', '3.0 0 8'], 2, &
                            'MSH version 3.0 is not supported (expected 4.1 or 2.2)')
        call expect_failure('no $EndMeshFormat', [character(len=W) :: '$MeshFormat', &
                            '4.1 0 8', '$Nodes'], 3, 'expected $EndMeshFormat, found ''$Nodes''')
    end subroutine check_format_errors

    subroutine check_section_errors()
        call expect_failure('text between sections', [character(len=W) :: HEAD4, 'junk'], 4, &
                            'unexpected text ''junk''; expected a section header')
        call expect_failure('an end marker without its section', &
                            [character(len=W) :: HEAD4, '$EndNodes'], 4, &
                            'unexpected text ''$EndNodes''')
        call expect_failure('partitioned', [character(len=W) :: HEAD4, &
                            '$PartitionedEntities'], 4, 'partitioned meshes are not supported')
        call expect_failure('an unknown section without its end', &
                            [character(len=W) :: HEAD4, '$Comments', 'text'], 5, &
                            'expected $EndComments')
        call expect_failure('no $Nodes', HEAD4, 3, 'no $Nodes section')
        call expect_failure('no $Elements', [character(len=W) :: HEAD4, '$Nodes', '0 0 0 0', &
                            '$EndNodes'], 6, 'no $Elements section')
        call expect_failure('a second $Nodes', [character(len=W) :: HEAD4, '$Nodes', &
                            '0 0 0 0', '$EndNodes', '$Nodes'], 7, &
                            'a second $Nodes section (the first began at line 4)')
    end subroutine check_section_errors

    subroutine check_name_errors()
        call expect_failure('$PhysicalNames: no count', [character(len=W) :: HEAD4, &
                            '$PhysicalNames', 'x'], 5, 'expected the number of physical names')
        call expect_failure('$PhysicalNames: more than the file holds', &
                            [character(len=W) :: HEAD4, '$PhysicalNames', '5', '1 2 "a"'], 5, &
                            'the header announces 5 names (a line each), but the file ends 1')
        call expect_failure('$PhysicalNames: no tag', [character(len=W) :: HEAD4, &
                            '$PhysicalNames', '1', '1 x "a"', '$EndPhysicalNames'], 6, &
                            'expected ''dimension tag "name"''')
        call expect_failure('$PhysicalNames: no quotes', [character(len=W) :: HEAD4, &
                            '$PhysicalNames', '1', '1 2 a', '$EndPhysicalNames'], 6, &
                            'expected the name in double quotes')
        call expect_failure('$PhysicalNames: a control character', [character(len=W) :: HEAD4, &
                            '$PhysicalNames', '1', '1 2 "a'//achar(27)//'b"', &
                            '$EndPhysicalNames'], 6, 'control characters in the physical name')
        call expect_failure('$PhysicalNames: a name too long', [character(len=W) :: HEAD4, &
                            '$PhysicalNames', '1', '1 2 "'//repeat('n', 65)//'"', &
                            '$EndPhysicalNames'], 6, 'physical name longer than 64 characters')
        call expect_failure('$PhysicalNames: more names than announced', &
                            [character(len=W) :: HEAD4, '$PhysicalNames', '1', '1 2 "a"', &
                            '1 3 "b"', '$EndPhysicalNames'], 7, &
                            'expected $EndPhysicalNames, found ''1 3 "b"'' (more entries')
    end subroutine check_name_errors

    subroutine check_entity_errors()
        call expect_failure('$Entities: a negative count', [character(len=W) :: HEAD4, &
                            '$Entities', '1 1 -1 0'], 5, 'found negative counts')
        call expect_failure('$Entities: more of one kind than lines', &
                            [character(len=W) :: HEAD4, '$Entities', '0 3 0 0', 'c'], 5, &
                            'announces 3 entities of one kind')
        call expect_failure('$Entities: a bad curve', [character(len=W) :: HEAD4, '$Entities', &
                            '0 1 0 0', '5 0 0 0 1 0 0 x', '$EndEntities'], 6, &
                            'expected ''curveTag minX minY minZ maxX maxY maxZ numPhysicalTags')
        call expect_failure('$Entities: a surface line missing', [character(len=W) :: HEAD4, &
                            '$Entities', '1 0 1 0', 'point'], 6, &
                            'unexpected end of file (truncated?); expected a surface entity')
        call expect_failure('$Entities: a curve line missing', [character(len=W) :: HEAD4, &
                            '$Entities', '1 1 0 0', 'point'], 6, &
                            'unexpected end of file (truncated?); expected a curve entity')
        call expect_failure('$Entities: a volume line missing', [character(len=W) :: HEAD4, &
                            '$Entities', '1 0 0 1', 'point'], 6, &
                            'unexpected end of file (truncated?); expected a volume entity')
    end subroutine check_entity_errors

    subroutine check_node_errors()
        call expect_failure('$Nodes 4.1: a short header', [character(len=W) :: HEAD4, &
                            '$Nodes', '1 2 1'], 5, 'expected $Nodes header (numEntityBlocks')
        call expect_failure('$Nodes 4.1: more nodes than lines', [character(len=W) :: HEAD4, &
                            '$Nodes', '1 5 1 5', '0 1 0 5', '1'], 5, &
                            'announces 5 nodes (a tag line and a coordinate line each)')
        call expect_failure('$Nodes 4.1: a bad block header', [character(len=W) :: HEAD4, &
                            '$Nodes', '1 1 1 1', '0 1 x 1', '1', '0 0 0', '$EndNodes'], 6, &
                            'expected node block 1 of 1')
        call expect_failure('$Nodes 4.1: a block larger than the section', &
                            [character(len=W) :: HEAD4, '$Nodes', '1 1 1 1', '0 1 0 2', '1', &
                            '2', '0 0 0', '0 0 0', '$EndNodes'], 6, &
                            'more nodes than the 1 of the $Nodes header')
        call expect_failure('$Nodes 4.1: a bad node tag', [character(len=W) :: HEAD4, &
                            '$Nodes', '1 1 1 1', '0 1 0 1', 'x', '0 0 0', '$EndNodes'], 7, &
                            'expected a node tag, found ''x''')
        call expect_failure('$Nodes 4.1: two coordinates', [character(len=W) :: HEAD4, &
                            '$Nodes', '1 1 1 1', '0 1 0 1', '1', '0 0', '$EndNodes'], 8, &
                            'expected coordinates x y z (decimal numbers below 1e100')
        call expect_failure('$Nodes 4.1: an overflowing coordinate', &
                            [character(len=W) :: HEAD4, '$Nodes', '1 1 1 1', '0 1 0 1', '1', &
                            '0 1e999 0', '$EndNodes'], 8, 'expected coordinates x y z')
        call expect_failure('$Nodes 4.1: blocks holding fewer nodes than announced', &
                            [character(len=W) :: HEAD4, '$Nodes', '1 2 1 2', '0 1 0 1', '1', &
                            '0 0 0', '$EndNodes'], 8, &
                            'the node blocks hold 1 nodes, the $Nodes header announced 2')
        call expect_failure('$Nodes 4.1: the coordinates cut off', [character(len=W) :: HEAD4, &
                            '$Nodes', '2 1 1 1', '0 1 0 1', '1'], 7, &
                            'unexpected end of file (truncated?); expected coordinates x y z')
        call expect_failure('$Nodes 4.1: more nodes than announced', &
                            [character(len=W) :: HEAD4, NODES4, '0 0 0', &
                            '$EndNodes'], 9, 'expected $EndNodes')
        call expect_failure('$Nodes 2.2: a negative count', [character(len=W) :: HEAD2, &
                            '$Nodes', '-3'], 5, 'expected the number of nodes, found ''-3''')
        call expect_failure('$Nodes 2.2: a bad node line', [character(len=W) :: HEAD2, &
                            '$Nodes', '1', '1 0 y 0', '$EndNodes'], 6, &
                            'expected ''tag x y z'' (decimal numbers')
    end subroutine check_node_errors

    subroutine check_element_errors()
        character(len=W) :: base4(9), base2(7)
        base4 = [character(len=W) :: HEAD4, NODES4, '$EndNodes']
        call expect_failure('$Elements 4.1: a short header', [character(len=W) :: base4, &
                            '$Elements', '1 1'], 11, 'expected $Elements header')
        call expect_failure('$Elements 4.1: a 3D element', [character(len=W) :: base4, &
                            '$Elements', '1 1 1 1', '3 1 4 1', '1 1 1 1 1', '$EndElements'], &
                            12, 'unsupported element type 4 (4-node tetrahedron: a 3D mesh)')
        call expect_failure('$Elements 4.1: a block larger than the section', &
                            [character(len=W) :: base4, '$Elements', '1 1 1 1', '2 1 2 2', &
                            '1 1 1 1', '2 1 1 1', '$EndElements'], 12, &
                            'more elements than the 1 of the $Elements header')
        call expect_failure('$Elements 4.1: a node tag missing', [character(len=W) :: base4, &
                            '$Elements', '1 1 1 1', '2 1 2 1', '1 1 1', '$EndElements'], 13, &
                            'expected an element tag and 3 node tags (3-node triangle)')
        call expect_failure('$Elements 4.1: blocks holding fewer than announced', &
                            [character(len=W) :: base4, '$Elements', '1 2 1 2', '2 1 2 1', &
                            '1 1 1 1', '$EndElements'], 13, &
                            'the element blocks hold 1 elements, the $Elements header announced 2')
        base2 = [character(len=W) :: HEAD2, '$Nodes', '1', '1 0 0 0', '$EndNodes']
        call expect_failure('$Elements 2.2: a short line', [character(len=W) :: base2, &
                            '$Elements', '1', '1 2', '$EndElements'], 10, &
                            'expected ''tag type numTags tags nodes''')
        call expect_failure('$Elements 2.2: a 3D element', [character(len=W) :: base2, &
                            '$Elements', '1', '1 11 0 1 1 1 1 1 1 1 1 1 1', '$EndElements'], 10, &
                            'unsupported element type 11 (10-node tetrahedron')
        call expect_failure('$Elements 2.2: a negative tag count', [character(len=W) :: base2, &
                            '$Elements', '1', '1 2 -1 1 1 1', '$EndElements'], 10, &
                            'expected 0 tags and 3 node tags (3-node triangle)')
        call expect_failure('$Elements 2.2: tags but too few nodes', [character(len=W) :: base2, &
                            '$Elements', '1', '1 2 2 0 0 1 1', '$EndElements'], 10, &
                            'expected 2 tags and 3 node tags')
        call expect_failure('$Elements 2.2: more than announced', [character(len=W) :: base2, &
                            '$Elements', '1', '1 15 0 1', '2 15 0 1', '$EndElements'], 11, &
                            'expected $EndElements, found ''2 15 0 1''')
    end subroutine check_element_errors
end program test_msh_parser
