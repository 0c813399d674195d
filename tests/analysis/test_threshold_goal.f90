! SPDX-License-Identifier: MIT
!> &adapt strategy = 'hp' for analysis 'threshold' (threshold_goal): on the reference scene the
!> loop meets 1e-10 with both critical lambdas within their bars of the independent truth
!> and of each other's mirror image; its levels climb the hp ladder; a level whose contact
!> blocks do not fit the memory stops the loop (before the first level: STATUS_NOT_MET), as
!> max_levels does. With the left side clamped too, the two sides are independent targets:
!> lambda+ is met at an early level and reported with that level's value and bar, which
!> the later, finer levels confirm; lambda- appears and vanishes and is not met, with no bar,
!> and where it has a value at the last level a warning says where its vector sits. The same
!> on h levels: the side met reported with its bar, the other with none and its own reason.
!> On hp levels as on h levels, a side whose value vanished is not met as 'none'.
program test_threshold_goal
    use kinds, only: wp, i8
    use run_inputs, only: run_inputs_t, translate_input
    use fixtures, only: problem_of
    use status, only: status_t, STATUS_NOT_MET
    use testing, only: test_suite_t
    use fixtures, only: square_scene
    use run_config, only: config_t
    use timer, only: timings_t
    use problem, only: problem_t, build_problem
    use threshold_analysis, only: threshold_result_t
    use threshold_goal, only: adaptive_thresholds_t, solve_adapted_thresholds, &
                              threshold_goal_t, threshold_level_t
    use hp_levels, only: hp_refiner_t
    use critical_lambda, only: SIDE_PLUS, SIDE_MINUS
    implicit none

    !> lambda+ of the reference scene and its uncertainty (tests/data/truths.csv,
    !> ref-threshold: graded P4 meshes, an independent computation); lambda- is its mirror
    !> image (x -> 1 - x reverses t, so lambda -> -lambda)
    real(wp), parameter :: TRUTH_PLUS = 1.9447114426738574_wp, TRUTH_UNCERTAINTY = 5.65e-10_wp
    type(test_suite_t) :: t
    t%name = 'test_threshold_goal'
    call reference_meets_tolerance(t)
    call memory_stops_the_loop(t)
    call max_levels_stops_the_loop(t)
    call sides_are_independent(t)
    call h_sides_are_independent(t)
    call hp_vanished_side_not_met(t)
    call t%report()

contains

    !> The reference scene (unit square, nu = 0.3) from 2 x 2 P1 squares, adapted by hp to
    !> `tolerance`; the boundary search only over [-3, 3] (both thresholds inside).
    function reference_config(tolerance) result(config)
        real(wp), intent(in) :: tolerance
        type(config_t) :: config
        call square_scene(2, 'p1', 'right', config)
        config%analysis%kind = 'threshold'
        config%analysis%lambda = 5.0_wp
        config%adapt%tolerance = tolerance
        config%adapt%strategy = 'hp'
        config%sweep%lambda_min = -3.0_wp
        config%sweep%lambda_max = 3.0_wp
        config%sweep%n_lambda = 7
    end function reference_config

    subroutine run(config, out, res, stat, available)
        type(config_t), intent(in) :: config
        type(adaptive_thresholds_t), intent(out) :: out
        type(threshold_result_t), intent(out) :: res
        type(status_t), intent(out) :: stat
        integer(i8), intent(in), optional :: available
        type(problem_t) :: start
        type(timings_t) :: timings
        type(run_inputs_t) :: inputs
        call problem_of(config, start, stat)
        call translate_input(config, inputs)
        if (stat%ok()) call solve_adapted_thresholds(inputs%scene, inputs%point%lambda, &
            inputs%eigen, inputs%adapt, inputs%scan, start, out, res, timings, stat, available)
    end subroutine run

    !> The bar is meant to hold: |lambda - truth| <= bar |lambda| plus the truth's own
    !> uncertainty; the two sides are mirror images, so they agree within both bars. Level
    !> k has k layers and degrees 1 to k + 1, more dofs than level k - 1, and a bar from
    !> level 2 on.
    subroutine reference_meets_tolerance(t)
        type(test_suite_t), intent(inout) :: t
        type(adaptive_thresholds_t) :: out
        type(threshold_result_t) :: res
        type(status_t) :: stat
        real(wp) :: plus, minus, bar(2)
        integer :: k
        logical :: ladder
        call run(reference_config(1.0e-10_wp), out, res, stat)
        call t%check('reference: runs', stat%ok())
        if (.not. stat%ok()) return
        call t%check('reference: 1e-10 met', out%converged .and. &
                     all(res%estimate%computed) .and. all(res%estimate%bar <= 1.0e-10_wp))
        plus = res%thresholds%lambda(SIDE_PLUS)
        minus = res%thresholds%lambda(SIDE_MINUS)
        bar = res%estimate%bar*abs(res%thresholds%lambda)
        call t%check('reference: lambda+ within its bar of the truth', &
                     abs(plus - TRUTH_PLUS) <= bar(SIDE_PLUS) + TRUTH_UNCERTAINTY)
        call t%check('reference: lambda- within its bar of the truth', &
                     abs(minus + TRUTH_PLUS) <= bar(SIDE_MINUS) + TRUTH_UNCERTAINTY)
        call t%check('reference: lambda- mirrors lambda+ within the bars', &
                     abs(plus + minus) <= sum(bar))
        ladder = .true.
        do k = 1, size(out%levels)
            ladder = ladder .and. out%levels(k)%layers == k .and. out%levels(k)%p_min == 1 &
                     .and. out%levels(k)%p_max == k + 1
            if (k > 1) ladder = ladder .and. out%levels(k)%n_dofs > &
                                out%levels(k - 1)%n_dofs .and. &
                                all(out%levels(k)%error_bar >= 0.0_wp)
        end do
        call t%check('reference: the levels climb the hp ladder, bars from level 2', ladder .and. &
                     all(out%levels(1)%error_bar < 0.0_wp))
    end subroutine reference_meets_tolerance

    !> Level 1 has 15 contact functions (10 p^2 doubles: 18000 bytes), level 2 has 27
    !> (58320 bytes): with 30000 bytes the loop stops after level 1 and says why; with
    !> 1000 bytes nothing is solved.
    subroutine memory_stops_the_loop(t)
        type(test_suite_t), intent(inout) :: t
        type(adaptive_thresholds_t) :: out
        type(threshold_result_t) :: res
        type(status_t) :: stat
        call run(reference_config(1.0e-10_wp), out, res, stat, available=30000_i8)
        call t%check('memory: stops after level 1', stat%ok() .and. &
                     .not. out%converged .and. size(out%levels) == 1)
        if (.not. stat%ok()) return
        call t%check('memory: the outcome says so, and what the level needs', &
                     index(out%outcome, 'level 2 has p = 27 contact functions') > 0 &
                     .and. index(out%outcome, 'more than the memory available') > 0)
        call t%check('memory: the last level is reported', &
                     res%thresholds%found(SIDE_PLUS) .and. res%thresholds%found(SIDE_MINUS))
        call run(reference_config(1.0e-10_wp), out, res, stat, available=1000_i8)
        call t%check('memory: no level fits: STATUS_NOT_MET naming level 1', &
                     stat%code == STATUS_NOT_MET .and. index(stat%message, 'level 1 has p') > 0)
    end subroutine memory_stops_the_loop

    subroutine max_levels_stops_the_loop(t)
        type(test_suite_t), intent(inout) :: t
        type(adaptive_thresholds_t) :: out
        type(threshold_result_t) :: res
        type(status_t) :: stat
        type(config_t) :: config
        config = reference_config(1.0e-10_wp)
        config%adapt%max_levels = 2
        call run(config, out, res, stat)
        call t%check('max_levels: two levels, not converged, the limit named', stat%ok() .and. &
                     size(out%levels) == 2 .and. .not. out%converged .and. &
                     index(out%outcome, 'max_levels = 2') > 0)
    end subroutine max_levels_stops_the_loop

    !> The unit square with its top and left sides clamped, contact on the bottom, from 2 x 2
    !> P1 squares, hp to 1e-6 in at most 9 levels. lambda+ (1.99163) has bars that fall by a
    !> factor of about 4 per level and meets 1e-6 at level 8 (3.7e-7); lambda- (-118.2046)
    !> has a value at levels 1, 4, 5, 8, 9 only, never at three consecutive levels, so it
    !> is not met and has no bar. lambda+ is then quoted as at level 8, and the next level,
    !> a finer discretisation, lies within the sum of both levels' bars of it.
    subroutine sides_are_independent(t)
        type(test_suite_t), intent(inout) :: t
        type(adaptive_thresholds_t) :: out
        type(threshold_result_t) :: res
        type(status_t) :: stat
        type(config_t) :: config
        integer :: k, m
        logical :: appears, vanishes
        config = reference_config(1.0e-6_wp)
        config%mesh%dirichlet = 'top left'
        config%mesh%neumann = 'right'
        config%adapt%max_levels = 9
        call run(config, out, res, stat)
        call t%check('independent sides: runs 9 levels', stat%ok() .and. size(out%levels) == 9)
        if (.not. stat%ok() .or. size(out%levels) /= 9) return
        k = size(out%levels)
        m = res%estimate%met_level(SIDE_PLUS)
        call t%check('independent sides: lambda+ met before the last level, with its bar', &
                     res%estimate%computed(SIDE_PLUS) .and. m >= 2 .and. m < k .and. &
                     res%estimate%bar(SIDE_PLUS) <= 1.0e-6_wp)
        if (m < 2 .or. m >= k) return
        call t%check('independent sides: lambda+ quoted with the value and bar of its level', &
                     abs(res%thresholds%lambda(SIDE_PLUS) - out%levels(m)%lambda(SIDE_PLUS)) <= &
                     0.0_wp .and. abs(res%estimate%bar(SIDE_PLUS) - &
                                      out%levels(m)%error_bar(SIDE_PLUS)) <= 0.0_wp)
        call t%check('independent sides: the finer last level within both bars of it', &
                     abs(out%levels(k)%lambda(SIDE_PLUS) - res%thresholds%lambda(SIDE_PLUS)) <= &
                     res%estimate%bar(SIDE_PLUS)*abs(res%thresholds%lambda(SIDE_PLUS)) + &
                     out%levels(k)%error_bar(SIDE_PLUS)*abs(out%levels(k)%lambda(SIDE_PLUS)))
        appears = .false.
        vanishes = .false.
        do m = 2, k
            appears = appears .or. (out%levels(m)%found(SIDE_MINUS) .and. &
                                    .not. out%levels(m - 1)%found(SIDE_MINUS))
            vanishes = vanishes .or. (.not. out%levels(m)%found(SIDE_MINUS) .and. &
                                      out%levels(m - 1)%found(SIDE_MINUS))
        end do
        call t%check('independent sides: lambda- appears and vanishes, not met, no bar', &
                     appears .and. vanishes .and. .not. out%converged .and. &
                     .not. res%estimate%computed(SIDE_MINUS) .and. &
                     index(out%outcome, 'lambda-: tolerance') == 1 .and. &
                     index(out%outcome, 'max_levels = 9') > 0)
        ! what is known of a side that did not converge: only of lambda-, followed where it
        ! has a value at the last level, and then named in a warning of its own
        call t%check('independent sides: nothing said of lambda+ (met) as moving', &
                     .not. res%estimate%moving(SIDE_PLUS)%known)
        call t%check('independent sides: lambda- followed where it has a value at the end', &
                     res%estimate%moving(SIDE_MINUS)%known .eqv. out%levels(k)%found(SIDE_MINUS))
        if (res%estimate%moving(SIDE_MINUS)%known) call t%check('independent sides: a '// &
            'warning says where lambda- sits', any(index(res%eigen%warnings, 'lambda- = ') == 1 &
            .and. index(res%eigen%warnings, 'its vector sits') > 0))
    end subroutine sides_are_independent

    !> The same clamped square on h levels (P2 from 2 x 2 squares, 2e-2, at most 12 levels):
    !> lambda+ (1.99163, the hp run above) has a value and a bar at every level, below 2e-2
    !> from level 4 on; lambda- comes and goes (values near -5.8 and -5.0 at some levels,
    !> none at others) and never has a bar at two consecutive levels below 2e-2 (its bars
    !> are 0.45 and more). Each side is its own target: lambda+ is met and reported with the
    !> bar of the last level, which covers its value to within the digits known; lambda- is
    !> not met, reported with no bar, named first in the outcome and so in the warnings. The
    !> sides judged together (largest bar) met neither and quoted lambda-'s bar.
    subroutine h_sides_are_independent(t)
        type(test_suite_t), intent(inout) :: t
        !> lambda+ of this scene to the digits the hp run gives it (its bar 3.7e-7)
        real(wp), parameter :: PLUS = 1.99163_wp, PLUS_DIGITS = 1.0e-5_wp
        type(adaptive_thresholds_t) :: out
        type(threshold_result_t) :: res
        type(status_t) :: stat
        type(config_t) :: config
        integer :: k
        config = reference_config(2.0e-2_wp)
        config%mesh%element = 'p2'
        config%mesh%dirichlet = 'top left'
        config%mesh%neumann = 'right'
        config%adapt%strategy = 'h'
        config%adapt%max_levels = 12
        call run(config, out, res, stat)
        call t%check('h, independent sides: runs', stat%ok() .and. size(out%levels) > 0)
        if (.not. stat%ok() .or. size(out%levels) == 0) return
        k = size(out%levels)
        call t%check('h, independent sides: lambda+ met, its bar the last level''s', &
                     res%estimate%computed(SIDE_PLUS) .and. &
                     res%estimate%bar(SIDE_PLUS) <= 2.0e-2_wp .and. &
                     abs(res%estimate%bar(SIDE_PLUS) - out%levels(k)%error_bar(SIDE_PLUS)) <= &
                     0.0_wp .and. index(out%outcome, 'lambda+: tolerance 2.00E-02 met') > 0)
        call t%check('h, independent sides: lambda+ within its bar of the hp value', &
                     abs(res%thresholds%lambda(SIDE_PLUS) - PLUS) <= res%estimate%bar(SIDE_PLUS)* &
                     abs(res%thresholds%lambda(SIDE_PLUS)) + PLUS_DIGITS)
        call t%check('h, independent sides: lambda- not met, no bar, its reason first', &
                     .not. out%converged .and. .not. res%estimate%computed(SIDE_MINUS) .and. &
                     res%estimate%bar(SIDE_MINUS) < 0.0_wp .and. &
                     index(out%outcome, 'lambda-: tolerance 2.00E-02 not met') == 1 .and. &
                     any(index(res%eigen%warnings, 'lambda-: tolerance') == 1))
    end subroutine h_sides_are_independent
    !> The rule of the sides on hp levels, as on h levels (judge_sides): a side with no value
    !> at the last three levels is met as 'none' only where it never had one; lambda- had a
    !> value at levels 1 and 2 and none at levels 3 to 5: it vanishes with the mesh, not
    !> converged (before, hp met it as 'none at hp levels 3 to 5'). lambda+, never found, is
    !> met as none at level 3. The levels are the goal's rows alone (no mesh is solved).
    subroutine hp_vanished_side_not_met(t)
        type(test_suite_t), intent(inout) :: t
        type(threshold_goal_t) :: goal
        type(hp_refiner_t) :: refiner
        type(threshold_level_t) :: row
        integer :: level
        allocate (goal%levels(0), goal%targets(2))
        goal%targets(1)%outcome = ''
        goal%targets(2)%outcome = ''
        do level = 1, 5
            row = threshold_level_t()
            row%level = level
            row%layers = level
            row%n_dofs = 100*2**level
            row%found(SIDE_MINUS) = level <= 2
            row%lambda(SIDE_MINUS) = -3.0_wp - 0.1_wp*level
            if (level == 2) row%error_bar(SIDE_MINUS) = 0.03_wp
            goal%levels = [goal%levels, row]
            call goal%judge(refiner, level, 1.0e-6_wp)
        end do
        call t%check('hp, a vanished side: lambda- stopped as vanishing, not met as none', &
                     .not. goal%targets(SIDE_MINUS)%converged() .and. &
                     .not. goal%targets(SIDE_MINUS)%active() .and. &
                     index(goal%targets(SIDE_MINUS)%outcome, 'lambda-: no value at hp levels '// &
                           '3 to 5 after') == 1 .and. &
                     index(goal%targets(SIDE_MINUS)%outcome, 'it vanishes with the mesh, '// &
                           'not converged') > 0 .and. &
                     index(goal%targets(SIDE_PLUS)%outcome, 'none at hp levels 1 to 3') > 0 .and. &
                     goal%targets(SIDE_PLUS)%converged())
    end subroutine hp_vanished_side_not_met
end program test_threshold_goal
