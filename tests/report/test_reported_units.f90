! SPDX-License-Identifier: MIT
!> The one conversion of the report (reported_units): mu in a problem's scaled units times
!> 2^(young exponent - length exponent) is the input's, exactly (a power of two); and the
!> same body at E = 2^30, size 2^-20 gives, once converted, 2^50 times the lowest positive
!> mu of the unit body bit for bit (the scaled problems are the same arithmetic), with the
!> same backward errors. critical_cn: the lowest alone, or every positive mu up to cn_max
!> in ascending order.
program test_reported_units
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use timer, only: timings_t
    use unit_scaling, only: units_t
    use spectrum, only: spectrum_t, KIND_POSITIVE, KIND_NEGATIVE
    use scene, only: scene_t
    use problem, only: problem_t, build_problem
    use method_options, only: eigen_options_t, SOLVER_DENSE
    use eigen_solve, only: eigen_result_t, solve_eigen
    use reported_units, only: to_input_units, critical_cn
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_reported_units'
    call powers_of_two(t)
    call scaled_body(t)
    call critical_list(t)
    call t%report()

contains

    subroutine powers_of_two(t)
        type(test_suite_t), intent(inout) :: t
        type(units_t) :: units
        complex(wp) :: mu(2)
        real(wp) :: x(2)
        units%young_exponent = 3
        units%length_exponent = -2
        mu = [(0.75_wp, 0.0_wp), (1.5_wp, -2.5_wp)]
        x = [0.75_wp, -3.0_wp]
        call to_input_units(units, mu)
        call to_input_units(units, x)
        call t%check('complex mu times 2^5, exactly', &
                     all(abs(mu - 32.0_wp*[(0.75_wp, 0.0_wp), (1.5_wp, -2.5_wp)]) <= 0.0_wp))
        call t%check('real mu times 2^5, exactly', &
                     all(abs(x - 32.0_wp*[0.75_wp, -3.0_wp]) <= 0.0_wp))
    end subroutine powers_of_two

    subroutine scaled_body(t)
        type(test_suite_t), intent(inout) :: t
        type(eigen_result_t) :: unit, scaled
        type(status_t) :: stat
        real(wp) :: mu_unit, mu_scaled
        call solve(1.0_wp, 1.0_wp, unit, stat)
        if (stat%ok()) call solve(2.0_wp**30, 2.0_wp**(-20), scaled, stat)
        call t%check('both bodies solved', stat%ok())
        if (.not. stat%ok()) return
        mu_unit = real(unit%spec%mu(unit%spec%lowest_positive()), wp)
        mu_scaled = real(scaled%spec%mu(scaled%spec%lowest_positive()), wp)
        call t%check('mu(2^30, 2^-20) = 2^50 mu(1, 1), bit for bit', &
                     abs(mu_scaled - 2.0_wp**50*mu_unit) <= 0.0_wp)
        call t%check('the same backward errors', &
                     all(abs(scaled%spec%residual - unit%spec%residual) <= 0.0_wp))
    end subroutine scaled_body

    !> The 4 x 4 reference scene with E and a side `size`, densely at lambda = 5, reported
    !> in the input's units.
    subroutine solve(young, size, res, stat)
        real(wp), intent(in) :: young, size
        type(eigen_result_t), intent(out) :: res
        type(status_t), intent(out) :: stat
        type(scene_t) :: scn
        type(problem_t) :: prob
        type(eigen_options_t) :: options
        type(timings_t) :: timings
        scn%name = 'in.nml'
        scn%nx = 4
        scn%ny = 4
        scn%width = size
        scn%height = size
        scn%material%young = young
        options%solver = SOLVER_DENSE
        call build_problem(scn, prob, stat)
        if (stat%ok()) call solve_eigen(scn, prob, 5.0_wp, options, res, timings, stat)
        if (stat%ok()) call to_input_units(prob%units, res%spec%mu)
    end subroutine solve

    subroutine critical_list(t)
        type(test_suite_t), intent(inout) :: t
        type(spectrum_t) :: spec
        real(wp), allocatable :: values(:)
        allocate (spec%mu(4), spec%kind(4))
        spec%mu(:) = [(0.75_wp, 0.0_wp), (2.0_wp, 0.0_wp), (3.0_wp, 0.0_wp), (-3.0_wp, 0.0_wp)]
        spec%kind(:) = [KIND_POSITIVE, KIND_POSITIVE, KIND_POSITIVE, KIND_NEGATIVE]
        values = critical_cn(spec, 0.0_wp)
        call t%check('cn_max 0: the lowest alone', size(values) == 1 .and. &
                     abs(values(1) - 0.75_wp) <= 0.0_wp)
        values = critical_cn(spec, 2.5_wp)
        call t%check('cn_max 2.5: 0.75 and 2, ascending', size(values) == 2 .and. &
                     all(abs(values - [0.75_wp, 2.0_wp]) <= 0.0_wp))
    end subroutine critical_list
end program test_reported_units
