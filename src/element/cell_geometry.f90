! SPDX-License-Identifier: MIT
!> The geometry of one cell: the Jacobian of its map from the reference element, and the
!> one test of when a cell is too flat or inverted to use. The Gmsh reader (which can name
!> the file line) and element_stiffness (which must not integrate such a cell) both apply
!> it, so that a cell the reader accepts is one the assembly accepts.
module cell_geometry
    use kinds, only: wp
    use shape_functions, only: evaluate_shape, reference_nodes, MAX_NODES
    use element_types, only: element_corners
    implicit none
    private
    public :: jacobian_at, jacobian_of, det_range, det_range_of, negligible_det, &
              orientation_of, cell_orientation, cell_thinness, local_coordinates
    public :: DEGENERATE_FRACTION, CELL_ANTICLOCKWISE, CELL_CLOCKWISE, CELL_DEGENERATE, &
              CELL_FOLDED

    !> det J is negligible at or below this fraction of (cell diameter)^2: a sliver so thin
    !> that its stiffness is dominated by round-off is as unusable as an inverted cell.
    real(wp), parameter :: DEGENERATE_FRACTION = 64.0_wp*epsilon(1.0_wp)

    ! Outcomes of orientation_of: det J of one sign, clear of zero, at every point; det J
    ! negligible at every point (collinear or coinciding corners); or neither (det J changes
    ! sign or vanishes somewhere: a folded cell, or misplaced mid-edge nodes).
    integer, parameter :: CELL_ANTICLOCKWISE = 1
    integer, parameter :: CELL_CLOCKWISE = -1
    integer, parameter :: CELL_DEGENERATE = 0
    integer, parameter :: CELL_FOLDED = 2

contains

    !> Jacobian matrix J(i, j) = d x_i / d xi_j of the map from the reference element and
    !> its determinant, at reference point `xi`, for the cell with node coordinates `xy`.
    pure subroutine jacobian_at(element, xy, xi, jacobian, det)
        integer, intent(in) :: element
        real(wp), intent(in) :: xy(:, :)   !! (2, nodes per cell)
        real(wp), intent(in) :: xi(2)
        real(wp), intent(out) :: jacobian(2, 2), det
        real(wp) :: values(MAX_NODES), gradients(2, MAX_NODES)
        call evaluate_shape(element, xi, values, gradients)
        call jacobian_of(xy, gradients(:, 1:size(xy, 2)), jacobian, det)
    end subroutine jacobian_at

    !> The same from the reference gradients of the cell's shape functions at the point.
    pure subroutine jacobian_of(xy, gradients, jacobian, det)
        real(wp), intent(in) :: xy(:, :)          !! (2, nodes per cell)
        real(wp), intent(in) :: gradients(:, :)   !! (2, nodes per cell)
        real(wp), intent(out) :: jacobian(2, 2), det
        jacobian = matmul(xy, transpose(gradients))
        det = jacobian(1, 1)*jacobian(2, 2) - jacobian(1, 2)*jacobian(2, 1)
    end subroutine jacobian_of

    !> Smallest and largest det J of cell `xy` at the reference points `points` (2, :),
    !> taken in order (the order of min/max decides which NaN, if any, is seen).
    pure subroutine det_range(element, xy, points, det_min, det_max)
        integer, intent(in) :: element
        real(wp), intent(in) :: xy(:, :)       !! (2, nodes per cell)
        real(wp), intent(in) :: points(:, :)   !! (2, n_points), reference coordinates
        real(wp), intent(out) :: det_min, det_max
        real(wp) :: values(MAX_NODES), gradients(2, MAX_NODES), at_points(2, size(xy, 2), &
                                                                           size(points, 2))
        integer :: q
        do q = 1, size(points, 2)
            call evaluate_shape(element, points(:, q), values, gradients)
            at_points(:, :, q) = gradients(:, 1:size(xy, 2))
        end do
        call det_range_of(xy, at_points, det_min, det_max)
    end subroutine det_range

    !> The same from the reference gradients (2, nodes per cell, n_points) at the points.
    pure subroutine det_range_of(xy, gradients, det_min, det_max)
        real(wp), intent(in) :: xy(:, :)             !! (2, nodes per cell)
        real(wp), intent(in) :: gradients(:, :, :)
        real(wp), intent(out) :: det_min, det_max
        real(wp) :: jacobian(2, 2), det
        integer :: q
        det_min = huge(1.0_wp)
        det_max = -huge(1.0_wp)
        do q = 1, size(gradients, 3)
            call jacobian_of(xy, gradients(:, :, q), jacobian, det)
            det_min = min(det_min, det)
            det_max = max(det_max, det)
        end do
    end subroutine det_range_of

    !> The |det J| at or below which cell `xy` counts as degenerate: DEGENERATE_FRACTION
    !> times its squared diameter (largest node distance), so the test is scale-free.
    pure real(wp) function negligible_det(xy)
        real(wp), intent(in) :: xy(:, :)   !! (2, nodes per cell)
        real(wp) :: diameter2
        integer :: a, b
        diameter2 = 0.0_wp
        do a = 1, size(xy, 2)
            do b = a + 1, size(xy, 2)
                diameter2 = max(diameter2, sum((xy(:, a) - xy(:, b))**2))
            end do
        end do
        negligible_det = DEGENERATE_FRACTION*diameter2
    end function negligible_det

    !> CELL_* of a cell whose det J ranges over [det_min, det_max] at the points checked,
    !> against negligible_det(xy). Only CELL_ANTICLOCKWISE is a usable cell as it stands.
    pure integer function orientation_of(det_min, det_max, xy)
        real(wp), intent(in) :: det_min, det_max
        real(wp), intent(in) :: xy(:, :)   !! (2, nodes per cell)
        real(wp) :: tol
        tol = negligible_det(xy)
        if (det_min > tol) then
            orientation_of = CELL_ANTICLOCKWISE
        else if (det_max < -tol) then
            orientation_of = CELL_CLOCKWISE
        else if (max(abs(det_min), abs(det_max)) <= tol) then
            orientation_of = CELL_DEGENERATE
        else
            orientation_of = CELL_FOLDED
        end if
    end function orientation_of

    !> The smallest |det J| of cell `xy` at its reference nodes over its squared diameter:
    !> about 1 for a well-shaped cell, tiny for a sliver, whose stiffness (~ 1 / this) swamps
    !> the others' and makes K numerically singular although it passed as non-degenerate.
    pure real(wp) function cell_thinness(element, xy)
        integer, intent(in) :: element
        real(wp), intent(in) :: xy(:, :)   !! (2, nodes per cell)
        real(wp) :: det_min, det_max
        call node_det_range(element, xy, det_min, det_max)
        cell_thinness = min(abs(det_min), abs(det_max))/ &
                        (negligible_det(xy)/DEGENERATE_FRACTION)
    end function cell_thinness

    !> The cell's node coordinates for integration: relative to its first node, and, where
    !> its higher-order nodes sit where its corners' map puts them (straight sides: every
    !> mesh nceig makes, and Gmsh meshes of polygons), at exactly those places.
    !> Why: a map from all nodes in global coordinates carries each node's rounding, eps
    !> |x|, relative to the cell size h, so a cell of 1e-9 at |x| ~ 1 integrated with
    !> relative errors ~1e-7 (diagonal entries of K that must be equal differed by 6e-10 on
    !> an adapted mesh); relative to one corner and straightened, the cell is an exact
    !> straight cell of corners perturbed by eps |x|, a backward error of order eps.
    !> Tolerance: a node counts as on the corners' map within 1e-8 of the cell's diameter
    !> plus the rounding of its coordinates (64 eps |x|); curved cells deviate far more.
    pure function local_coordinates(element, xy) result(local)
        integer, intent(in) :: element
        real(wp), intent(in) :: xy(:, :)   !! (2, nodes per cell)
        real(wp) :: local(size(xy, 1), size(xy, 2))
        real(wp) :: ref(2, MAX_NODES), mapped(2, size(xy, 2)), xi, eta, tolerance, diameter
        integer :: a, n, corners

        n = size(xy, 2)
        do a = 1, n
            local(:, a) = xy(:, a) - xy(:, 1)
        end do
        corners = element_corners(element)
        if (corners == 0 .or. n <= corners) return
        call reference_nodes(element, ref)
        diameter = maxval(abs(local(:, 1:corners)))
        tolerance = 1.0e-8_wp*diameter + 64.0_wp*epsilon(1.0_wp)*maxval(abs(xy))
        do a = corners + 1, n   ! where the corners' map puts each higher-order node
            xi = ref(1, a)
            eta = ref(2, a)
            if (corners == 3) then   ! reference triangle (0,0), (1,0), (0,1)
                mapped(:, a) = local(:, 2)*xi + local(:, 3)*eta
            else                     ! reference square [-1, 1]^2, corners anticlockwise
                mapped(:, a) = 0.25_wp*((1.0_wp + xi)*(1.0_wp - eta)*local(:, 2) + &
                                        (1.0_wp + xi)*(1.0_wp + eta)*local(:, 3) + &
                                        (1.0_wp - xi)*(1.0_wp + eta)*local(:, 4))
            end if
        end do
        ! curved: the isoparametric map of all nodes, translated only
        if (maxval(abs(local(:, corners + 1:n) - mapped(:, corners + 1:n))) > tolerance) return
        local(:, corners + 1:n) = mapped(:, corners + 1:n)
    end function local_coordinates

    !> CELL_* of cell `xy` from det J at its nodes: where a mesh file's cells are checked.
    pure integer function cell_orientation(element, xy)
        integer, intent(in) :: element
        real(wp), intent(in) :: xy(:, :)   !! (2, nodes per cell)
        real(wp) :: det_min, det_max
        call node_det_range(element, xy, det_min, det_max)
        cell_orientation = orientation_of(det_min, det_max, xy)
    end function cell_orientation

    !> det_range at the cell's own reference nodes: the points that cell_thinness and
    !> cell_orientation check.
    pure subroutine node_det_range(element, xy, det_min, det_max)
        integer, intent(in) :: element
        real(wp), intent(in) :: xy(:, :)   !! (2, nodes per cell)
        real(wp), intent(out) :: det_min, det_max
        real(wp) :: ref_nodes(2, MAX_NODES)
        call reference_nodes(element, ref_nodes)
        call det_range(element, xy, ref_nodes(:, 1:size(xy, 2)), det_min, det_max)
    end subroutine node_det_range
end module cell_geometry
