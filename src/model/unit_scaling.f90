! SPDX-License-Identifier: MIT
!> The units of the eigen analyses' arithmetic: E and the mesh size are divided by powers of
!> two that bring them into [1, 2). mu scales exactly like E / size (2D: K does not change
!> with the size, M grows with it) and a change of unit by a power of two is exact, so the
!> scaled problem is the input problem itself while the products of the assembly and of
!> the solvers stay far from overflow and underflow. Scaled and input values meet only
!> here: every conversion between them is a call on units_t. 'branch' and 'solve' work in
!> the input's units (both exponents 0: every conversion is the identity).
module unit_scaling
    use kinds, only: wp
    use csr_matrix, only: csr_matrix_t
    implicit none
    private
    public :: units_of

    type, public :: units_t
        integer :: young_exponent = 0    !! scaled E = E / 2^young_exponent
        integer :: length_exponent = 0   !! scaled length = length / 2^length_exponent
    contains
        procedure :: mu_exponent => units_mu_exponent
        procedure :: scaled_young => units_scaled_young
        procedure :: scaled_lengths => units_scaled_lengths
        procedure :: mu_to_input => units_mu_to_input
        procedure :: mu_to_scaled => units_mu_to_scaled
        procedure :: input_exponent => units_input_exponent
        procedure :: input_log10 => units_input_log10
        procedure :: young_dominates => units_young_dominates
        procedure :: lambda_dominates => units_lambda_dominates
        procedure :: stiffness_to_input => units_stiffness_to_input
        procedure :: mass_to_input => units_mass_to_input
    end type units_t

contains

    !> The units of a problem with Young's modulus `young` on a mesh with coordinates
    !> `coords` (input units).
    pure function units_of(young, coords) result(u)
        real(wp), intent(in) :: young, coords(:, :)
        type(units_t) :: u
        u%young_exponent = unit_exponent(young)
        u%length_exponent = unit_exponent(maxval(abs(coords)))
    end function units_of

    !> e such that x / 2^e is in [1, 2) (x > 0; a subnormal x too): the unit of x.
    elemental integer function unit_exponent(x)
        real(wp), intent(in) :: x
        unit_exponent = 0
        if (x > 0.0_wp) unit_exponent = exponent(x) - 1
    end function unit_exponent

    !> mu of the input problem = 2^mu_exponent x mu of the scaled one.
    pure integer function units_mu_exponent(this)
        class(units_t), intent(in) :: this
        units_mu_exponent = this%young_exponent - this%length_exponent
    end function units_mu_exponent

    pure real(wp) function units_scaled_young(this, young)
        class(units_t), intent(in) :: this
        real(wp), intent(in) :: young
        units_scaled_young = scale(young, -this%young_exponent)
    end function units_scaled_young

    !> Input coordinates (or any lengths) in the scaled unit; a length too far below the
    !> largest underflows (the caller checks).
    pure function units_scaled_lengths(this, lengths) result(scaled)
        class(units_t), intent(in) :: this
        real(wp), intent(in) :: lengths(:, :)
        real(wp) :: scaled(size(lengths, 1), size(lengths, 2))
        scaled = scale(lengths, -this%length_exponent)
    end function units_scaled_lengths

    !> A scaled eigenvalue (or a bound on them) in input units, exactly (the caller keeps it
    !> in range: input_exponent).
    elemental real(wp) function units_mu_to_input(this, mu)
        class(units_t), intent(in) :: this
        real(wp), intent(in) :: mu
        units_mu_to_input = scale(mu, this%mu_exponent())
    end function units_mu_to_input

    !> An input-unit eigenvalue (a target, cn_max, a computed mu) in scaled units, exactly;
    !> clamped to +-huge where that overflows, which is far outside any accepted input.
    elemental real(wp) function units_mu_to_scaled(this, mu)
        class(units_t), intent(in) :: this
        real(wp), intent(in) :: mu
        integer :: e
        e = -this%mu_exponent()
        units_mu_to_scaled = mu
        if (.not. abs(mu) > 0.0_wp) return
        if (exponent(mu) + e > maxexponent(mu)) then
            units_mu_to_scaled = sign(huge(mu), mu)
        else
            units_mu_to_scaled = scale(mu, e)
        end if
    end function units_mu_to_scaled

    !> The binary exponent a scaled |mu| > 0 would have in input units (may leave the range).
    elemental integer function units_input_exponent(this, mu)
        class(units_t), intent(in) :: this
        real(wp), intent(in) :: mu
        units_input_exponent = exponent(mu) + this%mu_exponent()
    end function units_input_exponent

    !> log10 of a scaled |mu| > 0 in input units, for values beyond the binary64 range.
    elemental real(wp) function units_input_log10(this, mu)
        class(units_t), intent(in) :: this
        real(wp), intent(in) :: mu
        units_input_log10 = log10(abs(mu)) + real(this%mu_exponent(), wp)*log10(2.0_wp)
    end function units_input_log10

    !> Whether E moved the unit of mu at least as far as the size did.
    pure logical function units_young_dominates(this)
        class(units_t), intent(in) :: this
        units_young_dominates = abs(this%young_exponent) >= abs(this%length_exponent)
    end function units_young_dominates

    !> Whether |lambda| > 1 pushes a small mu further than E and the size do (mu ~ 1 /
    !> lambda for large |lambda|).
    pure logical function units_lambda_dominates(this, lambda)
        class(units_t), intent(in) :: this
        real(wp), intent(in) :: lambda
        units_lambda_dominates = abs(lambda) > 1.0_wp .and. &
            exponent(lambda) > max(-this%young_exponent, this%length_exponent)
    end function units_lambda_dominates

    !> The scaled K in input units (beyond the binary64 range Infinity).
    function units_stiffness_to_input(this, k) result(physical)
        class(units_t), intent(in) :: this
        type(csr_matrix_t), intent(in) :: k
        type(csr_matrix_t) :: physical
        physical = scaled_matrix(k, this%young_exponent)
    end function units_stiffness_to_input

    !> A scaled contact mass (or B, made of it) in input units.
    function units_mass_to_input(this, b) result(physical)
        class(units_t), intent(in) :: this
        type(csr_matrix_t), intent(in) :: b
        type(csr_matrix_t) :: physical
        physical = scaled_matrix(b, this%length_exponent)
    end function units_mass_to_input

    !> a 2^e, exactly (but for overflow and underflow).
    function scaled_matrix(a, e) result(scaled)
        type(csr_matrix_t), intent(in) :: a
        integer, intent(in) :: e
        type(csr_matrix_t) :: scaled
        scaled = a
        scaled%val = scale(scaled%val, e)
    end function scaled_matrix
end module unit_scaling
