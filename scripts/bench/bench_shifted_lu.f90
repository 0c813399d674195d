! SPDX-License-Identifier: MIT
!> UMFPACK's fill-reducing orderings for the full operator's K - sigma B, measured on the
!> reference scene (P1 'right', N x N, lambda = 5, sigma = 0.5): for each N given on the
!> command line and each ordering (UMFPACK's default AMD, METIS, and CHOLMOD's choice of
!> AMD or METIS), without and with UMFPACK's iterative refinement, the median over REPEATS
!> of the factorization time, of one solve, and nnz(L + U). Usage: bench_shifted_lu N... (scripts/bench/bench_operator.sh builds it).
program bench_shifted_lu
    use iso_fortran_env, only: output_unit, error_unit
    use kinds, only: wp
    use status, only: status_t
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use contact_boundary, only: assemble_b
    use csr_matrix, only: csr_matrix_t
    use sparse_lu, only: lu_t, LU_ORDERING_DEFAULT, LU_ORDERING_METIS, LU_ORDERING_CHOLMOD
    use timer, only: wall_time
    use sorting, only: sort_index
    implicit none

    integer, parameter :: REPEATS = 3
    real(wp), parameter :: SIGMA = 0.5_wp
    integer, parameter :: ORDERINGS(3) = [LU_ORDERING_DEFAULT, LU_ORDERING_METIS, &
                                          LU_ORDERING_CHOLMOD]
    character(len=*), parameter :: ORDERING_NAMES(3) = [character(len=7) :: 'amd', 'metis', &
                                                        'cholmod']
    character(len=32) :: argument
    type(config_t) :: config
    type(problem_t) :: prob
    type(csr_matrix_t) :: b
    type(lu_t) :: lu
    type(status_t) :: stat
    real(wp) :: t_factor(REPEATS), t_solve(REPEATS), start
    !> UMFPACK's iterative refinement steps per solve: none (as the full operator) and its
    !> default
    integer, parameter :: REFINEMENTS(2) = [0, 2]
    integer :: refinement, i_step
    real(wp), allocatable :: rhs(:), x(:)
    integer :: i_arg, n, o, r

    write (output_unit, '(a)') '|     N |    dofs | ordering | refine | factor s | solve s |'// &
        '   nnz(L+U) |'
    write (output_unit, '(a)') '|------:|--------:|----------|-------:|---------:|--------:|'// &
        '-----------:|'
    do i_arg = 1, command_argument_count()
        call get_command_argument(i_arg, argument)
        read (argument, *) n
        config%input_file = 'bench'
        config%mesh%nx = n
        config%mesh%ny = n
        call build_problem(config, prob, stat)
        if (stat%ok()) call assemble_b(prob%contact, prob%dofs%n_free, 5.0_wp, b, stat)
        if (.not. stat%ok()) then
            write (error_unit, '(a)') stat%message
            error stop 1
        end if
        allocate (rhs(prob%dofs%n_free), x(prob%dofs%n_free))
        rhs = 1.0_wp
        do i_step = 1, size(REFINEMENTS)
        do o = 1, size(ORDERINGS)
            refinement = REFINEMENTS(i_step)
            do r = 1, REPEATS
                start = wall_time()
                call lu%factor_shifted(prob%k, b, SIGMA, stat, ORDERINGS(o), refinement)
                t_factor(r) = wall_time() - start
                if (.not. stat%ok()) exit
                start = wall_time()
                call lu%solve(rhs, x, stat)
                t_solve(r) = wall_time() - start
            end do
            if (.not. stat%ok()) then
                write (error_unit, '(a)') ORDERING_NAMES(o)//': '//stat%message
                cycle
            end if
            write (output_unit, '(a, i5, a, i7, a, a8, a, i6, a, f8.3, a, f7.4, a, i10, a)') &
                '| ', n, ' | ', prob%dofs%n_free, ' | ', ORDERING_NAMES(o), ' | ', refinement, &
                ' | ', median(t_factor), ' | ', median(t_solve), ' | ', &
                nint(lu%factor_nnz()), ' |'
            call lu%free()
        end do
        end do
        deallocate (rhs, x)
    end do

contains

    real(wp) function median(values)
        real(wp), intent(in) :: values(:)
        real(wp) :: sorted(size(values))
        sorted = values(sort_index(values))
        median = sorted((size(values) + 1)/2)
    end function median
end program bench_shifted_lu
