! SPDX-License-Identifier: MIT
!> Geometric grading toward singular points: the distances and diameters it is built on in
!> closed form; the graded mesh meets its two bounds (cells at a point no larger than
!> h_min = sigma^layers h_0, cells at distance d no larger than (1 - sigma)/sigma d) and
!> covers the same domain with the same boundary; the layers are the rings of ratio
!> 1/sigma around the points; degrees rise linearly with the layer up to p_max.
program test_mesh_geometric
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P2
    use mesh_structured, only: structured_rectangle
    use mesh_geometric, only: geometric_mesh, cell_layers, layer_degrees, cell_diameter, &
                              point_distance
    use testing, only: test_suite_t
    implicit none

    real(wp), parameter :: TRIANGLE(2, 3) = reshape([0.0_wp, 0.0_wp, 3.0_wp, 0.0_wp, &
                                                     0.0_wp, 4.0_wp], [2, 3])
    real(wp), parameter :: SIGMA = 0.5_wp
    integer, parameter :: LAYERS = 4
    type(test_suite_t) :: t
    type(mesh_t) :: m, graded
    type(status_t) :: stat
    real(wp) :: points(2, 2), h_min, h0
    integer, allocatable :: layer(:)

    t%name = 'test_mesh_geometric'
    call t%check('cell_diameter: the 3-4-5 triangle is 5 across', &
                 abs(cell_diameter(TRIANGLE) - 5.0_wp) <= 4.0_wp*epsilon(1.0_wp))
    call t%check('point_distance: 0 inside and on the boundary', &
                 point_distance([1.0_wp, 1.0_wp], TRIANGLE) <= 0.0_wp .and. &
                 point_distance([1.5_wp, 0.0_wp], TRIANGLE) <= 0.0_wp)
    call t%check('point_distance: to the nearest side, to the nearest corner', &
                 abs(point_distance([1.0_wp, -2.0_wp], TRIANGLE) - 2.0_wp) <= 1.0e-15_wp .and. &
                 abs(point_distance([-3.0_wp, -4.0_wp], TRIANGLE) - 5.0_wp) <= 1.0e-15_wp .and. &
                 ! beyond the hypotenuse 4x + 3y = 12: (3, 4) is 12/5 away
                 abs(point_distance([3.0_wp, 4.0_wp], TRIANGLE) - 2.4_wp) <= 1.0e-15_wp)

    ! the unit square of 2 x 2 P2 squares (higher-order nodes dropped), graded toward the
    ! two bottom corners
    call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P2, 'right', m, stat)
    points = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp], [2, 2])
    h0 = sqrt(0.5_wp)   ! the diagonal of a square of side 1/2
    call geometric_mesh(m, points, SIGMA, LAYERS, graded, h_min, stat)
    call t%check('geometric_mesh: a P1 mesh', stat%ok() .and. graded%element == ELEMENT_P1)
    call t%check('cells at a point: h <= h_min <= sigma^layers h_0', &
                 h_min <= SIGMA**LAYERS*h0*(1.0_wp + 1.0e-12_wp) .and. h_min > 0.0_wp &
                 .and. at_points_within(h_min))
    call t%check('cells at distance d: h <= (1 - sigma)/sigma d', graded_away())
    call t%check('the same domain: areas sum to 1, boundary lengths to 4, parts kept', &
                 abs(total_area(graded) - 1.0_wp) <= 1.0e-14_wp .and. &
                 abs(boundary_length(graded) - 4.0_wp) <= 1.0e-14_wp .and. &
                 all(graded%part_names == m%part_names))
    call t%check('finer than the input', graded%n_cells() > 8)

    layer = cell_layers(graded, points, SIGMA, h_min)
    call t%check('cell_layers: 0 exactly at the points, else the ring of ratio 1/sigma '// &
                 'holding the distance', layers_are_rings())
    call t%check('layer_degrees: min(p_max, p_min + nint(slope layer))', &
                 all(layer_degrees([0, 1, 2, 3, 10], 1, 0.75_wp, 4) == [1, 2, 3, 3, 4]))

    call geometric_mesh(m, points, 1.0_wp, LAYERS, graded, h_min, stat)
    call t%check('sigma = 1 is bad input', stat%code == STATUS_BAD_INPUT)
    call geometric_mesh(m, points, SIGMA, -1, graded, h_min, stat)
    call t%check('layers < 0 is bad input', stat%code == STATUS_BAD_INPUT)
    deallocate (layer)   ! (AddressSanitizer reports a main program's allocatables)
    call t%report()

contains

    real(wp) function nearest_distance(c)
        integer, intent(in) :: c
        nearest_distance = min(point_distance(points(:, 1), &
                                              graded%coords(:, graded%cells(:, c))), &
                               point_distance(points(:, 2), &
                                              graded%coords(:, graded%cells(:, c))))
    end function nearest_distance

    logical function at_points_within(h)
        real(wp), intent(in) :: h
        integer :: c
        at_points_within = .true.
        do c = 1, graded%n_cells()
            if (nearest_distance(c) <= 0.0_wp) at_points_within = at_points_within .and. &
                cell_diameter(graded%coords(:, graded%cells(:, c))) <= h
        end do
    end function at_points_within

    logical function graded_away()
        integer :: c
        real(wp) :: d
        graded_away = .true.
        do c = 1, graded%n_cells()
            d = nearest_distance(c)
            if (d > 0.0_wp) graded_away = graded_away .and. &
                cell_diameter(graded%coords(:, graded%cells(:, c))) <= &
                (1.0_wp - SIGMA)/SIGMA*d*(1.0_wp + 1.0e-12_wp)
        end do
    end function graded_away

    logical function layers_are_rings()
        integer :: c
        real(wp) :: d
        layers_are_rings = .true.
        do c = 1, graded%n_cells()
            d = nearest_distance(c)
            if (d <= 0.0_wp) then
                layers_are_rings = layers_are_rings .and. layer(c) == 0
            else
                layers_are_rings = layers_are_rings .and. layer(c) >= 1 .and. &
                    d < h_min/SIGMA**layer(c)*(1.0_wp + 1.0e-12_wp) .and. &
                    (layer(c) == 1 .or. d >= h_min/SIGMA**(layer(c) - 1)*(1.0_wp - 1.0e-12_wp))
            end if
        end do
    end function layers_are_rings

    real(wp) function total_area(mesh_in)
        type(mesh_t), intent(in) :: mesh_in
        integer :: c
        real(wp) :: a(2), b(2)
        total_area = 0.0_wp
        do c = 1, mesh_in%n_cells()
            a = mesh_in%coords(:, mesh_in%cells(2, c)) - mesh_in%coords(:, mesh_in%cells(1, c))
            b = mesh_in%coords(:, mesh_in%cells(3, c)) - mesh_in%coords(:, mesh_in%cells(1, c))
            total_area = total_area + 0.5_wp*(a(1)*b(2) - a(2)*b(1))
        end do
    end function total_area

    real(wp) function boundary_length(mesh_in)
        type(mesh_t), intent(in) :: mesh_in
        integer :: e
        boundary_length = 0.0_wp
        do e = 1, size(mesh_in%edge_part)
            boundary_length = boundary_length + norm2(mesh_in%coords(:, mesh_in%edges(2, e)) &
                                                      - mesh_in%coords(:, mesh_in%edges(1, e)))
        end do
    end function boundary_length
end program test_mesh_geometric
