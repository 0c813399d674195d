! SPDX-License-Identifier: MIT
!> Singular points and geometric meshes: the points found where the boundary turns or changes
!> part (also in the middle of a straight side), the grading laws the refinement promises
!> (cells at a singular point no larger than h_min, every other cell no larger than
!> (1 - sigma)/sigma times its distance), area conserved, layers and degrees as defined, and
!> the hp space's counts (minimum rule, clamped edges).
program test_hp_mesh
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P2
    use mesh_structured, only: structured_rectangle
    use mesh_singular, only: singular_vertices
    use mesh_geometric, only: geometric_mesh, cell_layers, layer_degrees, cell_diameter, &
                              point_distance, MESH_GRADED, MESH_BELOW_RESOLUTION, &
                              MESH_OVER_CELLS
    use hp_space, only: hp_space_t, build_hp_space
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_hp_mesh'
    call part_change_on_a_straight_side(t)
    call grading_laws_hold(t)
    call vertex_near_a_singular_point(t)
    call levels_the_builder_cannot_make(t)
    call degrees_rise_with_the_layer(t)
    call space_counts(t)
    call t%report()

contains

    !> The bottom side of a 4 x 4 square split into two parts at x = 1/2: five singular
    !> points (four corners and (1/2, 0)); a P2 mesh gives the same (corners only count).
    subroutine part_change_on_a_straight_side(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(status_t) :: stat
        integer, allocatable :: singular(:)
        integer :: e, element
        logical :: found
        do element = ELEMENT_P1, ELEMENT_P2, ELEMENT_P2 - ELEMENT_P1
            call structured_rectangle(1.0_wp, 1.0_wp, 4, 4, element, 'right', m, stat)
            m%part_names = [character(len=len(m%part_names)) :: m%part_names, 'half']
            do e = 1, size(m%edge_part)
                if (m%edge_part(e) == m%part_index('bottom') .and. &
                    maxval(m%coords(1, m%edges(1:2, e))) <= 0.5_wp) &
                    m%edge_part(e) = size(m%part_names)
            end do
            allocate (singular(0))   ! (gfortran 12 warns of an unallocated one at -O3)
            singular = singular_vertices(m)
            found = any(abs(m%coords(1, singular) - 0.5_wp) < 1.0e-15_wp .and. &
                        abs(m%coords(2, singular)) < 1.0e-15_wp)
            call t%check('five singular points with a part change mid-side', &
                         size(singular) == 5 .and. found)
            deallocate (singular)
        end do
    end subroutine part_change_on_a_straight_side

    !> sigma = 0.2, 6 layers on a 3 x 3 square toward its corners: every cell touching a
    !> corner has diameter <= h_min <= 0.2^6 h_0 (bisection may overshoot by a factor 2
    !> below it, never above), every other cell h <= 4 d; the cells still tile the square
    !> (area 1 to round-off, all anticlockwise).
    subroutine grading_laws_hold(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: SIGMA = 0.2_wp
        type(mesh_t) :: m, graded
        type(status_t) :: stat
        real(wp), allocatable :: points(:, :)
        real(wp) :: h_min, h_0, area, twice, d, h
        logical :: touching_ok, graded_ok, oriented
        integer :: c, k
        call structured_rectangle(1.0_wp, 1.0_wp, 3, 3, ELEMENT_P1, 'left', m, stat)
        h_0 = sqrt(2.0_wp)/3.0_wp
        allocate (points(2, 0))   ! (gfortran 12 warns of an unallocated one at -O3)
        points = m%coords(:, singular_vertices(m))
        call geometric_mesh(m, points, SIGMA, 6, graded, h_min, stat)
        call t%check('geometric mesh builds', stat%ok())
        if (.not. stat%ok()) return
        call t%check('h_min within [sigma^6 h_0 / 2, sigma^6 h_0]', &
                     h_min <= SIGMA**6*h_0*(1.0_wp + 1.0e-12_wp) .and. &
                     h_min >= 0.5_wp*SIGMA**6*h_0)
        area = 0.0_wp
        touching_ok = .true.
        graded_ok = .true.
        oriented = .true.
        do c = 1, graded%n_cells()
            associate (xy => graded%coords(:, graded%cells(:, c)))
                twice = (xy(1, 2) - xy(1, 1))*(xy(2, 3) - xy(2, 1)) - &
                        (xy(2, 2) - xy(2, 1))*(xy(1, 3) - xy(1, 1))
                oriented = oriented .and. twice > 0.0_wp
                area = area + 0.5_wp*twice
                h = cell_diameter(xy)
                d = minval([(point_distance(points(:, k), xy), k=1, size(points, 2))])
                if (d <= 0.0_wp) then
                    touching_ok = touching_ok .and. h <= h_min*(1.0_wp + 1.0e-12_wp)
                else
                    graded_ok = graded_ok .and. h <= (1.0_wp - SIGMA)/SIGMA*d
                end if
            end associate
        end do
        call t%check('cells at the corners no larger than h_min', touching_ok)
        call t%check('other cells h <= (1 - sigma)/sigma d', graded_ok)
        call t%check('all cells anticlockwise', oriented)
        call t%check_close('cells tile the unit square', area, 1.0_wp, 1.0e-13_wp)
        call t%check('parts carry over', size(graded%part_names) == size(m%part_names) .and. &
                     size(singular_vertices(graded)) == 4)
    end subroutine grading_laws_hold

    !> A vertex 1e-6 from a corner (a short input edge, as a Gmsh mesh may have): level 1 is
    !> graded to h_min = 0.15 h_0 and no cell is asked to be smaller than 0.15 h_min
    !> (bisection may overshoot by 2): it ends, with few cells. Before, the cells beside that vertex were asked to be
    !> below its distance, each bisection put a vertex nearer the corner, and the sweeps
    !> never ended (a hang in the first hp level).
    subroutine vertex_near_a_singular_point(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m, graded
        type(status_t) :: stat
        real(wp), allocatable :: points(:, :)
        real(wp) :: h_min, smallest
        integer :: near, outcome, c
        call structured_rectangle(1.0_wp, 1.0_wp, 4, 4, ELEMENT_P1, 'right', m, stat)
        near = minloc(norm2(m%coords - spread([0.25_wp, 0.0_wp], 2, m%n_nodes()), dim=1), &
                      dim=1)
        m%coords(:, near) = [1.0e-6_wp, 0.0_wp]
        allocate (points(2, 0))   ! (gfortran 12 warns of an unallocated one at -O3)
        points = m%coords(:, singular_vertices(m))
        call geometric_mesh(m, points, 0.15_wp, 1, graded, h_min, stat, 100000, outcome)
        call t%check('a vertex 1e-6 from a corner: level 1 is made', &
                     stat%ok() .and. outcome == MESH_GRADED)
        if (.not. (stat%ok() .and. outcome == MESH_GRADED)) return
        smallest = huge(1.0_wp)
        do c = 1, graded%n_cells()
            smallest = min(smallest, cell_diameter(graded%coords(:, graded%cells(:, c))))
        end do
        ! the short edge itself stays (1e-6); every cell the grading made is at least
        ! 0.15 h_min / 2
        call t%check('a vertex 1e-6 from a corner: at most 1000 cells, none made below '// &
                     '0.15 h_min / 2 but those of the short edge', graded%n_cells() <= 1000 &
                     .and. count([(cell_diameter(graded%coords(:, graded%cells(:, c))) < &
                                   0.075_wp*h_min, c=1, graded%n_cells())]) <= 2 .and. &
                     smallest >= 1.0e-6_wp)
    end subroutine vertex_near_a_singular_point

    !> Levels the builder cannot make: sigma = 0.01 at 8 layers asks cells of 1e-16 h_0 at
    !> the corners, below binary64's resolution (MESH_BELOW_RESOLUTION, nothing refined);
    !> 6 layers at sigma = 0.15 need more than 50 cells (MESH_OVER_CELLS with max_cells =
    !> 50: the sweeps stop there).
    subroutine levels_the_builder_cannot_make(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m, graded
        type(status_t) :: stat
        real(wp), allocatable :: points(:, :)
        real(wp) :: h_min
        integer :: outcome
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        allocate (points(2, 0))   ! (gfortran 12 warns of an unallocated one at -O3)
        points = m%coords(:, singular_vertices(m))
        call geometric_mesh(m, points, 0.01_wp, 8, graded, h_min, stat, outcome=outcome)
        call t%check('cells of 1e-16 at the corners: below the resolution', &
                     stat%ok() .and. outcome == MESH_BELOW_RESOLUTION)
        call geometric_mesh(m, points, 0.15_wp, 6, graded, h_min, stat, 50, outcome)
        call t%check('6 layers within 50 cells: over the cells allowed', &
                     stat%ok() .and. outcome == MESH_OVER_CELLS)
    end subroutine levels_the_builder_cannot_make

    !> Layer 0 exactly at the singular points; the degree min(p_max, p_min + nint(slope l)).
    subroutine degrees_rise_with_the_layer(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m, graded
        type(status_t) :: stat
        real(wp), allocatable :: points(:, :)
        integer, allocatable :: layer(:), degree(:)
        real(wp) :: h_min, d
        logical :: zero_ok
        integer :: c, k
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        allocate (points(2, 0))   ! (gfortran 12 warns of an unallocated one at -O3)
        points = m%coords(:, singular_vertices(m))
        call geometric_mesh(m, points, 0.15_wp, 5, graded, h_min, stat)
        layer = cell_layers(graded, points, 0.15_wp, h_min)
        zero_ok = .true.
        do c = 1, graded%n_cells()
            d = minval([(point_distance(points(:, k), graded%coords(:, graded%cells(:, c))), &
                         k=1, size(points, 2))])
            zero_ok = zero_ok .and. ((layer(c) == 0) .eqv. (d <= 0.0_wp))
        end do
        call t%check('layer 0 exactly at the singular points', zero_ok)
        call t%check('layers reach at least 5', maxval(layer) >= 5)
        degree = layer_degrees(layer, 2, 0.5_wp, 4)
        call t%check('degrees min(4, 2 + nint(l/2))', &
                     all(degree == min(4, 2 + nint(0.5_wp*layer))))
    end subroutine degrees_rise_with_the_layer

    !> A 2 x 2 square (9 vertices, 16 edges, 8 cells) with degrees 3 in the cells left of
    !> x = 1/2 and 5 right of it: the two edges on x = 1/2 take degree 3 (minimum rule),
    !> so the vertex and edge functions number 9 + sum(p_e - 1); clamping the top (3
    !> vertices, 2 edges of degree 3 and 5) leaves 2 (n_functions - 3 - 2 - 4) dofs.
    subroutine space_counts(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(status_t) :: stat
        type(hp_space_t) :: space
        integer, allocatable :: degree(:)
        integer :: c
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        allocate (degree(m%n_cells()))
        do c = 1, m%n_cells()
            degree(c) = merge(3, 5, sum(m%coords(1, m%cells(:, c)))/3.0_wp < 0.5_wp)
        end do
        call build_hp_space(m, degree, [m%part_index('top')], space, stat)
        call t%check('hp space builds', stat%ok())
        if (.not. stat%ok()) return
        call t%check('16 edges', space%n_edges() == 16)
        call t%check('edge degree is the smaller cell degree', all([(space%edge_degree( &
            space%cell_edge(:, c)) <= degree(c), c=1, m%n_cells())]))
        call t%check('functions: vertices plus p_e - 1 per edge', space%n_functions == &
                     9 + sum(space%edge_degree - 1))
        call t%check('top clamped: its vertex and edge functions removed', space%n_free() == &
                     2*(space%n_functions - 3 - 2 - 4))
        call t%check('bad degree refused', .not. bad_degree_accepted(m))
    end subroutine space_counts

    !> Whether a degree 0 (below the basis's range) gets through build_hp_space.
    logical function bad_degree_accepted(m)
        type(mesh_t), intent(in) :: m
        type(hp_space_t) :: space
        type(status_t) :: stat
        integer :: c
        call build_hp_space(m, [(0, c=1, m%n_cells())], [integer ::], space, stat)
        bad_degree_accepted = stat%ok()
    end function bad_degree_accepted
end program test_hp_mesh
