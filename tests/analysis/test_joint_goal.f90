! SPDX-License-Identifier: MIT
!> One hp climb for a sweep and its thresholds (joint_goal), against the two climbs it
!> replaces on the same levels: the reference scene from 2 x 2 P1 squares to 1e-6 at
!> lambda = -5, 1 and 5. The hp levels do not depend on the goal, so each point and each
!> side must end at the level and with the values its own loop reaches (an independent
!> computation: adapt_eigen of the sweep's lambdas for the points, solve_adapted_thresholds
!> for the sides); a target judged or stopped by the wrong part, or a factor borrowed from
!> the wrong level, changes the level count or the values. The second scene, the 2 x 1 rectangle at nu = 0.1
!> with 11 lambdas, has sides that meet the tolerance at level 4 while the points climb on,
!> and whose check one degree higher takes them above it: alone their loop climbs again
!> (to level 8), and so must they in the joint loop.
program test_joint_goal
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use fixtures, only: problem_of, adaptive_scene
    use run_config, only: config_t
    use run_inputs, only: run_inputs_t, translate_input
    use timer, only: timings_t
    use problem, only: problem_t
    use critical_lambda, only: SIDE_PLUS, SIDE_MINUS, SIDE_LABELS
    use eigen_goal, only: adapt_eigen, adapted_eigen_t
    use threshold_goal, only: adaptive_thresholds_t, solve_adapted_thresholds
    use threshold_analysis, only: threshold_result_t
    use joint_goal, only: solve_joint_sweep
    use real_format, only: real_to_text
    implicit none

    !> Relative agreement asserted: both climbs factor the same matrices with the same
    !> library, so the values agree to the last bits; 1e-12 leaves room for a BLAS that
    !> sums in another order (a few hundred ulps of values near 1), far below the 1e-6 bars.
    real(wp), parameter :: SAME = 1.0e-12_wp
    real(wp), parameter :: SQUARE_LAMBDAS(3) = [-5.0_wp, 1.0_wp, 5.0_wp]
    real(wp), allocatable :: lambdas(:)
    integer :: i
    type(test_suite_t) :: t
    type(config_t) :: config
    type(run_inputs_t) :: inputs
    type(problem_t) :: start
    type(status_t) :: stat
    type(adaptive_thresholds_t) :: joint_sides, alone_sides
    type(threshold_result_t) :: joint_res, alone_res
    t%name = 'test_joint_goal'
    lambdas = SQUARE_LAMBDAS
    call adaptive_scene('lambda_sweep', 'hp', 1.0e-6_wp, 0, 'unused', config)
    call compare('square: ')
    lambdas = [(-20.0_wp + 4.0_wp*i, i=0, 10)]
    call adaptive_scene('lambda_sweep', 'hp', 1.0e-6_wp, 0, 'unused', config)
    config%mesh%width = 2.0_wp
    config%material%poisson = 0.1_wp
    call compare('2 x 1, nu = 0.1: ')
    deallocate (lambdas)   ! the main program's (AddressSanitizer)
    call t%report()

contains

    !> The joint climb of `config` at `lambdas` against the climbs alone.
    subroutine compare(scene)
        character(len=*), intent(in) :: scene
        config%sweep%adapt_thresholds = .true.
        call problem_of(config, start, stat)
        call translate_input(config, inputs)
        if (stat%ok()) call joint_run(stat)
        call t%check(scene//'the joint climb runs', stat%ok())
        if (.not. stat%ok()) return
        call points_end_as_alone(t, scene)
        call sides_end_as_alone(t, scene)
    end subroutine compare

    subroutine joint_run(stat)
        type(status_t), intent(out) :: stat
        type(timings_t) :: timings
        call solve_joint_sweep(inputs%scene, inputs%point%lambda, lambdas, inputs%eigen, &
                               inputs%adapt, inputs%scan, start, joint_sides, joint_res, &
                               timings, stat)
    end subroutine joint_run

    !> Each lambda: the mu, bar and dofs of its own climb (adapt_eigen of that lambda alone),
    !> and lambda = 1 (no positive mu on the scene) none.
    subroutine points_end_as_alone(t, scene)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: scene
        type(adapted_eigen_t), allocatable :: alone(:)
        type(timings_t) :: timings
        type(status_t) :: stat
        character(len=:), allocatable :: name
        integer :: i, n, not_met
        not_met = 0
        associate (curve => joint_res%sweep)
            call t%check(scene//'the sweep has its points, all complete', &
                         size(curve%lambda) == size(lambdas) .and. all(curve%complete))
            if (size(curve%lambda) /= size(lambdas)) return
            call adapt_eigen(inputs%scene, lambdas, inputs%eigen, inputs%adapt, start, alone, &
                             timings, stat, .false.)
            call t%check(scene//'the sweep alone runs', stat%ok())
            if (.not. stat%ok()) return
            do i = 1, size(lambdas)
                n = size(alone(i)%levels)
                if (a_has_mu_not_met(alone(i))) not_met = not_met + 1
                name = scene//'lambda '//trim(real_to_text(lambdas(i)))
                associate (a => alone(i)%levels(n))
                    call t%check(name//': mu found as alone', curve%found(i) .eqv. a%has_mu)
                    if (.not. a%has_mu) cycle
                    call t%check(name//': the same mu', &
                                 abs(curve%mu(i) - a%mu) <= SAME*abs(a%mu))
                    call t%check(name//': the same bar on the same level', &
                                 abs(curve%error_bar(i) - a%error_bar) <= SAME*a%error_bar &
                                 .and. curve%n_dofs(i) == a%n_dofs)
                end associate
            end do
            if (size(lambdas) == 3) call t%check(scene//'lambda = 1 has no positive mu', &
                                                 .not. curve%found(2))
            call t%check(scene//'the points not met are those not met alone', &
                         curve%n_not_met == not_met)
        end associate
    end subroutine points_end_as_alone

    pure logical function a_has_mu_not_met(o)
        type(adapted_eigen_t), intent(in) :: o
        a_has_mu_not_met = (any(o%levels%has_mu)) .and. .not. o%converged
    end function a_has_mu_not_met

    !> Each side: the levels, values and bars of the threshold run's own climb, and its
    !> verdict.
    subroutine sides_end_as_alone(t, scene)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: scene
        type(timings_t) :: timings
        type(status_t) :: stat
        character(len=:), allocatable :: name
        integer :: side, n
        call solve_adapted_thresholds(inputs%scene, inputs%point%lambda, inputs%eigen, &
            inputs%adapt, inputs%scan, start, alone_sides, alone_res, timings, stat)
        call t%check(scene//'the threshold run alone runs', stat%ok())
        if (.not. stat%ok()) return
        n = size(alone_sides%levels)
        call t%check(scene//'the sides climb as many levels as alone', &
                     size(joint_sides%levels) == n .and. n > 1)
        if (size(joint_sides%levels) /= n) return
        call t%check(scene//'the sides converge as alone', &
                     (joint_sides%converged .eqv. alone_sides%converged) .and. &
                     joint_sides%converged)
        do side = SIDE_PLUS, SIDE_MINUS
            name = scene//trim(SIDE_LABELS(side))
            associate (j => joint_sides%levels(n), a => alone_sides%levels(n))
                call t%check(name//': found as alone', j%found(side) .eqv. a%found(side))
                call t%check(name//': the same value at the last level', &
                             abs(j%lambda(side) - a%lambda(side)) <= SAME*abs(a%lambda(side)))
                call t%check(name//': the same bar', abs(j%error_bar(side) - &
                             a%error_bar(side)) <= SAME*abs(a%error_bar(side)))
                call t%check(name//': the reported value as alone', &
                             abs(joint_res%thresholds%lambda(side) - &
                                 alone_res%thresholds%lambda(side)) <= &
                             SAME*abs(alone_res%thresholds%lambda(side)))
            end associate
        end do
    end subroutine sides_end_as_alone
end program test_joint_goal
