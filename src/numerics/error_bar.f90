! SPDX-License-Identifier: MIT
!> The error bar quoted beside a critical value (c_n, lambda+, lambda-): a relative bound
!> meant to hold, at least the true error against the continuum value and at most about ten
!> times it, where the error estimate beside it is only asymptotically exact.
!>
!> One mesh: BAR_FACTOR times the estimate (the difference to the solution one degree higher
!> on the same cells, or on the halved mesh where there is no degree higher). On uniform
!> meshes of the reference scene the estimate is 0.25 to 1 times the true error (P2 at
!> 4 x 4 the lowest: the corner singularities, which the enriched space does not resolve
!> either); 5 puts the bar between 1.2 and 5 times it (docs/accuracy.md).
!> Adaptive levels: the estimate dips by cancellation (errors of opposite signs at the two
!> ends of the contact segment) while the true error does not. The bar at level k is
!> LEVEL_FACTOR times the largest of the last BAR_WINDOW levels' estimates, each carried to
!> level k at the optimal rate (error ~ dofs^-p for degree p), so that a single dip cannot
!> make it small, and at least the change of the value over those levels (a value that
!> still moves by more than the bar claims is not converged: a mode that moves with the
!> mesh gets a large bar). Measured along adaptive P2 and P3 runs of the reference scene,
!> LEVEL_FACTOR = 3 gives bar / true error 1.5 to 4.2 (median) where the true error does
!> not itself cross zero.
!> The floating-point part is added where known (roundoff >= 0).
module error_bar
    use kinds, only: wp
    implicit none
    private
    public :: single_bar, level_bar
    public :: BAR_FACTOR, LEVEL_FACTOR, BAR_WINDOW

    real(wp), parameter :: BAR_FACTOR = 5.0_wp
    real(wp), parameter :: LEVEL_FACTOR = 3.0_wp
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
    !> `estimates` (negative: none at that level) of the values `values` on `dofs` free dofs,
    !> for elements of degree `degree`: LEVEL_FACTOR max_j estimates(j) (dofs(j) / dofs(k))^degree
    !> and at least max_j |values(k) - values(j)| / |values(k)|, over the last BAR_WINDOW
    !> levels j <= k with an estimate, plus `roundoff`. Negative when the last level has no
    !> estimate.
    pure real(wp) function level_bar(estimates, values, dofs, degree, roundoff) result(bar)
        real(wp), intent(in) :: estimates(:), values(:)
        integer, intent(in) :: dofs(:), degree
        real(wp), intent(in) :: roundoff
        real(wp) :: envelope, moved
        integer :: k, j
        bar = -1.0_wp
        k = size(estimates)
        if (k == 0) return
        if (estimates(k) < 0.0_wp) return
        envelope = estimates(k)
        moved = 0.0_wp
        do j = max(1, k - BAR_WINDOW + 1), k - 1
            if (estimates(j) < 0.0_wp) cycle
            envelope = max(envelope, estimates(j)* &
                           (real(dofs(j), wp)/real(dofs(k), wp))**degree)
            moved = max(moved, abs(values(k) - values(j))/abs(values(k)))
        end do
        bar = max(LEVEL_FACTOR*envelope, moved) + max(roundoff, 0.0_wp)
    end function level_bar
end module error_bar
