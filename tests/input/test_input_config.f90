! SPDX-License-Identifier: MIT
!> Reading the namelist input: defaults, values, normalisation, and one failure per rule,
!> each of which must name the file, the group and the variable.
program test_input_config
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use run_config, only: config_t
    use strings, only: NAME_LEN, split_names, lowercase
    use input_config, only: read_input, default_output_directory, resolve_relative
    use input_help, only: help_text
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t
    type(config_t) :: config, defaults
    type(status_t) :: stat
    character(len=*), parameter :: NL = new_line('a')
    character(len=NAME_LEN), allocatable :: names(:)
    character(len=:), allocatable :: help

    t%name = 'test_input_config'

    ! An empty file: every group absent, so every value is the documented default.
    call write_file('empty.nml', [character(len=1) :: ''])
    call read_input('empty.nml', config, stat)
    call t%check('empty file is accepted', stat%ok())
    call t%check('empty file: default nx', config%mesh%nx == defaults%mesh%nx)
    call t%check('empty file: default element', config%mesh%element == defaults%mesh%element)
    call t%check_close('empty file: default poisson', config%material%poisson, &
                       defaults%material%poisson, 0.0_wp)
    call t%check_close('empty file: default lambda', config%analysis%lambda, &
                       defaults%analysis%lambda, 0.0_wp)
    call t%check('empty file: default solver', config%eigen%solver == defaults%eigen%solver)
    call t%check('empty file: default vtk', config%output%vtk .eqv. defaults%output%vtk)
    call t%check('empty file: vtk_format is binary', config%output%vtk_format == 'binary')
    call t%check('input_file is the path', config%input_file == 'empty.nml')
    call t%check('empty directory becomes output/<stem>', &
                 config%output%directory == 'output/empty')

    ! Values are read, names lowercased and trimmed, other groups keep their defaults.
    call write_file('values.nml', [character(len=80) :: &
                    '! a comment line, then two groups', &
                    '&mesh', &
                    "  element = ' Q2', nx = 3, ny = 5   ! trailing comment with a / and &x", &
                    "  width = 2.5, dirichlet = 'TOP', neumann = '  Left   right ',", &
                    "  contact = 'Bottom' /", &
                    '&material young = 210.0e9, poisson = 0.25 /', &
                    "&eigen solver = 'Dense', nev = 3, target = -1.5 /"])
    call read_input('values.nml', config, stat)
    call t%check('values file is accepted', stat%ok())
    if (.not. stat%ok()) print '(a)', '      '//stat%message
    call t%check('nx read', config%mesh%nx == 3)
    call t%check('ny read', config%mesh%ny == 5)
    call t%check_close('width read', config%mesh%width, 2.5_wp, 0.0_wp)
    call t%check('element lowercased and trimmed', config%mesh%element == 'q2')
    call t%check('dirichlet lowercased', config%mesh%dirichlet == 'top')
    call t%check('neumann normalised', config%mesh%neumann == 'left right')
    call t%check('contact lowercased', config%mesh%contact == 'bottom')
    call t%check_close('young read', config%material%young, 210.0e9_wp, 0.0_wp)
    call t%check_close('poisson read', config%material%poisson, 0.25_wp, 0.0_wp)
    call t%check('solver lowercased', config%eigen%solver == 'dense')
    call t%check('nev read', config%eigen%nev == 3)
    call t%check_close('target read', config%eigen%target, -1.5_wp, 0.0_wp)
    call t%check_close('absent &analysis keeps lambda', config%analysis%lambda, &
                       defaults%analysis%lambda, 0.0_wp)
    call t%check('absent &output keeps modes', config%output%modes == defaults%output%modes)

    ! The mesh file is relative to the input file's folder; the directory is kept as given.
    call write_file('gmsh.nml', [character(len=100) :: &
                    "&mesh source = 'GMSH', file = 'plate.msh', dirichlet = 'clamp', " &
                    //"neumann = '', contact = 'Slide' /", &
                    "&output directory = 'results/run1', modes = 0, vtk_format = ' ASCII' /"])
    call read_input('gmsh.nml', config, stat)
    call t%check('gmsh file is accepted', stat%ok())
    if (.not. stat%ok()) print '(a)', '      '//stat%message
    call t%check('group names are free for gmsh', config%mesh%contact == 'slide')
    call t%check('mesh file kept (input in the working directory)', &
                 config%mesh%file == 'plate.msh')
    call t%check('output directory as given', config%output%directory == 'results/run1')
    call t%check('modes = 0 accepted', config%output%modes == 0)
    call t%check('vtk_format lowercased and trimmed', config%output%vtk_format == 'ascii')

    ! Each rule: STATUS_BAD_INPUT, and the message names file, group and variable.
    call expect_rejected('nx = 0', '&mesh nx = 0 /', '&mesh', 'nx')
    call expect_rejected('ny too large', '&mesh ny = 1000001 /', '&mesh', 'ny')
    call expect_rejected('width = 0', '&mesh width = 0.0 /', '&mesh', 'width')
    call expect_rejected('height NaN', '&mesh height = NaN /', '&mesh', 'height')
    call expect_rejected('source unknown', "&mesh source = 'disc' /", '&mesh', 'source')
    call expect_rejected('gmsh without file', "&mesh source = 'gmsh' /", '&mesh', 'file')
    call expect_rejected('element p5', "&mesh element = 'p5' /", '&mesh', "element = 'p5'")
    call expect_rejected('diagonal', "&mesh diagonal = 'up' /", '&mesh', 'diagonal')
    call expect_rejected('not a side', "&mesh neumann = 'left front' /", '&mesh', 'front')
    call expect_rejected('two contact sides', "&mesh contact = 'bottom top' /", '&mesh', &
                         'contact')
    call expect_rejected('no contact side', "&mesh contact = '' /", '&mesh', 'contact')
    call expect_rejected('empty dirichlet', "&mesh dirichlet = '' /", '&mesh', 'dirichlet')
    call expect_rejected('singular K explained', "&mesh dirichlet = '' /", '&mesh', 'singular')
    call expect_rejected('side used twice', "&mesh neumann = 'left right bottom' /", &
                         '&mesh', "'bottom' is also in neumann")
    call expect_rejected('side twice in one list', "&mesh neumann = 'left left' /", &
                         '&mesh', 'neumann')
    call expect_rejected('young <= 0', '&material young = -1.0 /', '&material', 'young')
    call expect_rejected('poisson = 0.5', '&material poisson = 0.5 /', '&material', &
                         'poisson = 0.5')
    call expect_rejected('poisson = 0.5 explained', '&material poisson = 0.5 /', &
                         '&material', 'incompressible')
    call expect_rejected('poisson = -1', '&material poisson = -1.0 /', '&material', 'poisson')
    call expect_rejected('analysis kind', "&analysis kind = 'buckling' /", '&analysis', 'kind')
    call expect_rejected('lambda infinite', '&analysis lambda = Inf /', '&analysis', 'lambda')
    call expect_rejected('solver misspelt', "&eigen solver = 'arpak' /", '&eigen', &
                         'solver')
    call expect_rejected('tol >= 1', '&eigen tol = 1.0 /', '&eigen', 'tol')
    call expect_rejected('nev = 0', '&eigen nev = 0 /', '&eigen', 'nev')
    call expect_rejected('tol < 0', '&eigen tol = -1.0e-3 /', '&eigen', 'tol')
    call expect_rejected('maxit = 0', '&eigen maxit = 0 /', '&eigen', 'maxit')
    call expect_rejected('ncv too small', '&eigen nev = 6, ncv = 7 /', '&eigen', 'nev + 2 = 8')
    call expect_rejected('dense_max_contact', '&eigen dense_max_contact = 0 /', '&eigen', &
                         'dense_max_contact')
    call expect_rejected('modes < 0', '&output modes = -1 /', '&output', 'modes')
    call expect_rejected('unknown vtk_format', "&output vtk_format = 'base64' /", '&output', &
                         "vtk_format = 'base64'")
    call expect_rejected('unknown variable', '&mesh nxx = 3 /', '&mesh', 'nxx')
    call expect_rejected('wrong type', "&mesh ny = 2, nx = 'a' /", '&mesh', 'nx')
    call expect_rejected('wrong type in a later group', "&eigen nev = 2.5x /", '&eigen', 'nev')
    call expect_rejected('unknown group', '&meshh nx = 3 /', '&meshh', '&material')
    call expect_rejected('group twice', '&mesh nx = 3 / &mesh ny = 3 /', '&mesh', 'twice')
    call expect_rejected('missing slash', '&mesh nx = 3', '&mesh', "'/'")
    ! Overflow inside the runtime's number read trapped in Debug (found by the fuzz test).
    call expect_rejected('overflowing real', '&branch beta = 0.1e999 /', '&branch', 'finite')
    call expect_rejected('unreadable real', '&material young = 1.0e /', '&material', &
                         'line 1: young = 1.0e')
    call expect_rejected('logical not .true./.false.', '&output vtk = .trash. /', '&output', &
                         '.trash.')
    call expect_rejected('variable twice', '&mesh nx = 4, nx = 6 /', '&mesh', 'given twice')
    ! one hp climb for the points and the thresholds: an adapted hp lambda_sweep only
    call expect_rejected('adapt_thresholds without &adapt', "&analysis kind = " // &
                         "'lambda_sweep' /"//NL//"&sweep adapt_thresholds = .true. /", &
                         '&sweep', 'adapt_thresholds')
    call expect_rejected('adapt_thresholds on h levels', "&analysis kind = 'lambda_sweep' /" &
                         //NL//"&adapt tolerance = 1e-6, strategy = 'h' /"//NL &
                         //"&sweep adapt_thresholds = .true. /", '&sweep', "strategy = 'hp'")
    call expect_rejected('adapt_thresholds of a threshold run', "&analysis kind = " // &
                         "'threshold' /"//NL//"&adapt tolerance = 1e-6, strategy = 'hp' /" &
                         //NL//"&sweep adapt_thresholds = .true. /", '&sweep', &
                         'adapt_thresholds')
    call write_file('joint.nml', [character(len=80) :: "&analysis kind = 'lambda_sweep' /", &
        "&adapt tolerance = 1e-6, strategy = 'hp' /", '&sweep adapt_thresholds = .true. /'])
    call read_input('joint.nml', config, stat)
    call t%check('adapt_thresholds of an adapted hp lambda_sweep is accepted', stat%ok() &
                 .and. config%sweep%adapt_thresholds)

    ! One line per message: main prints it on one line of standard error.
    call write_file('bad.nml', [character(len=40) :: '&mesh', "dirichlet = ''", '/'])
    call read_input('bad.nml', config, stat)
    call t%check('messages are one line', index(stat%message, new_line('a')) == 0)

    call read_input('no_such_file.nml', config, stat)
    call t%check('missing file: STATUS_BAD_INPUT', stat%code == STATUS_BAD_INPUT)
    call t%check('missing file: message names it', &
                 index(stat%message, 'no_such_file.nml: cannot open input file') == 1)

    allocate (names(0))   ! GCC 12 -O3 warns (falsely) when the first assignment allocates
    names = split_names('  top   Bottom left ')
    call t%check('split_names: three names', size(names) == 3)
    if (size(names) == 3) call t%check('split_names: in order', names(1) == 'top' .and. &
                                       names(2) == 'Bottom' .and. names(3) == 'left')
    names = split_names('')
    call t%check('split_names: empty list', size(names) == 0)
    call t%check('lowercase', lowercase('Q2 Top') == 'q2 top')

    call t%check('default directory of a nested file', &
                 default_output_directory('input/square.p1.nml') == 'output/square.p1')
    call t%check('default directory without extension', &
                 default_output_directory('case') == 'output/case')
    ! '..nml' named output/. (output/ itself), '...nml' output/.. (the working directory)
    call t%check('default directory of a stem of dots: the whole name', &
                 default_output_directory('..nml') == 'output/..nml' .and. &
                 default_output_directory('in/...nml') == 'output/...nml' .and. &
                 default_output_directory('.nml') == 'output/.nml' .and. &
                 default_output_directory('a..nml') == 'output/a.')
    call t%check('relative path from the input folder', &
                 resolve_relative('input/a.nml', 'meshes/b.msh') == 'input/meshes/b.msh')
    call t%check('absolute path untouched', &
                 resolve_relative('input/a.nml', '/x/b.msh') == '/x/b.msh')
    call t%check('input in working directory', resolve_relative('a.nml', 'b.msh') == 'b.msh')

    help = help_text()
    call t%check('help: usage line', index(help, 'nceig INPUT.nml | --help | --version') == 8)
    call t%check('help: default nx shown', index(help, 'nx = 8') > 0)
    call t%check('help: default poisson shown', index(help, 'poisson = 0.3 ') > 0)
    call t%check('help: default neumann shown', index(help, "neumann = 'left right'") > 0)
    call t%check('help: every group', index(help, '&mesh') > 0 .and. &
                 index(help, '&material') > 0 &
                 .and. index(help, '&analysis') > 0 .and. index(help, '&eigen') > 0 &
                 .and. index(help, '&output') > 0)
    call t%check('help: file relative to the input folder', &
                 index(help, 'input file''s folder') > 0)
    call t%check('help: default directory', index(help, 'output/<input file stem>') > 0)
    call t%check('help: vtk_format and its choices', index(help, "vtk_format = 'binary'") > 0 &
                 .and. index(help, "'ascii'") > 0)
    call t%check('help: lines under 100 characters', longest_line(help) < 100)

    ! gfortran 12 keeps main-program allocatables in a frame gone before LeakSanitizer
    ! looks: free them here so a sanitizer build reports only real leaks.
    deallocate (names, help)
    call t%report()

contains

    pure integer function longest_line(text)
        character(len=*), intent(in) :: text
        integer :: start, length
        longest_line = 0
        start = 1
        do while (start <= len(text))
            length = index(text(start:), new_line('a')) - 1
            if (length < 0) length = len(text) - start + 1
            longest_line = max(longest_line, length)
            start = start + length + 1
        end do
    end function longest_line

    subroutine write_file(name, lines)
        character(len=*), intent(in) :: name
        character(len=*), intent(in) :: lines(:)
        integer :: unit, i
        open (newunit=unit, file=name, status='replace', action='write')
        do i = 1, size(lines)
            write (unit, '(a)') trim(lines(i))
        end do
        close (unit)
    end subroutine write_file

    !> The one-line file `text` must fail with STATUS_BAD_INPUT and a message naming the
    !> file, containing `group` and `fragment` (the variable, or the reason).
    subroutine expect_rejected(what, text, group, fragment)
        character(len=*), intent(in) :: what, text, group, fragment
        character(len=*), parameter :: NAME = 'rejected.nml'
        type(config_t) :: c
        type(status_t) :: s
        logical :: named

        call write_file(NAME, [text])
        call read_input(NAME, c, s)
        call t%check(what//': STATUS_BAD_INPUT', s%code == STATUS_BAD_INPUT)
        named = .false.
        if (allocated(s%message)) named = index(s%message, NAME//':') == 1 .and. &
            index(s%message, group) > 0 .and. index(s%message, fragment) > 0
        call t%check(what//': message names file, group and '//fragment, named)
        ! The messages are the product here: show them in the test log.
        if (allocated(s%message)) print '(a)', '      '//s%message
    end subroutine expect_rejected
end program test_input_config
