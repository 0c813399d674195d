! SPDX-License-Identifier: MIT
!> The files of the analyses of the frictional problem itself, in the input's units (their
!> problem's): 'branch' (eigenvalues.csv of the critical point, branch.csv, branch_NNN.vtu)
!> and 'solve' (newton.csv, contact_states.csv, solution.vtu).
module compliance_files
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string, zero_padded
    use real_format, only: real_to_text
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use branch_analysis, only: branch_result_t
    use solve_analysis, only: solve_result_t
    use normal_compliance, only: state_name
    use eigen_files, only: write_eigenvalues_csv
    use output_stage, only: output_stage_t
    use csv_writer, only: csv_writer_t
    use vtk_writer, only: write_vtu
    implicit none
    private
    public :: write_branch_files, write_solve_files, member_indices

contains

    !> eigenvalues.csv of the critical point, branch.csv (every member's residual) and the
    !> members branch_NNN.vtu that &branch write_members asks for, spread over the deltas.
    subroutine write_branch_files(stage, inputs, prob, res, stat)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(branch_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        integer, allocatable :: members(:)
        real(wp), allocatable :: x_base(:), u(:)
        integer :: j, i
        character(len=:), allocatable :: path

        call stage%add('eigenvalues.csv', path)
        call write_eigenvalues_csv(path, res%critical%eig%spec, stat)
        if (stat%ok()) then
            call stage%add('branch.csv', path)
            call write_branch_csv(path, res, stat)
        end if
        if (.not. (stat%ok() .and. inputs%output%vtk)) return
        x_base = res%critical%u_base(res%cp%free_to_all)
        members = member_indices(size(res%deltas), inputs%branch%write_members)
        allocate (u(size(res%cp%prescribed)))
        do j = 1, size(members)
            i = members(j)
            u(:) = res%cp%expand(x_base + res%deltas(i)*res%critical%phi)
            call stage%add('branch_'//zero_padded(i, 3)//'.vtu', path)
            call write_vtu(path, prob%mesh, &
                ['displacement'], reshape(u, [prob%mesh%dim(), prob%mesh%n_nodes(), 1]), &
                trim(inputs%output%vtk_format), stat)
            if (.not. stat%ok()) return
        end do
    end subroutine write_branch_files

    !> Indices of `wanted` members spread evenly over n (the middle one alone for one).
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

    !> index,delta,residual: one row per member U + delta phi.
    subroutine write_branch_csv(path, res, stat)
        character(len=*), intent(in) :: path
        type(branch_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        integer :: i
        call csv%open(path, 'index,delta,residual')
        do i = 1, size(res%deltas)
            call csv%row(to_string(i)//','//real_to_text(res%deltas(i))//','// &
                         real_to_text(res%residuals(i)))
        end do
        call csv%close(stat)
    end subroutine write_branch_csv

    !> newton.csv (the history), contact_states.csv (the state of every contact node) and,
    !> converged, solution.vtu.
    subroutine write_solve_files(stage, inputs, prob, res, stat)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(solve_result_t), intent(in) :: res
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: path
        call stage%add('newton.csv', path)
        call write_newton_csv(path, res, stat)
        if (stat%ok()) then
            call stage%add('contact_states.csv', path)
            call write_states_csv(path, prob, res, stat)
        end if
        if (stat%ok() .and. inputs%output%vtk .and. res%report%converged) then
            call stage%add('solution.vtu', path)
            call write_vtu(path, prob%mesh, ['displacement'], &
                reshape(res%cp%expand(res%x), [prob%mesh%dim(), prob%mesh%n_nodes(), 1]), &
                trim(inputs%output%vtk_format), stat)
        end if
    end subroutine write_solve_files

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
end module compliance_files
