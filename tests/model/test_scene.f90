! SPDX-License-Identifier: MIT
!> The scene (module scene) and the problem built from it (build_problem): halving a
!> rectangle doubles nx and ny and keeps the rest, a Gmsh scene stays itself; the words that
!> name its mesh in messages; the sizes of the problem of a P1 rectangle in closed form (with
!> the top fixed: 2 (nx + 1) ny free dofs, 2 nx ny cells, nx + 1 contact nodes) on the scene
!> and on its halved scene; the scaled units of E and of the size (powers of two: E = 2^10,
!> size 2^-3), the mesh kept in the input's coordinates; a problem in the input's units
!> refused beyond their range, naming the analysis.
program test_scene
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use testing, only: test_suite_t
    use element_types, only: ELEMENT_P1
    use scene, only: scene_t, MESH_GMSH
    use problem, only: problem_t, build_problem
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_scene'
    call halving_and_words(t)
    call problem_sizes(t)
    call scaled_units(t)
    call input_units_range(t)
    call t%report()

contains

    !> a and b are the same number (a copy, or a binary fraction: exact).
    elemental logical function same(a, b)
        real(wp), intent(in) :: a, b
        same = abs(a - b) <= 0.0_wp
    end function same

    function rectangle(nx, ny) result(scn)
        integer, intent(in) :: nx, ny
        type(scene_t) :: scn
        scn%name = 'in.nml'
        scn%width = 2.0_wp
        scn%height = 1.0_wp
        scn%nx = nx
        scn%ny = ny
        scn%element = ELEMENT_P1
        scn%file = ''
    end function rectangle

    subroutine halving_and_words(t)
        type(test_suite_t), intent(inout) :: t
        type(scene_t) :: scn, halved
        scn = rectangle(4, 2)
        scn%material%poisson = 0.25_wp
        halved = scn%halved()
        call t%check('halved rectangle: 2 nx x 2 ny, the rest kept', halved%nx == 8 .and. &
                     halved%ny == 4 .and. same(halved%width, scn%width) .and. &
                     same(halved%material%poisson, scn%material%poisson) .and. &
                     halved%name == 'in.nml' .and. halved%contact == scn%contact)
        call t%check('rectangle words: nx = 4, ny = 2', scn%mesh_words() == 'nx = 4, ny = 2' &
                     .and. scn%source_name() == 'rectangle')
        scn%source = MESH_GMSH
        scn%file = 'a.msh'
        halved = scn%halved()
        call t%check('halved Gmsh scene: itself', halved%nx == 4 .and. halved%ny == 2 .and. &
                     halved%source == MESH_GMSH)
        call t%check('Gmsh words: file = ''a.msh''', scn%mesh_words() == "file = 'a.msh'" &
                     .and. scn%source_name() == 'gmsh')
    end subroutine halving_and_words

    subroutine problem_sizes(t)
        type(test_suite_t), intent(inout) :: t
        type(problem_t) :: prob, fine
        type(status_t) :: stat
        type(scene_t) :: scn
        scn = rectangle(4, 2)
        call build_problem(scn, prob, stat)
        if (stat%ok()) call build_problem(scn%halved(), fine, stat)
        call t%check('problems build', stat%ok())
        if (.not. stat%ok()) return
        call t%check('4 x 2 P1: 20 free dofs, 16 cells, 5 contact nodes', &
                     prob%dofs%n_free == 20 .and. prob%mesh%n_cells() == 16 .and. &
                     prob%contact%p() == 5)
        call t%check('halved, 8 x 4: 72 free dofs, 64 cells, 9 contact nodes', &
                     fine%dofs%n_free == 72 .and. fine%mesh%n_cells() == 64 .and. &
                     fine%contact%p() == 9)
        call t%check('the material is the scene''s', same(prob%young, scn%material%young) .and. &
                     same(prob%poisson, scn%material%poisson))
    end subroutine problem_sizes

    subroutine scaled_units(t)
        type(test_suite_t), intent(inout) :: t
        type(problem_t) :: prob
        type(status_t) :: stat
        type(scene_t) :: scn
        scn = rectangle(2, 2)
        scn%width = 0.125_wp
        scn%height = 0.0625_wp
        scn%material%young = 1024.0_wp
        call build_problem(scn, prob, stat)
        call t%check('scaled problem builds', stat%ok())
        if (.not. stat%ok()) return
        call t%check('E = 2^10, size 2^-3: exponents 10 and -3, mu by 2^13', &
                     prob%units%young_exponent == 10 .and. prob%units%length_exponent == -3 &
                     .and. prob%units%mu_exponent() == 13)
        call t%check('the mesh keeps the input''s coordinates', &
                     same(maxval(prob%mesh%coords(1, :)), 0.125_wp))
    end subroutine scaled_units

    subroutine input_units_range(t)
        type(test_suite_t), intent(inout) :: t
        type(problem_t) :: prob
        type(status_t) :: stat
        type(scene_t) :: scn
        scn = rectangle(2, 2)
        scn%material%young = 1.0e200_wp
        call build_problem(scn, prob, stat, input_units_for='branch')
        call t%check('E = 1e200 in the input''s units: refused naming the analysis', &
                     stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'in.nml: '// &
                     '&material: young = ') == 1 .and. index(stat%message, "'branch'") > 0)
        call build_problem(scn, prob, stat)
        call t%check('E = 1e200 scaled: builds', stat%ok())
    end subroutine input_units_range
end program test_scene
