! SPDX-License-Identifier: MIT
!> Error bars of the boundary points of {lambda : a positive mu exists} (critical_set).
!> A 'pencil' point is a real eigenvalue of the pencil: where it is lambda+ or lambda-, it
!> takes their bar (threshold_estimate). A 'complex_pair' point, where two positive mu meet,
!> has no weighted residual (at a double eigenvalue it has no meaning), so its estimate is
!> the difference to the same point of the problem one degree higher on the same cells
!> (enrichment: a space that holds this one, as for mu), found by the same search in a
!> window around it; the bar is BAR_FACTOR times that difference plus the point's round-off
!> part (error_bar; roundoff: collision_roundoff).
module boundary_estimate
    use kinds, only: wp
    use status, only: status_t
    use problem, only: problem_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: reduced_blocks_t
    use critical_lambda, only: thresholds_t, pencil_thresholds, SIDE_PLUS, SIDE_MINUS
    use critical_set, only: critical_set_t, find_critical_set, MECHANISM_PENCIL, &
                            MECHANISM_COMPLEX_PAIR
    use enrichment, only: enrichment_t, build_enrichment
    use threshold_estimate, only: threshold_estimate_t
    use error_bar, only: single_bar
    implicit none
    private
    public :: estimate_boundary_bars, enriched_pair_lambdas

    !> The window searched around a complex_pair point on the enriched problem, relative to
    !> |lambda|, and its scan points: wider than the difference between two degrees on any
    !> mesh the analysis accepts (measured: 0.3 % on the half-contact example's h = 1/16).
    real(wp), parameter :: WINDOW = 0.05_wp
    integer, parameter :: WINDOW_POINTS = 41

contains

    !> set%points(:)%error_bar for the points of `set`, the boundary of the positive set of
    !> `prob` whose thresholds are `thr` with bars `est`. Points it cannot estimate keep -1
    !> (stat ok); `max_contact` bounds the enriched contact nodes (dense reduction).
    subroutine estimate_boundary_bars(prob, thr, est, max_contact, set, stat)
        type(problem_t), intent(in) :: prob
        type(thresholds_t), intent(in) :: thr
        type(threshold_estimate_t), intent(in) :: est
        integer, intent(in) :: max_contact
        type(critical_set_t), intent(inout) :: set
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: nearest(:)
        integer :: i, side

        do i = 1, size(set%points)
            if (set%points(i)%mechanism /= MECHANISM_PENCIL) cycle
            do side = SIDE_PLUS, SIDE_MINUS
                ! the same pencil eigenvalue (copied, so equal up to its last bit)
                if (thr%found(side) .and. est%computed(side) .and. &
                    abs(set%points(i)%lambda - thr%lambda(side)) <= &
                    4.0_wp*epsilon(1.0_wp)*abs(thr%lambda(side))) then
                    set%points(i)%error_bar = est%bar(side)
                    set%points(i)%roundoff = thr%roundoff(side)
                end if
            end do
        end do
        call enriched_pair_lambdas(prob, max_contact, set, nearest, stat)
        if (.not. stat%ok()) return
        do i = 1, size(set%points)
            if (nearest(i) < huge(1.0_wp)) set%points(i)%error_bar = single_bar( &
                abs(nearest(i) - set%points(i)%lambda)/abs(set%points(i)%lambda), &
                set%points(i)%roundoff)
        end do
    end subroutine estimate_boundary_bars

    !> nearest(i): the complex_pair point of the same direction of the problem one degree
    !> higher on the cells of `prob` nearest the complex_pair point i of `set`, found by the
    !> same search in a window around it; huge where there is none (or no enrichment, or
    !> more than `max_contact` enriched contact nodes; stat ok).
    subroutine enriched_pair_lambdas(prob, max_contact, set, nearest, stat)
        type(problem_t), intent(in) :: prob
        integer, intent(in) :: max_contact
        type(critical_set_t), intent(in) :: set
        real(wp), allocatable, intent(out) :: nearest(:)
        type(status_t), intent(out) :: stat
        type(enrichment_t) :: enr
        type(cholesky_t) :: chol
        type(reduced_blocks_t) :: blocks
        type(thresholds_t) :: thr_plus
        type(critical_set_t) :: near
        character(len=:), allocatable :: skipped
        real(wp) :: lambda, scan(WINDOW_POINTS)
        integer :: i, j

        allocate (nearest(size(set%points)), source=huge(1.0_wp))
        if (.not. any(set%points%mechanism == MECHANISM_COMPLEX_PAIR)) return
        call build_enrichment(prob, max_contact, enr, skipped, stat)
        if (.not. stat%ok() .or. enr%element == 0 .or. len(skipped) > 0) return
        call enr%reduce(chol, blocks%kt_nn, blocks%kt_nt, stat)
        call chol%free()
        if (stat%ok()) call pencil_thresholds(blocks%kt_nn, blocks%kt_nt, thr_plus, stat)
        if (.not. stat%ok()) return
        blocks%mass = enr%contact%mass
        do i = 1, size(set%points)
            if (set%points(i)%mechanism /= MECHANISM_COMPLEX_PAIR) cycle
            lambda = set%points(i)%lambda
            scan = [(lambda + abs(lambda)*WINDOW*(real(2*j - WINDOW_POINTS - 1, wp)/ &
                     real(WINDOW_POINTS - 1, wp)), j=1, WINDOW_POINTS)]
            call find_critical_set(blocks, scan, thr_plus%real_lambdas, near, stat)
            if (.not. stat%ok()) return
            do j = 1, size(near%points)
                if (near%points(j)%mechanism /= MECHANISM_COMPLEX_PAIR .or. &
                    (near%points(j)%appears .neqv. set%points(i)%appears)) cycle
                if (abs(near%points(j)%lambda - lambda) < abs(nearest(i) - lambda)) &
                    nearest(i) = near%points(j)%lambda
            end do
        end do
    end subroutine enriched_pair_lambdas
end module boundary_estimate
