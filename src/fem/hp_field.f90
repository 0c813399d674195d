! SPDX-License-Identifier: MIT
!> A vector field of an hp space (hp_space) sampled on a linear sub-triangulation, for
!> viewers that draw P1 cells only: each cell of degree p is cut into p x p similar
!> triangles and the field evaluated at their corners (the points are the cell's own, so
!> the sub-mesh repeats the points on shared sides; the field is continuous there). The
!> coefficients given are those of the condensed system (hp_stiffness: vertex and edge
!> functions); the interior ones are recovered cell by cell, u_b = -K_bb^-1 K_bc u_c, so
!> the sampled field is the full discrete solution, not its condensed part.
module hp_field
    use kinds, only: wp
    use status, only: status_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use hp_basis, only: hp_triangle_shape, hp_local_count
    use hp_space, only: hp_space_t
    use hp_stiffness, only: hp_tables_t, hp_cell_fields
    implicit none
    private
    public :: sample_hp_field

contains

    !> The P1 sub-triangulation `sub` of the cells of `m` (cell c cut into
    !> space%cell_degree(c)^2 triangles), the field `u` (free dofs of `space`, interleaved
    !> x, y) at its points as values(2, n_points), and each sub-cell's degree. Material data
    !> (`young`, `poisson`) give the element stiffness that recovers the interior functions.
    subroutine sample_hp_field(m, space, young, poisson, u, sub, values, degree, stat)
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        real(wp), intent(in) :: young, poisson, u(:)
        type(mesh_t), intent(out) :: sub
        real(wp), allocatable, intent(out) :: values(:, :)
        real(wp), allocatable, intent(out) :: degree(:)
        type(status_t), intent(out) :: stat
        type(hp_tables_t), allocatable :: tables(:)
        real(wp), allocatable :: coefficients(:, :), shape(:), gradient(:, :), &
                                 field(:, :)
        real(wp) :: xi(2), jacobian(2, 2)
        integer :: c, p, s, n_points, n_cells, n_local, i, j, a, &
                   n_tables, point, cell, t
        integer, allocatable :: index_of(:, :)

        n_points = 0
        n_cells = 0
        do c = 1, m%n_cells()
            s = space%cell_degree(c)
            n_points = n_points + (s + 1)*(s + 2)/2
            n_cells = n_cells + s*s
        end do
        sub%element = ELEMENT_P1
        allocate (sub%coords(2, n_points), sub%cells(3, n_cells), values(2, n_points), &
                  degree(n_cells))
        allocate (sub%edges(2, 0), sub%edge_part(0), sub%part_names(0))
        field = reshape(u, [size(u), 1])
        n_tables = 0
        point = 0
        cell = 0
        do c = 1, m%n_cells()
            p = space%cell_degree(c)
            call hp_cell_fields(m, space, c, young, poisson, field, tables, n_tables, &
                                coefficients, t, stat)
            if (.not. stat%ok()) then
                stat%message = 'hp field: '//stat%message
                return
            end if
            n_local = hp_local_count(space%edge_degrees_of(c), p)
            allocate (shape(n_local), gradient(2, n_local))
            jacobian(:, 1) = m%coords(:, m%cells(2, c)) - m%coords(:, m%cells(1, c))
            jacobian(:, 2) = m%coords(:, m%cells(3, c)) - m%coords(:, m%cells(1, c))
            allocate (index_of(0:p, 0:p), source=0)
            do j = 0, p
                do i = 0, p - j
                    point = point + 1
                    index_of(i, j) = point
                    xi = [real(i, wp), real(j, wp)]/real(p, wp)
                    sub%coords(:, point) = m%coords(:, m%cells(1, c)) + matmul(jacobian, xi)
                    call hp_triangle_shape(space%edge_degrees_of(c), p, space%cell_flip(:, c), &
                                           xi, shape, gradient)
                    do a = 1, 2
                        values(a, point) = dot_product(shape, coefficients(a:2*n_local:2, 1))
                    end do
                end do
            end do
            do j = 0, p - 1   ! p^2 triangles, anticlockwise as their cell
                do i = 0, p - 1 - j
                    cell = cell + 1
                    sub%cells(:, cell) = [index_of(i, j), index_of(i + 1, j), index_of(i, j + 1)]
                    if (i + j < p - 1) then
                        cell = cell + 1
                        sub%cells(:, cell) = [index_of(i + 1, j), index_of(i + 1, j + 1), &
                                              index_of(i, j + 1)]
                    end if
                end do
            end do
            degree(cell - p*p + 1:cell) = real(p, wp)
            deallocate (coefficients, shape, gradient, index_of)
        end do

    end subroutine sample_hp_field
end module hp_field
