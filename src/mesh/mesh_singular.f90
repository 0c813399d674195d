! SPDX-License-Identifier: MIT
!> The points of a triangle mesh where solutions are singular, found from its geometry and
!> boundary parts alone: the boundary vertices where the boundary turns (corners) or where
!> the boundary condition changes (two boundary edges of different parts meet, the ends of
!> the contact segment among them; sides in no part count as one part of their own). These
!> are the points an hp mesh grades toward.
module mesh_singular
    use kinds, only: wp
    use mesh, only: mesh_t
    use element_types, only: element_corners
    use mesh_refine, only: edge_table_t, build_edge_table, edge_number
    implicit none
    private
    public :: singular_vertices

    !> A turn of the boundary by less than this sine is straight: Gmsh's and the rectangle's
    !> straight sides are collinear to round-off (about 1e-16 relative).
    real(wp), parameter :: STRAIGHT_SINE = 1.0e-10_wp

contains

    !> The mesh nodes (cell corners) at which the boundary turns or changes part, ascending.
    pure function singular_vertices(m) result(vertices)
        type(mesh_t), intent(in) :: m
        integer, allocatable :: vertices(:)
        type(edge_table_t) :: table
        integer, allocatable :: part_of(:), first_edge(:), n_edges_at(:)
        logical, allocatable :: singular(:)
        integer :: e, i, v, corners, n_nodes
        real(wp) :: d1(2), d2(2)

        corners = element_corners(m%element)
        n_nodes = m%n_nodes()
        call build_edge_table(m%cells(1:corners, :), n_nodes, table)
        ! part of each edge of the table: 0 inside or in no part, else the mesh's part index
        allocate (part_of(table%n_edges), source=0)
        do i = 1, size(m%edge_part)
            e = edge_number(table, m%edges(1, i), m%edges(2, i))
            if (e > 0) part_of(e) = m%edge_part(i)
        end do
        allocate (first_edge(n_nodes), source=0)
        allocate (n_edges_at(n_nodes), source=0)
        allocate (singular(n_nodes), source=.false.)
        do e = 1, table%n_edges
            if (table%cells_of(2, e) /= 0) cycle   ! an interior edge
            do i = 1, 2
                v = table%ends(i, e)
                n_edges_at(v) = n_edges_at(v) + 1
                if (first_edge(v) == 0) then
                    first_edge(v) = e
                else
                    ! the second boundary edge at v: a change of part or a turn
                    d1 = direction(first_edge(v))
                    d2 = direction(e)
                    if (part_of(e) /= part_of(first_edge(v)) .or. &
                        abs(d1(1)*d2(2) - d1(2)*d2(1)) > STRAIGHT_SINE) singular(v) = .true.
                end if
            end do
        end do
        ! a vertex where the boundary touches itself (more than two boundary edges)
        singular = singular .or. n_edges_at > 2
        vertices = pack([(v, v=1, n_nodes)], singular)

    contains

        pure function direction(edge) result(d)
            integer, intent(in) :: edge
            real(wp) :: d(2)
            d = m%coords(:, table%ends(2, edge)) - m%coords(:, table%ends(1, edge))
            d = d/norm2(d)
        end function direction
    end function singular_vertices
end module mesh_singular
