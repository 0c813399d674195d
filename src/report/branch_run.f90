! SPDX-License-Identifier: MIT
!> analysis = 'branch': the files summary.json, eigenvalues.csv, branch.csv and
!> branch_NNN.vtu (members U + delta phi), and the short summary on stdout.
module branch_run
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string, zero_padded, short_real_text
    use real_format, only: real_to_text
    use timer, only: timings_t
    use version, only: NCEIG_VERSION
    use run_config, only: config_t
    use problem, only: problem_t
    use analysis_base, only: analysis_t
    use eigen_files, only: eigen_summary_json, write_eigenvalues_csv
    use branch_analysis, only: branch_result_t, run_branch
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use csv_writer, only: csv_writer_t
    use vtk_writer, only: write_vtu
    implicit none
    private
    public :: member_indices

    type, extends(analysis_t), public :: branch_run_t
        !> allocatable, allocated by solve: gfortran 12 frees it whole (docs/testing.md)
        type(branch_result_t), allocatable :: res
    contains
        procedure :: solve => branch_run_solve
        procedure :: write_files => branch_run_write_files
        procedure :: summary => branch_run_summary
        procedure :: report => branch_run_report
    end type branch_run_t

contains

    subroutine branch_run_solve(this, config, prob, timings, stat)
        class(branch_run_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        call run_branch(config, prob, this%res, timings, stat)
    end subroutine branch_run_solve

    !> eigenvalues.csv, branch.csv and the members asked for as branch_NNN.vtu.
    subroutine branch_run_write_files(this, stage, config, prob, stat)
        class(branch_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        integer, allocatable :: members(:)
        real(wp), allocatable :: x_base(:), u(:)
        integer :: j, i
        character(len=:), allocatable :: path

        associate (res => this%res)
            call stage%add('eigenvalues.csv', path)
            call write_eigenvalues_csv(path, res%critical%eig%spec, stat)
            if (stat%ok()) then
                call stage%add('branch.csv', path)
                call write_branch_csv(path, res, stat)
            end if
            if (.not. (stat%ok() .and. config%output%vtk)) return
            x_base = res%critical%u_base(res%cp%free_to_all)
            members = member_indices(size(res%deltas), config%branch%write_members)
            allocate (u(size(res%cp%prescribed)))
            do j = 1, size(members)
                i = members(j)
                u(:) = res%cp%expand(x_base + res%deltas(i)*res%critical%phi)
                call stage%add('branch_'//zero_padded(i, 3)//'.vtu', path)
                call write_vtu(path, prob%mesh, &
                    ['displacement'], reshape(u, [prob%mesh%dim(), prob%mesh%n_nodes(), 1]), &
                    trim(config%output%vtk_format), stat)
                if (.not. stat%ok()) return
            end do
        end associate
    end subroutine branch_run_write_files

    function branch_run_summary(this, config, prob) result(summary)
        class(branch_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(json_object_t) :: summary
        associate (res => this%res)
            summary = eigen_summary_json(config, prob, res%critical%eig, this%timings)
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
        end associate
    end function branch_run_summary

    function branch_run_report(this, config, prob) result(text)
        class(branch_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        text = branch_summary_lines(config, prob, this%res)
    end function branch_run_report

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
end module branch_run
