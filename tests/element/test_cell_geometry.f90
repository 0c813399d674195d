! SPDX-License-Identifier: MIT
!> The one cell-geometry test: Jacobians of reference maps, the degenerate threshold, and
!> the promise it carries: a cell the Gmsh reader accepts is one element_stiffness accepts,
!> and a nearly flat cell the reader refuses is one the assembly refuses too.
program test_cell_geometry
    use kinds, only: wp
    use status, only: status_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, element_nodes_per_cell
    use shape_functions, only: reference_nodes, MAX_NODES
    use cell_geometry, only: jacobian_at, det_range, negligible_det, orientation_of, &
                             cell_orientation, cell_thinness, DEGENERATE_FRACTION, &
                             CELL_ANTICLOCKWISE, &
                             CELL_CLOCKWISE, CELL_DEGENERATE, CELL_FOLDED
    use elasticity, only: element_stiffness, ELEMENT_OK, ELEMENT_INVERTED
    use mesh, only: mesh_t
    use mesh_gmsh, only: read_gmsh
    use testing, only: test_suite_t
    implicit none

    ! Multiples of the threshold around it: below it a cell is refused although its area is
    ! positive, so a threshold of 0 in either place would fail these checks.
    real(wp), parameter :: FACTORS(*) = [0.25_wp, 0.5_wp, 0.99_wp, 1.01_wp, 2.0_wp, 1.0e6_wp]
    type(test_suite_t) :: t
    real(wp) :: unit_triangle(2, 3), jacobian(2, 2), det, det_min, det_max
    real(wp) :: ref_nodes(2, MAX_NODES)
    integer :: i

    t%name = 'test_cell_geometry'
    unit_triangle = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 0.0_wp, 3.0_wp], [2, 3])

    call jacobian_at(ELEMENT_P1, unit_triangle, [0.25_wp, 0.25_wp], jacobian, det)
    call t%check('jacobian_at: P1 map is x = 2 xi, y = 3 eta', &
                 all(abs(jacobian - reshape([2.0_wp, 0.0_wp, 0.0_wp, 3.0_wp], [2, 2])) &
                     <= 1.0e-15_wp) .and. abs(det - 6.0_wp) <= 1.0e-14_wp)

    call reference_nodes(ELEMENT_Q1, ref_nodes)
    call det_range(ELEMENT_Q1, trapezoid(), ref_nodes(:, 1:4), det_min, det_max)
    call t%check('det_range: a trapezoid''s det J varies between its corners', &
                 det_min > 0.0_wp .and. det_max > det_min)

    call t%check_close('negligible_det: the fraction of the squared diameter', &
                       negligible_det(unit_triangle), DEGENERATE_FRACTION*13.0_wp, 1.0e-15_wp)

    call t%check('orientation_of: signs and the band around zero', &
                 orientation_of(1.0_wp, 2.0_wp, unit_triangle) == CELL_ANTICLOCKWISE .and. &
                 orientation_of(-2.0_wp, -1.0_wp, unit_triangle) == CELL_CLOCKWISE .and. &
                 orientation_of(0.0_wp, 0.0_wp, unit_triangle) == CELL_DEGENERATE .and. &
                 orientation_of(-1.0_wp, 1.0_wp, unit_triangle) == CELL_FOLDED)

    call t%check('cell_orientation: anticlockwise, clockwise, folded', &
                 cell_orientation(ELEMENT_P1, unit_triangle) == CELL_ANTICLOCKWISE .and. &
                 cell_orientation(ELEMENT_P1, unit_triangle(:, [1, 3, 2])) == CELL_CLOCKWISE &
                 .and. cell_orientation(ELEMENT_Q1, dart()) == CELL_FOLDED)
    ! x = 2 xi, y = 3 eta: det J = 6, diameter^2 = 13; a corner 1e-13 off the opposite side
    call t%check('cell_thinness: det J / diameter^2, tiny for a sliver', &
                 abs(cell_thinness(ELEMENT_P1, unit_triangle) - 6.0_wp/13.0_wp) < 1.0e-15_wp &
                 .and. abs(cell_thinness(ELEMENT_P1, reshape([0.0_wp, 0.0_wp, 0.5_wp, &
                 0.5_wp - 1.0e-13_wp, 1.0_wp, 1.0_wp], [2, 3])) - 5.0e-14_wp) < 1.0e-16_wp)

    ! The reader and the assembly against each other, across the threshold.
    do i = 1, size(FACTORS)
        call compare('P1 sliver', ELEMENT_P1, sliver_triangle(FACTORS(i)), &
                     FACTORS(i) > 1.0_wp)
        call compare('Q1 sliver', ELEMENT_Q1, sliver_quad(FACTORS(i)), FACTORS(i) > 1.0_wp)
    end do
    call compare('Q1 with a re-entrant corner', ELEMENT_Q1, dart(), .false.)
    call t%report()

contains

    !> Triangle (0,0), (1,0), (1/2, h): det J = h, diameter 1; h = factor * threshold.
    function sliver_triangle(factor) result(xy)
        real(wp), intent(in) :: factor
        real(wp) :: xy(2, 3)
        xy = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.5_wp, factor*DEGENERATE_FRACTION], &
                     [2, 3])
    end function sliver_triangle

    !> Rectangle 1 x h on [-1, 1]^2: det J = h/4, diameter^2 = 1 + h^2 (h^2 is below the
    !> round-off of 1 here); h = 4 * factor * threshold.
    function sliver_quad(factor) result(xy)
        real(wp), intent(in) :: factor
        real(wp) :: xy(2, 4), h
        h = 4.0_wp*factor*DEGENERATE_FRACTION
        xy = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, h, 0.0_wp, h], [2, 4])
    end function sliver_quad

    function trapezoid() result(xy)
        real(wp) :: xy(2, 4)
        xy = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 1.5_wp, 1.0_wp, 0.5_wp, 1.0_wp], [2, 4])
    end function trapezoid

    !> Its third corner points inwards: det J < 0 there, > 0 at the other corners.
    function dart() result(xy)
        real(wp) :: xy(2, 4)
        xy = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.2_wp, 0.2_wp, 0.0_wp, 1.0_wp], [2, 4])
    end function dart

    !> Whether read_gmsh accepts the one-cell mesh `xy` equals whether element_stiffness
    !> does, and both equal `expected`.
    subroutine compare(what, element, xy, expected)
        character(len=*), intent(in) :: what
        integer, intent(in) :: element
        real(wp), intent(in) :: xy(:, :)
        logical, intent(in) :: expected
        type(mesh_t) :: m
        type(status_t) :: stat
        real(wp) :: ke(2*size(xy, 2), 2*size(xy, 2))
        integer :: info
        character(len=32) :: factor_text

        call write_one_cell('cell_geometry.msh', element, xy)
        call read_gmsh('cell_geometry.msh', m, stat)
        call element_stiffness(element, xy, 1.0_wp, 0.3_wp, ke, info)
        write (factor_text, '(es10.3)') maxval(xy(2, :))
        call t%check('reader and assembly agree: '//what//', height '//trim(factor_text), &
                     stat%ok() .eqv. (info == ELEMENT_OK))
        call t%check('expected verdict: '//what//', height '//trim(factor_text), &
                     (stat%ok() .eqv. expected) .and. (expected .or. info == ELEMENT_INVERTED))
    end subroutine compare

    !> MSH 2.2 with the single cell `xy` (3-node triangle or 4-node quadrangle), its
    !> coordinates written with enough digits to be read back exactly.
    subroutine write_one_cell(path, element, xy)
        character(len=*), intent(in) :: path
        integer, intent(in) :: element
        real(wp), intent(in) :: xy(:, :)
        integer :: unit, a, n, gmsh_type
        n = element_nodes_per_cell(element)
        gmsh_type = merge(2, 3, element == ELEMENT_P1)
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') '$MeshFormat', '2.2 0 8', '$EndMeshFormat', '$Nodes'
        write (unit, '(i0)') n
        do a = 1, n
            write (unit, '(i0, 2(1x, es25.17), a)') a, xy(:, a), ' 0'
        end do
        write (unit, '(a)') '$EndNodes', '$Elements', '1'
        write (unit, '(i0, 1x, i0, a, *(1x, i0))') 1, gmsh_type, ' 2 0 1', (a, a=1, n)
        write (unit, '(a)') '$EndElements'
        close (unit)
    end subroutine write_one_cell
end program test_cell_geometry
