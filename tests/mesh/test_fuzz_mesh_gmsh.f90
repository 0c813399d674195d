! SPDX-License-Identifier: MIT
!> Fuzzing the Gmsh reader: a few thousand mutated copies of real MSH files (MSH 4.1 and 2.2;
!> P1, Q1, P2, Q2; shipped, written here, and Delaunay meshes from scripts/make_mesh.sh when
!> gmsh is installed), each read by read_gmsh in this process, so that the Debug build
!> (-fcheck=all, FPE traps) and the sanitizer build watch every parse. Each mutant must end
!> either in a valid mesh or in a failed status whose message is one non-empty line naming
!> the file; a crash or a hang fails the test (CTest TIMEOUT bounds it, see CMakeLists.txt).
!> Mutations: byte changes, deleted, duplicated, swapped and moved lines, truncation, tokens
!> replaced by huge, negative, zero, NaN-like or malformed text, counts nudged, section
!> headers removed or duplicated. The pseudo-random stream is fixed (seeded per seed file),
!> so every run reads the same mutants. After a crash, fuzz_mutant.msh in the test's
!> working directory is the input that crashed; a rejected-without-message or accepted-but-
!> invalid mutant is kept as fuzz_failure_<n>.msh.
program test_fuzz_mesh_gmsh
    use kinds, only: wp, i8
    use status, only: status_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, element_nodes_per_cell, &
                             element_nodes_per_edge
    use mesh_structured, only: structured_rectangle
    use mesh_gmsh, only: read_gmsh
    use strings, only: to_string
    use testing, only: test_suite_t
    use fixtures, only: random_t, uniform, read_text, write_text
    use msh_writer, only: write_msh41, write_msh22
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    implicit none

    ! 500 mutants per seed file: 2500 without gmsh, 4000 with (three Delaunay seeds); about
    ! 2 s in the Debug build, 5 s under the sanitizers. Runs of 40 000 mutants with other
    ! seeds and up to 5 mutations each were clean too (see docs/testing.md).
    integer, parameter :: MUTANTS_PER_SEED = 500
    integer, parameter :: MAX_MUTATIONS = 3          !! per mutant, at least 1
    integer(i8), parameter :: BASE_SEED = 20240808_i8
    character(len=*), parameter :: MUTANT_PATH = 'fuzz_mutant.msh'

    ! Mutation kinds.
    integer, parameter :: CHANGE_BYTE = 1, DELETE_LINE = 2, DUPLICATE_LINE = 3, &
                          SWAP_LINES = 4, MOVE_LINE = 5, TRUNCATE = 6, REPLACE_TOKEN = 7, &
                          NUDGE_NUMBER = 8, HEADER_LINE = 9, N_KINDS = 9
    character(len=14), parameter :: KIND_NAMES(N_KINDS) = [character(len=14) :: &
        'change byte', 'delete line', 'duplicate line', 'swap lines', 'move line', &
        'truncate', 'replace token', 'nudge number', 'header line']
    ! What replaces a token: extremes of integer and real, NaN and infinity spellings, and
    ! text that list-directed input treats specially (',' null value, '/' end of input,
    ! 'r*c' repeat counts), which a reader using read(*) could take for numbers.
    character(len=24), parameter :: ODD_TOKENS(27) = [character(len=24) :: &
        '0', '-1', '1', '-0', '2147483647', '2147483648', '-2147483648', &
        '99999999999999999999999', 'NaN', 'nan', '-Infinity', 'Inf', '1e308', '-1e308', &
        '1e999', '1e-320', '0x1F', '1.5', '+', '-', '""', ',', '/', '3*1', '2*', &
        '1d3', '$Nodes']

    !> Minimal standard generator (Park and Miller): x <- 48271 x mod (2^31 - 1). Its
    !> products stay below 2^47, so 64-bit integers never overflow; the state is local.
    type :: seed_file_t
        character(len=:), allocatable :: name
        character(len=:), allocatable :: text
    end type seed_file_t

    type(test_suite_t) :: t
    type(seed_file_t), allocatable :: seeds(:)
    integer :: s, n_ok, n_rejected

    t%name = 'test_fuzz_mesh_gmsh'
    call collect_seeds(seeds)
    n_ok = 0
    n_rejected = 0
    do s = 1, size(seeds)
        call fuzz_seed(s, seeds(s), n_ok, n_rejected)
    end do
    print '(a)', '      total: '//to_string(n_ok + n_rejected)//' mutants, '// &
        to_string(n_ok)//' parsed OK, '//to_string(n_rejected)//' rejected'
    deallocate (seeds)   ! gfortran does not free main-program allocatables (LeakSanitizer)
    call t%report()

contains

    !> Shipped meshes, grids written by tests/support/msh_writer.f90, and make_mesh.sh's Delaunay
    !> meshes when gmsh runs. Each must read as it is, or fuzzing it would prove little.
    subroutine collect_seeds(seeds)
        type(seed_file_t), allocatable, intent(out) :: seeds(:)
        character(len=4096) :: source_dir
        type(mesh_t) :: grid
        type(status_t) :: stat
        character(len=:), allocatable :: script
        integer :: i, exit_status, command_status
        logical :: have_gmsh
        character(len=16), parameter :: GMSH_SEEDS(3) = [character(len=16) :: &
            '2 2 msh22', '3 1 msh22', '2 2 msh41']

        call get_environment_variable('NCEIG_SOURCE_DIR', source_dir)
        allocate (seeds(0))
        call add_seed(seeds, trim(source_dir)//'/input/meshes/square_16.msh')
        call add_seed(seeds, trim(source_dir)//'/input/meshes/single_element.msh')
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_Q2, 'right', grid, stat)
        call write_msh22('seed_q2_22.msh', grid)
        call add_seed(seeds, 'seed_q2_22.msh')
        call structured_rectangle(1.5_wp, 1.0_wp, 3, 2, ELEMENT_Q1, 'right', grid, stat)
        call write_msh41('seed_q1_41.msh', grid, .false.)
        call add_seed(seeds, 'seed_q1_41.msh')
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 1, ELEMENT_P2, 'left', grid, stat)
        call write_msh41('seed_p2_41_cw.msh', grid, .true.)
        call add_seed(seeds, 'seed_p2_41_cw.msh')

        call execute_command_line('command -v gmsh >/dev/null 2>&1', exitstat=exit_status, &
                                  cmdstat=command_status)
        have_gmsh = exit_status == 0 .and. command_status == 0
        if (.not. have_gmsh) print '(a)', 'SKIP  gmsh is not installed: no Delaunay seeds'
        do i = 1, size(GMSH_SEEDS)
            if (.not. have_gmsh) exit
            script = 'bash '//trim(source_dir)//'/scripts/make_mesh.sh '// &
                GMSH_SEEDS(i)(:4)//'seed_gmsh_'//to_string(i)//'.msh '//trim(GMSH_SEEDS(i)(5:))
            call execute_command_line(script, exitstat=exit_status, cmdstat=command_status)
            if (command_status /= 0) exit_status = command_status
            call t%check('make_mesh.sh '//trim(GMSH_SEEDS(i))//' writes a seed', exit_status == 0)
            if (exit_status == 0) call add_seed(seeds, 'seed_gmsh_'//to_string(i)//'.msh')
        end do
    end subroutine collect_seeds

    subroutine add_seed(seeds, path)
        type(seed_file_t), allocatable, intent(inout) :: seeds(:)
        character(len=*), intent(in) :: path
        type(seed_file_t), allocatable :: grown(:)
        type(mesh_t) :: m
        type(status_t) :: stat
        integer :: i
        call read_gmsh(path, m, stat)
        call t%check('seed '//path//' reads as it is', stat%ok())
        if (.not. stat%ok()) then
            print '(a)', '      '//stat%message
            return
        end if
        ! Grown by hand: gfortran leaks the components of array-constructor temporaries.
        allocate (grown(size(seeds) + 1))
        do i = 1, size(seeds)
            call move_alloc(seeds(i)%name, grown(i)%name)
            call move_alloc(seeds(i)%text, grown(i)%text)
        end do
        grown(size(grown))%name = path
        call read_text(path, grown(size(grown))%text)
        call move_alloc(grown, seeds)
    end subroutine add_seed

    !> MUTANTS_PER_SEED mutants of one seed, each read in turn; counts the outcomes.
    subroutine fuzz_seed(index, seed, n_ok, n_rejected)
        integer, intent(in) :: index
        type(seed_file_t), intent(in) :: seed
        integer, intent(inout) :: n_ok, n_rejected
        type(random_t) :: rng
        type(mesh_t) :: m
        type(status_t) :: stat
        character(len=:), allocatable :: text, problem
        integer :: i, k, kind, ok_here, rejected_here, n_bad, used(N_KINDS)
        integer(i8) :: start, finish, rate, slowest
        character(len=16) :: milliseconds

        ! One stream per seed: the mutants of a seed do not depend on which others exist.
        rng%state = 1 + modulo(BASE_SEED + 7919_i8*index, 2147483646_i8)
        ok_here = 0
        rejected_here = 0
        n_bad = 0
        used = 0
        slowest = 0
        do i = 1, MUTANTS_PER_SEED
            text = seed%text
            do k = 1, uniform(rng, 1, MAX_MUTATIONS)
                kind = uniform(rng, 1, N_KINDS)
                call mutate(text, kind, rng)
                used(kind) = used(kind) + 1
            end do
            call write_text(MUTANT_PATH, text)
            call system_clock(start, rate)
            call read_gmsh(MUTANT_PATH, m, stat)
            call system_clock(finish)
            slowest = max(slowest, finish - start)
            if (stat%ok()) then
                ok_here = ok_here + 1
                problem = mesh_problem(m)
            else
                rejected_here = rejected_here + 1
                problem = message_problem(stat)
            end if
            if (len(problem) > 0) then
                n_bad = n_bad + 1
                call write_text('fuzz_failure_'//to_string(n_bad)//'.msh', text)
                print '(a)', '      mutant '//to_string(i)//' of '//seed%name//' ('// &
                    'fuzz_failure_'//to_string(n_bad)//'.msh): '//problem
            end if
        end do
        n_ok = n_ok + ok_here
        n_rejected = n_rejected + rejected_here
        call t%check(seed%name//': every mutant gives a valid mesh or a one-line message ' &
                     //'naming the file', n_bad == 0)
        write (milliseconds, '(f0.1)') 1000.0_wp*real(slowest, wp)/real(rate, wp)
        print '(a)', '      '//to_string(MUTANTS_PER_SEED)//' mutants: '// &
            to_string(ok_here)//' parsed OK, '//to_string(rejected_here)// &
            ' rejected; slowest parse '//trim(milliseconds)//' ms'
        do kind = 1, N_KINDS
            if (used(kind) == 0) print '(a)', '      mutation never used: '//KIND_NAMES(kind)
        end do
    end subroutine fuzz_seed

    !> Empty when the message is one non-empty line that names the mutant's file.
    function message_problem(stat) result(problem)
        type(status_t), intent(in) :: stat
        character(len=:), allocatable :: problem
        integer :: i
        problem = ''
        if (.not. allocated(stat%message)) then
            problem = 'failed status without a message'
        else if (index(stat%message, MUTANT_PATH) == 0) then
            problem = 'message does not name the file: '//stat%message
        else if (len_trim(stat%message) <= len(MUTANT_PATH) + 2) then
            problem = 'message says nothing but the file: '//stat%message
        else if (any([(iachar(stat%message(i:i)) < 32, i=1, len(stat%message))])) then
            problem = 'control characters (line breaks, ...) in the message: '//stat%message
        end if
    end function message_problem

    !> Empty when the mesh is one the rest of the program can use: cells and edges of the
    !> element's node counts referring to existing nodes, finite coordinates, edge parts
    !> that exist.
    function mesh_problem(m) result(problem)
        type(mesh_t), intent(in) :: m
        character(len=:), allocatable :: problem
        integer :: n
        problem = ''
        n = m%n_nodes()
        if (m%n_cells() == 0 .or. n == 0) then
            problem = 'accepted a mesh without cells or nodes'
        else if (size(m%cells, 1) /= element_nodes_per_cell(m%element)) then
            problem = 'cells have the wrong number of nodes'
        else if (any(m%cells < 1) .or. any(m%cells > n)) then
            problem = 'a cell refers to a node that does not exist'
        else if (.not. all(ieee_is_finite(m%coords))) then
            problem = 'accepted non-finite coordinates'
        else if (.not. allocated(m%edges) .or. .not. allocated(m%edge_part) .or. &
                 .not. allocated(m%part_names)) then
            problem = 'edges or parts unallocated'
        else if (size(m%edges, 2) > 0 .and. &
                 size(m%edges, 1) /= element_nodes_per_edge(m%element)) then
            problem = 'edges have the wrong number of nodes'
        else if (any(m%edges < 1) .or. any(m%edges > n)) then
            problem = 'an edge refers to a node that does not exist'
        else if (any(m%edge_part < 1) .or. any(m%edge_part > size(m%part_names))) then
            problem = 'an edge belongs to a part that does not exist'
        end if
    end function mesh_problem

    ! ------------------------------------------------------------------ mutations

    !> Apply one mutation of kind `kind` to `text`.
    subroutine mutate(text, kind, rng)
        character(len=:), allocatable, intent(inout) :: text
        integer, intent(in) :: kind
        type(random_t), intent(inout) :: rng
        integer, allocatable :: starts(:)
        integer :: n_lines, a, b, pos
        character(len=:), allocatable :: line_a, line_b

        if (len(text) == 0) return
        starts = line_starts(text)
        n_lines = size(starts) - 1
        a = uniform(rng, 1, n_lines)
        b = uniform(rng, 1, n_lines)
        line_a = text(starts(a):starts(a + 1) - 1)
        select case (kind)
        case (CHANGE_BYTE)
            pos = uniform(rng, 1, len(text))
            text(pos:pos) = achar(uniform(rng, 0, 255))
        case (DELETE_LINE)
            text = text(:starts(a) - 1)//text(starts(a + 1):)
        case (DUPLICATE_LINE)
            text = text(:starts(a + 1) - 1)//line_a//text(starts(a + 1):)
        case (SWAP_LINES)
            if (a > b) call swap(a, b)
            if (a == b) return
            line_a = text(starts(a):starts(a + 1) - 1)
            line_b = text(starts(b):starts(b + 1) - 1)
            text = text(:starts(a) - 1)//line_b//text(starts(a + 1):starts(b) - 1)//line_a// &
                   text(starts(b + 1):)
        case (MOVE_LINE)
            ! A copy of line a before line b: a line out of its section.
            text = text(:starts(b) - 1)//line_a//text(starts(b):)
        case (TRUNCATE)
            text = text(:uniform(rng, 0, len(text) - 1))
        case (REPLACE_TOKEN)
            call put_token(text, starts(a), starts(a + 1) - 1, rng, .false.)
        case (NUDGE_NUMBER)
            call put_token(text, starts(a), starts(a + 1) - 1, rng, .true.)
        case (HEADER_LINE)
            call mutate_header(text, starts, rng)
        end select
    end subroutine mutate

    !> Replace a random blank-separated token of text(first:last) by an odd token or, with
    !> `nudge`, an integer token by a nearby or scaled value (counts off by one, doubled...).
    subroutine put_token(text, first, last, rng, nudge)
        character(len=:), allocatable, intent(inout) :: text
        integer, intent(in) :: first, last
        type(random_t), intent(inout) :: rng
        logical, intent(in) :: nudge
        integer :: token_first(64), token_last(64), n_tokens, pos, k, value, ios
        character(len=:), allocatable :: new

        n_tokens = 0
        pos = first
        do while (pos <= last .and. n_tokens < size(token_first))
            if (index(' '//achar(9)//achar(10)//achar(13), text(pos:pos)) > 0) then
                pos = pos + 1
                cycle
            end if
            n_tokens = n_tokens + 1
            token_first(n_tokens) = pos
            do while (pos <= last)
                if (index(' '//achar(9)//achar(10)//achar(13), text(pos:pos)) > 0) exit
                pos = pos + 1
            end do
            token_last(n_tokens) = pos - 1
        end do
        if (n_tokens == 0) return
        k = uniform(rng, 1, n_tokens)
        new = trim(ODD_TOKENS(uniform(rng, 1, size(ODD_TOKENS))))
        if (nudge) then
            read (text(token_first(k):token_last(k)), *, iostat=ios) value
            if (ios /= 0) return
            ! Kept within +-2^30 so that the arithmetic cannot overflow.
            value = max(-2**30, min(2**30, value))
            select case (uniform(rng, 1, 6))
            case (1); new = to_string(value + 1)
            case (2); new = to_string(value - 1)
            case (3); new = to_string(2*value)
            case (4); new = to_string(value/2)
            case (5); new = to_string(-value)
            case (6); new = to_string(value + uniform(rng, 2, 1000))
            end select
        end if
        text = text(:token_first(k) - 1)//new//text(token_last(k) + 1:)
    end subroutine put_token

    !> Delete or duplicate a random section header or end marker (a line starting '$'),
    !> or give it another section's name.
    subroutine mutate_header(text, starts, rng)
        character(len=:), allocatable, intent(inout) :: text
        integer, intent(in) :: starts(:)
        type(random_t), intent(inout) :: rng
        integer :: headers(size(starts)), n_headers, k, a
        character(len=:), allocatable :: line
        character(len=16), parameter :: NAMES(8) = [character(len=16) :: '$Nodes', &
            '$EndNodes', '$Elements', '$EndElements', '$Entities', '$PhysicalNames', &
            '$MeshFormat', '$EndEntities']

        n_headers = 0
        do k = 1, size(starts) - 1
            if (text(starts(k):starts(k)) /= '$') cycle
            n_headers = n_headers + 1
            headers(n_headers) = k
        end do
        if (n_headers == 0) return
        a = headers(uniform(rng, 1, n_headers))
        line = text(starts(a):starts(a + 1) - 1)
        select case (uniform(rng, 1, 3))
        case (1)
            text = text(:starts(a) - 1)//text(starts(a + 1):)
        case (2)
            text = text(:starts(a + 1) - 1)//line//text(starts(a + 1):)
        case (3)
            text = text(:starts(a) - 1)//trim(NAMES(uniform(rng, 1, size(NAMES))))// &
                   new_line('a')//text(starts(a + 1):)
        end select
    end subroutine mutate_header

    !> Offsets of the first character of each line, then len(text) + 1.
    pure function line_starts(text) result(starts)
        character(len=*), intent(in) :: text
        integer, allocatable :: starts(:)
        integer :: i, n
        n = 1
        do i = 1, len(text) - 1
            if (text(i:i) == new_line('a')) n = n + 1
        end do
        allocate (starts(n + 1))
        starts(1) = 1
        n = 1
        do i = 1, len(text) - 1
            if (text(i:i) /= new_line('a')) cycle
            n = n + 1
            starts(n) = i + 1
        end do
        starts(n + 1) = len(text) + 1
    end function line_starts

    subroutine swap(a, b)
        integer, intent(inout) :: a, b
        integer :: c
        c = a
        a = b
        b = c
    end subroutine swap


    ! ------------------------------------------------------------------ files

end program test_fuzz_mesh_gmsh
