! SPDX-License-Identifier: MIT
!> Reads the namelist input file into a validated `config_t`, and documents it (`help_text`).
!> Every default lives in `run_config`; this module only reads, checks and describes.
module input_config
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use run_config, only: config_t, mesh_config_t, material_config_t, analysis_config_t, &
                          eigen_config_t, output_config_t, branch_config_t, solve_config_t, &
                          sweep_config_t, MAX_SWEEP_LAMBDAS, PATH_LEN, count_set_lambdas, &
                          lambda_is_set
    use strings, only: to_string, lowercase, split_words, count_names, normalized_list, &
                       NAME_LEN, LIST_LEN
    use text_file, only: read_line
    use real_format, only: real_to_text
    use ieee_arithmetic, only: ieee_is_finite
    use iso_fortran_env, only: iostat_end
    use filesystem, only: is_directory
    implicit none
    private
    public :: read_input, help_text, default_output_directory, resolve_relative
    public :: KNOWN_GROUPS, MESH_SOURCES, ELEMENT_NAMES, DIAGONALS, RECTANGLE_SIDES, &
              ACCEPTED_ANALYSES, ACCEPTED_SOLVERS, MAX_CELLS_PER_SIDE, SOLVE_DATA, SOLVE_STARTS
    public :: SWEEP_SPACINGS, VTK_FORMATS

    !> Namelist groups, in the order they are read and documented.
    character(len=*), parameter :: KNOWN_GROUPS(*) = [character(len=8) :: &
                                   'mesh', 'material', 'analysis', 'eigen', 'output', 'sweep', &
                                   'branch', 'solve']
    character(len=*), parameter :: MESH_SOURCES(*) = [character(len=9) :: 'rectangle', 'gmsh']
    character(len=*), parameter :: ELEMENT_NAMES(*) = [character(len=2) :: &
                                   'p1', 'q1', 'p2', 'q2']
    character(len=*), parameter :: DIAGONALS(*) = [character(len=5) :: 'right', 'left']
    character(len=*), parameter :: RECTANGLE_SIDES(*) = [character(len=6) :: &
                                   'top', 'bottom', 'left', 'right']
    !> Analyses this build can run; each new analysis adds its name here.
    character(len=*), parameter :: ACCEPTED_ANALYSES(*) = [character(len=12) :: 'eigen', &
                                   'threshold', 'lambda_sweep', 'branch', 'solve']
    !> Eigensolvers this build offers.
    character(len=*), parameter :: ACCEPTED_SOLVERS(*) = [character(len=6) :: 'dense', &
                                                          'arpack', 'auto']
    integer, parameter :: MAX_CELLS_PER_SIDE = 1000000
    character(len=*), parameter :: SWEEP_SPACINGS(*) = [character(len=6) :: 'linear', 'log']
    integer, parameter :: MAX_SWEEP_POINTS = 100000   !! n_lambda of a &sweep range
    !> &output vtk_format: the encodings of vtk_writer (VTK_BINARY, VTK_ASCII).
    character(len=*), parameter :: VTK_FORMATS(*) = [character(len=6) :: 'binary', 'ascii']
    !> &solve data: loads of the input, or the data of SPEC section 5 at the critical point.
    character(len=*), parameter :: SOLVE_DATA(*) = [character(len=6) :: 'given', 'branch']
    !> &solve start: the starting guesses of the Newton iteration.
    character(len=*), parameter :: SOLVE_STARTS(*) = [character(len=6) :: &
                                   'zero', 'branch', 'random', 'mode']
    !> 'group variable:expected value' of every namelist variable, for messages about a
    !> value the runtime could not read. New groups add their lines.
    character(len=*), parameter :: VARIABLE_TYPES(*) = [character(len=64) :: &
        'mesh source:a quoted name', 'mesh file:a quoted path', 'mesh width:a real number', &
        'mesh height:a real number', 'mesh nx:an integer', 'mesh ny:an integer', &
        'mesh element:a quoted name', 'mesh diagonal:a quoted name', &
        'mesh dirichlet:a quoted list of names', 'mesh neumann:a quoted list of names', &
        'mesh contact:a quoted name', 'material young:a real number', &
        'material poisson:a real number', 'analysis kind:a quoted name', &
        'analysis lambda:a real number', 'eigen solver:a quoted name', &
        'eigen nev:an integer', 'eigen target:a real number', 'eigen tol:a real number', &
        'eigen maxit:an integer', 'eigen ncv:an integer', 'eigen dense_max_contact:an integer', &
        'output directory:a quoted path', 'output vtk:.true. or .false.', &
        'output modes:an integer', 'output matrices:.true. or .false.', &
        'output vtk_format:a quoted name', &
        'sweep lambda_min:a real number', 'sweep lambda_max:a real number', &
        'sweep n_lambda:an integer', 'sweep spacing:a quoted name', &
        'sweep lambdas:a list of real numbers', 'sweep plot:.true. or .false.', &
        'branch alpha:a real number', 'branch beta:a real number', &
        'branch n_delta:an integer', 'branch write_members:an integer', &
        'solve data:a quoted name', 'solve c_n:a real number', 'solve c_t:a real number', &
        'solve critical_factor:a real number', 'solve f1:a real number', &
        'solve f2:a real number', 'solve t1:a real number', 'solve t2:a real number', &
        'solve u_d1:a real number', 'solve u_d2:a real number', 'solve start:a quoted name', &
        'solve start_delta:a real number', 'solve start_scale:a real number', &
        'solve start_noise:a real number', 'solve seed:an integer', 'solve tol:a real number', &
        'solve max_iterations:an integer']

    integer, parameter :: MSG_LEN = 1024     !! iomsg buffers
    integer, parameter :: HELP_COLUMN = 28   !! where descriptions start in the help text
    character(len=*), parameter :: NAME_CHARS = &
        'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_'
    character(len=*), parameter :: BLANKS = ' '//achar(9)   !! blanks outside groups

    !> One namelist group as found in the file: lines joined by blanks, comments removed.
    type :: group_text_t
        character(len=:), allocatable :: name   !! lowercased, without the '&'
        character(len=:), allocatable :: body   !! text between '&name' and the closing '/'
        integer :: line = 0                     !! line of the '&name'
    end type group_text_t

    !> A piece of text, for arrays of strings of different lengths.
    type :: text_t
        character(len=:), allocatable :: text
    end type text_t

    !> Reads one '&group assignment /' record with the group's namelist.
    abstract interface
        subroutine record_reader(record, config, ios, msg)
            import :: config_t
            character(len=*), intent(in) :: record
            type(config_t), intent(inout) :: config
            integer, intent(out) :: ios
            character(len=*), intent(inout) :: msg
        end subroutine record_reader
    end interface

contains

    !> Read and validate the namelist file `path`. Groups are read in the order of
    !> KNOWN_GROUPS; an absent group keeps its defaults. Names (source, element, side
    !> lists, kind, solver) are stored trimmed and lowercased. The mesh `file` is resolved
    !> relative to the input file's folder, and an empty output `directory` becomes
    !> default_output_directory(path). Any problem gives STATUS_BAD_INPUT with a one-line
    !> message naming the file, the group and the variable.
    subroutine read_input(path, config, stat)
        character(len=*), intent(in) :: path
        type(config_t), intent(out) :: config
        type(status_t), intent(out) :: stat
        type(group_text_t), allocatable :: groups(:)
        character(len=:), allocatable :: input
        character(len=MSG_LEN) :: msg
        integer :: unit, ios

        input = trim(path)
        config%input_file = input
        ! Opening a directory succeeds and reads as an empty file: all defaults, silently.
        if (is_directory(input)) then
            call stat%fail(STATUS_BAD_INPUT, input//': is a directory: expected a namelist ' &
                           //'input file')
            return
        end if
        open (newunit=unit, file=input, status='old', action='read', iostat=ios, iomsg=msg)
        if (ios /= 0) then
            call stat%fail(STATUS_BAD_INPUT, input//': cannot open input file: '//trim(msg))
            return
        end if
        call scan_groups(unit, input, groups, stat)
        if (stat%ok()) call read_group(input, 'mesh', groups, mesh_record, config, stat)
        if (stat%ok()) call read_group(input, 'material', groups, material_record, config, &
                                       stat)
        if (stat%ok()) call read_group(input, 'analysis', groups, analysis_record, config, &
                                       stat)
        if (stat%ok()) call read_group(input, 'eigen', groups, eigen_record, config, stat)
        if (stat%ok()) call read_group(input, 'output', groups, output_record, config, stat)
        if (stat%ok()) call read_group(input, 'sweep', groups, sweep_record, config, stat)
        if (stat%ok()) call read_group(input, 'branch', groups, branch_record, config, stat)
        if (stat%ok()) call read_group(input, 'solve', groups, solve_record, config, stat)
        close (unit)
        if (.not. stat%ok()) return

        call validate_mesh(config%mesh, input, stat)
        if (stat%ok()) call validate_material(config%material, input, stat)
        if (stat%ok()) call validate_analysis(config%analysis, input, stat)
        if (stat%ok()) call validate_eigen(config%eigen, input, stat)
        if (stat%ok()) call validate_output(config%output, input, stat)
        if (stat%ok()) call validate_sweep(config%sweep, input, stat)
        if (stat%ok()) call validate_branch(config%branch, input, stat)
        if (stat%ok()) call validate_solve(config%solve, input, stat)
        if (.not. stat%ok()) return

        if (len_trim(config%mesh%file) > 0) then
            config%mesh%file = resolve_relative(input, config%mesh%file)
        end if
        if (len_trim(config%output%directory) == 0) then
            config%output%directory = default_output_directory(input)
        end if
    end subroutine read_input

    ! ---------------------------------------------------------------- finding the groups

    !> List the groups of the file before reading them, so that an absent group is told
    !> apart from a broken one (both end a namelist read at end of file), and a misspelt
    !> group name, which the runtime would silently skip, is an error.
    subroutine scan_groups(unit, path, groups, stat)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: path
        type(group_text_t), allocatable, intent(out) :: groups(:)
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: line, name, body
        character(len=MSG_LEN) :: msg
        character(len=1) :: c, quote
        integer :: ios, line_number, group_line, i, j
        logical :: inside

        allocate (groups(0))
        inside = .false.
        quote = ' '
        line_number = 0
        group_line = 0
        body = ''
        rewind (unit)
        do
            call read_line(unit, line, ios, msg)
            if (ios == iostat_end) exit
            if (ios /= 0) then
                call stat%fail(STATUS_BAD_INPUT, path//': cannot read input file: '//trim(msg))
                return
            end if
            line_number = line_number + 1
            i = 1
            do while (i <= len(line))
                c = line(i:i)
                if (quote /= ' ') then
                    ! Inside a quoted value: '&', '/' and '!' are text ('' toggles twice).
                    if (c == quote) quote = ' '
                    body = body//c
                else if (c == '!') then
                    exit
                else if (inside .and. (c == '"' .or. c == "'")) then
                    quote = c
                    body = body//c
                else if (c == '&' .or. c == '$') then
                    j = i + 1
                    do while (j <= len(line))
                        if (index(NAME_CHARS, line(j:j)) == 0) exit
                        j = j + 1
                    end do
                    name = lowercase(line(i + 1:j - 1))
                    ! '&end' closes a group; a new '&name' inside one means a missing '/'.
                    if (inside .and. name == 'end') then
                        call close_group()
                    else if (inside) then
                        call unclosed()
                        return
                    end if
                    if (name /= 'end' .and. len(name) > 0) then
                        inside = .true.
                        group_line = line_number
                        body = ''
                        call append_group(groups, name, group_line)
                    end if
                    i = j
                    cycle
                else if (inside .and. c == '/') then
                    call close_group()
                else if (inside) then
                    body = body//c
                else if (index(BLANKS//achar(13), c) == 0) then
                    ! The runtime would skip it; it is garbage or a group without its '&'.
                    call stat%fail(STATUS_BAD_INPUT, path//': line '//to_string(line_number) &
                        //', column '//to_string(i)//': text outside any namelist group: ' &
                        //"expected '&group name = value ... /' or a '!' comment")
                    return
                end if
                i = i + 1
            end do
            if (inside) body = body//' '
        end do
        if (inside) then
            call unclosed()
            return
        end if

        do i = 1, size(groups)
            if (.not. any(KNOWN_GROUPS == groups(i)%name)) then
                call stat%fail(STATUS_BAD_INPUT, path//': line '//to_string(groups(i)%line) &
                               //': unknown namelist group &'//groups(i)%name &
                               //' (known groups: '//group_list()//')')
                return
            end if
            do j = 1, i - 1
                if (groups(j)%name == groups(i)%name) then
                    call stat%fail(STATUS_BAD_INPUT, path//': line ' &
                                   //to_string(groups(i)%line)//': namelist group &' &
                                   //groups(i)%name//' appears twice (first on line ' &
                                   //to_string(groups(j)%line)//'); merge them')
                    return
                end if
            end do
        end do

    contains

        subroutine close_group()
            groups(size(groups))%body = body
            inside = .false.
            quote = ' '
        end subroutine close_group

        subroutine unclosed()
            character(len=:), allocatable :: why
            why = ''
            if (quote /= ' ') why = ' (a quoted value is not closed)'
            call stat%fail(STATUS_BAD_INPUT, path//': line '//to_string(group_line)//': &' &
                           //groups(size(groups))%name//": the group has no closing '/'"//why)
        end subroutine unclosed
    end subroutine scan_groups

    !> groups = [groups, group_text_t(name, '', line)] without the array constructor, whose
    !> temporary copies of allocatable components gfortran 12 never frees (LeakSanitizer).
    subroutine append_group(groups, name, line)
        type(group_text_t), allocatable, intent(inout) :: groups(:)
        character(len=*), intent(in) :: name
        integer, intent(in) :: line
        type(group_text_t), allocatable :: grown(:)
        integer :: i
        allocate (grown(size(groups) + 1))
        do i = 1, size(groups)
            call move_alloc(groups(i)%name, grown(i)%name)
            call move_alloc(groups(i)%body, grown(i)%body)
            grown(i)%line = groups(i)%line
        end do
        grown(size(grown))%name = name
        grown(size(grown))%body = ''
        grown(size(grown))%line = line
        call move_alloc(grown, groups)
    end subroutine append_group

    !> Text of group `name` as scanned, or '' when the file lacks it.
    function group_body(groups, name) result(body)
        type(group_text_t), intent(in) :: groups(:)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: body
        integer :: i
        body = ''
        do i = 1, size(groups)
            if (groups(i)%name == name) then
                body = groups(i)%body
                return
            end if
        end do
    end function group_body

    pure logical function has_group(groups, name)
        type(group_text_t), intent(in) :: groups(:)
        character(len=*), intent(in) :: name
        integer :: i
        has_group = .false.
        do i = 1, size(groups)
            if (groups(i)%name == name) has_group = .true.
        end do
    end function has_group

    !> The assignments 'name = value' of a group body, to find the one a failed read
    !> choked on: the runtime's message alone does not always name the variable.
    function split_assignments(body) result(pieces)
        character(len=*), intent(in) :: body
        type(text_t), allocatable :: pieces(:)
        integer, allocatable :: starts(:)
        character(len=1) :: quote
        integer :: i, j, last

        allocate (starts(0))
        quote = ' '
        do i = 1, len(body)
            if (quote /= ' ') then
                if (body(i:i) == quote) quote = ' '
            else if (body(i:i) == '"' .or. body(i:i) == "'") then
                quote = body(i:i)
            else if (body(i:i) == '=') then
                j = len_trim(body(:i - 1))
                do while (j >= 1)
                    if (index(NAME_CHARS//'%()', body(j:j)) == 0) exit
                    j = j - 1
                end do
                if (j + 1 <= len_trim(body(:i - 1))) starts = [starts, j + 1]
            end if
        end do
        allocate (pieces(size(starts)))
        do i = 1, size(starts)
            last = len(body)
            if (i < size(starts)) last = starts(i + 1) - 1
            pieces(i)%text = trim(body(starts(i):last))
            ! Drop the value separator that ends all but the last assignment.
            j = len(pieces(i)%text)
            if (j > 0) then
                if (pieces(i)%text(j:j) == ',') pieces(i)%text = trim(pieces(i)%text(:j - 1))
            end if
        end do
    end function split_assignments

    !> Message for a failed read of group `group` when no single assignment was to blame.
    function read_failure(path, group, ios, msg) result(text)
        character(len=*), intent(in) :: path, group, msg
        integer, intent(in) :: ios
        character(len=:), allocatable :: text
        text = path//': &'//group//': '//trim(msg)
        if (ios == iostat_end) text = text//" (is the closing '/' of the group missing?)"
    end function read_failure

    !> Read group `group` (when the file has it) through its `read_record`, from the text
    !> scan_groups collected. On failure, re-read its assignments one at a time on a scratch
    !> copy to name the culprit and what it expects.
    subroutine read_group(path, group, groups, read_record, config, stat)
        character(len=*), intent(in) :: path, group
        type(group_text_t), intent(in) :: groups(:)
        procedure(record_reader) :: read_record
        type(config_t), intent(inout) :: config
        type(status_t), intent(inout) :: stat
        type(config_t) :: scratch
        type(text_t), allocatable :: pieces(:)
        character(len=MSG_LEN) :: msg
        integer :: i, ios
        if (.not. has_group(groups, group)) return
        msg = ''
        call read_record('&'//group//' '//group_body(groups, group)//' /', config, ios, msg)
        if (ios == 0) return
        call stat%fail(STATUS_BAD_INPUT, read_failure(path, group, ios, msg))
        pieces = split_assignments(group_body(groups, group))
        scratch = config
        do i = 1, size(pieces)
            msg = ''
            call read_record('&'//group//' '//pieces(i)%text//' /', scratch, ios, msg)
            if (ios /= 0) then
                call stat%fail(STATUS_BAD_INPUT, path//': &'//group//': '//pieces(i)%text &
                               //': '//trim(msg)//expectation(group, pieces(i)%text))
                exit
            end if
        end do
    end subroutine read_group

    ! ------------------------------------------------------------- reading each group
    ! Each reader copies the defaults into locals named like the namelist variables, reads
    ! the group after a rewind, and on failure re-reads the assignments one at a time from
    ! an internal file to name the culprit.

    !> One '&mesh ... /' record into config%mesh (unchanged if it fails).
    subroutine mesh_record(record, config, ios, msg)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        character(len=NAME_LEN) :: source, element, diagonal
        character(len=PATH_LEN) :: file
        character(len=LIST_LEN) :: dirichlet, neumann, contact
        real(wp) :: width, height
        integer :: nx, ny
        namelist /mesh/ source, file, width, height, nx, ny, element, diagonal, dirichlet, &
            neumann, contact

        source = config%mesh%source
        file = config%mesh%file
        width = config%mesh%width
        height = config%mesh%height
        nx = config%mesh%nx
        ny = config%mesh%ny
        element = config%mesh%element
        diagonal = config%mesh%diagonal
        dirichlet = config%mesh%dirichlet
        neumann = config%mesh%neumann
        contact = config%mesh%contact
        read (record, nml=mesh, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%mesh%source = lowercase(adjustl(source))
        config%mesh%file = adjustl(file)
        config%mesh%width = width
        config%mesh%height = height
        config%mesh%nx = nx
        config%mesh%ny = ny
        config%mesh%element = lowercase(adjustl(element))
        config%mesh%diagonal = lowercase(adjustl(diagonal))
        config%mesh%dirichlet = normalized_list(dirichlet)
        config%mesh%neumann = normalized_list(neumann)
        config%mesh%contact = normalized_list(contact)
    end subroutine mesh_record

    !> One '&material ... /' record into config%material (unchanged if it fails).
    subroutine material_record(record, config, ios, msg)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        real(wp) :: young, poisson
        namelist /material/ young, poisson

        young = config%material%young
        poisson = config%material%poisson
        read (record, nml=material, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%material%young = young
        config%material%poisson = poisson
    end subroutine material_record

    !> One '&analysis ... /' record into config%analysis (unchanged if it fails).
    subroutine analysis_record(record, config, ios, msg)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        character(len=NAME_LEN) :: kind     ! shadows the intrinsic here, as the file names it
        real(wp) :: lambda
        namelist /analysis/ kind, lambda

        kind = config%analysis%kind
        lambda = config%analysis%lambda
        read (record, nml=analysis, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%analysis%kind = lowercase(adjustl(kind))
        config%analysis%lambda = lambda
    end subroutine analysis_record

    !> One '&eigen ... /' record into config%eigen (unchanged if it fails).
    subroutine eigen_record(record, config, ios, msg)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        character(len=NAME_LEN) :: solver
        integer :: nev, maxit, ncv, dense_max_contact
        real(wp) :: target, tol
        namelist /eigen/ solver, nev, target, tol, maxit, ncv, dense_max_contact

        solver = config%eigen%solver
        nev = config%eigen%nev
        target = config%eigen%target
        tol = config%eigen%tol
        maxit = config%eigen%maxit
        ncv = config%eigen%ncv
        dense_max_contact = config%eigen%dense_max_contact
        read (record, nml=eigen, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%eigen%solver = lowercase(adjustl(solver))
        config%eigen%nev = nev
        config%eigen%target = target
        config%eigen%tol = tol
        config%eigen%maxit = maxit
        config%eigen%ncv = ncv
        config%eigen%dense_max_contact = dense_max_contact
    end subroutine eigen_record

    !> One '&output ... /' record into config%output (unchanged if it fails).
    subroutine output_record(record, config, ios, msg)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        character(len=PATH_LEN) :: directory
        logical :: vtk, matrices
        integer :: modes
        character(len=len(config%output%vtk_format)) :: vtk_format
        namelist /output/ directory, vtk, modes, matrices, vtk_format

        directory = config%output%directory
        vtk = config%output%vtk
        modes = config%output%modes
        matrices = config%output%matrices
        vtk_format = config%output%vtk_format
        read (record, nml=output, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%output%directory = adjustl(directory)
        config%output%vtk = vtk
        config%output%modes = modes
        config%output%matrices = matrices
        config%output%vtk_format = lowercase(adjustl(vtk_format))
    end subroutine output_record

    !> One '&branch ... /' record into config%branch (unchanged if it fails).
    subroutine branch_record(record, config, ios, msg)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        real(wp) :: alpha, beta
        integer :: n_delta, write_members
        namelist /branch/ alpha, beta, n_delta, write_members

        alpha = config%branch%alpha
        beta = config%branch%beta
        n_delta = config%branch%n_delta
        write_members = config%branch%write_members
        read (record, nml=branch, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%branch%alpha = alpha
        config%branch%beta = beta
        config%branch%n_delta = n_delta
        config%branch%write_members = write_members
    end subroutine branch_record

    !> One '&solve ... /' record into config%solve (unchanged if it fails).
    subroutine solve_record(record, config, ios, msg)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        character(len=NAME_LEN) :: data, start
        real(wp) :: c_n, c_t, critical_factor, f1, f2, t1, t2, u_d1, u_d2, start_delta, &
                    start_scale, start_noise, tol
        integer :: seed, max_iterations
        namelist /solve/ data, c_n, c_t, critical_factor, f1, f2, t1, t2, u_d1, u_d2, start, &
            start_delta, start_scale, start_noise, seed, tol, max_iterations

        data = config%solve%data
        c_n = config%solve%c_n
        c_t = config%solve%c_t
        critical_factor = config%solve%critical_factor
        f1 = config%solve%f1
        f2 = config%solve%f2
        t1 = config%solve%t1
        t2 = config%solve%t2
        u_d1 = config%solve%u_d1
        u_d2 = config%solve%u_d2
        start = config%solve%start
        start_delta = config%solve%start_delta
        start_scale = config%solve%start_scale
        start_noise = config%solve%start_noise
        seed = config%solve%seed
        tol = config%solve%tol
        max_iterations = config%solve%max_iterations
        read (record, nml=solve, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%solve%data = lowercase(adjustl(data))
        config%solve%c_n = c_n
        config%solve%c_t = c_t
        config%solve%critical_factor = critical_factor
        config%solve%f1 = f1
        config%solve%f2 = f2
        config%solve%t1 = t1
        config%solve%t2 = t2
        config%solve%u_d1 = u_d1
        config%solve%u_d2 = u_d2
        config%solve%start = lowercase(adjustl(start))
        config%solve%start_delta = start_delta
        config%solve%start_scale = start_scale
        config%solve%start_noise = start_noise
        config%solve%seed = seed
        config%solve%tol = tol
        config%solve%max_iterations = max_iterations
    end subroutine solve_record
    !> What a failed assignment 'name = value' of `group` should have looked like: the
    !> type of a known variable, or the variables the group knows. The runtime's own message
    !> ('Cannot match namelist object name 5') says what went wrong, not what was expected.
    pure function expectation(group, assignment) result(text)
        character(len=*), intent(in) :: group, assignment
        character(len=:), allocatable :: text
        character(len=:), allocatable :: name
        integer :: i, equals, space
        equals = index(assignment, '=')
        name = lowercase(trim(adjustl(assignment(:max(0, equals - 1)))))
        text = ''
        do i = 1, size(VARIABLE_TYPES)
            space = index(VARIABLE_TYPES(i), ' ')
            if (VARIABLE_TYPES(i)(:space - 1) /= group) cycle
            if (len(text) > 0) text = text//', '
            text = text//trim(VARIABLE_TYPES(i)(space + 1:index(VARIABLE_TYPES(i), ':') - 1))
            if (trim(VARIABLE_TYPES(i)(space + 1:index(VARIABLE_TYPES(i), ':') - 1)) == name) &
                then
                text = ' (expected '//trim(VARIABLE_TYPES(i)(index(VARIABLE_TYPES(i), ':') + &
                       1:))//')'
                return
            end if
        end do
        if (len(text) > 0) text = ' (&'//group//' knows: '//text//')'
    end function expectation

    ! ---------------------------------------------------------------------- validation

    subroutine validate_mesh(c, path, stat)
        type(mesh_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        character(len=*), parameter :: LIST_VARIABLES(3) = [character(len=9) :: &
                                       'dirichlet', 'neumann', 'contact']
        character(len=LIST_LEN) :: lists(3)
        character(len=LIST_LEN), allocatable :: names(:), seen(:)
        integer, allocatable :: seen_in(:)
        integer :: k, i, j

        if (.not. any(MESH_SOURCES == c%source)) then
            call reject('source', quoted(c%source), 'one of '//one_of(MESH_SOURCES))
        else if (c%source == 'gmsh' .and. len_trim(c%file) == 0) then
            call reject('file', quoted(c%file), &
                        "the path of a Gmsh .msh file when source = 'gmsh'")
        else if (.not. positive_finite(c%width)) then
            call reject('width', real_to_text(c%width), 'a finite number > 0')
        else if (.not. positive_finite(c%height)) then
            call reject('height', real_to_text(c%height), 'a finite number > 0')
        else if (c%nx < 1 .or. c%nx > MAX_CELLS_PER_SIDE) then
            call reject('nx', to_string(c%nx), &
                        'an integer from 1 to '//to_string(MAX_CELLS_PER_SIDE))
        else if (c%ny < 1 .or. c%ny > MAX_CELLS_PER_SIDE) then
            call reject('ny', to_string(c%ny), &
                        'an integer from 1 to '//to_string(MAX_CELLS_PER_SIDE))
        else if (.not. any(ELEMENT_NAMES == c%element)) then
            call reject('element', quoted(c%element), 'one of '//one_of(ELEMENT_NAMES))
        else if (.not. any(DIAGONALS == c%diagonal)) then
            call reject('diagonal', quoted(c%diagonal), 'one of '//one_of(DIAGONALS))
        end if
        if (.not. stat%ok()) return

        lists = [c%dirichlet, c%neumann, c%contact]
        do k = 1, 3
            call split_words(lists(k), names)
            do i = 1, size(names)
                if (len_trim(names(i)) > NAME_LEN) then
                    call reject(trim(LIST_VARIABLES(k)), quoted(lists(k)), 'names of at most ' &
                                //to_string(NAME_LEN)//' characters')
                else if (c%source == 'rectangle' .and. &
                         .not. any(RECTANGLE_SIDES == names(i))) then
                    call reject(trim(LIST_VARIABLES(k)), quoted(lists(k)), 'sides among ' &
                                //one_of(RECTANGLE_SIDES)//" ('"//trim(names(i)) &
                                //"' is not a side of the rectangle)")
                end if
                if (.not. stat%ok()) return
            end do
        end do
        if (count_names(c%dirichlet) == 0) then
            call reject('dirichlet', quoted(c%dirichlet), &
                        'at least one side or group name (without a Dirichlet boundary K would ' &
                        //'be singular)')
            return
        end if
        if (count_names(c%contact) /= 1) then
            call reject('contact', quoted(c%contact), 'exactly one side or group name ' &
                        //'(the contact boundary is one straight segment)')
            return
        end if

        allocate (seen(0), seen_in(0))
        do k = 1, 3
            call split_words(lists(k), names)
            do i = 1, size(names)
                do j = 1, size(seen)
                    if (seen(j) /= names(i)) cycle
                    if (seen_in(j) == k) then
                        call reject(trim(LIST_VARIABLES(k)), quoted(lists(k)), &
                                    "each name once ('"//trim(names(i))//"' is named twice)")
                    else
                        call reject(trim(LIST_VARIABLES(k)), quoted(lists(k)), &
                                    'each name in only one of dirichlet, neumann, contact (' &
                                    //quoted(names(i))//' is also in ' &
                                    //trim(LIST_VARIABLES(seen_in(j)))//')')
                    end if
                    return
                end do
                seen = [character(len=LIST_LEN) :: seen, names(i)]
                seen_in = [seen_in, k]
            end do
        end do

    contains

        subroutine reject(variable, value, expected)
            character(len=*), intent(in) :: variable, value, expected
            call fail_value(stat, path, 'mesh', variable, value, expected)
        end subroutine reject
    end subroutine validate_mesh

    subroutine validate_material(c, path, stat)
        type(material_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        logical :: poisson_ok

        poisson_ok = ieee_is_finite(c%poisson)
        if (poisson_ok) poisson_ok = c%poisson > -1.0_wp .and. c%poisson < 0.5_wp
        if (.not. positive_finite(c%young)) then
            call fail_value(stat, path, 'material', 'young', real_to_text(c%young), &
                            'a finite number > 0')
        else if (.not. poisson_ok) then
            call fail_value(stat, path, 'material', 'poisson', real_to_text(c%poisson), &
                            '-1 < poisson < 0.5 (0.5 is incompressible, which this ' &
                            //'displacement formulation cannot represent)')
        end if
    end subroutine validate_material

    subroutine validate_analysis(c, path, stat)
        type(analysis_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat

        if (.not. any(ACCEPTED_ANALYSES == c%kind)) then
            call fail_value(stat, path, 'analysis', 'kind', quoted(c%kind), &
                            'one of '//one_of(ACCEPTED_ANALYSES))
        else if (.not. ieee_is_finite(c%lambda)) then
            call fail_value(stat, path, 'analysis', 'lambda', real_to_text(c%lambda), &
                            'a finite number')
        end if
    end subroutine validate_analysis

    subroutine validate_eigen(c, path, stat)
        type(eigen_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        logical :: tol_ok

        tol_ok = ieee_is_finite(c%tol)
        if (tol_ok) tol_ok = c%tol >= 0.0_wp .and. c%tol < 1.0_wp
        if (.not. any(ACCEPTED_SOLVERS == c%solver)) then
            call reject('solver', quoted(c%solver), 'one of '//one_of(ACCEPTED_SOLVERS))
        else if (c%nev < 1) then
            call reject('nev', to_string(c%nev), 'an integer >= 1')
        else if (.not. ieee_is_finite(c%target)) then
            call reject('target', real_to_text(c%target), 'a finite number')
        else if (.not. tol_ok) then
            call reject('tol', real_to_text(c%tol), 'a number in [0, 1) (0: machine precision)')
        else if (c%maxit < 1) then
            call reject('maxit', to_string(c%maxit), 'an integer >= 1')
        else if (c%ncv /= 0 .and. c%ncv < c%nev + 2) then
            call reject('ncv', to_string(c%ncv), '0 (automatic) or at least nev + 2 = ' &
                        //to_string(c%nev + 2))
        else if (c%dense_max_contact < 1) then
            call reject('dense_max_contact', to_string(c%dense_max_contact), 'an integer >= 1')
        end if

    contains

        subroutine reject(variable, value, expected)
            character(len=*), intent(in) :: variable, value, expected
            call fail_value(stat, path, 'eigen', variable, value, expected)
        end subroutine reject
    end subroutine validate_eigen

    subroutine validate_output(c, path, stat)
        type(output_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat

        if (c%modes < 0) then
            call fail_value(stat, path, 'output', 'modes', to_string(c%modes), 'an integer >= 0')
        else if (.not. any(VTK_FORMATS == c%vtk_format)) then
            call fail_value(stat, path, 'output', 'vtk_format', quoted(c%vtk_format), &
                            'one of '//one_of(VTK_FORMATS))
        end if
    end subroutine validate_output

    subroutine validate_branch(c, path, stat)
        type(branch_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat

        if (.not. positive_finite(c%alpha)) then
            call fail_value(stat, path, 'branch', 'alpha', real_to_text(c%alpha), &
                            'a finite number > 0 (u_n of U on the contact boundary)')
        else if (.not. positive_finite(c%beta)) then
            call fail_value(stat, path, 'branch', 'beta', real_to_text(c%beta), &
                            'a finite number > 0 (|u_t| of U on the contact boundary)')
        else if (c%n_delta < 1) then
            call fail_value(stat, path, 'branch', 'n_delta', to_string(c%n_delta), &
                            'an integer >= 1')
        else if (c%write_members < 0) then
            call fail_value(stat, path, 'branch', 'write_members', to_string(c%write_members), &
                            'an integer >= 0')
        end if
    end subroutine validate_branch

    subroutine validate_solve(c, path, stat)
        type(solve_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        logical :: tol_ok

        tol_ok = ieee_is_finite(c%tol)
        if (tol_ok) tol_ok = c%tol > 0.0_wp .and. c%tol < 1.0_wp
        if (.not. any(SOLVE_DATA == c%data)) then
            call reject('data', quoted(c%data), 'one of '//one_of(SOLVE_DATA))
        else if (.not. positive_finite(c%c_n)) then
            call reject('c_n', real_to_text(c%c_n), 'a finite number > 0')
        else if (.not. positive_finite(c%c_t)) then
            call reject('c_t', real_to_text(c%c_t), 'a finite number > 0')
        else if (.not. positive_finite(c%critical_factor)) then
            call reject('critical_factor', real_to_text(c%critical_factor), 'a finite number > 0')
        else if (.not. all(ieee_is_finite([c%f1, c%f2, c%t1, c%t2, c%u_d1, c%u_d2]))) then
            call reject('f1, f2, t1, t2, u_d1, u_d2', real_to_text(c%f1)//', ' &
                        //real_to_text(c%f2)//', '//real_to_text(c%t1)//', ' &
                        //real_to_text(c%t2)//', '//real_to_text(c%u_d1)//', ' &
                        //real_to_text(c%u_d2), 'finite numbers')
        else if (.not. any(SOLVE_STARTS == c%start)) then
            call reject('start', quoted(c%start), 'one of '//one_of(SOLVE_STARTS))
        else if (.not. ieee_is_finite(c%start_delta)) then
            call reject('start_delta', real_to_text(c%start_delta), 'a finite number')
        else if (.not. ieee_is_finite(c%start_scale)) then
            call reject('start_scale', real_to_text(c%start_scale), 'a finite number')
        else if (.not. ieee_is_finite(c%start_noise)) then
            call reject('start_noise', real_to_text(c%start_noise), 'a finite number')
        else if (.not. tol_ok) then
            call reject('tol', real_to_text(c%tol), 'a number with 0 < tol < 1')
        else if (c%max_iterations < 1) then
            call reject('max_iterations', to_string(c%max_iterations), 'an integer >= 1')
        end if

    contains

        subroutine reject(variable, value, expected)
            character(len=*), intent(in) :: variable, value, expected
            call fail_value(stat, path, 'solve', variable, value, expected)
        end subroutine reject
    end subroutine validate_solve

    !> The one message format of a rejected value.
    subroutine fail_value(stat, path, group, variable, value, expected)
        type(status_t), intent(inout) :: stat
        character(len=*), intent(in) :: path, group, variable, value, expected
        call stat%fail(STATUS_BAD_INPUT, path//': &'//group//': '//variable//' = '//value &
                       //': expected '//expected)
    end subroutine fail_value

    !> Tested before any comparison: an ordered comparison with NaN traps in debug builds.
    elemental logical function positive_finite(x)
        real(wp), intent(in) :: x
        positive_finite = ieee_is_finite(x)
        if (positive_finite) positive_finite = x > 0.0_wp
    end function positive_finite

    ! -------------------------------------------------------------- &sweep (lambda_sweep)

    !> One '&sweep ... /' record into config%sweep (unchanged if it fails).
    subroutine sweep_record(record, config, ios, msg)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        real(wp) :: lambda_min, lambda_max, lambdas(MAX_SWEEP_LAMBDAS)
        integer :: n_lambda
        character(len=NAME_LEN) :: spacing
        logical :: plot
        namelist /sweep/ lambda_min, lambda_max, n_lambda, spacing, lambdas, plot

        lambda_min = config%sweep%lambda_min
        lambda_max = config%sweep%lambda_max
        n_lambda = config%sweep%n_lambda
        spacing = config%sweep%spacing
        lambdas = config%sweep%lambdas
        plot = config%sweep%plot
        read (record, nml=sweep, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%sweep%lambda_min = lambda_min
        config%sweep%lambda_max = lambda_max
        config%sweep%n_lambda = n_lambda
        config%sweep%spacing = lowercase(adjustl(spacing))
        config%sweep%lambdas = lambdas
        config%sweep%plot = plot
    end subroutine sweep_record

    !> The list, when given, must be a prefix of finite values (unset entries are huge()).
    !> A range needs lambda_min < lambda_max, and for 'log' one sign and no zero.
    subroutine validate_sweep(c, path, stat)
        type(sweep_config_t), intent(in) :: c
        character(len=*), intent(in) :: path
        type(status_t), intent(inout) :: stat
        integer :: n_list, i

        n_list = count_set_lambdas(c)
        do i = 1, size(c%lambdas)
            if (i <= n_list) then
                if (.not. ieee_is_finite(c%lambdas(i))) then
                    call reject('lambdas('//to_string(i)//')', real_to_text(c%lambdas(i)), &
                                'a finite number')
                    return
                end if
            else if (lambda_is_set(c%lambdas(i))) then
                call reject('lambdas('//to_string(i)//')', real_to_text(c%lambdas(i)), &
                            'consecutive entries from lambdas(1) (lambdas('//to_string(i - 1) &
                            //') is unset)')
                return
            end if
        end do
        if (n_list > 0) return

        if (.not. ieee_is_finite(c%lambda_min)) then
            call reject('lambda_min', real_to_text(c%lambda_min), 'a finite number')
        else if (.not. ieee_is_finite(c%lambda_max)) then
            call reject('lambda_max', real_to_text(c%lambda_max), 'a finite number')
        else if (.not. c%lambda_max > c%lambda_min) then
            call reject('lambda_max', real_to_text(c%lambda_max), 'a number > lambda_min = ' &
                        //real_to_text(c%lambda_min))
        else if (c%n_lambda < 2 .or. c%n_lambda > MAX_SWEEP_POINTS) then
            call reject('n_lambda', to_string(c%n_lambda), 'an integer from 2 to ' &
                        //to_string(MAX_SWEEP_POINTS))
        else if (.not. any(SWEEP_SPACINGS == c%spacing)) then
            call reject('spacing', quoted(c%spacing), 'one of '//one_of(SWEEP_SPACINGS))
        else if (c%spacing == 'log' .and. .not. (c%lambda_min > 0.0_wp .or. &
                                                 c%lambda_max < 0.0_wp)) then
            call reject('lambda_min', real_to_text(c%lambda_min), "lambda_min and lambda_max" &
                        //" of one sign, both nonzero, with spacing = 'log' (lambda_max = " &
                        //real_to_text(c%lambda_max)//')')
        end if

    contains

        subroutine reject(variable, value, expected)
            character(len=*), intent(in) :: variable, value, expected
            call fail_value(stat, path, 'sweep', variable, value, expected)
        end subroutine reject
    end subroutine validate_sweep

    ! -------------------------------------------------------------------------- paths

    !> Default output directory of a run: output/<input file name without extension>,
    !> relative to the working directory.
    function default_output_directory(input_path) result(directory)
        character(len=*), intent(in) :: input_path
        character(len=:), allocatable :: directory
        character(len=:), allocatable :: base
        integer :: dot

        base = trim(input_path)
        base = base(index(base, '/', back=.true.) + 1:)
        dot = index(base, '.', back=.true.)
        if (dot > 1) base = base(:dot - 1)   ! a leading dot starts a hidden name, not a suffix
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

    ! ---------------------------------------------------------------------- help text

    !> The --help text: usage, then every group and variable with its default, taken from
    !> a default `config_t` so that the documentation cannot drift from the code. Lines
    !> are separated by new_line('a'); the text ends with one. Lines stay under 100.
    function help_text() result(text)
        character(len=:), allocatable :: text
        type(config_t) :: d
        character(len=*), parameter :: NL = new_line('a')

        text = 'Usage: nceig INPUT.nml | --help | --version'//NL//NL &
               //'Finds the critical interface parameters of the normal compliance friction' &
               //NL//'model: the eigenvalues mu of K phi = mu B phi for the plane-strain body' &
               //NL//'described by the namelist file INPUT.nml. Every variable is optional;' &
               //NL//'defaults are shown. Names are case-insensitive. Results go to the' &
               //NL//'output directory: summary.json, eigenvalues.csv, mode_NNN.vtu.'//NL//NL
        text = text//'&mesh'//NL &
               //entry('source', quoted(d%mesh%source), 'one of '//one_of(MESH_SOURCES)) &
               //entry('file', quoted(d%mesh%file), "Gmsh .msh (source = 'gmsh'), relative" &
                       //' to the input file''s folder') &
               //entry('width', real_to_text(d%mesh%width), 'rectangle size along x') &
               //entry('height', real_to_text(d%mesh%height), 'rectangle size along y') &
               //entry('nx', to_string(d%mesh%nx), 'cells along x (1 to ' &
                       //to_string(MAX_CELLS_PER_SIDE)//')') &
               //entry('ny', to_string(d%mesh%ny), 'cells along y') &
               //entry('element', quoted(d%mesh%element), one_of(ELEMENT_NAMES) &
                       //' (rectangle; a Gmsh file sets its own)') &
               //entry('diagonal', quoted(d%mesh%diagonal), one_of(DIAGONALS) &
                       //': triangle diagonals rise to the right or left') &
               //entry('dirichlet', quoted(d%mesh%dirichlet), 'fixed sides (' &
                       //one_of(RECTANGLE_SIDES)//') or Gmsh groups') &
               //entry('neumann', quoted(d%mesh%neumann), 'traction-free sides; sides named' &
                       //' nowhere are traction-free too') &
               //entry('contact', quoted(d%mesh%contact), 'the one side or group in contact')
        text = text//'&material'//NL &
               //entry('young', real_to_text(d%material%young), 'Young''s modulus E > 0') &
               //entry('poisson', real_to_text(d%material%poisson), &
                       'Poisson''s ratio, -1 < poisson < 0.5')
        text = text//'&analysis'//NL &
               //entry('kind', quoted(d%analysis%kind), 'one of '//one_of(ACCEPTED_ANALYSES)) &
               //entry('lambda', real_to_text(d%analysis%lambda), &
                       'ratio in b_lambda(phi, v) = lambda int phi_n v_t - int phi_n v_n')
        text = text//'&eigen'//NL &
               //entry('solver', quoted(d%eigen%solver), 'one of '//one_of(ACCEPTED_SOLVERS)) &
               //entry('nev', to_string(d%eigen%nev), 'ARPACK: eigenvalues nearest target' &
                       //' per run (doubled while undecided)') &
               //entry('target', real_to_text(d%eigen%target), 'shift sigma: eigenvalues' &
                       //' nearest to it are found first') &
               //entry('tol', real_to_text(d%eigen%tol), 'sparse solver tolerance' &
                       //' (0: machine precision)') &
               //entry('maxit', to_string(d%eigen%maxit), 'sparse solver restarts') &
               //entry('ncv', to_string(d%eigen%ncv), 'Krylov dimension, 0 or >= nev + 2' &
                       //' (0: chosen from nev)') &
               //entry('dense_max_contact', to_string(d%eigen%dense_max_contact), &
                       "'auto' picks 'dense' up to this many contact nodes, else 'arpack'")
        text = text//'&output'//NL &
               //entry('directory', quoted(d%output%directory), "'' means output/<input" &
                       //' file stem> (from the working directory)') &
               //entry('vtk', logical_text(d%output%vtk), 'write mode_NNN.vtu for ParaView') &
               //entry('modes', to_string(d%output%modes), 'how many modes to write as .vtu') &
               //entry('matrices', logical_text(d%output%matrices), &
                       'write K.mtx and B.mtx (Matrix Market)') &
               //entry('vtk_format', quoted(d%output%vtk_format), one_of(VTK_FORMATS) &
                       //" ('binary': raw appended data; 'ascii': text)")
        text = text//"&sweep  (kind = 'lambda_sweep': lowest positive mu against lambda)"//NL &
               //entry('lambda_min', real_to_text(d%sweep%lambda_min), 'first lambda of the' &
                       //' range (either sign)') &
               //entry('lambda_max', real_to_text(d%sweep%lambda_max), 'last lambda, >' &
                       //' lambda_min') &
               //entry('n_lambda', to_string(d%sweep%n_lambda), 'points in the range (2 to ' &
                       //to_string(MAX_SWEEP_POINTS)//')') &
               //entry('spacing', quoted(d%sweep%spacing), one_of(SWEEP_SPACINGS) &
                       //" ('log': one sign, geometric in |lambda|)") &
               //entry('lambdas', 'unset', 'explicit list (up to '// &
                       to_string(MAX_SWEEP_LAMBDAS)//'), replaces the range') &
               //entry('plot', logical_text(d%sweep%plot), 'draw lambda_sweep.png with' &
                       //' gnuplot when it is installed')
        text = text//'&branch      (kind = ''branch'': U + delta phi, SPEC section 5)'//NL &
               //entry('alpha', real_to_text(d%branch%alpha), 'u_n of U on Gamma_C, > 0') &
               //entry('beta', real_to_text(d%branch%beta), '|u_t| of U on Gamma_C, > 0') &
               //entry('n_delta', to_string(d%branch%n_delta), 'deltas evenly spaced in' &
                       //' [-delta_max, delta_max]') &
               //entry('write_members', to_string(d%branch%write_members), &
                       'members written as branch_NNN.vtu')
        text = text//'&solve       (kind = ''solve'': frictional normal compliance, Newton)'//NL &
               //entry('data', quoted(d%solve%data), one_of(SOLVE_DATA)//': the loads below,' &
                       //' or those of &branch') &
               //entry('c_n', real_to_text(d%solve%c_n), 'normal compliance (data = ''given'')') &
               //entry('c_t', real_to_text(d%solve%c_t), 'tangential compliance') &
               //entry('critical_factor', real_to_text(d%solve%critical_factor), &
                       'data = ''branch'': c_n, c_t = factor * critical') &
               //entry('f1, f2', real_to_text(d%solve%f1)//', '//real_to_text(d%solve%f2), &
                       'body force') &
               //entry('t1, t2', real_to_text(d%solve%t1)//', '//real_to_text(d%solve%t2), &
                       'traction on every Neumann part') &
               //entry('u_d1, u_d2', real_to_text(d%solve%u_d1)//', ' &
                       //real_to_text(d%solve%u_d2), 'displacement on Gamma_D') &
               //entry('start', quoted(d%solve%start), one_of(SOLVE_STARTS)) &
               //entry('start_delta', real_to_text(d%solve%start_delta), &
                       'start = ''branch'': U + start_delta phi') &
               //entry('start_scale', real_to_text(d%solve%start_scale), &
                       'start = ''random'' or ''mode'': size of the guess') &
               //entry('start_noise', real_to_text(d%solve%start_noise), &
                       'uniform noise of this size added to any start') &
               //entry('seed', to_string(d%solve%seed), 'of the random start and the noise') &
               //entry('tol', real_to_text(d%solve%tol), '||residual|| / ||load||' &
                       //' (infinity norms) to stop at') &
               //entry('max_iterations', to_string(d%solve%max_iterations), 'Newton iterations')

    contains

        function entry(name, value, description) result(line)
            character(len=*), intent(in) :: name, value, description
            character(len=:), allocatable :: line
            line = '    '//name//' = '//value
            if (len(line) < HELP_COLUMN) line = line//repeat(' ', HELP_COLUMN - len(line))
            line = line//'  '//description//NL
        end function entry
    end function help_text

    ! ------------------------------------------------------------------ small helpers

    pure function quoted(text) result(q)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: q
        q = "'"//trim(text)//"'"
    end function quoted

    pure function logical_text(flag) result(text)
        logical, intent(in) :: flag
        character(len=:), allocatable :: text
        text = '.false.'
        if (flag) text = '.true.'
    end function logical_text

    !> "'a', 'b', 'c'": the accepted values of a choice, for messages and help.
    pure function one_of(choices) result(text)
        character(len=*), intent(in) :: choices(:)
        character(len=:), allocatable :: text
        integer :: i
        text = ''
        do i = 1, size(choices)
            if (i > 1) text = text//', '
            text = text//quoted(choices(i))
        end do
    end function one_of

    !> "&mesh, &material, ...": the known groups, for messages.
    pure function group_list() result(text)
        character(len=:), allocatable :: text
        integer :: i
        text = ''
        do i = 1, size(KNOWN_GROUPS)
            if (i > 1) text = text//', '
            text = text//'&'//trim(KNOWN_GROUPS(i))
        end do
    end function group_list
end module input_config
