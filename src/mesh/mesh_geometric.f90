! SPDX-License-Identifier: MIT
!> Geometric meshes for the hp method: a triangle mesh refined by newest-vertex bisection
!> (mesh_refine) until the cells shrink geometrically toward given singular points, and a
!> polynomial degree per cell that rises linearly with the cell's layer away from them.
!>
!> Grading: with the factor sigma in (0, 1), the cells at distance d from the nearest
!> singular point get h <= (1 - sigma)/sigma d (a ring [sigma r, r] is about one cell wide),
!> and the cells touching a singular point h <= h_min = sigma^layers h_0, h_0 the largest
!> cell of the input mesh. sigma near 0.15-0.2 is known to be about optimal for corner
!> singularities (Babuska and Guo); bisection only halves cells, so the grading reached is
!> sigma's up to a factor 2.
module mesh_geometric
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: to_string, short_real_text
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use mesh_refine, only: refinable_mesh_t, build_refinable_mesh
    implicit none
    private
    public :: geometric_mesh, cell_layers, layer_degrees, cell_diameter, point_distance

    !> bound on the bisection sweeps (each at least halves the largest marked cell's area)
    integer, parameter :: MAX_SWEEPS = 400
    !> The smallest cell size a grading may ask for, relative to the largest coordinate: a
    !> thousand times binary64's resolution of a coordinate (2.2e-16 relative); below, the
    !> new vertices of a bisection are no longer distinct points.
    real(wp), parameter :: RESOLVED = 1.0e3_wp*epsilon(1.0_wp)

    !> geometric_mesh's `outcome`
    integer, parameter, public :: MESH_GRADED = 0       !! the mesh is made
    integer, parameter, public :: MESH_BELOW_RESOLUTION = 1   !! h_min below RESOLVED |x|
    integer, parameter, public :: MESH_OVER_CELLS = 2   !! more cells than max_cells

contains

    !> Longest side of the triangle with corners xy(:, 1:3).
    pure real(wp) function cell_diameter(xy)
        real(wp), intent(in) :: xy(:, :)
        cell_diameter = max(norm2(xy(:, 2) - xy(:, 1)), norm2(xy(:, 3) - xy(:, 2)), &
                            norm2(xy(:, 1) - xy(:, 3)))
    end function cell_diameter

    !> Distance from `point` to the triangle xy(:, 1:3) (anticlockwise); 0 on or inside it.
    pure real(wp) function point_distance(point, xy)
        real(wp), intent(in) :: point(2), xy(:, :)
        real(wp) :: a(2), b(2), edge(2), t
        integer :: k
        logical :: inside
        inside = .true.
        point_distance = huge(1.0_wp)
        do k = 1, 3
            a = xy(:, k)
            b = xy(:, mod(k, 3) + 1)
            edge = b - a
            if (edge(1)*(point(2) - a(2)) - edge(2)*(point(1) - a(1)) < 0.0_wp) inside = .false.
            t = max(0.0_wp, min(1.0_wp, dot_product(point - a, edge)/dot_product(edge, edge)))
            point_distance = min(point_distance, norm2(point - (a + t*edge)))
        end do
        if (inside) point_distance = 0.0_wp
    end function point_distance

    !> The P1 mesh of `m` refined geometrically toward `points` (2, n) with factor `sigma`
    !> and `layers` levels (see the module's comment); `h_min` returns the size reached at
    !> the points (the largest diameter of the cells touching one). Parts and boundary edges
    !> carry over; any triangle mesh (P1 to P4) is accepted, its higher-order nodes dropped.
    !> A cell away from the points is not asked to be smaller than sigma h_min (the size of
    !> the ring after the last): a vertex of the input mesh a short edge away from a singular
    !> point (1e-6 on a side 1 long) otherwise asked for cells below its distance, whose
    !> bisection put a new vertex nearer still, without end. Where no input vertex is that
    !> near a point no such cell arises, and the mesh is the one the rule alone makes. `outcome` (optional): MESH_BELOW_RESOLUTION when h_min is below what binary64
    !> resolves of the coordinates (RESOLVED; nothing is refined), MESH_OVER_CELLS when the
    !> mesh would exceed `max_cells` (the refinement stops; `graded` is not made), else
    !> MESH_GRADED. Without it, a level below the resolution fails (STATUS_BAD_INPUT).
    subroutine geometric_mesh(m, points, sigma, layers, graded, h_min, stat, max_cells, &
                              outcome)
        type(mesh_t), intent(in) :: m
        real(wp), intent(in) :: points(:, :)
        real(wp), intent(in) :: sigma
        integer, intent(in) :: layers
        type(mesh_t), intent(out) :: graded
        real(wp), intent(out) :: h_min
        type(status_t), intent(out) :: stat
        integer, intent(in), optional :: max_cells
        integer, intent(out), optional :: outcome
        type(refinable_mesh_t) :: r
        integer, allocatable :: marked(:)
        real(wp) :: ratio, h, d, floor_size
        integer :: sweep, c, i

        if (present(outcome)) outcome = MESH_GRADED
        if (.not. (sigma > 0.0_wp .and. sigma < 1.0_wp) .or. layers < 0) then
            call stat%fail(STATUS_BAD_INPUT, 'geometric mesh: expected 0 < sigma < 1 and '// &
                           'layers >= 0, got layers = '//to_string(layers))
            return
        end if
        call build_refinable_mesh(m, r, stat)
        if (.not. stat%ok()) return
        h_min = 0.0_wp
        do c = 1, r%n_cells()
            h_min = max(h_min, cell_diameter(r%coords(:, r%cells(:, c))))
        end do
        h_min = h_min*sigma**layers
        if (h_min < RESOLVED*maxval(abs(r%coords))) then
            if (present(outcome)) outcome = MESH_BELOW_RESOLUTION
            if (.not. present(outcome)) call stat%fail(STATUS_BAD_INPUT, 'geometric mesh: '// &
                'cells of '//short_real_text(h_min)//' at the singular points are below '// &
                'the resolution of binary64 coordinates')
            return
        end if
        ratio = (1.0_wp - sigma)/sigma
        ! ring k + 1 would start below h_min: only an input vertex that near a point puts a
        ! cell there, and refining it toward the point would not end (see above)
        floor_size = sigma*h_min
        do sweep = 1, MAX_SWEEPS
            allocate (marked(r%n_cells()))
            i = 0
            do c = 1, r%n_cells()
                associate (xy => r%coords(:, r%cells(:, c)))
                    h = cell_diameter(xy)
                    d = nearest_point(xy)
                    if ((d <= 0.0_wp .and. h > h_min*(1.0_wp + 1.0e-12_wp)) .or. &
                        (d > 0.0_wp .and. h > ratio*d .and. h > floor_size)) then
                        i = i + 1
                        marked(i) = c
                    end if
                end associate
            end do
            if (i == 0) exit
            if (present(max_cells)) then
                ! each marked cell becomes at least two (the closure adds more)
                if (r%n_cells() + i > max_cells) then
                    if (present(outcome)) outcome = MESH_OVER_CELLS
                    return
                end if
            end if
            call r%refine(marked(:i), stat)
            if (.not. stat%ok()) return
            deallocate (marked)
        end do
        call r%to_mesh(ELEMENT_P1, graded, stat)
        if (.not. stat%ok()) return
        h_min = 0.0_wp   ! the largest cell at a point: every one there is no larger
        do c = 1, graded%n_cells()
            if (nearest_point(graded%coords(:, graded%cells(:, c))) <= 0.0_wp) &
                h_min = max(h_min, cell_diameter(graded%coords(:, graded%cells(:, c))))
        end do

    contains

        pure real(wp) function nearest_point(xy)
            real(wp), intent(in) :: xy(:, :)
            integer :: k
            nearest_point = huge(1.0_wp)
            do k = 1, size(points, 2)
                nearest_point = min(nearest_point, point_distance(points(:, k), xy))
            end do
        end function nearest_point
    end subroutine geometric_mesh

    !> Layer of each cell of the P1 mesh `m` away from `points`: 0 for the cells touching a
    !> point, else 1 + floor(log(d / h_min) / log(1 / sigma)) (at least 1), d the distance to
    !> the nearest point: the index of the ring [sigma^-(k-1), sigma^-k] h_min holding it.
    pure function cell_layers(m, points, sigma, h_min) result(layer)
        type(mesh_t), intent(in) :: m
        real(wp), intent(in) :: points(:, :), sigma, h_min
        integer :: layer(m%n_cells())
        real(wp) :: d
        integer :: c, k
        do c = 1, m%n_cells()
            d = huge(1.0_wp)
            do k = 1, size(points, 2)
                d = min(d, point_distance(points(:, k), m%coords(:, m%cells(1:3, c))))
            end do
            if (d <= 0.0_wp) then
                layer(c) = 0
            else
                layer(c) = max(1, 1 + floor(log(d/h_min)/log(1.0_wp/sigma)))
            end if
        end do
    end function cell_layers

    !> Degrees rising linearly with the layer: min(p_max, p_min + nint(slope layer)).
    elemental integer function layer_degrees(layer, p_min, slope, p_max) result(degree)
        integer, intent(in) :: layer, p_min, p_max
        real(wp), intent(in) :: slope
        degree = min(p_max, p_min + nint(slope*real(layer, wp)))
    end function layer_degrees
end module mesh_geometric
