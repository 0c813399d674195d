! SPDX-License-Identifier: MIT
!> The Gmsh reader: structured grids written here as MSH 4.1 and MSH 2.2 read back to the
!> same mesh and give the eigenvalues of the rectangle generator (P1, Q1, P2, Q2, P3, P4);
!> clockwise files are reoriented; the single element of model.md section 8 read from its .msh
!> matches the closed form; each bad file fails with STATUS_MESH naming the file and the line.
program test_mesh_gmsh
    use kinds, only: wp
    use fixtures, only: problem_of, eigen_of
    use status, only: status_t, STATUS_MESH, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, MAX_ELEMENT, element_name
    use mesh_structured, only: structured_rectangle
    use mesh_gmsh, only: read_gmsh
    use mesh_renumber, only: node_order, node_bandwidth, renumber_nodes, RENUMBER_NONE, &
                             RENUMBER_RCM, RENUMBER_METIS
    use run_config, only: config_t
    use input_config, only: read_input
    use problem, only: problem_t, build_problem
    use eigen_solve, only: eigen_result_t, solve_eigen
    use elasticity, only: lame_coefficients
    use timer, only: timings_t
    use strings, only: to_string
    use testing, only: test_suite_t
    use msh_writer, only: write_msh41, write_msh22
    implicit none

    type(test_suite_t) :: t
    integer :: element

    t%name = 'test_mesh_gmsh'
    do element = ELEMENT_P1, MAX_ELEMENT
        call check_structured(element)
    end do
    call check_single_element()
    call check_renumbering()
    call check_errors()
    call t%report()

contains

    !> A 4 x 3 grid of a 1.5 x 1 rectangle written as MSH 4.1, MSH 2.2 and clockwise MSH 4.1:
    !> the same mesh from all three, and the rectangle generator's eigenvalues.
    subroutine check_structured(element)
        integer, intent(in) :: element
        type(mesh_t) :: grid, from41, from22, clockwise
        type(status_t) :: stat
        type(eigen_result_t) :: reference, result41, result22, result_cw
        character(len=:), allocatable :: label, path41, path22, path_cw
        integer :: n_reoriented

        label = ' ('//element_name(element)//')'
        call structured_rectangle(1.5_wp, 1.0_wp, 4, 3, element, 'right', grid, stat)
        path41 = 'grid_'//element_name(element)//'_41.msh'
        path22 = 'grid_'//element_name(element)//'_22.msh'
        path_cw = 'grid_'//element_name(element)//'_cw.msh'
        call write_msh41(path41, grid, .false.)
        call write_msh22(path22, grid)
        call write_msh41(path_cw, grid, .true.)

        call read_gmsh(path41, from41, stat)
        call t%check('MSH 4.1 grid reads'//label, stat%ok())
        if (.not. stat%ok()) then
            print '(a)', stat%message
            return
        end if
        call read_gmsh(path22, from22, stat)
        call t%check('MSH 2.2 grid reads'//label, stat%ok())
        if (.not. stat%ok()) return
        call read_gmsh(path_cw, clockwise, stat, n_reoriented)
        call t%check('clockwise MSH 4.1 grid reads'//label, stat%ok())
        if (.not. stat%ok()) return
        call t%check('clockwise grid: every cell reoriented'//label, &
                     n_reoriented == grid%n_cells())

        call t%check('element type from the cell type'//label, from41%element == element)
        call t%check('counts as the generator'//label, from41%n_nodes() == grid%n_nodes() &
                     .and. from41%n_cells() == grid%n_cells() .and. &
                     size(from41%edges, 2) == size(grid%edges, 2))
        call t%check('parts named by $PhysicalNames'//label, &
                     from41%part_index('bottom') > 0 .and. from41%part_index('top') > 0 .and. &
                     from41%part_index('left') > 0 .and. from41%part_index('right') > 0 .and. &
                     from41%part_index('body') == 0)
        ! Both formats carry the same numbers (coordinates written with 17 digits), and the
        ! reader is deterministic: the meshes must be identical, not merely close.
        call t%check('MSH 2.2 and 4.1 give identical meshes'//label, same_mesh(from41, from22))
        call t%check('clockwise file: same cells once reoriented'//label, &
                     same_mesh(from41, clockwise))
        call t%check('cells keep their file lines'//label, allocated(from41%cell_line) .and. &
                     from41%file == path41)

        call solve(build_config('rectangle', '', element), reference)
        call solve(build_config('gmsh', path41, element), result41)
        call solve(build_config('gmsh', path22, element), result22)
        call solve(build_config('gmsh', path_cw, element), result_cw)
        if (.not. (allocated(reference%spec%mu) .and. allocated(result41%spec%mu))) return
        ! Same element matrices added in another order and factored with another node
        ! numbering: the eigenvalues agree to round-off, ~ cond(K) eps ~ 1e-13 on this grid;
        ! 1e-10 leaves room and still catches any modelling difference (1e-3 or more).
        call t%check('Gmsh grid gives the generator''s eigenvalues'//label, &
                     same_spectrum(reference%spec%mu, result41%spec%mu, 1.0e-10_wp))
        call t%check('MSH 2.2 and 4.1 give identical eigenvalues'//label, &
                     same_spectrum(result41%spec%mu, result22%spec%mu, 0.0_wp))
        call t%check('clockwise file gives the same eigenvalues'//label, &
                     same_spectrum(result41%spec%mu, result_cw%spec%mu, 0.0_wp))
    end subroutine check_structured

    !> model.md section 8 from input/single_element.nml and its .msh (l = 2): the single
    !> eigenvalue is mu = -6 G (L + 2G) / ((L (lambda + 1) + G (lambda + 3)) l).
    subroutine check_single_element()
        type(config_t) :: config
        type(problem_t) :: prob
        type(eigen_result_t) :: res
        type(timings_t) :: timings
        type(status_t) :: stat
        character(len=4096) :: source_dir
        real(wp), parameter :: LAMBDAS(4) = [-5.0_wp, -2.5_wp, 1.0_wp, 5.0_wp]
        real(wp) :: lame_l, shear_g, l, lambda, expected
        integer :: i

        call get_environment_variable('NCEIG_SOURCE_DIR', source_dir)
        call read_input(trim(source_dir)//'/input/single_element.nml', config, stat)
        call t%check('single_element.nml reads', stat%ok())
        if (.not. stat%ok()) return
        call problem_of(config, prob, stat)
        call t%check('single element: problem builds from the .msh', stat%ok())
        if (.not. stat%ok()) return
        call t%check('single element: 2 free dofs, p = 1', prob%dofs%n_free == 2 .and. &
                     prob%contact%p() == 1)
        call t%check('single element: n = (0, -1) on [A, B]', &
                     maxval(abs(prob%contact%normal - [0.0_wp, -1.0_wp])) <= 0.0_wp)
        l = maxval(prob%mesh%coords(1, :))
        call lame_coefficients(config%material%young, config%material%poisson, lame_l, shear_g)
        do i = 1, 4
            lambda = LAMBDAS(i)
            expected = -6.0_wp*shear_g*(lame_l + 2.0_wp*shear_g)/ &
                       ((lame_l*(lambda + 1.0_wp) + shear_g*(lambda + 3.0_wp))*l)
            call eigen_of(config, prob, lambda, res, timings, stat)
            if (.not. stat%ok()) then
                call t%check('single element: solve at lambda = '//to_string(lambda), .false.)
                cycle
            end if
            ! A 2 x 2 system and a 1 x 1 eigenproblem: a few dozen roundings, so 1e-13. The
            ! solver's mu is in the problem's scaled units: the input's by a power of two.
            call t%check('single element: one eigenvalue, real', res%spec%n() == 1 .and. &
                         abs(aimag(res%spec%mu(1))) <= 0.0_wp)
            call t%check_close('single element: closed form mu at lambda = '// &
                               to_string(lambda), prob%units%mu_to_input(real(res%spec%mu(1), &
                               wp)), expected, 1.0e-13_wp)
        end do
    end subroutine check_single_element

    !> RCM and METIS give permutations; RCM undoes a scrambled numbering of a grid.
    subroutine check_renumbering()
        type(mesh_t) :: grid, scrambled
        type(status_t) :: stat
        integer, allocatable :: new_of_old(:), seen(:)
        integer :: method, i, n, row_bandwidth
        logical :: ok

        call structured_rectangle(1.0_wp, 1.0_wp, 12, 12, ELEMENT_P1, 'right', grid, stat)
        row_bandwidth = node_bandwidth(grid)   ! row by row: nx + 2 = 14
        ! Scramble: new number = 1 + mod(37 (old - 1), n), a permutation as gcd(37, 169) = 1.
        n = grid%n_nodes()
        scrambled = grid
        new_of_old = [(1 + modulo(37*(i - 1), n), i=1, n)]
        scrambled%coords(:, new_of_old) = grid%coords
        scrambled%cells = reshape(new_of_old(reshape(grid%cells, [size(grid%cells)])), &
                                  shape(grid%cells))
        scrambled%edges = reshape(new_of_old(reshape(grid%edges, [size(grid%edges)])), &
                                  shape(grid%edges))
        call t%check('scrambled grid has a large bandwidth', &
                     node_bandwidth(scrambled) > 5*row_bandwidth)
        do method = RENUMBER_NONE, RENUMBER_METIS
            call node_order(scrambled, method, new_of_old, stat)
            allocate (seen(n), source=0)
            if (stat%ok()) seen(new_of_old) = seen(new_of_old) + 1
            call t%check('renumbering '//to_string(method)//' is a permutation', &
                         stat%ok() .and. all(seen == 1))
            deallocate (seen)
        end do
        call renumber_nodes(scrambled, RENUMBER_RCM, stat)
        ! Level sets of a breadth-first search on this grid are anti-diagonals of at most
        ! 13 nodes; an RCM bandwidth is below two level widths, so below 2 (nx + 2).
        call t%check('RCM bandwidth <= 2 x that of the row-by-row grid', stat%ok() .and. &
                     node_bandwidth(scrambled) <= 2*row_bandwidth)
        ! Renumbering moves nodes, not geometry: every cell keeps its corner coordinates.
        ok = .true.
        do i = 1, grid%n_cells()
            ok = ok .and. maxval(abs(scrambled%coords(:, scrambled%cells(:, i)) - &
                                     grid%coords(:, grid%cells(:, i)))) <= 0.0_wp
        end do
        call t%check('RCM keeps every cell''s coordinates', ok)
    end subroutine check_renumbering

    !> Each bad file: STATUS_MESH, the file name and line number, and what is wrong.
    subroutine check_errors()
        character(len=48) :: base(23)
        character(len=48), allocatable :: lines(:)
        type(mesh_t) :: m
        type(status_t) :: stat
        type(config_t) :: config
        type(problem_t) :: prob

        base = [character(len=48) :: '$MeshFormat', '2.2 0 8', '$EndMeshFormat', &
                '$PhysicalNames', '3', '1 1 "Bottom"', '1 2 "top"', '2 3 "body"', &
                '$EndPhysicalNames', '$Nodes', '4', '1 0 0 0', '2 1 0 0', '3 1 1 0', &
                '4 0 1 0', '$EndNodes', '$Elements', '4', '1 1 2 1 1 1 2', '2 1 2 2 3 3 4', &
                '3 2 2 3 1 1 2 3', '4 2 2 3 1 1 3 4', '$EndElements']
        call write_lines('good.msh', base)
        call read_gmsh('good.msh', m, stat)
        call t%check('the base file of the error cases reads', stat%ok())
        call t%check('physical names are lowercased', m%part_index('bottom') > 0)

        lines = base(:14)
        call expect_error('truncated file', lines, 11, 'the file ends 3 lines later (truncated?)')
        lines = base(:22)
        call expect_error('no end marker', lines, 22, &
                          'unexpected end of file (truncated?); expected $EndElements')
        lines = base
        lines(22) = '4 2 2 3 1 1 3 7'
        call expect_error('undefined node', lines, 22, 'node 7, which $Nodes does not define')
        lines = base
        lines(22) = '4 2 2 3 1 1 4 3'
        call expect_error('clockwise cell among anticlockwise ones', lines, 22, 'inverted cell')
        lines = base
        lines(15) = '4 0.5 0.5 0'   ! on the diagonal [1, 3] of the cell of line 22
        call expect_error('degenerate cell', lines, 22, 'degenerate: zero area')
        lines = base
        lines(2) = '2.2 1 8'
        call expect_error('binary file', lines, 2, 'binary MSH files are not supported')
        lines = base
        lines(2) = '4.0 0 8'
        call expect_error('MSH 4.0', lines, 2, 'MSH version 4.0 is not supported')
        lines = base
        lines(22) = '4 4 2 3 1 1 2 3 4'
        call expect_error('tetrahedron', lines, 22, 'unsupported element type 4')
        lines = base
        lines(22) = '4 9 2 3 1 1 2 3 4 1 2'
        call expect_error('6-node triangle after 3-node ones', lines, 22, 'mixed element orders')
        lines = base
        lines(20) = '2 8 2 2 3 3 4 1'
        call expect_error('3-node line with 3-node triangles', lines, 20, 'mixed element orders')
        lines = base
        lines(22) = '4 3 2 3 1 1 2 3 4'
        call expect_error('quadrangle after triangles', lines, 22, 'mixed cell shapes')
        lines = base
        lines(18) = '5'
        call expect_error('fewer elements than announced', lines, 23, 'found ''$EndElements''')
        lines = [base(:9), base(17:)]
        call expect_error('no $Nodes section', lines, 16, 'no $Nodes section')
        call check_fuzz_regressions(base)

        ! Errors found while building the problem from a readable file.
        config%input_file = 'errors.nml'
        config%mesh%source = 'gmsh'
        config%mesh%file = 'good.msh'
        config%mesh%dirichlet = 'top'
        config%mesh%neumann = ''
        config%mesh%contact = 'side'
        call problem_of(config, prob, stat)
        call t%check('missing physical group: STATUS_BAD_INPUT', stat%code == STATUS_BAD_INPUT)
        if (allocated(stat%message)) call t%check('missing physical group: message names ' &
            //'the mesh file, the group and those it has', &
            index(stat%message, 'good.msh has no 1D physical group ''side''') > 0 .and. &
            index(stat%message, '(it has: bottom, top)') > 0)
        ! Group 'bottom' also holding the right side [2, 3] (line 20): not a straight segment.
        lines = base
        lines(20) = '2 1 2 1 1 2 3'
        call write_lines('bent.msh', lines)
        config%mesh%file = 'bent.msh'
        config%mesh%dirichlet = 'top'
        config%mesh%contact = 'bottom'
        call problem_of(config, prob, stat)
        call t%check('bent contact group: STATUS_MESH', stat%code == STATUS_MESH)
        if (allocated(stat%message)) call t%check('bent contact group: message names the ' &
            //'file, the line of the edge and the problem', &
            index(stat%message, 'bent.msh:20: contact boundary ''bottom'' is not one ' &
            //'straight segment') == 1)
    end subroutine check_errors

    !> The reader bugs test_fuzz_mesh_gmsh found, one file each (base: the MSH 2.2 file of
    !> check_errors). Before the fixes these crashed (Debug FPE trap, allocation of an
    !> allocated array, array bound, failed huge allocation), read unset or non-finite
    !> coordinates, or printed control characters.
    subroutine check_fuzz_regressions(base)
        character(len=48), intent(in) :: base(:)
        character(len=48), allocatable :: lines(:)
        character(len=48) :: base41(36)
        character(len=*), parameter :: XYZ = 'expected ''tag x y z'' (decimal numbers below 1e100'
        type(mesh_t) :: m
        type(status_t) :: stat
        integer :: i

        allocate (lines(0))   ! avoids a false -Wuninitialized at -O3 (see split_names)
        ! Coordinates: overflow (trapped in the list-directed read), NaN and Infinity, and
        ! list-directed syntax that left values unset (',' '/') or repeated them ('3*1').
        lines = base
        lines(13) = '2 1e999 0 0'
        call expect_error('coordinate 1e999', lines, 13, XYZ)
        lines(13) = '2 1e100 0 0'
        call expect_error('coordinate 1e100', lines, 13, XYZ)
        lines(13) = '2 NaN 0 0'
        call expect_error('coordinate NaN', lines, 13, XYZ)
        lines(13) = '2 1 -Infinity 0'
        call expect_error('coordinate -Infinity', lines, 13, XYZ)
        lines(13) = '2 1 /'
        call expect_error('coordinates ended by a slash', lines, 13, XYZ)
        lines(13) = '2 1 , 0'
        call expect_error('coordinate left empty by a comma', lines, 13, XYZ)
        lines(13) = '2 3*1'
        call expect_error('coordinates as a repeat count', lines, 13, XYZ)
        ! A fifth node, on no cell (so dropped), just inside the bound.
        lines = [character(len=48) :: base(:10), '5', base(12:15), '5 9.99e99 -9.99e99 0', &
                 base(16:)]
        call write_lines('large_coordinate.msh', lines)
        call read_gmsh('large_coordinate.msh', m, stat)
        call t%check('coordinate 9.99e99 (below the bound) reads', stat%ok())
        lines = base
        lines(13) = '2 1.0E0 .0 0.'
        call write_lines('coordinate_spellings.msh', lines)
        call read_gmsh('coordinate_spellings.msh', m, stat)
        call t%check('coordinates 1.0E0, .0 and 0. read', stat%ok())
        ! The version line read token by token (',' left the file type unset).
        lines = base
        lines(2) = '2.2 , 8'
        call expect_error('file type left empty', lines, 2, 'expected ''version file-type')
        ! A second section of one kind (allocated twice).
        lines = [base(:16), base(10:)]
        call expect_error('a second $Nodes section', lines, 17, &
                          'a second $Nodes section (the first began at line 10)')
        ! A count beyond what the file holds (a 72 GB allocation).
        lines = base
        lines(18) = '2000000000'
        call expect_error('huge element count', lines, 18, &
                          'the header announces 2000000000 elements')
        lines = base
        lines(11) = '2147483647'
        call expect_error('huge node count', lines, 11, 'the header announces 2147483647 nodes')
        lines = base
        lines(5) = '999999'
        call expect_error('huge name count', lines, 5, 'the header announces 999999 names')
        ! Control characters quoted from the file (an escape in a header, a carriage
        ! return in a name): the message stays one printable line.
        lines = base
        lines(17) = '$Ele'//achar(27)//'ments'
        call expect_error('escape character in a header', lines, 23, 'expected $End')
        call read_gmsh('bad_escapecharacterinaheader.msh', m, stat)
        if (allocated(stat%message)) call t%check('escape character in a header: message ' &
            //'printable', all([(iachar(stat%message(i:i)) >= 32, i=1, len(stat%message))]))
        lines = base
        lines(6) = '1 1 "Bot'//achar(13)//'tom"'
        call expect_error('carriage return in a name', lines, 6, 'control characters in ' &
                          //'the physical name "Bot?tom"; expected printable text')

        ! MSH 4.1: a block count whose sum with the elements before overflowed the check
        ! (array bound), and entity counts beyond the file.
        base41 = [character(len=48) :: '$MeshFormat', '4.1 0 8', '$EndMeshFormat', &
                  '$PhysicalNames', '2', '1 1 "bottom"', '1 2 "top"', '$EndPhysicalNames', &
                  '$Entities', '0 2 1 0', '1 0 0 0 1 0 0 1 1 0', '2 0 1 0 1 1 0 1 2 0', &
                  '1 0 0 0 1 1 0 0 0', '$EndEntities', '$Nodes', '1 4 1 4', '2 1 0 4', '1', &
                  '2', '3', '4', '0 0 0', '1 0 0', '1 1 0', '0 1 0', '$EndNodes', '$Elements', &
                  '3 4 1 4', '1 1 1 1', '1 1 2', '1 2 1 1', '2 3 4', '2 1 2 2', '3 1 2 3', &
                  '4 1 3 4', '$EndElements']
        call write_lines('good41.msh', base41)
        call read_gmsh('good41.msh', m, stat)
        call t%check('the MSH 4.1 base file of the regressions reads', stat%ok() .and. &
                     m%part_index('bottom') > 0 .and. m%part_index('top') > 0)
        lines = base41
        lines(31) = '1 2 1 2147483647'
        call expect_error('MSH 4.1 block count overflowing the sum', lines, 31, &
                          'more elements than the 4 of the $Elements header')
        lines = base41
        lines(17) = '2 1 0 2147483647'
        call expect_error('MSH 4.1 node block count overflowing the sum', lines, 17, &
                          'more nodes than the 4 of the $Nodes header')
        lines = base41
        lines(10) = '0 2 2147483647 2147483647'
        call expect_error('MSH 4.1 huge entity counts', lines, 10, &
                          'the header announces 2147483647 entities')
        lines = base41
        lines(23) = '1 1e999 0'
        call expect_error('MSH 4.1 coordinate 1e999', lines, 23, 'expected coordinates x y z')
    end subroutine check_fuzz_regressions

    !> Write `lines` to a file named after `what`, read it, and check the failure.
    subroutine expect_error(what, lines, line, words)
        character(len=*), intent(in) :: what, lines(:), words
        integer, intent(in) :: line
        type(mesh_t) :: m
        type(status_t) :: stat
        character(len=:), allocatable :: path
        integer :: i
        path = 'bad_'
        do i = 1, len(what)
            if (verify(what(i:i), 'abcdefghijklmnopqrstuvwxyz0123456789') == 0) &
                path = path//what(i:i)
        end do
        path = path//'.msh'
        call write_lines(path, lines)
        call read_gmsh(path, m, stat)
        call t%check(what//': STATUS_MESH', stat%code == STATUS_MESH)
        if (.not. allocated(stat%message)) return
        call t%check(what//': message starts with file:line', &
                     index(stat%message, path//':'//to_string(line)//': ') == 1)
        call t%check(what//': message says '''//words//'''', index(stat%message, words) > 0)
        if (index(stat%message, path//':'//to_string(line)//': ') /= 1 .or. &
            index(stat%message, words) == 0) print '(a)', '      got: '//stat%message
    end subroutine expect_error

    subroutine write_lines(path, lines)
        character(len=*), intent(in) :: path, lines(:)
        integer :: unit, i
        open (newunit=unit, file=path, status='replace', action='write')
        do i = 1, size(lines)
            write (unit, '(a)') trim(lines(i))
        end do
        close (unit)
    end subroutine write_lines

    function build_config(source, file, element) result(config)
        character(len=*), intent(in) :: source, file
        integer, intent(in) :: element
        type(config_t) :: config
        config%input_file = 'test_mesh_gmsh.nml'
        config%mesh%source = source
        config%mesh%file = file
        config%mesh%width = 1.5_wp
        config%mesh%height = 1.0_wp
        config%mesh%nx = 4
        config%mesh%ny = 3
        config%mesh%element = element_name(element)
        config%mesh%dirichlet = 'top'
        config%mesh%neumann = 'left right'
        config%mesh%contact = 'bottom'
        config%eigen%solver = 'dense'
    end function build_config

    subroutine solve(config, res)
        type(config_t), intent(in) :: config
        type(eigen_result_t), intent(out) :: res
        type(problem_t) :: prob
        type(timings_t) :: timings
        type(status_t) :: stat
        call problem_of(config, prob, stat)
        if (stat%ok()) call eigen_of(config, prob, config%analysis%lambda, res, timings, stat)
        call t%check('solves: '//trim(config%mesh%source)//' '//trim(config%mesh%file), &
                     stat%ok())
        if (.not. stat%ok()) print '(a)', '      '//stat%message
    end subroutine solve

    !> Every eigenvalue of `a` has one of `b` within tol |mu| (and the counts agree).
    logical function same_spectrum(a, b, tol)
        complex(wp), intent(in) :: a(:), b(:)
        real(wp), intent(in) :: tol
        integer :: i
        same_spectrum = size(a) == size(b)
        if (.not. same_spectrum) return
        do i = 1, size(a)
            same_spectrum = same_spectrum .and. minval(abs(b - a(i))) <= tol*abs(a(i))
        end do
    end function same_spectrum

    logical function same_mesh(a, b)
        type(mesh_t), intent(in) :: a, b
        same_mesh = a%element == b%element .and. all(shape(a%coords) == shape(b%coords)) &
                    .and. all(shape(a%cells) == shape(b%cells)) .and. &
                    all(shape(a%edges) == shape(b%edges))
        if (.not. same_mesh) return
        same_mesh = maxval(abs(a%coords - b%coords)) <= 0.0_wp .and. &
                    all(a%cells == b%cells) .and. all(a%edges == b%edges) .and. &
                    all(a%edge_part == b%edge_part) .and. all(a%part_names == b%part_names)
    end function same_mesh

end program test_mesh_gmsh
