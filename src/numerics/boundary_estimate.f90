! SPDX-License-Identifier: MIT
!> Error bars of the boundary points of {lambda : a positive mu exists} (critical_set).
!> A 'pencil' point is a real eigenvalue of the pencil: where it is lambda+ or lambda-, it
!> takes their bar (threshold_estimate). A 'complex_pair' point, where two positive mu meet,
!> has no weighted residual (at a double eigenvalue it has no meaning). On one mesh its bar
!> is the larger of two, each from the same point found by the same search in a window
!> around it: BAR_FACTOR times the difference to the problem one degree higher on the same
!> cells (enrichment), and the three-mesh bar of the meshes of halved and twice halved cells
!> (halved_mesh; error_bar: three_mesh_bar). The enriched difference alone cancels on coarse
!> meshes and the halved one misses a slow order: on Delaunay trapezoids (P2 h = 1/8, P3 h =
!> 1/16) both were a tenth of the true error. Plus the point's round-off part (roundoff:
!> collision_roundoff). An adaptive loop uses the enriched difference at each level and its
!> window of levels (threshold_goal).
module boundary_estimate
    use kinds, only: wp
    use status, only: status_t
    use problem, only: problem_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: reduced_blocks_t
    use critical_lambda, only: thresholds_t, pencil_thresholds, SIDE_PLUS, SIDE_MINUS
    use critical_set, only: critical_set_t, find_critical_set, onset_point, MECHANISM_PENCIL, &
                            MECHANISM_COMPLEX_PAIR
    use enrichment, only: enrichment_t, build_enrichment
    use scene, only: scene_t
    use halved_mesh, only: build_halved_problem
    use timer, only: timings_t
    use contact_reduction, only: factor_contact_blocks
    use threshold_estimate, only: threshold_estimate_t
    use error_bar, only: single_bar, three_mesh_bar
    use h_refiner, only: adaptive_dof_limit
    use system_memory, only: available_memory_bytes
    implicit none
    private
    public :: estimate_boundary_bars, enriched_pair_lambdas

    !> The bars of the sides' collision onsets known already (an adaptive loop's last level),
    !> by SIDE_PLUS, SIDE_MINUS: they stand for the one-mesh bars of the same points.
    type, public :: onset_bars_t
        logical :: collision(2) = .false.     !! the side's onset is a collision
        real(wp) :: lambda(2) = 0.0_wp        !! where
        real(wp) :: bar(2) = -1.0_wp          !! its bar; < 0: none
        !> the side did not meet its tolerance in the loop: its onset gets no bar, wherever
        !> the report's search puts it (a one-mesh bar would quote what the loop refused)
        logical :: withheld(2) = .false.
    contains
        procedure :: apply => onset_bars_apply
    end type onset_bars_t

    !> The window searched around a complex_pair point on the enriched problem, relative to
    !> |lambda|, and its scan points: wider than the difference between two degrees on any
    !> mesh the analysis accepts (measured: 0.3 % on the half-contact example's h = 1/16).
    real(wp), parameter :: WINDOW = 0.05_wp
    integer, parameter :: WINDOW_POINTS = 41
    !> The twice halved mesh of a collision's three-mesh bar has 16 times the dofs and 4
    !> times the contact nodes of the mesh; beyond this many free dofs it is left out (its
    !> dense search alone took minutes for a P3 mesh of 23 000 dofs) and the bar counts
    !> a slow order instead (error_bar: three_mesh_bar, Q_UNKNOWN).
    integer, parameter :: QUARTER_MAX_DOFS = 160000

contains

    !> set%points(:)%error_bar for the points of `set`, the boundary of the positive set of
    !> `prob` (of the scene `scn`) whose thresholds are `thr` with bars `est`. Points it
    !> cannot estimate keep -1
    !> (stat ok); `max_contact` bounds the enriched contact nodes (dense reduction). The
    !> collision onsets of `onsets` take its bars, and nothing is computed for them.
    subroutine estimate_boundary_bars(scn, prob, thr, est, max_contact, set, stat, onsets)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(thresholds_t), intent(in) :: thr
        type(threshold_estimate_t), intent(in) :: est
        integer, intent(in) :: max_contact
        type(critical_set_t), intent(inout) :: set
        type(status_t), intent(out) :: stat
        type(onset_bars_t), intent(in), optional :: onsets
        real(wp), allocatable :: nearest(:), halved(:), quartered(:)
        logical :: known(size(set%points)), pair(size(set%points))
        type(status_t) :: halved_stat
        real(wp) :: lambda, bar
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
        known = .false.
        if (present(onsets)) call onsets%apply(set, known)
        pair = set%points%mechanism == MECHANISM_COMPLEX_PAIR .and. .not. known
        call enriched_pair_lambdas(prob, max_contact, set, nearest, stat, pair)
        if (.not. stat%ok()) return
        ! the halved meshes are a second opinion: where they fail (memory), the enriched
        ! difference alone makes the bar
        call halved_pair_lambdas(scn, prob, set, pair, halved, quartered, halved_stat)
        do i = 1, size(set%points)
            if (.not. pair(i)) cycle
            lambda = set%points(i)%lambda
            bar = -1.0_wp
            if (nearest(i) < huge(1.0_wp)) bar = single_bar(abs(nearest(i) - lambda)/ &
                abs(lambda), set%points(i)%roundoff)
            if (halved(i) < huge(1.0_wp)) bar = max(bar, three_mesh_bar(lambda, halved(i), &
                quartered(i), set%points(i)%roundoff))
            set%points(i)%error_bar = bar
        end do
    end subroutine estimate_boundary_bars

    !> halved(i), quartered(i): the complex_pair point of the same direction of the problem
    !> on the mesh of halved cells (halved_mesh) and on that mesh halved again nearest the
    !> complex_pair point i of `set`, for the points with `pair`(i) (pair_points_near); huge
    !> where there is none, or no halved mesh, or (quartered) where 16 times the dofs are more
    !> than QUARTER_MAX_DOFS or would not fit the memory available (stat ok); where a fine
    !> problem fails, the points not found stay huge.
    subroutine halved_pair_lambdas(scn, prob, set, pair, halved, quartered, stat)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(critical_set_t), intent(in) :: set
        logical, intent(in) :: pair(:)
        real(wp), allocatable, intent(out) :: halved(:), quartered(:)
        type(status_t), intent(out) :: stat
        type(scene_t) :: half_scene, quarter_scene
        type(problem_t) :: half, quarter
        character(len=:), allocatable :: why_not

        allocate (halved(size(set%points)), quartered(size(set%points)), source=huge(1.0_wp))
        if (.not. any(pair)) return
        call build_halved_problem(scn, prob, half_scene, half, why_not, stat)
        if (.not. stat%ok() .or. len(why_not) > 0) return
        call points_on(half, halved, stat)
        if (.not. stat%ok()) return
        if (4*half%dofs%n_free > min(QUARTER_MAX_DOFS, &
                                     adaptive_dof_limit(available_memory_bytes()))) return
        call build_halved_problem(half_scene, half, quarter_scene, quarter, why_not, stat)
        if (.not. stat%ok() .or. len(why_not) > 0) return
        call points_on(quarter, quartered, stat)

    contains

        !> the points of `set` on the problem `fine`
        subroutine points_on(fine, nearest, stat)
            type(problem_t), intent(in) :: fine
            real(wp), intent(inout) :: nearest(:)
            type(status_t), intent(out) :: stat
            type(cholesky_t) :: chol
            type(reduced_blocks_t) :: blocks
            type(timings_t) :: quiet
            call factor_contact_blocks(fine%k, fine%mesh, fine%dofs, fine%contact, chol, &
                                       blocks%kt_nn, blocks%kt_nt, quiet, stat)
            call chol%free()
            if (.not. stat%ok()) return
            blocks%mass = fine%contact%mass
            call pair_points_near(blocks, set, pair, nearest, stat)
        end subroutine points_on
    end subroutine halved_pair_lambdas

    !> nearest(i): the complex_pair point of the same direction of the problem one degree
    !> higher on the cells of `prob` nearest the complex_pair point i of `set`, found by the
    !> same search in a window around it; huge where there is none (or no enrichment, or
    !> more than `max_contact` enriched contact nodes; stat ok), or where not `wanted`(i).
    subroutine enriched_pair_lambdas(prob, max_contact, set, nearest, stat, wanted)
        type(problem_t), intent(in) :: prob
        integer, intent(in) :: max_contact
        type(critical_set_t), intent(in) :: set
        real(wp), allocatable, intent(out) :: nearest(:)
        type(status_t), intent(out) :: stat
        logical, intent(in), optional :: wanted(:)
        logical :: pair(size(set%points))
        type(enrichment_t) :: enr
        type(cholesky_t) :: chol
        type(reduced_blocks_t) :: blocks
        character(len=:), allocatable :: skipped

        allocate (nearest(size(set%points)), source=huge(1.0_wp))
        pair = set%points%mechanism == MECHANISM_COMPLEX_PAIR
        if (present(wanted)) pair = pair .and. wanted
        if (.not. any(pair)) return
        call build_enrichment(prob, max_contact, enr, skipped, stat)
        if (.not. stat%ok() .or. enr%element == 0 .or. len(skipped) > 0) return
        call enr%reduce(chol, blocks%kt_nn, blocks%kt_nt, stat)
        call chol%free()
        if (.not. stat%ok()) return
        blocks%mass = enr%contact%mass
        call pair_points_near(blocks, set, pair, nearest, stat)
    end subroutine enriched_pair_lambdas

    !> nearest(i): the complex_pair point of the same direction of the problem of `blocks`
    !> nearest the complex_pair point i of `set` where `pair`(i), found by the same search on
    !> a window of WINDOW |lambda| around it; huge where there is none.
    subroutine pair_points_near(blocks, set, pair, nearest, stat)
        type(reduced_blocks_t), intent(in) :: blocks
        type(critical_set_t), intent(in) :: set
        logical, intent(in) :: pair(:)
        real(wp), intent(inout) :: nearest(:)
        type(status_t), intent(out) :: stat
        type(thresholds_t) :: thr
        type(critical_set_t) :: near
        real(wp) :: lambda, scan(WINDOW_POINTS)
        integer :: i, j

        call pencil_thresholds(blocks%kt_nn, blocks%kt_nt, thr, stat)
        if (.not. stat%ok()) return
        do i = 1, size(set%points)
            if (.not. pair(i)) cycle
            lambda = set%points(i)%lambda
            scan = [(lambda + abs(lambda)*WINDOW*(real(2*j - WINDOW_POINTS - 1, wp)/ &
                     real(WINDOW_POINTS - 1, wp)), j=1, WINDOW_POINTS)]
            call find_critical_set(blocks, scan, thr%real_lambdas, near, stat)
            if (.not. stat%ok()) return
            do j = 1, size(near%points)
                if (near%points(j)%mechanism /= MECHANISM_COMPLEX_PAIR .or. &
                    (near%points(j)%appears .neqv. set%points(i)%appears)) cycle
                if (abs(near%points(j)%lambda - lambda) < abs(nearest(i) - lambda)) &
                    nearest(i) = near%points(j)%lambda
            end do
        end do
    end subroutine pair_points_near

    !> The bars of `this` into the onset points of `set` that are these collisions (the same
    !> search on the same problem: the same points, to round-off), and no bar into the onset
    !> point of a withheld side, whatever it is; known(i) where set.
    subroutine onset_bars_apply(this, set, known)
        class(onset_bars_t), intent(in) :: this
        type(critical_set_t), intent(inout) :: set
        logical, intent(inout) :: known(:)
        integer :: side, i
        do side = SIDE_PLUS, SIDE_MINUS
            i = onset_point(set, side)
            if (i == 0) cycle
            if (this%withheld(side)) then
                set%points(i)%error_bar = -1.0_wp
                known(i) = .true.
                cycle
            end if
            if (.not. this%collision(side)) cycle
            if (set%points(i)%mechanism /= MECHANISM_COMPLEX_PAIR .or. &
                abs(set%points(i)%lambda - this%lambda(side)) > &
                1.0e-12_wp*abs(this%lambda(side))) cycle
            set%points(i)%error_bar = this%bar(side)
            known(i) = .true.
        end do
    end subroutine onset_bars_apply
end module boundary_estimate
