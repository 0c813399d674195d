! SPDX-License-Identifier: MIT
!> The adaptive loop (adaptive_loop) of analysis 'threshold' with &adapt tolerance > 0: its
!> goal is the pair of critical lambdas, lambda+ and lambda-, the real eigenvalues of the
!> pencil Kt_nn x = lambda Kt_nt x nearest zero, each with its own error estimate
!> (threshold_estimate).
!>
!> Both sides on one mesh. Each level marks, for every side whose estimate is still above
!> the tolerance, the Doerfler set of that side's indicators, and refines the union. The
!> two sides need different refinement (on the reference scene each threshold's mode is
!> singular at the other corner of Gamma_C), so the mesh is finer than either side alone
!> needs; in exchange one mesh carries both answers and everything else a threshold run
!> reports on it (the spectrum at &analysis lambda, the confirmations and the boundary of
!> the set where a positive mu exists), and a side that meets the tolerance first stops
!> asking for cells.
!>
!> Where a side's onset (the boundary point of {lambda : a positive mu exists} nearest zero
!> on that side) is a collision of two real mu (complex_pair), that collision, not the
!> pencil eigenvalue, is the side's goal: its estimate is the difference to the same point
!> one degree higher on the same cells (boundary_estimate), its bar level_bar's, and its
!> indicators those of the dual-weighted residual of the lowest positive mu just on the real
!> side of it. Why they fit: at the collision A(lambda_c) has a 2 x 2 Jordan block with right
!> and left eigenvectors x, y (y'x = 0); a perturbation E of A keeps the double eigenvalue
!> where y'(E + A' d lambda)x = 0, so d lambda_c = -y'Ex / y'A'x, a residual of x weighted
!> by y. Just beside the collision the two colliding eigenpairs tend to x and y, so the
!> weighted residual of either, cell by cell, tends to that of lambda_c up to one factor;
!> Doerfler's marking ignores the factor.
module adaptive_threshold
    use kinds, only: wp
    use status, only: status_t
    use strings, only: to_string, short_real_text
    use timer, only: wall_time, timings_t, PHASE_REDUCTION
    use scene, only: scene_t
    use method_options, only: eigen_options_t, adapt_options_t, SOLVER_DENSE
    use problem, only: problem_t
    use sparse_cholesky, only: cholesky_t
    use threshold_analysis, only: factor_with_contact_blocks, threshold_result_t, &
                                  solve_thresholds
    use critical_lambda, only: thresholds_t, pencil_thresholds, SIDE_PLUS, SIDE_MINUS, &
                               SIDE_LABELS, SIDE_NAMES, lowest_positive_mu
    use error_estimate, only: ENRICHED_CONTACT_MAX
    use threshold_estimate, only: threshold_estimate_t, threshold_displacements, &
                                  estimate_threshold_errors
    use adaptive_loop, only: adapt_goal_t, adapt_mesh, doerfler_marking
    use contact_reduction, only: reduced_blocks_t
    use contact_boundary, only: assemble_b
    use critical_set, only: critical_set_t, find_critical_set, search_critical_set, &
                            onset_point, side_offset, &
                            MECHANISM_COMPLEX_PAIR
    use boundary_estimate, only: enriched_pair_lambdas, onset_bars_t
    use eigen_solve, only: eigen_result_t, eigen_with_factor
    use error_estimate, only: error_estimate_t, estimate_lowest_error
    use error_bar, only: level_bar, theta_warnings
    use roundoff, only: threshold_roundoff, collision_roundoffs
    use element_types, only: element_degree
    implicit none
    private
    public :: adapt_thresholds, solve_adapted_thresholds, apply_collision_bars
    public :: onset_search, collision_onsets, goal_bars, level_line   ! (hp_threshold too)

    !> coarse_scan_t: the largest level scanned at the end, in contact functions
    integer, parameter :: SCAN_CONTACT_MAX = 100

    !> One level of the loop: a row of adapt.csv, arrays by SIDE_PLUS, SIDE_MINUS.
    type, public :: threshold_level_t
        integer :: level = 0
        integer :: n_dofs = 0
        integer :: n_contact = 0
        integer :: n_cells = 0
        logical :: found(2) = .false.             !! a threshold on that side
        real(wp) :: lambda(2) = 0.0_wp
        logical :: estimated(2) = .false.
        real(wp) :: error_estimate(2) = 0.0_wp    !! |relative error estimate| of lambda
        real(wp) :: error_bar(2) = -1.0_wp         !! the bars at this level; < 0: none
        !> the side's onset is a collision (complex_pair): its lambda, |relative estimate|
        !> (< 0: none) and bar (< 0: none)
        logical :: collision(2) = .false.
        real(wp) :: collision_lambda(2) = 0.0_wp
        real(wp) :: collision_estimate(2) = -1.0_wp
        real(wp) :: collision_bar(2) = -1.0_wp
        real(wp) :: collision_roundoff(2) = -1.0_wp   !! its round-off part; < 0: unknown
        !> hp: the side's goal has stopped converging at this level or before (error_bar:
        !> hp_run_bar): no bar from then on
        logical :: stalled(2) = .false.
        real(wp) :: time_s = 0.0_wp
    end type threshold_level_t

    type, public :: adaptive_thresholds_t
        type(threshold_level_t), allocatable :: levels(:)
        type(problem_t) :: prob                   !! the problem of the last level solved
        type(threshold_estimate_t) :: estimate    !! of its thresholds
        logical :: converged = .false.
        logical :: floor_reached = .false.   !! stopped by round-off, not by a limit
        character(len=:), allocatable :: outcome
        !> the boundary the final report carries (coarse_scan_t); scan_contact 0: none
        type(critical_set_t) :: coarse
    end type adaptive_thresholds_t

    !> The boundary of the positive set for a loop's last level, found cheaply: the set of the
    !> last level that searched it (onset_search), else a scan of the last level with at most
    !> SCAN_CONTACT_MAX contact functions, made once at the end (coarse_set); the last level
    !> then carries its points (carry_critical_set). The scan's hundred dense p x p solves cost
    !> 1/8 or less of the last level's (hp to 1e-10 on the reference scene: 75 of 291
    !> contact functions; before, the scan on the last level took three times the loop).
    type, public :: coarse_scan_t
        type(critical_set_t) :: searched   !! scan_contact 0: no level searched
        type(reduced_blocks_t), private :: blocks
        real(wp), allocatable, private :: pencil(:)
    contains
        procedure :: note => coarse_scan_note
        procedure :: coarse_set => coarse_scan_coarse_set
    end type coarse_scan_t

    type, extends(adapt_goal_t) :: threshold_goal_t
        type(threshold_level_t), allocatable :: levels(:)
        type(thresholds_t) :: thr
        type(threshold_estimate_t) :: est
        real(wp) :: tolerance = 0.0_wp   !! &adapt tolerance: the sides above it mark cells
        type(eigen_options_t) :: options   !! of the spectra beside a collision
        real(wp), allocatable :: scan(:)   !! the lambdas of the boundary search
        !> per side, the indicators of its collision onset (n_cells, 2), summing to 1
        real(wp), allocatable :: collision_indicators(:, :)
        real(wp) :: collision_estimate(2) = -1.0_wp
        character(len=200) :: collision_skipped(2) = ''
        !> the dofs of the last level that found both onsets at the pencil eigenvalues
        !> (onset_search); 0: none yet
        integer :: pencil_dofs = 0
        !> what the next level and the final report carry the boundary of the positive set from
        type(coarse_scan_t) :: scan_state
    contains
        procedure :: solve => threshold_goal_solve
        procedure :: error => threshold_goal_error
        procedure :: mark => threshold_goal_mark
        procedure :: missing => threshold_goal_missing
    end type threshold_goal_t

contains

    !> Run the loop from the problem `start` (level 0) of the scene `scn` as `adapt` asks, the
    !> boundary searched over `scan`. A limit reached is no failure (stat ok, out%converged
    !> false, out%outcome says so).
    subroutine adapt_thresholds(scn, options, adapt, scan, start, out, timings, stat)
        type(scene_t), intent(in) :: scn
        type(eigen_options_t), intent(in) :: options
        type(adapt_options_t), intent(in) :: adapt
        real(wp), intent(in) :: scan(:)
        type(problem_t), intent(in) :: start
        type(adaptive_thresholds_t), intent(out) :: out
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(threshold_goal_t) :: goal

        allocate (goal%levels(0))
        goal%tolerance = adapt%tolerance
        goal%options = options
        goal%scan = scan
        call adapt_mesh(scn, adapt, start, goal, out%prob, out%converged, out%floor_reached, &
                        out%outcome, timings, stat)
        if (.not. stat%ok()) return
        call move_alloc(goal%levels, out%levels)
        out%estimate = goal%est
        call goal%scan_state%coarse_set(scan, out%prob%contact%p(), out%coarse, stat)
    end subroutine adapt_thresholds

    !> The adaptive 'threshold' analysis: the loop from `start` (adapt_thresholds), then the
    !> threshold analysis on its final problem with the loop's estimates and the collision
    !> onsets' level bars (last_onset_bars: their one-mesh bars are not computed); a limit
    !> reached heads the warnings of `res` (out%converged false says so).
    subroutine solve_adapted_thresholds(scn, lambda, options, adapt, scan, start, out, res, &
                                        timings, stat)
        type(scene_t), intent(in) :: scn
        real(wp), intent(in) :: lambda
        type(eigen_options_t), intent(in) :: options
        type(adapt_options_t), intent(in) :: adapt
        real(wp), intent(in) :: scan(:)
        type(problem_t), intent(in) :: start
        type(adaptive_thresholds_t), intent(out) :: out
        type(threshold_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        call adapt_thresholds(scn, options, adapt, scan, start, out, timings, stat)
        if (stat%ok()) call solve_thresholds(scn, out%prob, lambda, options, scan, res, timings, &
                                             stat, estimate=out%estimate, &
                                             onsets=last_onset_bars(out), coarse=out%coarse)
        if (stat%ok() .and. .not. out%converged) res%eigen%warnings = &
            [character(len=len(res%eigen%warnings)) :: out%outcome, res%eigen%warnings]
        if (stat%ok()) res%eigen%warnings = [character(len=len(res%eigen%warnings)) :: &
                                             res%eigen%warnings, theta_warnings(adapt%theta)]
    end subroutine solve_adapted_thresholds

    !> Factor K, form the contact blocks, solve the pencil, and estimate both thresholds.
    subroutine threshold_goal_solve(this, scn, prob, level, loop_start, timings, stat)
        class(threshold_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        integer, intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(cholesky_t) :: chol
        type(reduced_blocks_t) :: blocks
        type(critical_set_t) :: set
        type(eigen_result_t) :: beside(2)
        real(wp), allocatable :: u(:, :)
        real(wp) :: start, bar(2), roundoff(2)
        real(wp), allocatable :: nearest(:)
        integer :: onset(2)

        call factor_with_contact_blocks(scn, prob, chol, blocks%kt_nn, blocks%kt_nt, &
                                        timings, stat)
        if (.not. stat%ok()) return
        start = wall_time()
        call pencil_thresholds(blocks%kt_nn, blocks%kt_nt, this%thr, stat)
        if (stat%ok()) call threshold_roundoff(prob%k, chol, prob%contact, blocks%kt_nn, &
                                               blocks%kt_nt, this%thr, stat)
        if (stat%ok()) call threshold_displacements(chol, prob%contact, prob%dofs%n_free, &
                                                    this%thr, u, stat)
        blocks%mass = prob%contact%mass
        if (stat%ok()) call onset_search(this%scan, blocks, this%thr, prob%dofs%n_free, &
                                         this%pencil_dofs, set, stat, this%scan_state%searched)
        if (stat%ok()) call this%scan_state%note(blocks, this%thr%real_lambdas, set)
        if (stat%ok()) call collision_onsets(set, onset)
        if (stat%ok() .and. any(onset > 0)) call collision_roundoffs(prob%k, chol, &
            prob%contact, blocks, set, stat)
        allocate (nearest(size(set%points)), source=huge(1.0_wp))
        if (stat%ok() .and. any(onset > 0)) call enriched_pair_lambdas(prob, &
            ENRICHED_CONTACT_MAX, set, nearest, stat)
        if (stat%ok() .and. any(onset > 0)) call collision_spectra(scn, prob, this%options, &
            chol, blocks, set, onset, nearest, beside, stat)
        call chol%free()
        if (.not. stat%ok()) return
        deallocate (blocks%kt_nn, blocks%kt_nt)
        call estimate_threshold_errors(prob, this%thr, u, ENRICHED_CONTACT_MAX, this%est, stat)
        if (stat%ok()) call estimate_collisions(this, prob, set, onset, nearest, beside)
        if (.not. stat%ok()) return
        call timings%add(PHASE_REDUCTION, wall_time() - start, ': thresholds and their '// &
                         'error estimates, level '//to_string(level))
        this%levels = [this%levels, level_row()]
        call level_bars(this%levels, element_degree(prob%mesh%element), this%thr%roundoff, &
                        this%est)
        ! the floor test's round-off part: that of the side with the largest bar
        call goal_bars(this%levels(size(this%levels)), this%thr%roundoff, bar, roundoff)
        this%roundoff = -1.0_wp
        if (maxval(bar) >= 0.0_wp) this%roundoff = roundoff(maxloc(bar, 1))
        call timings%note(level_line(this%levels(size(this%levels)), 'adapt level'))

    contains

        type(threshold_level_t) function level_row() result(row)
            row%level = level
            row%n_dofs = prob%dofs%n_free
            row%n_contact = prob%contact%p()
            row%n_cells = prob%mesh%n_cells()
            row%found = this%thr%found
            row%lambda = this%thr%lambda
            row%estimated = this%est%computed
            row%error_estimate = abs(this%est%relative)
            row%collision = onset > 0
            where (row%collision) row%collision_lambda = set%points(max(onset, 1))%lambda
            where (row%collision) row%collision_roundoff = set%points(max(onset, 1))%roundoff
            row%collision_estimate = this%collision_estimate
            row%time_s = wall_time() - loop_start
        end function level_row
    end subroutine threshold_goal_solve

    !> The largest bar of the sides' goals (goal_bars); negative when one of them has none,
    !> or when there is neither.
    real(wp) function threshold_goal_error(this)
        class(threshold_goal_t), intent(in) :: this
        real(wp) :: bar(2), roundoff(2)
        threshold_goal_error = -1.0_wp
        associate (row => this%levels(size(this%levels)))
            if (.not. any(row%found .or. row%collision)) return
            call goal_bars(row, this%thr%roundoff, bar, roundoff)
            if (any(bar < 0.0_wp)) return
            threshold_goal_error = maxval(bar)
        end associate
    end function threshold_goal_error

    !> The boundary of the positive set (find_critical_set over the analysis' scan) on a
    !> level of `n_free` dofs, searched only where a side may have a collision onset: where
    !> it has no pencil eigenvalue, or a positive mu just inside it (NOT confirmed). Where
    !> both are confirmed `set` stays empty and the thresholds are the goals, and that check
    !> (two dense p x p eigen-solves) is made again only once the dofs have doubled since
    !> `pencil_dofs`, the last level it held on: at every level the check cost as much as
    !> the rest of input/threshold_adapt.nml (scan: twice that), for an answer that does
    !> not change there. With `previous` (the set a coarser level found, if it searched),
    !> its points are carried (carry_critical_set) unless the structure differs here.
    subroutine onset_search(scan, blocks, thr, n_free, pencil_dofs, set, stat, previous)
        real(wp), intent(in) :: scan(:)   !! the lambdas of the search
        type(reduced_blocks_t), intent(in) :: blocks
        type(thresholds_t), intent(in) :: thr
        integer, intent(in) :: n_free
        integer, intent(inout) :: pencil_dofs
        type(critical_set_t), intent(out) :: set
        type(status_t), intent(out) :: stat
        type(critical_set_t), intent(in), optional :: previous
        real(wp) :: mu, inside
        logical :: found, search
        integer :: side, n_positive

        allocate (set%points(0))
        search = .not. all(thr%found)
        if (.not. search .and. pencil_dofs > 0 .and. n_free < 2*pencil_dofs) return
        do side = SIDE_PLUS, SIDE_MINUS
            if (search) exit
            inside = thr%lambda(side) - sign(side_offset(thr%lambda(side)), thr%lambda(side))
            call lowest_positive_mu(blocks, inside, mu, found, n_positive, stat)
            if (.not. stat%ok()) return
            search = found
        end do
        pencil_dofs = 0
        if (.not. search) pencil_dofs = n_free
        if (search) call search_critical_set(blocks, scan, thr%real_lambdas, set, stat, previous)
    end subroutine onset_search

    !> onset(side): the index in `set` of the side's onset where it is a collision of two
    !> real mu (complex_pair), 0 where the side has none or it is a pencil eigenvalue.
    subroutine collision_onsets(set, onset)
        type(critical_set_t), intent(in) :: set
        integer, intent(out) :: onset(2)
        integer :: side
        do side = SIDE_PLUS, SIDE_MINUS
            onset(side) = onset_point(set, side)
            if (onset(side) == 0) cycle
            if (set%points(onset(side))%mechanism /= MECHANISM_COMPLEX_PAIR) onset(side) = 0
        end do
    end subroutine collision_onsets

    !> beside(side): the spectrum (dense, with vectors) where the two colliding mu of the
    !> side's collision onset are real on this mesh and on the enriched one (`nearest`, the
    !> enriched point; huge: none): past both points by their distance, at least
    !> side_offset.
    subroutine collision_spectra(scn, prob, options, chol, blocks, set, onset, nearest, beside, &
                                 stat)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(eigen_options_t), intent(in) :: options
        type(cholesky_t), intent(in) :: chol
        type(reduced_blocks_t), intent(in) :: blocks
        type(critical_set_t), intent(in) :: set
        integer, intent(in) :: onset(2)
        real(wp), intent(in) :: nearest(:)
        type(eigen_result_t), intent(inout) :: beside(2)
        type(status_t), intent(out) :: stat
        type(timings_t) :: quiet
        real(wp) :: lambda, gap
        integer :: side

        do side = SIDE_PLUS, SIDE_MINUS
            if (onset(side) == 0) cycle
            if (.not. nearest(onset(side)) < huge(1.0_wp)) cycle
            lambda = set%points(onset(side))%lambda
            gap = abs(nearest(onset(side)) - lambda)
            if (set%points(onset(side))%appears) then   ! real above
                lambda = max(lambda, nearest(onset(side))) + max(gap, side_offset(lambda))
            else
                lambda = min(lambda, nearest(onset(side))) - max(gap, side_offset(lambda))
            end if
            beside(side)%lambda = lambda
            beside(side)%solver = SOLVER_DENSE
            call assemble_b(prob%contact, prob%dofs%n_free, lambda, beside(side)%b, stat)
            if (stat%ok()) call eigen_with_factor(scn, prob, options, chol, beside(side), quiet, &
                                                  stat, blocks%kt_nn, blocks%kt_nt)
            if (.not. stat%ok()) return
        end do
    end subroutine collision_spectra

    !> The estimate and the indicators of each collision onset: |lambda+ - lambda_h| /
    !> |lambda_h| to the enriched point `nearest`, and the weighted-residual indicators of
    !> the lowest positive mu of `beside` scaled to sum 1. A side that cannot be estimated
    !> keeps estimate -1 and says why in collision_skipped (never a failure of the run).
    subroutine estimate_collisions(this, prob, set, onset, nearest, beside)
        type(threshold_goal_t), intent(inout) :: this
        type(problem_t), intent(in) :: prob
        type(critical_set_t), intent(in) :: set
        integer, intent(in) :: onset(2)
        real(wp), intent(in) :: nearest(:)
        type(eigen_result_t), intent(in) :: beside(2)
        type(error_estimate_t) :: err
        type(status_t) :: stat
        real(wp) :: lambda
        integer :: side, lowest

        if (allocated(this%collision_indicators)) deallocate (this%collision_indicators)
        allocate (this%collision_indicators(prob%mesh%n_cells(), 2), source=0.0_wp)
        this%collision_estimate = -1.0_wp
        this%collision_skipped = ''
        do side = SIDE_PLUS, SIDE_MINUS
            if (onset(side) == 0) cycle
            lambda = set%points(onset(side))%lambda
            this%collision_skipped(side) = 'collision onset: no collision of the problem '// &
                'one degree higher near it'
            if (.not. nearest(onset(side)) < huge(1.0_wp)) cycle
            this%collision_skipped(side) = 'collision onset: no positive mu beside it'
            lowest = beside(side)%spec%lowest_positive()
            if (lowest == 0 .or. size(beside(side)%spec%vectors, 2) < lowest) cycle
            call estimate_lowest_error(prob, beside(side)%lambda, &
                prob%units%mu_to_scaled(real(beside(side)%spec%mu(lowest), wp)), &
                real(beside(side)%spec%vectors(:, lowest), wp), ENRICHED_CONTACT_MAX, err, stat)
            this%collision_skipped(side) = 'collision onset: no indicators beside it'
            if (.not. stat%ok()) this%collision_skipped(side) = 'collision onset: '//stat%message
            if (.not. stat%ok() .or. .not. err%computed) cycle
            if (.not. sum(err%indicators) > 0.0_wp) cycle
            this%collision_indicators(:, side) = err%indicators/sum(err%indicators)
            this%collision_estimate(side) = abs(nearest(onset(side)) - lambda)/abs(lambda)
            this%collision_skipped(side) = ''
        end do
    end subroutine estimate_collisions

    !> Each side's bar at the last of `levels` (error_bar's level_bar over its window of the
    !> levels where that side was found and estimated), into the last row and `est`.
    subroutine level_bars(levels, degree, roundoff, est)
        type(threshold_level_t), intent(inout) :: levels(:)
        integer, intent(in) :: degree
        real(wp), intent(in) :: roundoff(2)   !! of the last level's lambdas; -1: unknown
        type(threshold_estimate_t), intent(inout) :: est
        real(wp) :: estimates(size(levels)), lambdas(size(levels))
        integer :: dofs(size(levels)), side, k, i
        k = size(levels)
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. (levels(k)%found(side) .and. levels(k)%estimated(side))) cycle
            ! plain arrays: components of a derived-type array would make temporaries
            do i = 1, k
                estimates(i) = -1.0_wp
                if (levels(i)%found(side) .and. levels(i)%estimated(side)) &
                    estimates(i) = levels(i)%error_estimate(side)
                lambdas(i) = levels(i)%lambda(side)
                dofs(i) = levels(i)%n_dofs
            end do
            levels(k)%error_bar(side) = level_bar(estimates, lambdas, dofs, degree, &
                                                  roundoff(side))
            est%bar(side) = levels(k)%error_bar(side)
        end do
        ! the collision onsets' bars, over the levels where that side's onset was one
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. levels(k)%collision(side)) cycle
            do i = 1, k
                estimates(i) = -1.0_wp
                if (levels(i)%collision(side)) estimates(i) = levels(i)%collision_estimate(side)
                lambdas(i) = levels(i)%collision_lambda(side)
                dofs(i) = levels(i)%n_dofs
            end do
            levels(k)%collision_bar(side) = level_bar(estimates, lambdas, dofs, degree, &
                                                      levels(k)%collision_roundoff(side))
        end do
    end subroutine level_bars

    !> The progress line of a level: each threshold found, then each collision onset, with
    !> its estimate and bar where it has them.
    function level_line(row, name) result(line)
        type(threshold_level_t), intent(in) :: row
        character(len=*), intent(in) :: name   !! of the level: 'adapt level', 'hp level'
        character(len=:), allocatable :: line
        integer :: side
        line = name//' '//to_string(row%level)//': '//to_string(row%n_dofs)//' dofs'
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. row%found(side)) cycle
            line = line//', '//SIDE_LABELS(side)//' = '// &
                short_real_text(row%lambda(side), 12)
            if (row%estimated(side)) line = line//' (estimate '// &
                short_real_text(row%error_estimate(side))//', bar '// &
                short_real_text(row%error_bar(side))//')'
        end do
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. row%collision(side)) cycle
            line = line//', collision onset '//trim(SIDE_NAMES(side))//' = '// &
                short_real_text(row%collision_lambda(side), 12)
            if (row%collision_estimate(side) >= 0.0_wp) line = line//' (estimate '// &
                short_real_text(row%collision_estimate(side))//', bar '// &
                short_real_text(row%collision_bar(side))//')'
        end do
        do side = SIDE_PLUS, SIDE_MINUS
            if (row%stalled(side)) line = line//', '//trim(SIDE_NAMES(side))// &
                ' side stalled (no bar)'
        end do
    end function level_line

    !> Per side, the bar of its goal at level `row` (the collision onset where its onset is
    !> one, else the threshold; 0 where the side has neither: nothing to meet; -1 where the
    !> goal has no bar yet) and that bar's round-off part (-1: unknown).
    pure subroutine goal_bars(row, threshold_roundoff, bar, roundoff)
        type(threshold_level_t), intent(in) :: row
        real(wp), intent(in) :: threshold_roundoff(2)
        real(wp), intent(out) :: bar(2), roundoff(2)
        integer :: side
        do side = SIDE_PLUS, SIDE_MINUS
            bar(side) = 0.0_wp
            roundoff(side) = -1.0_wp
            if (row%collision(side)) then
                bar(side) = row%collision_bar(side)
                roundoff(side) = row%collision_roundoff(side)
            else if (row%found(side)) then
                bar(side) = row%error_bar(side)
                roundoff(side) = threshold_roundoff(side)
            end if
            if (bar(side) < 0.0_wp) bar(side) = -1.0_wp
        end do
    end subroutine goal_bars

    !> The union of the Doerfler sets of the sides still above the tolerance.
    function threshold_goal_mark(this, theta) result(marked)
        class(threshold_goal_t), intent(in) :: this
        real(wp), intent(in) :: theta
        integer, allocatable :: marked(:)
        logical, allocatable :: chosen(:)
        integer :: side, i

        allocate (chosen(size(this%collision_indicators, 1)), source=.false.)
        associate (row => this%levels(size(this%levels)))
            do side = SIDE_PLUS, SIDE_MINUS
                if (row%collision(side)) then
                    if (row%collision_bar(side) <= this%tolerance) cycle
                    chosen(doerfler_marking(this%collision_indicators(:, side), theta)) = .true.
                    cycle
                end if
                if (.not. this%thr%found(side)) cycle
                if (this%est%bar(side) <= this%tolerance) cycle
                chosen(doerfler_marking(this%est%indicators(:, side), theta)) = .true.
            end do
        end associate
        marked = pack([(i, i=1, size(chosen))], chosen)
    end function threshold_goal_mark

    function threshold_goal_missing(this) result(reason)
        class(threshold_goal_t), intent(in) :: this
        character(len=:), allocatable :: reason
        integer :: side
        reason = 'no real eigenvalue of the pencil Kt_nn x = lambda Kt_nt x: no threshold '// &
                 'to adapt to'
        do side = SIDE_PLUS, SIDE_MINUS
            if (len_trim(this%collision_skipped(side)) > 0) then
                reason = SIDE_LABELS(side)//': '//trim(this%collision_skipped(side))
                return
            end if
            if (this%levels(size(this%levels))%collision(side)) cycle
            if (this%thr%found(side) .and. .not. this%est%computed(side)) then
                reason = SIDE_LABELS(side)//': '//trim(this%est%skipped(side))
                if (len_trim(this%est%skipped(side)) == 0) reason = reason// &
                    'no enrichment for these cells'
                return
            end if
        end do
    end function threshold_goal_missing

    !> The bars of the final level's collision onsets into the boundary points of `set`
    !> (the same problem's search: the same points), replacing their one-mesh bars.
    subroutine apply_collision_bars(out, set)
        type(adaptive_thresholds_t), intent(in) :: out
        type(critical_set_t), intent(inout) :: set
        logical :: known(size(set%points))
        type(onset_bars_t) :: onsets
        onsets = last_onset_bars(out)
        known = .false.
        call onsets%apply(set, known)
    end subroutine apply_collision_bars

    !> The collision onsets of the final level and their bars (none before a level).
    type(onset_bars_t) function last_onset_bars(out) result(onsets)
        type(adaptive_thresholds_t), intent(in) :: out
        if (size(out%levels) == 0) return
        associate (row => out%levels(size(out%levels)))
            onsets%collision = row%collision
            onsets%lambda = row%collision_lambda
            onsets%bar = row%collision_bar
        end associate
    end function last_onset_bars

    !> A level's contact `blocks` (mass set) and pencil eigenvalues, and its boundary `set`
    !> if it searched (set%scan_contact > 0).
    subroutine coarse_scan_note(this, blocks, pencil, set)
        class(coarse_scan_t), intent(inout) :: this
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: pencil(:)
        type(critical_set_t), intent(in) :: set
        if (size(blocks%kt_nn, 1) <= SCAN_CONTACT_MAX) then
            this%blocks = blocks
            this%pencil = pencil
        end if
        if (set%scan_contact > 0) this%searched = set
    end subroutine coarse_scan_note

    !> The set for a last level of `p_last` contact functions to carry: the searched one, else
    !> the scan of the noted blocks where they have at most half as many contact functions
    !> (its solves in set%n_evaluations), else none (scan_contact 0: the last level scans).
    subroutine coarse_scan_coarse_set(this, scan, p_last, set, stat)
        class(coarse_scan_t), intent(in) :: this
        real(wp), intent(in) :: scan(:)   !! the lambdas of the search
        integer, intent(in) :: p_last
        type(critical_set_t), intent(out) :: set
        type(status_t), intent(out) :: stat
        if (this%searched%scan_contact > 0) then
            set = this%searched
            set%n_evaluations = 0   ! counted where it was searched
        else if (allocated(this%pencil)) then
            if (2*size(this%blocks%kt_nn, 1) <= p_last) call find_critical_set(this%blocks, &
                scan, this%pencil, set, stat)
        end if
    end subroutine coarse_scan_coarse_set
end module adaptive_threshold
