! SPDX-License-Identifier: MIT
!> The namelist records: reading one, what a bad assignment expected, and the check that
!> ties the places a variable is named together: the variables each namelist reads, those
!> of input_table (behind the messages, --set and the help) and those of the help text are
!> the same, in the same order. Readers and table are generated from one definition per
!> variable (src/input/input_variables.cmake), so this now guards the generator; the
!> definitions themselves are checked against --help by the test input_definitions.
program test_input_records
    use run_config, only: config_t
    use strings, only: NAME_LEN
    use input_records, only: read_record, reader_variables
    use input_table, only: input_variable_t, load_table, expectation, table_variables, &
                           KNOWN_GROUPS
    use input_help, only: help_text
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t
    type(config_t) :: config
    character(len=256) :: msg
    character(len=NAME_LEN), allocatable :: read_names(:), typed_names(:), help_names(:)
    type(input_variable_t), allocatable :: table(:)
    integer :: ios, g, n_read, n_typed, n_help

    t%name = 'test_input_records'

    msg = ''
    call read_record('mesh', '&mesh nx = 3, element = "Q2" /', config, ios, msg)
    call t%check('read_record: values read, names lowercased, others kept', ios == 0 .and. &
                 config%mesh%nx == 3 .and. config%mesh%element == 'q2' .and. &
                 config%mesh%ny == 8)

    call t%check('expectation: the type of a known variable, the list for an unknown one', &
                 expectation('eigen', 'nev = x') == ' (expected an integer)' .and. &
                 expectation('material', 'young_modulus = 1') == &
                 ' (&material knows: young, poisson)')

    read_names = reader_variables('analysis')
    call t%check('reader_variables: &analysis reads kind and lambda', size(read_names) == 2)
    if (size(read_names) == 2) call t%check('reader_variables: in namelist order', &
                                            read_names(1) == 'kind' .and. &
                                            read_names(2) == 'lambda')

    typed_names = table_variables('branch')
    call t%check('table_variables: the four of &branch', size(typed_names) == 4)

    n_read = 0
    n_typed = 0
    n_help = 0
    do g = 1, size(KNOWN_GROUPS)
        read_names = reader_variables(trim(KNOWN_GROUPS(g)))
        typed_names = table_variables(trim(KNOWN_GROUPS(g)))
        help_names = help_variables(help_text(), trim(KNOWN_GROUPS(g)))
        n_read = n_read + size(read_names)
        n_typed = n_typed + size(typed_names)
        n_help = n_help + size(help_names)
        call t%check('&'//trim(KNOWN_GROUPS(g))//': input_table = namelist', &
                     same_list(typed_names, read_names))
        call t%check('&'//trim(KNOWN_GROUPS(g))//': help text = namelist', &
                     same_list(help_names, read_names))
    end do
    ! the table's groups are KNOWN_GROUPS: then no variable escaped the loop above
    call load_table(table)
    call t%check('every variable counted once in each place', n_read == size(table) .and. &
                 n_typed == size(table) .and. n_help == size(table))
    ! gfortran 12 never frees main-program allocatables: LeakSanitizer would report them.
    deallocate (read_names, typed_names, help_names, table)
    call t%report()

contains

    logical function same_list(a, b)
        character(len=*), intent(in) :: a(:), b(:)
        same_list = size(a) == size(b)
        if (same_list) same_list = all(a == b)
    end function same_list

    !> The variables the help text documents under '&group': the names before ' = ' of its
    !> indented lines, where 'f1, f2 = ...' documents two.
    function help_variables(help, group) result(names)
        character(len=*), intent(in) :: help, group
        character(len=NAME_LEN), allocatable :: names(:)
        character(len=:), allocatable :: line, left
        integer :: start, finish, equals, comma
        logical :: inside
        allocate (names(0))
        inside = .false.
        start = 1
        do while (start <= len(help))
            finish = index(help(start:), new_line('a')) + start - 1
            if (finish < start) finish = len(help) + 1
            line = help(start:finish - 1)
            start = finish + 1
            if (len(line) == 0) cycle
            if (line(1:1) == '&') then
                inside = line(2:) == group .or. index(line, '&'//group//' ') == 1
                cycle
            end if
            if (.not. inside .or. line(1:4) /= '    ') cycle
            equals = index(line, ' = ')
            if (equals == 0) cycle
            left = adjustl(line(:equals - 1))
            do
                comma = index(left, ',')
                if (comma == 0) exit
                names = [character(len=NAME_LEN) :: names, left(:comma - 1)]
                left = adjustl(left(comma + 1:))
            end do
            names = [character(len=NAME_LEN) :: names, left]
        end do
    end function help_variables
end program test_input_records
