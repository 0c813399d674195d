! SPDX-License-Identifier: MIT
!> The problem on the mesh of halved cells (halved_mesh): a rectangle rebuilt with 2 nx x
!> 2 ny cells (its scene halved); a mesh of triangles bisected twice (four times the cells,
!> the same area and contact length, the halved scene the same); a mesh of quadrilaterals of
!> a file not halved, saying why. And what the halved mesh is for: the lowest positive mu of
!> the reference scene (P1, 8 x 8) moves toward the continuum value (tests/data/truths.csv)
!> on the halved mesh, its error falling by a factor between 2^-2.5 and 2^-0.5: an order
!> between 0.5 and 2.5 (measured 1.4 from 8 x 8 and 1.7 from 16 x 16; from 4 x 4 the mesh is
!> not yet in the asymptotic range, 0.3).
program test_halved_mesh
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use timer, only: timings_t
    use element_types, only: ELEMENT_Q1
    use scene, only: scene_t, MESH_GMSH
    use mesh, only: mesh_t
    use mesh_structured, only: structured_rectangle
    use problem, only: problem_t, build_problem
    use method_options, only: eigen_options_t, SOLVER_DENSE
    use eigen_solve, only: eigen_result_t, solve_eigen
    use halved_mesh, only: build_halved_problem
    use fixtures, only: single_triangle, REF_MU
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_halved_mesh'
    call rectangle_halved(t)
    call triangles_bisected_twice(t)
    call quadrilaterals_of_a_file(t)
    call mu_moves_toward_the_continuum(t)
    call t%report()

contains

    subroutine rectangle_halved(t)
        type(test_suite_t), intent(inout) :: t
        type(scene_t) :: scn, halved
        type(problem_t) :: prob, fine
        type(status_t) :: stat
        character(len=:), allocatable :: why_not
        scn%name = 'in.nml'
        scn%nx = 3
        scn%ny = 2
        call build_problem(scn, prob, stat)
        if (stat%ok()) call build_halved_problem(scn, prob, halved, fine, why_not, stat)
        call t%check('rectangle: halved', stat%ok() .and. len(why_not) == 0)
        if (.not. stat%ok()) return
        call t%check('rectangle: 6 x 4 cells, four times as many', halved%nx == 6 .and. &
                     halved%ny == 4 .and. fine%mesh%n_cells() == 4*prob%mesh%n_cells())
    end subroutine rectangle_halved

    subroutine triangles_bisected_twice(t)
        type(test_suite_t), intent(inout) :: t
        type(scene_t) :: scn, halved
        type(mesh_t) :: m
        type(problem_t) :: prob, fine
        type(status_t) :: stat
        character(len=:), allocatable :: why_not
        call single_triangle(2.0_wp, m)
        scn%name = 'in.nml'
        scn%source = MESH_GMSH
        scn%file = 'one.msh'
        scn%dirichlet = 'fixed'
        scn%neumann = 'side'
        scn%contact = 'contact'
        call build_problem(scn, prob, stat, given_mesh=m)
        if (stat%ok()) call build_halved_problem(scn, prob, halved, fine, why_not, stat)
        call t%check('one triangle: halved', stat%ok() .and. len(why_not) == 0)
        if (.not. stat%ok()) return
        call t%check('one triangle: four cells, the same scene', fine%mesh%n_cells() == 4 &
                     .and. halved%source == MESH_GMSH .and. halved%file == 'one.msh')
        call t%check('one triangle: the same area (bisections of binary fractions: exact)', &
                     abs(area(fine%mesh) - area(prob%mesh)) <= 0.0_wp)
        call t%check('one triangle: the contact nodes on the same segment (y = 0, 0 <= x < 2)', &
                     fine%contact%p() >= prob%contact%p() .and. &
                     all(abs(fine%mesh%coords(2, fine%contact%nodes)) <= 0.0_wp) .and. &
                     all(fine%mesh%coords(1, fine%contact%nodes) >= 0.0_wp .and. &
                         fine%mesh%coords(1, fine%contact%nodes) < 2.0_wp))
    end subroutine triangles_bisected_twice

    subroutine quadrilaterals_of_a_file(t)
        type(test_suite_t), intent(inout) :: t
        type(scene_t) :: scn, halved
        type(mesh_t) :: m
        type(problem_t) :: prob, fine
        type(status_t) :: stat
        character(len=:), allocatable :: why_not
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_Q1, 'right', m, stat)
        scn%name = 'in.nml'
        scn%source = MESH_GMSH
        scn%file = 'quads.msh'
        if (stat%ok()) call build_problem(scn, prob, stat, given_mesh=m)
        if (stat%ok()) call build_halved_problem(scn, prob, halved, fine, why_not, stat)
        call t%check('Q1 of a file: not halved, saying why', stat%ok() .and. &
                     why_not == 'q1 cells of a Gmsh mesh are not halved here')
    end subroutine quadrilaterals_of_a_file

    subroutine mu_moves_toward_the_continuum(t)
        type(test_suite_t), intent(inout) :: t
        type(scene_t) :: scn, halved
        type(problem_t) :: prob, fine
        type(eigen_options_t) :: options
        type(eigen_result_t) :: coarse_res, fine_res
        type(timings_t) :: timings
        type(status_t) :: stat
        character(len=:), allocatable :: why_not
        real(wp) :: e_coarse, e_fine, ratio
        scn%name = 'in.nml'
        scn%nx = 8
        scn%ny = 8
        options%solver = SOLVER_DENSE
        call build_problem(scn, prob, stat)
        if (stat%ok()) call build_halved_problem(scn, prob, halved, fine, why_not, stat)
        if (stat%ok()) call solve_eigen(scn, prob, 5.0_wp, options, coarse_res, timings, stat)
        if (stat%ok()) call solve_eigen(halved, fine, 5.0_wp, options, fine_res, timings, stat)
        call t%check('reference scene, 8 x 8 and 16 x 16: solved', stat%ok())
        if (.not. stat%ok()) return
        ! the unit square with E = 1: the scaled units are the input's
        e_coarse = abs(lowest(coarse_res) - REF_MU)
        e_fine = abs(lowest(fine_res) - REF_MU)
        ratio = e_fine/e_coarse
        call t%check('the error falls by 2^-2.5 to 2^-0.5 on the halved mesh', &
                     ratio >= 2.0_wp**(-2.5_wp) .and. ratio <= 2.0_wp**(-0.5_wp))
    end subroutine mu_moves_toward_the_continuum

    real(wp) function lowest(res)
        type(eigen_result_t), intent(in) :: res
        lowest = real(res%spec%mu(res%spec%lowest_positive()), wp)
    end function lowest

    real(wp) function area(m)
        type(mesh_t), intent(in) :: m
        real(wp) :: d1(2), d2(2)
        integer :: c
        area = 0.0_wp
        do c = 1, m%n_cells()
            d1 = m%coords(:, m%cells(2, c)) - m%coords(:, m%cells(1, c))
            d2 = m%coords(:, m%cells(3, c)) - m%coords(:, m%cells(1, c))
            area = area + 0.5_wp*abs(d1(1)*d2(2) - d1(2)*d2(1))
        end do
    end function area
end program test_halved_mesh
