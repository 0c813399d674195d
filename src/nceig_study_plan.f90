! SPDX-License-Identifier: MIT
!> nceig-study-plan STUDY.nml OUTDIR: the plan of a study (scripts/nceig-study). Reads the
!> study file (study_input), judges every point through nceig's own input reader (the
!> template groups with the point's geometry, Poisson ratio and analysis, as `--set` would
!> give them), and writes in OUTDIR (an existing folder):
!>   plan/template.nml      the template groups, on the lines of the study file
!>   plan/geometries        index, kind (rectangle, geo, msh), label, path: tab-separated
!>   plan/tasks             id, geometry index, geometry label, poisson, runs (cn, thr)
!>   plan/lambdas           the study's lambdas, one per line
!>   plan/mesh_size         the Gmsh element size of its .geo geometries
!>   tasks/ID/cn.nml        the lambda_sweep input of task ID (quantity c_n)
!>   tasks/ID/thr.nml       its threshold input (quantities lambda+-, onsets)
!> and prints the task list on stdout. One task per (geometry, nu). Bad input: one stderr
!> line naming the study file, the group, the variable and what was expected; exit 2.
program nceig_study_plan
    use iso_fortran_env, only: output_unit
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_IO
    use process_exit, only: exit_with, stop_with, stop_on_failure
    use strings, only: to_string, zero_padded, text_t, append_text
    use real_format, only: real_to_text
    use filesystem, only: make_directories, is_directory
    use run_config, only: config_t
    use input_config, only: read_input
    use input_validation, only: one_climb_possible
    use command_line, only: command_argument
    use input_records, only: read_record, LISTING_LINE_LEN
    use input_table, only: KNOWN_GROUPS
    use study_input, only: study_t, read_study
    use version, only: NCEIG_VERSION
    implicit none

    character(len=*), parameter :: PROGRAM_NAME = 'nceig-study'
    character(len=*), parameter :: USAGE = 'usage: nceig-study-plan STUDY.nml OUTDIR'
    character(len=1), parameter :: TAB = achar(9)
    type(study_t) :: study
    type(status_t) :: stat
    character(len=:), allocatable :: study_path, outdir, template_path, id, task_dir
    integer :: g, k, unit_tasks, unit_geometries, unit_lambdas
    !> the task's c_n run adapts its thresholds too (&sweep adapt_thresholds): no 'thr' run
    logical :: joint = .false.

    call parse_arguments(study_path, outdir)
    call read_study(study_path, study, stat)
    call stop_on_failure(PROGRAM_NAME, stat)

    call make_folder(outdir//'/plan')
    template_path = outdir//'/plan/template.nml'
    call write_text(template_path, study%template)

    open (newunit=unit_geometries, file=outdir//'/plan/geometries', status='replace', &
          action='write')
    do g = 1, size(study%label)
        write (unit_geometries, '(a)') to_string(g)//TAB//trim(study%geometry_kind(g))//TAB &
            //trim(study%label(g))//TAB//trim(study%geometry(g))
    end do
    close (unit_geometries)
    open (newunit=unit_lambdas, file=outdir//'/plan/lambdas', status='replace', action='write')
    do k = 1, size(study%lambdas)
        write (unit_lambdas, '(a)') real_to_text(study%lambdas(k))
    end do
    close (unit_lambdas)
    call write_text(outdir//'/plan/mesh_size', real_to_text(study%mesh_size)//achar(10))

    open (newunit=unit_tasks, file=outdir//'/plan/tasks', status='replace', action='write')
    do g = 1, size(study%label)
        do k = 1, size(study%poisson)
            id = 'g'//zero_padded(g, 2)//'_nu'//zero_padded(k, 2)
            task_dir = outdir//'/tasks/'//id
            call make_folder(task_dir)
            joint = .false.
            if (study%c_n) call write_point('lambda_sweep', 'cn')
            if (study%thresholds .and. .not. joint) call write_point('threshold', 'thr')
            write (unit_tasks, '(a)') id//TAB//to_string(g)//TAB//trim(study%label(g))//TAB &
                //real_to_text(study%poisson(k))//TAB//trim(runs())
            write (output_unit, '(a)') id//'  geometry '//trim(study%label(g))//', nu = ' &
                //real_to_text(study%poisson(k))//', runs: '//trim(runs())
        end do
    end do
    close (unit_tasks)
    deallocate (study%path, study%geometry, study%geometry_kind, study%label, study%width, &
                study%poisson, study%lambdas, study%template)
    call exit_with(0)

contains

    subroutine parse_arguments(study_path, outdir)
        character(len=:), allocatable, intent(out) :: study_path, outdir
        character(len=:), allocatable :: first
        select case (command_argument_count())
        case (1)
            first = command_argument(1)
            if (first == '--help' .or. first == '-h') then
                write (output_unit, '(a)') USAGE
                call exit_with(0)
            else if (first == '--version') then
                write (output_unit, '(a)') 'nceig '//NCEIG_VERSION
                call exit_with(0)
            end if
            call stop_with(PROGRAM_NAME, USAGE, STATUS_BAD_INPUT)
        case (2)
            study_path = command_argument(1)
            outdir = command_argument(2)
            if (.not. is_directory(outdir)) call stop_with(PROGRAM_NAME, outdir// &
                ': no such folder: expected the study''s output folder', STATUS_BAD_INPUT)
        case default
            call stop_with(PROGRAM_NAME, USAGE, STATUS_BAD_INPUT)
        end select
    end subroutine parse_arguments

    !> 'cn thr', 'cn' or 'thr': the runs of every task ('cn' alone also where it adapts
    !> the thresholds in its climb: `joint`).
    function runs() result(text)
        character(len=8) :: text
        text = ''
        if (study%c_n) text = 'cn'
        if (study%thresholds .and. .not. joint) text = trim(text)//merge(' thr', 'thr ', &
                                                                         study%c_n)
        text = adjustl(text)
    end function runs

    !> The input of run `name` (analysis `kind`) of the task in task_dir at geometry g,
    !> Poisson ratio k: the template read by nceig's own reader with the point's values
    !> set as --set sets them, so that a point nceig would refuse is refused here, named
    !> in the study file's terms; then written as a complete, normalized nceig input.
    subroutine write_point(kind, name)
        character(len=*), intent(in) :: kind, name
        type(text_t), allocatable :: settings(:)
        type(config_t) :: config
        type(status_t) :: point_stat
        allocate (settings(0))
        call append_text(settings, 'analysis%kind='//kind)
        call append_text(settings, 'output%modes=1')
        call append_text(settings, 'material%poisson='//real_to_text(study%poisson(k)))
        call append_text(settings, 'output%directory='//task_dir//'/'//name)
        ! The mode files of the c_n run (study.pvd): at the study's last lambda.
        if (kind == 'lambda_sweep') call append_text(settings, 'analysis%lambda=' &
            //real_to_text(study%lambdas(size(study%lambdas))))
        if (.not. study%task_plots) call append_text(settings, 'output%plot=.false.')
        if (.not. study%strategy_given) call append_text(settings, 'adapt%strategy=hp')
        if (.not. study%tolerance_given) call append_text(settings, 'adapt%tolerance=1e-8')
        if (study%geometry_kind(g) == 'rectangle') then
            call append_text(settings, 'mesh%source=rectangle')
            if (study%width(g) > 0.0_wp) call append_text(settings, 'mesh%width=' &
                //real_to_text(study%width(g)))
        else
            ! Relative paths, as nceig sees them from the task's folder where it runs, so
            ! that the text and its hash do not hold OUTDIR (--set paths stay as given).
            call append_text(settings, 'mesh%source=gmsh')
            call append_text(settings, 'mesh%file=../../meshes/g'//zero_padded(g, 2)//'.msh')
        end if
        call append_text(settings, 'output%directory='//name)
        call read_input(template_path, config, point_stat, settings)
        if (.not. point_stat%ok()) call stop_with(PROGRAM_NAME, in_study_terms( &
            point_stat%message), point_stat%code)
        ! c_n and the thresholds in one hp climb (&sweep adapt_thresholds), where the
        ! template adapts on hp levels; h levels adapt each point alone: two runs
        joint = study%thresholds .and. one_climb_possible(config)
        call write_input(task_dir//'/'//name//'.nml', config, kind == 'lambda_sweep')
    end subroutine write_point

    !> A message about the template (plan/template.nml) or about the point's values
    !> ('--set'), told in the study file's terms.
    function in_study_terms(message) result(text)
        character(len=*), intent(in) :: message
        character(len=:), allocatable :: text
        integer :: at
        text = message
        at = index(text, template_path)
        if (at > 0) text = text(1:at - 1)//study_path//text(at + len(template_path):)
        if (index(text, '--set') == 1) text = study_path//': the point geometry '// &
            trim(study%label(g))//', poisson = '//real_to_text(study%poisson(k))// &
            ' with the template:'//text(len('--set') + 1:)
    end function in_study_terms

    !> The complete input of a point: every group nceig reads, from the namelist write of
    !> its validated config (the runtime's own spelling of every value, trailing blanks of
    !> text values dropped), but &sweep, written here with the study's lambdas (c_n) or
    !> left to its defaults (the thresholds' boundary search range).
    subroutine write_input(path, config, with_lambdas)
        character(len=*), intent(in) :: path
        type(config_t), intent(inout) :: config
        logical, intent(in) :: with_lambdas
        character(len=LISTING_LINE_LEN) :: line
        character(len=1024) :: msg
        integer :: scratch, unit, ios, i
        open (newunit=scratch, status='scratch', action='readwrite', delim='quote')
        do i = 1, size(KNOWN_GROUPS)
            select case (trim(KNOWN_GROUPS(i)))
            case ('sweep', 'branch', 'solve')
                cycle
            end select
            call read_record(trim(KNOWN_GROUPS(i)), '', config, ios, msg, listing_unit=scratch)
            if (ios /= 0) call stop_with(PROGRAM_NAME, path//': cannot write &'// &
                                         trim(KNOWN_GROUPS(i))//': '//trim(msg), STATUS_IO)
        end do
        rewind (scratch)
        open (newunit=unit, file=path, status='replace', action='write', iostat=ios, &
              iomsg=msg)
        if (ios /= 0) call stop_with(PROGRAM_NAME, path//': '//trim(msg), STATUS_IO)
        ! Nothing but the point itself: the text is hashed (the task key), so the study
        ! file's name or folder must not be in it.
        write (unit, '(a)') '! A point of a study, written by nceig-study-plan'
        do
            read (scratch, '(a)', iostat=ios) line
            if (ios /= 0) exit
            write (unit, '(a)') trim(without_padding(line))
        end do
        close (scratch)
        if (with_lambdas) then
            write (unit, '(a)') '&sweep'
            write (unit, '(a)') ' lambdas = '//real_to_text(study%lambdas(1))
            do i = 2, size(study%lambdas)
                write (unit, '(a)') '  , '//real_to_text(study%lambdas(i))
            end do
            if (joint) write (unit, '(a)') ' adapt_thresholds = T'
            write (unit, '(a)') '/'
        end if
        close (unit)
    end subroutine write_input

    !> A namelist line with the blanks that pad a quoted text value dropped: gfortran
    !> writes every character of the variable ('"p1      ",').
    pure function without_padding(line) result(text)
        character(len=*), intent(in) :: line
        character(len=:), allocatable :: text
        integer :: i, j
        logical :: inside
        text = ''
        inside = .false.
        i = 1
        do while (i <= len_trim(line))
            if (line(i:i) == '"') then
                if (inside .and. i < len_trim(line)) then
                    if (line(i + 1:i + 1) == '"') then   ! a doubled quote inside the text
                        text = text//'""'
                        i = i + 2
                        cycle
                    end if
                end if
                if (inside) then
                    j = len(text)
                    do while (j > 0)
                        if (text(j:j) /= ' ') exit
                        j = j - 1
                    end do
                    text = text(1:j)
                end if
                inside = .not. inside
            end if
            text = text//line(i:i)
            i = i + 1
        end do
    end function without_padding

    subroutine make_folder(path)
        character(len=*), intent(in) :: path
        type(status_t) :: folder_stat
        call make_directories(path, folder_stat)
        call stop_on_failure(PROGRAM_NAME, folder_stat)
    end subroutine make_folder

    subroutine write_text(path, text)
        character(len=*), intent(in) :: path, text
        integer :: unit, ios
        character(len=1024) :: msg
        open (newunit=unit, file=path, status='replace', action='write', access='stream', &
              form='unformatted', iostat=ios, iomsg=msg)
        if (ios /= 0) call stop_with(PROGRAM_NAME, path//': '//trim(msg), STATUS_IO)
        write (unit) text
        close (unit)
    end subroutine write_text
end program nceig_study_plan
