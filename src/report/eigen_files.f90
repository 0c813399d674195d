! SPDX-License-Identifier: MIT
!> The files of a spectrum, from an eigen result in the input's units (reported_units):
!> eigenvalues.csv, mode_NNN.vtu (on the mesh, or for an hp level on the sub-triangulation
!> of its hp field), K.mtx and B.mtx, mode_001.png. Every analysis with a spectrum writes
!> them.
module eigen_files
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string, zero_padded
    use real_format, only: real_to_text, known_text
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use eigen_solve, only: eigen_result_t
    use spectrum, only: spectrum_t, kind_name, KIND_COMPLEX, KIND_POSITIVE
    use run_inputs, only: ANALYSIS_THRESHOLD, ANALYSIS_SWEEP
    use output_stage, only: output_stage_t
    use csv_writer, only: csv_writer_t
    use vtk_writer, only: write_vtu
    use matrix_market, only: write_matrix_market
    use element_types, only: element_corners
    use mesh, only: mesh_t
    use hp_space, only: hp_space_t
    use hp_field, only: sample_hp_field
    use pictures, only: draw_mode
    use error_estimate, only: error_estimate_t
    implicit none
    private
    public :: write_eigenvalues_csv, write_modes, write_eigen_files, write_hp_modes

contains

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
    pure integer function modes_to_write(inputs, spec)
        type(run_inputs_t), intent(in) :: inputs
        type(spectrum_t), intent(in) :: spec
        modes_to_write = max(0, min(inputs%output%modes, size(spec%vectors, 2)))
        if (inputs%analysis == ANALYSIS_THRESHOLD .or. inputs%analysis == ANALYSIS_SWEEP) &
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

    !> eigenvalues.csv, mode_NNN.vtu and K.mtx, B.mtx as &output asks, and mode_001.png, into
    !> `stage`: the files of an eigen run, which the threshold and sweep runs write too.
    !> `plot_note`: where the picture is, why it is missing, or '' when none was asked for.
    subroutine write_eigen_files(stage, inputs, prob, res, stat, plot_note)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        character(len=:), allocatable, intent(out), optional :: plot_note
        character(len=:), allocatable :: path
        call stage%add('eigenvalues.csv', path)
        call write_eigenvalues_csv(path, res%spec, stat, res%error)
        if (stat%ok() .and. inputs%output%vtk) call write_modes(stage, prob, res%spec, &
            modes_to_write(inputs, res%spec), trim(inputs%output%vtk_format), stat, &
            res%error, res%lambda)
        if (stat%ok() .and. inputs%output%matrices) call write_matrices(stage, prob, res, stat)
        if (.not. present(plot_note)) return
        plot_note = ''
        if (.not. (stat%ok() .and. inputs%output%plot)) return
        if (modes_to_write(inputs, res%spec) > 0) then
            call draw_first_mode(stage, inputs, prob, res, plot_note)
        else if (inputs%output%modes > 0 .and. size(res%spec%vectors, 2) > 0) then
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
    subroutine draw_first_mode(stage, inputs, prob, res, note)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        character(len=:), allocatable, intent(out) :: note
        call draw_mode(stage, trim(inputs%output%directory), 'mode 1: mu = '// &
            real_to_text(real(res%spec%mu(1), wp))//', lambda = '//real_to_text(res%lambda), &
            prob%mesh%coords, prob%mesh%cells, element_corners(prob%mesh%element), &
            prob%dofs%nodal_field(real(res%spec%vectors(:, 1), wp)), note)
    end subroutine draw_first_mode
    !> mode_NNN.vtu: the real part of each kept mode (modes_to_write) of `spec` (on the hp
    !> problem `prob` with space `space`, at `lambda`), sampled on the sub-triangulation of
    !> hp_field, with each sub-cell's degree and the field data of write_modes' files.
    subroutine write_hp_modes(stage, inputs, prob, space, spec, lambda, stat)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(hp_space_t), intent(in) :: space
        type(spectrum_t), intent(in) :: spec
        real(wp), intent(in) :: lambda
        type(status_t), intent(out) :: stat
        type(mesh_t) :: sub
        real(wp), allocatable :: values(:, :), degree(:), mode(:)
        integer :: i
        character(len=:), allocatable :: path
        do i = 1, modes_to_write(inputs, spec)
            mode = real(spec%vectors(:, i), wp)
            call sample_hp_field(prob%mesh, space, prob%young, prob%poisson, &
                                 mode, sub, values, degree, stat)
            if (.not. stat%ok()) return
            call stage%add('mode_'//zero_padded(i, 3)//'.vtu', path)
            call write_vtu(path, sub, &
                           ['displacement'], reshape(values, [2, size(values, 2), 1]), &
                           trim(inputs%output%vtk_format), stat, ['degree'], &
                           reshape(degree, [size(degree), 1]), mode_field_names(), &
                           mode_field_values(spec, i, lambda, prob%poisson))
            if (.not. stat%ok()) return
        end do
    end subroutine write_hp_modes
end module eigen_files
