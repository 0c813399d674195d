! SPDX-License-Identifier: MIT
!> lambda_sweep.csv: the curve lambda -> critical c_n, c_t of a sweep, in the input's units
!> (reported_units).
module sweep_files
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string
    use real_format, only: real_to_text, known_text
    use critical_point, only: slip_sign, critical_c_t
    use threshold_analysis, only: sweep_curve_t
    use csv_writer, only: csv_writer_t
    implicit none
    private
    public :: write_sweep_csv

    character(len=*), parameter, public :: SWEEP_FILE = 'lambda_sweep.csv'
    character(len=*), parameter :: SWEEP_HEADER = &
        'lambda,critical_c_n,critical_c_t,slip_sign,n_positive,error_estimate,n_dofs,error_bar'

contains

    !> lambda,critical_c_n,critical_c_t,slip_sign,n_positive,error_estimate,n_dofs: one row
    !> per lambda in input order (of a partial set, per complete point); c_n and c_t are
    !> empty where no positive real mu exists, error_estimate where none was computed
    !> (always without &adapt).
    subroutine write_sweep_csv(path, curve, stat)
        character(len=*), intent(in) :: path
        type(sweep_curve_t), intent(in) :: curve
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        character(len=:), allocatable :: values
        integer :: i

        call csv%open(path, SWEEP_HEADER)
        do i = 1, size(curve%lambda)
            if (allocated(curve%complete)) then
                if (.not. curve%complete(i)) cycle   ! a partial set: its complete points
            end if
            values = ','
            if (curve%found(i)) values = real_to_text(curve%mu(i))//','// &
                real_to_text(critical_c_t(curve%mu(i), curve%lambda(i)))
            call csv%row(real_to_text(curve%lambda(i))//','//values//','// &
                to_string(slip_sign(curve%lambda(i)))//','//to_string(curve%n_positive(i))// &
                ','//known_text(curve%error_estimate(i) >= 0.0_wp, curve%error_estimate(i))// &
                ','//to_string(curve%n_dofs(i))//','// &
                known_text(curve%error_bar(i) >= 0.0_wp, curve%error_bar(i)))
        end do
        call csv%close(stat)
    end subroutine write_sweep_csv
end module sweep_files
