! SPDX-License-Identifier: MIT
!> analysis = 'eigen' with &adapt tolerance > 0: the adaptive loop (adaptive_eigen) and its
!> files: those of an eigen run on the final mesh (eigenvalues.csv, mode_NNN.vtu with the
!> indicators, mode_001.png), adapt.csv (one row per level), adapt.png, and mesh.msh, the
!> final mesh as a Gmsh file any analysis reads back.
module adapt_run
    use status, only: status_t
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

    character(len=*), parameter, public :: ADAPT_HEADER = &
        'level,n_dofs,n_contact,n_cells,mu,error_estimate,time_s'
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
        if (stat%ok()) call write_gmsh(stage%path(MESH_FILE), this%out%prob%mesh, stat)
        this%adapt_note = ''
        if (.not. (stat%ok() .and. config%output%plot)) return
        if (any(this%out%levels%estimated)) then
            call draw_adapt(this, stage, config, prob, stat)
        else
            this%adapt_note = 'not drawn: no level has an error estimate'
        end if
    end subroutine adapt_run_write_files

    !> adapt.png into the staging folder, from adapt.csv and a scratch summary.json.
    subroutine draw_adapt(this, stage, config, prob, stat)
        class(adapt_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        character(len=*), parameter :: PNG = 'adapt.png'
        character(len=:), allocatable :: summary_path, png_path
        type(json_object_t) :: summary
        logical :: drawn

        summary_path = stage%scratch('.adapt-summary.json')
        summary = this%summary(config, prob)
        call summary%write(summary_path, stat)
        if (.not. stat%ok()) return
        call run_plot_script('plot_adapt.sh', stage%folder(), summary_path, drawn, this%adapt_note)
        call remove_file(summary_path)
        if (.not. drawn) return
        png_path = stage%path(PNG)   ! registered: part of the committed set
        this%adapt_note = trim(config%output%directory)//'/'//PNG
    end subroutine draw_adapt

    !> level,n_dofs,n_contact,n_cells,mu,error_estimate,time_s; mu and error_estimate empty
    !> where there is no positive mu or no estimate.
    subroutine write_adapt_csv(path, out, stat)
        character(len=*), intent(in) :: path
        type(adaptive_result_t), intent(in) :: out
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        character(len=:), allocatable :: mu, estimate
        integer :: i

        call csv%open(path, ADAPT_HEADER)
        do i = 1, size(out%levels)
            associate (row => out%levels(i))
                mu = ''
                if (row%has_mu) mu = real_to_text(row%mu)
                estimate = ''
                if (row%estimated) estimate = real_to_text(row%error_estimate)
                call csv%row(to_string(row%level)//','//to_string(row%n_dofs)//','// &
                    to_string(row%n_contact)//','//to_string(row%n_cells)//','//mu//','// &
                    estimate//','//real_to_text(row%time_s))
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
        call summary%add_real('adapt_tolerance', config%adapt%tolerance)
        call summary%add_real('adapt_theta', config%adapt%theta)
        call summary%add_integer('adapt_levels', size(this%out%levels) - 1)
        call summary%add_integer('adapt_start_dofs', prob%dofs%n_free)
        call summary%add_logical('adapt_converged', this%out%converged)
        call summary%add_string('adapt_outcome', this%out%outcome)
        call summary%add_string('adapted_mesh_file', MESH_FILE)
    end function adapt_run_summary

    function adapt_run_report(this, config, prob) result(text)
        class(adapt_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        text = summary_lines(config, this%out%prob, this%out%res, this%timings, this%plot_note)
        text = text//NL//'  adapt       '//to_string(size(this%out%levels) - 1)// &
            ' refinements from '//to_string(prob%dofs%n_free)//' dofs; '//this%out%outcome// &
            NL//'  mesh        '//trim(config%output%directory)//'/'//MESH_FILE// &
            ' (the final mesh, for &mesh source = ''gmsh'')'
        if (len(this%adapt_note) > 0) text = text//NL//'  adapt plot  '//this%adapt_note
    end function adapt_run_report
end module adapt_run
