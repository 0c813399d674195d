! SPDX-License-Identifier: MIT
!> analysis = 'eigen' with &adapt tolerance > 0 and strategy = 'hp': the loop of
!> hp_adaptive and its files: eigenvalues.csv of the last level, mode_NNN.vtu (the hp field
!> on a linear sub-triangulation, hp_field, with the cell field `degree`), adapt.csv (one
!> row per level: layers, degrees, dofs, mu, bar), mesh.msh (the last graded mesh) and
!> degrees.csv (its cell degrees), K.mtx and B.mtx of the condensed system as &output asks,
!> mode_001.png and adapt.png (module pictures), summary.json with the keys of the h loop
!> and the hp ones.
module hp_adapt_run
    use kinds, only: wp
    use status, only: status_t, STATUS_NOT_MET
    use strings, only: to_string, zero_padded
    use real_format, only: real_to_text, known_text
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t
    use analysis_base, only: analysis_t
    use hp_adaptive, only: hp_adapt_eigen, hp_result_t
    use eigen_files, only: eigen_summary_json, summary_lines, write_eigenvalues_csv, &
                           modes_to_write, mode_field_names, mode_field_values
    use adapt_files, only: add_adapt_keys, write_adapted_mesh
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use csv_writer, only: csv_writer_t
    use vtk_writer, only: write_vtu
    use matrix_market, only: write_matrix_market
    use mesh, only: mesh_t
    use hp_field, only: sample_hp_field
    use pictures, only: draw_hp_mode, draw_hp_adapt
    use hp_space, only: hp_space_t
    use spectrum, only: spectrum_t
    implicit none
    private

    character(len=*), parameter, public :: HP_ADAPT_HEADER = &
        'level,layers,p_min,p_max,n_dofs,n_contact,n_cells,mu,error_bar,roundoff,time_s'
    character(len=*), parameter, public :: DEGREES_FILE = 'degrees.csv'
    public :: write_hp_modes, write_degrees, add_hp_keys, hp_report_lines

    type, extends(analysis_t), public :: hp_adapt_run_t
        !> allocatable: gfortran 12's finalizer of this type, inlined component by component,
        !> skipped out%prob%k (LeakSanitizer); an allocatable component is freed whole
        type(hp_result_t), allocatable :: out
        integer :: start_dofs = 0   !! free dofs of the input mesh (P1 to P4 as given)
        character(len=:), allocatable :: plot_note   !! mode_001.png: where, or why not
    contains
        procedure :: solve => hp_run_solve
        procedure :: write_files => hp_run_write_files
        procedure :: summary => hp_run_summary
        procedure :: report => hp_run_report
    end type hp_adapt_run_t

contains

    subroutine hp_run_solve(this, config, prob, timings, stat)
        class(hp_adapt_run_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        this%start_dofs = prob%dofs%n_free
        if (.not. allocated(this%out)) allocate (this%out)
        call hp_adapt_eigen(config, prob, this%out, timings, stat)
        ! as the h loop: without a positive mu at any level there is no value, so no
        ! tolerance to miss; one that vanished on refinement misses it
        if (.not. stat%ok() .or. this%out%converged) return
        if (this%out%res%spec%lowest_positive() > 0 .or. this%out%mu_vanished) &
            call this%verdict%fail(STATUS_NOT_MET, &
            config%input_file//': &adapt: '//this%out%outcome// &
            ' (the set of the last level is written)')
    end subroutine hp_run_solve

    subroutine hp_run_write_files(this, stage, config, prob, stat)
        class(hp_adapt_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: path
        if (prob%mesh%n_cells() == 0) return   ! no input mesh: nothing was solved
        call stage%add('eigenvalues.csv', path)
        call write_eigenvalues_csv(path, this%out%res%spec, stat, this%out%res%error)
        if (stat%ok() .and. config%output%vtk) call write_hp_modes(stage, config, &
            this%out%prob, this%out%space, this%out%res%spec, this%out%res%lambda, stat)
        if (stat%ok()) then
            call stage%add('adapt.csv', path)
            call write_hp_adapt_csv(path, this%out, stat)
        end if
        if (stat%ok()) call write_adapted_mesh(stage, this%out%prob, stat)
        if (stat%ok()) then
            call stage%add(DEGREES_FILE, path)
            call write_degrees(path, this%out%space, stat)
        end if
        ! the condensed hp system (vertex and edge functions), in the input's units
        if (stat%ok() .and. config%output%matrices) then
            call stage%add('K.mtx', path)
            call write_matrix_market(path, this%out%prob%k, stat)
        end if
        if (stat%ok() .and. config%output%matrices) then
            call stage%add('B.mtx', path)
            call write_matrix_market(path, this%out%res%b, stat)
        end if
        if (stat%ok()) call draw_hp_mode(stage, config, this%out, this%plot_note, stat)
        if (stat%ok()) call draw_hp_adapt(stage, config, this%out%res%lambda, &
                                          this%start_dofs, this%out%levels, this%picture_note)
    end subroutine hp_run_write_files

    !> mode_NNN.vtu: the real part of each kept mode (modes_to_write) of `spec` (on the hp
    !> problem `prob` with space `space`, at `lambda`), sampled on the sub-triangulation of
    !> hp_field, with each sub-cell's degree and the field data of eigen_files' modes.
    subroutine write_hp_modes(stage, config, prob, space, spec, lambda, stat)
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(hp_space_t), intent(in) :: space
        type(spectrum_t), intent(in) :: spec
        real(wp), intent(in) :: lambda
        type(status_t), intent(out) :: stat
        type(mesh_t) :: sub
        real(wp), allocatable :: values(:, :), degree(:), mode(:)
        integer :: i
        character(len=:), allocatable :: path
        do i = 1, modes_to_write(config, spec)
            mode = real(spec%vectors(:, i), wp)
            call sample_hp_field(prob%mesh, space, prob%young, prob%poisson, &
                                 mode, sub, values, degree, stat)
            if (.not. stat%ok()) return
            call stage%add('mode_'//zero_padded(i, 3)//'.vtu', path)
            call write_vtu(path, sub, &
                           ['displacement'], reshape(values, [2, size(values, 2), 1]), &
                           trim(config%output%vtk_format), stat, ['degree'], &
                           reshape(degree, [size(degree), 1]), mode_field_names(), &
                           mode_field_values(spec, i, lambda, prob%poisson))
            if (.not. stat%ok()) return
        end do
    end subroutine write_hp_modes

    !> adapt.csv of an hp run (HP_ADAPT_HEADER); mu, error_bar and roundoff empty where
    !> there is none.
    subroutine write_hp_adapt_csv(path, out, stat)
        character(len=*), intent(in) :: path
        type(hp_result_t), intent(in) :: out
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        integer :: i
        call csv%open(path, HP_ADAPT_HEADER)
        do i = 1, size(out%levels)
            associate (row => out%levels(i))
                call csv%row(to_string(row%level)//','//to_string(row%layers)//','// &
                    to_string(row%p_min)//','//to_string(row%p_max)//','// &
                    to_string(row%n_dofs)//','//to_string(row%n_contact)//','// &
                    to_string(row%n_cells)//','//known_text(row%has_mu, row%mu)//','// &
                    known_text(row%error_bar >= 0.0_wp, row%error_bar)//','// &
                    known_text(row%roundoff >= 0.0_wp, row%roundoff)//','// &
                    real_to_text(row%time_s))
            end associate
        end do
        call csv%close(stat)
    end subroutine write_hp_adapt_csv

    !> degrees.csv: cell,degree for the cells of mesh.msh, in its order.
    subroutine write_degrees(path, space, stat)
        character(len=*), intent(in) :: path
        type(hp_space_t), intent(in) :: space
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        integer :: c
        call csv%open(path, 'cell,degree')
        do c = 1, size(space%cell_degree)
            call csv%row(to_string(c)//','//to_string(space%cell_degree(c)))
        end do
        call csv%close(stat)
    end subroutine write_degrees

    function hp_run_summary(this, config, prob) result(summary)
        class(hp_adapt_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(json_object_t) :: summary
        summary = eigen_summary_json(config, this%out%prob, this%out%res, this%timings)
        call add_adapt_keys(summary, config, this%start_dofs, size(this%out%levels), &
                            this%out%converged, this%out%floor_reached, this%out%outcome)
        call add_hp_keys(summary, config, this%out%space, prob%mesh%n_cells())
    end function hp_run_summary

    !> The keys every hp loop adds: its strategy and parameters, the degrees of the last
    !> level's `space`, the cells of the input mesh.
    subroutine add_hp_keys(summary, config, space, start_cells)
        type(json_object_t), intent(inout) :: summary
        type(config_t), intent(in) :: config
        type(hp_space_t), intent(in) :: space
        integer, intent(in) :: start_cells
        call summary%add_string('adapt_strategy', 'hp')
        call summary%add_real('adapt_sigma', config%adapt%sigma)
        call summary%add_integer('adapt_p_max', config%adapt%p_max)
        call summary%add_string('degrees_file', DEGREES_FILE)
        if (size(space%cell_degree) > 0) then
            call summary%add_integer('hp_degree_min', minval(space%cell_degree))
            call summary%add_integer('hp_degree_max', maxval(space%cell_degree))
        end if
        call summary%add_integer('adapt_start_cells', start_cells)
    end subroutine add_hp_keys

    function hp_run_report(this, config, prob) result(text)
        class(hp_adapt_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        text = summary_lines(config, this%out%prob, this%out%res, this%timings, this%plot_note)
        text = text//hp_report_lines(config, size(this%out%levels), this%out%space, &
                                     prob%mesh%n_cells(), this%out%outcome)
        if (allocated(this%picture_note)) then
            if (len(this%picture_note) > 0) text = text//NL//'  adapt plot  '//this%picture_note
        end if
    end function hp_run_report

    !> The stdout lines every hp loop adds: its `levels` from the `start_cells`-cell input
    !> mesh, the last `space`'s degrees, the `outcome`, and the mesh files.
    function hp_report_lines(config, levels, space, start_cells, outcome) result(text)
        type(config_t), intent(in) :: config
        integer, intent(in) :: levels, start_cells
        type(hp_space_t), intent(in) :: space
        character(len=*), intent(in) :: outcome
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        text = NL//'  adapt       hp, '//to_string(levels)// &
            trim(merge(' level ', ' levels', levels == 1))//' from the '// &
            to_string(start_cells)//'-cell input mesh'
        if (size(space%cell_degree) > 0) text = text//' (last: degrees '// &
            to_string(minval(space%cell_degree))//' to '// &
            to_string(maxval(space%cell_degree))//')'
        text = text//'; '//outcome//NL//'  mesh        '//trim(config%output%directory)// &
            '/mesh.msh and '//DEGREES_FILE//' (the last graded mesh and its cell degrees)'
    end function hp_report_lines
end module hp_adapt_run
