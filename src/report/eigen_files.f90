! SPDX-License-Identifier: MIT
!> The files, summary.json keys and stdout lines of an eigen solve, from its result
!> (eigen_result_t): eigenvalues.csv, mode_NNN.vtu, K.mtx and B.mtx, mode_001.png, the keys
!> every summary.json starts with, and the summary lines. The eigen run writes them, and so
!> do the other analyses for the eigen solve they contain.
module eigen_files
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string, zero_padded, short_real_text, seconds_text
    use real_format, only: real_to_text, known_text
    use timer, only: timings_t
    use version, only: NCEIG_VERSION
    use run_config, only: config_t
    use problem, only: problem_t
    use eigen_analysis, only: eigen_result_t, solver_name, operator_name, critical_cn
    use critical_point, only: slip_sign, critical_c_t
    use spectrum, only: spectrum_t, kind_name, KIND_COMPLEX, KIND_POSITIVE
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use csv_writer, only: csv_writer_t
    use vtk_writer, only: write_vtu
    use matrix_market, only: write_matrix_market
    use element_types, only: element_name, element_corners
    use pictures, only: draw_mode
    use blas_info, only: blas_in_use
    use error_estimate, only: error_estimate_t, estimate_label
    use hp_adaptive, only: HP_ESTIMATE
    implicit none
    private
    public :: eigen_summary_json, no_eigen_summary_json, summary_lines, &
              write_eigenvalues_csv, write_modes, write_eigen_files, modes_to_write, &
              mode_field_names, mode_field_values

contains

    !> summary.json of an eigen run; other analyses add their own keys to it.
    function eigen_summary_json(config, prob, res, timings) result(summary)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        type(timings_t), intent(in) :: timings
        type(json_object_t) :: summary
        summary = summary_json(config, prob, timings, res)
    end function eigen_summary_json

    !> The same keys for a run that solved no eigenproblem: those of the spectrum are null
    !> (n_eigenvalues 0), lambda is &analysis lambda.
    function no_eigen_summary_json(config, prob, timings) result(summary)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(in) :: timings
        type(json_object_t) :: summary
        summary = summary_json(config, prob, timings)
    end function no_eigen_summary_json

    !> The keys every summary.json starts with: the run, the mesh, the problem sizes, the
    !> lowest positive eigenvalue with its meaning (null without `res`), the timings.
    function summary_json(config, prob, timings, res) result(summary)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(in) :: timings
        type(eigen_result_t), intent(in), optional :: res
        type(json_object_t) :: summary
        character(len=*), parameter :: LOWEST_KEYS(8) = [character(len=30) :: &
            'lowest_positive_mu', 'critical_c_n', 'critical_c_t', &
            'lowest_positive_condition', 'lowest_positive_residual', &
            'lowest_positive_error_estimate', 'lowest_positive_error_bar', &
            'lowest_positive_roundoff']
        integer :: lowest, i, blas_threads
        real(wp) :: mu, lambda
        character(len=:), allocatable :: blas_library, blas_config

        lambda = config%analysis%lambda
        lowest = 0
        if (present(res)) then
            lambda = res%lambda
            lowest = res%spec%lowest_positive()
        end if
        call summary%add_string('nceig_version', NCEIG_VERSION)
        call summary%add_string('input', config%input_file)
        call summary%add_string('analysis', trim(config%analysis%kind))
        call summary%add_real('lambda', lambda)
        ! From the mesh: a Gmsh file decides its element type, not &mesh element.
        call summary%add_string('element', mesh_element(config, prob))
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
        if (present(res)) then
            call summary%add_string('solver', solver_name(res%solver))
            call summary%add_string('operator', operator_name(res%solver, config%eigen%operator))
        else
            call summary%add_null('solver')
            call summary%add_null('operator')
        end if
        if (lowest > 0) then
            mu = real(res%spec%mu(lowest), wp)
            call summary%add_real('lowest_positive_mu', mu)
            call summary%add_real('critical_c_n', mu)
            call summary%add_real('critical_c_t', critical_c_t(mu, res%lambda))
            ! ARPACK gives no condition number (-1 inside): null, never a number to misread
            call summary%add_real_or_null('lowest_positive_condition', &
                                          res%spec%condition(lowest), &
                                          res%spec%condition(lowest) >= 0.0_wp)
            call summary%add_real('lowest_positive_residual', res%spec%residual(lowest))
            ! |mu - mu_h| / mu_h estimated (error_estimate); null where not computed
            call summary%add_real_or_null('lowest_positive_error_estimate', &
                                          abs(res%error%relative), res%error%computed)
            ! the relative bar quoted with c_n (error_bar); null where there is none
            call summary%add_real_or_null('lowest_positive_error_bar', res%error%bar, &
                                          res%error%computed .and. res%error%bar >= 0.0_wp)
            ! the round-off part of that bar (module roundoff); null where unknown
            call summary%add_real_or_null('lowest_positive_roundoff', res%roundoff, &
                                          res%roundoff >= 0.0_wp)
        else
            do i = 1, size(LOWEST_KEYS)
                call summary%add_null(trim(LOWEST_KEYS(i)))
            end do
        end if
        call summary%add_real('cn_max', config%eigen%cn_max)
        if (present(res)) then
            call summary%add_real_array('critical_cn', critical_cn(res%spec, config%eigen%cn_max))
        else
            call summary%add_real_array('critical_cn', [real(wp) ::])
        end if
        call summary%add_integer('slip_sign', slip_sign(lambda))
        if (present(res)) then
            call summary%add_integer('n_eigenvalues', res%spec%n())
            call summary%add_real('max_residual', res%spec%max_residual())
            call summary%add_integer('operator_applications', res%spec%n_operator)
            call summary%add_logical('dense_decision', res%spec%dense_decision)
        else
            call summary%add_integer('n_eigenvalues', 0)
            call summary%add_null('max_residual')
            call summary%add_integer('operator_applications', 0)
            call summary%add_null('dense_decision')
        end if
        call blas_in_use(blas_library, blas_config, blas_threads)
        call summary%add_string('blas_library', blas_library)
        call summary%add_string('blas_config', blas_config)
        call summary%add_integer('blas_threads', blas_threads)
        call summary%add_real('time_assembly_s', timings%assembly)
        call summary%add_real('time_ordering_s', timings%ordering)
        call summary%add_real('time_factor_s', timings%factor)
        call summary%add_real('time_reduction_s', timings%reduction)
        call summary%add_real('time_eigen_s', timings%eigen)
        ! part of time_eigen_s: the left eigenvector and the round-off bound
        if (present(res)) then
            call summary%add_real('time_roundoff_s', res%spec%roundoff_seconds)
        else
            call summary%add_real('time_roundoff_s', 0.0_wp)
        end if
        call summary%add_real('time_output_s', timings%output)
        call summary%add_real('time_total_s', timings%total)
        call summary%add_string_array('warnings', [character(len=1) ::])
        if (present(res)) then
            if (allocated(res%warnings)) call summary%add_string_array('warnings', res%warnings)
        end if
    end function summary_json

    !> index,re,im,kind,residual,condition,error_estimate,error_bar; an unknown condition is
    !> left empty, and so are error_estimate and error_bar but for the lowest positive mu
    !> when `error` holds them.
    subroutine write_eigenvalues_csv(path, spec, stat, error)
        character(len=*), intent(in) :: path
        type(spectrum_t), intent(in) :: spec
        type(status_t), intent(out) :: stat
        type(error_estimate_t), intent(in), optional :: error
        type(csv_writer_t) :: csv
        character(len=:), allocatable :: estimate, bar
        integer :: i

        call csv%open(path, 'index,re,im,kind,residual,condition,error_estimate,error_bar')
        do i = 1, spec%n()
            estimate = ''
            bar = ''
            if (present(error) .and. i == spec%lowest_positive()) then
                if (error%computed) estimate = real_to_text(abs(error%relative))
                if (error%computed .and. error%bar >= 0.0_wp) bar = real_to_text(error%bar)
            end if
            call csv%row(to_string(i)//','//real_to_text(real(spec%mu(i), wp))//','// &
                real_to_text(aimag(spec%mu(i)))//','//kind_name(spec%kind(i))//','// &
                real_to_text(spec%residual(i))//','// &
                known_text(spec%condition(i) >= 0.0_wp, spec%condition(i))//','//estimate// &
                ','//bar)
        end do
        call csv%close(stat)
    end subroutine write_eigenvalues_csv

    !> How many modes of `spec` a run writes (mode files, and mode_001.png when at least one):
    !> the first &output modes; for 'threshold' and 'lambda_sweep', whose modes are those of
    !> the critical c_n, only the positive real mu among them (they come first), so none at
    !> a lambda without a positive mu.
    pure integer function modes_to_write(config, spec)
        type(config_t), intent(in) :: config
        type(spectrum_t), intent(in) :: spec
        modes_to_write = max(0, min(config%output%modes, size(spec%vectors, 2)))
        if (trim(config%analysis%kind) == 'threshold' .or. &
            trim(config%analysis%kind) == 'lambda_sweep') &
            modes_to_write = min(modes_to_write, count(spec%kind == KIND_POSITIVE))
    end function modes_to_write

    !> The field data of a mode file: what the mode is the mode of.
    pure function mode_field_names() result(names)
        character(len=7) :: names(4)
        names = [character(len=7) :: 'mu', 'mu_imag', 'lambda', 'nu']
    end function mode_field_names

    !> mu (its real and imaginary parts, in the input's units) of mode i of `spec`, at
    !> `lambda` for the material of Poisson ratio `nu`, in mode_field_names' order.
    pure function mode_field_values(spec, i, lambda, nu) result(values)
        type(spectrum_t), intent(in) :: spec
        integer, intent(in) :: i
        real(wp), intent(in) :: lambda, nu
        real(wp) :: values(4)
        values = [real(spec%mu(i), wp), aimag(spec%mu(i)), lambda, nu]
    end function mode_field_values

    !> mode_001.vtu ...: displacement (real part) and, for complex modes, displacement_imag;
    !> the mode of the lowest positive mu gets the cell data error_indicator when `error`
    !> holds its estimate (eta_K relative to mu, see error_estimate); every file the field
    !> data mu, mu_imag, lambda (the run's, `lambda`) and nu.
    subroutine write_modes(stage, prob, spec, n_modes, vtk_format, stat, error, lambda)
        type(output_stage_t), intent(inout) :: stage
        type(problem_t), intent(in) :: prob
        type(spectrum_t), intent(in) :: spec
        integer, intent(in) :: n_modes
        character(len=*), intent(in) :: vtk_format   !! VTK_BINARY or VTK_ASCII
        type(status_t), intent(out) :: stat
        type(error_estimate_t), intent(in), optional :: error
        real(wp), intent(in) :: lambda
        character(len=*), parameter :: FIELD_NAMES(2) = [character(len=17) :: &
                                                          'displacement', 'displacement_imag']
        real(wp), allocatable :: fields(:, :, :)
        character(len=:), allocatable :: path
        integer :: i, n_nodes

        n_nodes = prob%mesh%n_nodes()
        do i = 1, min(n_modes, size(spec%vectors, 2))
            if (spec%kind(i) == KIND_COMPLEX) then
                allocate (fields(2, n_nodes, 2))
                fields(:, :, 2) = prob%dofs%nodal_field(aimag(spec%vectors(:, i)))
            else
                allocate (fields(2, n_nodes, 1))
            end if
            fields(:, :, 1) = prob%dofs%nodal_field(real(spec%vectors(:, i), wp))
            call stage%add('mode_'//zero_padded(i, 3)//'.vtu', path)
            if (with_indicators(i)) then
                call write_vtu(path, prob%mesh, &
                               FIELD_NAMES(1:size(fields, 3)), fields, vtk_format, stat, &
                               ['error_indicator'], reshape(error%indicators, &
                                                            [size(error%indicators), 1]), &
                               mode_field_names(), &
                               mode_field_values(spec, i, lambda, prob%poisson))
            else
                call write_vtu(path, prob%mesh, FIELD_NAMES(1:size(fields, 3)), fields, &
                               vtk_format, stat, field_names=mode_field_names(), &
                               field_values=mode_field_values(spec, i, lambda, prob%poisson))
            end if
            deallocate (fields)
            if (.not. stat%ok()) return
        end do

    contains

        logical function with_indicators(mode)
            integer, intent(in) :: mode
            with_indicators = .false.
            if (.not. present(error)) return
            with_indicators = error%computed .and. mode == spec%lowest_positive()
            if (with_indicators) with_indicators = size(error%indicators) == prob%mesh%n_cells()
        end function with_indicators
    end subroutine write_modes

    !> The element of the run: its name, or 'hp' for an hp run, whose graded mesh carries a
    !> degree per cell (the p1 of its geometry is not the element solved).
    function mesh_element(config, prob) result(name)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: name
        name = element_name(prob%mesh%element)
        if (config%adapt%tolerance > 0.0_wp .and. trim(config%adapt%strategy) == 'hp') &
            name = 'hp'
    end function mesh_element

    !> The human summary: mesh, sizes, the headline eigenvalue and the time of each phase.
    function summary_lines(config, prob, res, timings, plot_note) result(text)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        type(timings_t), intent(in) :: timings
        character(len=*), intent(in), optional :: plot_note   !! from write_eigen_files
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        integer :: lowest, i
        real(wp) :: mu
        real(wp), allocatable :: critical(:)

        text = 'nceig '//NCEIG_VERSION//': '//config%input_file//NL// &
            '  mesh        '//trim(config%mesh%source)//', '//mesh_element(config, prob)// &
            ', '//to_string(prob%mesh%n_cells())//' cells, '//to_string(prob%mesh%n_nodes())// &
            ' nodes'//NL// &
            '  problem     '//to_string(prob%dofs%n_free)//' dofs, '// &
            to_string(prob%contact%p())//' contact nodes, lambda = '//real_to_text(res%lambda)// &
            NL//'  solver      '//solver_name(res%solver)//': '//to_string(res%spec%n())// &
            ' eigenvalues, max backward error '//short_real_text(res%spec%max_residual())//NL
        lowest = res%spec%lowest_positive()
        if (lowest > 0) then
            mu = real(res%spec%mu(lowest), wp)
            text = text//'  lowest positive mu = critical c_n = '//real_to_text(mu)
            ! the headline quotes its bar, absolute: c_n = X +- B
            if (res%error%computed .and. res%error%bar >= 0.0_wp) text = text//' +- '// &
                short_real_text(res%error%bar*mu)
            if (res%error%computed .and. res%error%bar >= 1.0_wp) text = text// &
                ' (no certain digit)'
            text = text//NL// &
                '  critical c_t = mu |lambda| = '//real_to_text(critical_c_t(mu, res%lambda))// &
                ', slip sign s = '//to_string(slip_sign(res%lambda))// &
                ' (u_t '//merge('< 0', '> 0', slip_sign(res%lambda) < 0)//' along t)'//NL
            if (res%error%computed) then
                if (estimate_label(res%error) == HP_ESTIMATE) then
                    ! the change is the previous level's error: the bar may be below it
                    text = text//'  relative change of mu to the previous hp level: '// &
                        short_real_text(abs(res%error%relative))// &
                        ' (the error of that level); error bar '// &
                        short_real_text(res%error%bar)//NL
                else
                    text = text//'  relative error estimate of mu: '// &
                        short_real_text(abs(res%error%relative))//' ('// &
                        estimate_label(res%error)//'); error bar '// &
                        short_real_text(res%error%bar)//NL
                end if
            end if
            if (allocated(res%error%skipped)) text = text//'  relative error estimate of mu: '// &
                res%error%skipped//NL
            if (res%roundoff >= 0.0_wp) then
                text = text//'  round-off bound of mu: '//short_real_text(res%roundoff)// &
                       ' relative'
                if (res%quotient) text = text//' (Rayleigh quotient without a stored K)'
                if (res%error%computed) text = text//' (in the error bar)'
                text = text//NL
            end if
        else
            text = text//'  no positive real eigenvalue for this lambda'//NL
        end if
        if (config%eigen%cn_max > 0.0_wp) then
            critical = critical_cn(res%spec, config%eigen%cn_max)
            text = text//'  critical c_n in (0, '//real_to_text(config%eigen%cn_max)//']: '// &
                to_string(size(critical))
            do i = 1, size(critical)
                text = text//merge(': ', ', ', i == 1)//real_to_text(critical(i))
            end do
            text = text//NL
        end if
        text = text//'  time [s]    assembly '//seconds_text(timings%assembly)// &
            ', ordering '//seconds_text(timings%ordering)// &
            ', factor '//seconds_text(timings%factor)// &
            ', reduction '//seconds_text(timings%reduction)// &
            ', eigen '//seconds_text(timings%eigen)// &
            ', output '//seconds_text(timings%output)// &
            ', total '//seconds_text(timings%total)//NL// &
            '  output      '//trim(config%output%directory)
        if (present(plot_note)) then
            if (len(plot_note) > 0) text = text//NL//'  mode plot   '//plot_note
        end if
        if (allocated(res%warnings)) then
            do i = 1, size(res%warnings)
                text = text//NL//'warning: '//trim(res%warnings(i))
            end do
        end if
    end function summary_lines

    !> eigenvalues.csv, mode_NNN.vtu and K.mtx, B.mtx as &output asks, and mode_001.png, into
    !> `stage`: the files of an eigen run, which the threshold and sweep runs write too.
    !> `plot_note`: where the picture is, why it is missing, or '' when none was asked for.
    subroutine write_eigen_files(stage, config, prob, res, stat, plot_note)
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        character(len=:), allocatable, intent(out), optional :: plot_note
        character(len=:), allocatable :: path
        call stage%add('eigenvalues.csv', path)
        call write_eigenvalues_csv(path, res%spec, stat, res%error)
        if (stat%ok() .and. config%output%vtk) call write_modes(stage, prob, res%spec, &
            modes_to_write(config, res%spec), trim(config%output%vtk_format), stat, &
            res%error, res%lambda)
        if (stat%ok() .and. config%output%matrices) call write_matrices(stage, prob, res, stat)
        if (.not. present(plot_note)) return
        plot_note = ''
        if (.not. (stat%ok() .and. config%output%plot)) return
        if (modes_to_write(config, res%spec) > 0) then
            call draw_first_mode(stage, config, prob, res, plot_note)
        else if (config%output%modes > 0 .and. size(res%spec%vectors, 2) > 0) then
            plot_note = 'none, and no mode file: no positive mu at lambda = '// &
                real_to_text(res%lambda)//' (a threshold or sweep run writes those only)'
        end if
    end subroutine write_eigen_files

    !> K.mtx and B.mtx of the input problem: prob%k and res%b are in prob%units (powers of
    !> two, so the conversion is exact; beyond the binary64 range Infinity).
    subroutine write_matrices(stage, prob, res, stat)
        type(output_stage_t), intent(inout) :: stage
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: path
        call stage%add('K.mtx', path)
        call write_matrix_market(path, prob%units%stiffness_to_input(prob%k), stat)
        if (.not. stat%ok()) return
        call stage%add('B.mtx', path)
        call write_matrix_market(path, prob%units%mass_to_input(res%b), stat)
    end subroutine write_matrices

    !> mode_001.png of the first mode (its real part), joined to the set when drawn.
    subroutine draw_first_mode(stage, config, prob, res, note)
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        character(len=:), allocatable, intent(out) :: note
        call draw_mode(stage, trim(config%output%directory), 'mode 1: mu = '// &
            real_to_text(real(res%spec%mu(1), wp))//', lambda = '//real_to_text(res%lambda), &
            prob%mesh%coords, prob%mesh%cells, element_corners(prob%mesh%element), &
            prob%dofs%nodal_field(real(res%spec%vectors(:, 1), wp)), note)
    end subroutine draw_first_mode
end module eigen_files
