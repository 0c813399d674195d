! SPDX-License-Identifier: MIT
!> The report boundary of the units: every result leaves the numerics in the units of its
!> problem (problem_t%units: E and the mesh size scaled to [1, 2) for the eigen analyses; the
!> input's for 'branch' and 'solve' and on hp levels), and every value of mu the report shows
!> or writes is converted here, once, to the input's units: exactly (powers of two; the
!> numerics checked that each fits the normal binary64 range: eigen_solve,
!> check_input_range). Lambda has no unit.
module reported_units
    use kinds, only: wp
    use unit_scaling, only: units_t
    use spectrum, only: spectrum_t, KIND_POSITIVE
    implicit none
    private
    public :: to_input_units, critical_cn

    interface to_input_units
        module procedure complex_to_input_units, real_to_input_units
    end interface to_input_units

contains

    !> The critical c_n a run reports: every positive real mu of `spec` (input units) in
    !> (0, cn_max], ascending; with cn_max = 0 the lowest alone. Complete as certified by the
    !> solver (both solvers hold every positive real mu up to cn_max in their spectrum).
    pure function critical_cn(spec, cn_max) result(values)
        type(spectrum_t), intent(in) :: spec
        real(wp), intent(in) :: cn_max
        real(wp), allocatable :: values(:)
        integer :: lowest
        allocate (values(0))
        lowest = spec%lowest_positive()
        if (lowest == 0) return
        ! output order: positive real ascending first
        if (.not. cn_max > 0.0_wp) then
            values = [real(spec%mu(lowest), wp)]
        else
            values = pack(real(spec%mu, wp), spec%kind == KIND_POSITIVE .and. &
                          real(spec%mu, wp) <= cn_max)
        end if
    end function critical_cn

    !> Eigenvalues `mu` in `units` to the input's, in place (a copy the report owns).
    pure subroutine complex_to_input_units(units, mu)
        type(units_t), intent(in) :: units
        complex(wp), intent(inout) :: mu(:)
        integer :: i
        do i = 1, size(mu)
            mu(i) = cmplx(units%mu_to_input(real(mu(i), wp)), units%mu_to_input(aimag(mu(i))), wp)
        end do
    end subroutine complex_to_input_units

    !> Real `mu` in `units` to the input's, in place (a copy the report owns).
    pure subroutine real_to_input_units(units, mu)
        type(units_t), intent(in) :: units
        real(wp), intent(inout) :: mu(:)
        mu = units%mu_to_input(mu)
    end subroutine real_to_input_units
end module reported_units
