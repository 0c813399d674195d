! SPDX-License-Identifier: MIT
!> Gamma_C for an hp space: the contact_t that the eigensolvers take (contact_reduction,
!> dense_eigen, arpack_eigen), with its "nodes" the hp basis functions whose trace on
!> Gamma_C is not zero (the free vertex functions on it and the functions of its edges), in
!> order along t, their dofs (x, y), and the trace mass matrix M_ab = int_C phi_a phi_b.
!> The segment's checks (one straight piece, outward normal) are build_contact's, run on
!> the vertex mesh.
module hp_contact
    use kinds, only: wp
    use status, only: status_t
    use mesh, only: mesh_t
    use dof_map, only: dof_map_t
    use csr_matrix, only: csr_from_element_dofs
    use contact_boundary, only: contact_t, build_contact
    use gauss_rules, only: gauss_rule_t, line_rule_exact
    use hp_basis, only: hp_edge_trace
    use hp_space, only: hp_space_t
    use sorting, only: sort_index
    implicit none
    private
    public :: build_hp_contact, hp_edge_mass, half_degree_forces

contains

    !> Trace mass matrix of an edge of length h and degree p_e, in the order of
    !> hp_edge_trace (its two vertices from the lower-numbered one, then Lhat_2..Lhat_pe):
    !> (h/2) int_{-1}^{1} phi_a phi_b ds by Gauss exact to degree 2 p_e.
    pure function hp_edge_mass(p_e, h) result(me)
        integer, intent(in) :: p_e
        real(wp), intent(in) :: h
        real(wp) :: me(1 + max(p_e, 1), 1 + max(p_e, 1))
        type(gauss_rule_t) :: rule
        real(wp) :: v(1 + max(p_e, 1))
        integer :: q, a
        rule = line_rule_exact(2*p_e)
        me = 0.0_wp
        do q = 1, rule%n_points()
            v = hp_edge_trace(p_e, rule%points(1, q))
            do a = 1, size(v)
                me(:, a) = me(:, a) + 0.5_wp*h*rule%weights(q)*v(a)*v
            end do
        end do
    end function hp_edge_mass

    !> The contact data of boundary part `part` of the P1 mesh `m` for the hp space `space`.
    subroutine build_hp_contact(m, space, part, contact, stat)
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        integer, intent(in) :: part
        type(contact_t), intent(out) :: contact
        type(status_t), intent(out) :: stat
        type(dof_map_t) :: vertex_dofs
        integer, allocatable :: edges(:), functions(:), order(:), local(:), edge_local(:, :)
        real(wp), allocatable :: position(:)
        integer :: v, k, i, e, f, n, p_max, a

        ! the vertex functions' dofs as a dof map, for build_contact's checks and normal
        allocate (vertex_dofs%free_dof(2, space%n_vertices), source=0)
        do v = 1, space%n_vertices
            k = space%free_function(v)
            if (k > 0) vertex_dofs%free_dof(:, v) = [2*k - 1, 2*k]
        end do
        vertex_dofs%n_free = space%n_free()
        call build_contact(m, part, vertex_dofs, contact, stat)
        if (.not. stat%ok()) return

        ! contact functions: the free vertices build_contact found, and the edge functions
        edges = pack([(e, e=1, space%n_edges())], space%edge_part == part)
        n = size(contact%nodes) + sum(max(0, space%edge_degree(edges) - 1))
        allocate (functions(n), position(n))
        n = size(contact%nodes)
        functions(1:n) = contact%nodes
        do a = 1, n
            position(a) = dot_product(m%coords(:, contact%nodes(a)), contact%tangent)
        end do
        do i = 1, size(edges)
            e = edges(i)
            do k = 2, space%edge_degree(e)
                n = n + 1
                functions(n) = space%edge_first(e) + k - 2
                position(n) = 0.5_wp*dot_product(sum(m%coords(:, space%edge_ends(:, e)), &
                                                     dim=2), contact%tangent)
            end do
        end do
        order = sort_index(position)   ! stable: an edge's functions stay in degree order
        contact%nodes = functions(order)
        deallocate (contact%dofs)
        allocate (contact%dofs(2, n))
        do a = 1, n
            k = space%free_function(contact%nodes(a))
            contact%dofs(:, a) = [2*k - 1, 2*k]
        end do

        ! trace mass matrix, edge by edge
        allocate (local(space%n_functions), source=0)
        local(contact%nodes) = [(a, a=1, n)]
        p_max = maxval([1, space%edge_degree(edges)])
        allocate (edge_local(1 + p_max, size(edges)), source=0)
        do i = 1, size(edges)
            e = edges(i)
            edge_local(1:2, i) = local(space%edge_ends(:, e))
            do k = 2, space%edge_degree(e)
                f = space%edge_first(e) + k - 2
                edge_local(1 + k, i) = local(f)
            end do
        end do
        call csr_from_element_dofs(n, edge_local, contact%mass)
        do i = 1, size(edges)
            e = edges(i)
            associate (p_e => max(1, space%edge_degree(e)))
                call contact%mass%add_block(edge_local(1:1 + p_e, i), hp_edge_mass(p_e, &
                    norm2(m%coords(:, space%edge_ends(2, e)) - m%coords(:, space%edge_ends(1, e)))), &
                    stat)
            end associate
            if (.not. stat%ok()) return
        end do
    end subroutine build_hp_contact

    !> Which contact functions of `contact` (built by build_hp_contact on `space`) carry the
    !> forces of a threshold pencil coarser than the trace space: every vertex function, and
    !> on each contact edge of degree p_e its edge functions of degree at most ceil(p_e / 2).
    !> With the forces in the trace space itself (equal order) the pencil holds force
    !> patterns that alternate from function to function, whose real pencil values move with
    !> the mesh on graded levels; this coarser space removes most of them and keeps every
    !> converging threshold measured (docs/thresholds.md, "Spurious values from the
    !> discretisation of the contact forces").
    pure function half_degree_forces(space, contact) result(keep)
        type(hp_space_t), intent(in) :: space
        type(contact_t), intent(in) :: contact
        logical :: keep(size(contact%nodes))
        integer :: edge_of(space%n_functions), degree_of(space%n_functions)
        integer :: e, k, a, f
        edge_of = 0
        degree_of = 1
        do e = 1, space%n_edges()
            do k = 2, space%edge_degree(e)
                f = space%edge_first(e) + k - 2
                edge_of(f) = e
                degree_of(f) = k
            end do
        end do
        do a = 1, size(contact%nodes)
            f = contact%nodes(a)
            keep(a) = .true.
            if (edge_of(f) > 0) keep(a) = degree_of(f) <= (space%edge_degree(edge_of(f)) + 1)/2
        end do
    end function half_degree_forces
end module hp_contact
