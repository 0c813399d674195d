! SPDX-License-Identifier: MIT
!> The files of the 'branch' and 'solve' analyses, staged and moved into place together, and
!> their short summaries on stdout.
!> branch: summary.json, eigenvalues.csv, branch.csv, branch_NNN.vtu.
!> solve:  summary.json, newton.csv, contact_states.csv, solution.vtu (only when converged).
module compliance_output
    use kinds, only: wp, N_DIM
    use status, only: status_t, STATUS_IO
    use strings, only: to_string, zero_padded, short_real_text
    use real_format, only: real_to_text
    use timer, only: wall_time, timings_t
    use version, only: NCEIG_VERSION
    use run_config, only: config_t
    use problem, only: problem_t
    use output_stage, only: output_stage_t
    use filesystem, only: close_output
    use json_writer, only: json_object_t
    use vtk_writer, only: write_vtu
    use results_output, only: eigen_summary_json, write_eigenvalues_csv, commit_with_summary, &
                              slip_sign
    use mesh, only: element_name
    use normal_compliance, only: state_name, STATE_SEPARATED, STATE_STICK, &
                                 STATE_SLIP_PLUS, STATE_SLIP_MINUS
    use branch_analysis, only: branch_result_t
    use solve_analysis, only: solve_result_t
    implicit none
    private
    public :: write_branch_outputs, branch_summary_lines, write_solve_outputs, &
              solve_summary_lines, member_indices

contains

    !> Which of n members to write when `wanted` are asked for: all, or spread evenly from
    !> the first to the last (the middle one when wanted = 1).
    pure function member_indices(n, wanted) result(indices)
        integer, intent(in) :: n, wanted
        integer, allocatable :: indices(:)
        integer :: j, count
        count = min(n, wanted)
        allocate (indices(count))
        if (count == 1) then
            indices(1) = (n + 1)/2
        else
            do j = 1, count
                indices(j) = 1 + nint(real((j - 1)*(n - 1), wp)/real(count - 1, wp))
            end do
        end if
    end function member_indices

    subroutine write_branch_outputs(config, prob, res, run_start, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(branch_result_t), intent(in) :: res
        real(wp), intent(in) :: run_start
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(output_stage_t) :: stage
        type(json_object_t) :: summary
        integer, allocatable :: members(:)
        real(wp), allocatable :: x_base(:), u(:)
        real(wp) :: start
        integer :: j, i

        start = wall_time()
        call stage%begin(trim(config%output%directory), stat)
        if (.not. stat%ok()) return
        call write_eigenvalues_csv(stage%path('eigenvalues.csv'), res%critical%eig%spec, stat)
        if (stat%ok()) call write_branch_csv(stage%path('branch.csv'), res, stat)
        if (stat%ok() .and. config%output%vtk) then
            x_base = res%critical%u_base(res%cp%free_to_all)
            members = member_indices(size(res%deltas), config%branch%write_members)
            do j = 1, size(members)
                i = members(j)
                u = res%cp%expand(x_base + res%deltas(i)*res%critical%phi)
                call write_vtu(stage%path('branch_'//zero_padded(i, 3)//'.vtu'), prob%mesh, &
                    ['displacement'], reshape(u, [N_DIM, prob%mesh%n_nodes(), 1]), &
                    trim(config%output%vtk_format), stat)
                if (.not. stat%ok()) exit
            end do
        end if
        if (stat%ok()) then
            timings%output = wall_time() - start
            timings%total = wall_time() - run_start
            summary = eigen_summary_json(config, prob, res%critical%eig, timings)
            call summary%add_real('alpha', res%critical%alpha)
            call summary%add_real('beta', res%critical%beta)
            call summary%add_real('c_n', res%cp%c_n)
            call summary%add_real('c_t', res%cp%c_t)
            call summary%add_real('delta_max', res%delta_max)
            call summary%add_integer('n_delta', size(res%deltas))
            call summary%add_real('branch_base_residual', res%residual_base)
            call summary%add_real('branch_max_residual', res%max_residual)
            call summary%add_real('load_norm', res%cp%load_norm)
            call summary%add_real('time_branch_s', res%time_branch)
            call commit_with_summary(stage, summary, stat)
        end if
        if (.not. stat%ok()) call stage%abort()
    end subroutine write_branch_outputs

    !> index,delta,residual: one row per member U + delta phi.
    subroutine write_branch_csv(path, res, stat)
        character(len=*), intent(in) :: path
        type(branch_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        character(len=512) :: msg
        integer :: unit, ios, i
        open (newunit=unit, file=path, status='replace', action='write', iostat=ios, iomsg=msg)
        if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) 'index,delta,residual'
        do i = 1, size(res%deltas)
            if (ios /= 0) exit
            write (unit, '(a)', iostat=ios, iomsg=msg) to_string(i)//','// &
                real_to_text(res%deltas(i))//','//real_to_text(res%residuals(i))
        end do
        if (ios == 0) call close_output(unit, path, ios, msg)
        if (ios /= 0) call stat%fail(STATUS_IO, path//': cannot write: '//trim(msg))
    end subroutine write_branch_csv

    function branch_summary_lines(config, prob, res) result(text)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(branch_result_t), intent(in) :: res
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        text = 'nceig '//NCEIG_VERSION//': '//config%input_file//' (branch)'//NL// &
            '  problem     '//to_string(prob%dofs%n_free)//' dofs, '// &
            to_string(prob%contact%p())//' contact nodes, lambda = '// &
            real_to_text(res%critical%lambda)//NL// &
            '  critical    c_n = mu = '//real_to_text(res%cp%c_n)//', c_t = '// &
            real_to_text(res%cp%c_t)//NL// &
            '  branch      U + delta phi for |delta| <= delta_max = '// &
            real_to_text(res%delta_max)//' (alpha = '//real_to_text(res%critical%alpha)// &
            ', beta = '//real_to_text(res%critical%beta)//')'//NL// &
            '  residual    U: '//short_real_text(res%residual_base)//', max over '// &
            to_string(size(res%deltas))//' members: '//short_real_text(res%max_residual)// &
            ' (relative to the load)'//NL// &
            '  output      '//trim(config%output%directory)
    end function branch_summary_lines

    subroutine write_solve_outputs(config, prob, res, run_start, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(solve_result_t), intent(in) :: res
        real(wp), intent(in) :: run_start
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(output_stage_t) :: stage
        type(json_object_t) :: summary
        real(wp) :: start

        start = wall_time()
        call stage%begin(trim(config%output%directory), stat)
        if (.not. stat%ok()) return
        call write_newton_csv(stage%path('newton.csv'), res, stat)
        if (stat%ok()) call write_states_csv(stage%path('contact_states.csv'), prob, res, stat)
        if (stat%ok() .and. config%output%vtk .and. res%report%converged) then
            call write_vtu(stage%path('solution.vtu'), prob%mesh, ['displacement'], &
                reshape(res%cp%expand(res%x), [N_DIM, prob%mesh%n_nodes(), 1]), &
                trim(config%output%vtk_format), stat)
        end if
        if (stat%ok()) then
            timings%output = wall_time() - start
            timings%total = wall_time() - run_start
            summary = solve_summary_json(config, prob, res, timings)
            call commit_with_summary(stage, summary, stat)
        end if
        if (.not. stat%ok()) call stage%abort()
    end subroutine write_solve_outputs

    function solve_summary_json(config, prob, res, timings) result(summary)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(solve_result_t), intent(in) :: res
        type(timings_t), intent(in) :: timings
        type(json_object_t) :: summary

        ! The keys every summary.json has (SPEC section 7): from the eigen solve when the run
        ! needed the critical eigenpair, null where no eigenproblem was solved.
        if (res%has_critical) then
            summary = eigen_summary_json(config, prob, res%critical%eig, timings)
        else
            call summary%add_string('nceig_version', NCEIG_VERSION)
            call summary%add_string('input', config%input_file)
            call summary%add_string('analysis', trim(config%analysis%kind))
            call summary%add_real('lambda', config%analysis%lambda)
            call summary%add_string('element', element_name(prob%mesh%element))
            call summary%add_string('mesh_source', trim(config%mesh%source))
            call summary%add_integer('n_nodes', prob%mesh%n_nodes())
            call summary%add_integer('n_cells', prob%mesh%n_cells())
            call summary%add_integer('n_dofs', prob%dofs%n_free)
            call summary%add_integer('n_contact', prob%contact%p())
            call summary%add_null('solver')
            call summary%add_null('lowest_positive_mu')
            call summary%add_null('critical_c_n')
            call summary%add_null('critical_c_t')
            call summary%add_integer('slip_sign', slip_sign(config%analysis%lambda))
            call summary%add_integer('n_eigenvalues', 0)
            call summary%add_null('max_residual')
            call summary%add_string_array('warnings', [character(len=1) ::])
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
        character(len=512) :: msg
        integer :: unit, ios, k
        open (newunit=unit, file=path, status='replace', action='write', iostat=ios, iomsg=msg)
        if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) 'iteration,residual,step,shift'
        do k = 1, size(res%report%residual)
            if (ios /= 0) exit
            write (unit, '(a)', iostat=ios, iomsg=msg) to_string(k - 1)//','// &
                real_to_text(res%report%residual(k))//','//real_to_text(res%report%step(k))// &
                ','//real_to_text(res%report%shift(k))
        end do
        if (ios == 0) call close_output(unit, path, ios, msg)
        if (ios /= 0) call stat%fail(STATUS_IO, path//': cannot write: '//trim(msg))
    end subroutine write_newton_csv

    !> node,x,y,u_n,u_t,normal_force,tangential_force,friction_bound,state per free contact
    !> node, in order along t.
    subroutine write_states_csv(path, prob, res, stat)
        character(len=*), intent(in) :: path
        type(problem_t), intent(in) :: prob
        type(solve_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: u_n(:), u_t(:), p_n(:), s_t(:), bound(:)
        character(len=512) :: msg
        integer :: unit, ios, a, node

        call res%cp%nodal_forces(res%x, u_n, u_t, p_n, s_t, bound)
        open (newunit=unit, file=path, status='replace', action='write', iostat=ios, iomsg=msg)
        if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) &
            'node,x,y,u_n,u_t,normal_force,tangential_force,friction_bound,state'
        do a = 1, res%cp%contact%p()
            if (ios /= 0) exit
            if (res%cp%contact_free(1, a) == 0) cycle
            node = res%cp%contact%nodes(a)
            write (unit, '(a)', iostat=ios, iomsg=msg) to_string(node)//','// &
                real_to_text(prob%mesh%coords(1, node))//','// &
                real_to_text(prob%mesh%coords(2, node))//','//real_to_text(u_n(a))//','// &
                real_to_text(u_t(a))//','//real_to_text(p_n(a))//','//real_to_text(s_t(a))// &
                ','//real_to_text(bound(a))//','//state_name(res%states(a))
        end do
        if (ios == 0) call close_output(unit, path, ios, msg)
        if (ios /= 0) call stat%fail(STATUS_IO, path//': cannot write: '//trim(msg))
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
end module compliance_output
