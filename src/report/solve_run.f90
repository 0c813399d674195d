! SPDX-License-Identifier: MIT
!> analysis = 'solve': the files summary.json, newton.csv, contact_states.csv and
!> solution.vtu (only when Newton converged), and the short summary on stdout. A Newton
!> failure still writes its history, then ends the run in error (the verdict).
module solve_run
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string, short_real_text
    use real_format, only: real_to_text
    use timer, only: timings_t
    use version, only: NCEIG_VERSION
    use run_config, only: config_t
    use problem, only: problem_t
    use analysis_base, only: analysis_t
    use eigen_files, only: eigen_summary_json, no_eigen_summary_json
    use solve_analysis, only: solve_result_t, run_solve, solve_status
    use normal_compliance, only: state_name, STATE_SEPARATED, STATE_STICK, &
                                 STATE_SLIP_PLUS, STATE_SLIP_MINUS
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use csv_writer, only: csv_writer_t
    use vtk_writer, only: write_vtu
    implicit none
    private

    type, extends(analysis_t), public :: solve_run_t
        !> allocatable, allocated by solve: gfortran 12 frees it whole (docs/testing.md)
        type(solve_result_t), allocatable :: res
    contains
        procedure :: solve => solve_run_solve
        procedure :: write_files => solve_run_write_files
        procedure :: summary => solve_run_summary
        procedure :: report => solve_run_report
    end type solve_run_t

contains

    subroutine solve_run_solve(this, config, prob, timings, stat)
        class(solve_run_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        call run_solve(config, prob, this%res, timings, stat)
        if (stat%ok()) call solve_status(config, this%res, this%verdict)
    end subroutine solve_run_solve

    subroutine solve_run_write_files(this, stage, config, prob, stat)
        class(solve_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: path
        associate (res => this%res)
            call stage%add('newton.csv', path)
            call write_newton_csv(path, res, stat)
            if (stat%ok()) then
                call stage%add('contact_states.csv', path)
                call write_states_csv(path, prob, res, stat)
            end if
            if (stat%ok() .and. config%output%vtk .and. res%report%converged) then
                call stage%add('solution.vtu', path)
                call write_vtu(path, prob%mesh, ['displacement'], &
                    reshape(res%cp%expand(res%x), [prob%mesh%dim(), prob%mesh%n_nodes(), 1]), &
                    trim(config%output%vtk_format), stat)
            end if
        end associate
    end subroutine solve_run_write_files

    function solve_run_summary(this, config, prob) result(summary)
        class(solve_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(json_object_t) :: summary
        summary = solve_summary_json(config, prob, this%res, this%timings)
    end function solve_run_summary

    function solve_run_report(this, config, prob) result(text)
        class(solve_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        text = solve_summary_lines(config, prob, this%res)
    end function solve_run_report

    function solve_summary_json(config, prob, res, timings) result(summary)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(solve_result_t), intent(in) :: res
        type(timings_t), intent(in) :: timings
        type(json_object_t) :: summary

        ! The keys every summary.json has (docs/outputs.md): from the eigen solve when the run
        ! needed the critical eigenpair, null where no eigenproblem was solved.
        if (res%has_critical) then
            summary = eigen_summary_json(config, prob, res%critical%eig, timings)
        else
            summary = no_eigen_summary_json(config, prob, timings)
        end if
        call summary%add_string('data', trim(config%solve%data))
        call summary%add_string('start', trim(config%solve%start))
        call summary%add_real('c_n', res%cp%c_n)
        call summary%add_real('c_t', res%cp%c_t)
        call summary%add_logical('converged', res%report%converged)
        call summary%add_string('newton_stop', res%report%reason)
        call summary%add_integer('iterations', res%report%iterations)
        call summary%add_real('residual', res%report%residual(size(res%report%residual)))
        call summary%add_real('tol', config%solve%tol)
        call summary%add_real('load_norm', res%cp%load_norm)
        call summary%add_integer('n_separated', res%n_state(STATE_SEPARATED))
        call summary%add_integer('n_stick', res%n_state(STATE_STICK))
        call summary%add_integer('n_slip_plus', res%n_state(STATE_SLIP_PLUS))
        call summary%add_integer('n_slip_minus', res%n_state(STATE_SLIP_MINUS))
        if (res%on_branch_data) then
            call summary%add_real('branch_delta', res%branch_delta)
            call summary%add_real('branch_distance', res%branch_distance)
        end if
        call summary%add_real('time_assembly_s', timings%assembly)
        call summary%add_real('time_factor_s', timings%factor)
        call summary%add_real('time_eigen_s', timings%eigen)
        call summary%add_real('time_newton_s', res%time_newton)
        call summary%add_real('time_output_s', timings%output)
        call summary%add_real('time_total_s', timings%total)
    end function solve_summary_json

    !> iteration,residual,step,shift: e_k, the line-search step and the shift nu to reach x_k.
    subroutine write_newton_csv(path, res, stat)
        character(len=*), intent(in) :: path
        type(solve_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        integer :: k
        call csv%open(path, 'iteration,residual,step,shift')
        do k = 1, size(res%report%residual)
            call csv%row(to_string(k - 1)//','//real_to_text(res%report%residual(k))//','// &
                         real_to_text(res%report%step(k))//','//real_to_text(res%report%shift(k)))
        end do
        call csv%close(stat)
    end subroutine write_newton_csv

    !> node,x,y,u_n,u_t,normal_force,tangential_force,friction_bound,state per free contact
    !> node, in order along t.
    subroutine write_states_csv(path, prob, res, stat)
        character(len=*), intent(in) :: path
        type(problem_t), intent(in) :: prob
        type(solve_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: u_n(:), u_t(:), p_n(:), s_t(:), bound(:)
        type(csv_writer_t) :: csv
        integer :: a, node

        call res%cp%nodal_forces(res%x, u_n, u_t, p_n, s_t, bound)
        call csv%open(path, 'node,x,y,u_n,u_t,normal_force,tangential_force,friction_bound,state')
        do a = 1, res%cp%contact%p()
            if (res%cp%contact_free(1, a) == 0) cycle
            node = res%cp%contact%nodes(a)
            call csv%row(to_string(node)//','//real_to_text(prob%mesh%coords(1, node))//','// &
                real_to_text(prob%mesh%coords(2, node))//','//real_to_text(u_n(a))//','// &
                real_to_text(u_t(a))//','//real_to_text(p_n(a))//','//real_to_text(s_t(a))// &
                ','//real_to_text(bound(a))//','//state_name(res%states(a)))
        end do
        call csv%close(stat)
    end subroutine write_states_csv

    function solve_summary_lines(config, prob, res) result(text)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(solve_result_t), intent(in) :: res
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        text = 'nceig '//NCEIG_VERSION//': '//config%input_file//' (solve)'//NL// &
            '  problem     '//to_string(prob%dofs%n_free)//' dofs, '// &
            to_string(prob%contact%p())//' contact nodes, c_n = '//real_to_text(res%cp%c_n)// &
            ', c_t = '//real_to_text(res%cp%c_t)//NL// &
            '  newton      '//res%report%reason//' after '// &
            to_string(res%report%iterations)//' iterations, relative residual '// &
            short_real_text(res%report%residual(size(res%report%residual)))//NL// &
            '  contact     '//to_string(res%n_state(STATE_SEPARATED))//' separated, '// &
            to_string(res%n_state(STATE_STICK))//' stick, '// &
            to_string(res%n_state(STATE_SLIP_PLUS))//' slip+, '// &
            to_string(res%n_state(STATE_SLIP_MINUS))//' slip-'//NL
        if (res%on_branch_data) then
            text = text//'  branch      x = U + delta phi + r with delta = '// &
                real_to_text(res%branch_delta)//', ||r|| / ||U|| = '// &
                short_real_text(res%branch_distance)//NL
        end if
        text = text//'  output      '//trim(config%output%directory)
    end function solve_summary_lines
end module solve_run
