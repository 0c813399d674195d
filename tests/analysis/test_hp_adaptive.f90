! SPDX-License-Identifier: MIT
!> The hp loop of analysis 'eigen' (hp_adaptive) on the reference scene from 2 x 2 P1 squares
!> at lambda = 5, to a tolerance of 1e-6 (6 levels, about 0.15 s): it converges with the
!> continuum mu of tests/data/truths.csv (0.75284361680855649 +- 4.6e-12) inside its bar, the
!> bar of every level at least that level's true error, and each level one graded layer and
!> one degree more than the one before, degree 1 at the singular corners.
program test_hp_adaptive
    use kinds, only: wp
    use run_inputs, only: run_inputs_t, translate_input
    use fixtures, only: problem_of
    use status, only: status_t
    use testing, only: test_suite_t
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use eigen_goal, only: adapt_eigen, adapted_eigen_t, HP_ESTIMATE
    use fixtures, only: adaptive_scene, REF_MU
    implicit none

    type(test_suite_t) :: t
    type(adapted_eigen_t) :: out

    t%name = 'test_hp_adaptive'
    call run_loop(out)
    if (allocated(out%levels)) then
        call converges_to_the_truth(t, out)
        call bars_cover_the_true_errors(t, out)
        call degrees_rise_by_one_per_level(t, out)
    end if
    call t%report()

contains

    subroutine run_loop(out)
        type(adapted_eigen_t), intent(out) :: out
        type(config_t) :: config
        type(problem_t) :: start
        type(timings_t) :: timings
        type(status_t) :: stat
        type(run_inputs_t) :: inputs
        type(adapted_eigen_t), allocatable :: outs(:)
        call adaptive_scene('eigen', 'hp', 1.0e-6_wp, 0, 'unused', config)
        call problem_of(config, start, stat)
        call translate_input(config, inputs)
        if (stat%ok()) call adapt_eigen(inputs%scene, [inputs%point%lambda], inputs%eigen, &
                                        inputs%adapt, start, outs, timings, stat, .true.)
        if (stat%ok()) out = outs(1)
        call t%check('the loop runs', stat%ok())
        if (.not. stat%ok()) write (*, '(a)') stat%message
    end subroutine run_loop

    !> Converged (not by a limit nor the round-off floor), the last bar at most 1e-6 and the
    !> truth within it; the result's error record is the last level's bar, of the hp kind.
    subroutine converges_to_the_truth(t, out)
        type(test_suite_t), intent(inout) :: t
        type(adapted_eigen_t), intent(in) :: out
        real(wp) :: mu, bar
        associate (last => out%levels(size(out%levels)))
            mu = last%mu
            bar = last%error_bar
            call t%check('converged, not at the floor', out%converged .and. .not. out%floor_reached)
            call t%check('last bar in (0, 1e-6]', bar > 0.0_wp .and. bar <= 1.0e-6_wp)
            call t%check('|mu - truth| <= bar mu', last%has_mu .and. abs(mu - REF_MU) <= bar*mu)
            call t%check('the result''s mu and bar are the last level''s', &
                         abs(real(out%res%spec%mu(out%res%spec%lowest_positive()), wp) - mu) <= 0.0_wp &
                         .and. abs(out%res%error%bar - bar) <= 0.0_wp .and. &
                         out%res%error%method == HP_ESTIMATE)
            call t%check('the outcome says the tolerance was met', &
                         index(out%outcome, ' met at level ') > 0)
        end associate
    end subroutine converges_to_the_truth

    !> Every level after the first carries a bar, at least its true relative error; the
    !> first has none (no previous level to compare with).
    subroutine bars_cover_the_true_errors(t, out)
        type(test_suite_t), intent(inout) :: t
        type(adapted_eigen_t), intent(in) :: out
        integer :: k
        logical :: covered
        call t%check('first level: no bar', out%levels(1)%error_bar < 0.0_wp)
        covered = size(out%levels) >= 2
        do k = 2, size(out%levels)
            associate (row => out%levels(k))
                if (.not. (row%has_mu .and. row%error_bar >= abs(row%mu - REF_MU)/row%mu)) &
                    covered = .false.
            end associate
        end do
        call t%check('every later level: bar >= |mu - truth| / mu', covered)
    end subroutine bars_cover_the_true_errors

    !> Level k: k layers, degrees 1 (at the singular points) to k + 1, more dofs and cells
    !> than level k - 1.
    subroutine degrees_rise_by_one_per_level(t, out)
        type(test_suite_t), intent(inout) :: t
        type(adapted_eigen_t), intent(in) :: out
        integer :: k
        logical :: rising
        rising = .true.
        do k = 1, size(out%levels)
            associate (row => out%levels(k))
                if (row%level /= k .or. row%layers /= k .or. row%p_min /= 1 .or. &
                    row%p_max /= k + 1) rising = .false.
                if (k > 1) then
                    if (row%n_dofs <= out%levels(k - 1)%n_dofs .or. &
                        row%n_cells <= out%levels(k - 1)%n_cells) rising = .false.
                end if
            end associate
        end do
        call t%check('level k: k layers, degrees 1 to k + 1, more dofs and cells', rising)
        call t%check('the last space''s degrees are the last level''s', &
                     minval(out%space%cell_degree) == 1 .and. &
                     maxval(out%space%cell_degree) == out%levels(size(out%levels))%p_max)
    end subroutine degrees_rise_by_one_per_level
end program test_hp_adaptive
