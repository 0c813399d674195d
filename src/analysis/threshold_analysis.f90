! SPDX-License-Identifier: MIT
!> analysis = 'threshold' and 'lambda_sweep': the critical lambdas (model.md sections 4-7) and the
!> curve lambda -> lowest positive mu, from ONE factorization of K and ONE formation of the
!> contact blocks Kt_nn, Kt_nt. B depends on lambda only through the reduced matrix
!> (lambda Kt_nt - Kt_nn) M, so every further lambda costs one p x p eigen-solve: dense
!> (dgeev, eigenvalues only) for the dense solver, the certified ARPACK search on that matrix
!> (O(p^2) per product) for ARPACK, with a dense decision whenever ARPACK cannot certify.
!> Both analyses also solve the eigenproblem at &analysis lambda as 'eigen' does, with the
!> same solver choice and on the same factor, so that their summary.json carries every key
!> of the contract.
module threshold_analysis
    use kinds, only: wp
    use status, only: status_t
    use timer, only: wall_time, timings_t, PHASE_ASSEMBLY, PHASE_REDUCTION
    use strings, only: to_string, seconds_text, short_real_text
    use real_format, only: real_to_text
    use scene, only: scene_t
    use method_options, only: eigen_options_t, adapt_options_t, SOLVER_ARPACK, REFINE_NONE, &
                              REFINE_HP
    use problem, only: problem_t, explain_singular_k
    use unit_scaling, only: units_t
    use enrichment, only: enriched_element
    use sparse_cholesky, only: cholesky_t
    use contact_boundary, only: assemble_b
    use contact_reduction, only: factor_contact_blocks, reduced_blocks_t, &
                                 lambda_unit
    use memory_budget, only: check_contact_memory, contact_peak_blocks
    use arpack_eigen, only: arpack_options_t, arpack_lowest_positive
    use critical_lambda, only: thresholds_t, pencil_thresholds, confirm_thresholds, &
                               lowest_positive_mu, SIDE_PLUS, SIDE_MINUS, SIDE_LABELS
    use roundoff, only: threshold_roundoff, collision_roundoffs
    use critical_set, only: critical_set_t, search_critical_set, MECHANISM_COMPLEX_PAIR
    use eigen_goal, only: adapt_eigen, adapted_eigen_t
    use eigen_solve, only: eigen_result_t, choose_solver, eigen_with_factor, estimate_wanted, &
                           check_real_range
    use error_estimate, only: ENRICHED_CONTACT_MAX
    use boundary_estimate, only: estimate_boundary_bars, onset_bars_t
    use threshold_estimate, only: threshold_estimate_t, threshold_displacements, &
                                  estimate_threshold_errors
    use accuracy, only: WARNING_LEN, roundoff_warnings
    use error_bar, only: theta_warnings
    use halved_mesh, only: build_halved_problem
    implicit none
    private
    public :: start_sweep_curve, end_adapted_sweep, record_hp_sweep
    public :: threshold_result_t, solve_thresholds, factor_with_contact_blocks, &
              confirm_and_bound

    !> The curve of a lambda sweep, one entry per lambda.
    type, public :: sweep_curve_t
        real(wp), allocatable :: lambda(:)
        !> lowest positive mu where found(i), in `units`
        real(wp), allocatable :: mu(:)
        !> of mu: those of the problems the points were solved on (problem_t%units: the
        !> sweep's problem, whose E and extent an h-adapted point's share; hp levels')
        type(units_t) :: units
        logical, allocatable :: found(:)
        !> positive real eigenvalues at lambda(i); -1 where ARPACK decided (it sees a few)
        !> or the point was adapted
        integer, allocatable :: n_positive(:)
        !> with &adapt: |relative error estimate| of mu(i) (negative: none) and the free dofs
        !> of the mesh it was computed on; without, -1 and the dofs of the one mesh
        real(wp), allocatable :: error_estimate(:)
        real(wp), allocatable :: error_bar(:)    !! &adapt: the bar of mu(i); negative: none
        integer, allocatable :: n_dofs(:)
        integer :: n_reused = 0                  !! &adapt: points met with no refinement
        !> &adapt: points whose tolerance was not met (record_point), and the first such
        !> point's outcome
        integer :: n_not_met = 0
        character(len=:), allocatable :: not_met
        integer :: n_arpack = 0                  !! points certified by ARPACK
        integer :: n_dense = 0                   !! points decided densely (incl. fallbacks)
        !> &adapt: a point's loop failed (a library, the memory): the points whose loops had
        !> ended are kept, complete(i), as a partial set; `failure` is the loop's status
        logical, allocatable :: complete(:)
        type(status_t) :: failure
    end type sweep_curve_t

    type, public :: threshold_result_t
        type(eigen_result_t) :: eigen            !! the spectrum at &analysis lambda
        type(thresholds_t) :: thresholds
        !> the boundary of {lambda : a positive mu exists} over the &sweep range
        type(critical_set_t) :: set
        !> the error estimates of lambda+ and lambda- (as &eigen estimate asks)
        type(threshold_estimate_t) :: estimate
        type(sweep_curve_t) :: sweep             !! allocated for 'lambda_sweep' only
        real(wp) :: time_threshold = 0.0_wp      !! pencil QZ and the confirming solves, s
        real(wp) :: time_sweep = 0.0_wp          !! all the p x p solves of the sweep, s
    end type threshold_result_t

contains

    !> Factor K of `prob` (the problem of the scene `scn`), form Kt_nn and Kt_nt, and compute
    !> the spectrum at `lambda` as `options` ask, the thresholds with their error estimates
    !> and confirmations, the boundary of the positive set over the lambdas `scan`, and (with
    !> `sweep`, its lambdas) the sweep curve, adapted as `adapt` asks. `estimate`: the
    !> thresholds' estimate on this very problem, known already (the adaptive loop's last
    !> level), not computed again; `onsets` likewise the bars of its collision onsets.
    subroutine solve_thresholds(scn, prob, lambda, options, scan, res, timings, stat, sweep, &
                                adapt, estimate, onsets, coarse)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: lambda
        type(eigen_options_t), intent(in) :: options
        real(wp), intent(in) :: scan(:)
        type(threshold_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: sweep(:)
        type(adapt_options_t), intent(in), optional :: adapt
        type(threshold_estimate_t), intent(in), optional :: estimate
        type(onset_bars_t), intent(in), optional :: onsets
        !> the boundary a coarser level found, to carry (confirm_and_bound)
        type(critical_set_t), intent(in), optional :: coarse
        type(cholesky_t) :: chol
        type(reduced_blocks_t) :: blocks
        type(arpack_options_t) :: arpack
        real(wp) :: start
        real(wp), allocatable :: u_threshold(:, :)
        integer :: i, n_operator
        logical :: certified, estimated

        res%eigen%solver = choose_solver(options, prob%contact%p())
        res%eigen%lambda = lambda
        start = wall_time()
        call assemble_b(prob%contact, prob%dofs%n_free, res%eigen%lambda, res%eigen%b, stat)
        if (.not. stat%ok()) return
        call timings%add(PHASE_ASSEMBLY, wall_time() - start, ': B for lambda = '// &
                         real_to_text(res%eigen%lambda))

        call factor_with_contact_blocks(scn, prob, chol, blocks%kt_nn, blocks%kt_nt, timings, &
                                        stat)
        if (.not. stat%ok()) return
        call eigen_with_factor(scn, prob, options, chol, res%eigen, timings, stat, blocks%kt_nn, &
                               blocks%kt_nt)
        start = wall_time()
        if (stat%ok()) call pencil_thresholds(blocks%kt_nn, blocks%kt_nt, res%thresholds, stat)
        if (stat%ok()) call threshold_roundoff(prob%k, chol, prob%contact, blocks%kt_nn, &
                                               blocks%kt_nt, res%thresholds, stat)
        ! the displacements of the limit modes, for the estimate, while the factor is there
        estimated = .false.
        if (present(estimate)) then
            res%estimate = estimate
        else
            estimated = wants_estimate()
            if (estimated .and. stat%ok()) call threshold_displacements(chol, prob%contact, &
                prob%dofs%n_free, res%thresholds, u_threshold, stat)
        end if
        ! the confirmations and the boundary of the positive set while the factor is there:
        ! the round-off part of a collision needs two solves with it
        blocks%mass = prob%contact%mass
        if (stat%ok()) call confirm_and_bound(scn, prob, lambda, scan, chol, blocks, &
                                              res%thresholds, res%set, stat, coarse)
        call chol%free()
        if (.not. stat%ok()) return
        if (estimated) call add_threshold_estimate()
        ! the round-off part of the one-mesh bars (the adaptive levels' carry it already)
        if (estimated) where (res%estimate%computed .and. res%estimate%bar >= 0.0_wp .and. &
                              res%thresholds%roundoff >= 0.0_wp) &
            res%estimate%bar = res%estimate%bar + res%thresholds%roundoff
        call warn_roundoff(.false.)
        if (estimated .or. present(estimate)) call add_boundary_bars()
        call warn_roundoff(.true.)
        res%time_threshold = wall_time() - start
        call timings%note('thresholds '//seconds_text(res%time_threshold)//' s')
        if (.not. present(sweep)) return

        start = wall_time()
        call start_sweep_curve(sweep, prob, res%sweep)
        if (present(adapt)) then
            if (adapt%refine /= REFINE_NONE) then
                call adaptive_sweep(scn, prob, options, adapt, res%sweep, timings, stat)
                if (.not. stat%ok()) return
                call end_adapted_sweep(adapt, start, res, timings)
                return
            end if
        end if
        arpack = arpack_options_t(nev=options%nev, ncv=options%ncv, maxit=options%maxit, &
                                  tol=options%tol)
        do i = 1, size(res%sweep%lambda)
            call timings%tick('sweep, lambda', i, size(res%sweep%lambda))
            certified = .false.
            ! Where the boundary search found no positive mu, ARPACK could never certify that
            ! (only the whole spectrum can): its attempts would be wasted. A point the scan
            ! judged wrongly is still right: ARPACK that cannot certify falls back to dgeev.
            if (res%eigen%solver == SOLVER_ARPACK .and. &
                res%set%positive_at(res%sweep%lambda(i))) then
                call arpack_lowest_positive(blocks%matrix(res%sweep%lambda(i)), arpack, &
                                            res%sweep%mu(i), res%sweep%found(i), certified, &
                                            n_operator, stat)
                if (.not. stat%ok()) return
                ! blocks%matrix is A / lambda_unit: mu = 1 / (lambda_unit theta)
                res%sweep%mu(i) = res%sweep%mu(i)/lambda_unit(res%sweep%lambda(i))
            end if
            if (certified) then
                res%sweep%n_positive(i) = -1
                res%sweep%n_arpack = res%sweep%n_arpack + 1
            else
                call lowest_positive_mu(blocks, res%sweep%lambda(i), res%sweep%mu(i), &
                                        res%sweep%found(i), res%sweep%n_positive(i), stat)
                if (.not. stat%ok()) return
                res%sweep%n_dense = res%sweep%n_dense + 1
            end if
        end do
        call check_real_range(scn, prob%units, maxval(abs(res%sweep%lambda)), .true., &
                              res%sweep%mu, stat)
        if (.not. stat%ok()) return
        res%time_sweep = wall_time() - start
        call timings%note('sweep      '//seconds_text(res%time_sweep)//' s: '// &
                          to_string(size(res%sweep%lambda))//' lambdas')

    contains

        !> The round-off warnings (accuracy: roundoff_warnings) of each critical lambda found
        !> and, once their bars are known, of each collision point.
        subroutine warn_roundoff(collisions)
            logical, intent(in) :: collisions
            real(wp) :: rest
            integer :: side, i
            if (.not. collisions) then
                do side = SIDE_PLUS, SIDE_MINUS
                    if (.not. res%thresholds%found(side)) cycle
                    rest = -1.0_wp
                    if (res%estimate%computed(side) .and. res%estimate%bar(side) >= 0.0_wp) &
                        rest = res%estimate%bar(side) - res%thresholds%roundoff(side)
                    res%eigen%warnings = [character(len=WARNING_LEN) :: res%eigen%warnings, &
                        roundoff_warnings(res%thresholds%roundoff(side), rest, &
                                          trim(SIDE_LABELS(side)))]
                end do
                return
            end if
            do i = 1, size(res%set%points)
                associate (point => res%set%points(i))
                    if (point%mechanism /= MECHANISM_COMPLEX_PAIR) cycle
                    rest = -1.0_wp
                    if (point%error_bar >= 0.0_wp) rest = point%error_bar - point%roundoff
                    res%eigen%warnings = [character(len=WARNING_LEN) :: res%eigen%warnings, &
                        roundoff_warnings(point%roundoff, rest, 'the collision point lambda = ' &
                                          //short_real_text(point%lambda, 12))]
                end associate
            end do
        end subroutine warn_roundoff

        !> As &eigen estimate asks (estimate_wanted); res%estimate%skipped says why not on
        !> the sides with a threshold.
        logical function wants_estimate()
            character(len=:), allocatable :: why_not
            wants_estimate = estimate_wanted(options, prob%dofs%n_free, why_not)
            where (res%thresholds%found) res%estimate%skipped = why_not
        end function wants_estimate

        !> res%estimate; its failure costs the estimate (a warning), never the run.
        subroutine add_threshold_estimate()
            type(status_t) :: failed
            real(wp) :: begin
            begin = wall_time()
            if (enriched_element(prob%mesh%element) == 0) then
                call halved_mesh_thresholds(scn, prob, res%thresholds, res%estimate, failed)
            else
                call estimate_threshold_errors(prob, res%thresholds, u_threshold, &
                                               ENRICHED_CONTACT_MAX, res%estimate, failed)
            end if
            if (.not. failed%ok()) then
                res%eigen%warnings = [character(len=WARNING_LEN) :: res%eigen%warnings, &
                    'no error estimate for the critical lambdas: '//failed%message]
                return
            end if
            if (any(res%estimate%computed)) call timings%add(PHASE_REDUCTION, &
                wall_time() - begin, ': error estimates of the critical lambdas')
        end subroutine add_threshold_estimate

        !> The bars of the boundary points (boundary_estimate); a failure costs them only.
        subroutine add_boundary_bars()
            type(status_t) :: failed
            real(wp) :: begin
            begin = wall_time()
            call estimate_boundary_bars(scn, prob, res%thresholds, res%estimate, &
                                        ENRICHED_CONTACT_MAX, res%set, failed, onsets)
            if (.not. failed%ok()) then
                res%eigen%warnings = [character(len=WARNING_LEN) :: res%eigen%warnings, &
                    'no error bars for the boundary points: '//failed%message]
                return
            end if
            if (any(res%set%points%error_bar >= 0.0_wp)) call timings%add(PHASE_REDUCTION, &
                wall_time() - begin, ': error bars of the boundary points')
        end subroutine add_boundary_bars
    end subroutine solve_thresholds

    !> The confirmations of the thresholds `thr` and the boundary `set` of {lambda : a
    !> positive mu exists} over the lambdas `scan`, from the contact `blocks` (mass set) of
    !> `prob` (of the scene `scn`, at the run's `lambda`: for messages), their mu in the
    !> input's units, and the round-off part
    !> of each collision point (two solves each with `chol`, the factor of K with the contact
    !> dofs last): what every threshold report gives on its (last) problem. Dense on
    !> purpose, whatever the solver: just inside a threshold there is no positive mu, which
    !> only the complete spectrum shows, and just outside the wanted mu is huge, deep in the
    !> spectrum; dgeev without vectors is O(p^3) with a small constant. The count of
    !> positive mu needs the whole spectrum too.
    !> With `coarse` (the set a coarser discretisation of the scene found over the same
    !> scan; scan_contact 0: none), its points are carried (carry_critical_set) unless the
    !> structure differs here (its own solves, n_evaluations, are counted with these);
    !> with `known` (found on these blocks over the same scan), that set is taken.
    subroutine confirm_and_bound(scn, prob, lambda, scan, chol, blocks, thr, set, stat, coarse, &
                                 known, lift, near)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: lambda
        real(wp), intent(in) :: scan(:)
        type(cholesky_t), intent(in) :: chol
        type(reduced_blocks_t), intent(in) :: blocks
        type(thresholds_t), intent(inout) :: thr
        type(critical_set_t), intent(out) :: set
        type(status_t), intent(out) :: stat
        type(critical_set_t), intent(in), optional :: coarse, known
        !> blocks of restricted forces: their vectors on the contact functions (roundoff)
        real(wp), intent(in), optional :: lift(:, :)
        !> the first bracket (relative) of coarse's complex_pair points (carry_critical_set)
        real(wp), intent(in), optional :: near
        real(wp), allocatable :: mu_meet(:), confirmed_lambda(:)
        integer, allocatable :: confirmed_count(:)
        call confirm_thresholds(blocks, thr, stat)
        if (.not. stat%ok()) return
        ! their mu must be reportable in the input's units (lambda has none)
        call check_real_range(scn, prob%units, lambda, .false., thr%mu_outside, stat)
        if (stat%ok()) call check_real_range(scn, prob%units, lambda, .false., thr%mu_inside, &
                                             stat)
        if (.not. stat%ok()) return
        ! the confirmations' counts bracket the pencil points: the search need not redo them
        confirmed_lambda = pack([thr%lambda_outside, thr%lambda_inside], &
                                [thr%n_outside, thr%n_inside] >= 0)
        confirmed_count = pack([thr%n_outside, thr%n_inside], [thr%n_outside, thr%n_inside] >= 0)
        if (present(known)) then
            set = known
        else
            call search_critical_set(blocks, scan, thr%real_lambdas, set, stat, coarse, &
                                     confirmed_lambda, confirmed_count, near)
            ! the coarse scan made for this report (none for a loop level's own search)
            if (stat%ok() .and. present(coarse)) set%n_evaluations = set%n_evaluations + &
                                                                     coarse%n_evaluations
        end if
        if (stat%ok()) call collision_roundoffs(prob%k, chol, prob%contact, blocks, set, stat, &
                                                lift)
        if (.not. stat%ok() .or. size(set%points) == 0) return
        mu_meet = set%points%mu_meet   ! a plain array: no temporary for the call
        call check_real_range(scn, prob%units, lambda, .false., mu_meet, stat)
    end subroutine confirm_and_bound

    !> Factor K with the contact dofs last and form Kt_nn and Kt_nt, which every threshold
    !> computation needs (their memory checked first); `chol` stays factored for the
    !> caller's solves (free it), and is freed here on failure.
    subroutine factor_with_contact_blocks(scn, prob, chol, kt_nn, kt_nt, timings, stat)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(cholesky_t), intent(inout) :: chol
        real(wp), allocatable, intent(out) :: kt_nn(:, :), kt_nt(:, :)
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        call check_contact_memory(scn, prob%contact%p(), contact_peak_blocks(.false.), stat)
        if (.not. stat%ok()) return
        call factor_contact_blocks(prob%k, prob%mesh, prob%dofs, prob%contact, chol, kt_nn, &
                                   kt_nt, timings, stat)
        call explain_singular_k(scn, prob%mesh, stat)
        if (.not. stat%ok()) call chol%free()
    end subroutine factor_with_contact_blocks

    !> `est` for an element with no degree above it (Q1, Q2, P4): the thresholds of the same
    !> element on the rectangle of halved cells (2 nx x 2 ny), whose space holds this one's,
    !> relative = (lambda_h/2 - lambda_h) / lambda_h and the bar from it (error_bar), as the
    !> estimate of mu does (eigen_solve); no cell indicators. It costs the factor and the
    !> contact blocks of a mesh with four times the dofs and twice the contact nodes.
    subroutine halved_mesh_thresholds(scn, prob, thr, est, stat)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(thresholds_t), intent(in) :: thr
        type(threshold_estimate_t), intent(inout) :: est
        type(status_t), intent(out) :: stat
        type(scene_t) :: halved
        type(problem_t) :: fine
        type(thresholds_t) :: fine_thr
        type(timings_t) :: quiet
        type(cholesky_t) :: chol
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :)
        character(len=:), allocatable :: why_not
        real(wp) :: start
        integer :: side

        start = wall_time()
        if (.not. any(thr%found)) return
        call build_halved_problem(scn, prob, halved, fine, why_not, stat)
        if (len(why_not) > 0) then
            where (thr%found) est%skipped = 'not computed: '//why_not
            return
        end if
        if (stat%ok()) call factor_with_contact_blocks(halved, fine, chol, kt_nn, kt_nt, &
                                                       quiet, stat)
        if (.not. stat%ok()) return
        call chol%free()
        call pencil_thresholds(kt_nn, kt_nt, fine_thr, stat)
        if (.not. stat%ok()) return
        est%element = prob%mesh%element
        est%halved_mesh = .true.
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. thr%found(side)) cycle
            if (.not. fine_thr%found(side)) then
                est%skipped(side) = 'not computed: the halved mesh''s pencil has no real '// &
                    'eigenvalue '//merge('> 0', '< 0', side == SIDE_PLUS)
                cycle
            end if
            est%lambda_enriched(side) = fine_thr%lambda(side)
            call est%record(side, (fine_thr%lambda(side) - thr%lambda(side))/thr%lambda(side))
        end do
        est%seconds = wall_time() - start
    end subroutine halved_mesh_thresholds

    !> The curve of a sweep over `lambdas` on `prob`, before its points are solved: every
    !> point complete, no estimate, no bar, the dofs of `prob`.
    subroutine start_sweep_curve(lambdas, prob, curve)
        real(wp), intent(in) :: lambdas(:)
        type(problem_t), intent(in) :: prob
        type(sweep_curve_t), intent(inout) :: curve
        integer :: n
        n = size(lambdas)
        curve%lambda = lambdas
        curve%units = prob%units
        allocate (curve%mu(n), curve%found(n), curve%n_positive(n))
        allocate (curve%error_estimate(n), source=-1.0_wp)
        allocate (curve%error_bar(n), source=-1.0_wp)
        allocate (curve%n_dofs(n), source=prob%dofs%n_free)
        allocate (curve%complete(n), source=.true.)
    end subroutine start_sweep_curve

    !> The warnings of an adapted sweep (`res%sweep`, started at wall time `start`) in those
    !> of the spectrum at &analysis lambda, where a user looks, and its time.
    subroutine end_adapted_sweep(adapt, start, res, timings)
        type(adapt_options_t), intent(in) :: adapt
        real(wp), intent(in) :: start
        type(threshold_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        if (.not. res%sweep%failure%ok()) res%eigen%warnings = &
            [character(len=WARNING_LEN) :: res%eigen%warnings, 'the sweep is partial: '// &
             to_string(count(res%sweep%complete))//' of its '// &
             to_string(size(res%sweep%lambda))//' points are complete ('// &
             'sweep_partial), a point''s loop failed: '//res%sweep%failure%message]
        ! the points' own warnings are not kept (record): the run's stands for them
        if (adapt%refine /= REFINE_HP) res%eigen%warnings = &
            [character(len=WARNING_LEN) :: res%eigen%warnings, theta_warnings(adapt%theta)]
        ! where a user looks, not only in the exit status and sweep_n_not_met
        if (res%sweep%n_not_met > 0) res%eigen%warnings = &
            [character(len=WARNING_LEN) :: res%eigen%warnings, &
             to_string(res%sweep%n_not_met)//' of the '// &
             to_string(size(res%sweep%lambda))//' sweep points did not meet the '// &
             'tolerance (sweep_n_not_met; the first at '//res%sweep%not_met//')']
        res%time_sweep = wall_time() - start
        call timings%note('sweep      '//seconds_text(res%time_sweep)//' s: '// &
            to_string(size(res%sweep%lambda))//' lambdas, adapted to '// &
            seconds_text(adapt%tolerance))
    end subroutine end_adapted_sweep

    !> The curve with &adapt: at each lambda the adaptive loop of analysis 'eigen' until the
    !> bar meets the tolerance. With strategy 'h' it starts from the last mesh that met it
    !> at a lambda before (the mesh of a neighbouring lambda is usually fine already: the
    !> point then costs one solve and one estimate), and a point whose loop stops short
    !> keeps its last mu and estimate, its mesh not passed on; after a point without a
    !> positive mu (confirmed on uniform refinements) the next starts from the input mesh.
    !> With 'hp' every point climbs the hp levels of the input mesh, which do not depend on
    !> lambda: one climb (one goal with a target per lambda, eigen_goal) builds and factors
    !> each level once for all points not yet stopped.
    subroutine adaptive_sweep(scn, prob, options, adapt, curve, timings, stat)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(eigen_options_t), intent(in) :: options
        type(adapt_options_t), intent(in) :: adapt
        type(sweep_curve_t), intent(inout) :: curve
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(problem_t) :: current
        type(adapted_eigen_t), allocatable :: outs(:)
        !> a point's phases would flood the progress lines; the sweep's time is time_sweep
        type(timings_t) :: quiet
        integer :: i

        if (adapt%refine == REFINE_HP) then
            call adapt_eigen(scn, curve%lambda, options, adapt, prob, outs, quiet, stat, &
                             keep_problem=.false.)
            ! a level that failed after the first: each point as its last complete level
            ! had it, the failure the curve's (record_hp_sweep)
            if (stat%ok() .and. size(outs) > 0) then
                if (.not. outs(1)%failure%ok()) stat = outs(1)%failure
            end if
            call record_hp_sweep(outs, curve, timings, stat)
            return
        end if
        current = prob
        do i = 1, size(curve%lambda)
            call timings%tick('sweep, lambda', i, size(curve%lambda))
            call adapt_eigen(scn, [curve%lambda(i)], options, adapt, current, outs, quiet, stat, &
                             keep_problem=.true.)
            ! a point whose level after the first failed ends the sweep as a point's failure
            if (stat%ok()) then
                if (.not. outs(1)%failure%ok()) stat = outs(1)%failure
            end if
            if (.not. stat%ok()) then
                ! the points before are complete: a partial set, the failure its verdict
                curve%failure = stat
                stat = status_t()
                curve%complete(i:) = .false.
                call clear_incomplete(curve)
                return
            end if
            associate (o => outs(1))
                call record_point(curve, i, o%res, o%prob%dofs%n_free, o%converged, &
                                  size(o%levels) == 1, o%outcome)
                ! after a 'none, confirmed' the input mesh, not its uniformly refined one
                ! nor the last mu's: the next point without a mu confirms it from the
                ! input mesh as its own run would (three small levels), where refining
                ! a mesh adapted to another lambda's mode twice cost seconds per point
                if (o%converged .and. curve%found(i)) current = o%prob
                if (o%converged .and. .not. curve%found(i)) current = prob
            end associate
        end do
    end subroutine adaptive_sweep

    !> The curve from the points `outs` of one hp climb for all its lambdas (eigen_goal),
    !> whose loop ended with `stat`: a failed loop (`outs` allocated) makes the points whose
    !> loops had ended a partial set, its failure the curve's, and `stat` ok.
    subroutine record_hp_sweep(outs, curve, timings, stat)
        type(adapted_eigen_t), allocatable, intent(in) :: outs(:)
        type(sweep_curve_t), intent(inout) :: curve
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(inout) :: stat
        integer :: i
        if (.not. stat%ok()) then
            if (.not. allocated(outs)) return
            curve%failure = stat
            stat = status_t()
            do i = 1, size(curve%lambda)
                curve%complete(i) = len(outs(i)%outcome) > 0
            end do
        end if
        do i = 1, size(curve%lambda)
            if (size(outs(i)%levels) == 0) cycle
            curve%units = outs(i)%units   ! (every hp level's)
            exit
        end do
        do i = 1, size(curve%lambda)
            call timings%tick('sweep, lambda', i, size(curve%lambda))
            if (.not. curve%complete(i)) cycle
            associate (o => outs(i))
                call record_point(curve, i, o%res, last_dofs(o), o%converged, .false., &
                                  o%outcome)
            end associate
        end do
        call clear_incomplete(curve)

    contains

        !> The free dofs of the last level an hp point solved (0: none).
        pure integer function last_dofs(o)
            type(adapted_eigen_t), intent(in) :: o
            last_dofs = 0
            if (size(o%levels) > 0) last_dofs = o%levels(size(o%levels))%n_dofs
        end function last_dofs
    end subroutine record_hp_sweep

    !> The points of `curve` not complete (a failed loop): no mu, no estimate, no bar.
    subroutine clear_incomplete(curve)
        type(sweep_curve_t), intent(inout) :: curve
        where (.not. curve%complete)
            curve%found = .false.
            curve%mu = 0.0_wp
            curve%n_positive = -1
            curve%error_estimate = -1.0_wp
            curve%error_bar = -1.0_wp
        end where
    end subroutine clear_incomplete

    !> Point i of `curve` from the result `res` of its loop on `n_free` dofs. A point misses
    !> the tolerance when its loop did not meet it: a mu not converged, one it had at a
    !> coarser level (vanished: adapted_eigen_t%mu_vanished), or no positive mu on levels
    !> too few to confirm there is none (eigen_goal_judge: 'none, confirmed' is met).
    subroutine record_point(curve, i, res, n_free, converged, reused, outcome)
        type(sweep_curve_t), intent(inout) :: curve
        integer, intent(in) :: i
        type(eigen_result_t), intent(in) :: res
        integer, intent(in) :: n_free
        logical, intent(in) :: converged, reused
        character(len=*), intent(in) :: outcome
        integer :: lowest
        lowest = res%spec%lowest_positive()
        curve%found(i) = lowest > 0
        curve%mu(i) = 0.0_wp
        if (curve%found(i)) curve%mu(i) = real(res%spec%mu(lowest), wp)
        curve%n_positive(i) = -1
        if (res%error%computed) curve%error_estimate(i) = abs(res%error%relative)
        if (res%error%computed) curve%error_bar(i) = res%error%bar
        curve%n_dofs(i) = n_free
        if (converged .and. reused) curve%n_reused = curve%n_reused + 1
        if (.not. converged) then
            curve%n_not_met = curve%n_not_met + 1
            if (.not. allocated(curve%not_met)) curve%not_met = 'lambda = '// &
                real_to_text(curve%lambda(i))//': '//outcome
        end if
    end subroutine record_point
end module threshold_analysis
