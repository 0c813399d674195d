! SPDX-License-Identifier: MIT
!> The analyses by their &analysis kind. A new analysis is one module extending analysis_t
!> and one line here (and its name among the kinds the input accepts).
module analysis_registry
    use analysis_base, only: analysis_t
    use eigen_run, only: eigen_run_t
    use threshold_run, only: threshold_run_t
    use branch_run, only: branch_run_t
    use solve_run, only: solve_run_t
    use adapt_run, only: adapt_run_t
    use hp_adapt_run, only: hp_adapt_run_t   ! &adapt strategy = 'hp'
    implicit none
    private
    public :: new_analysis

contains

    !> The analysis of `kind`, adaptive (&adapt tolerance > 0) or not; an unknown kind
    !> (which the input check refuses first) leaves `analysis` unallocated. `strategy`:
    !> &adapt strategy, 'h' (the default) or 'hp' (only 'eigen': the input check refuses
    !> the others).
    subroutine new_analysis(kind, adaptive, analysis, strategy)
        character(len=*), intent(in) :: kind
        logical, intent(in) :: adaptive
        class(analysis_t), allocatable, intent(out) :: analysis
        character(len=*), intent(in), optional :: strategy
        type(threshold_run_t) :: sweep, threshold
        select case (kind)
        case ('eigen')
            if (adaptive .and. present(strategy)) then
                if (strategy == 'hp') allocate (hp_adapt_run_t :: analysis)   ! strategy 'hp'
            end if
            if (allocated(analysis)) then
                continue
            else if (adaptive) then
                allocate (adapt_run_t :: analysis)
            else
                allocate (eigen_run_t :: analysis)
            end if
        case ('threshold')
            threshold%adaptive = adaptive
            allocate (analysis, source=threshold)
        case ('lambda_sweep')
            sweep%with_sweep = .true.
            allocate (analysis, source=sweep)
        case ('branch'); allocate (branch_run_t :: analysis)
        case ('solve'); allocate (solve_run_t :: analysis)
        end select
        ! The compliance problem needs K and Gamma_C on all dofs (non-zero Dirichlet data).
        if (any(kind == [character(len=6) :: 'branch', 'solve'])) analysis%needs_all_dofs = .true.
    end subroutine new_analysis
end module analysis_registry
