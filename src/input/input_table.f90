! SPDX-License-Identifier: MIT
!> The table of input variables: for each namelist variable its group, name, type and help
!> line, in the order of the namelists. The messages about a value the runtime could not
!> read, the quoting and length checks of --set and the file, `nceig --help` and the tests
!> all read it; the defaults stay those of run_config (the help prints them from a default
!> config_t).
!> A new input variable is one line in src/input/input_variables.cmake (group, name, kind,
!> default, help, choices; its format is documented there), from which the build generates
!> this table's entries (input_table_entries.inc), the component and default in run_config
!> and the namelist reader in input_records; then its row in docs/input.md and, if it has
!> one, its special rule in input_validation (a constant its help names or a new list of
!> choices is also imported below). cli_input_reference fails until docs/input.md and the
!> help agree; input_definitions until --help shows every definition with its default.
module input_table
    use run_config, only: MAX_SWEEP_LAMBDAS, PATH_LEN
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

    !> What a variable holds; VALUE_TEXT names what each expects in messages.
    integer, parameter :: VALUE_REAL = 1, VALUE_INTEGER = 2, VALUE_LOGICAL = 3, &
                          VALUE_NAME = 4, VALUE_PATH = 5, VALUE_LIST = 6, VALUE_REALS = 7
    character(len=*), parameter :: VALUE_TEXT(7) = [character(len=24) :: 'a real number', &
        'an integer', '.true. or .false.', 'a quoted name', 'a quoted path', &
        'a quoted list of names', 'a list of real numbers']
    include 'input_table_groups.inc'   ! KNOWN_GROUPS, IN_* (from input_variables.cmake)
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

    ! input_variables, allowed_values, group_header: generated from input_variables.cmake
    include 'input_table_entries.inc'

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
