! SPDX-License-Identifier: MIT
!> What every adaptive run writes besides the files of its goal: mesh.msh (the final mesh),
!> the summary.json keys and the stdout lines of the loop (adapt.png: module pictures). The
!> adaptive eigen and threshold runs share them.
module adapt_files
    use status, only: status_t
    use strings, only: to_string
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use gmsh_writer, only: write_gmsh
    implicit none
    private
    public :: add_adapt_keys, adapt_report_lines, write_adapted_mesh

    character(len=*), parameter :: MESH_FILE = 'mesh.msh'

contains

    !> mesh.msh: the final mesh of an adaptive run, for &mesh source = 'gmsh'.
    subroutine write_adapted_mesh(stage, prob, stat)
        type(output_stage_t), intent(inout) :: stage
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: path
        call stage%add(MESH_FILE, path)
        call write_gmsh(path, prob%mesh, stat)
    end subroutine write_adapted_mesh

    !> The keys of an adaptive loop (any goal) that started from `start_dofs` free dofs.
    subroutine add_adapt_keys(summary, inputs, start_dofs, levels, converged, floor, outcome)
        type(json_object_t), intent(inout) :: summary
        type(run_inputs_t), intent(in) :: inputs
        integer, intent(in) :: start_dofs, levels
        logical, intent(in) :: converged, floor
        character(len=*), intent(in) :: outcome
        call summary%add_real('adapt_tolerance', inputs%adapt%tolerance)
        call summary%add_real('adapt_theta', inputs%adapt%theta)
        call summary%add_integer('adapt_levels', levels)
        call summary%add_integer('adapt_start_dofs', start_dofs)
        call summary%add_logical('adapt_converged', converged)
        call summary%add_logical('adapt_floor_reached', floor)
        call summary%add_string('adapt_outcome', outcome)
        call summary%add_string('adapted_mesh_file', MESH_FILE)
    end subroutine add_adapt_keys

    !> The stdout lines of an adaptive loop: refinements and outcome, the mesh file, the plot.
    function adapt_report_lines(inputs, start_dofs, levels, outcome, adapt_note) result(text)
        type(run_inputs_t), intent(in) :: inputs
        integer, intent(in) :: start_dofs, levels
        character(len=*), intent(in) :: outcome, adapt_note
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        text = NL//'  adapt       '//to_string(levels)//' refinements from '// &
            to_string(start_dofs)//' dofs; '//outcome//NL//'  mesh        '// &
            trim(inputs%output%directory)//'/'//MESH_FILE// &
            ' (the final mesh, for &mesh source = ''gmsh'')'
        if (len(adapt_note) > 0) text = text//NL//'  adapt plot  '//adapt_note
    end function adapt_report_lines
end module adapt_files
