! SPDX-License-Identifier: MIT
!> The analyses by their &analysis kind. A new analysis is one module extending analysis_t
!> and one line here (and its name among the kinds the input accepts).
module analysis_registry
    use analysis_base, only: analysis_t
    use eigen_run, only: eigen_run_t
    use threshold_run, only: threshold_run_t, sweep_run_t, adapt_threshold_run_t
    use branch_run, only: branch_run_t
    use solve_run, only: solve_run_t
    use adapt_run, only: adapt_run_t
    use hp_adapt_run, only: hp_adapt_run_t   ! &adapt strategy = 'hp'
    use hp_threshold_run, only: hp_threshold_run_t
    implicit none
    private
    public :: new_analysis

contains

    !> The analysis of `kind`, adaptive (&adapt tolerance > 0) or not, with the &adapt
    !> `strategy` 'h' (the default) or 'hp' (the input check refuses it for 'branch' and
    !> 'solve'): each variant is a type of its own, chosen here once. An unknown kind (which
    !> the input check refuses first) leaves `analysis` unallocated. 'lambda_sweep' adapts
    !> each point itself (&adapt, either strategy).
    subroutine new_analysis(kind, adaptive, analysis, strategy)
        character(len=*), intent(in) :: kind
        logical, intent(in) :: adaptive
        class(analysis_t), allocatable, intent(out) :: analysis
        character(len=*), intent(in), optional :: strategy
        logical :: hp
        hp = .false.
        if (present(strategy)) hp = strategy == 'hp'
        select case (kind)
        case ('eigen')
            if (.not. adaptive) allocate (eigen_run_t :: analysis)
            if (adaptive .and. hp) allocate (hp_adapt_run_t :: analysis)
            if (adaptive .and. .not. hp) allocate (adapt_run_t :: analysis)
        case ('threshold')
            if (adaptive .and. hp) allocate (hp_threshold_run_t :: analysis)
            if (adaptive .and. .not. hp) allocate (adapt_threshold_run_t :: analysis)
            if (.not. adaptive) allocate (threshold_run_t :: analysis)
        case ('lambda_sweep'); allocate (sweep_run_t :: analysis)
        case ('branch'); allocate (branch_run_t :: analysis)
        case ('solve'); allocate (solve_run_t :: analysis)
        end select
        ! The compliance problem needs K and Gamma_C on all dofs (non-zero Dirichlet data).
        if (any(kind == [character(len=6) :: 'branch', 'solve'])) analysis%needs_all_dofs = .true.
    end subroutine new_analysis
end module analysis_registry
