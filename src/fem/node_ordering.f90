! SPDX-License-Identifier: MIT
!> Fill-reducing orderings of the free dofs computed on the node graph (two dofs per node
!> share one vertex, so METIS sees a graph four times smaller than the dof graph), with a
!> chosen set of nodes forced last: the contact nodes, so that the trailing block of the
!> Cholesky factor of K is the Schur complement of K onto the contact dofs.
module node_ordering
    use, intrinsic :: iso_c_binding, only: c_null_ptr
    use metis_c, only: metis_nodend, metis_status_message, IDX_T, METIS_OK
    use status, only: status_t, STATUS_SOLVER, STATUS_BAD_INPUT
    use strings, only: to_string
    use mesh, only: mesh_t
    use dof_map, only: dof_map_t
    use element_types, only: element_corners, element_degree
    use sorting, only: sort, sort_index
    implicit none
    private
    public :: nested_dissection_last

contains

    !> Dof permutation (1-based; permutation(k) = the dof pivoted k-th) for a Cholesky factor
    !> of K: METIS nested dissection of the graph of the free cell corners not in
    !> `last_nodes` (two corners adjacent when they share a cell), each node's free dofs
    !> together, then the free dofs of `last_nodes` in their given order.
    !>
    !> The other nodes of a higher-order cell (P2 to P4, Q2) join that order just before the
    !> first-ordered corner of their cell side (edge nodes) or of their cell (interior nodes):
    !> eliminated there, they couple only nodes their corners couple already, so the fill
    !> follows the corner ordering's, while METIS sees a graph of the corners alone, whose
    !> cliques are 3 or 4 wide instead of up to 15: 8 to 12 times faster, for a factor with
    !> 0 (P2) to 29% (P4) more entries (docs/performance.md, "Ordering higher-order meshes").
    subroutine nested_dissection_last(m, dofs, last_nodes, permutation, stat)
        type(mesh_t), intent(in) :: m
        type(dof_map_t), intent(in) :: dofs
        integer, intent(in) :: last_nodes(:)
        integer, allocatable, intent(out) :: permutation(:)
        type(status_t), intent(out) :: stat
        integer, allocatable :: vertex(:), node_of(:), degree(:), rank(:), key(:), &
                                candidates(:), order(:)
        logical, allocatable :: ordered(:)
        integer(IDX_T), allocatable :: xadj(:), adjncy(:), perm(:), iperm(:), fill(:)
        integer :: n_nodes, n_vertices, e, a, b, na, nb, k, c, node, n_corners, inner, &
                   side, anchor
        integer :: code

        n_nodes = m%n_nodes()
        n_corners = element_corners(m%element)
        inner = max(0, element_degree(m%element) - 1)   ! nodes inside a cell side
        ! ordered(node): a node with a free dof that is not forced last
        allocate (ordered(n_nodes), source=.false.)
        do node = 1, n_nodes
            ordered(node) = any(dofs%free_dof(:, node) > 0)
        end do
        ordered(last_nodes) = .false.
        ! vertex(node) > 0 for an ordered cell corner: the graph METIS orders
        allocate (vertex(n_nodes), source=0)
        do c = 1, size(m%cells, 2)
            do a = 1, n_corners
                if (ordered(m%cells(a, c))) vertex(m%cells(a, c)) = -1
            end do
        end do
        n_vertices = 0
        allocate (node_of(n_nodes))
        do node = 1, n_nodes
            if (vertex(node) /= -1) cycle
            n_vertices = n_vertices + 1
            vertex(node) = n_vertices
            node_of(n_vertices) = node
        end do

        allocate (permutation(dofs%n_free))
        allocate (rank(n_nodes), source=0)
        k = 0
        if (n_vertices > 0) then
            ! Cell cliques give each edge several times; METIS accepts only simple graphs,
            ! so build the adjacency with duplicates, then sort and compress each row.
            allocate (degree(n_vertices), source=0)
            call corner_pairs(.false.)
            allocate (xadj(n_vertices + 1), adjncy(sum(degree)), fill(n_vertices))
            xadj(1) = 0
            do a = 1, n_vertices
                xadj(a + 1) = xadj(a) + degree(a)
            end do
            fill = xadj(1:n_vertices)
            call corner_pairs(.true.)
            call compress_rows(xadj, adjncy)

            allocate (perm(n_vertices), iperm(n_vertices))
            code = metis_nodend(int(n_vertices, IDX_T), xadj, adjncy, c_null_ptr, c_null_ptr, &
                                perm, iperm)
            if (code /= METIS_OK) then
                call stat%fail(STATUS_SOLVER, 'METIS_NodeND on the node graph ('// &
                    to_string(n_vertices)//' nodes): '//metis_status_message(code))
                return
            end if
            do a = 1, n_vertices
                rank(node_of(perm(a) + 1)) = a
            end do
        end if

        ! sort keys: corner of rank r at 2 r, another node at 2 r - 1 (r its anchor's rank),
        ! 0 when none of its corners is ordered (all fixed or last)
        allocate (key(n_nodes), source=0)
        do c = 1, size(m%cells, 2)
            do a = 1, size(m%cells, 1)
                node = m%cells(a, c)
                if (.not. ordered(node)) cycle
                if (a <= n_corners) then
                    key(node) = 2*rank(node)
                    cycle
                end if
                side = (a - n_corners - 1)/max(inner, 1) + 1
                if (side <= n_corners) then   ! on side `side`, from corner side to side + 1
                    anchor = first_ranked([m%cells(side, c), &
                                           m%cells(mod(side, n_corners) + 1, c)])
                else                          ! inside the cell
                    anchor = first_ranked(m%cells(1:n_corners, c))
                end if
                if (anchor > 0) key(node) = 2*anchor - 1
            end do
        end do
        candidates = pack([(node, node=1, n_nodes)], ordered)
        allocate (order(size(candidates)))   ! (gfortran 12 warns of an unallocated one at -O3)
        order = sort_index(key(candidates))  ! stable: node order among equal keys
        do a = 1, size(order)
            call append(candidates(order(a)))
        end do
        do a = 1, size(last_nodes)
            call append(last_nodes(a))
        end do
        if (k /= dofs%n_free) then
            call stat%fail(STATUS_BAD_INPUT, 'node ordering: '//to_string(k)//' of '// &
                to_string(dofs%n_free)//' free dofs ordered (a node listed twice as last?)')
        end if

    contains

        subroutine append(node)
            integer, intent(in) :: node
            do c = 1, size(dofs%free_dof, 1)
                if (dofs%free_dof(c, node) > 0 .and. k < size(permutation)) then
                    k = k + 1
                    permutation(k) = dofs%free_dof(c, node)
                end if
            end do
        end subroutine append

        !> The smallest positive rank among `corners` (0 if none is ordered).
        pure integer function first_ranked(corners)
            integer, intent(in) :: corners(:)
            first_ranked = minval(rank(corners), mask=rank(corners) > 0)
            if (first_ranked == huge(first_ranked)) first_ranked = 0
        end function first_ranked

        !> Every ordered pair of distinct graph vertices (na, nb) that share a cell: counted
        !> in degree(na), or with `store` written into adjncy after fill(na) (METIS's 0-based
        !> numbers). Pairs repeat across cells; compress_rows removes the repeats.
        subroutine corner_pairs(store)
            logical, intent(in) :: store
            do e = 1, size(m%cells, 2)
                do a = 1, n_corners
                    na = vertex(m%cells(a, e))
                    if (na <= 0) cycle
                    do b = 1, n_corners
                        nb = vertex(m%cells(b, e))
                        if (nb <= 0 .or. nb == na) cycle
                        if (store) then
                            fill(na) = fill(na) + 1
                            adjncy(fill(na)) = int(nb - 1, IDX_T)
                        else
                            degree(na) = degree(na) + 1
                        end if
                    end do
                end do
            end do
        end subroutine corner_pairs
    end subroutine nested_dissection_last

    !> Sort each row of a 0-based CSR graph and drop repeated neighbours, in place.
    pure subroutine compress_rows(xadj, adjncy)
        integer(IDX_T), intent(inout) :: xadj(:)
        integer(IDX_T), allocatable, intent(inout) :: adjncy(:)
        integer :: row, first, last, out, i
        out = 0
        first = xadj(1) + 1
        do row = 1, size(xadj) - 1
            last = xadj(row + 1)
            call sort(adjncy(first:last))
            xadj(row) = out
            do i = first, last
                if (i > first) then
                    if (adjncy(i) == adjncy(i - 1)) cycle
                end if
                out = out + 1
                adjncy(out) = adjncy(i)
            end do
            first = last + 1
        end do
        xadj(size(xadj)) = out
        adjncy = adjncy(1:out)
    end subroutine compress_rows
end module node_ordering
