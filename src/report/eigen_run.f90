! SPDX-License-Identifier: MIT
!> analysis = 'eigen': the spectrum at &analysis lambda with its estimate, written as
!> eigen_files writes an eigen solve (eigenvalues.csv, mode_NNN.vtu, K.mtx and B.mtx,
!> summary.json) with the short human summary on stdout.
module eigen_run
    use kinds, only: wp
    use status, only: status_t, STATUS_NO_DIGIT
    use strings, only: short_real_text
    use timer, only: timings_t
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use eigen_solve, only: eigen_result_t, solve_eigen, estimate_eigen
    use analysis_base, only: analysis_t
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use eigen_files, only: eigen_summary_json, summary_lines, write_eigen_files
    implicit none
    private

    type, extends(analysis_t), public :: eigen_run_t
        !> allocatable, allocated by solve: gfortran 12 frees it whole (docs/testing.md)
        type(eigen_result_t), allocatable :: res
        character(len=:), allocatable :: plot_note   !! where mode_001.png is, or why not
    contains
        procedure :: solve => eigen_run_solve
        procedure :: write_files => eigen_run_write_files
        procedure :: summary => eigen_run_summary
        procedure :: report => eigen_run_report
    end type eigen_run_t

contains

    subroutine eigen_run_solve(this, inputs, prob, timings, stat)
        class(eigen_run_t), intent(inout) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        call solve_eigen(inputs%scene, prob, inputs%point%lambda, inputs%eigen, this%res, &
                         timings, stat)
        if (stat%ok()) call estimate_eigen(inputs%scene, prob, inputs%eigen, .true., this%res, &
                                           timings)
        ! the verdict, after the outputs: the set shows what was computed, the status that
        ! its value is none
        if (stat%ok() .and. this%res%roundoff >= 1.0_wp) call this%verdict%fail( &
            STATUS_NO_DIGIT, inputs%scene%name//': round-off leaves no correct digit of the '// &
            'lowest positive mu (bound '//short_real_text(this%res%roundoff)//' relative); '// &
            'the output set is written')
    end subroutine eigen_run_solve

    subroutine eigen_run_write_files(this, stage, inputs, prob, stat)
        class(eigen_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        call write_eigen_files(stage, inputs, prob, this%res, stat, this%plot_note)
    end subroutine eigen_run_write_files

    function eigen_run_summary(this, inputs, prob) result(summary)
        class(eigen_run_t), intent(in) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(json_object_t) :: summary
        summary = eigen_summary_json(inputs, prob, this%res, this%timings)
    end function eigen_run_summary

    function eigen_run_report(this, inputs, prob) result(text)
        class(eigen_run_t), intent(in) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        text = summary_lines(inputs, prob, this%res, this%timings, this%plot_note)
    end function eigen_run_report
end module eigen_run
