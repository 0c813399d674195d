! SPDX-License-Identifier: MIT
!> The error bar quoted beside a critical value (c_n, lambda+, lambda-): a relative bound
!> meant to hold, at least the true error against the continuum value and at most about ten
!> times it, where the error estimate beside it is only asymptotically exact.
!>
!> The discretisation part is BAR_FACTOR times the estimate (the difference to the solution
!> one degree higher on the same cells, or on the halved mesh where there is no degree
!> higher). On uniform meshes the estimate is 0.3 to 1 times the true error (P2 0.31 on the
!> reference scene, the corner singularities that the enriched space does not resolve
!> either); BAR_FACTOR = 4 puts the bar between 1.2 and 4 times it there. Along an adaptive
!> run the estimate dips by cancellation (errors of opposite signs at the two ends of the
!> contact segment) while the true error does not: the bar at level k takes the largest of
!> the last BAR_WINDOW levels' estimates, each carried to level k at the optimal rate
!> (error ~ dofs^-p for degree p), so that a single dip cannot make the bar small, and a run
!> stops only where the envelope of its estimates meets the tolerance.
!> The floating-point part (the eigenvalue's condition times its backward error and the
!> assembly's rounding) is added where known.
module error_bar
    use kinds, only: wp
    implicit none
    private
    public :: single_bar, level_bar
    public :: BAR_FACTOR, BAR_WINDOW

    real(wp), parameter :: BAR_FACTOR = 4.0_wp
    integer, parameter :: BAR_WINDOW = 3

contains

    !> The bar of one discretisation: BAR_FACTOR |estimate| plus `roundoff` (relative; a
    !> negative value: unknown, nothing added). Negative when `estimate` is (none).
    elemental real(wp) function single_bar(estimate, roundoff) result(bar)
        real(wp), intent(in) :: estimate, roundoff
        bar = -1.0_wp
        if (estimate < 0.0_wp) return
        bar = BAR_FACTOR*estimate + max(roundoff, 0.0_wp)
    end function single_bar

    !> The bar at the last of successive adaptive levels with |relative estimates|
    !> `estimates` (negative: none at that level) on `dofs` free dofs, for elements of
    !> degree `degree`: BAR_FACTOR max_j estimates(j) (dofs(j) / dofs(k))^degree over the
    !> last BAR_WINDOW levels j <= k with an estimate, plus `roundoff`. Negative when the
    !> last level has no estimate.
    pure real(wp) function level_bar(estimates, dofs, degree, roundoff) result(bar)
        real(wp), intent(in) :: estimates(:)
        integer, intent(in) :: dofs(:), degree
        real(wp), intent(in) :: roundoff
        real(wp) :: envelope
        integer :: k, j
        bar = -1.0_wp
        k = size(estimates)
        if (k == 0) return
        if (estimates(k) < 0.0_wp) return
        envelope = estimates(k)
        do j = max(1, k - BAR_WINDOW + 1), k - 1
            if (estimates(j) < 0.0_wp) cycle
            envelope = max(envelope, estimates(j)* &
                           (real(dofs(j), wp)/real(dofs(k), wp))**degree)
        end do
        bar = single_bar(envelope, roundoff)
    end function level_bar
end module error_bar
