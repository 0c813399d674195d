! SPDX-License-Identifier: MIT
!> UMFPACK's int ("di") against its long ("dl") index API on the full operator's K - sigma B
!> (reference scene: unit square, top fixed, contact on the bottom, E = 1, nu = 0.3,
!> lambda = 5, sigma = 0.5; UMFPACK's default ordering, no iterative refinement, as
!> full_operator_t factors it): for each scene N:ELEMENT on the command line (e.g. 128:p3
!> 512:p1), the medians over REPEATS of the symbolic + numeric time and of one solve, the
!> peak memory UMFPACK reports (Info PEAK_MEMORY x SIZE_OF_UNIT), the size of the Numeric
!> object, and the bytes of the 0-based index copies lu_t keeps. Also the largest difference
!> between the two solutions, to show that the index width changes no digit. Run by
!> scripts/bench/bench_index_width.sh. The interfaces of the dl routines are local: nceig
!> itself calls only the di ones (docs/performance.md, "Index width").
program bench_index_width
    use, intrinsic :: iso_c_binding, only: c_int, c_int64_t, c_double, c_ptr, c_null_ptr
    use iso_fortran_env, only: output_unit, error_unit
    use kinds, only: wp
    use status, only: status_t
    use mesh, only: mesh_t
    use element_types, only: element_from_name
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use contact_boundary, only: contact_t, build_contact, assemble_b
    use csr_matrix, only: csr_matrix_t
    use umfpack_c, only: umfpack_di_symbolic, umfpack_di_numeric, umfpack_di_solve, &
                         umfpack_di_free_symbolic, umfpack_di_free_numeric, umfpack_di_defaults, &
                         UMFPACK_CONTROL, UMFPACK_INFO, UMFPACK_At, UMFPACK_PRL, UMFPACK_IRSTEP
    use timer, only: wall_time
    use sorting, only: sort_index
    implicit none

    integer, parameter :: REPEATS = 3
    real(wp), parameter :: SIGMA = 0.5_wp, LAMBDA = 5.0_wp
    ! C indices into Info (umfpack.h), plus 1 in Fortran
    integer, parameter :: SIZE_OF_UNIT = 3, NUMERIC_SIZE = 40, PEAK_MEMORY = 41

    interface
        function umfpack_dl_symbolic(n_row, n_col, ap, ai, ax, symbolic, control, info) &
                bind(C, name='umfpack_dl_symbolic') result(status)
            import :: c_int64_t, c_double, c_ptr
            integer(c_int64_t), value :: n_row, n_col
            integer(c_int64_t), intent(in) :: ap(*), ai(*)
            real(c_double), intent(in) :: ax(*), control(*)
            type(c_ptr), intent(out) :: symbolic
            real(c_double), intent(out) :: info(*)
            integer(c_int64_t) :: status
        end function umfpack_dl_symbolic

        function umfpack_dl_numeric(ap, ai, ax, symbolic, numeric, control, info) &
                bind(C, name='umfpack_dl_numeric') result(status)
            import :: c_int64_t, c_double, c_ptr
            integer(c_int64_t), intent(in) :: ap(*), ai(*)
            real(c_double), intent(in) :: ax(*), control(*)
            type(c_ptr), value :: symbolic
            type(c_ptr), intent(out) :: numeric
            real(c_double), intent(out) :: info(*)
            integer(c_int64_t) :: status
        end function umfpack_dl_numeric

        function umfpack_dl_solve(sys, ap, ai, ax, x, b, numeric, control, info) &
                bind(C, name='umfpack_dl_solve') result(status)
            import :: c_int64_t, c_double, c_ptr
            integer(c_int64_t), value :: sys
            integer(c_int64_t), intent(in) :: ap(*), ai(*)
            real(c_double), intent(in) :: ax(*), b(*), control(*)
            real(c_double), intent(out) :: x(*), info(*)
            type(c_ptr), value :: numeric
            integer(c_int64_t) :: status
        end function umfpack_dl_solve

        subroutine umfpack_dl_free_symbolic(symbolic) bind(C, name='umfpack_dl_free_symbolic')
            import :: c_ptr
            type(c_ptr), intent(inout) :: symbolic
        end subroutine umfpack_dl_free_symbolic

        subroutine umfpack_dl_free_numeric(numeric) bind(C, name='umfpack_dl_free_numeric')
            import :: c_ptr
            type(c_ptr), intent(inout) :: numeric
        end subroutine umfpack_dl_free_numeric
    end interface

    character(len=32) :: argument
    type(mesh_t) :: m
    type(dof_map_t) :: dofs
    type(contact_t) :: contact
    type(csr_matrix_t) :: k, b
    type(status_t) :: stat
    real(c_double) :: control(UMFPACK_CONTROL), info(UMFPACK_INFO), info_factor(UMFPACK_INFO)
    real(c_double), allocatable :: ax(:), rhs(:), x_int(:), x_long(:)
    integer(c_int), allocatable :: ap32(:), ai32(:)
    integer(c_int64_t), allocatable :: ap64(:), ai64(:)
    real(wp) :: t_factor(REPEATS), t_solve(REPEATS), start, peak, numeric_bytes
    integer :: i_arg, n_cells, colon, r, width

    write (output_unit, '(a)') '| scene | dofs | nnz(A) | API | factor s | solve s | '// &
        'peak MB | Numeric MB | index copies MB | max |x_dl - x_di| / max |x_di| |'
    write (output_unit, '(a)') '|---|---:|---:|---|---:|---:|---:|---:|---:|---:|'
    call umfpack_di_defaults(control)
    control(UMFPACK_PRL + 1) = 0.0_c_double
    control(UMFPACK_IRSTEP + 1) = 0.0_c_double
    do i_arg = 1, command_argument_count()
        call get_command_argument(i_arg, argument)
        colon = index(argument, ':')
        read (argument(:colon - 1), *) n_cells
        call scene(n_cells, argument(colon + 1:), stat)
        if (.not. stat%ok()) then
            write (error_unit, '(a)') trim(argument)//': '//stat%message
            error stop 1
        end if
        ! ax = K - sigma B in K's pattern (B's lies inside it, as in lu_factor_shifted)
        ax = shifted_values(k, b)
        allocate (rhs(k%n()), source=1.0_c_double)
        allocate (x_int(k%n()), x_long(k%n()))
        do width = 32, 64, 32
            do r = 1, REPEATS
                if (width == 32) then
                    ap32 = int(k%row_start - 1, c_int)
                    ai32 = int(k%col - 1, c_int)
                    call factor_and_solve_di(t_factor(r), t_solve(r), x_int)
                else
                    ap64 = int(k%row_start, c_int64_t) - 1_c_int64_t
                    ai64 = int(k%col, c_int64_t) - 1_c_int64_t
                    call factor_and_solve_dl(t_factor(r), t_solve(r), x_long)
                end if
            end do
            peak = info_factor(PEAK_MEMORY + 1)*info_factor(SIZE_OF_UNIT + 1)/1.0e6_wp
            numeric_bytes = info_factor(NUMERIC_SIZE + 1)*info_factor(SIZE_OF_UNIT + 1)/1.0e6_wp
            write (output_unit, '(a, i0, a, a, a, i0, a, i0, a, a, a, f8.3, a, f7.4, a, ' // &
                   'f9.1, a, f9.1, a, f7.1, a, es9.2, a)') &
                '| ', n_cells, ' x ', trim(argument(colon + 1:)), ' | ', k%n(), ' | ', &
                size(k%col), ' | ', merge('di', 'dl', width == 32), ' | ', median(t_factor), &
                ' | ', median(t_solve), ' | ', peak, ' | ', numeric_bytes, ' | ', &
                real(width/8, wp)*real(size(k%col) + k%n() + 1, wp)/1.0e6_wp, ' | ', &
                merge(0.0_wp, maxval(abs(x_long - x_int))/maxval(abs(x_int)), width == 32), ' |'
        end do
        deallocate (rhs, x_int, x_long)
    end do

contains

    !> The reference scene at n x n cells of `element_name`: K on the free dofs and B.
    subroutine scene(n, element_name, stat)
        integer, intent(in) :: n
        character(len=*), intent(in) :: element_name
        type(status_t), intent(out) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, n, n, element_from_name(element_name), &
                                  'right', m, stat)
        if (.not. stat%ok()) return
        call build_dof_map(m, [m%part_index('top')], dofs, stat)
        if (.not. stat%ok()) return
        call build_contact(m, m%part_index('bottom'), dofs, contact, stat)
        if (.not. stat%ok()) return
        call assemble_stiffness(m, dofs, 1.0_wp, 0.3_wp, k, stat)
        if (.not. stat%ok()) return
        call assemble_b(contact, dofs%n_free, LAMBDA, b, stat)
    end subroutine scene

    !> The values of a - SIGMA b in the pattern of a.
    function shifted_values(a, b) result(values)
        type(csr_matrix_t), intent(in) :: a, b
        real(c_double), allocatable :: values(:)
        integer :: i, j
        values = a%val
        do i = 1, b%n()
            do j = b%row_start(i), b%row_start(i + 1) - 1
                associate (slot => a%slot(i, b%col(j)))
                    values(slot) = values(slot) - SIGMA*b%val(j)
                end associate
            end do
        end do
    end function shifted_values

    subroutine factor_and_solve_di(t_factor, t_solve, x)
        real(wp), intent(out) :: t_factor, t_solve
        real(c_double), intent(out) :: x(:)
        type(c_ptr) :: symbolic, numeric
        integer(c_int) :: code, n
        n = int(size(ap32) - 1, c_int)
        symbolic = c_null_ptr
        numeric = c_null_ptr
        start = wall_time()
        code = umfpack_di_symbolic(n, n, ap32, ai32, ax, symbolic, control, info)
        if (code == 0) code = umfpack_di_numeric(ap32, ai32, ax, symbolic, numeric, control, &
                                                 info)
        t_factor = wall_time() - start
        info_factor = info   ! the solve overwrites Info's memory statistics
        call umfpack_di_free_symbolic(symbolic)
        if (code /= 0) call fail(int(code))
        start = wall_time()
        code = umfpack_di_solve(UMFPACK_At, ap32, ai32, ax, x, rhs, numeric, control, info)
        t_solve = wall_time() - start
        if (code /= 0) call fail(int(code))
        call umfpack_di_free_numeric(numeric)
    end subroutine factor_and_solve_di

    subroutine factor_and_solve_dl(t_factor, t_solve, x)
        real(wp), intent(out) :: t_factor, t_solve
        real(c_double), intent(out) :: x(:)
        type(c_ptr) :: symbolic, numeric
        integer(c_int64_t) :: code, n
        n = int(size(ap64) - 1, c_int64_t)
        symbolic = c_null_ptr
        numeric = c_null_ptr
        start = wall_time()
        code = umfpack_dl_symbolic(n, n, ap64, ai64, ax, symbolic, control, info)
        if (code == 0) code = umfpack_dl_numeric(ap64, ai64, ax, symbolic, numeric, control, &
                                                 info)
        t_factor = wall_time() - start
        info_factor = info   ! the solve overwrites Info's memory statistics
        call umfpack_dl_free_symbolic(symbolic)
        if (code /= 0) call fail(int(code))
        start = wall_time()
        code = umfpack_dl_solve(int(UMFPACK_At, c_int64_t), ap64, ai64, ax, x, rhs, numeric, &
                                control, info)
        t_solve = wall_time() - start
        if (code /= 0) call fail(int(code))
        call umfpack_dl_free_numeric(numeric)
    end subroutine factor_and_solve_dl

    subroutine fail(code)
        integer, intent(in) :: code
        write (error_unit, '(a, i0)') 'bench_index_width: UMFPACK status ', code
        error stop 1
    end subroutine fail

    real(wp) function median(values)
        real(wp), intent(in) :: values(:)
        real(wp) :: sorted(size(values))
        sorted = values(sort_index(values))
        median = sorted((size(values) + 1)/2)
    end function median
end program bench_index_width
