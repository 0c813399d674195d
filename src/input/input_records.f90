! SPDX-License-Identifier: MIT
!> The namelist records of the input file, one group at a time: the namelist of each
!> (whose variables are those of its `run_config` type, as input_table lists them), read
!> into a config_t or written from one. Values are read, not judged: see input_validation.
module input_records
    use kinds, only: wp
    use run_config, only: config_t, MAX_SWEEP_LAMBDAS, PATH_LEN
    use strings, only: lowercase, normalized_list, NAME_LEN, LIST_LEN
    use input_table, only: KNOWN_GROUPS
    use ieee_exceptions, only: ieee_status_type, ieee_get_status, ieee_set_status, &
                               ieee_set_halting_mode, ieee_support_halting, ieee_overflow
    implicit none
    private
    public :: read_record, reader_variables, reader_defaults, LISTING_LINE_LEN

    integer, parameter :: LISTING_LINE_LEN = 4*PATH_LEN   !! a line of a namelist write

contains

    !> Read one '&group assignment ... /' record of group `group` into `config` (whose
    !> group is unchanged when the read fails: ios /= 0, msg the runtime's message). With
    !> `listing_unit`, write the group's namelist with the values of `config` there instead.
    subroutine read_record(group, record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: group, record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
        type(ieee_status_type) :: saved
        ! '1e999' overflows inside the runtime's strtod: in a build that traps overflow
        ! (Debug) that is a crash, so the read runs without; the value becomes Inf and
        ! validation refuses it as not finite. Flags and modes are restored after.
        call ieee_get_status(saved)
        if (ieee_support_halting(ieee_overflow)) call ieee_set_halting_mode(ieee_overflow, &
                                                                            .false.)
        select case (group)
        case ('mesh'); call mesh_record(record, config, ios, msg, listing_unit)
        case ('material'); call material_record(record, config, ios, msg, listing_unit)
        case ('analysis'); call analysis_record(record, config, ios, msg, listing_unit)
        case ('eigen'); call eigen_record(record, config, ios, msg, listing_unit)
        case ('output'); call output_record(record, config, ios, msg, listing_unit)
        case ('sweep'); call sweep_record(record, config, ios, msg, listing_unit)
        case ('branch'); call branch_record(record, config, ios, msg, listing_unit)
        case ('solve'); call solve_record(record, config, ios, msg, listing_unit)
        case ('adapt'); call adapt_record(record, config, ios, msg, listing_unit)
        case default
            ios = -1
            msg = 'no namelist group &'//group
        end select
        call ieee_set_status(saved)
    end subroutine read_record

    !> The variables of group `group` as its namelist declares them, lowercased, in order:
    !> taken from a namelist write, so that they can be checked against input_table and
    !> the help text. Empty for an unknown group.
    function reader_variables(group) result(names)
        character(len=*), intent(in) :: group
        character(len=NAME_LEN), allocatable :: names(:)
        character(len=LISTING_LINE_LEN), allocatable :: values(:)
        call reader_defaults(group, names, values)
    end function reader_variables

    !> The variables of group `group` (as reader_variables) and their default values as a
    !> namelist write of a default config_t gives them ('1.0000000000000000', '"p1   "',
    !> 'T'), so that the help shows run_config's defaults without naming each one.
    subroutine reader_defaults(group, names, values)
        character(len=*), intent(in) :: group
        character(len=NAME_LEN), allocatable, intent(out) :: names(:)
        character(len=LISTING_LINE_LEN), allocatable, intent(out) :: values(:)
        type(config_t) :: defaults
        character(len=LISTING_LINE_LEN) :: line
        character(len=256) :: msg
        integer :: unit, ios, equals, last

        allocate (names(0), values(0))
        open (newunit=unit, status='scratch', action='readwrite', delim='quote', &
              recl=LISTING_LINE_LEN, iostat=ios)
        if (ios /= 0) return
        msg = ''
        call read_record(group, '', defaults, ios, msg, listing_unit=unit)
        if (ios == 0) then
            rewind (unit)
            do
                read (unit, '(a)', iostat=ios) line
                if (ios /= 0) exit
                ! 'NAME=value' starts a variable; other lines continue an array's values.
                line = adjustl(line)
                equals = index(line, '=')
                if (equals < 2) cycle
                if (verify(line(:equals - 1), 'abcdefghijklmnopqrstuvwxyz' &
                           //'ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') /= 0) cycle
                names = [character(len=NAME_LEN) :: names, lowercase(line(:equals - 1))]
                last = len_trim(line)
                if (line(last:last) == ',') last = last - 1
                values = [character(len=LISTING_LINE_LEN) :: values, &
                          adjustl(line(equals + 1:last))]
            end do
        end if
        close (unit)
    end subroutine reader_defaults

    ! Each reader copies the current values into locals named like the namelist variables,
    ! reads the record from the internal file `record`, and only on success copies them
    ! back, normalising names (trimmed, lowercased).

    !> One '&mesh ... /' record into config%mesh (unchanged if it fails).
    subroutine mesh_record(record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
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
        if (present(listing_unit)) then
            write (listing_unit, nml=mesh, iostat=ios, iomsg=msg)
            return
        end if
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
    subroutine material_record(record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
        real(wp) :: young, poisson
        namelist /material/ young, poisson

        young = config%material%young
        poisson = config%material%poisson
        if (present(listing_unit)) then
            write (listing_unit, nml=material, iostat=ios, iomsg=msg)
            return
        end if
        read (record, nml=material, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%material%young = young
        config%material%poisson = poisson
    end subroutine material_record

    !> One '&analysis ... /' record into config%analysis (unchanged if it fails).
    subroutine analysis_record(record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
        character(len=NAME_LEN) :: kind     ! shadows the intrinsic here, as the file names it
        real(wp) :: lambda
        namelist /analysis/ kind, lambda

        kind = config%analysis%kind
        lambda = config%analysis%lambda
        if (present(listing_unit)) then
            write (listing_unit, nml=analysis, iostat=ios, iomsg=msg)
            return
        end if
        read (record, nml=analysis, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%analysis%kind = lowercase(adjustl(kind))
        config%analysis%lambda = lambda
    end subroutine analysis_record

    !> One '&eigen ... /' record into config%eigen (unchanged if it fails).
    subroutine eigen_record(record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
        character(len=NAME_LEN) :: solver, estimate, operator
        integer :: nev, maxit, ncv, dense_max_contact
        real(wp) :: target, tol, cn_max
        namelist /eigen/ solver, nev, target, tol, maxit, ncv, dense_max_contact, estimate, &
            operator, cn_max

        solver = config%eigen%solver
        nev = config%eigen%nev
        target = config%eigen%target
        tol = config%eigen%tol
        maxit = config%eigen%maxit
        ncv = config%eigen%ncv
        dense_max_contact = config%eigen%dense_max_contact
        estimate = config%eigen%estimate
        operator = config%eigen%operator
        cn_max = config%eigen%cn_max
        if (present(listing_unit)) then
            write (listing_unit, nml=eigen, iostat=ios, iomsg=msg)
            return
        end if
        read (record, nml=eigen, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%eigen%solver = lowercase(adjustl(solver))
        config%eigen%nev = nev
        config%eigen%target = target
        config%eigen%tol = tol
        config%eigen%maxit = maxit
        config%eigen%ncv = ncv
        config%eigen%dense_max_contact = dense_max_contact
        config%eigen%estimate = lowercase(adjustl(estimate))
        config%eigen%operator = lowercase(adjustl(operator))
        config%eigen%cn_max = cn_max
    end subroutine eigen_record

    !> One '&output ... /' record into config%output (unchanged if it fails).
    subroutine output_record(record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
        character(len=PATH_LEN) :: directory
        logical :: vtk, matrices, plot, progress
        integer :: modes
        character(len=len(config%output%vtk_format)) :: vtk_format
        namelist /output/ directory, vtk, modes, matrices, vtk_format, plot, progress

        directory = config%output%directory
        vtk = config%output%vtk
        modes = config%output%modes
        matrices = config%output%matrices
        vtk_format = config%output%vtk_format
        plot = config%output%plot
        progress = config%output%progress
        if (present(listing_unit)) then
            write (listing_unit, nml=output, iostat=ios, iomsg=msg)
            return
        end if
        read (record, nml=output, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%output%directory = adjustl(directory)
        config%output%vtk = vtk
        config%output%modes = modes
        config%output%matrices = matrices
        config%output%vtk_format = lowercase(adjustl(vtk_format))
        config%output%plot = plot
        config%output%progress = progress
    end subroutine output_record

    !> One '&sweep ... /' record into config%sweep (unchanged if it fails).
    subroutine sweep_record(record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
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
        if (present(listing_unit)) then
            write (listing_unit, nml=sweep, iostat=ios, iomsg=msg)
            return
        end if
        read (record, nml=sweep, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%sweep%lambda_min = lambda_min
        config%sweep%lambda_max = lambda_max
        config%sweep%n_lambda = n_lambda
        config%sweep%spacing = lowercase(adjustl(spacing))
        config%sweep%lambdas = lambdas
        config%sweep%plot = plot
    end subroutine sweep_record

    !> One '&branch ... /' record into config%branch (unchanged if it fails).
    subroutine branch_record(record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
        real(wp) :: alpha, beta
        integer :: n_delta, write_members
        namelist /branch/ alpha, beta, n_delta, write_members

        alpha = config%branch%alpha
        beta = config%branch%beta
        n_delta = config%branch%n_delta
        write_members = config%branch%write_members
        if (present(listing_unit)) then
            write (listing_unit, nml=branch, iostat=ios, iomsg=msg)
            return
        end if
        read (record, nml=branch, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%branch%alpha = alpha
        config%branch%beta = beta
        config%branch%n_delta = n_delta
        config%branch%write_members = write_members
    end subroutine branch_record

    !> One '&solve ... /' record into config%solve (unchanged if it fails).
    subroutine solve_record(record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
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
        if (present(listing_unit)) then
            write (listing_unit, nml=solve, iostat=ios, iomsg=msg)
            return
        end if
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

    !> One '&adapt ... /' record into config%adapt (unchanged if it fails).
    subroutine adapt_record(record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
        real(wp) :: tolerance, theta, sigma
        integer :: max_dofs, max_levels, p_max
        character(len=len(config%adapt%strategy)) :: strategy
        namelist /adapt/ tolerance, max_dofs, max_levels, theta, strategy, sigma, p_max

        tolerance = config%adapt%tolerance
        max_dofs = config%adapt%max_dofs
        max_levels = config%adapt%max_levels
        theta = config%adapt%theta
        strategy = config%adapt%strategy
        sigma = config%adapt%sigma
        p_max = config%adapt%p_max
        if (present(listing_unit)) then
            write (listing_unit, nml=adapt, iostat=ios, iomsg=msg)
            return
        end if
        read (record, nml=adapt, iostat=ios, iomsg=msg)
        if (ios /= 0) return
        config%adapt%tolerance = tolerance
        config%adapt%max_dofs = max_dofs
        config%adapt%max_levels = max_levels
        config%adapt%theta = theta
        config%adapt%strategy = strategy
        config%adapt%sigma = sigma
        config%adapt%p_max = p_max
    end subroutine adapt_record
end module input_records
