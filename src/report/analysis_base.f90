! SPDX-License-Identifier: MIT
!> The one shape of every analysis: solve, write its files into a staging area, build its
!> summary.json, commit the set, print its summary. An analysis extends analysis_t with what
!> is its own (the numerics, its files, its summary keys and lines); run_analysis is the
!> skeleton they all share, so staging, timings and the commit are written once.
module analysis_base
    use kinds, only: wp
    use status, only: status_t
    use timer, only: wall_time, timings_t, PHASE_OUTPUT
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use filesystem, only: MAX_NAME_LEN
    use strings, only: text_t
    implicit none
    private
    public :: run_analysis

    !> Files older builds wrote into the output directory unlisted in their sets (they drew
    !> lambda_sweep.png after the commit); now every file is staged and listed, and these go
    !> with the previous set.
    character(len=*), parameter :: OLD_UNLISTED = 'lambda_sweep.png'

    type, abstract, public :: analysis_t
        !> The run's verdict once its outputs are written: a solve whose Newton iteration did
        !> not converge still writes its history, then ends in error.
        type(status_t) :: verdict
        !> The phase timings as committed to summary.json, which the report prints too.
        type(timings_t) :: timings
        !> The problem must carry K and Gamma_C on all dofs too (non-zero Dirichlet data).
        logical :: needs_all_dofs = .false.
        !> Where the picture write_files drew (adapt.png, lambda_sweep.png; module pictures)
        !> is, or why it is not drawn; unallocated: none was asked for.
        character(len=:), allocatable :: picture_note
    contains
        procedure(solve_interface), deferred :: solve
        procedure(write_interface), deferred :: write_files
        procedure(summary_interface), deferred :: summary
        procedure(report_interface), deferred :: report
    end type analysis_t

    abstract interface
        !> The numerics: fill the analysis from the problem, adding to the phase timings.
        subroutine solve_interface(this, inputs, prob, timings, stat)
            import :: analysis_t, run_inputs_t, problem_t, timings_t, status_t
            class(analysis_t), intent(inout) :: this
            type(run_inputs_t), intent(in) :: inputs
            type(problem_t), intent(in) :: prob
            type(timings_t), intent(inout) :: timings
            type(status_t), intent(out) :: stat
        end subroutine solve_interface

        !> Every file of the analysis but summary.json, each at the path stage%add(name, path)
        !> gives.
        subroutine write_interface(this, stage, inputs, prob, stat)
            import :: analysis_t, output_stage_t, run_inputs_t, problem_t, status_t
            class(analysis_t), intent(inout) :: this
            type(output_stage_t), intent(inout) :: stage
            type(run_inputs_t), intent(in) :: inputs
            type(problem_t), intent(in) :: prob
            type(status_t), intent(out) :: stat
        end subroutine write_interface

        !> summary.json without its 'files' list, which the commit adds.
        function summary_interface(this, inputs, prob) result(summary)
            import :: analysis_t, run_inputs_t, problem_t, json_object_t
            class(analysis_t), intent(in) :: this
            type(run_inputs_t), intent(in) :: inputs
            type(problem_t), intent(in) :: prob
            type(json_object_t) :: summary
        end function summary_interface

        !> The human summary printed on stdout once the outputs are in place.
        function report_interface(this, inputs, prob) result(text)
            import :: analysis_t, run_inputs_t, problem_t
            class(analysis_t), intent(in) :: this
            type(run_inputs_t), intent(in) :: inputs
            type(problem_t), intent(in) :: prob
            character(len=:), allocatable :: text
        end function report_interface
    end interface

contains

    !> Solve, then write every output to the output directory or none of them: the files are
    !> staged, pictures included; summary.json is built once, after the timings are final,
    !> registered last as the commit's completion marker and lists the files of its set (an
    !> older run may have left other mode_NNN.vtu), and the set moves into place together.
    !> The output time covers every file but summary.json.
    subroutine run_analysis(this, inputs, prob, run_start, timings, stat)
        class(analysis_t), intent(inout) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: run_start          !! wall_time() at the start of the run
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(output_stage_t) :: stage
        type(json_object_t) :: summary
        character(len=:), allocatable :: summary_path
        ! a named array, not a constructor: gfortran 12 does not free a constructor's
        ! allocatable components (LeakSanitizer reports them)
        type(text_t) :: unlisted(1)
        real(wp) :: start

        unlisted(1)%text = OLD_UNLISTED
        call this%solve(inputs, prob, timings, stat)
        if (.not. stat%ok()) return
        start = wall_time()
        call stage%begin(trim(inputs%output%directory), stat, unlisted)
        if (.not. stat%ok()) then
            ! output_stage knows the directory, not the input file that named it.
            call stat%fail(stat%code, inputs%scene%name//': &output directory: '//stat%message)
            return
        end if
        call this%write_files(stage, inputs, prob, stat)
        if (stat%ok()) then
            call timings%add(PHASE_OUTPUT, wall_time() - start, &
                             ': '//trim(inputs%output%directory))
            timings%total = wall_time() - run_start
            this%timings = timings
            summary = this%summary(inputs, prob)
        end if
        if (stat%ok()) then
            call stage%add('summary.json', summary_path)
            call summary%add_string_array('files', stage%file_names(MAX_NAME_LEN))
            call summary%write(summary_path, stat)
            if (stat%ok()) call stage%commit(stat)
        end if
        if (.not. stat%ok()) call stage%abort()
    end subroutine run_analysis
end module analysis_base
