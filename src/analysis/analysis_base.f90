! SPDX-License-Identifier: MIT
!> The one shape of every analysis: it solves its problem from the run's inputs (run_inputs)
!> and holds its result, with the verdict of the run once the result is written. Each
!> analysis extends analysis_t with its own result and solve; the report (run_report) writes
!> each by its type. An analysis computes and writes nothing.
module analysis_base
    use status, only: status_t
    use timer, only: timings_t
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    implicit none
    private

    type, abstract, public :: analysis_t
        !> The run's verdict once its outputs are written: a solve whose Newton iteration did
        !> not converge still writes its history, then ends in error.
        type(status_t) :: verdict
    contains
        procedure(solve_interface), deferred :: solve
        !> whether the problem is built in the input's units on all dofs (non-zero Dirichlet
        !> data: the compliance problem), rather than scaled on the free dofs
        procedure :: in_input_units => analysis_in_input_units
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
    end interface

contains

    !> The eigen analyses work in the scaled units of problem_t (build_problem).
    pure logical function analysis_in_input_units(this)
        class(analysis_t), intent(in) :: this
        analysis_in_input_units = .false.
    end function analysis_in_input_units
end module analysis_base
