! SPDX-License-Identifier: MIT
!> nceig INPUT.nml: read input -> build the problem -> solve -> write outputs -> summary.
!> The only place that prints, and the only place that ends the process on an error.
program nceig
    use iso_fortran_env, only: error_unit, output_unit
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use version, only: NCEIG_VERSION
    use process_exit, only: exit_with, exit_now, stop_with, stop_on_failure
    use timer, only: wall_time, timings_t, PHASE_ASSEMBLY
    use strings, only: to_string
    use run_config, only: config_t
    use input_config, only: read_input
    use run_inputs, only: run_inputs_t, translate_input
    use command_line, only: command_t, read_command_line
    use input_help, only: help_text
    use problem, only: problem_t, build_problem
    use analysis_base, only: analysis_t
    use analysis_registry, only: new_analysis
    use run_report, only: report_run
    use console, only: print_progress
    use process, only: ignore_broken_pipe
    use memory_budget, only: check_address_space
    use program_start, only: start_signal_thread
    implicit none

    character(len=*), parameter :: PROGRAM_NAME = 'nceig'
    type(config_t) :: config
    type(run_inputs_t) :: inputs
    type(problem_t) :: prob
    class(analysis_t), allocatable :: analysis
    type(timings_t) :: timings
    type(status_t) :: stat
    type(command_t) :: command
    real(wp) :: start, phase
    character(len=:), allocatable :: text
    integer :: ios

    ! stdout is a report, not the results: a reader that stops early (`| head`) must not end
    ! the run by SIGPIPE, maybe before its commit. Lines it did not take are lost (iostat).
    call ignore_broken_pipe()
    call read_command_line(command, stat)
    call stop_on_failure(PROGRAM_NAME, stat)
    select case (command%action)
    case ('help')
        write (output_unit, '(a)', iostat=ios) help_text()
        call exit_with(0)
    case ('version')
        write (output_unit, '(a)', iostat=ios) 'nceig '//NCEIG_VERSION
        call exit_with(0)
    end select

    ! From here SIGTERM, SIGINT, SIGHUP and SIGXCPU end the run by that signal, whatever
    ! library runs (blocked in every thread since the start, taken by a thread of their own).
    call start_signal_thread(command%input)
    start = wall_time()
    call read_input(command%input, config, stat, command%settings)
    call stop_on_failure(PROGRAM_NAME, stat)

    call translate_input(config, inputs)
    call new_analysis(inputs, analysis)
    if (.not. allocated(analysis)) then
        call stop_with(PROGRAM_NAME, config%input_file//': &analysis: kind = '''// &
                       trim(config%analysis%kind)//''' has no analysis', STATUS_BAD_INPUT)
    end if

    if (config%output%progress) then
        timings%listener => print_progress
        call print_progress('nceig '//NCEIG_VERSION//': '//config%input_file//' ('// &
                            trim(config%analysis%kind)//'), started')
    end if
    phase = wall_time()
    if (analysis%in_input_units()) then
        call build_problem(inputs%scene, prob, stat, input_units_for=inputs%analysis_name)
    else
        call build_problem(inputs%scene, prob, stat)
    end if
    call stop_on_failure(PROGRAM_NAME, stat, inputs%scene%name)
    call timings%add(PHASE_ASSEMBLY, wall_time() - phase, ': '//to_string(prob%mesh%n_cells())// &
        ' cells, '//to_string(prob%dofs%n_free)//' dofs, '//to_string(prob%contact%p())// &
        ' contact nodes, K with '//to_string(prob%k%nnz())//' entries')

    call check_address_space(stat)
    if (.not. stat%ok()) then
        ! exit handlers would hang: OpenBLAS's shutdown joins a thread retrying its buffer
        write (error_unit, '(a)') 'nceig: '//config%input_file//': '//stat%message
        call exit_now(stat%code)
    end if
    call analysis%solve(inputs, prob, timings, stat)
    call stop_on_failure(PROGRAM_NAME, stat, inputs%scene%name)
    call report_run(analysis, inputs, prob, start, timings, text, stat)
    call stop_on_failure(PROGRAM_NAME, stat, inputs%scene%name)
    write (output_unit, '(a)', iostat=ios) text
    call stop_on_failure(PROGRAM_NAME, analysis%verdict, inputs%scene%name)
    ! gfortran 12 keeps main-program allocatables in a frame gone before LeakSanitizer looks
    deallocate (command%action, command%input, command%settings)
    deallocate (analysis, text)
end program nceig
