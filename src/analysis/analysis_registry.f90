! SPDX-License-Identifier: MIT
!> The analyses by their &analysis kind. A new analysis is one module extending analysis_t,
!> one line here, its name among the kinds the input accepts (input_validation,
!> run_inputs) and its files and summary in the report (run_report).
module analysis_registry
    use run_inputs, only: run_inputs_t, ANALYSIS_EIGEN, ANALYSIS_THRESHOLD, ANALYSIS_SWEEP, &
                          ANALYSIS_BRANCH, ANALYSIS_SOLVE
    use method_options, only: REFINE_NONE
    use analysis_base, only: analysis_t
    use eigen_run, only: eigen_run_t, adapt_eigen_run_t
    use threshold_run, only: threshold_run_t, sweep_run_t, adapt_threshold_run_t, &
                             joint_sweep_run_t
    use compliance_run, only: branch_run_t, solve_run_t
    implicit none
    private
    public :: new_analysis

contains

    !> The analysis of `inputs`: its kind, adaptive (&adapt tolerance > 0, h or hp: the
    !> refiner is the loop's, adapt_driver) or not. An unknown kind (which the input check
    !> refuses first) leaves `analysis` unallocated. 'lambda_sweep' adapts each point itself,
    !> or with &sweep adapt_thresholds its points and thresholds in one hp climb.
    subroutine new_analysis(inputs, analysis)
        type(run_inputs_t), intent(in) :: inputs
        class(analysis_t), allocatable, intent(out) :: analysis
        logical :: adaptive
        adaptive = inputs%adapt%refine /= REFINE_NONE
        select case (inputs%analysis)
        case (ANALYSIS_EIGEN)
            if (adaptive) then
                allocate (adapt_eigen_run_t :: analysis)
            else
                allocate (eigen_run_t :: analysis)
            end if
        case (ANALYSIS_THRESHOLD)
            if (adaptive) then
                allocate (adapt_threshold_run_t :: analysis)
            else
                allocate (threshold_run_t :: analysis)
            end if
        case (ANALYSIS_SWEEP)
            if (inputs%sweep_thresholds) then   ! (input_validation: adapted on hp levels)
                allocate (joint_sweep_run_t :: analysis)
            else
                allocate (sweep_run_t :: analysis)
            end if
        case (ANALYSIS_BRANCH); allocate (branch_run_t :: analysis)
        case (ANALYSIS_SOLVE); allocate (solve_run_t :: analysis)
        end select
    end subroutine new_analysis
end module analysis_registry
