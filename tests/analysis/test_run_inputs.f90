! SPDX-License-Identifier: MIT
!> The translation of the input record into the analyses' types (run_inputs): the defaults
!> of the input are those of the scene, the study point and the options; every accepted
!> string becomes its enumeration (the kinds, the solvers, the estimate modes, the
!> operators, the refinements); the mesh file is kept as given; the boundary search of a
!> 'threshold' takes every 10th of the 401 default lambdas (41, both ends), a sweep all of
!> them; an explicit list of lambdas is the sweep, with its spacing named 'list'.
program test_run_inputs
    use kinds, only: wp
    use testing, only: test_suite_t
    use run_config, only: config_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q2
    use scene, only: MESH_RECTANGLE, MESH_GMSH
    use method_options, only: SOLVER_AUTO, SOLVER_DENSE, SOLVER_ARPACK, ESTIMATE_AUTO, &
                              ESTIMATE_ON, ESTIMATE_OFF, OPERATOR_REDUCED, OPERATOR_FULL, &
                              REFINE_NONE, REFINE_H, REFINE_HP
    use run_inputs, only: run_inputs_t, translate_input, ANALYSIS_EIGEN, ANALYSIS_THRESHOLD, &
                          ANALYSIS_SWEEP, ANALYSIS_BRANCH, ANALYSIS_SOLVE, ANALYSIS_UNKNOWN, &
                          THRESHOLD_SCAN_POINTS
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_run_inputs'
    call defaults(t)
    call strings_become_enumerations(t)
    call scans(t)
    call t%report()

contains

    subroutine defaults(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        config%input_file = 'in.nml'
        call translate_input(config, inputs)
        call t%check('default: eigen', inputs%analysis == ANALYSIS_EIGEN .and. &
                     inputs%analysis_name == 'eigen')
        associate (s => inputs%scene)
            call t%check('default scene: the 8 x 8 P1 unit square, right diagonals', &
                         s%name == 'in.nml' .and. s%source == MESH_RECTANGLE .and. &
                         s%nx == 8 .and. s%ny == 8 .and. s%element == ELEMENT_P1 .and. &
                         s%diagonal == 'right' .and. same(s%width, 1.0_wp) .and. &
                         same(s%height, 1.0_wp))
            call t%check('default scene: E = 1, nu = 0.3, top fixed, bottom in contact', &
                         same(s%material%young, 1.0_wp) .and. &
                         same(s%material%poisson, 0.3_wp) .and. s%dirichlet == 'top' .and. &
                         s%neumann == 'left right' .and. s%contact == 'bottom')
        end associate
        call t%check('default point: lambda = 5, nu = 0.3, scene 1', &
                     same(inputs%point%lambda, 5.0_wp) .and. &
                     same(inputs%point%poisson, 0.3_wp) .and. inputs%point%scene == 1)
        call t%check('default eigen options: auto, auto, reduced, one mode', &
                     inputs%eigen%solver == SOLVER_AUTO .and. &
                     inputs%eigen%estimate == ESTIMATE_AUTO .and. &
                     inputs%eigen%operator == OPERATOR_REDUCED .and. inputs%eigen%modes == 1 &
                     .and. inputs%eigen%nev == 6 .and. inputs%eigen%dense_max_contact == 24)
        call t%check('default adapt options: no refinement', &
                     inputs%adapt%refine == REFINE_NONE .and. inputs%adapt%p_max == 20)
    end subroutine defaults

    subroutine strings_become_enumerations(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: KINDS(6) = [character(len=12) :: 'eigen', 'threshold', &
            'lambda_sweep', 'branch', 'solve', 'other']
        integer, parameter :: ANALYSES(6) = [ANALYSIS_EIGEN, ANALYSIS_THRESHOLD, &
            ANALYSIS_SWEEP, ANALYSIS_BRANCH, ANALYSIS_SOLVE, ANALYSIS_UNKNOWN]
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        integer :: i
        do i = 1, size(KINDS)
            config%analysis%kind = KINDS(i)
            call translate_input(config, inputs)
            call t%check('kind '//trim(KINDS(i)), inputs%analysis == ANALYSES(i))
        end do
        config%eigen%solver = 'dense'
        config%eigen%estimate = 'on'
        config%eigen%operator = 'full'
        config%mesh%source = 'gmsh'
        config%mesh%file = 'meshes/a.msh'
        config%mesh%element = 'q2'
        config%adapt%tolerance = 1.0e-6_wp
        config%adapt%strategy = 'h'
        call translate_input(config, inputs)
        call t%check('dense, on, full, gmsh, q2, h', inputs%eigen%solver == SOLVER_DENSE .and. &
                     inputs%eigen%estimate == ESTIMATE_ON .and. &
                     inputs%eigen%operator == OPERATOR_FULL .and. &
                     inputs%scene%source == MESH_GMSH .and. &
                     inputs%scene%file == 'meshes/a.msh' .and. &
                     inputs%scene%element == ELEMENT_Q2 .and. inputs%adapt%refine == REFINE_H)
        config%eigen%solver = 'arpack'
        config%eigen%estimate = 'off'
        config%adapt%strategy = 'hp'
        call translate_input(config, inputs)
        call t%check('arpack, off, hp', inputs%eigen%solver == SOLVER_ARPACK .and. &
                     inputs%eigen%estimate == ESTIMATE_OFF .and. inputs%adapt%refine == REFINE_HP)
        config%adapt%tolerance = 0.0_wp
        call translate_input(config, inputs)
        call t%check('hp without a tolerance: no refinement', inputs%adapt%refine == REFINE_NONE)
    end subroutine strings_become_enumerations

    subroutine scans(t)
        type(test_suite_t), intent(inout) :: t
        type(config_t) :: config
        type(run_inputs_t) :: inputs
        config%analysis%kind = 'threshold'
        call translate_input(config, inputs)
        call t%check('threshold: 401 sweep lambdas, linear', size(inputs%sweep) == 401 .and. &
                     inputs%sweep_spacing == 'linear')
        call t%check('threshold: the search on every 10th, both ends', &
                     size(inputs%scan) == THRESHOLD_SCAN_POINTS .and. &
                     same(inputs%scan(1), -20.0_wp) .and. same(inputs%scan(41), 20.0_wp) .and. &
                     same(inputs%scan(2), inputs%sweep(11)))
        config%analysis%kind = 'lambda_sweep'
        call translate_input(config, inputs)
        call t%check('lambda_sweep: the search on all of them', &
                     size(inputs%scan) == 401 .and. all(same(inputs%scan, inputs%sweep)))
        config%sweep%lambdas(1:3) = [-1.0_wp, 2.0_wp, 3.0_wp]
        call translate_input(config, inputs)
        call t%check('an explicit list: the sweep, spacing ''list''', size(inputs%sweep) == 3 &
                     .and. same(inputs%sweep(2), 2.0_wp) .and. inputs%sweep_spacing == 'list')
    end subroutine scans

    !> a and b are the same number (a copy of a constant: exact).
    elemental logical function same(a, b)
        real(wp), intent(in) :: a, b
        same = abs(a - b) <= 0.0_wp
    end function same
end program test_run_inputs
