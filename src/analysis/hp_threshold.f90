! SPDX-License-Identifier: MIT
!> &adapt strategy = 'hp' for analysis 'threshold': the levels of hp_levels (level k: the
!> input mesh graded in k layers toward the singular points, degrees 1 + layer), on each the
!> threshold computation of the h loop (adaptive_threshold): the contact blocks, the pencil
!> thresholds lambda+ and lambda- with their round-off bound, and where a side's onset is a
!> collision of two real mu (complex_pair) that collision. Each goal's bar is hp_level_bar's
!> (the changes between levels) plus its round-off part (roundoff: threshold_roundoff,
!> collision_roundoff).
!> The loop stops when every side's goal meets &adapt tolerance, when the sides that do not
!> have reached the floating-point floor, or at a limit: max_levels, max_dofs, or a level
!> whose dense contact blocks would not fit the memory (checked before they are formed).
!> The last level solved is then reported as the threshold analysis reports its mesh: the
!> spectrum at &analysis lambda, the confirmations, the boundary of the positive set.
!> This module computes; hp_threshold_run writes.
module hp_threshold
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_NOT_MET
    use strings, only: to_string, short_real_text, given_real_text, seconds_text
    use timer, only: wall_time, timings_t, PHASE_REDUCTION
    use run_config, only: config_t
    use problem, only: problem_t
    use hp_space, only: hp_space_t
    use hp_levels, only: hp_ladder_t
    use sparse_cholesky, only: cholesky_t
    use contact_boundary, only: assemble_b
    use contact_reduction, only: reduced_blocks_t, contact_flexibility
    use memory_budget, only: check_contact_memory, contact_peak_blocks, contact_blocks_bytes
    use critical_lambda, only: thresholds_t, pencil_thresholds, &
                               SIDE_PLUS, SIDE_MINUS, SIDE_NAMES
    use critical_set, only: critical_set_t, MECHANISM_PENCIL
    use roundoff, only: threshold_roundoff, collision_roundoffs
    use threshold_analysis, only: threshold_result_t, confirm_and_bound
    use adaptive_threshold, only: adaptive_thresholds_t, threshold_level_t, onset_search, &
                                  collision_onsets, apply_collision_bars, goal_bars, &
                                  level_line, coarse_scan_t
    use eigen_analysis, only: eigen_with_factor, choose_solver
    use error_bar, only: hp_run_bar, floor_reached, floor_outcome, stall_outcome
    use accuracy, only: WARNING_LEN
    implicit none
    private
    public :: hp_adapt_thresholds

    character(len=*), parameter :: HP_ESTIMATE = 'change to the previous hp level'

    type, public :: hp_thresholds_t
        !> the rows of the h loop's adapt.csv (levels numbered from 1), the last level's
        !> problem (graded P1 mesh, condensed K, hp contact, dofs%n_free only), its
        !> estimate (the hp bars), converged and outcome
        type(adaptive_thresholds_t) :: adapted
        integer, allocatable :: layers(:), p_min(:), p_max(:)   !! per level
        type(hp_space_t) :: space           !! the last level's (cell degrees)
    end type hp_thresholds_t

contains

    !> Run the loop from `start` (its mesh and parts; its K is not used) and report its last
    !> level in `res`. A limit reached is no failure (stat ok, out%adapted%converged false,
    !> its outcome heading the warnings of res%eigen); a first level whose contact blocks
    !> do not fit `available` bytes (default: the memory available) is (STATUS_NOT_MET).
    subroutine hp_adapt_thresholds(config, start, out, res, timings, stat, available)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: start
        type(hp_thresholds_t), intent(out) :: out
        type(threshold_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        integer(i8), intent(in), optional :: available
        type(hp_ladder_t) :: ladder
        type(problem_t) :: prob, next
        type(cholesky_t) :: chol
        type(reduced_blocks_t) :: blocks
        !> what the next level and the last level's report carry the boundary from
        type(coarse_scan_t) :: scan
        type(thresholds_t) :: thr
        type(critical_set_t) :: set
        type(status_t) :: memory
        real(wp) :: loop_start, tolerance
        integer :: onset(2), pencil_dofs
        logical :: too_big, factored

        loop_start = wall_time()
        tolerance = config%adapt%tolerance
        allocate (out%adapted%levels(0), out%layers(0), out%p_min(0), out%p_max(0))
        out%adapted%outcome = ''
        factored = .false.
        pencil_dofs = 0
        call ladder%begin(config, start, stat)
        if (.not. stat%ok()) return
        do
            call ladder%climb(config, start, size(out%layers), too_big, stat)
            if (.not. stat%ok()) exit
            if (too_big) then
                out%adapted%outcome = ladder%limit_outcome(tolerance, bar_text())
                exit
            end if
            call ladder%problem(config, start, next, timings, stat)
            if (.not. stat%ok()) exit
            call check_contact_memory(config, next%contact%p(), contact_peak_blocks(.false.), &
                                      memory, available)
            if (.not. memory%ok()) then
                if (.not. factored) then
                    call stat%fail(STATUS_NOT_MET, config%input_file//": &adapt: "// &
                                   "strategy = 'hp': "//memory_text())
                    return
                end if
                out%adapted%outcome = 'tolerance '//given_real_text(tolerance)// &
                    ' not met: the next '//memory_text()//'; reached error bar '//bar_text()
                exit
            end if
            if (factored) call chol%free()
            factored = .false.
            prob = next
            call ladder%factor(config, prob, chol, timings, stat)
            if (.not. stat%ok()) exit
            factored = .true.
            call solve_level(stat)
            if (.not. stat%ok()) exit
            if (stop_here()) exit
            if (config%adapt%max_levels > 0 .and. ladder%layers >= config%adapt%max_levels) then
                out%adapted%outcome = 'tolerance '//given_real_text(tolerance)//' not met: '// &
                    'max_levels = '//to_string(config%adapt%max_levels)// &
                    ' reached with error bar '//bar_text()
                exit
            end if
        end do
        if (stat%ok() .and. factored) call report_last_level(stat)
        if (factored) call chol%free()
        if (.not. stat%ok()) return
        out%adapted%estimate = res%estimate
        if (.not. out%adapted%converged) res%eigen%warnings = [character(len=WARNING_LEN) :: &
            out%adapted%outcome, res%eigen%warnings]

    contains

        !> The current level: its contact blocks, thresholds, round-off and collision onsets;
        !> a row with the bars (set_bars).
        subroutine solve_level(stat)
            type(status_t), intent(out) :: stat
            type(threshold_level_t) :: row
            real(wp) :: start
            start = wall_time()
            call contact_flexibility(chol, prob%contact, blocks%kt_nn, blocks%kt_nt, stat)
            if (stat%ok()) call pencil_thresholds(blocks%kt_nn, blocks%kt_nt, thr, stat)
            if (stat%ok()) call threshold_roundoff(prob%k, chol, prob%contact, blocks%kt_nn, &
                                                   blocks%kt_nt, thr, stat)
            if (.not. stat%ok()) return
            blocks%mass = prob%contact%mass
            call onset_search(config, blocks, thr, prob%dofs%n_free, pencil_dofs, set, stat, &
                              scan%searched)
            if (.not. stat%ok()) return
            call scan%note(blocks, thr%real_lambdas, set)
            call collision_onsets(set, onset)
            if (any(onset > 0)) call collision_roundoffs(prob%k, chol, prob%contact, blocks, &
                                                         set, stat)
            if (.not. stat%ok()) return
            call timings%add(PHASE_REDUCTION, wall_time() - start, ': contact blocks, '// &
                             'thresholds and the boundary search, hp level '// &
                             to_string(ladder%layers))
            row%level = ladder%layers
            row%n_dofs = prob%dofs%n_free
            row%n_contact = prob%contact%p()
            row%n_cells = prob%mesh%n_cells()
            row%found = thr%found
            row%lambda = thr%lambda
            row%collision = onset > 0
            where (row%collision) row%collision_lambda = set%points(max(onset, 1))%lambda
            where (row%collision) row%collision_roundoff = set%points(max(onset, 1))%roundoff
            out%adapted%levels = [out%adapted%levels, row]
            out%layers = [out%layers, ladder%layers]
            out%p_min = [out%p_min, minval(ladder%degree)]
            out%p_max = [out%p_max, maxval(ladder%degree)]
            call set_bars(out%adapted%levels, thr%roundoff)
            out%adapted%levels(size(out%adapted%levels))%time_s = wall_time() - loop_start
            out%adapted%prob = prob
            out%space = ladder%space
            call timings%note(level_line(out%adapted%levels(size(out%adapted%levels)), &
                                         'hp level'))
        end subroutine solve_level

        !> Whether the loop stops after the level just solved: no goal, the tolerance met on
        !> every side, or each side that does not meet it stalled or at the floor.
        logical function stop_here()
            real(wp) :: bar(2), roundoff(2)
            integer :: side, worst, stalled
            stop_here = .true.
            call goal_bars(out%adapted%levels(size(out%adapted%levels)), thr%roundoff, bar, &
                           roundoff)
            associate (last => out%adapted%levels(size(out%adapted%levels)))
                if (.not. any(last%found .or. last%collision)) then
                    out%adapted%outcome = 'tolerance not met: no real eigenvalue of the '// &
                        'pencil Kt_nn x = lambda Kt_nt x at hp level '//to_string(last%level)
                    return
                end if
                stop_here = .false.
                ! a goal without a bar yet
                if (any(bar < -0.5_wp .and. .not. last%stalled)) return
                if (all(bar <= tolerance .and. .not. last%stalled)) then
                    out%adapted%converged = .true.
                    out%adapted%outcome = 'tolerance '//given_real_text(tolerance)// &
                        ' met at level '//to_string(last%level)//': error bar '//bar_text()
                    stop_here = .true.
                    return
                end if
                worst = 0
                stalled = 0
                do side = SIDE_PLUS, SIDE_MINUS
                    if (last%stalled(side)) then
                        stalled = side
                        cycle
                    end if
                    if (bar(side) <= tolerance) cycle
                    if (.not. floor_reached(bar(side), roundoff(side))) return
                    if (worst == 0) worst = side
                    if (bar(side) > bar(worst)) worst = side
                end do
                stop_here = .true.
                if (stalled > 0) then
                    out%adapted%outcome = stall_outcome(tolerance, &
                                                        'the '//trim(SIDE_NAMES(stalled))//' side')
                    return
                end if
                out%adapted%floor_reached = .true.
                out%adapted%outcome = floor_outcome(tolerance, roundoff(worst), bar(worst), &
                                                    to_string(last%n_dofs))
            end associate
        end function stop_here

        !> res for the last level solved (its factor and blocks still there): the spectrum
        !> at &analysis lambda, the thresholds confirmed, the boundary of the positive set,
        !> and the hp bars as the estimate of the thresholds and of the collision onsets.
        subroutine report_last_level(stat)
            type(status_t), intent(out) :: stat
            real(wp) :: begin
            integer :: side, i, k
            type(critical_set_t) :: coarse
            begin = wall_time()
            res%eigen%solver = choose_solver(config%eigen%solver, prob%contact%p(), &
                config%eigen%dense_max_contact, config%eigen%operator)
            res%eigen%lambda = config%analysis%lambda
            call assemble_b(prob%contact, prob%dofs%n_free, res%eigen%lambda, res%eigen%b, stat)
            if (stat%ok()) call eigen_with_factor(config, prob, chol, res%eigen, timings, stat, &
                                                  blocks%kt_nn, blocks%kt_nt)
            res%thresholds = thr
            if (.not. stat%ok()) return
            if (set%scan_contact > 0) then   ! the last level searched: its set stands
                call confirm_and_bound(config, prob, chol, blocks, .false., res%thresholds, &
                                       res%set, stat, known=set)
            else
                call scan%coarse_set(config, prob%contact%p(), coarse, stat)
                if (stat%ok()) call confirm_and_bound(config, prob, chol, blocks, .false., &
                                                      res%thresholds, res%set, stat, coarse)
            end if
            if (.not. stat%ok()) return
            k = size(out%adapted%levels)
            res%estimate%method = HP_ESTIMATE
            associate (last => out%adapted%levels(k))
                do side = SIDE_PLUS, SIDE_MINUS
                    if (.not. thr%found(side)) cycle
                    if (last%stalled(side)) then
                        res%estimate%skipped(side) = 'none: the '//trim(SIDE_NAMES(side))// &
                            ' side does not converge under hp refinement'
                        cycle
                    end if
                    if (last%error_bar(side) < 0.0_wp) then
                        res%estimate%skipped(side) = 'none at the first hp level'
                        cycle
                    end if
                    res%estimate%computed(side) = .true.
                    res%estimate%bar(side) = last%error_bar(side)
                    res%estimate%relative(side) = last%error_estimate(side)
                    res%estimate%lambda_enriched(side) = out%adapted%levels(k - 1)%lambda(side)
                    ! the boundary point at this threshold carries its bar
                    do i = 1, size(res%set%points)
                        if (res%set%points(i)%mechanism == MECHANISM_PENCIL .and. &
                            abs(res%set%points(i)%lambda - thr%lambda(side)) <= &
                            1.0e-12_wp*abs(thr%lambda(side))) &
                            res%set%points(i)%error_bar = last%error_bar(side)
                    end do
                end do
            end associate
            call apply_collision_bars(out%adapted, res%set)
            res%time_threshold = wall_time() - begin
            call timings%note('thresholds '//seconds_text(res%time_threshold)//' s')
        end subroutine report_last_level

        !> The next level's contact blocks against the memory available.
        function memory_text() result(text)
            character(len=:), allocatable :: text
            integer :: p
            p = next%contact%p()
            text = 'level '//to_string(ladder%layers)//' has p = '//to_string(p)// &
                ' contact functions, whose dense blocks ('// &
                to_string(contact_peak_blocks(.false.))//' p x p doubles) need an estimated '// &
                short_real_text(contact_blocks_bytes(p, contact_peak_blocks(.false.))/1.0e9_wp)// &
                ' GB, more than the memory available'
        end function memory_text

        function bar_text() result(text)
            character(len=:), allocatable :: text
            real(wp) :: bar(2), roundoff(2)
            text = 'none'
            if (size(out%adapted%levels) == 0) return
            associate (last => out%adapted%levels(size(out%adapted%levels)))
                call goal_bars(last, thr%roundoff, bar, roundoff)
                if (all(bar >= -0.5_wp)) text = short_real_text(maxval(bar))
                text = text//' at '//to_string(last%n_dofs)//' dofs'
            end associate
        end function bar_text
    end subroutine hp_adapt_thresholds

    !> The bars of the last of `levels`: per side, hp_level_bar of the thresholds over the
    !> levels since the last one without it, plus `roundoff` (the last level's), and of the
    !> collision onsets likewise with theirs; error_estimate is the relative
    !> change to the previous level (what the bar is made of). A side whose goal (its
    !> collision onset where it has one, else its threshold) has stalled (hp_run_bar) stays
    !> stalled, with no bar, at every later level.
    subroutine set_bars(levels, roundoff)
        type(threshold_level_t), intent(inout) :: levels(:)
        real(wp), intent(in) :: roundoff(2)
        real(wp) :: values(size(levels)), change
        logical :: have(size(levels)), stalled(2)
        integer :: k, side, i
        k = size(levels)
        do side = SIDE_PLUS, SIDE_MINUS
            ! plain arrays: components of a derived-type array would make temporaries
            do i = 1, k
                have(i) = levels(i)%found(side)
                values(i) = levels(i)%lambda(side)
            end do
            call hp_run_bar(have, values, roundoff(side), levels(k)%error_bar(side), change, &
                            stalled(1))
            levels(k)%estimated(side) = levels(k)%error_bar(side) >= 0.0_wp
            if (levels(k)%estimated(side)) levels(k)%error_estimate(side) = change
            do i = 1, k
                have(i) = levels(i)%collision(side)
                values(i) = levels(i)%collision_lambda(side)
            end do
            call hp_run_bar(have, values, levels(k)%collision_roundoff(side), &
                            levels(k)%collision_bar(side), levels(k)%collision_estimate(side), &
                            stalled(2))
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

end module hp_threshold
