! SPDX-License-Identifier: MIT
!> nceig INPUT.nml: read input -> build the problem -> solve -> write outputs -> summary.
!> The only place that prints, and the only place that ends the process on an error.
program nceig
    use iso_fortran_env, only: error_unit, output_unit
    use kinds, only: wp
    use status, only: status_t
    use version, only: NCEIG_VERSION
    use process_exit, only: exit_with
    use timer, only: wall_time, timings_t
    use run_config, only: config_t
    use input_config, only: read_input
    use command_line, only: command_t, read_command_line
    use input_help, only: help_text
    use problem, only: problem_t, build_problem
    use eigen_analysis, only: eigen_result_t, solve_eigen
    use results_output, only: write_eigen_outputs, summary_lines
    use threshold_analysis, only: threshold_result_t, solve_thresholds
    use threshold_output, only: write_threshold_outputs, threshold_summary_lines
    use sweep_plot, only: plot_lambda_sweep
    use branch_analysis, only: branch_result_t, run_branch
    use solve_analysis, only: solve_result_t, run_solve, solve_status
    use compliance_output, only: write_branch_outputs, branch_summary_lines, &
                                 write_solve_outputs, solve_summary_lines
    implicit none

    type(config_t) :: config
    type(problem_t) :: prob
    type(eigen_result_t) :: res
    type(threshold_result_t) :: thresholds
    character(len=:), allocatable :: plot_note
    type(branch_result_t) :: branch_res
    type(solve_result_t) :: solve_res
    type(timings_t) :: timings
    type(status_t) :: stat
    type(command_t) :: command
    real(wp) :: start, phase

    call read_command_line(command, stat)
    call stop_on_failure(stat)
    select case (command%action)
    case ('help')
        write (output_unit, '(a)') help_text()
        call exit_with(0)
    case ('version')
        write (output_unit, '(a)') 'nceig '//NCEIG_VERSION
        call exit_with(0)
    end select

    start = wall_time()
    call read_input(command%input, config, stat, command%settings)
    call stop_on_failure(stat)

    phase = wall_time()
    call build_problem(config, prob, stat)
    call stop_on_failure(stat)
    timings%assembly = wall_time() - phase

    select case (config%analysis%kind)
    case ('threshold')
        call solve_thresholds(config, prob, .false., thresholds, timings, stat)
        call stop_on_failure(stat)
        call write_threshold_outputs(config, prob, thresholds, start, timings, stat)
        call stop_on_failure(stat)
        write (output_unit, '(a)') threshold_summary_lines(config, prob, thresholds, timings)
    case ('lambda_sweep')
        call solve_thresholds(config, prob, .true., thresholds, timings, stat)
        call stop_on_failure(stat)
        call write_threshold_outputs(config, prob, thresholds, start, timings, stat)
        call stop_on_failure(stat)
        write (output_unit, '(a)') threshold_summary_lines(config, prob, thresholds, timings)
        if (config%sweep%plot) then
            call plot_lambda_sweep(trim(config%output%directory), plot_note)
            write (output_unit, '(a)') '  plot        '//plot_note
        end if
    case ('branch')
        call run_branch(config, prob, branch_res, timings, stat)
        call stop_on_failure(stat)
        call write_branch_outputs(config, prob, branch_res, start, timings, stat)
        call stop_on_failure(stat)
        write (output_unit, '(a)') branch_summary_lines(config, prob, branch_res)
    case ('solve')
        call run_solve(config, prob, solve_res, timings, stat)
        call stop_on_failure(stat)
        ! A failed Newton iteration still writes its history, then ends the run in error.
        call write_solve_outputs(config, prob, solve_res, start, timings, stat)
        call stop_on_failure(stat)
        write (output_unit, '(a)') solve_summary_lines(config, prob, solve_res)
        call solve_status(config, solve_res, stat)
        call stop_on_failure(stat)
    case default
        call solve_eigen(config, prob, config%analysis%lambda, res, timings, stat)
        call stop_on_failure(stat)
        call write_eigen_outputs(config, prob, res, start, timings, stat)
        call stop_on_failure(stat)
        write (output_unit, '(a)') summary_lines(config, prob, res, timings)
    end select
    ! gfortran 12 keeps main-program allocatables in a frame gone before LeakSanitizer looks
    deallocate (command%action, command%input, command%settings)
    if (allocated(plot_note)) deallocate (plot_note)

contains

    !> One line on standard error and a non-zero exit: 2 for bad input, the status code else.
    subroutine stop_on_failure(stat)
        type(status_t), intent(in) :: stat
        if (stat%ok()) return
        write (error_unit, '(a)') 'nceig: '//stat%message
        call exit_with(stat%code)
    end subroutine stop_on_failure
end program nceig
