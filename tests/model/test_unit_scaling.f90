! SPDX-License-Identifier: MIT
!> unit_scaling: the units bring E and the mesh size into [1, 2) by powers of two, so that
!> every conversion is exact and mu scales like E / size; a target beyond the range of the
!> scaled units is clamped, never Infinity; the default units are the input's.
program test_unit_scaling
    use kinds, only: wp
    use unit_scaling, only: units_t, units_of
    use csr_matrix, only: csr_matrix_t
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t

    t%name = 'test_unit_scaling'
    call check_unit_range()
    call check_round_trip()
    call check_mu_scaling_law()
    call check_clamped()
    call check_identity()
    call check_matrices()
    call t%report()

contains

    !> Steel-like E = 2.1e11 on a 3 mm body: both in [1, 2) once scaled.
    subroutine check_unit_range()
        type(units_t) :: u
        real(wp) :: coords(2, 3), scaled(2, 3)
        coords = reshape([0.0_wp, 0.0_wp, 3.0e-3_wp, 0.0_wp, 0.0_wp, -2.0e-3_wp], [2, 3])
        u = units_of(2.1e11_wp, coords)
        call t%check('scaled E in [1, 2)', u%scaled_young(2.1e11_wp) >= 1.0_wp .and. &
                     u%scaled_young(2.1e11_wp) < 2.0_wp)
        scaled = u%scaled_lengths(coords)
        call t%check('largest scaled |coordinate| in [1, 2)', maxval(abs(scaled)) >= 1.0_wp &
                     .and. maxval(abs(scaled)) < 2.0_wp)
        call t%check('lengths keep their ratios exactly', same(scaled(2, 3)/scaled(1, 2), &
                     coords(2, 3)/coords(1, 2)))
    end subroutine check_unit_range

    !> Powers of two: input -> scaled -> input gives the same bits.
    subroutine check_round_trip()
        type(units_t) :: u
        real(wp), parameter :: values(4) = [0.7516698639178927_wp, 1.0e-3_wp, 3.0e5_wp, &
                                            -2.5_wp]
        u = units_of(7.0e9_wp, reshape([1.0e-2_wp, 0.0_wp], [2, 1]))
        call t%check('mu to scaled and back is exact', &
                     all(same(u%mu_to_input(u%mu_to_scaled(values)), values)))
    end subroutine check_round_trip

    !> mu scales like E / size: a scaled eigenvalue of 1 is 2^(e_E - e_L) in input units.
    subroutine check_mu_scaling_law()
        type(units_t) :: u
        u = units_of(1024.0_wp, reshape([0.25_wp, 0.0_wp], [2, 1]))
        call t%check('E = 2^10, size 2^-2: mu exponent 12', u%mu_exponent() == 12)
        call t%check('a scaled mu of 1 is 4096 in input units', same(u%mu_to_input(1.0_wp), &
                     4096.0_wp))
        ! Fortran's exponent: 1.5 = 0.75 x 2^1
        call t%check('input exponent of a scaled 1.5: 1 + 12', u%input_exponent(1.5_wp) == 13)
        call t%check_close('log10 in input units', u%input_log10(1.0_wp), &
                           12.0_wp*log10(2.0_wp), 1.0e-14_wp)
    end subroutine check_mu_scaling_law

    !> E = 1e-300 on a body of 1e300: mu ~ 1e-600 moves the unit of mu by about 2^-1993, and
    !> an input target of 1e300 is clamped to huge in the scaled units.
    subroutine check_clamped()
        type(units_t) :: u
        u = units_of(1.0e-300_wp, reshape([1.0e300_wp, 0.0_wp], [2, 1]))
        call t%check('beyond the range: clamped to +huge', same(u%mu_to_scaled(1.0e300_wp), &
                     huge(1.0_wp)))
        call t%check('beyond the range: clamped to -huge', same(u%mu_to_scaled(-1.0e300_wp), &
                     -huge(1.0_wp)))
        call t%check('zero stays zero', same(u%mu_to_scaled(0.0_wp), 0.0_wp))
        call t%check('E pushed further than the size', u%young_dominates())
    end subroutine check_clamped

    !> 'branch' and 'solve' keep the default units: every conversion is the identity.
    subroutine check_identity()
        type(units_t) :: u
        real(wp) :: coords(2, 1)
        coords = reshape([3.0_wp, -7.0_wp], [2, 1])
        call t%check('default: mu unchanged', same(u%mu_to_input(0.3_wp), 0.3_wp) .and. &
                     same(u%mu_to_scaled(0.3_wp), 0.3_wp))
        call t%check('default: E and lengths unchanged', same(u%scaled_young(5.0_wp), 5.0_wp) &
                     .and. all(same(u%scaled_lengths(coords), coords)))
    end subroutine check_identity

    !> K scales like E, the contact mass (and B) like the size.
    subroutine check_matrices()
        type(units_t) :: u
        type(csr_matrix_t) :: k, physical
        u%young_exponent = 30
        u%length_exponent = -9
        allocate (k%val(2))
        k%val = [1.5_wp, -0.75_wp]
        physical = u%stiffness_to_input(k)
        call t%check('K times 2^young_exponent', all(same(physical%val, k%val*2.0_wp**30)))
        physical = u%mass_to_input(k)
        call t%check('B times 2^length_exponent', all(same(physical%val, k%val*2.0_wp**(-9))))
        call t%check('lambda beyond E and size dominates', u%lambda_dominates(1.0e20_wp) .and. &
                     .not. u%lambda_dominates(0.5_wp))
    end subroutine check_matrices

    !> The same value to the bit (conversions by powers of two are exact).
    elemental logical function same(a, b)
        real(wp), intent(in) :: a, b
        same = abs(a - b) <= 0.0_wp
    end function same
end program test_unit_scaling
