! SPDX-License-Identifier: MIT
!> nceig-extrapolate RESULTS.csv | --tradeoff RESULTS.csv: the numerics of a mesh
!> refinement sweep (scripts/sweep_mesh.sh). From the table of runs (columns family, h,
!> lowest_positive_mu; optional status, element, mesh, n, n_dofs, time_total_s,
!> time_output_s, wall_s, peak_rss_mb, error_bar) it prints on standard output either the
!> Richardson extrapolation of each family (extrapolation.csv) or, with --tradeoff, every
!> run's relative error against the best extrapolated limit next to its cost (tradeoff.csv).
!> Each run's own error bar (error_bar, from its summary.json) is carried beside the
!> extrapolation's estimate: the finest run's in extrapolation.csv, every run's in
!> tradeoff.csv, so that a reader sees both and never has to trust the extrapolation alone.
program nceig_extrapolate
    use iso_fortran_env, only: output_unit
    use kinds, only: wp
    use ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
    use status, only: status_t, STATUS_BAD_INPUT
    use process_exit, only: exit_with, stop_with, stop_on_failure
    use real_format, only: real_to_text, known_text
    use strings, only: to_string
    use csv_table, only: csv_table_t, csv_field_t, read_csv_table
    use command_line, only: command_argument
    use extrapolation, only: family_estimate_t, family_estimate, reference_index, fit_note, &
                             FIT_OK, FIT_CONSTANT
    implicit none

    character(len=*), parameter :: PROGRAM_NAME = 'nceig-extrapolate'
    character(len=*), parameter :: USAGE = &
        'usage: nceig-extrapolate RESULTS.csv | nceig-extrapolate --tradeoff RESULTS.csv'
    type(csv_table_t) :: table
    type(status_t) :: stat
    type(csv_field_t), allocatable :: families(:)
    type(family_estimate_t), allocatable :: estimates(:)
    integer, allocatable :: family_of_row(:)
    character(len=:), allocatable :: path, mode
    integer :: col_family, col_h, col_mu, col_status, best, i

    call parse_arguments(mode, path)
    call read_csv_table(path, table, stat)
    call stop_on_failure(PROGRAM_NAME, stat)
    col_family = required_column('family')
    col_h = required_column('h')
    col_mu = required_column('lowest_positive_mu')
    col_status = table%column('status')

    call group_rows(families, family_of_row)
    allocate (estimates(size(families)))
    do i = 1, size(families)
        estimates(i) = family_estimate(values(col_h, i), values(col_mu, i))
    end do
    best = reference_index(estimates)

    if (mode == 'extrapolation') then
        call print_extrapolation()
    else
        if (best == 0) then
            call stop_with(PROGRAM_NAME, path//': no family has an extrapolated limit, so '// &
                           'there is no reference for the relative error', STATUS_BAD_INPUT)
        end if
        call print_tradeoff()
    end if
    call exit_with(0)

contains

    subroutine parse_arguments(mode, path)
        character(len=:), allocatable, intent(out) :: mode, path
        mode = 'extrapolation'
        select case (command_argument_count())
        case (1)
            path = command_argument(1)
            if (path == '--help' .or. path == '-h') then
                write (output_unit, '(a)') USAGE
                call exit_with(0)
            end if
        case (2)
            if (command_argument(1) /= '--tradeoff') call usage_error()
            mode = 'tradeoff'
            path = command_argument(2)
        case default
            call usage_error()
        end select
    end subroutine parse_arguments

    subroutine usage_error()
        call stop_with(PROGRAM_NAME, USAGE, STATUS_BAD_INPUT)
    end subroutine usage_error

    integer function required_column(name) result(column)
        character(len=*), intent(in) :: name
        column = table%column(name)
        if (column == 0) then
            call stop_with(PROGRAM_NAME, path//': the header has no column '''//name//'''', &
                           STATUS_BAD_INPUT)
        end if
    end function required_column

    !> Families in order of first appearance; rows of failed runs belong to none (0).
    subroutine group_rows(families, family_of_row)
        type(csv_field_t), allocatable, intent(out) :: families(:)
        integer, allocatable, intent(out) :: family_of_row(:)
        type(csv_field_t), allocatable :: grown(:)
        integer :: row, f
        character(len=:), allocatable :: name

        allocate (families(0))
        allocate (family_of_row(table%n_rows()))
        family_of_row = 0
        do row = 1, table%n_rows()
            if (col_status > 0) then
                if (table%text(row, col_status) /= 'ok') cycle
            end if
            name = table%text(row, col_family)
            do f = 1, size(families)
                if (families(f)%text == name) exit
            end do
            if (f > size(families)) then
                ! Grown by hand: gfortran 12 leaks the components of an array constructor
                ! of derived types with allocatable components.
                allocate (grown(f))
                grown(:f - 1) = families
                grown(f)%text = name
                call move_alloc(grown, families)
            end if
            family_of_row(row) = f
        end do
    end subroutine group_rows

    !> Column `column` as reals over the rows of family `f` (NaN where not a number).
    function values(column, f) result(x)
        integer, intent(in) :: column, f
        real(wp), allocatable :: x(:)
        integer :: row
        allocate (x(0))
        do row = 1, table%n_rows()
            if (family_of_row(row) == f) x = [x, table%number(row, column)]
        end do
    end function values

    !> First text of `name` in family f ('' when the column is absent).
    function family_text(name, f) result(text)
        character(len=*), intent(in) :: name
        integer, intent(in) :: f
        character(len=:), allocatable :: text
        integer :: row
        text = ''
        row = findloc(family_of_row, f, dim=1)
        if (row > 0) text = table%text(row, table%column(name))
    end function family_text

    subroutine print_extrapolation()
        type(family_estimate_t) :: e
        character(len=:), allocatable :: note
        integer :: f

        write (output_unit, '(a)') 'family,element,mesh,n_meshes,n_coarse,n_middle,n_fine,'// &
            'mu_finest,limit,order,constant,error_estimate,relative_error_estimate,'// &
            'finest_error_bar,previous_limit,previous_order,reference,note'
        do f = 1, size(families)
            e = estimates(f)
            note = fit_note(e%code)
            if (e%code == FIT_OK .or. e%code == FIT_CONSTANT) then
                if (e%from_two_fits) then
                    note = note//': error from the fit on the previous three meshes'
                else if (e%n_points == 3) then
                    note = note//': 3 meshes only; error_estimate = |mu_finest - limit|'
                else
                    note = note//': previous three meshes '//fit_note(e%previous_code)// &
                           '; error_estimate = |mu_finest - limit|'
                end if
            end if
            write (output_unit, '(a)') families(f)%text//','//family_text('element', f)//','// &
                family_text('mesh', f)//','//to_string(e%n_points)//','// &
                mesh_n(e%h_used(1))//','//mesh_n(e%h_used(2))//','//mesh_n(e%h_used(3))//','// &
                field(e%finest)//','//field(e%limit)//','//field(e%order)//','// &
                field(e%constant)//','//field(e%error_estimate)//','// &
                field(relative(e%error_estimate, e%limit))//','// &
                column_text(finest_row(f), 'error_bar')//','//field(e%previous_limit)//','// &
                field(e%previous_order)//','//trim(merge('yes', 'no ', f == best))//','//note
        end do
    end subroutine print_extrapolation

    subroutine print_tradeoff()
        real(wp) :: reference, mu, time
        integer :: row, col_total, col_output

        reference = estimates(best)%limit
        col_total = table%column('time_total_s')
        col_output = table%column('time_output_s')
        write (output_unit, '(a)') 'family,element,mesh,n,n_dofs,time_s,wall_s,peak_rss_mb,'// &
            'lowest_positive_mu,relative_error,error_bar,reference_limit,reference_family'
        do row = 1, table%n_rows()
            if (family_of_row(row) == 0) cycle
            mu = table%number(row, col_mu)
            if (.not. ieee_is_finite(mu)) cycle
            ! The cost of c_n itself: writing optional mode files (VTK) is not part of it.
            time = table%number(row, col_total)
            if (ieee_is_finite(table%number(row, col_output))) &
                time = time - table%number(row, col_output)
            write (output_unit, '(a)') families(family_of_row(row))%text//','// &
                column_text(row, 'element')//','//column_text(row, 'mesh')//','// &
                column_text(row, 'n')//','//column_text(row, 'n_dofs')//','//field(time)//','// &
                column_text(row, 'wall_s')//','//column_text(row, 'peak_rss_mb')//','// &
                field(mu)//','//field(relative(abs(mu - reference), reference))//','// &
                column_text(row, 'error_bar')//','//field(reference)//','//families(best)%text
        end do
    end subroutine print_tradeoff

    !> The row of family f with the finest mesh (smallest h) and a value; 0 when none.
    integer function finest_row(f) result(finest)
        integer, intent(in) :: f
        integer :: row
        finest = 0
        do row = 1, table%n_rows()
            if (family_of_row(row) /= f) cycle
            if (.not. ieee_is_finite(table%number(row, col_mu))) cycle
            if (finest == 0) then
                finest = row
            else if (table%number(row, col_h) < table%number(finest, col_h)) then
                finest = row
            end if
        end do
    end function finest_row

    !> Text of column `name` in `row`; '' for row 0 or an absent column.
    function column_text(row, name) result(text)
        integer, intent(in) :: row
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: text
        text = ''
        if (row > 0) text = table%text(row, table%column(name))
    end function column_text

    !> A real as the shortest exact text; empty for NaN and infinities (no value).
    function field(x) result(text)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        text = known_text(ieee_is_finite(x), x)
    end function field

    !> |error| / |value|, NaN unless both are finite and the value is not zero.
    real(wp) function relative(error, value)
        real(wp), intent(in) :: error, value
        relative = ieee_value(1.0_wp, ieee_quiet_nan)
        if (.not. (ieee_is_finite(error) .and. ieee_is_finite(value))) return
        if (abs(value) > 0.0_wp) relative = abs(error)/abs(value)
    end function relative

    !> N of a mesh of size h = 1/N; empty when there is no such mesh.
    function mesh_n(h) result(text)
        real(wp), intent(in) :: h
        character(len=:), allocatable :: text
        text = ''
        if (ieee_is_finite(h)) text = to_string(nint(1.0_wp/h))
    end function mesh_n
end program nceig_extrapolate
