! SPDX-License-Identifier: MIT
!> analysis = 'threshold' and 'lambda_sweep', one type each: the critical lambdas on the mesh
!> of &mesh (threshold_run_t), with the curve lambda -> lowest positive mu over &sweep
!> (sweep_run_t, its points adapted with &adapt), and with &adapt tolerance > 0 the adaptive
!> loop of the critical lambdas on h or hp levels (adapt_threshold_run_t, threshold_goal),
!> whose last level is reported.
module threshold_run
    use kinds, only: wp
    use status, only: status_t, STATUS_NOT_MET, STATUS_NO_DIGIT
    use strings, only: to_string, short_real_text
    use timer, only: timings_t
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use critical_lambda, only: SIDE_PLUS, SIDE_MINUS, SIDE_LABELS
    use threshold_analysis, only: threshold_result_t, solve_thresholds
    use threshold_goal, only: adaptive_thresholds_t, solve_adapted_thresholds
    use joint_goal, only: solve_joint_sweep
    use analysis_base, only: analysis_t
    use process_exit, only: naming_file
    implicit none
    private

    !> 'threshold': the thresholds on the mesh of &mesh.
    type, extends(analysis_t), public :: threshold_run_t
        !> allocatable, allocated by solve: gfortran 12 frees it whole (docs/testing.md)
        type(threshold_result_t), allocatable :: res
    contains
        procedure :: solve => threshold_run_solve
    end type threshold_run_t

    !> 'lambda_sweep': the thresholds and the lowest positive mu at every lambda of &sweep.
    type, extends(analysis_t), public :: sweep_run_t
        type(threshold_result_t), allocatable :: res
    contains
        procedure :: solve => sweep_run_solve
    end type sweep_run_t

    !> 'threshold' with &adapt: the loop, whose last level the result describes.
    type, extends(analysis_t), public :: adapt_threshold_run_t
        type(threshold_result_t), allocatable :: res
        type(adaptive_thresholds_t), allocatable :: adapted
    contains
        procedure :: solve => adapt_threshold_run_solve
    end type adapt_threshold_run_t

    !> 'lambda_sweep' with &sweep adapt_thresholds: the points and the thresholds adapted in
    !> one hp climb (joint_goal), whose last level the thresholds' result describes.
    type, extends(analysis_t), public :: joint_sweep_run_t
        type(threshold_result_t), allocatable :: res
        type(adaptive_thresholds_t), allocatable :: adapted
    contains
        procedure :: solve => joint_sweep_run_solve
    end type joint_sweep_run_t

contains

    subroutine threshold_run_solve(this, inputs, prob, timings, stat)
        class(threshold_run_t), intent(inout) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        call solve_thresholds(inputs%scene, prob, inputs%point%lambda, inputs%eigen, inputs%scan, &
                              this%res, timings, stat)
        if (stat%ok()) call no_digit_verdict(this%res, inputs%scene%name, this%verdict)
    end subroutine threshold_run_solve

    subroutine sweep_run_solve(this, inputs, prob, timings, stat)
        class(sweep_run_t), intent(inout) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        call solve_thresholds(inputs%scene, prob, inputs%point%lambda, inputs%eigen, inputs%scan, &
                              this%res, timings, stat, inputs%sweep, inputs%adapt)
        if (.not. stat%ok()) return
        ! a point's loop failed: its failure is the run's, after the partial set is written
        associate (curve => this%res%sweep)
            if (.not. curve%failure%ok()) then
                call this%verdict%fail(curve%failure%code, naming_file( &
                    curve%failure%message, inputs%scene%name)//' (the sweep stopped there: '// &
                    'a partial set of the '//to_string(count(curve%complete))//' of '// &
                    to_string(size(curve%lambda))//' points complete is written)')
                return
            end if
        end associate
        call no_digit_verdict(this%res, inputs%scene%name, this%verdict)
        if (this%verdict%ok()) call points_verdict(this%res, inputs%scene%name, this%verdict)
    end subroutine sweep_run_solve

    subroutine adapt_threshold_run_solve(this, inputs, prob, timings, stat)
        class(adapt_threshold_run_t), intent(inout) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        if (.not. allocated(this%adapted)) allocate (this%adapted)
        call solve_adapted_thresholds(inputs%scene, inputs%point%lambda, inputs%eigen, &
            inputs%adapt, inputs%scan, prob, this%adapted, this%res, timings, stat)
        if (stat%ok()) call sides_verdict(this%adapted, inputs%scene%name, this%verdict)
        if (stat%ok()) call no_digit_verdict(this%res, inputs%scene%name, this%verdict)
        if (stat%ok()) call failure_verdict(this%adapted%failure, inputs%scene%name, &
                                            this%verdict)
    end subroutine adapt_threshold_run_solve

    !> The verdict is the thresholds' (as an adaptive threshold run's), else the points'
    !> (as an adapted sweep's): each part's outcome is in its own files.
    subroutine joint_sweep_run_solve(this, inputs, prob, timings, stat)
        class(joint_sweep_run_t), intent(inout) :: this
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        if (.not. allocated(this%adapted)) allocate (this%adapted)
        call solve_joint_sweep(inputs%scene, inputs%point%lambda, inputs%sweep, inputs%eigen, &
            inputs%adapt, inputs%scan, prob, this%adapted, this%res, timings, stat)
        if (.not. stat%ok()) return
        call sides_verdict(this%adapted, inputs%scene%name, this%verdict)
        if (this%verdict%ok()) call points_verdict(this%res, inputs%scene%name, this%verdict)
        if (this%verdict%ok()) call no_digit_verdict(this%res, inputs%scene%name, this%verdict)
        call failure_verdict(this%adapted%failure, inputs%scene%name, this%verdict)
    end subroutine joint_sweep_run_solve

    !> A level that failed after the first (`failure`, ok: none) is the run's verdict, over
    !> any other: its outputs are the last complete level's.
    subroutine failure_verdict(failure, name, verdict)
        type(status_t), intent(in) :: failure
        character(len=*), intent(in) :: name
        type(status_t), intent(inout) :: verdict
        if (.not. failure%ok()) call verdict%fail(failure%code, naming_file(failure%message, &
            name)//': the results of the last complete level are written')
    end subroutine failure_verdict

    !> `verdict` STATUS_NOT_MET where the adapted thresholds missed the tolerance.
    subroutine sides_verdict(adapted, name, verdict)
        type(adaptive_thresholds_t), intent(in) :: adapted
        character(len=*), intent(in) :: name
        type(status_t), intent(inout) :: verdict
        if (.not. adapted%converged) call verdict%fail(STATUS_NOT_MET, name//': &adapt: '// &
            adapted%outcome//' (the set of the last level is written)')
    end subroutine sides_verdict

    !> `verdict` STATUS_NOT_MET where points of the adapted sweep of `res` missed it.
    subroutine points_verdict(res, name, verdict)
        type(threshold_result_t), intent(in) :: res
        character(len=*), intent(in) :: name
        type(status_t), intent(inout) :: verdict
        if (res%sweep%n_not_met > 0) call verdict%fail(STATUS_NOT_MET, name//': &adapt: '// &
            to_string(res%sweep%n_not_met)//' of the sweep''s points did not meet the '// &
            'tolerance, the first at '//res%sweep%not_met// &
            ' (the set is written)')
    end subroutine points_verdict

    !> `verdict` STATUS_NO_DIGIT (after the outputs: the set shows what was computed) where
    !> round-off leaves no correct digit of a critical lambda of `res` or of a collision
    !> point: its round-off bound is 1 or more. `name`: the input's, for the message.
    subroutine no_digit_verdict(res, name, verdict)
        type(threshold_result_t), intent(in) :: res
        character(len=*), intent(in) :: name
        type(status_t), intent(inout) :: verdict
        real(wp) :: worst
        integer :: side, i
        character(len=:), allocatable :: what
        worst = -1.0_wp
        what = ''
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. res%thresholds%found(side)) cycle
            if (res%thresholds%roundoff(side) <= worst) cycle
            worst = res%thresholds%roundoff(side)
            what = trim(SIDE_LABELS(side))
        end do
        do i = 1, size(res%set%points)
            if (res%set%points(i)%roundoff <= worst) cycle
            worst = res%set%points(i)%roundoff
            what = 'the collision point lambda = '//short_real_text(res%set%points(i)%lambda, 12)
        end do
        if (worst >= 1.0_wp) call verdict%fail(STATUS_NO_DIGIT, name// &
            ': round-off leaves no correct digit of '//what//' (bound '// &
            short_real_text(worst)//' relative); the output set is written')
    end subroutine no_digit_verdict
end module threshold_run
