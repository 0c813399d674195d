! SPDX-License-Identifier: MIT
!> The text of `nceig --help`: usage, then every group and variable of input_table with its
!> default (from a default `config_t`) and its help line, so that the documentation cannot
!> drift from the code. test_input_records checks that it names the variables the namelists
!> read; cli_input_reference that docs/input.md shows the same variables and defaults.
module input_help
    use kinds, only: wp
    use strings, only: to_string, quoted, one_of, NAME_LEN
    use real_format, only: real_to_text
    use input_table, only: input_variable_t, load_table, group_header, allowed_values, &
                           KNOWN_GROUPS, VALUE_REAL, VALUE_INTEGER, VALUE_LOGICAL, VALUE_NAME, &
                           VALUE_PATH, VALUE_LIST
    use input_records, only: reader_defaults, LISTING_LINE_LEN
    implicit none
    private
    public :: help_text

    integer, parameter :: HELP_COLUMN = 28   !! where descriptions start in the help text

contains

    !> The --help text: usage, then every group and variable of input_table with its
    !> default, taken from a namelist write of a default `config_t` so that the
    !> documentation cannot drift from the code. Lines are separated by new_line('a'); the
    !> text ends with one. Lines stay under 100.
    function help_text() result(text)
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        type(input_variable_t), allocatable :: table(:)
        character(len=NAME_LEN), allocatable :: names(:)
        character(len=LISTING_LINE_LEN), allocatable :: values(:)
        character(len=:), allocatable :: name, value
        integer :: g, i

        text = 'Usage: nceig INPUT.nml | --help | --version'//NL &
               //'       nceig INPUT.nml --set group%variable=value [--set ...]'//NL//NL &
               //'Finds the critical interface parameters of the normal compliance friction' &
               //NL//'model: the eigenvalues mu of K phi = mu B phi for the plane-strain body' &
               //NL//'described by the namelist file INPUT.nml. Every variable is optional;' &
               //NL//'defaults are shown. Names are case-insensitive. Results go to the' &
               //NL//'output directory: summary.json, eigenvalues.csv, mode_NNN.vtu.'//NL//NL &
               //'--set group%variable=value overrides one variable of INPUT.nml, with the' &
               //NL//'same checks (--set analysis%lambda=2.5 --set mesh%element=q2; names need' &
               //NL//'no quotes). A path given so is relative to the working directory.'//NL//NL
        call load_table(table)
        do g = 1, size(KNOWN_GROUPS)
            text = text//group_header(trim(KNOWN_GROUPS(g)))//NL
            call reader_defaults(trim(KNOWN_GROUPS(g)), names, values)
            name = ''
            value = ''
            do i = 1, size(table)
                if (table(i)%group /= KNOWN_GROUPS(g)) cycle
                name = name//trim(table(i)%name)
                value = value//default_text(table(i))
                if (table(i)%joined) then
                    name = name//', '
                    value = value//', '
                    cycle
                end if
                text = text//entry(name, value, described(table(i)))
                name = ''
                value = ''
            end do
        end do

    contains

        function entry(name, value, description) result(line)
            character(len=*), intent(in) :: name, value, description
            character(len=:), allocatable :: line
            integer :: break
            line = '    '//name//' = '//value
            if (len(line) < HELP_COLUMN) line = line//repeat(' ', HELP_COLUMN - len(line))
            break = index(description, NL)
            if (break == 0) then
                line = line//'  '//description//NL
            else   ! the rest on a line of its own, under the description
                line = line//'  '//description(:break)//repeat(' ', HELP_COLUMN + 2) &
                       //description(break + 1:)//NL
            end if
        end function entry

        !> The help line of `variable`, its accepted values in place of '@'.
        function described(variable) result(description)
            type(input_variable_t), intent(in) :: variable
            character(len=:), allocatable :: description
            integer :: at
            description = trim(variable%help)
            at = index(description, '@')
            if (at > 0) description = description(:at - 1) &
                //one_of(allowed_values(variable%choices))//description(at + 1:)
        end function described

        !> The default of `variable` as the help shows it: from the namelist write of
        !> `values` (names(k) its variable), in the input file's own notation.
        function default_text(variable) result(shown)
            type(input_variable_t), intent(in) :: variable
            character(len=:), allocatable :: shown
            character(len=:), allocatable :: raw
            integer :: k, ios, n
            real(wp) :: x
            logical :: flag
            shown = trim(variable%shown_default)
            if (len(shown) > 0) return
            shown = '?'
            k = findloc(names, variable%name, dim=1)
            if (k == 0) return
            raw = trim(values(k))
            select case (variable%value_type)
            case (VALUE_REAL)
                read (raw, *, iostat=ios) x
                if (ios == 0) shown = real_to_text(x)
            case (VALUE_INTEGER)
                read (raw, *, iostat=ios) n
                if (ios == 0) shown = to_string(n)
            case (VALUE_LOGICAL)
                read (raw, *, iostat=ios) flag
                if (ios == 0) shown = logical_text(flag)
            case (VALUE_NAME, VALUE_PATH, VALUE_LIST)
                ! written between double quotes, padded with blanks; no quotes inside
                if (len(raw) >= 2) shown = quoted(trim(raw(2:len(raw) - 1)))
            end select
        end function default_text
    end function help_text

    pure function logical_text(flag) result(text)
        logical, intent(in) :: flag
        character(len=:), allocatable :: text
        text = '.false.'
        if (flag) text = '.true.'
    end function logical_text
end module input_help
