! SPDX-License-Identifier: MIT
!> Fill-reducing Cholesky ordering of the dofs of an hp space with chosen functions (the
!> contact ones) pivoted last, so that the factor's trailing block is K's Schur complement
!> onto their dofs (contact_reduction). It reuses node_ordering's nested dissection on an
!> auxiliary P2 mesh whose nodes are the hp space's vertices and edges: METIS orders the
!> vertices, each edge's functions are eliminated next to the first-ordered of its two
!> vertices, exactly as node_ordering does with the mid-edge nodes of P2.
module hp_ordering
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: to_string
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P2
    use dof_map, only: dof_map_t
    use node_ordering, only: nested_dissection_last
    use hp_space, only: hp_space_t
    implicit none
    private
    public :: hp_cholesky_permutation

contains

    !> Dof permutation (permutation(k) = the dof pivoted k-th) of the free dofs of `space`
    !> on the P1 mesh `m`, with the dofs (x, y) of `last_functions` (free ones, in their
    !> order) last.
    subroutine hp_cholesky_permutation(m, space, last_functions, permutation, stat)
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        integer, intent(in) :: last_functions(:)
        integer, allocatable, intent(out) :: permutation(:)
        type(status_t), intent(out) :: stat
        type(mesh_t) :: entities
        type(dof_map_t) :: entity_dofs
        integer, allocatable :: entity_permutation(:), entity_of_dof(:), last_entities(:), &
                                first_function(:), n_functions(:)
        logical, allocatable :: is_last(:), taken(:)
        integer :: n_vertices, n_edges, c, e, i, f, k, entity, n_entities, count

        n_vertices = space%n_vertices
        n_edges = space%n_edges()
        n_entities = n_vertices + n_edges
        ! entity -> its functions: a vertex has one, an edge p_e - 1
        allocate (first_function(n_entities), n_functions(n_entities))
        first_function(1:n_vertices) = [(i, i=1, n_vertices)]
        n_functions(1:n_vertices) = 1
        first_function(n_vertices + 1:) = space%edge_first
        n_functions(n_vertices + 1:) = max(0, space%edge_degree - 1)

        allocate (is_last(space%n_functions), source=.false.)
        is_last(last_functions) = .true.
        if (any(space%free_function(last_functions) == 0)) then
            call stat%fail(STATUS_BAD_INPUT, 'hp ordering: a function to pivot last is clamped')
            return
        end if

        entities%element = ELEMENT_P2
        allocate (entities%coords(2, n_entities), source=0.0_wp)
        allocate (entities%cells(6, m%n_cells()))
        do c = 1, m%n_cells()
            entities%cells(1:3, c) = m%cells(1:3, c)
            entities%cells(4:6, c) = n_vertices + space%cell_edge(:, c)
        end do
        ! an entity is free (one pseudo node with two dofs) when one of its functions is
        ! free; it goes last when one of its functions is last
        allocate (entity_dofs%free_dof(2, n_entities), source=0)
        allocate (entity_of_dof(2*n_entities))
        allocate (taken(n_entities), source=.false.)
        count = 0
        do entity = 1, n_entities
            f = first_function(entity)
            k = n_functions(entity)
            if (k == 0) cycle
            if (all(space%free_function(f:f + k - 1) == 0)) cycle
            entity_dofs%free_dof(:, entity) = [count + 1, count + 2]
            entity_of_dof(count + 1:count + 2) = entity
            count = count + 2
            taken(entity) = any(is_last(f:f + k - 1))
        end do
        entity_dofs%n_free = count
        last_entities = pack([(entity, entity=1, n_entities)], taken)
        call nested_dissection_last(entities, entity_dofs, last_entities, entity_permutation, &
                                    stat)
        if (.not. stat%ok()) return

        allocate (permutation(space%n_free()))
        k = 0
        do i = 1, size(entity_permutation), 2
            entity = entity_of_dof(entity_permutation(i))
            if (taken(entity)) cycle
            do f = first_function(entity), first_function(entity) + n_functions(entity) - 1
                call append(f)
            end do
        end do
        do e = 1, n_entities   ! functions of last entities that are not last themselves
            if (.not. taken(e)) cycle
            do f = first_function(e), first_function(e) + n_functions(e) - 1
                if (.not. is_last(f)) call append(f)
            end do
        end do
        do i = 1, size(last_functions)
            call append(last_functions(i))
        end do
        if (k /= size(permutation)) then
            call stat%fail(STATUS_BAD_INPUT, 'hp ordering: '//to_string(k)//' of '// &
                to_string(size(permutation))//' dofs ordered (a function listed twice?)')
        end if

    contains

        subroutine append(function)
            integer, intent(in) :: function
            integer :: free
            free = space%free_function(function)
            if (free == 0 .or. k + 2 > size(permutation)) return
            permutation(k + 1:k + 2) = [2*free - 1, 2*free]
            k = k + 2
        end subroutine append
    end subroutine hp_cholesky_permutation
end module hp_ordering
