! SPDX-License-Identifier: MIT
!> analysis = 'eigen' with &adapt tolerance > 0: the adaptive loop (eigen_goal) and its
!> files: those of an eigen run on the final mesh (eigenvalues.csv, mode_NNN.vtu with the
!> indicators, mode_001.png), adapt.csv (one row per level), adapt.png, and mesh.msh, the
!> final mesh as a Gmsh file any analysis reads back.
module adapt_run
    use kinds, only: wp
    use status, only: status_t, STATUS_NOT_MET
    use strings, only: to_string
    use real_format, only: real_to_text, known_text
    use timer, only: timings_t
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use analysis_base, only: analysis_t
    use eigen_goal, only: adapt_eigen, adapted_eigen_t
    use eigen_files, only: eigen_summary_json, summary_lines, write_eigen_files
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use csv_writer, only: csv_writer_t
    use adapt_files, only: add_adapt_keys, adapt_report_lines, write_adapted_mesh
    use pictures, only: draw_eigen_adapt
    implicit none
    private
    character(len=*), parameter, public :: ADAPT_HEADER = &
        'level,n_dofs,n_contact,n_cells,mu,error_estimate,time_s,error_bar'

    type, extends(analysis_t), public :: adapt_run_t
        !> allocatable, allocated by solve: gfortran 12 frees it whole (docs/testing.md)
        type(adapted_eigen_t), allocatable :: out(:)   !! one: the loop at &analysis lambda
        character(len=:), allocatable :: plot_note    !! mode_001.png: where, or why not
    contains
        procedure :: solve => adapt_run_solve
        procedure :: write_files => adapt_run_write_files
        procedure :: summary => adapt_run_summary
        procedure :: report => adapt_run_report
    end type adapt_run_t

contains

    subroutine adapt_run_solve(this, inputs, prob, timings, stat)
        class(adapt_run_t), intent(inout) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        call adapt_eigen(inputs%scene, [inputs%point%lambda], inputs%eigen, inputs%adapt, prob, &
                         this%out, timings, stat, keep_problem=.true.)
        ! Without a positive mu at any level there is no value to quote, so nothing to take
        ! for a met tolerance: that stays exit 0 with its warning. One that vanished on
        ! refinement had values, none converged: a tolerance not met.
        if (.not. stat%ok() .or. this%out(1)%converged) return
        if (this%out(1)%res%spec%lowest_positive() > 0 .or. this%out(1)%mu_vanished) &
            call this%verdict%fail(STATUS_NOT_MET, &
            inputs%scene%name//': &adapt: '//this%out(1)%outcome// &
            ' (the set of the last level is written)')
    end subroutine adapt_run_solve

    !> The files of the final level; `prob` (the starting mesh) is not written.
    subroutine adapt_run_write_files(this, stage, inputs, prob, stat)
        class(adapt_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: path
        call write_eigen_files(stage, inputs, this%out(1)%prob, this%out(1)%res, stat, &
                               this%plot_note)
        if (stat%ok()) then
            call stage%add('adapt.csv', path)
            call write_adapt_csv(path, this%out(1), stat)
        end if
        if (stat%ok()) call write_adapted_mesh(stage, this%out(1)%prob, stat)
        ! the files describe the final level; of the starting problem `prob` only its dofs
        if (stat%ok()) call draw_eigen_adapt(stage, inputs, this%out(1)%prob%mesh%element, &
            this%out(1)%res%lambda, prob%dofs%n_free, this%out(1)%levels, this%picture_note)
    end subroutine adapt_run_write_files

    !> level,n_dofs,n_contact,n_cells,mu,error_estimate,time_s,error_bar (the bar is last so
    !> that the columns before it keep their places); mu, error_estimate and error_bar empty
    !> where there is no positive mu or no estimate.
    subroutine write_adapt_csv(path, out, stat)
        character(len=*), intent(in) :: path
        type(adapted_eigen_t), intent(in) :: out
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        integer :: i

        call csv%open(path, ADAPT_HEADER)
        do i = 1, size(out%levels)
            associate (row => out%levels(i))
                call csv%row(to_string(row%level)//','//to_string(row%n_dofs)//','// &
                    to_string(row%n_contact)//','//to_string(row%n_cells)//','// &
                    known_text(row%has_mu, row%mu)//','// &
                    known_text(row%estimated, row%error_estimate)//','// &
                    real_to_text(row%time_s)//','//known_text(row%error_bar >= 0.0_wp, &
                                                              row%error_bar))
            end associate
        end do
        call csv%close(stat)
    end subroutine write_adapt_csv

    !> The keys of an eigen run on the final mesh, and those of the loop.
    function adapt_run_summary(this, inputs, prob) result(summary)
        class(adapt_run_t), intent(in) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(json_object_t) :: summary
        summary = eigen_summary_json(inputs, this%out(1)%prob, this%out(1)%res, this%timings)
        call add_adapt_keys(summary, inputs, prob%dofs%n_free, size(this%out(1)%levels) - 1, &
                            this%out(1)%converged, this%out(1)%floor_reached, this%out(1)%outcome)
    end function adapt_run_summary

    function adapt_run_report(this, inputs, prob) result(text)
        class(adapt_run_t), intent(in) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        text = summary_lines(inputs, this%out(1)%prob, this%out(1)%res, this%timings, &
                             this%plot_note)
        text = text//adapt_report_lines(inputs, prob%dofs%n_free, size(this%out(1)%levels) - 1, &
                                        this%out(1)%outcome, this%picture_note)
    end function adapt_run_report
end module adapt_run
