! SPDX-License-Identifier: MIT
!> analysis = 'eigen' with &adapt tolerance > 0: the adaptive loop (adaptive_eigen) and its
!> files: those of an eigen run on the final mesh (eigenvalues.csv, mode_NNN.vtu with the
!> indicators, mode_001.png), adapt.csv (one row per level), adapt.png, and mesh.msh, the
!> final mesh as a Gmsh file any analysis reads back.
module adapt_run
    use kinds, only: wp
    use status, only: status_t, STATUS_NOT_MET
    use strings, only: to_string
    use real_format, only: real_to_text
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t
    use analysis_base, only: analysis_t
    use adaptive_eigen, only: adapt_eigen, adaptive_result_t
    use eigen_run, only: eigen_summary_json, summary_lines, write_eigen_files
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use csv_writer, only: csv_writer_t
    use gmsh_writer, only: write_gmsh
    use plot_script, only: run_plot_script
    use filesystem, only: remove_file
    implicit none
    private
    public :: add_adapt_keys, adapt_report_lines, write_adapted_mesh, draw_adapt_plot

    character(len=*), parameter, public :: ADAPT_HEADER = &
        'level,n_dofs,n_contact,n_cells,mu,error_estimate,time_s,error_bar'
    character(len=*), parameter :: MESH_FILE = 'mesh.msh'

    type, extends(analysis_t), public :: adapt_run_t
        type(adaptive_result_t) :: out
        character(len=:), allocatable :: plot_note    !! mode_001.png: where, or why not
        character(len=:), allocatable :: adapt_note   !! adapt.png: where, or why not
    contains
        procedure :: solve => adapt_run_solve
        procedure :: write_files => adapt_run_write_files
        procedure :: summary => adapt_run_summary
        procedure :: report => adapt_run_report
    end type adapt_run_t

contains

    subroutine adapt_run_solve(this, config, prob, timings, stat)
        class(adapt_run_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        call adapt_eigen(config, prob, this%out, timings, stat)
        ! Without a positive mu there is no value to quote, so nothing to take for a met
        ! tolerance: that stays exit 0 with its warning.
        if (.not. stat%ok() .or. this%out%converged) return
        if (this%out%res%spec%lowest_positive() > 0) call this%verdict%fail(STATUS_NOT_MET, &
            config%input_file//': &adapt: '//this%out%outcome// &
            ' (the set of the last level is written)')
    end subroutine adapt_run_solve

    !> The files of the final level; `prob` (the starting mesh) is not written.
    subroutine adapt_run_write_files(this, stage, config, prob, stat)
        class(adapt_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        call write_eigen_files(stage, config, this%out%prob, this%out%res, stat, this%plot_note)
        if (stat%ok()) call write_adapt_csv(stage%path('adapt.csv'), this%out, stat)
        if (stat%ok()) call write_adapted_mesh(stage, this%out%prob, stat)
        this%adapt_note = ''
        if (stat%ok() .and. config%output%plot) call draw_adapt_plot(stage, config, &
            this%summary(config, prob), any(this%out%levels%estimated), this%adapt_note, stat)
    end subroutine adapt_run_write_files

    !> mesh.msh: the final mesh of an adaptive run, for &mesh source = 'gmsh'.
    subroutine write_adapted_mesh(stage, prob, stat)
        type(output_stage_t), intent(inout) :: stage
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        call write_gmsh(stage%path(MESH_FILE), prob%mesh, stat)
    end subroutine write_adapted_mesh

    !> adapt.png into the staging folder, from adapt.csv and `summary` written as a scratch
    !> summary.json; `note` says where it is, or why it is not drawn (`any_estimated` false:
    !> no level has an estimate).
    subroutine draw_adapt_plot(stage, config, summary, any_estimated, note, stat)
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(json_object_t), intent(in) :: summary
        logical, intent(in) :: any_estimated
        character(len=:), allocatable, intent(inout) :: note
        type(status_t), intent(out) :: stat
        character(len=*), parameter :: PNG = 'adapt.png'
        character(len=:), allocatable :: summary_path, png_path
        logical :: drawn

        if (.not. any_estimated) then
            note = 'not drawn: no level has an error estimate'
            return
        end if
        summary_path = stage%scratch('.adapt-summary.json')
        call summary%write(summary_path, stat)
        if (.not. stat%ok()) return
        call run_plot_script('plot_adapt.sh', stage%folder(), summary_path, drawn, note)
        call remove_file(summary_path)
        if (.not. drawn) return
        png_path = stage%path(PNG)   ! registered: part of the committed set
        note = trim(config%output%directory)//'/'//PNG
    end subroutine draw_adapt_plot

    !> level,n_dofs,n_contact,n_cells,mu,error_estimate,time_s,error_bar (the bar is last so
    !> that the columns before it keep their places); mu, error_estimate and error_bar empty
    !> where there is no positive mu or no estimate.
    subroutine write_adapt_csv(path, out, stat)
        character(len=*), intent(in) :: path
        type(adaptive_result_t), intent(in) :: out
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        character(len=:), allocatable :: mu, estimate, bar
        integer :: i

        call csv%open(path, ADAPT_HEADER)
        do i = 1, size(out%levels)
            associate (row => out%levels(i))
                mu = ''
                if (row%has_mu) mu = real_to_text(row%mu)
                estimate = ''
                if (row%estimated) estimate = real_to_text(row%error_estimate)
                bar = ''
                if (row%error_bar >= 0.0_wp) bar = real_to_text(row%error_bar)
                call csv%row(to_string(row%level)//','//to_string(row%n_dofs)//','// &
                    to_string(row%n_contact)//','//to_string(row%n_cells)//','//mu//','// &
                    estimate//','//real_to_text(row%time_s)//','//bar)
            end associate
        end do
        call csv%close(stat)
    end subroutine write_adapt_csv

    !> The keys of an eigen run on the final mesh, and those of the loop.
    function adapt_run_summary(this, config, prob) result(summary)
        class(adapt_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(json_object_t) :: summary
        summary = eigen_summary_json(config, this%out%prob, this%out%res, this%timings)
        call add_adapt_keys(summary, config, prob%dofs%n_free, size(this%out%levels) - 1, &
                            this%out%converged, this%out%floor_reached, this%out%outcome)
    end function adapt_run_summary

    !> The keys of an adaptive loop (any goal) that started from `start_dofs` free dofs;
    !> `floor`: it stopped at the floating-point floor.
    subroutine add_adapt_keys(summary, config, start_dofs, levels, converged, floor, outcome)
        type(json_object_t), intent(inout) :: summary
        type(config_t), intent(in) :: config
        integer, intent(in) :: start_dofs, levels
        logical, intent(in) :: converged, floor
        character(len=*), intent(in) :: outcome
        call summary%add_real('adapt_tolerance', config%adapt%tolerance)
        call summary%add_real('adapt_theta', config%adapt%theta)
        call summary%add_integer('adapt_levels', levels)
        call summary%add_integer('adapt_start_dofs', start_dofs)
        call summary%add_logical('adapt_converged', converged)
        call summary%add_logical('adapt_floor_reached', floor)
        call summary%add_string('adapt_outcome', outcome)
        call summary%add_string('adapted_mesh_file', MESH_FILE)
    end subroutine add_adapt_keys

    function adapt_run_report(this, config, prob) result(text)
        class(adapt_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        text = summary_lines(config, this%out%prob, this%out%res, this%timings, this%plot_note)
        text = text//adapt_report_lines(config, prob%dofs%n_free, size(this%out%levels) - 1, &
                                        this%out%outcome, this%adapt_note)
    end function adapt_run_report

    !> The stdout lines of an adaptive loop: refinements and outcome, the mesh file, the plot.
    function adapt_report_lines(config, start_dofs, levels, outcome, adapt_note) result(text)
        type(config_t), intent(in) :: config
        integer, intent(in) :: start_dofs, levels
        character(len=*), intent(in) :: outcome, adapt_note
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        text = NL//'  adapt       '//to_string(levels)//' refinements from '// &
            to_string(start_dofs)//' dofs; '//outcome//NL//'  mesh        '// &
            trim(config%output%directory)//'/'//MESH_FILE// &
            ' (the final mesh, for &mesh source = ''gmsh'')'
        if (len(adapt_note) > 0) text = text//NL//'  adapt plot  '//adapt_note
    end function adapt_report_lines
end module adapt_run
