! SPDX-License-Identifier: MIT
!> The files of an eigen run (SPEC section 7): eigenvalues.csv, mode_NNN.vtu, K.mtx and
!> B.mtx, and summary.json last, all staged and moved into place together; and the short
!> human summary printed on stdout.
module results_output
    use kinds, only: wp
    use status, only: status_t, STATUS_IO
    use strings, only: to_string, zero_padded, short_real_text, seconds_text
    use real_format, only: real_to_text
    use timer, only: wall_time, timings_t
    use version, only: NCEIG_VERSION
    use run_config, only: config_t
    use problem, only: problem_t
    use eigen_analysis, only: eigen_result_t
    use spectrum, only: spectrum_t, kind_name, KIND_COMPLEX
    use output_stage, only: output_stage_t
    use filesystem, only: close_output
    use json_writer, only: json_object_t
    use vtk_writer, only: write_vtu
    use matrix_market, only: write_matrix_market
    use dof_map, only: dof_map_t
    use mesh, only: element_name
    implicit none
    private
    public :: write_eigen_outputs, summary_lines, nodal_field, eigen_summary_json
    public :: write_eigenvalues_csv, write_modes, slip_sign, write_eigen_files, &
              commit_with_summary

contains

    !> Write every output of an eigen run to the output directory, or none of them.
    subroutine write_eigen_outputs(config, prob, res, run_start, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        real(wp), intent(in) :: run_start          !! wall_time() at the start of the run
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(output_stage_t) :: stage
        type(json_object_t) :: summary
        real(wp) :: start

        start = wall_time()
        call stage%begin(trim(config%output%directory), stat)
        if (.not. stat%ok()) return
        call write_eigen_files(stage, config, prob, res, stat)
        if (stat%ok()) then
            timings%output = wall_time() - start
            timings%total = wall_time() - run_start
            summary = eigen_summary_json(config, prob, res, timings)
            call commit_with_summary(stage, summary, stat)
        end if
        if (.not. stat%ok()) call stage%abort()
    end subroutine write_eigen_outputs

    !> Every analysis ends its outputs here: summary.json is registered last, as the commit's
    !> completion marker, and lists the files of its set (an older run may have left other
    !> mode_NNN.vtu); then the staged files move into place together.
    subroutine commit_with_summary(stage, summary, stat)
        type(output_stage_t), intent(inout) :: stage
        type(json_object_t), intent(inout) :: summary
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: summary_path
        summary_path = stage%path('summary.json')
        call summary%add_string_array('files', stage%file_names(64))
        call summary%write(summary_path, stat)
        if (stat%ok()) call stage%commit(stat)
    end subroutine commit_with_summary

    !> summary.json of an eigen run; other analyses add their own keys to it.
    function eigen_summary_json(config, prob, res, timings) result(summary)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        type(timings_t), intent(in) :: timings
        type(json_object_t) :: summary
        integer :: lowest
        real(wp) :: mu

        lowest = res%spec%lowest_positive()
        call summary%add_string('nceig_version', NCEIG_VERSION)
        call summary%add_string('input', config%input_file)
        call summary%add_string('analysis', trim(config%analysis%kind))
        call summary%add_real('lambda', res%lambda)
        ! From the mesh: a Gmsh file decides its element type, not &mesh element.
        call summary%add_string('element', element_name(prob%mesh%element))
        call summary%add_string('mesh_source', trim(config%mesh%source))
        if (config%mesh%source == 'rectangle') then
            call summary%add_integer('nx', config%mesh%nx)
            call summary%add_integer('ny', config%mesh%ny)
            call summary%add_string('diagonal', trim(config%mesh%diagonal))
        end if
        if (config%mesh%source == 'gmsh') call summary%add_string('mesh_file', &
                                                                 trim(config%mesh%file))
        call summary%add_real('young', prob%young)
        call summary%add_real('poisson', prob%poisson)
        call summary%add_integer('n_nodes', prob%mesh%n_nodes())
        call summary%add_integer('n_cells', prob%mesh%n_cells())
        call summary%add_integer('n_dofs', prob%dofs%n_free)
        call summary%add_integer('nnz_k', prob%k%nnz())
        call summary%add_integer('n_contact', prob%contact%p())
        call summary%add_string('solver', res%solver)
        if (lowest > 0) then
            mu = real(res%spec%mu(lowest), wp)
            call summary%add_real('lowest_positive_mu', mu)
            call summary%add_real('critical_c_n', mu)
            call summary%add_real('critical_c_t', mu*abs(res%lambda))
            call summary%add_real('lowest_positive_condition', res%spec%condition(lowest))
            call summary%add_real('lowest_positive_residual', res%spec%residual(lowest))
        else
            call summary%add_null('lowest_positive_mu')
            call summary%add_null('critical_c_n')
            call summary%add_null('critical_c_t')
            call summary%add_null('lowest_positive_condition')
            call summary%add_null('lowest_positive_residual')
        end if
        call summary%add_integer('slip_sign', slip_sign(res%lambda))
        call summary%add_integer('n_eigenvalues', res%spec%n())
        call summary%add_real('max_residual', res%spec%max_residual())
        call summary%add_integer('operator_applications', res%spec%n_operator)
        call summary%add_real('time_assembly_s', timings%assembly)
        call summary%add_real('time_ordering_s', timings%ordering)
        call summary%add_real('time_factor_s', timings%factor)
        call summary%add_real('time_reduction_s', timings%reduction)
        call summary%add_real('time_eigen_s', timings%eigen)
        call summary%add_real('time_output_s', timings%output)
        call summary%add_real('time_total_s', timings%total)
        if (allocated(res%warnings)) then
            call summary%add_string_array('warnings', res%warnings)
        else
            call summary%add_string_array('warnings', [character(len=1) ::])
        end if
    end function eigen_summary_json

    !> s = -sgn(lambda): the slip direction along t on the critical branch (0 for lambda = 0).
    pure integer function slip_sign(lambda)
        real(wp), intent(in) :: lambda
        slip_sign = 0
        if (lambda > 0.0_wp) slip_sign = -1
        if (lambda < 0.0_wp) slip_sign = 1
    end function slip_sign

    !> index,re,im,kind,residual,condition; an unknown condition is left empty.
    subroutine write_eigenvalues_csv(path, spec, stat)
        character(len=*), intent(in) :: path
        type(spectrum_t), intent(in) :: spec
        type(status_t), intent(out) :: stat
        character(len=512) :: msg
        character(len=:), allocatable :: condition
        integer :: unit, ios, i

        open (newunit=unit, file=path, status='replace', action='write', iostat=ios, iomsg=msg)
        if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) &
            'index,re,im,kind,residual,condition'
        do i = 1, spec%n()
            if (ios /= 0) exit
            condition = ''
            if (spec%condition(i) >= 0.0_wp) condition = real_to_text(spec%condition(i))
            write (unit, '(a)', iostat=ios, iomsg=msg) to_string(i)//','// &
                real_to_text(real(spec%mu(i), wp))//','//real_to_text(aimag(spec%mu(i)))// &
                ','//kind_name(spec%kind(i))//','//real_to_text(spec%residual(i))//','// &
                condition
        end do
        if (ios == 0) call close_output(unit, path, ios, msg)
        if (ios /= 0) call stat%fail(STATUS_IO, path//': cannot write: '//trim(msg))
    end subroutine write_eigenvalues_csv

    !> mode_001.vtu ...: displacement (real part) and, for complex modes, displacement_imag.
    subroutine write_modes(stage, prob, spec, n_modes, vtk_format, stat)
        type(output_stage_t), intent(inout) :: stage
        type(problem_t), intent(in) :: prob
        type(spectrum_t), intent(in) :: spec
        integer, intent(in) :: n_modes
        character(len=*), intent(in) :: vtk_format   !! VTK_BINARY or VTK_ASCII
        type(status_t), intent(out) :: stat
        character(len=*), parameter :: FIELD_NAMES(2) = [character(len=17) :: &
                                                          'displacement', 'displacement_imag']
        real(wp), allocatable :: fields(:, :, :)
        integer :: i, n_nodes

        n_nodes = prob%mesh%n_nodes()
        do i = 1, min(n_modes, size(spec%vectors, 2))
            if (spec%kind(i) == KIND_COMPLEX) then
                allocate (fields(2, n_nodes, 2))
                fields(:, :, 2) = nodal_field(prob%dofs, aimag(spec%vectors(:, i)))
            else
                allocate (fields(2, n_nodes, 1))
            end if
            fields(:, :, 1) = nodal_field(prob%dofs, real(spec%vectors(:, i), wp))
            call write_vtu(stage%path('mode_'//zero_padded(i, 3)//'.vtu'), prob%mesh, &
                           FIELD_NAMES(1:size(fields, 3)), fields, vtk_format, stat)
            deallocate (fields)
            if (.not. stat%ok()) return
        end do
    end subroutine write_modes

    !> A free-dof vector as a (2, n_nodes) nodal field, zero on the Dirichlet boundary.
    pure function nodal_field(dofs, x) result(field)
        type(dof_map_t), intent(in) :: dofs
        real(wp), intent(in) :: x(:)
        real(wp) :: field(2, size(dofs%free_dof, 2))
        integer :: node, c
        do node = 1, size(dofs%free_dof, 2)
            do c = 1, 2
                field(c, node) = 0.0_wp
                if (dofs%free_dof(c, node) > 0) field(c, node) = x(dofs%free_dof(c, node))
            end do
        end do
    end function nodal_field

    !> The human summary: mesh, sizes, the headline eigenvalue and the time of each phase.
    function summary_lines(config, prob, res, timings) result(text)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        type(timings_t), intent(in) :: timings
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        integer :: lowest, i
        real(wp) :: mu

        text = 'nceig '//NCEIG_VERSION//': '//config%input_file//NL// &
            '  mesh        '//trim(config%mesh%source)//', '//element_name(prob%mesh%element)// &
            ', '//to_string(prob%mesh%n_cells())//' cells, '//to_string(prob%mesh%n_nodes())// &
            ' nodes'//NL// &
            '  problem     '//to_string(prob%dofs%n_free)//' dofs, '// &
            to_string(prob%contact%p())//' contact nodes, lambda = '//real_to_text(res%lambda)// &
            NL//'  solver      '//res%solver//': '//to_string(res%spec%n())// &
            ' eigenvalues, max backward error '//short_real_text(res%spec%max_residual())//NL
        lowest = res%spec%lowest_positive()
        if (lowest > 0) then
            mu = real(res%spec%mu(lowest), wp)
            text = text//'  lowest positive mu = critical c_n = '//real_to_text(mu)//NL// &
                '  critical c_t = mu |lambda| = '//real_to_text(mu*abs(res%lambda))// &
                ', slip sign s = '//to_string(slip_sign(res%lambda))// &
                ' (u_t '//merge('< 0', '> 0', slip_sign(res%lambda) < 0)//' along t)'//NL
        else
            text = text//'  no positive real eigenvalue for this lambda'//NL
        end if
        text = text//'  time [s]    assembly '//seconds_text(timings%assembly)// &
            ', ordering '//seconds_text(timings%ordering)// &
            ', factor '//seconds_text(timings%factor)// &
            ', reduction '//seconds_text(timings%reduction)// &
            ', eigen '//seconds_text(timings%eigen)// &
            ', output '//seconds_text(timings%output)// &
            ', total '//seconds_text(timings%total)//NL// &
            '  output      '//trim(config%output%directory)
        if (allocated(res%warnings)) then
            do i = 1, size(res%warnings)
                text = text//NL//'warning: '//trim(res%warnings(i))
            end do
        end if
    end function summary_lines

    !> eigenvalues.csv, mode_NNN.vtu and K.mtx, B.mtx as &output asks, into `stage`: the
    !> files of an eigen run, which the threshold and sweep runs write too.
    subroutine write_eigen_files(stage, config, prob, res, stat)
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        call write_eigenvalues_csv(stage%path('eigenvalues.csv'), res%spec, stat)
        if (stat%ok() .and. config%output%vtk) call write_modes(stage, prob, res%spec, &
            config%output%modes, trim(config%output%vtk_format), stat)
        if (stat%ok() .and. config%output%matrices) then
            call write_matrix_market(stage%path('K.mtx'), prob%k, stat)
            if (stat%ok()) call write_matrix_market(stage%path('B.mtx'), res%b, stat)
        end if
    end subroutine write_eigen_files
end module results_output
