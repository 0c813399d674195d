! SPDX-License-Identifier: MIT
!> The analyses of the frictional problem itself, which work in the input's units on all
!> dofs (non-zero Dirichlet data): 'branch' (branch_run_t: the branch U + delta phi at the
!> critical point, branch_analysis) and 'solve' (solve_run_t: the compliance problem by
!> Newton, solve_analysis).
module compliance_run
    use status, only: status_t
    use timer, only: timings_t
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use branch_analysis, only: branch_result_t, run_branch
    use solve_analysis, only: solve_result_t, run_solve, solve_status
    use analysis_base, only: analysis_t
    implicit none
    private

    type, extends(analysis_t), public :: branch_run_t
        type(branch_result_t), allocatable :: res
    contains
        procedure :: solve => branch_run_solve
        procedure :: in_input_units => branch_in_input_units
    end type branch_run_t

    type, extends(analysis_t), public :: solve_run_t
        type(solve_result_t), allocatable :: res
    contains
        procedure :: solve => solve_run_solve
        procedure :: in_input_units => solve_in_input_units
    end type solve_run_t

contains

    subroutine branch_run_solve(this, inputs, prob, timings, stat)
        class(branch_run_t), intent(inout) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        call run_branch(inputs, prob, this%res, timings, stat)
    end subroutine branch_run_solve

    subroutine solve_run_solve(this, inputs, prob, timings, stat)
        class(solve_run_t), intent(inout) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        call run_solve(inputs, prob, this%res, timings, stat)
        if (stat%ok()) call solve_status(inputs, this%res, this%verdict)
    end subroutine solve_run_solve

    !> Its loads, displacements and compliances have units: the input's.
    pure logical function branch_in_input_units(this)
        class(branch_run_t), intent(in) :: this
        branch_in_input_units = .true.
    end function branch_in_input_units

    !> Its loads, displacements and compliances have units: the input's.
    pure logical function solve_in_input_units(this)
        class(solve_run_t), intent(in) :: this
        solve_in_input_units = .true.
    end function solve_in_input_units
end module compliance_run
