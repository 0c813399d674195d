! SPDX-License-Identifier: MIT
!> The input of a study (nceig-study): a namelist file with a `&study` group (the geometries,
!> Poisson ratios, lambdas and quantities of the map) and the usual nceig groups (&mesh,
!> &material, &eigen, &adapt, &output) as the template of every point. This module reads and
!> judges the &study group and keeps the template's text, line for line, for the input
!> reader of nceig itself (input_config), which then judges every point as a run would.
module study_input
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use namelist_scan, only: group_text_t, text_t, scan_groups, split_assignments, body_line
    use input_table, only: KNOWN_GROUPS
    use input_config, only: resolve_relative
    use filesystem, only: file_exists, is_directory
    use strings, only: lowercase, printable, to_string, split_words, LIST_LEN
    use ieee_arithmetic, only: ieee_is_finite
    implicit none
    private
    public :: study_t, read_study, MAX_GEOMETRIES, MAX_POISSON, MAX_STUDY_LAMBDAS

    integer, parameter :: MAX_GEOMETRIES = 20      !! entries of &study geometry and widths
    integer, parameter :: MAX_POISSON = 50         !! entries of &study poisson
    integer, parameter :: MAX_STUDY_LAMBDAS = 1000 !! as &sweep lambdas of a run
    integer, parameter :: GEOMETRY_LEN = 1024
    integer, parameter :: MSG_LEN = 1024
    integer, parameter :: SHOWN_LEN = 200
    real(wp), parameter :: UNSET = huge(1.0_wp)   !! a list entry the file did not give
    !> Template groups a study owns (it sets the analysis and the lambdas of every point).
    character(len=*), parameter :: OWNED_GROUPS(4) = [character(len=8) :: 'analysis', &
                                                      'sweep', 'branch', 'solve']

    !> A validated study: one geometry per entry (`kind` 'rectangle' with its width, or
    !> 'geo' / 'msh' with its path resolved against the study file's folder).
    type :: study_t
        character(len=:), allocatable :: path        !! the study file
        character(len=GEOMETRY_LEN), allocatable :: geometry(:)   !! path or 'rectangle'
        character(len=12), allocatable :: geometry_kind(:)         !! rectangle, geo, msh
        character(len=64), allocatable :: label(:)  !! file stem or rectangle_w<width>
        real(wp), allocatable :: width(:)            !! rectangle width (0 for a file)
        real(wp), allocatable :: poisson(:)
        real(wp), allocatable :: lambdas(:)
        logical :: c_n = .true.          !! quantities holds 'c_n'
        logical :: thresholds = .true.   !! quantities holds 'thresholds'
        real(wp) :: mesh_size = 0.5_wp   !! Gmsh element size of a .geo geometry
        logical :: task_plots = .false.  !! each run draws its own pictures
        character(len=:), allocatable :: template   !! the other groups, line for line
        logical :: adapt_given = .false.     !! the template has an &adapt group
        logical :: strategy_given = .false.  !! ... which sets strategy
        logical :: tolerance_given = .false. !! ... which sets tolerance
    end type study_t

contains

    !> Read the study file `path`: its &study group into `study` (validated), the other
    !> groups as `study%template`, the same text on the same lines with the &study group's
    !> lines left empty, so that a message about the template names the right line. Any
    !> problem: STATUS_BAD_INPUT, one line naming the file, the group, the variable and
    !> what was expected.
    subroutine read_study(path, study, stat)
        character(len=*), intent(in) :: path
        type(study_t), intent(out) :: study
        type(status_t), intent(out) :: stat
        type(group_text_t), allocatable :: groups(:)
        character(len=:), allocatable :: shown
        character(len=MSG_LEN) :: msg
        integer :: unit, ios, i, k

        study%path = path
        shown = printable(path, SHOWN_LEN)
        if (is_directory(path)) then
            call stat%fail(STATUS_BAD_INPUT, shown//': is a directory: expected a study file')
            return
        end if
        open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
        if (ios /= 0) then
            call stat%fail(STATUS_BAD_INPUT, shown//': cannot open the study file: ' &
                           //printable(trim(msg), SHOWN_LEN))
            return
        end if
        call scan_groups(unit, path, [KNOWN_GROUPS, 'study   '], groups, stat)
        close (unit)
        if (.not. stat%ok()) return

        k = 0
        do i = 1, size(groups)
            if (groups(i)%name == 'study') k = i
            if (any(OWNED_GROUPS == groups(i)%name)) then
                call stat%fail(STATUS_BAD_INPUT, shown//': line '//to_string(groups(i)%line) &
                               //': &'//groups(i)%name//': a study sets the analysis and ' &
                               //'the lambdas of every point from &study: expected no &' &
                               //groups(i)%name//' group')
                return
            end if
            call check_template_group(shown, groups(i), study, stat)
            if (.not. stat%ok()) return
        end do
        if (k == 0) then
            call stat%fail(STATUS_BAD_INPUT, shown//': &study: missing: expected a &study ' &
                           //'group with geometry, poisson and lambda (nceig-study --help)')
            return
        end if
        call read_study_group(shown, groups(k), study, stat)
        if (.not. stat%ok()) return
        study%template = template_text(groups)
    end subroutine read_study

    !> The template's own groups: no &mesh source or file (the geometries are &study's) and
    !> no &output directory (each point writes in its task's folder); notes whether &adapt
    !> sets its strategy and tolerance (hp to 1e-8 by default).
    subroutine check_template_group(shown, group, study, stat)
        character(len=*), intent(in) :: shown
        type(group_text_t), intent(in) :: group
        type(study_t), intent(inout) :: study
        type(status_t), intent(inout) :: stat
        type(text_t), allocatable :: pieces(:)
        character(len=:), allocatable :: name
        integer :: i
        if (group%name == 'study') return
        if (group%name == 'adapt') study%adapt_given = .true.
        pieces = split_assignments(group%body)
        do i = 1, size(pieces)
            name = assigned_name(pieces(i)%text)
            if (group%name == 'adapt' .and. name == 'strategy') study%strategy_given = .true.
            if (group%name == 'adapt' .and. name == 'tolerance') study%tolerance_given = .true.
            if ((group%name == 'mesh' .and. (name == 'source' .or. name == 'file')) .or. &
                (group%name == 'output' .and. name == 'directory')) then
                call stat%fail(STATUS_BAD_INPUT, shown//': line ' &
                               //to_string(line_of(group, pieces, i))//': &'//group%name &
                               //': '//name//': a study sets it for every point (' &
                               //trim(merge('&study geometry ', 'the task folders', &
                                       group%name == 'mesh'))//'): expected no '//name)
                return
            end if
        end do
    end subroutine check_template_group

    !> The &study group: read as a namelist; when the read fails, each assignment alone,
    !> to name the culprit; then every value judged.
    subroutine read_study_group(shown, group, out, stat)
        character(len=*), intent(in) :: shown
        type(group_text_t), intent(in) :: group
        type(study_t), intent(inout) :: out
        type(status_t), intent(inout) :: stat
        character(len=GEOMETRY_LEN) :: geometry(MAX_GEOMETRIES)
        real(wp) :: widths(MAX_GEOMETRIES), poisson(MAX_POISSON), lambda(MAX_STUDY_LAMBDAS)
        real(wp) :: lambda_min, lambda_max, mesh_size
        integer :: n_lambda
        character(len=64) :: quantities
        logical :: task_plots
        namelist /study/ geometry, widths, poisson, lambda, lambda_min, lambda_max, n_lambda, &
            quantities, mesh_size, task_plots
        type(text_t), allocatable :: pieces(:)
        character(len=MSG_LEN) :: msg
        character(len=:), allocatable :: record
        integer :: ios, i

        call set_defaults()
        record = '&study '//group%body//' /'
        read (record, nml=study, iostat=ios, iomsg=msg)
        if (ios /= 0) then
            pieces = split_assignments(group%body)
            do i = 1, size(pieces)
                call set_defaults()
                record = '&study '//pieces(i)%text//' /'
                read (record, nml=study, iostat=ios, iomsg=msg)
                if (ios /= 0) then
                    call bad(assigned_name(pieces(i)%text), trim(pieces(i)%text), &
                             line_of(group, pieces, i))
                    return
                end if
            end do
            call stat%fail(STATUS_BAD_INPUT, shown//': line '//to_string(group%line) &
                           //': &study: '//printable(trim(msg), SHOWN_LEN))
            return
        end if
        call judge()
    contains
        subroutine set_defaults()
            geometry = ''
            geometry(1) = 'rectangle'
            widths = UNSET
            poisson = UNSET
            lambda = UNSET
            lambda_min = UNSET
            lambda_max = UNSET
            n_lambda = 0
            quantities = 'c_n thresholds'
            mesh_size = 0.5_wp
            task_plots = .false.
        end subroutine set_defaults

        !> The culprit `name` (as `text` gave it, on `line`) and what it expects.
        subroutine bad(name, text, line)
            character(len=*), intent(in) :: name, text
            integer, intent(in) :: line
            character(len=:), allocatable :: where
            where = shown//': line '//to_string(line)//': &study: '
            if (len(expectation(name)) == 0) then
                call stat%fail(STATUS_BAD_INPUT, where//'unknown variable '// &
                               printable(name, SHOWN_LEN)//': expected one of geometry, ' &
                               //'widths, poisson, lambda, lambda_min, lambda_max, ' &
                               //'n_lambda, quantities, mesh_size, task_plots')
            else
                call stat%fail(STATUS_BAD_INPUT, where//printable(text, SHOWN_LEN) &
                               //': expected '//expectation(name))
            end if
        end subroutine bad

        subroutine refuse(name, value)
            character(len=*), intent(in) :: name, value
            call stat%fail(STATUS_BAD_INPUT, shown//': line '//to_string(group%line) &
                           //': &study: '//name//' = '//printable(value, SHOWN_LEN) &
                           //': expected '//expectation(name))
        end subroutine refuse

        subroutine judge()
            character(len=LIST_LEN), allocatable :: words(:)
            character(len=:), allocatable :: entry
            integer :: n_geometry, n_width, n_poisson, n_lambdas, j, kind_index
            real(wp) :: step

            n_geometry = count(len_trim(geometry) > 0)
            if (n_geometry == 0 .or. any(len_trim(geometry(1:max(n_geometry, 1))) == 0)) then
                call refuse('geometry', '')
                return
            end if
            if (count(lowercase(geometry(1:n_geometry)) == 'rectangle') > 1) then
                call refuse('geometry', 'rectangle twice (list the widths in widths)')
                return
            end if
            n_width = count(widths < UNSET)
            if (any(widths(1:n_width) >= UNSET) .or. any(.not. ieee_is_finite(widths)) .or. &
                any(widths(1:n_width) <= 0.0_wp)) then
                call refuse('widths', 'a value that is not a positive finite number')
                return
            end if
            if (n_width > 0 .and. .not. any(lowercase(geometry(1:n_geometry)) == 'rectangle')) &
                then
                call refuse('widths', 'given without geometry = ''rectangle''')
                return
            end if
            n_poisson = count(poisson < UNSET)
            if (n_poisson == 0) then
                call refuse('poisson', 'nothing')
                return
            end if
            if (any(poisson(1:n_poisson) >= UNSET) .or. any(.not. ieee_is_finite(poisson)) &
                .or. any(poisson(1:n_poisson) <= -1.0_wp .or. poisson(1:n_poisson) >= 0.5_wp)) &
                then
                call refuse('poisson', 'a value outside (-1, 0.5)')
                return
            end if
            do j = 2, n_poisson
                if (any(poisson(1:j - 1) <= poisson(j) .and. poisson(1:j - 1) >= poisson(j))) &
                    then
                    call refuse('poisson', 'a value twice')
                    return
                end if
            end do
            out%poisson = poisson(1:n_poisson)

            ! The quantities: 'c_n', 'thresholds', both ('c_n thresholds' or 'both').
            call split_words(lowercase(quantities), words)
            out%c_n = .false.
            out%thresholds = .false.
            do j = 1, size(words)
                select case (trim(words(j)))
                case ('c_n'); out%c_n = .true.
                case ('thresholds'); out%thresholds = .true.
                case ('both'); out%c_n = .true.; out%thresholds = .true.
                case default
                    call refuse('quantities', "'"//trim(quantities)//"'")
                    return
                end select
            end do
            if (size(words) == 0) then
                call refuse('quantities', "''")
                return
            end if

            ! The lambdas: a list, or a range.
            n_lambdas = count(lambda < UNSET)
            if (n_lambdas > 0) then
                if (any(lambda(1:n_lambdas) >= UNSET) .or. any(.not. ieee_is_finite(lambda)) &
                    .or. lambda_min < UNSET .or. lambda_max < UNSET .or. n_lambda /= 0) then
                    call refuse('lambda', 'a list with a gap, a value not finite, or a list ' &
                                //'and a range')
                    return
                end if
                out%lambdas = lambda(1:n_lambdas)
            else if (lambda_min < UNSET .or. lambda_max < UNSET .or. n_lambda /= 0) then
                if (.not. (ieee_is_finite(lambda_min) .and. ieee_is_finite(lambda_max)) .or. &
                    lambda_min >= UNSET .or. lambda_max >= UNSET) then
                    call refuse('lambda_min', 'missing or not finite')
                    return
                end if
                if (lambda_min >= lambda_max) then
                    call refuse('lambda_max', 'not above lambda_min')
                    return
                end if
                if (n_lambda < 2 .or. n_lambda > MAX_STUDY_LAMBDAS) then
                    call refuse('n_lambda', to_string(n_lambda))
                    return
                end if
                step = (lambda_max - lambda_min)/real(n_lambda - 1, wp)
                out%lambdas = [(lambda_min + real(j, wp)*step, j=0, n_lambda - 1)]
                out%lambdas(n_lambda) = lambda_max
            else if (out%c_n) then
                call refuse('lambda', 'nothing (c_n needs lambdas)')
                return
            else
                allocate (out%lambdas(0))
            end if

            if (.not. (ieee_is_finite(mesh_size) .and. mesh_size > 0.0_wp)) then
                call refuse('mesh_size', 'not a positive finite number')
                return
            end if
            out%mesh_size = mesh_size
            out%task_plots = task_plots

            ! The geometries: the rectangle once per width (or once, the template's width).
            allocate (out%geometry(0), out%geometry_kind(0), out%label(0), out%width(0))
            do j = 1, n_geometry
                entry = trim(geometry(j))
                if (lowercase(entry) == 'rectangle') then
                    if (n_width == 0) then
                        call add_geometry('rectangle', 'rectangle', 'rectangle', 0.0_wp)
                    else
                        do kind_index = 1, n_width
                            call add_geometry('rectangle', 'rectangle', 'rectangle_w' &
                                              //short_text(widths(kind_index)), &
                                              widths(kind_index))
                        end do
                    end if
                    cycle
                end if
                if (scan(entry, achar(9)//achar(10)//achar(13)) > 0) then
                    call refuse('geometry', "a path with a tab or a line break")
                    return
                end if
                kind_index = len(entry) - 3
                if (kind_index < 2) kind_index = 1
                if (lowercase(entry(kind_index:)) /= '.geo' .and. &
                    lowercase(entry(kind_index:)) /= '.msh') then
                    call refuse('geometry', "'"//entry//"'")
                    return
                end if
                entry = resolve_relative(out%path, entry)
                if (.not. file_exists(entry)) then
                    call refuse('geometry', "'"//trim(geometry(j))//"' (no such file)")
                    return
                end if
                if (is_directory(entry)) then
                    call refuse('geometry', "'"//trim(geometry(j))//"' (a folder)")
                    return
                end if
                call add_geometry(entry, lowercase(entry(len(entry) - 2:)), &
                                  stem(trim(geometry(j))), 0.0_wp)
            end do
            do j = 2, size(out%label)
                if (any(out%label(1:j - 1) == out%label(j))) then
                    call refuse('geometry', "two entries named '"//trim(out%label(j))// &
                                "' (rename one file)")
                    return
                end if
            end do
        end subroutine judge

        subroutine add_geometry(entry, kind, label, width)
            character(len=*), intent(in) :: entry, kind, label
            real(wp), intent(in) :: width
            out%geometry = [character(len=GEOMETRY_LEN) :: out%geometry, entry]
            out%geometry_kind = [character(len=12) :: out%geometry_kind, kind]
            out%label = [character(len=64) :: out%label, label]
            out%width = [out%width, width]
        end subroutine add_geometry
    end subroutine read_study_group

    !> What a &study variable expects ('' for an unknown name).
    pure function expectation(name) result(text)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: text
        select case (lowercase(name))
        case ('geometry')
            text = "'rectangle' (the template's rectangle, once per width) or Gmsh .geo " &
                   //"or .msh files, relative to the study file (up to 20 entries, " &
                   //"each named once)"
        case ('widths')
            text = "rectangle widths > 0 (up to 20), with geometry = 'rectangle'"
        case ('poisson')
            text = 'Poisson ratios -1 < nu < 0.5, each once (1 to 50 values)'
        case ('lambda')
            text = 'a list of up to 1000 finite lambdas, or lambda_min, lambda_max ' &
                   //'and n_lambda instead'
        case ('lambda_min', 'lambda_max')
            text = 'finite numbers with lambda_min < lambda_max (with n_lambda)'
        case ('n_lambda')
            text = 'an integer from 2 to 1000 (with lambda_min and lambda_max)'
        case ('quantities')
            text = "'c_n', 'thresholds' or 'c_n thresholds' (also 'both')"
        case ('mesh_size')
            text = 'the Gmsh element size of a .geo geometry, a number > 0'
        case ('task_plots')
            text = '.true. or .false.'
        case default
            text = ''
        end select
    end function expectation

    !> The other groups of the file on their own lines (the &study group's lines empty).
    function template_text(groups) result(text)
        type(group_text_t), intent(in) :: groups(:)
        character(len=:), allocatable :: text
        character(len=1), parameter :: NL = achar(10)
        integer :: i, line, j, first, last, n_pieces
        text = ''
        line = 1
        do i = 1, size(groups)
            if (groups(i)%name == 'study') cycle
            do while (line < groups(i)%line)
                text = text//NL
                line = line + 1
            end do
            text = text//'&'//groups(i)%name//' '
            n_pieces = 0
            if (allocated(groups(i)%line_offsets)) n_pieces = size(groups(i)%line_offsets)
            first = 1
            do j = 1, n_pieces + 1
                last = len(groups(i)%body)
                if (j <= n_pieces) last = groups(i)%line_offsets(j) - 1
                text = text//groups(i)%body(first:last)
                if (j <= n_pieces) then
                    text = text//NL
                    line = line + 1
                    first = last + 1
                end if
            end do
            text = text//' /'//NL
            line = line + 1
        end do
    end function template_text

    !> The line of the file where assignment `i` of `group` starts.
    integer function line_of(group, pieces, i)
        type(group_text_t), intent(in) :: group
        type(text_t), intent(in) :: pieces(:)
        integer, intent(in) :: i
        integer :: offset
        offset = index(group%body, pieces(i)%text)
        line_of = group%line
        if (offset > 0) line_of = body_line(group, offset)
    end function line_of

    !> The lowercased variable name an assignment 'name = value' or 'name(3) = v' starts with.
    pure function assigned_name(assignment) result(name)
        character(len=*), intent(in) :: assignment
        character(len=:), allocatable :: name
        integer :: stop_at
        stop_at = scan(assignment, '=(% ')
        if (stop_at == 0) stop_at = len(assignment) + 1
        name = lowercase(trim(adjustl(assignment(1:stop_at - 1))))
    end function assigned_name

    !> A file name without its folder and extension, for the tables and picture titles (at
    !> most 64 characters): letters, digits, '.', '-' and '_', any other character as '_'.
    pure function stem(path) result(name)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: name
        character(len=*), parameter :: KEPT = 'abcdefghijklmnopqrstuvwxyz' &
                                              //'ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-'
        integer :: slash, dot, i
        slash = index(path, '/', back=.true.)
        dot = index(path, '.', back=.true.)
        if (dot <= slash) dot = len(path) + 1
        name = path(slash + 1:min(dot - 1, slash + 64))
        do i = 1, len(name)
            if (index(KEPT, name(i:i)) == 0) name(i:i) = '_'
        end do
        if (len(name) == 0) name = '_'
    end function stem

    !> A width as a short label: 2.0 -> '2', 0.5 -> '0.5'.
    pure function short_text(x) result(text)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: buffer
        integer :: last
        write (buffer, '(f0.6)') x
        text = trim(adjustl(buffer))
        last = len(text)
        do while (last > 1 .and. text(last:last) == '0')
            last = last - 1
        end do
        if (text(last:last) == '.') last = last - 1
        text = text(1:last)
        if (text(1:1) == '.') text = '0'//text
    end function short_text
end module study_input
