! SPDX-License-Identifier: MIT
!> The goal of the adaptive loop (adapt_driver) for analysis 'threshold': the critical
!> lambdas, lambda+ and lambda-, the real eigenvalues of the pencil Kt_nn x = lambda Kt_nt x
!> nearest zero, one target per side (SIDE_PLUS, SIDE_MINUS), each judged on its own by one
!> rule on h and hp levels (judge_sides): one side never stops, fails or hides the other.
!>
!> h levels (h_refiner): each side has its own error estimate (threshold_estimate). Each
!> level marks, for every side still active, the Doerfler set of that side's indicators,
!> and refines the union. The two sides need different refinement
!> (on the reference scene each threshold's mode is singular at the other corner of Gamma_C),
!> so the mesh is finer than either side alone needs; in exchange one mesh carries both
!> answers and everything else a threshold run reports on it (the spectrum at &analysis
!> lambda, the confirmations and the boundary of the set where a positive mu exists), and a
!> side that meets the tolerance first stops asking for cells.
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
!>
!> hp levels (hp_levels): the same thresholds and collision onsets on each level, with the
!> bar of each from its changes between levels (hp_run_bar) plus its round-off part; a level
!> whose dense contact blocks would not fit the memory is refused before they are formed.
!> Once the loop ends, each side's goal is checked on the last level's cells with every
!> degree raised by one (threshold_goal_check), folded into its bar (error_bar: checked_bar).
!> The last level solved is then reported on its own factor as the threshold analysis
!> reports its mesh: the spectrum at &analysis lambda, the confirmations, the boundary of
!> the positive set. (On h levels the analysis reports the final mesh afresh:
!> threshold_analysis.)
module threshold_goal
    use kinds, only: wp, i8
    use status, only: status_t
    use strings, only: to_string, short_real_text, given_real_text, seconds_text
    use timer, only: wall_time, timings_t, PHASE_REDUCTION
    use scene, only: scene_t
    use method_options, only: eigen_options_t, adapt_options_t, SOLVER_DENSE, REFINE_HP
    use problem, only: problem_t
    use hp_space, only: hp_space_t
    use sparse_cholesky, only: cholesky_t
    use threshold_analysis, only: factor_with_contact_blocks, threshold_result_t, &
                                  solve_thresholds, confirm_and_bound
    use critical_lambda, only: thresholds_t, pencil_thresholds, SIDE_PLUS, SIDE_MINUS, &
                               SIDE_LABELS, SIDE_NAMES, lowest_positive_mu, restricted_thresholds
    use hp_contact, only: half_degree_forces
    use error_estimate, only: ENRICHED_CONTACT_MAX
    use threshold_estimate, only: threshold_estimate_t, threshold_displacements, &
                                  estimate_threshold_errors
    use contact_reduction, only: reduced_blocks_t, contact_flexibility
    use contact_boundary, only: assemble_b
    use critical_set, only: critical_set_t, find_critical_set, search_critical_set, &
                            onset_point, side_offset, MECHANISM_COMPLEX_PAIR, MECHANISM_PENCIL, &
                            track_onsets, boundary_point_t
    use boundary_estimate, only: enriched_pair_lambdas, onset_bars_t
    use eigen_solve, only: eigen_result_t, eigen_with_factor, choose_solver
    use error_estimate, only: error_estimate_t, estimate_lowest_error
    use error_bar, only: theta_warnings, floor_reached, floor_outcome, stall_outcome, &
                         checked_bar, settled_floor
    use roundoff, only: threshold_roundoff, collision_roundoffs
    use memory_budget, only: check_contact_memory, contact_peak_blocks, contact_blocks_bytes
    use accuracy, only: WARNING_LEN
    use adapt_driver, only: adapt_goal_t, refiner_t, adapt_level_t, adapt_levels, &
                            check_target, adapt_target_t, TARGET_ACTIVE, TARGET_MET, &
                            TARGET_FLOOR, TARGET_STOPPED, no_estimate_outcome, NONE_LEVELS, &
                            absent_since, absence_confirmed, built_check_t
    use h_refiner, only: h_refiner_t, doerfler_marking
    use hp_levels, only: hp_refiner_t, HP_ESTIMATE, check_words
    use pencil_tracking, only: N_PROFILE_BINS, level_values_t
    use moving_side, only: contact_ends_t, contact_ends, level_profile, track_side, &
                           moving_words, past_crossing_end, unconfirmed_words, end_words
    implicit none
    private
    public :: solve_adapted_thresholds, threshold_goal_setup, threshold_goal_finish


    !> coarse_scan_t: the largest level scanned at the end, in contact functions
    integer, parameter :: SCAN_CONTACT_MAX = 100
    !> The first bracket (relative) of a collision onset the last level followed, when the
    !> report carries the whole range to the same blocks: it is there to round-off.
    real(wp), parameter :: TRACKED_WIDTH = 1.0e-9_wp

    !> One level of the loop: a row of adapt.csv, arrays by SIDE_PLUS, SIDE_MINUS.
    type, public :: threshold_level_t
        integer :: level = 0
        integer :: layers = 0                     !! hp: the layers of grading; h: 0
        integer :: p_min = 0                      !! hp: the lowest cell degree; h: 0
        integer :: p_max = 0                      !! hp: the highest cell degree; h: 0
        integer :: n_dofs = 0
        integer :: n_contact = 0
        integer :: n_cells = 0
        logical :: found(2) = .false.             !! a threshold on that side
        real(wp) :: lambda(2) = 0.0_wp
        !> of lambda at this level: the pencil's backward error and the round-off part of its
        !> bar (-1: unknown), for a side reported at the level where it met the tolerance
        real(wp) :: residual(2) = 0.0_wp
        real(wp) :: roundoff(2) = -1.0_wp
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
        !> hp: the profile on Gamma_C of each side's vector (pencil_tracking; zero where the
        !> side has no value) and the level's smallest contact cell relative to Gamma_C
        real(wp) :: profile(N_PROFILE_BINS, 2) = 0.0_wp
        real(wp) :: resolution = 0.0_wp
        real(wp) :: time_s = 0.0_wp
    end type threshold_level_t

    type, public :: adaptive_thresholds_t
        type(threshold_level_t), allocatable :: levels(:)
        !> the problem of the last level solved (hp: graded P1 mesh, condensed K, hp contact,
        !> dofs%n_free only) and its hp space (cell degrees; h: none)
        type(problem_t) :: prob
        type(hp_space_t) :: space
        type(threshold_estimate_t) :: estimate    !! of its thresholds
        logical :: converged = .false.
        logical :: floor_reached = .false.   !! stopped by round-off, not by a limit
        character(len=:), allocatable :: outcome
        !> the boundary the final report carries (coarse_scan_t); scan_contact 0: none
        type(critical_set_t) :: coarse
        !> a level after the first that failed (adapt_goal_t: failure): the run writes the
        !> last complete level's results, then exits with this status; ok: none
        type(status_t) :: failure
    end type adaptive_thresholds_t

    !> A level's restricted contact blocks and real pencil values, for a scan at the end.
    type :: noted_level_t
        type(reduced_blocks_t) :: blocks
        real(wp), allocatable :: pencil(:)
    end type noted_level_t

    !> The boundary of the positive set for a loop's last level, found cheaply: the set of the
    !> last level that searched it (onset_search), else a scan of the largest level with at
    !> most SCAN_CONTACT_MAX contact functions and at most half the last level's, made once
    !> at the end (coarse_set); the last level then carries its points (carry_critical_set),
    !> each side's onset bracketed where the last level followed it (merge_onsets). The
    !> scan's hundred dense p x p solves cost 1/8 or less of the last level's (hp to 1e-10 on
    !> the reference scene: 75 of 291 contact functions; before, the scan on the last level
    !> took three times the loop).
    type, public :: coarse_scan_t
        type(critical_set_t) :: searched   !! scan_contact 0: no level searched
        !> every level of at most SCAN_CONTACT_MAX contact functions, coarsest first: the
        !> scan takes the largest with at most half the last level's
        type(noted_level_t), allocatable, private :: noted(:)
    contains
        procedure :: note => coarse_scan_note
        procedure :: coarse_set => coarse_scan_coarse_set
    end type coarse_scan_t

    !> What a level overwrites in its goal before it is complete (keep_level).
    type :: kept_level_t
        type(thresholds_t) :: thr
        type(threshold_estimate_t) :: est
        type(coarse_scan_t) :: scan_state
        integer :: pencil_dofs = 0
        type(critical_set_t) :: set
        type(problem_t) :: prob
        type(hp_space_t) :: space
    end type kept_level_t

    type, extends(adapt_goal_t), public :: threshold_goal_t
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
        !> the last level solved: its problem and space; hp keeps its factor, contact blocks
        !> and boundary for the final report (`factored`)
        type(problem_t) :: prob
        type(hp_space_t) :: space
        type(cholesky_t) :: chol
        logical :: factored = .false.
        type(reduced_blocks_t) :: blocks
        !> hp: the blocks of the half-degree forces and their lift to the contact functions
        !> (critical_lambda: restricted_thresholds), where the thresholds are found
        type(reduced_blocks_t) :: restricted
        real(wp), allocatable :: lift(:, :)
        type(critical_set_t) :: set
        !> hp: the memory a level's contact blocks may take, in bytes (negative: as the
        !> machine has; absent: the memory available)
        logical :: memory_given = .false.
        integer(i8) :: memory = -1_i8
        !> hp: per side, the row of `levels` where its threshold met the tolerance with a bar
        !> (0: not met, or met as 'none', or its goal is a collision onset); the report quotes
        !> that level's value and bar (report_last_level)
        integer :: met_row(2) = 0
        !> the ends of Gamma_C (know_ends: of the first level; refinement keeps them) and, per end
        !> and side, whether that side's lambdas past the end's crossing lie there
        !> (moving_side: past_crossing_end) and that crossing, for the sides without a value
        logical :: ends_known = .false.
        type(contact_ends_t) :: ends
        logical :: past(2, 2) = .false.
        real(wp) :: crossing(2, 2) = 0.0_wp
    contains
        procedure :: solve => threshold_goal_solve
        procedure :: judge => threshold_goal_judge
        procedure :: bar_text => threshold_goal_bar_text
        procedure :: mark => threshold_goal_mark
        procedure :: check => threshold_goal_check
    end type threshold_goal_t

contains

    !> The adaptive 'threshold' analysis: the loop from the problem `start` of the scene
    !> `scn` as `adapt` asks, the boundary searched over `scan`, then the report of the last
    !> level at `lambda` as `options` ask: on h levels the threshold analysis on the final
    !> problem with the loop's estimates and the collision onsets' level bars
    !> (last_onset_bars: their one-mesh bars are not computed), on hp levels the report of
    !> the last level on its own factor (report_last_level). A limit reached is no failure
    !> (stat ok, out%converged false, its outcome heading the warnings of `res`); an hp first
    !> level whose contact blocks do not fit `available` bytes (default: the memory
    !> available) is (STATUS_NOT_MET).
    subroutine solve_adapted_thresholds(scn, lambda, options, adapt, scan, start, out, res, &
                                        timings, stat, available)
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
        integer(i8), intent(in), optional :: available
        class(refiner_t), allocatable :: refiner
        type(threshold_goal_t) :: goal

        if (adapt%refine == REFINE_HP) then
            allocate (hp_refiner_t :: refiner)
        else
            allocate (h_refiner_t :: refiner)
        end if
        call threshold_goal_setup(goal, options, adapt, scan, available)
        call adapt_levels(scn, adapt, start, refiner, goal, timings, stat)
        call threshold_goal_finish(scn, goal, refiner, lambda, options, adapt, scan, out, res, &
                                   timings, stat)
    end subroutine solve_adapted_thresholds

    !> The goal of both thresholds, every target active, as `adapt` asks
    !> (solve_adapted_thresholds: the other arguments).
    subroutine threshold_goal_setup(goal, options, adapt, scan, available)
        type(threshold_goal_t), intent(inout) :: goal
        type(eigen_options_t), intent(in) :: options
        type(adapt_options_t), intent(in) :: adapt
        real(wp), intent(in) :: scan(:)
        integer(i8), intent(in), optional :: available
        allocate (goal%levels(0), goal%targets(2))
        goal%targets(1)%outcome = ''
        goal%targets(2)%outcome = ''
        goal%tolerance = adapt%tolerance
        goal%options = options
        goal%scan = scan
        if (present(available)) then
            goal%memory_given = .true.
            goal%memory = available
        end if
    end subroutine threshold_goal_setup

    !> After the loop of `goal` (`stat` its status, kept or replaced by the report's): its
    !> outcome and levels in `out`, the last level reported in `res` (solve_adapted_thresholds).
    subroutine threshold_goal_finish(scn, goal, refiner, lambda, options, adapt, scan, out, &
                                     res, timings, stat)
        type(scene_t), intent(in) :: scn
        type(threshold_goal_t), intent(inout) :: goal
        class(refiner_t), intent(in) :: refiner
        real(wp), intent(in) :: lambda
        type(eigen_options_t), intent(in) :: options
        type(adapt_options_t), intent(in) :: adapt
        real(wp), intent(in) :: scan(:)
        type(adaptive_thresholds_t), intent(out) :: out
        type(threshold_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(inout) :: stat
        character(len=WARNING_LEN), allocatable :: moving_warnings(:)
        type(onset_bars_t) :: onsets
        allocate (moving_warnings(0))
        ! a failed level whose level before could not be made again: nothing to report
        if (stat%ok() .and. .not. goal%failure%ok() .and. .not. refiner%estimated() .and. &
            .not. goal%factored) stat = goal%failure
        out%failure = goal%failure
        call loop_outcome(goal, out)
        call move_alloc(goal%levels, out%levels)
        out%prob = goal%prob
        out%space = goal%space
        if (refiner%estimated()) then
            if (stat%ok()) then
                out%estimate = goal%est
                call h_verdicts(goal, out, out%estimate, onsets)
                call goal%scan_state%coarse_set(scan, out%prob%contact%p(), out%coarse, stat)
            end if
            if (stat%ok()) call solve_thresholds(scn, out%prob, lambda, options, scan, res, &
                timings, stat, estimate=out%estimate, onsets=onsets, coarse=out%coarse)
            if (stat%ok()) call track_moving(goal, out, res%estimate, moving_warnings)
        else
            if (stat%ok() .and. goal%factored) call report_last_level(scn, goal, out, lambda, &
                                                                      res, timings, stat)
            if (stat%ok() .and. goal%factored) call track_moving(goal, out, res%estimate, &
                                                                 moving_warnings)
            out%estimate = res%estimate
        end if
        if (goal%factored) call goal%chol%free()
        ! the last level's dense blocks, freed here: where the goal is a component of another
        ! goal (joint_goal), gfortran 12 does not free them with it (Asan)
        call goal%blocks%free()
        call goal%restricted%free()
        if (allocated(goal%lift)) deallocate (goal%lift)
        if (.not. stat%ok()) return
        if (.not. out%converged) res%eigen%warnings = &
            [character(len=len(res%eigen%warnings)) :: out%outcome, moving_warnings, &
             res%eigen%warnings]
        if (refiner%estimated()) res%eigen%warnings = [character(len=len(res%eigen%warnings)) &
            :: res%eigen%warnings, theta_warnings(adapt%theta)]
    end subroutine threshold_goal_finish

    !> The loop's verdict: converged only when every side met the tolerance; the outcome,
    !> one clause per side, each naming its side, those not met first.
    subroutine loop_outcome(goal, out)
        type(threshold_goal_t), intent(in) :: goal
        type(adaptive_thresholds_t), intent(inout) :: out
        integer :: side
        out%converged = all([(goal%targets(side)%converged(), side=1, 2)])
        out%floor_reached = .not. out%converged .and. all([(goal%targets(side)%converged() &
            .or. goal%targets(side)%floor_reached(), side=1, 2)])
        out%outcome = ''
        do side = SIDE_PLUS, SIDE_MINUS
            if (goal%targets(side)%converged()) cycle
            out%outcome = out%outcome//merge('; ', '  ', len(out%outcome) > 0)// &
                labelled(side, goal%targets(side)%outcome)
        end do
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. goal%targets(side)%converged()) cycle
            out%outcome = out%outcome//merge('; ', '  ', len(out%outcome) > 0)// &
                labelled(side, goal%targets(side)%outcome)
        end do
        out%outcome = trim(adjustl(out%outcome))
    end subroutine loop_outcome

    !> `text` headed by the side's label, unless it is already.
    function labelled(side, text) result(line)
        integer, intent(in) :: side
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: line
        line = text
        if (index(text, trim(SIDE_LABELS(side))//':') /= 1) line = trim(SIDE_LABELS(side))// &
            ': '//text
    end function labelled

    !> h: the report of each side that did not meet the tolerance at the last level: no bar
    !> for its threshold (`est`) or its collision onset (`onsets`, the last level's), and
    !> its own reason, as report_last_level gives them on hp levels.
    subroutine h_verdicts(goal, out, est, onsets)
        type(threshold_goal_t), intent(in) :: goal
        type(adaptive_thresholds_t), intent(in) :: out
        type(threshold_estimate_t), intent(inout) :: est
        type(onset_bars_t), intent(out) :: onsets
        integer :: side
        onsets = last_onset_bars(out)
        do side = SIDE_PLUS, SIDE_MINUS
            if (goal%targets(side)%converged()) cycle
            onsets%bar(side) = -1.0_wp
            onsets%withheld(side) = .true.
            est%computed(side) = .false.
            est%bar(side) = -1.0_wp
            if (goal%thr%found(side)) est%skipped(side) = 'none: '// &
                labelled(side, goal%targets(side)%outcome)
        end do
    end subroutine h_verdicts

    !> Both thresholds on `level`, with their error estimates (h) or their bars from the
    !> changes between levels (hp), and each side's collision onset where it has one.
    subroutine threshold_goal_solve(this, scn, refiner, level, loop_start, timings, refused, &
                                    stat)
        class(threshold_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable, intent(out) :: refused
        type(status_t), intent(out) :: stat
        refused = ''
        if (refiner%estimated()) then
            call solve_h_level(this, scn, refiner, level, loop_start, timings, stat)
        else
            call solve_hp_level(this, scn, refiner, level, loop_start, timings, refused, stat)
        end if
    end subroutine threshold_goal_solve

    !> An h level: factor K, form the contact blocks, solve the pencil, estimate both
    !> thresholds and the collision onsets; the row and each side's bar over the levels.
    subroutine solve_h_level(this, scn, refiner, level, loop_start, timings, stat)
        class(threshold_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(cholesky_t) :: chol
        type(reduced_blocks_t) :: blocks
        type(critical_set_t) :: set
        type(eigen_result_t) :: beside(2)
        real(wp), allocatable :: u(:, :)
        real(wp) :: start
        real(wp), allocatable :: nearest(:)
        integer :: onset(2)
        type(kept_level_t) :: kept

        call keep_level(this, .false., kept)
        associate (prob => level%prob)
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
            if (stat%ok() .and. any(onset > 0)) call collision_spectra(scn, prob, &
                this%options, chol, blocks, set, onset, nearest, beside, stat)
            call chol%free()
            if (stat%ok()) call estimate_threshold_errors(prob, this%thr, u, &
                ENRICHED_CONTACT_MAX, this%est, stat)
            if (.not. stat%ok()) then   ! the last complete level's, for its report
                call restore_level(this, kept)
                return
            end if
            call blocks%free()
            call estimate_collisions(this, prob, set, onset, nearest, beside)
            call timings%add(PHASE_REDUCTION, wall_time() - start, ': thresholds and their '// &
                             'error estimates, level '//to_string(level%number))
            this%levels = [this%levels, level_row(level, this%thr, set, onset, loop_start)]
            associate (row => this%levels(size(this%levels)))
                row%estimated = this%est%computed
                row%error_estimate = abs(this%est%relative)
                row%collision_estimate = this%collision_estimate
            end associate
            call set_bars(this%levels, refiner, this%thr%roundoff)
            where (this%levels(size(this%levels))%found .and. &
                   this%levels(size(this%levels))%estimated) &
                this%est%bar = this%levels(size(this%levels))%error_bar
            this%prob = prob
        end associate
        call timings%note(level_line(this%levels(size(this%levels)), 'adapt level'))
    end subroutine solve_h_level

    !> An hp level: refused (`refused` says why) when its dense contact blocks would not fit
    !> the memory, else factored (the last level's factor kept for the final report), its
    !> contact blocks, thresholds, round-off and collision onsets; a row with the bars.
    subroutine solve_hp_level(this, scn, refiner, level, loop_start, timings, refused, stat)
        class(threshold_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable, intent(inout) :: refused
        type(status_t), intent(out) :: stat
        type(status_t) :: memory
        real(wp) :: start, phase(3)
        integer :: onset(2), p
        type(critical_set_t) :: previous
        type(kept_level_t) :: kept

        p = level%prob%contact%p()
        if (this%memory_given) then
            call check_contact_memory(scn, p, contact_peak_blocks(.false.), memory, this%memory)
        else
            call check_contact_memory(scn, p, contact_peak_blocks(.false.), memory)
        end if
        if (.not. memory%ok()) then
            refused = 'level '//to_string(level%number)//' has p = '//to_string(p)// &
                ' contact functions, whose dense blocks ('// &
                to_string(contact_peak_blocks(.false.))//' p x p doubles) need an estimated '// &
                short_real_text(contact_blocks_bytes(p, contact_peak_blocks(.false.))/1.0e9_wp)// &
                ' GB, more than the memory available'
            return
        end if
        if (size(this%levels) > 0) call keep_level(this, .true., kept)
        call make_hp_level(this, refiner, level, timings, stat, start, phase(1))
        associate (prob => this%prob, blocks => this%blocks, set => this%set)
            if (stat%ok()) call threshold_roundoff(prob%k, this%chol, prob%contact, &
                blocks%kt_nn, blocks%kt_nt, this%thr, stat)
            if (.not. stat%ok()) then
                call give_up()
                return
            end if
            phase(2) = wall_time()
            if (size(this%levels) == 0) then   ! the first level scans where it searches
                call onset_search(this%scan, this%restricted, this%thr, prob%dofs%n_free, &
                                  this%pencil_dofs, set, stat, state=this%scan_state)
            else   ! each side's onset followed from the level before's
                previous = set
                call onset_search(this%scan, this%restricted, this%thr, prob%dofs%n_free, &
                                  this%pencil_dofs, set, stat, previous, &
                                  carry_width(this%levels), this%scan_state)
            end if
            if (.not. stat%ok()) then
                call give_up()
                return
            end if
            call this%scan_state%note(this%restricted, this%thr%real_lambdas, set)
            call collision_onsets(set, onset)
            if (any(onset > 0)) call collision_roundoffs(prob%k, this%chol, prob%contact, &
                                                         this%restricted, set, stat, this%lift)
            if (.not. stat%ok()) then
                call give_up()
                return
            end if
            phase(3) = wall_time()
            call timings%add(PHASE_REDUCTION, phase(3) - start, ': contact blocks '// &
                             seconds_text(phase(1) - start)//' s, thresholds '// &
                             seconds_text(phase(2) - phase(1))//' s, '//search_words(set)// &
                             ' '//seconds_text(phase(3) - phase(2))//' s ('// &
                             to_string(set%n_evaluations)//' p x p solves at p = '// &
                             to_string(size(this%restricted%kt_nn, 1))//'), hp level '// &
                             to_string(level%number))
            this%levels = [this%levels, level_row(level, this%thr, set, onset, loop_start)]
        end associate
        associate (row => this%levels(size(this%levels)))
            row%layers = level%number
            row%p_min = minval(level%degree)
            row%p_max = maxval(level%degree)
        end associate
        call set_bars(this%levels, refiner, this%thr%roundoff)
        this%levels(size(this%levels))%time_s = wall_time() - loop_start
        call timings%note(level_line(this%levels(size(this%levels)), 'hp level'))

    contains

        !> A failed level: the last complete one back, whose report the run writes.
        subroutine give_up()
            if (size(this%levels) > 0) call restore_hp_level(this, refiner, kept, timings)
        end subroutine give_up

    end subroutine solve_hp_level

    !> What a level overwrites in the goal before it is complete: the last complete level's,
    !> kept to restore it when the next level fails (hp: its problem and space too, its
    !> factor and blocks are made again from them).
    subroutine keep_level(this, hp, kept)
        class(threshold_goal_t), intent(in) :: this
        logical, intent(in) :: hp
        type(kept_level_t), intent(out) :: kept
        kept%thr = this%thr
        kept%est = this%est
        kept%scan_state = this%scan_state
        kept%pencil_dofs = this%pencil_dofs
        kept%set = this%set
        if (.not. hp) return
        kept%prob = this%prob
        kept%space = this%space
    end subroutine keep_level

    !> The goal as `kept` had it (keep_level), before a level that failed.
    subroutine restore_level(this, kept)
        class(threshold_goal_t), intent(inout) :: this
        type(kept_level_t), intent(in) :: kept
        this%thr = kept%thr
        this%est = kept%est
        this%scan_state = kept%scan_state
        this%pencil_dofs = kept%pencil_dofs
        this%set = kept%set
    end subroutine restore_level

    !> hp: `level` made the goal's last: its problem and space, its factor (`factored`), its
    !> contact blocks and the pencil's values with the forces of half the degree (`thr`:
    !> restricted_thresholds, docs/thresholds.md; `blocks` stay whole for the spectrum at
    !> lambda). `begun` and `blocks_made`: the wall times around the contact blocks.
    subroutine make_hp_level(this, refiner, level, timings, stat, begun, blocks_made)
        class(threshold_goal_t), intent(inout) :: this
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: level
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp), intent(out) :: begun, blocks_made
        begun = wall_time()
        blocks_made = begun
        if (this%factored) call this%chol%free()
        this%factored = .false.
        this%prob = level%prob
        this%space = level%space
        call refiner%factor(level, this%chol, timings, stat)
        if (.not. stat%ok()) return
        this%factored = .true.
        begun = wall_time()
        call contact_flexibility(this%chol, this%prob%contact, this%blocks%kt_nn, &
                                 this%blocks%kt_nt, stat)
        blocks_made = wall_time()
        if (.not. stat%ok()) return
        this%blocks%mass = this%prob%contact%mass
        call restricted_thresholds(this%blocks, half_degree_forces(this%space, &
            this%prob%contact), this%thr, this%restricted, this%lift, stat)
    end subroutine make_hp_level

    !> hp: the last complete level back after the next one failed: its problem, space and
    !> thresholds as `kept` had them, its factor and contact blocks made again (the same
    !> solves, so the same numbers). Where that fails too, the goal has no level to report
    !> (`factored` false).
    subroutine restore_hp_level(this, refiner, kept, timings)
        class(threshold_goal_t), intent(inout) :: this
        class(refiner_t), intent(in) :: refiner
        type(kept_level_t), intent(in) :: kept
        type(timings_t), intent(inout) :: timings
        type(adapt_level_t) :: level
        type(status_t) :: stat
        real(wp) :: begun, blocks_made
        ! the failed level's blocks go before the last level's are made again (peak memory)
        call this%blocks%free()
        call this%restricted%free()
        if (allocated(this%lift)) deallocate (this%lift)
        level%number = this%levels(size(this%levels))%layers
        level%prob = kept%prob
        level%space = kept%space
        call make_hp_level(this, refiner, level, timings, stat, begun, blocks_made)
        ! the kept thresholds carry their round-off bounds, which the remake does not redo
        call restore_level(this, kept)
        if (stat%ok() .or. .not. this%factored) return
        call this%chol%free()
        this%factored = .false.
    end subroutine restore_hp_level

    !> How a level found its boundary points, for its progress line.
    function search_words(set) result(words)
        type(critical_set_t), intent(in) :: set
        character(len=:), allocatable :: words
        if (set%scan_contact == 0 .and. set%contact > 0) then
            words = 'the onsets followed'
        else if (set%scan_contact == 0) then
            words = 'no boundary search'
        else if (set%scan_contact == set%contact) then
            words = 'the boundary scanned'
        else
            words = 'the boundary carried from p = '//to_string(set%scan_contact)
        end if
    end function search_words

    !> The row of `level` with its thresholds `thr` and collision onsets (`onset`, in `set`).
    type(threshold_level_t) function level_row(level, thr, set, onset, loop_start) result(row)
        type(adapt_level_t), intent(in) :: level
        type(thresholds_t), intent(in) :: thr
        type(critical_set_t), intent(in) :: set
        integer, intent(in) :: onset(2)
        real(wp), intent(in) :: loop_start
        row%level = level%number
        row%n_dofs = level%prob%dofs%n_free
        row%n_contact = level%prob%contact%p()
        row%n_cells = level%prob%mesh%n_cells()
        row%found = thr%found
        row%lambda = thr%lambda
        row%residual = thr%residual
        row%roundoff = thr%roundoff
        row%collision = onset > 0
        where (row%collision) row%collision_lambda = set%points(max(onset, 1))%lambda
        where (row%collision) row%collision_roundoff = set%points(max(onset, 1))%roundoff
        row%time_s = wall_time() - loop_start
    end function level_row

    !> After `level`: each side its own target (judge_sides); hp first notes the profiles
    !> of the level's vectors, which the report follows over the levels (track_moving).
    subroutine threshold_goal_judge(this, refiner, level, tolerance)
        class(threshold_goal_t), intent(inout) :: this
        class(refiner_t), intent(in) :: refiner
        integer, intent(in) :: level
        real(wp), intent(in) :: tolerance
        call note_profiles(this)
        call judge_sides(this, refiner%estimated(), level, tolerance)
    end subroutine threshold_goal_judge

    !> The profiles of the last level's vectors (its problem, space and thresholds are still
    !> in `this`), which the report follows over the levels (track_moving), from the vertex
    !> functions' forces (hp: those below the space's vertex count; h: the contact nodes at
    !> an end of a contact edge).
    subroutine note_profiles(this)
        class(threshold_goal_t), intent(inout) :: this
        logical, allocatable :: vertex(:)
        integer :: side, a
        if (size(this%levels) == 0 .or. .not. allocated(this%thr%vectors)) return
        call know_ends(this)
        associate (row => this%levels(size(this%levels)), prob => this%prob)
            if (this%space%n_vertices > 0) then
                vertex = prob%contact%nodes <= this%space%n_vertices
            else
                vertex = [(any(prob%mesh%edges(1:2, :) == prob%contact%nodes(a)), &
                           a=1, size(prob%contact%nodes))]
            end if
            do side = SIDE_PLUS, SIDE_MINUS
                if (.not. this%thr%found(side)) cycle
                associate (value => level_profile(prob, this%ends, vertex, this%thr%lambda(side), &
                           this%thr%vectors(:, side)))
                    row%profile(:, side) = value%profile
                    row%resolution = value%resolution
                end associate
            end do
        end associate
    end subroutine note_profiles

    !> The ends of Gamma_C, made once from the first level's problem (refinement, h or hp,
    !> keeps their points, angles and conditions), and per side whether its lambdas past an
    !> end's crossing lie there, and that crossing.
    subroutine know_ends(this)
        type(threshold_goal_t), intent(inout) :: this
        integer :: side
        if (this%ends_known) return
        this%ends = contact_ends(this%prob)
        do side = SIDE_PLUS, SIDE_MINUS
            call past_crossing_end(this%ends, this%prob%poisson, 0.0_wp, &
                                   this%past(:, side), this%crossing(:, side), &
                                   merge(1, -1, side == SIDE_PLUS))
        end do
        this%ends_known = .true.
    end subroutine know_ends

    !> What is known about each side of the last level that did not converge (its
    !> values followed over the levels by their profiles, where its vector sits, the wedge
    !> there), in `estimate`, and one warning per such side.
    subroutine track_moving(goal, out, estimate, warnings)
        type(threshold_goal_t), intent(in) :: goal
        type(adaptive_thresholds_t), intent(in) :: out
        type(threshold_estimate_t), intent(inout) :: estimate
        character(len=WARNING_LEN), allocatable, intent(inout) :: warnings(:)
        type(level_values_t), allocatable :: levels(:)
        type(contact_ends_t) :: ends
        integer :: side, i, k
        k = size(out%levels)
        if (k == 0) return
        ends = goal%ends   ! know_ends, at every judged level
        if (.not. goal%ends_known) ends = contact_ends(goal%prob)
        allocate (levels(k))
        do side = SIDE_PLUS, SIDE_MINUS
            if (goal%targets(side)%converged() .or. .not. out%levels(k)%found(side)) cycle
            do i = 1, k
                if (allocated(levels(i)%values)) deallocate (levels(i)%values)
                allocate (levels(i)%values(merge(1, 0, out%levels(i)%found(side))))
                if (.not. out%levels(i)%found(side)) cycle
                levels(i)%values(1)%lambda = out%levels(i)%lambda(side)
                levels(i)%values(1)%profile = out%levels(i)%profile(:, side)
                levels(i)%values(1)%resolution = out%levels(i)%resolution
            end do
            estimate%moving(side) = track_side(levels, ends, goal%prob%poisson, &
                                               max(out%levels(k)%roundoff(side), 0.0_wp))
            if (.not. estimate%moving(side)%known) cycle
            warnings = [character(len=WARNING_LEN) :: warnings, &
                        moving_words(trim(SIDE_LABELS(side)), estimate%moving(side))]
        end do
    end subroutine track_moving

    !> hp, once the loop ends: each side's goal with a bar at the last level `last` (its
    !> threshold, or its collision onset carried to the check's blocks as a level carries
    !> it) computed again on the same cells with every degree raised by one (hp_levels:
    !> check_level), folded into that side's bar (error_bar: checked_bar) and, for a side met
    !> at an earlier level, into that level's bar; each side is then judged again on its own
    !> (check_target; `reopen`: climb on). The check uses the levels' half-degree forces.
    subroutine threshold_goal_check(this, scn, start, refiner, last, tolerance, reopen, &
                                    timings, stat, built)
        class(threshold_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: start
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: last
        real(wp), intent(in) :: tolerance
        logical, intent(in) :: reopen
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        !> where present, the hp check level, its factor and contact blocks are kept in it
        type(built_check_t), intent(inout), target, optional :: built
        type(adapt_level_t), target :: own_check
        type(adapt_level_t), pointer :: check
        type(cholesky_t), target :: own_chol
        type(cholesky_t), pointer :: chol
        type(reduced_blocks_t) :: blocks, restricted
        type(thresholds_t) :: thr
        type(critical_set_t) :: set, carried
        real(wp), allocatable :: lift(:, :)
        real(wp) :: before(2), after(2), roundoff(2), value, moved(2), begin, check_roundoff(2), &
                    check_value(2)
        character(len=:), allocatable :: why, head
        integer :: side, onset(2), m
        logical :: has_check(2), tracked, none_met(2)
        real(wp) :: both

        if (size(this%levels) == 0) return
        begin = wall_time()
        none_met = [(this%targets(side)%met_absent(), side=SIDE_PLUS, SIDE_MINUS)]
        associate (row => this%levels(size(this%levels)))
            call goal_bars(row, this%thr%roundoff, before, roundoff)
            ! nothing to check: no bar (none yet, or nothing to meet) and no side met as 'none'
            if (all(before <= 0.0_wp) .and. .not. any(none_met)) return
            check => own_check
            chol => own_chol
            if (present(built)) then
                check => built%level
                chol => built%chol
            end if
            select type (refiner)
            class is (hp_refiner_t)
                call refiner%check_level(start, last, check, timings, stat)
            class is (h_refiner_t)
                call check_graded(this, scn, refiner, last, tolerance, reopen, timings, stat)
                return
            class default
                return
            end select
            if (stat%ok()) call refiner%factor(check, chol, timings, stat)
            if (.not. stat%ok()) return
            if (present(built)) then
                call contact_flexibility(chol, check%prob%contact, blocks%kt_nn, blocks%kt_nt, &
                                         stat, check%prob%k, built%share)
                if (stat%ok()) then
                    built%kt_nn = blocks%kt_nn
                    built%kt_nt = blocks%kt_nt
                    built%built = .true.
                end if
            else
                call contact_flexibility(chol, check%prob%contact, blocks%kt_nn, blocks%kt_nt, &
                                         stat)
            end if
            ! the same force space as the levels (half the degree): with equal-order forces
            ! the check would see the spurious values the levels no longer have
            blocks%mass = check%prob%contact%mass
            if (stat%ok()) call restricted_thresholds(blocks, &
                half_degree_forces(check%space, check%prob%contact), thr, restricted, lift, stat)
            if (stat%ok()) call threshold_roundoff(check%prob%k, chol, check%prob%contact, &
                                                   blocks%kt_nn, blocks%kt_nt, thr, stat)
            onset = 0
            if (stat%ok() .and. any(row%collision)) then
                ! the check needs the onsets alone: followed from the level's, as a level
                ! follows them (track_onsets), else the whole range carried
                tracked = .false.
                if (this%set%lambda_max > this%set%lambda_min) call track_onsets(restricted, &
                    this%set, thr, set, tracked, stat, carry_width(this%levels))
                if (stat%ok() .and. .not. tracked) then
                    carried = this%set
                    if (this%set%scan_contact == 0) call this%scan_state%coarse_set( &
                        this%scan, size(restricted%kt_nn, 1), carried, stat, this%set)
                    if (stat%ok()) call search_critical_set(restricted, this%scan, &
                        thr%real_lambdas, set, stat, carried, near=carry_width(this%levels))
                end if
                if (stat%ok()) call collision_onsets(set, onset)
                if (stat%ok() .and. any(onset > 0)) call collision_roundoffs(check%prob%k, &
                    chol, check%prob%contact, restricted, set, stat, lift)
            end if
            if (.not. (present(built) .and. stat%ok())) call chol%free()
            if (.not. stat%ok()) then
                if (present(built)) built%built = .false.
                stat%message = scn%name//': the check of hp level '//to_string(last%number)// &
                    ': '//stat%message
                return
            end if
            moved = -1.0_wp
            check_roundoff = 0.0_wp
            check_value = 0.0_wp
            has_check = .false.
            do side = SIDE_PLUS, SIDE_MINUS
                if (before(side) <= 0.0_wp) cycle
                if (row%collision(side)) then
                    value = row%collision_lambda(side)
                    has_check(side) = onset(side) > 0
                    if (has_check(side)) then
                        check_value(side) = set%points(onset(side))%lambda
                        check_roundoff(side) = max(set%points(onset(side))%roundoff, 0.0_wp)
                    end if
                    row%collision_bar(side) = checked_bar(before(side), value, &
                        has_check(side), check_value(side), roundoff(side), check_roundoff(side))
                else
                    value = row%lambda(side)
                    has_check(side) = thr%found(side)
                    if (has_check(side)) then
                        check_value(side) = thr%lambda(side)
                        check_roundoff(side) = max(thr%roundoff(side), 0.0_wp)
                    end if
                    row%error_bar(side) = checked_bar(before(side), value, has_check(side), &
                        check_value(side), roundoff(side), check_roundoff(side))
                end if
                if (has_check(side)) moved(side) = abs(check_value(side) - value)/abs(value)
            end do
            call goal_bars(row, this%thr%roundoff, after, roundoff)
            do side = SIDE_PLUS, SIDE_MINUS
                if (before(side) <= 0.0_wp) cycle
                ! a side met at an earlier level is quoted with that level's value: the check
                ! bounds that value too, and its checked bar is the one judged
                m = this%met_row(side)
                if (m > 0 .and. m < size(this%levels) .and. has_check(side)) then
                    associate (met => this%levels(m))
                        met%error_bar(side) = checked_bar(met%error_bar(side), &
                            met%lambda(side), .true., check_value(side), &
                            max(met%roundoff(side), 0.0_wp), check_roundoff(side))
                        after(side) = met%error_bar(side)
                    end associate
                end if
                head = check_words(check%prob%dofs%n_free)
                if (moved(side) >= 0.0_wp) then
                    why = head//' moves the '//trim(SIDE_NAMES(side))//' side by '// &
                        short_real_text(moved(side))//' (relative): error bar '// &
                        short_real_text(after(side))//' at '//to_string(row%n_dofs)//' dofs'
                else
                    why = head//' does not find the '//trim(SIDE_NAMES(side))//' side''s '// &
                        'goal, which has no error bar'
                    after(side) = -1.0_wp
                end if
                call timings%note('hp check of level '//to_string(last%number)//': '//why// &
                                  ', '//seconds_text(wall_time() - begin)//' s')
                if (len(refiner%cap_words(last)) > 0) why = why//'; '//refiner%cap_words(last)
                both = max(roundoff(side), 0.0_wp) + check_roundoff(side)
                if (settled_check_fails(this%targets(side), tolerance, after(side), both) .and. &
                    settled(this%levels, side, both, tolerance)) then
                    ! more levels cannot take it within the tolerance: at the floor, not reopened
                    call this%targets(side)%finish(TARGET_FLOOR, trim(SIDE_LABELS(side))// &
                        ': '//floor_outcome(tolerance, both, after(side), &
                                            to_string(row%n_dofs)))
                else
                    call check_target(this%targets(side), tolerance, before(side), &
                                      after(side), both, reopen .and. row%level == last%number, &
                                      trim(SIDE_LABELS(side))//': '//why)
                end if
                if (this%targets(side)%active()) this%met_row(side) = 0
            end do
            call check_none_sides(this%targets, none_met, thr, check%prob%dofs%n_free, &
                                  last%number, timings)
        end associate
    end subroutine threshold_goal_check

    !> hp: each side met as 'none' (`none_met`) is confirmed only where the check of the last
    !> level `level` (`thr`: its pencil on `dofs` free dofs, every degree raised by one) has
    !> no real pencil value on that side either. The levels' changes cannot bound a value
    !> they never had: one the check finds appears with the degree, so the side stops as not
    !> converged (exit 8), its outcome naming the value.
    subroutine check_none_sides(targets, none_met, thr, dofs, level, timings)
        type(adapt_target_t), intent(inout) :: targets(:)
        logical, intent(in) :: none_met(2)
        type(thresholds_t), intent(in) :: thr
        integer, intent(in) :: dofs, level
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable :: head, words
        integer :: side
        head = check_words(dofs, level)
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. none_met(side)) cycle
            if (.not. thr%found(side)) then
                call timings%note(head//' finds no '//trim(SIDE_LABELS(side))//' either')
                cycle
            end if
            words = targets(side)%outcome//', but '//head//' finds '// &
                trim(SIDE_LABELS(side))//' = '//short_real_text(thr%lambda(side), 6)// &
                ': it appears with the degree, not converged'
            call timings%note(words)
            call targets(side)%finish(TARGET_STOPPED, words)
        end do
    end subroutine check_none_sides

    !> h, once the loop ends: each side met or at the floor whose value lies past the crossing
    !> of an end of Gamma_C (moving_side: past_crossing_end), solved again on the last mesh
    !> graded toward those ends (h_refiner: graded_level, the cells there bisected
    !> GRADE_PASSES times more; one factor for both sides), the change folded into its bar
    !> (error_bar: checked_bar) and the side judged again (check_target; `reopen`: it climbs
    !> on, the next level graded toward those ends). Past a crossing the mode can gather
    !> below the cells' scale at that end, where the estimate one degree higher on the same
    !> cells does not look (docs/thresholds.md, "Past a crossing"); elsewhere nothing is
    !> solved.
    subroutine check_graded(this, scn, refiner, last, tolerance, reopen, timings, stat)
        class(threshold_goal_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        class(h_refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: last
        real(wp), intent(in) :: tolerance
        logical, intent(in) :: reopen
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(adapt_level_t) :: check
        type(cholesky_t) :: chol
        type(thresholds_t) :: thr
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :)
        real(wp) :: before(2), after(2), roundoff(2), crossing(2, 2), begin, moved, both
        logical :: past(2, 2)
        character(len=:), allocatable :: why, ends
        integer :: side, e

        begin = wall_time()
        past = .false.
        crossing = 0.0_wp
        associate (row => this%levels(size(this%levels)))
            call goal_bars(row, this%thr%roundoff, before, roundoff)
            do side = SIDE_PLUS, SIDE_MINUS
                if (.not. (this%targets(side)%converged() .or. &
                           this%targets(side)%floor_reached())) cycle
                if (.not. row%found(side) .or. row%collision(side) .or. before(side) < 0.0_wp) &
                    cycle
                call past_crossing_end(this%ends, this%prob%poisson, row%lambda(side), &
                                       past(:, side), crossing(:, side))
            end do
            if (.not. any(past)) return
            call refiner%graded_level(last, this%ends%point(:, pack([1, 2], any(past, 2))), &
                                      check, timings, stat)
            if (stat%ok()) call factor_with_contact_blocks(scn, check%prob, chol, kt_nn, &
                                                           kt_nt, timings, stat)
            if (stat%ok()) call pencil_thresholds(kt_nn, kt_nt, thr, stat)
            if (stat%ok()) call threshold_roundoff(check%prob%k, chol, check%prob%contact, &
                                                   kt_nn, kt_nt, thr, stat)
            call chol%free()
            if (.not. stat%ok()) return
            do side = SIDE_PLUS, SIDE_MINUS
                if (.not. any(past(:, side))) cycle
                after(side) = checked_bar(before(side), row%lambda(side), thr%found(side), &
                                          thr%lambda(side), roundoff(side), &
                                          max(thr%roundoff(side), 0.0_wp))
                row%error_bar(side) = after(side)
                this%est%bar(side) = after(side)
                ends = ''
                do e = 1, 2
                    if (.not. past(e, side)) cycle
                    if (len(ends) > 0) ends = ends//' and '
                    ends = ends//end_words(this%ends, e)//', past its crossing '// &
                        short_real_text(crossing(e, side))
                end do
                why = trim(SIDE_LABELS(side))//': the check on the last mesh graded toward '// &
                    ends//' ('//to_string(check%prob%dofs%n_free)//' dofs)'
                if (thr%found(side)) then
                    moved = abs(thr%lambda(side) - row%lambda(side))/abs(row%lambda(side))
                    why = why//' moves lambda by '//short_real_text(moved)// &
                        ' (relative): error bar '//short_real_text(after(side))//' at '// &
                        to_string(row%n_dofs)//' dofs'
                else
                    why = why//' has no value on that side: no error bar'
                end if
                call timings%note('h check of level '//to_string(last%number)//': '//why// &
                                  ', '//seconds_text(wall_time() - begin)//' s')
                both = max(roundoff(side), 0.0_wp) + max(thr%roundoff(side), 0.0_wp)
                call check_target(this%targets(side), tolerance, before(side), after(side), &
                                  both, reopen, why)
                ! still met: its outcome quotes the bar the check made
                if (this%targets(side)%converged() .and. after(side) > before(side)) &
                    call this%targets(side)%finish(TARGET_MET, trim(SIDE_LABELS(side))// &
                        ': tolerance '//short_real_text(tolerance)//' met at level '// &
                        to_string(row%level)//': error bar '//this%bar_text(side)// &
                        ', with the check graded toward its end')
                ! climbing on: the next level grades those ends too (h_refiner: grade_toward)
                if (this%targets(side)%active()) call grade_ends(this, past(:, side))
            end do
        end associate
    end subroutine check_graded

    !> The ends of Gamma_C marked in `ends` added to the points the next h level grades
    !> toward (h_refiner: grade_toward).
    subroutine grade_ends(this, ends)
        class(threshold_goal_t), intent(inout) :: this
        logical, intent(in) :: ends(2)
        this%grade = reshape([this%grade, this%ends%point(:, pack([1, 2], ends))], &
                             [2, size(this%grade, 2) + count(ends)])
    end subroutine grade_ends

    !> Whether the check (bar `bar`, round-off part `roundoff`) takes target `t`, met or at
    !> the floor, off what it was (adapt_driver: check_target's test).
    logical function settled_check_fails(t, tolerance, bar, roundoff) result(fails)
        type(adapt_target_t), intent(in) :: t
        real(wp), intent(in) :: tolerance, bar, roundoff
        fails = .false.
        if (bar < 0.0_wp) return
        if (t%converged()) fails = bar > tolerance
        if (t%floor_reached()) fails = .not. floor_reached(bar, roundoff)
    end function settled_check_fails

    !> Each side is its own target, judged on its own goal (its collision onset where it
    !> has one, else its threshold), the same rule on h and hp levels (`estimated`: h, whose
    !> levels carry their own estimate): met within the tolerance once the goal has a value
    !> at each of the last levels (h: two, the level before confirms the bar; hp: three, its
    !> bar rests on the changes between them), stopped where its goal stalls (hp) or has no
    !> estimate (h), at the floor where round-off dominates its bar (hp: or where its last
    !> changes are within their round-off bounds, `settled`); a side without a value at the
    !> last NONE_LEVELS levels (h: over which the dofs at least doubled, as an h level adds
    !> a fraction of them: adapt_driver's absence_confirmed, an eigen lambda's rule for 'no
    !> positive mu' too) is met as 'none'. A side whose value appears or vanishes
    !> between levels has no bar (series_bar needs it on consecutive levels) and stays
    !> active, so it ends at a limit, named, never as met; one whose value has vanished for
    !> as long as 'none' needs is stopped then (h: whose limit is the memory; hp too). A
    !> side met, with a value or as 'none', whose value then vanishes or appears at a later
    !> level is stopped as not converging (exit 8). On h levels a side met with a value is
    !> judged again at every later level (each re-estimates it on a finer mesh, and the
    !> report quotes the last): above the tolerance there it is active again. One side never
    !> stops or fails the other; where neither side has a value at an h level, there is
    !> nothing to mark and both stop, each saying so.
    subroutine judge_sides(this, estimated, level, tolerance)
        type(threshold_goal_t), intent(inout) :: this
        logical, intent(in) :: estimated
        integer, intent(in) :: level   !! the last level's number
        real(wp), intent(in) :: tolerance
        real(wp) :: bar(2), roundoff(2)
        integer :: side, k, i, present_levels, before, past_end
        logical :: absent, present_all, has
        k = size(this%levels)
        present_levels = merge(2, 3, estimated)
        call goal_bars(this%levels(k), this%thr%roundoff, bar, roundoff)
        call know_ends(this)
        if (allocated(this%grade)) deallocate (this%grade)
        allocate (this%grade(2, 0))
        do side = SIDE_PLUS, SIDE_MINUS
            associate (last => this%levels(k), t => this%targets(side))
                has = last%found(side) .or. last%collision(side)
                ! h: a side without a value grades the next level toward the ends past whose
                ! crossing its lambdas lie (uniform levels cannot see what concentrates there)
                if (estimated .and. .not. has .and. t%active()) &
                    call grade_ends(this, this%past(:, side))
                if (t%converged()) then
                    ! met at an earlier level: it must keep (or keep lacking) its value
                    if (has .neqv. t%met_absent()) then
                        if (.not. (estimated .and. has)) cycle
                        ! h: its estimate on this finer mesh is the one reported
                        if (bar(side) >= 0.0_wp .and. bar(side) <= tolerance) then
                            call met(side)
                            cycle
                        end if
                        call t%finish(TARGET_ACTIVE, '')
                    else
                        call t%finish(TARGET_STOPPED, trim(SIDE_LABELS(side))//': '// &
                            trim(merge('a value ', 'no value', has))//' at level '// &
                            to_string(level)//' after '// &
                            t%outcome(len_trim(SIDE_LABELS(side)) + 3:)//': it '// &
                            trim(merge('appears ', 'vanishes', has))// &
                            ' with the mesh, not converged')
                        this%met_row(side) = 0
                        cycle
                    end if
                end if
                if (.not. t%active()) cycle
                absent = absence_confirmed(side_has(side), [(this%levels(i)%n_dofs, i=1, k)], &
                                           estimated)
                present_all = k >= present_levels
                do i = max(1, k - present_levels + 1), k
                    present_all = present_all .and. (this%levels(i)%found(side) .or. &
                                                     this%levels(i)%collision(side))
                end do
                if (.not. has) then
                    if (.not. absent) cycle
                    ! a value at an earlier level that has vanished is no 'none' (h and hp)
                    before = findloc(side_has(side), .true., 1, back=.true.)
                    past_end = findloc(this%past(:, side), .true., 1)
                    if (before == 0 .and. past_end > 0) then
                        ! no level sees a value that concentrates at that end below its finest
                        ! cells: h levels are uniform there, hp ones see three layers more
                        ! (seed 43 body 17: none at hp levels 1 to 3 from a mesh of size L/2,
                        ! a value past the crossing from one of size L/4; docs/thresholds.md)
                        call t%finish(TARGET_STOPPED, trim(SIDE_LABELS(side))//': no value '// &
                            'at '//trim(merge('h levels ', 'hp levels', estimated))//' '// &
                            to_string(this%levels(merge(absent_since(side_has(side)), &
                                k - NONE_LEVELS + 1, estimated))%level)//' to '// &
                            to_string(level)//', '// &
                            unconfirmed_words(this%ends, past_end, 'its lambdas beyond '// &
                            short_real_text(this%crossing(past_end, side))//' lie past '// &
                            'that end''s crossing', estimated))
                    else if (before == 0) then
                        call t%finish(TARGET_MET, SIDE_LABELS(side)//': none at '// &
                            trim(merge('h levels ', 'hp levels', estimated))//' '// &
                            to_string(this%levels(merge(absent_since(side_has(side)), &
                                k - NONE_LEVELS + 1, estimated))%level)//' to '// &
                            to_string(level), absent=.true.)
                    else
                        call t%finish(TARGET_STOPPED, trim(SIDE_LABELS(side))//': no value at '// &
                            trim(merge('h levels ', 'hp levels', estimated))//' '// &
                            to_string(this%levels(before + 1)%level)//' to '// &
                            to_string(level)//' after '//short_real_text(merge( &
                            this%levels(before)%collision_lambda(side), &
                            this%levels(before)%lambda(side), &
                            this%levels(before)%collision(side)), 6)//' at level '// &
                            to_string(this%levels(before)%level)//': it vanishes with the '// &
                            'mesh, not converged')
                    end if
                    cycle
                end if
                if (estimated .and. bar(side) < 0.0_wp) then
                    call t%finish(TARGET_STOPPED, trim(SIDE_LABELS(side))//': '// &
                        no_estimate_outcome(level, missing(this, side)))
                else if (last%stalled(side)) then
                    call t%finish(TARGET_STOPPED, trim(SIDE_LABELS(side))//': '// &
                        stall_outcome(tolerance, 'the '//trim(SIDE_NAMES(side))//' side'))
                else if (bar(side) < -0.5_wp .or. .not. present_all) then
                    cycle   ! no bar yet, or the value has appeared too recently
                else if (bar(side) <= tolerance) then
                    call met(side)
                else if (floor_reached(bar(side), roundoff(side)) .or. (.not. estimated .and. &
                         settled(this%levels, side, roundoff(side), tolerance))) then
                    call t%finish(TARGET_FLOOR, trim(SIDE_LABELS(side))//': '// &
                        floor_outcome(tolerance, roundoff(side), bar(side), &
                                      to_string(last%n_dofs)))
                end if
            end associate
        end do

    contains

        !> Per level: whether side `s` has a value (a pencil value or a collision onset).
        function side_has(s) result(has_value)
            integer, intent(in) :: s
            logical :: has_value(k)
            integer :: j
            has_value = [(this%levels(j)%found(s) .or. this%levels(j)%collision(s), j=1, k)]
        end function side_has

        !> Side `s` met at the last level; hp quotes that level's value (met_row).
        subroutine met(s)
            integer, intent(in) :: s
            call this%targets(s)%finish(TARGET_MET, trim(SIDE_LABELS(s))//': tolerance '// &
                short_real_text(tolerance)//' met at level '// &
                to_string(level)//': error bar '//this%bar_text(s))
            if (.not. estimated .and. .not. this%levels(k)%collision(s)) this%met_row(s) = k
        end subroutine met
    end subroutine judge_sides

    !> The bar of side `i`'s goal at the last level, as outcomes quote it ('none' where it
    !> has no value or no bar) at its dofs.
    function threshold_goal_bar_text(this, i) result(text)
        class(threshold_goal_t), intent(in) :: this
        integer, intent(in) :: i
        character(len=:), allocatable :: text
        real(wp) :: bar(2), roundoff(2)
        text = 'none'
        if (size(this%levels) == 0 .or. i < 1) return
        associate (last => this%levels(size(this%levels)))
            call goal_bars(last, this%thr%roundoff, bar, roundoff)
            if (bar(i) >= -0.5_wp .and. (last%found(i) .or. last%collision(i))) &
                text = short_real_text(bar(i))
            text = text//' at '//to_string(last%n_dofs)//' dofs'
        end associate
    end function threshold_goal_bar_text

    !> hp: the report of the last level solved, on its factor and contact blocks (still in
    !> `goal`): the spectrum at `lambda`, the thresholds confirmed, the boundary of the
    !> positive set, and the hp bars as the estimate of the thresholds and of the collision
    !> onsets.
    subroutine report_last_level(scn, goal, out, lambda, res, timings, stat)
        type(scene_t), intent(in) :: scn
        type(threshold_goal_t), intent(inout) :: goal
        type(adaptive_thresholds_t), intent(in) :: out
        real(wp), intent(in) :: lambda
        type(threshold_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp) :: begin
        integer :: side, i, k, m
        type(critical_set_t) :: coarse, followed
        logical :: tracked
        real(wp) :: spectrum
        begin = wall_time()
        associate (prob => goal%prob, blocks => goal%blocks, thr => goal%thr)
            res%eigen%solver = choose_solver(goal%options, prob%contact%p())
            res%eigen%lambda = lambda
            call assemble_b(prob%contact, prob%dofs%n_free, res%eigen%lambda, res%eigen%b, stat)
            if (stat%ok()) call eigen_with_factor(scn, prob, goal%options, goal%chol, res%eigen, &
                                                  timings, stat, blocks%kt_nn, blocks%kt_nt)
            res%thresholds = thr
            if (.not. stat%ok()) return
            spectrum = wall_time()
            if (goal%set%scan_contact > 0) then   ! the last level searched: its set stands
                call confirm_and_bound(scn, prob, lambda, goal%scan, goal%chol, &
                                       goal%restricted, res%thresholds, res%set, stat, &
                                       known=goal%set, lift=goal%lift)
            else
                ! the onsets the last level followed are located on these very blocks
                call goal%scan_state%coarse_set(goal%scan, size(goal%restricted%kt_nn, 1), &
                                                coarse, stat, goal%set, here=.true.)
                ! a last level that followed nothing: its onsets first, from the coarse ones
                if (stat%ok() .and. goal%set%contact == 0 .and. coarse%scan_contact > 0) then
                    call track_onsets(goal%restricted, coarse, thr, followed, tracked, stat)
                    if (stat%ok() .and. tracked) call merge_onsets(coarse, followed, here=.true.)
                    coarse%n_evaluations = coarse%n_evaluations + followed%n_evaluations
                end if
                if (stat%ok()) call confirm_and_bound(scn, prob, lambda, goal%scan, goal%chol, &
                    goal%restricted, res%thresholds, res%set, stat, coarse, lift=goal%lift, &
                    near=TRACKED_WIDTH)
            end if
            if (.not. stat%ok()) return
            call timings%note('thresholds of the last level: the spectrum at lambda '// &
                seconds_text(spectrum - begin)//' s, the confirmations and '// &
                search_words(res%set)//' '//seconds_text(wall_time() - spectrum)//' s ('// &
                to_string(res%set%n_evaluations)//' p x p solves at p = '// &
                to_string(size(goal%restricted%kt_nn, 1))//')')
            k = size(out%levels)
            res%estimate%method = HP_ESTIMATE
            do side = SIDE_PLUS, SIDE_MINUS
                if (.not. thr%found(side)) cycle
                ! a side met at an earlier level is quoted with that level's value and bar:
                ! later levels grade its end further, and its round-off can only grow there
                m = k
                if (goal%met_row(side) > 0) m = goal%met_row(side)
                associate (row => out%levels(m))
                    if (row%stalled(side)) then
                        res%estimate%skipped(side) = 'none: the '//trim(SIDE_NAMES(side))// &
                            ' side does not converge under hp refinement'
                        cycle
                    end if
                    if (row%error_bar(side) < 0.0_wp .or. m == 1) then
                        res%estimate%skipped(side) = 'none at the first hp level'
                        cycle
                    end if
                    if (.not. goal%targets(side)%converged()) then   ! its own reason
                        res%estimate%skipped(side) = 'none: '// &
                            labelled(side, goal%targets(side)%outcome)
                        cycle
                    end if
                    res%estimate%computed(side) = .true.
                    res%estimate%bar(side) = row%error_bar(side)
                    res%estimate%relative(side) = row%error_estimate(side)
                    res%estimate%lambda_enriched(side) = out%levels(m - 1)%lambda(side)
                    res%estimate%met_level(side) = row%level
                    ! the boundary point at this threshold carries its value and bar
                    do i = 1, size(res%set%points)
                        if (res%set%points(i)%mechanism == MECHANISM_PENCIL .and. &
                            abs(res%set%points(i)%lambda - thr%lambda(side)) <= &
                            1.0e-12_wp*abs(thr%lambda(side))) then
                            res%set%points(i)%lambda = row%lambda(side)
                            res%set%points(i)%error_bar = row%error_bar(side)
                        end if
                    end do
                    if (m < k) then
                        res%thresholds%lambda(side) = row%lambda(side)
                        res%thresholds%residual(side) = row%residual(side)
                        res%thresholds%roundoff(side) = row%roundoff(side)
                    end if
                end associate
            end do
        end associate
        call apply_collision_bars(out, res%set)
        res%time_threshold = wall_time() - begin
        call timings%note('thresholds '//seconds_text(res%time_threshold)//' s')
    end subroutine report_last_level

    !> Each side's bars at the last of `levels`, from its threshold and its collision onset
    !> over the levels (refiner_t: series_bar): h, over the levels where that side was found
    !> and estimated (the threshold) or where its onset was a collision; hp, plus the
    !> round-off part `roundoff` (of the last level's thresholds), the change to the level
    !> before as the estimate, and a side whose goal (its collision onset where it has one,
    !> else its threshold) has stalled stays stalled, with no bar, at every later level.
    subroutine set_bars(levels, refiner, roundoff)
        type(threshold_level_t), intent(inout) :: levels(:)
        class(refiner_t), intent(in) :: refiner
        real(wp), intent(in) :: roundoff(2)
        real(wp) :: values(size(levels)), estimates(size(levels)), change, bar
        logical :: have(size(levels)), stalled(2)
        integer :: dofs(size(levels)), k, side, i
        k = size(levels)
        do i = 1, k
            dofs(i) = levels(i)%n_dofs
        end do
        do side = SIDE_PLUS, SIDE_MINUS
            ! plain arrays: components of a derived-type array would make temporaries
            do i = 1, k
                have(i) = levels(i)%found(side)
                values(i) = levels(i)%lambda(side)
                estimates(i) = -1.0_wp
                if (levels(i)%found(side) .and. levels(i)%estimated(side)) &
                    estimates(i) = levels(i)%error_estimate(side)
            end do
            stalled = .false.
            if (.not. refiner%estimated() .or. (levels(k)%found(side) .and. &
                                                levels(k)%estimated(side))) then
                call refiner%series_bar(have, values, estimates, dofs, roundoff(side), bar, &
                                        change, stalled(1))
                levels(k)%error_bar(side) = bar
                if (.not. refiner%estimated()) then
                    levels(k)%estimated(side) = bar >= 0.0_wp
                    if (levels(k)%estimated(side)) levels(k)%error_estimate(side) = change
                end if
            end if
            do i = 1, k
                have(i) = levels(i)%collision(side)
                values(i) = levels(i)%collision_lambda(side)
                estimates(i) = -1.0_wp
                if (levels(i)%collision(side)) estimates(i) = levels(i)%collision_estimate(side)
            end do
            if (.not. refiner%estimated() .or. levels(k)%collision(side)) then
                call refiner%series_bar(have, values, estimates, dofs, &
                                        levels(k)%collision_roundoff(side), bar, change, &
                                        stalled(2))
                levels(k)%collision_bar(side) = bar
                if (.not. refiner%estimated()) levels(k)%collision_estimate(side) = change
            end if
            if (refiner%estimated()) cycle
            associate (row => levels(k))
                row%stalled(side) = merge(stalled(2), stalled(1), row%collision(side))
                if (k > 1) row%stalled(side) = row%stalled(side) .or. levels(k - 1)%stalled(side)
                if (row%stalled(side)) then
                    row%error_bar(side) = -1.0_wp
                    row%estimated(side) = .false.
                    row%collision_bar(side) = -1.0_wp
                end if
            end associate
        end do
    end subroutine set_bars

    !> The boundary of the positive set (find_critical_set over the analysis' scan) on a
    !> level of `n_free` dofs, searched only where a side may have a collision onset: where
    !> it has no pencil eigenvalue, or a positive mu just inside it (NOT confirmed). Where
    !> both are confirmed `set` stays empty and the thresholds are the goals, and that check
    !> (two dense p x p eigen-solves) is made again only once the dofs have doubled since
    !> `pencil_dofs`, the last level it held on: at every level the check cost as much as
    !> the rest of input/threshold_adapt.nml (scan: twice that), for an answer that does
    !> not change there. With `previous` (the set a coarser level found, if it searched),
    !> its points are carried (carry_critical_set) unless the structure differs here. With
    !> `state` (hp), `previous` is the level before's set, whose onsets are followed alone
    !> (track_onsets: the bars need no more), and where that fails, the set of the last level
    !> that searched is carried, else, the first time a level searches, the scan of a level
    !> of at most SCAN_CONTACT_MAX contact functions (coarse_set): a scan of a late level
    !> costs a hundred solves at its p (4.4 of the 13 s of the slanted top to 1e-8,
    !> scripts/bench/bench_thresholds.sh). The last level's whole range is then carried for
    !> the report from these onsets (coarse_set, `tracked`).
    subroutine onset_search(scan, blocks, thr, n_free, pencil_dofs, set, stat, previous, near, &
                            state)
        real(wp), intent(in) :: scan(:)   !! the lambdas of the search
        type(reduced_blocks_t), intent(in) :: blocks
        type(thresholds_t), intent(in) :: thr
        integer, intent(in) :: n_free
        integer, intent(inout) :: pencil_dofs
        type(critical_set_t), intent(out) :: set
        type(status_t), intent(out) :: stat
        type(critical_set_t), intent(in), optional :: previous
        real(wp), intent(in), optional :: near   !! search_critical_set's
        type(coarse_scan_t), intent(in), optional :: state
        type(critical_set_t) :: coarse
        real(wp) :: mu, inside
        logical :: found, search, tracked
        integer :: side, n_positive, tried

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
        if (.not. search) return
        if (present(state)) then
            tried = 0
            if (present(previous)) then
                if (previous%lambda_max > previous%lambda_min) then
                    call track_onsets(blocks, previous, thr, set, tracked, stat, near)
                else   ! no level searched: both onsets were their pencil values
                    call track_onsets(blocks, pencil_onsets(thr, scan), thr, set, tracked, &
                                      stat, near)
                end if
                if (.not. stat%ok() .or. tracked) return
                tried = set%n_evaluations
            end if
            call state%coarse_set(scan, size(blocks%kt_nn, 1), coarse, stat)
            if (stat%ok()) call search_critical_set(blocks, scan, thr%real_lambdas, set, stat, &
                                                    coarse, near=near)
            if (stat%ok()) set%n_evaluations = set%n_evaluations + tried
            if (stat%ok() .and. state%searched%scan_contact == 0) &
                set%n_evaluations = set%n_evaluations + coarse%n_evaluations
        else
            call search_critical_set(blocks, scan, thr%real_lambdas, set, stat, previous, &
                                     near=near)
        end if
    end subroutine onset_search

    !> Both sides' onsets as the pencil values of `thr` (every side found), over the range
    !> of `scan`: where track_onsets starts when no level has searched.
    type(critical_set_t) function pencil_onsets(thr, scan) result(set)
        type(thresholds_t), intent(in) :: thr
        real(wp), intent(in) :: scan(:)
        integer :: side
        set%lambda_min = minval(scan)
        set%lambda_max = maxval(scan)
        allocate (set%points(0))
        do side = SIDE_MINUS, SIDE_PLUS, SIDE_PLUS - SIDE_MINUS
            if (.not. thr%found(side)) cycle
            set%points = [set%points, boundary_point_t(lambda=thr%lambda(side), &
                          mechanism=MECHANISM_PENCIL, appears=side == SIDE_PLUS)]
        end do
    end function pencil_onsets

    !> hp: how near (relative) the previous level's collision points are expected on the
    !> next level: 8 times the largest relative change between the last two levels (the
    !> next change is smaller where they converge), at least 1e-9; 0 where no level has had
    !> two in a row (carry_critical_set then brackets as it always did).
    pure real(wp) function carry_width(levels)
        type(threshold_level_t), intent(in) :: levels(:)
        integer :: side, k
        carry_width = 0.0_wp
        k = size(levels)
        if (k < 2) return
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. (levels(k)%collision(side) .and. levels(k - 1)%collision(side))) cycle
            carry_width = max(carry_width, 8.0_wp*abs(levels(k)%collision_lambda(side) - &
                levels(k - 1)%collision_lambda(side))/abs(levels(k)%collision_lambda(side)), &
                1.0e-9_wp)
        end do
    end function carry_width

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
                real(beside(side)%spec%mu(lowest), wp), &
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
            if (row%roundoff(side) >= 0.0_wp) line = line//' [roundoff '// &
                short_real_text(row%roundoff(side))//']'
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

    !> hp: the goal of `side` (its collision onset where it has one, else its threshold) has
    !> settled to round-off at the last of `levels` (error_bar: settled_floor), with
    !> `roundoff` the round-off part of the bar judged: the same kind of goal at the last
    !> three levels, its last two changes each within that level's round-off bound.
    pure logical function settled(levels, side, roundoff, tolerance)
        type(threshold_level_t), intent(in) :: levels(:)
        integer, intent(in) :: side
        real(wp), intent(in) :: roundoff, tolerance
        real(wp) :: values(3), roundoffs(3)
        integer :: k, j
        logical :: collision
        settled = .false.
        k = size(levels)
        if (k < 3) return
        collision = levels(k)%collision(side)
        do j = 1, 3
            associate (row => levels(k - 3 + j))
                if (collision .neqv. row%collision(side)) return
                if (collision) then
                    values(j) = row%collision_lambda(side)
                    roundoffs(j) = row%collision_roundoff(side)
                else
                    if (.not. row%found(side)) return
                    values(j) = row%lambda(side)
                    roundoffs(j) = row%roundoff(side)
                end if
            end associate
        end do
        settled = settled_floor(values, roundoffs, roundoff, tolerance)
    end function settled

    !> The union of the Doerfler sets of the sides still active (a side met, none, or
    !> stopped marks nothing). Where no active side has indicators at this level (its value
    !> has vanished, the other side is met) the sides that have them mark, and where none
    !> has, every cell is: the next level must differ, or it would repeat this one.
    function threshold_goal_mark(this, theta) result(marked)
        class(threshold_goal_t), intent(in) :: this
        real(wp), intent(in) :: theta
        integer, allocatable :: marked(:)
        logical, allocatable :: chosen(:)
        integer :: side, i

        allocate (chosen(size(this%collision_indicators, 1)), source=.false.)
        do side = SIDE_PLUS, SIDE_MINUS
            if (this%targets(side)%active()) call add_side(side)
        end do
        if (.not. any(chosen)) then
            do side = SIDE_PLUS, SIDE_MINUS
                call add_side(side)
            end do
        end if
        if (.not. any(chosen)) chosen = .true.
        marked = pack([(i, i=1, size(chosen))], chosen)

    contains

        !> The Doerfler set of side `s`'s indicators, where it has them.
        subroutine add_side(s)
            integer, intent(in) :: s
            if (this%levels(size(this%levels))%collision(s)) then
                if (this%collision_estimate(s) >= 0.0_wp) &
                    chosen(doerfler_marking(this%collision_indicators(:, s), theta)) = .true.
            else if (this%thr%found(s) .and. this%est%computed(s)) then
                chosen(doerfler_marking(this%est%indicators(:, s), theta)) = .true.
            end if
        end subroutine add_side
    end function threshold_goal_mark

    !> Why side `side`'s estimate is missing at the last h level.
    function missing(this, side) result(reason)
        type(threshold_goal_t), intent(in) :: this
        integer, intent(in) :: side
        character(len=:), allocatable :: reason
        if (len_trim(this%collision_skipped(side)) > 0) then
            reason = trim(this%collision_skipped(side))
        else
            reason = trim(this%est%skipped(side))
            if (len(reason) == 0) reason = 'no enrichment for these cells'
        end if
    end function missing

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
        type(noted_level_t), allocatable :: noted(:)
        integer :: n
        if (size(blocks%kt_nn, 1) <= SCAN_CONTACT_MAX) then
            if (.not. allocated(this%noted)) allocate (this%noted(0))
            n = size(this%noted)
            allocate (noted(n + 1))
            noted(1:n) = this%noted
            noted(n + 1)%blocks = blocks
            noted(n + 1)%pencil = pencil
            call move_alloc(noted, this%noted)
        end if
        if (set%scan_contact > 0) this%searched = set
    end subroutine coarse_scan_note

    !> The set for a last level of `p_last` contact functions to carry: the searched one, else
    !> the scan of the noted blocks where they have at most half as many contact functions
    !> (its solves in set%n_evaluations), else none (scan_contact 0: the last level scans).
    subroutine coarse_scan_coarse_set(this, scan, p_last, set, stat, tracked, here)
        class(coarse_scan_t), intent(in) :: this
        real(wp), intent(in) :: scan(:)   !! the lambdas of the search
        integer, intent(in) :: p_last
        type(critical_set_t), intent(out) :: set
        type(status_t), intent(out) :: stat
        !> the onsets a later level followed (track_onsets), merged in (merge_onsets)
        type(critical_set_t), intent(in), optional :: tracked
        logical, intent(in), optional :: here   !! merge_onsets'
        integer :: i
        if (this%searched%scan_contact > 0) then
            set = this%searched
            set%n_evaluations = 0   ! counted where it was searched
        else if (allocated(this%noted)) then
            do i = size(this%noted), 1, -1
                associate (noted => this%noted(i))
                    if (2*size(noted%blocks%kt_nn, 1) > p_last) cycle
                    call find_critical_set(noted%blocks, scan, noted%pencil, set, stat)
                    exit
                end associate
            end do
        end if
        if (present(tracked)) call merge_onsets(set, tracked, here)
    end subroutine coarse_scan_coarse_set

    !> Each side's onset in `set` (searched or scanned) becomes the collision `tracked`
    !> followed (track_onsets) on that side, or a pencil point where it followed none
    !> (carry_pairs takes the pencil points afresh), so that a carry brackets each where it
    !> was followed. Nothing where `set` has no search or `tracked` followed nothing. With
    !> `here` true, `tracked` was followed on the blocks the carry is for: its points are
    !> taken as they are (boundary_point_t: located_here), not located again.
    pure subroutine merge_onsets(set, tracked, here)
        type(critical_set_t), intent(inout) :: set
        type(critical_set_t), intent(in) :: tracked
        logical, intent(in), optional :: here
        type(boundary_point_t) :: point
        integer :: side, i, j
        if (set%scan_contact == 0) return
        if (tracked%scan_contact > 0 .or. tracked%contact == 0) return
        do side = SIDE_PLUS, SIDE_MINUS
            i = onset_point(set, side)
            j = onset_point(tracked, side)
            if (j > 0) then
                point = tracked%points(j)
                if (present(here)) point%located_here = here
                if (i > 0) then
                    set%points(i) = point
                else if (side == SIDE_PLUS) then
                    set%points = [set%points, point]
                else
                    set%points = [point, set%points]
                end if
            else if (i > 0) then
                set%points(i)%mechanism = MECHANISM_PENCIL
            end if
        end do
    end subroutine merge_onsets
end module threshold_goal
