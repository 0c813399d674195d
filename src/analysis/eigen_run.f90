! SPDX-License-Identifier: MIT
!> analysis = 'eigen': the spectrum at &analysis lambda with its estimate (eigen_run_t), or
!> with &adapt tolerance > 0 the adaptive loop of its lowest positive mu on h or hp levels
!> (adapt_eigen_run_t, eigen_goal).
module eigen_run
    use kinds, only: wp
    use status, only: status_t, STATUS_NO_DIGIT, STATUS_NOT_MET
    use strings, only: short_real_text
    use timer, only: timings_t
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use eigen_solve, only: eigen_result_t, solve_eigen, estimate_eigen
    use eigen_goal, only: adapt_eigen, adapted_eigen_t
    use analysis_base, only: analysis_t
    use process_exit, only: naming_file
    implicit none
    private

    type, extends(analysis_t), public :: eigen_run_t
        !> allocatable, allocated by solve: gfortran 12 frees it whole (docs/testing.md)
        type(eigen_result_t), allocatable :: res
    contains
        procedure :: solve => eigen_run_solve
    end type eigen_run_t

    type, extends(analysis_t), public :: adapt_eigen_run_t
        !> one: the loop at &analysis lambda (allocated by solve, its last level kept)
        type(adapted_eigen_t), allocatable :: out(:)
    contains
        procedure :: solve => adapt_eigen_run_solve
    end type adapt_eigen_run_t

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

    subroutine adapt_eigen_run_solve(this, inputs, prob, timings, stat)
        class(adapt_eigen_run_t), intent(inout) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        call adapt_eigen(inputs%scene, [inputs%point%lambda], inputs%eigen, inputs%adapt, prob, &
                         this%out, timings, stat, keep_problem=.true.)
        ! Every end but a met tolerance is one not met: a mu not converged, one that
        ! vanished on refinement, and levels without a positive mu too few to confirm that
        ! there is none (a coarse mesh can miss a mu a finer one finds). 'none, confirmed'
        ! is met (eigen_goal_judge).
        if (.not. stat%ok()) return
        associate (out => this%out(1))
            ! a level that failed after the first: the last complete level is written
            if (.not. out%failure%ok()) then
                call this%verdict%fail(out%failure%code, naming_file(out%failure%message, &
                    inputs%scene%name)//': the results of the last complete level are written')
                return
            end if
            if (.not. out%converged) call this%verdict%fail(STATUS_NOT_MET, &
                inputs%scene%name//': &adapt: '//out%outcome// &
                ' (the set of the last level is written)')
        end associate
    end subroutine adapt_eigen_run_solve
end module eigen_run
