! SPDX-License-Identifier: MIT
!> The table of input variables: for each namelist variable its group, name, type and help
!> line, in the order of the namelists. The messages about a value the runtime could not
!> read, the quoting and length checks of --set and the file, `nceig --help` and the tests
!> all read it; the defaults stay those of run_config (the help prints them from a default
!> config_t). A new variable is one entry here, its component in run_config, its lines in
!> the group's namelist reader (input_records), its row in docs/input.md and, if it has
!> one, its special rule in input_validation; test_input_records fails until the table and
!> the reader agree, cli_input_reference until docs/input.md and the help do.
module input_table
    use run_config, only: config_t, MAX_SWEEP_LAMBDAS, PATH_LEN
    use strings, only: lowercase, to_string, NAME_LEN, LIST_LEN
    use input_validation, only: MESH_SOURCES, ELEMENT_NAMES, DIAGONALS, RECTANGLE_SIDES, &
                                ACCEPTED_ANALYSES, ACCEPTED_SOLVERS, MAX_CELLS_PER_SIDE, &
                                SWEEP_SPACINGS, MAX_SWEEP_POINTS, VTK_FORMATS, SOLVE_DATA, &
                                SOLVE_STARTS, ESTIMATE_MODES, EIGEN_OPERATORS, &
                                ADAPT_STRATEGIES
    implicit none
    private
    public :: input_variable_t, input_variables, load_table, group_header, table_variables, &
              expected_value, is_text_variable, text_capacity, expectation
    public :: KNOWN_GROUPS, HELP_LEN, allowed_values
    public :: VALUE_REAL, VALUE_INTEGER, VALUE_LOGICAL, VALUE_NAME, VALUE_PATH, VALUE_LIST, &
              VALUE_REALS

    !> Namelist groups, in the order they are read, validated and documented.
    character(len=*), parameter :: KNOWN_GROUPS(*) = [character(len=8) :: &
                                   'mesh', 'material', 'analysis', 'eigen', 'output', 'sweep', &
                                   'branch', 'solve', 'adapt']

    !> What a variable holds; VALUE_TEXT names what each expects in messages.
    integer, parameter :: VALUE_REAL = 1, VALUE_INTEGER = 2, VALUE_LOGICAL = 3, &
                          VALUE_NAME = 4, VALUE_PATH = 5, VALUE_LIST = 6, VALUE_REALS = 7
    character(len=*), parameter :: VALUE_TEXT(7) = [character(len=24) :: 'a real number', &
        'an integer', '.true. or .false.', 'a quoted name', 'a quoted path', &
        'a quoted list of names', 'a list of real numbers']
    !> The accepted values of a choice (input_validation's lists): allowed_values(IN_*).
    !> (Codes, not the texts: the table is built at every look-up, the texts only for --help.)
    integer, parameter :: IN_MESH_SOURCES = 1, IN_ELEMENT_NAMES = 2, IN_DIAGONALS = 3, &
                          IN_RECTANGLE_SIDES = 4, IN_ACCEPTED_ANALYSES = 5, &
                          IN_ACCEPTED_SOLVERS = 6, IN_ESTIMATE_MODES = 7, &
                          IN_EIGEN_OPERATORS = 8, IN_VTK_FORMATS = 9, IN_SWEEP_SPACINGS = 10, &
                          IN_SOLVE_DATA = 11, IN_SOLVE_STARTS = 12, &
                          IN_ADAPT_STRATEGIES = 13
    !> A help line's description; new_line('a') in it continues under the description,
    !> '@' stands for the accepted values of its choice.
    integer, parameter :: HELP_LEN = 160

    type :: input_variable_t
        character(len=8) :: group = ''
        character(len=NAME_LEN) :: name = ''
        integer :: value_type = 0
        character(len=HELP_LEN) :: help = ''      !! its --help description
        !> --help shows this instead of the default (lambdas: 'unset'); '' for the default
        character(len=8) :: shown_default = ''
        !> --help documents it on the next variable's line ('f1, f2 = 0.0, 0.0'), which
        !> carries the description
        logical :: joined = .false.
        integer :: capacity = 0                   !! characters of a text variable
        integer :: choices = 0                    !! IN_*: its accepted values; 0: any
    end type input_variable_t

contains

    !> Every input variable, group by group in KNOWN_GROUPS order, each group's in the
    !> order of its namelist.
    pure function input_variables() result(table)
        type(input_variable_t), allocatable :: table(:)
        character(len=*), parameter :: NL = new_line('a')
        type(config_t) :: d
        table = [ &
            v('mesh', 'source', VALUE_NAME, 'one of @', choices=IN_MESH_SOURCES), &
            v('mesh', 'file', VALUE_PATH, "Gmsh .msh (source = 'gmsh'), relative to the " &
              //'input file''s folder'), &
            v('mesh', 'width', VALUE_REAL, 'rectangle size along x'), &
            v('mesh', 'height', VALUE_REAL, 'rectangle size along y'), &
            v('mesh', 'nx', VALUE_INTEGER, 'cells along x (1 to ' &
              //to_string(MAX_CELLS_PER_SIDE)//')'), &
            v('mesh', 'ny', VALUE_INTEGER, 'cells along y'), &
            v('mesh', 'element', VALUE_NAME, '@'//NL &
              //'(p3, p4: cubic, quartic triangles; rectangle; Gmsh sets its own)', &
              choices=IN_ELEMENT_NAMES), &
            v('mesh', 'diagonal', VALUE_NAME, '@' &
              //': triangle diagonals rise to the right or left', choices=IN_DIAGONALS), &
            v('mesh', 'dirichlet', VALUE_LIST, 'fixed sides (@) or Gmsh groups', &
              choices=IN_RECTANGLE_SIDES), &
            v('mesh', 'neumann', VALUE_LIST, 'loaded by &solve t1, t2 (free in eigen runs);' &
              //' unnamed sides are free'), &
            v('mesh', 'contact', VALUE_LIST, 'the one side or group in contact'), &
            v('material', 'young', VALUE_REAL, 'Young''s modulus E > 0'), &
            v('material', 'poisson', VALUE_REAL, 'Poisson''s ratio, -1 < poisson < 0.5'), &
            v('analysis', 'kind', VALUE_NAME, 'one of @', choices=IN_ACCEPTED_ANALYSES), &
            v('analysis', 'lambda', VALUE_REAL, &
              'ratio in b_lambda(phi, v) = lambda int phi_n v_t - int phi_n v_n'), &
            v('eigen', 'solver', VALUE_NAME, 'one of @', choices=IN_ACCEPTED_SOLVERS), &
            v('eigen', 'nev', VALUE_INTEGER, 'ARPACK: eigenvalues nearest target per run' &
              //' (doubled while undecided)'), &
            v('eigen', 'target', VALUE_REAL, 'shift sigma: eigenvalues nearest to it are' &
              //' found first'), &
            v('eigen', 'tol', VALUE_REAL, 'sparse solver tolerance (0: machine precision)'), &
            v('eigen', 'maxit', VALUE_INTEGER, 'sparse solver restarts'), &
            v('eigen', 'ncv', VALUE_INTEGER, 'Krylov dimension, 0 or >= nev + 2' &
              //' (0: chosen from nev)'), &
            v('eigen', 'dense_max_contact', VALUE_INTEGER, &
              "'auto' picks 'dense' up to this many contact nodes, else 'arpack'"), &
            v('eigen', 'estimate', VALUE_NAME, '@' &
              //': error estimate of mu (auto: <= 40000 dofs)', choices=IN_ESTIMATE_MODES), &
            v('eigen', 'operator', VALUE_NAME, '@' &
              //': ARPACK on p x p or (K - target B)^-1 B', choices=IN_EIGEN_OPERATORS), &
            v('eigen', 'cn_max', VALUE_REAL, 'report every positive mu in (0, cn_max]' &
              //' (0: only the lowest)'), &
            v('output', 'directory', VALUE_PATH, "'' means output/<input file stem>" &
              //' (from the working directory)'), &
            v('output', 'vtk', VALUE_LOGICAL, 'write mode_NNN.vtu for ParaView'), &
            v('output', 'modes', VALUE_INTEGER, 'how many modes to write as .vtu'), &
            v('output', 'matrices', VALUE_LOGICAL, 'write K.mtx and B.mtx (Matrix Market)'), &
            v('output', 'vtk_format', VALUE_NAME, '@' &
              //" ('binary': raw appended data; 'ascii': text)", &
              capacity=len(d%output%vtk_format), choices=IN_VTK_FORMATS), &
            v('output', 'plot', VALUE_LOGICAL, 'draw mode_001.png with gnuplot' &
              //' (the first mode on the deformed mesh)'), &
            v('output', 'progress', VALUE_LOGICAL, 'a line on stdout as each phase ends' &
              //' (.false.: the final summary only)'), &
            v('sweep', 'lambda_min', VALUE_REAL, 'first lambda of the range (either sign)'), &
            v('sweep', 'lambda_max', VALUE_REAL, 'last lambda, > lambda_min'), &
            v('sweep', 'n_lambda', VALUE_INTEGER, 'points in the range (2 to ' &
              //to_string(MAX_SWEEP_POINTS)//')'), &
            v('sweep', 'spacing', VALUE_NAME, '@' &
              //" ('log': one sign, geometric in |lambda|)", choices=IN_SWEEP_SPACINGS), &
            v('sweep', 'lambdas', VALUE_REALS, 'explicit list (up to ' &
              //to_string(MAX_SWEEP_LAMBDAS)//'), replaces the range', shown_default='unset'), &
            v('sweep', 'plot', VALUE_LOGICAL, 'draw lambda_sweep.png with gnuplot when it' &
              //' is installed'), &
            v('branch', 'alpha', VALUE_REAL, 'u_n of U on Gamma_C, > 0'), &
            v('branch', 'beta', VALUE_REAL, '|u_t| of U on Gamma_C, > 0'), &
            v('branch', 'n_delta', VALUE_INTEGER, 'deltas evenly spaced in' &
              //' [-delta_max, delta_max]'), &
            v('branch', 'write_members', VALUE_INTEGER, 'members written as branch_NNN.vtu'), &
            v('solve', 'data', VALUE_NAME, '@: the loads below, or those of &branch', &
              choices=IN_SOLVE_DATA), &
            v('solve', 'c_n', VALUE_REAL, 'normal compliance (data = ''given'')'), &
            v('solve', 'c_t', VALUE_REAL, 'tangential compliance'), &
            v('solve', 'critical_factor', VALUE_REAL, &
              'data = ''branch'': c_n, c_t = factor * critical'), &
            v('solve', 'f1', VALUE_REAL, '', joined=.true.), &
            v('solve', 'f2', VALUE_REAL, 'body force'), &
            v('solve', 't1', VALUE_REAL, '', joined=.true.), &
            v('solve', 't2', VALUE_REAL, 'traction on every Neumann part'), &
            v('solve', 'u_d1', VALUE_REAL, '', joined=.true.), &
            v('solve', 'u_d2', VALUE_REAL, 'displacement on Gamma_D'), &
            v('solve', 'start', VALUE_NAME, '@', choices=IN_SOLVE_STARTS), &
            v('solve', 'start_delta', VALUE_REAL, 'start = ''branch'': U + start_delta phi'), &
            v('solve', 'start_scale', VALUE_REAL, &
              'start = ''random'' or ''mode'': size of the guess'), &
            v('solve', 'start_noise', VALUE_REAL, &
              'uniform noise of this size added to any start'), &
            v('solve', 'seed', VALUE_INTEGER, 'of the random start and the noise'), &
            v('solve', 'tol', VALUE_REAL, '||residual|| / ||load|| (infinity norms) to stop at'), &
            v('solve', 'max_iterations', VALUE_INTEGER, 'Newton iterations'), &
            v('adapt', 'tolerance', VALUE_REAL, 'relative error of mu or of both critical' &
              //' lambdas (0: off; < 1)'), &
            v('adapt', 'max_dofs', VALUE_INTEGER, 'no level solves on more free dofs' &
              //' (0: as memory allows)'), &
            v('adapt', 'max_levels', VALUE_INTEGER, 'refinement steps after the starting' &
              //' mesh (0: no limit)'), &
            v('adapt', 'theta', VALUE_REAL, 'Doerfler fraction: refine cells holding this' &
              //' part of the estimate'), &
            v('adapt', 'strategy', VALUE_NAME, '@: refine cells, or graded meshes with' &
              //' rising degrees (eigen)', choices=IN_ADAPT_STRATEGIES), &
            v('adapt', 'sigma', VALUE_REAL, 'hp: grading factor toward the singular points' &
              //' (0 < sigma < 1)'), &
            v('adapt', 'p_max', VALUE_INTEGER, 'hp: highest degree of a cell (1 to 20)')]
    end function input_variables

    !> The table into `table` (an allocatable of the caller: gfortran 12 at -O3 warns of
    !> uninitialised bounds when a function's array result is assigned to one).
    pure subroutine load_table(table)
        type(input_variable_t), allocatable, intent(out) :: table(:)
        allocate (table, source=input_variables())
    end subroutine load_table

    !> One table entry; a text variable holds NAME_LEN, PATH_LEN or LIST_LEN characters
    !> unless `capacity` says otherwise.
    pure function v(group, name, value_type, help, shown_default, joined, capacity, choices) &
            result(entry)
        character(len=*), intent(in) :: group, name, help
        integer, intent(in) :: value_type
        character(len=*), intent(in), optional :: shown_default
        logical, intent(in), optional :: joined
        integer, intent(in), optional :: capacity, choices
        type(input_variable_t) :: entry
        entry%group = group
        entry%name = name
        entry%value_type = value_type
        entry%help = help
        if (present(shown_default)) entry%shown_default = shown_default
        if (present(joined)) entry%joined = joined
        select case (value_type)
        case (VALUE_NAME); entry%capacity = NAME_LEN
        case (VALUE_PATH); entry%capacity = PATH_LEN
        case (VALUE_LIST); entry%capacity = LIST_LEN
        end select
        if (present(capacity)) entry%capacity = capacity
        if (present(choices)) entry%choices = choices
    end function v

    !> The accepted values of choice `choices` (IN_*); none for 0.
    pure function allowed_values(choices) result(values)
        integer, intent(in) :: choices
        character(len=:), allocatable :: values(:)
        select case (choices)
        case (IN_MESH_SOURCES); values = MESH_SOURCES
        case (IN_ELEMENT_NAMES); values = ELEMENT_NAMES
        case (IN_DIAGONALS); values = DIAGONALS
        case (IN_RECTANGLE_SIDES); values = RECTANGLE_SIDES
        case (IN_ACCEPTED_ANALYSES); values = ACCEPTED_ANALYSES
        case (IN_ACCEPTED_SOLVERS); values = ACCEPTED_SOLVERS
        case (IN_ESTIMATE_MODES); values = ESTIMATE_MODES
        case (IN_ADAPT_STRATEGIES); values = ADAPT_STRATEGIES
        case (IN_EIGEN_OPERATORS); values = EIGEN_OPERATORS
        case (IN_VTK_FORMATS); values = VTK_FORMATS
        case (IN_SWEEP_SPACINGS); values = SWEEP_SPACINGS
        case (IN_SOLVE_DATA); values = SOLVE_DATA
        case (IN_SOLVE_STARTS); values = SOLVE_STARTS
        case default; allocate (character(len=1) :: values(0))
        end select
    end function allowed_values

    !> The --help line that opens group `group`: '&group', for the groups of one analysis
    !> followed by what they are for.
    pure function group_header(group) result(header)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: header
        select case (group)
        case ('sweep')
            header = "&sweep  (kind = 'lambda_sweep': lowest positive mu against lambda)"
        case ('branch')
            header = '&branch      (kind = ''branch'': U + delta phi, docs/model.md 9)'
        case ('solve')
            header = '&solve       (kind = ''solve'': frictional normal compliance, Newton)'
        case ('adapt')
            header = '&adapt       (eigen, threshold, lambda_sweep: refine until the error' &
                     //' bar is met)'
        case default
            header = '&'//group
        end select
    end function group_header

    !> The variables of group `group` in the table, in order.
    pure function table_variables(group) result(names)
        character(len=*), intent(in) :: group
        character(len=NAME_LEN), allocatable :: names(:)
        type(input_variable_t), allocatable :: table(:)
        call load_table(table)
        names = pack(table%name, table%group == group)
    end function table_variables

    !> The table entry of `variable` of `group` (any case, blanks around); `found` tells.
    pure subroutine find_variable(group, variable, entry, found)
        character(len=*), intent(in) :: group, variable
        type(input_variable_t), intent(out) :: entry
        logical, intent(out) :: found
        type(input_variable_t), allocatable :: table(:)
        character(len=:), allocatable :: name
        integer :: i
        name = lowercase(trim(adjustl(variable)))
        found = .false.
        call load_table(table)
        do i = 1, size(table)
            if (table(i)%group /= group .or. table(i)%name /= name) cycle
            entry = table(i)
            found = .true.
            exit
        end do
    end subroutine find_variable

    !> What `variable` of `group` expects ('a real number', 'a quoted path', ...); '' for a
    !> variable the group does not have.
    pure function expected_value(group, variable) result(text)
        character(len=*), intent(in) :: group, variable
        character(len=:), allocatable :: text
        type(input_variable_t) :: entry
        logical :: found
        text = ''
        call find_variable(group, variable, entry, found)
        if (found) text = trim(VALUE_TEXT(entry%value_type))
    end function expected_value

    !> Whether `variable` of `group` holds text (a name, path or list of names), whose value
    !> the namelist reads only between quotes: --set adds them when they are left out.
    pure logical function is_text_variable(group, variable)
        character(len=*), intent(in) :: group, variable
        is_text_variable = text_capacity(group, variable) > 0
    end function is_text_variable

    !> Characters the text variable `variable` of `group` holds (0 for one that is not
    !> text): the namelist read silently cuts a longer value, so it is refused before.
    pure integer function text_capacity(group, variable)
        character(len=*), intent(in) :: group, variable
        type(input_variable_t) :: entry
        logical :: found
        call find_variable(group, variable, entry, found)
        text_capacity = 0
        if (found) text_capacity = entry%capacity
    end function text_capacity

    !> What a failed assignment 'name = value' of `group` should have looked like: the
    !> type of a known variable, or the variables the group knows. The runtime's own message
    !> ('Cannot match namelist object name 5') says what went wrong, not what was expected.
    pure function expectation(group, assignment) result(text)
        character(len=*), intent(in) :: group, assignment
        character(len=:), allocatable :: text
        type(input_variable_t), allocatable :: table(:)
        character(len=:), allocatable :: name
        integer :: i, equals
        equals = index(assignment, '=')
        name = lowercase(trim(adjustl(assignment(:max(0, equals - 1)))))
        text = ''
        call load_table(table)
        do i = 1, size(table)
            if (table(i)%group /= group) cycle
            if (trim(table(i)%name) == name) then
                text = ' (expected '//trim(VALUE_TEXT(table(i)%value_type))//')'
                return
            end if
            if (len(text) > 0) text = text//', '
            text = text//trim(table(i)%name)
        end do
        if (len(text) > 0) text = ' (&'//group//' knows: '//text//')'
    end function expectation
end module input_table
