! SPDX-License-Identifier: MIT
!> Reads the namelist input file into a validated `config_t`: scans its groups
!> (namelist_scan), reads each through its record (input_records), then checks the values
!> (input_validation) and resolves the paths; values of `--set` go through the same records
!> and rules. Every default lives in `run_config`.
module input_config
    use status, only: status_t, STATUS_BAD_INPUT
    use run_config, only: config_t
    use namelist_scan, only: group_text_t, text_t, scan_groups, has_group, &
                             split_assignments, group_list, assignment_starts, body_line
    use input_records, only: read_record
    use input_table, only: expectation, is_text_variable, expected_value, text_capacity, &
                           KNOWN_GROUPS
    use run_config, only: MAX_SWEEP_LAMBDAS
    use strings, only: lowercase, printable, to_string
    use input_validation, only: validate_config
    use iso_fortran_env, only: iostat_end
    use filesystem, only: is_directory, canonical_path
    implicit none
    private
    public :: read_input, default_output_directory, resolve_relative

    integer, parameter :: MSG_LEN = 1024     !! iomsg buffers
    integer, parameter :: MSG_SHOWN_LEN = 200   !! of a runtime message in ours
    integer, parameter :: MESSAGE_LEN = 1000    !! of a whole message (about 12 lines of 80)
    !> Assignments in one group: every variable once and each of the 1000 lambdas(k) alone
    !> stay below it; it bounds the check for repeated variables (quadratic).
    integer, parameter :: MAX_ASSIGNMENTS = 2000
    integer, parameter :: PATH_SHOWN_LEN = 256  !! of a file name in a message

contains

    !> Read and validate the namelist file `path`. Groups are read in the order of
    !> KNOWN_GROUPS; an absent group keeps its defaults. Names (source, element, side
    !> lists, kind, solver) are stored trimmed and lowercased. The mesh `file` is resolved
    !> relative to the input file's folder, and an empty output `directory` becomes
    !> default_output_directory(path). Any problem gives STATUS_BAD_INPUT with a one-line
    !> message naming the file, the group and the variable.
    !> `settings` ('group%variable=value', the --set options) then override the file, in
    !> order, as one-assignment records; a path so given stays relative to the working
    !> directory. Their problems name '--set' instead of the file, and so does a broken rule
    !> when the file alone keeps every rule.
    subroutine read_input(path, config, stat, settings)
        character(len=*), intent(in) :: path
        type(config_t), intent(out) :: config
        type(status_t), intent(out) :: stat
        type(text_t), intent(in), optional :: settings(:)
        call read_and_check(path, config, stat, settings)
        ! Whatever part of the input a message quotes, it stays one printable line.
        if (.not. stat%ok()) call stat%fail(stat%code, printable(stat%message, MESSAGE_LEN))
    end subroutine read_input

    !> read_input, its message not yet made printable.
    subroutine read_and_check(path, config, stat, settings)
        character(len=*), intent(in) :: path
        type(config_t), intent(out) :: config
        type(status_t), intent(out) :: stat
        type(text_t), intent(in), optional :: settings(:)
        type(group_text_t), allocatable :: groups(:)
        type(config_t) :: file_config
        type(status_t) :: file_stat, set_stat
        character(len=:), allocatable :: input
        character(len=MSG_LEN) :: msg
        integer :: unit, ios, i

        input = trim(path)
        config%input_file = input
        ! Opening a directory succeeds and reads as an empty file: all defaults, silently.
        if (is_directory(input)) then
            call stat%fail(STATUS_BAD_INPUT, shown_path(input)//': is a directory: expected ' &
                           //'a namelist input file')
            return
        end if
        open (newunit=unit, file=input, status='old', action='read', iostat=ios, iomsg=msg)
        if (ios /= 0) then
            call stat%fail(STATUS_BAD_INPUT, shown_path(input)//': cannot open input file: ' &
                           //printable(trim(msg), MSG_SHOWN_LEN))
            return
        end if
        ! Read once, whatever the file is (a pipe, <(...)): every later step uses the text.
        call scan_groups(unit, input, KNOWN_GROUPS, groups, stat)
        do i = 1, size(KNOWN_GROUPS)
            if (stat%ok()) call read_group(shown_path(input), trim(KNOWN_GROUPS(i)), groups, &
                                           config, stat)
        end do
        close (unit)
        if (.not. stat%ok()) return
        ! Only the file's own path is relative to its folder (validation never shows it).
        if (len_trim(config%mesh%file) > 0) then
            config%mesh%file = resolve_relative(input, config%mesh%file)
        end if

        if (present(settings)) then
            file_config = config
            do i = 1, size(settings)
                call apply_setting(settings(i)%text, config, stat)
                if (.not. stat%ok()) return
            end do
        end if
        call validate_config(config, shown_path(input), stat)
        if (.not. stat%ok() .and. present(settings)) then
            call validate_config(file_config, shown_path(input), file_stat)
            if (file_stat%ok()) then
                call validate_config(config, '--set', set_stat)
                stat = set_stat
            end if
        end if
        if (.not. stat%ok()) return

        if (len_trim(config%output%directory) == 0) then
            config%output%directory = default_output_directory(input)
        end if
        call check_inputs_outside_output(config, shown_path(input), stat)
    end subroutine read_and_check

    !> The output directory must not hold a file the run reads (the input file, the Gmsh
    !> mesh), at any depth: the commit replaces the directory as a whole, so such a file
    !> would be overwritten by an output of its name (an adaptive run's mesh.msh), deleted
    !> with the previous set that listed it, or, in a subfolder, fail the commit after all
    !> the computing. Refused before any computing, as bad input.
    subroutine check_inputs_outside_output(config, path, stat)
        type(config_t), intent(in) :: config
        character(len=*), intent(in) :: path   !! the input file, as shown in messages
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: output
        output = canonical_path(trim(config%output%directory))
        call check_one(config%input_file, 'the input file')
        if (config%mesh%source == 'gmsh') call check_one(trim(config%mesh%file), '&mesh file')
    contains
        subroutine check_one(file, what)
            character(len=*), intent(in) :: file, what
            character(len=:), allocatable :: read_path
            if (.not. stat%ok()) return
            read_path = canonical_path(file)
            if (output /= '/' .and. index(read_path, output//'/') /= 1) return
            call stat%fail(STATUS_BAD_INPUT, path//': &output directory = '''// &
                           trim(config%output%directory)//''' holds '//what//' '// &
                           shown_path(file)//', which this run reads; nceig replaces its ' &
                           //'output directory as a whole: choose another directory')
        end subroutine check_one
    end subroutine check_inputs_outside_output

    ! ------------------------------------------------------------------ reading groups

    !> Read group `group` (when the file has it) through its record, from the text
    !> scan_groups collected, after the checks of its raw assignments (check_group). On
    !> failure, re-read its assignments one at a time on a scratch copy to name the culprit,
    !> its line and what it expects.
    subroutine read_group(path, group, groups, config, stat)
        character(len=*), intent(in) :: path, group
        type(group_text_t), intent(in) :: groups(:)
        type(config_t), intent(inout) :: config
        type(status_t), intent(inout) :: stat
        type(config_t) :: scratch
        type(text_t), allocatable :: pieces(:)
        integer, allocatable :: starts(:)
        character(len=MSG_LEN) :: msg
        integer :: i, g, ios
        if (.not. has_group(groups, group)) return
        do g = 1, size(groups)
            if (groups(g)%name == group) exit
        end do
        allocate (pieces(0))
        pieces = split_assignments(groups(g)%body)
        allocate (starts(0))
        starts = assignment_starts(groups(g)%body)
        call check_group(path, groups(g), pieces, starts, stat)
        if (.not. stat%ok()) return
        msg = ''
        call read_record(group, '&'//group//' '//groups(g)%body//' /', config, ios, msg)
        if (ios == 0) return
        call stat%fail(STATUS_BAD_INPUT, read_failure(path, group, ios, msg))
        scratch = config
        do i = 1, size(pieces)
            msg = ''
            call read_record(group, '&'//group//' '//pieces(i)%text//' /', scratch, ios, msg)
            if (ios /= 0) then
                call stat%fail(STATUS_BAD_INPUT, path//': &'//group//': line ' &
                               //to_string(body_line(groups(g), starts(i)))//': ' &
                               //printable(pieces(i)%text)//': ' &
                               //printable(trim(msg), MSG_SHOWN_LEN) &
                               //expectation(group, pieces(i)%text))
                exit
            end if
        end do
    end subroutine read_group

    !> What the namelist read would get wrong without a word, checked on the raw text of
    !> each assignment of `group`: a variable given twice (the last would win), and what
    !> check_assignment refuses.
    subroutine check_group(path, group, pieces, starts, stat)
        character(len=*), intent(in) :: path
        type(group_text_t), intent(in) :: group
        type(text_t), intent(in) :: pieces(:)
        integer, intent(in) :: starts(:)
        type(status_t), intent(inout) :: stat
        type(text_t), allocatable :: names(:)
        integer :: i, j, paren
        if (size(pieces) > MAX_ASSIGNMENTS) then
            call stat%fail(STATUS_BAD_INPUT, path//': &'//group%name//': line ' &
                           //to_string(group%line)//': '//to_string(size(pieces)) &
                           //' assignments: ' &
                           //'expected at most '//to_string(MAX_ASSIGNMENTS)//' in one group')
            return
        end if
        allocate (names(size(pieces)))
        do i = 1, size(pieces)
            names(i)%text = assigned_name(pieces(i)%text)
            paren = index(names(i)%text, '(')
            if (paren == 0) paren = len(names(i)%text) + 1
            ! An unknown variable: the read names it with the variables the group knows.
            if (len(expected_value(group%name, names(i)%text(:paren - 1))) == 0) return
            do j = 1, i - 1
                if (names(j)%text /= names(i)%text) cycle
                call stat%fail(STATUS_BAD_INPUT, path//': &'//group%name//': line ' &
                               //to_string(body_line(group, starts(i)))//': ' &
                               //printable(names(i)%text)//' is given twice (first on ' &
                               //'line '//to_string(body_line(group, starts(j))) &
                               //'): expected each variable once')
                return
            end do
            call check_assignment(path, group%name, pieces(i)%text, stat, &
                                  'line '//to_string(body_line(group, starts(i)))//': ')
            if (.not. stat%ok()) return
        end do
    end subroutine check_group

    !> The name of 'name = value', lowercased, without blanks ('lambdas(2)' stays whole).
    pure function assigned_name(assignment) result(name)
        character(len=*), intent(in) :: assignment
        character(len=:), allocatable :: name
        integer :: i, n, equals
        equals = index(assignment, '=')
        allocate (character(len=max(equals - 1, 0)) :: name)
        n = 0
        do i = 1, equals - 1   ! filled in place: name//c per character is quadratic
            if (assignment(i:i) == ' ') cycle
            n = n + 1
            name(n:n) = lowercase(assignment(i:i))
        end do
        name = name(:n)
    end function assigned_name

    !> Refuse in `assignment` of `group` (`place` starts the message) what the runtime
    !> would read wrongly without a word: a text longer than its variable (cut), a logical
    !> other than .true./.false./t/f/.t./.f. (gfortran reads '.trash.' as true), a number
    !> it cannot read (some it skips: 'young = 1.0x'), more than MAX_SWEEP_LAMBDAS lambdas.
    subroutine check_assignment(place, group, assignment, stat, line)
        character(len=*), intent(in) :: place, group, assignment
        type(status_t), intent(inout) :: stat
        character(len=*), intent(in), optional :: line   !! 'line N: ', for a file
        character(len=:), allocatable :: name, variable, value, expected, content
        integer :: equals, paren, capacity, n_values
        logical :: good

        equals = index(assignment, '=')
        if (equals == 0) return
        name = assigned_name(assignment)
        paren = index(name, '(')
        variable = name
        if (paren > 0) variable = name(:paren - 1)
        expected = expected_value(group, variable)
        if (len(expected) == 0) return   ! an unknown variable: the read names the known ones
        value = trim(adjustl(assignment(equals + 1:)))
        if (len(value) == 0) return      ! a null value keeps the default
        capacity = text_capacity(group, variable)
        if (capacity > 0) then
            content = text_value(value)
            if (len_trim(content) > capacity) then
                call refuse('at most '//to_string(capacity)//' characters (the value has ' &
                            //to_string(len_trim(content))//')')
            end if
            return
        end if
        select case (expected)
        case ('.true. or .false.')
            select case (lowercase(value))
            case ('.true.', '.false.', 't', 'f', '.t.', '.f.')
            case default
                call refuse('.true. or .false. (or t, f, .t., .f.)')
            end select
        case ('a real number', 'an integer')
            call number_list(value, expected == 'an integer', good, n_values)
            if (.not. good .or. n_values > 1) call refuse(expected)
        case ('a list of real numbers')
            call number_list(value, .false., good, n_values)
            if (.not. good) then
                call refuse(expected)
            else if (n_values + first_index(name) - 1 > MAX_SWEEP_LAMBDAS) then
                call refuse('at most '//to_string(MAX_SWEEP_LAMBDAS)//' values (got ' &
                            //to_string(n_values + first_index(name) - 1)//')')
            end if
        end select

    contains

        subroutine refuse(what)
            character(len=*), intent(in) :: what
            character(len=:), allocatable :: where
            where = ''
            if (present(line)) where = line
            call stat%fail(STATUS_BAD_INPUT, place//': &'//group//': '//where//printable(name) &
                           //' = '//printable(value)//': expected '//what)
        end subroutine refuse
    end subroutine check_assignment

    !> The text a character value stands for: between its quotes, doubled quotes single;
    !> unquoted, its first word (where the runtime stops).
    pure function text_value(value) result(text)
        character(len=*), intent(in) :: value
        character(len=:), allocatable :: text
        integer :: i, n
        character(len=1) :: quote
        if (len(value) == 0) then
            text = ''
            return
        end if
        quote = value(1:1)
        if (quote /= '"' .and. quote /= "'") then
            n = scan(value, ' ,')
            if (n == 0) n = len(value) + 1
            text = value(:n - 1)
            return
        end if
        allocate (character(len=len(value)) :: text)
        n = 0
        i = 2
        do while (i <= len(value))
            if (value(i:i) == quote) then
                if (i == len(value)) exit
                if (value(i + 1:i + 1) /= quote) exit
                i = i + 1
            end if
            n = n + 1
            text(n:n) = value(i:i)
            i = i + 1
        end do
        text = text(:n)
    end function text_value

    !> The first index of 'lambdas(k)' (k; 1 without one or for a section 'lambdas(k:m)').
    pure integer function first_index(name)
        character(len=*), intent(in) :: name
        integer :: open_paren, close_paren, ios
        first_index = 1
        open_paren = index(name, '(')
        if (open_paren == 0) return
        close_paren = scan(name, ':)')
        if (close_paren <= open_paren + 1) return
        if (verify(name(open_paren + 1:close_paren - 1), '0123456789') /= 0) return
        if (close_paren - open_paren > 8) return
        read (name(open_paren + 1:close_paren - 1), *, iostat=ios) first_index
        if (ios /= 0) first_index = 1
    end function first_index

    !> `good`: whether `value` is a list of numbers as a namelist writes them (comma or blank
    !> separated, null values, repeat counts 'r*x'), integers only when `integers`;
    !> `n_values` counts them (a repeat count counts its copies).
    pure subroutine number_list(value, integers, good, n_values)
        character(len=*), intent(in) :: value
        logical, intent(in) :: integers
        logical, intent(out) :: good
        integer, intent(out) :: n_values
        integer :: i, first, star, repeat
        good = .true.
        n_values = 0
        i = 1
        do while (i <= len(value))
            if (index(' ,', value(i:i)) > 0) then
                i = i + 1
                cycle
            end if
            first = i
            do while (i <= len(value))
                if (index(' ,', value(i:i)) > 0) exit
                i = i + 1
            end do
            associate (word => value(first:i - 1))
                star = index(word, '*')
                repeat = 1
                if (star > 0) then
                    if (star == 1 .or. star > 9) then
                        good = .false.
                    else if (verify(word(:star - 1), '0123456789') /= 0) then
                        good = .false.
                    else
                        read (word(:star - 1), *) repeat
                    end if
                end if
                if (good .and. star < len(word)) then
                    if (integers) then
                        good = is_integer(word(star + 1:))
                    else
                        good = is_real(word(star + 1:))
                    end if
                end if
            end associate
            if (.not. good) return
            if (n_values > huge(n_values) - repeat) then
                n_values = huge(n_values)
            else
                n_values = n_values + repeat
            end if
        end do
    end subroutine number_list

    !> [+-]digits
    pure logical function is_integer(word)
        character(len=*), intent(in) :: word
        integer :: start
        start = 1
        if (index('+-', word(1:1)) > 0) start = 2
        is_integer = len(word) >= start
        if (is_integer) is_integer = verify(word(start:), '0123456789') == 0
    end function is_integer

    !> A real as list-directed input reads it: [+-] digits with at most one '.', at least
    !> one digit, then an optional exponent (e, d or q, or just a sign, then digits); or
    !> Inf, Infinity, NaN.
    pure logical function is_real(word)
        character(len=*), intent(in) :: word
        character(len=:), allocatable :: lower
        integer :: i, n_digits, n_dots
        is_real = .false.
        lower = lowercase(word)
        i = 1
        if (index('+-', lower(1:1)) > 0) i = 2
        if (i > len(lower)) return
        select case (lower(i:))
        case ('inf', 'infinity', 'nan')
            is_real = .true.
            return
        end select
        n_digits = 0
        n_dots = 0
        do while (i <= len(lower))
            if (lower(i:i) == '.') then
                n_dots = n_dots + 1
            else if (index('0123456789', lower(i:i)) > 0) then
                n_digits = n_digits + 1
            else
                exit
            end if
            i = i + 1
        end do
        if (n_digits == 0 .or. n_dots > 1) return
        if (i > len(lower)) then
            is_real = .true.
            return
        end if
        if (index('edq', lower(i:i)) > 0) i = i + 1
        if (i > len(lower)) return
        is_real = is_integer(lower(i:))
    end function is_real

    !> Message for a failed read of group `group` when no single assignment was to blame.
    function read_failure(path, group, ios, msg) result(text)
        character(len=*), intent(in) :: path, group, msg
        integer, intent(in) :: ios
        character(len=:), allocatable :: text
        text = path//': &'//group//': '//printable(trim(msg), MSG_SHOWN_LEN)
        if (ios == iostat_end) text = text//" (is the closing '/' of the group missing?)"
    end function read_failure

    !> Override one variable of `config` with `setting`, 'group%variable=value': read as the
    !> record '&group variable = value /', quotes added around a text value given without.
    subroutine apply_setting(setting, config, stat)
        character(len=*), intent(in) :: setting
        type(config_t), intent(inout) :: config
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: label, group, variable, value, assignment, blanked
        type(text_t), allocatable :: pieces(:)
        character(len=MSG_LEN) :: msg
        integer :: equals, percent, ios, k
        logical :: control

        label = '--set '//printable(setting)
        ! A tab is a blank, as in the file; any other control character (a newline from
        ! $'...' or a script) would cut the record and drop what follows it unread.
        blanked = setting
        control = .false.
        do k = 1, len(blanked)
            if (blanked(k:k) == achar(9)) blanked(k:k) = ' '
            if (iachar(blanked(k:k)) < 32 .or. iachar(blanked(k:k)) == 127) control = .true.
        end do
        if (control) then
            call stat%fail(STATUS_BAD_INPUT, label//': expected group%variable=value on ' &
                           //'one line: a value may not contain a newline or other control ' &
                           //'character (one --set per variable)')
            return
        end if
        equals = index(blanked, '=')
        percent = index(blanked(:max(equals - 1, 0)), '%')
        if (percent <= 1 .or. equals <= percent + 1) then
            call malformed()
            return
        end if
        group = lowercase(trim(adjustl(blanked(:percent - 1))))
        variable = trim(adjustl(blanked(percent + 1:equals - 1)))
        value = trim(adjustl(blanked(equals + 1:)))
        if (.not. any(KNOWN_GROUPS == group)) then
            call stat%fail(STATUS_BAD_INPUT, label//': unknown namelist group &' &
                           //printable(group) &
                           //' (known groups: '//group_list(KNOWN_GROUPS)//')')
            return
        end if
        if (len(value) == 0) then
            call stat%fail(STATUS_BAD_INPUT, label//': &'//group//': '//printable(variable) &
                           //": no value after '=': expected one")
            if (is_text_variable(group, variable)) &
                stat%message = stat%message//" (an empty text is written '')"
            return
        end if
        if (is_text_variable(group, variable) .and. index('"'//"'", value(1:1)) == 0) then
            value = '"'//doubled_quotes(value)//'"'
        end if
        assignment = variable//' = '//value
        if (index('"'//"'", value(1:1)) == 0 .and. scan(value, '/&$!') > 0) then
            ! They would end the record early or start a comment: part of the value lost.
            call stat%fail(STATUS_BAD_INPUT, label//': &'//group//': '//printable(assignment) &
                           //": expected one value, without '/', '&', '$' or '!'")
            return
        end if
        allocate (pieces(0))
        pieces = split_assignments(assignment)
        if (size(pieces) /= 1) then
            call stat%fail(STATUS_BAD_INPUT, label//': &'//group//': '//printable(variable) &
                           //': expected one variable per --set')
            return
        end if
        call check_assignment(label, group, assignment, stat)
        if (.not. stat%ok()) return
        msg = ''
        call read_record(group, '&'//group//' '//assignment//' /', config, ios, msg)
        if (ios /= 0) then
            call stat%fail(STATUS_BAD_INPUT, label//': &'//group//': '//printable(assignment) &
                           //': '//printable(trim(msg), MSG_SHOWN_LEN) &
                           //expectation(group, assignment))
        end if

    contains

        subroutine malformed()
            call stat%fail(STATUS_BAD_INPUT, label//': expected group%variable=value (such ' &
                           //'as analysis%lambda=2.5)')
        end subroutine malformed

        !> `text` with each double quote doubled, as a double-quoted namelist value needs.
        pure function doubled_quotes(text) result(escaped)
            character(len=*), intent(in) :: text
            character(len=:), allocatable :: escaped
            integer :: k, n
            allocate (character(len=2*len(text)) :: escaped)
            n = 0
            do k = 1, len(text)
                n = n + 1
                escaped(n:n) = text(k:k)
                if (text(k:k) /= '"') cycle
                n = n + 1
                escaped(n:n) = '"'
            end do
            escaped = escaped(:n)
        end function doubled_quotes
    end subroutine apply_setting

    !> A file name fit for a message (see printable).
    pure function shown_path(path) result(shown)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: shown
        shown = printable(path, PATH_SHOWN_LEN)
    end function shown_path

    ! -------------------------------------------------------------------------- paths

    !> Default output directory of a run: output/<input file name without extension>,
    !> relative to the working directory. A stem of dots only ('..nml', '...nml') would
    !> name output/ itself or its parent: the whole name is kept then (output/..nml).
    function default_output_directory(input_path) result(directory)
        character(len=*), intent(in) :: input_path
        character(len=:), allocatable :: directory
        character(len=:), allocatable :: base
        integer :: dot

        base = trim(input_path)
        base = base(index(base, '/', back=.true.) + 1:)
        dot = index(base, '.', back=.true.)
        ! a leading dot starts a hidden name, not a suffix
        if (dot > 1) then
            if (verify(base(:dot - 1), '.') > 0) base = base(:dot - 1)
        end if
        if (len(base) == 0) base = 'nceig'
        directory = 'output/'//base
    end function default_output_directory

    !> `path` as seen from the working directory when written relative to the folder of
    !> `base_file`; absolute and empty paths are returned unchanged.
    function resolve_relative(base_file, path) result(resolved)
        character(len=*), intent(in) :: base_file, path
        character(len=:), allocatable :: resolved
        integer :: slash

        resolved = trim(adjustl(path))
        if (len(resolved) == 0) return
        if (resolved(1:1) == '/') return
        slash = index(trim(base_file), '/', back=.true.)
        if (slash > 0) resolved = base_file(:slash)//resolved
    end function resolve_relative
end module input_config
