! SPDX-License-Identifier: MIT
!> Node renumbering for locality: reverse Cuthill-McKee (our own) or METIS nested dissection
!> (METIS_NodeND, bound in metis_c). Neighbouring nodes get nearby numbers, so the
!> assembly, the matrix-vector products and the sparse factorization touch memory in order.
!> Files written by mesh generators number nodes by geometric entity, which scatters the
!> nodes of one cell across the whole node array.
module mesh_renumber
    use, intrinsic :: iso_c_binding, only: c_null_ptr
    use metis_c, only: metis_nodend, IDX_T, METIS_OK
    use kinds, only: wp
    use status, only: status_t, STATUS_SOLVER, STATUS_INTERNAL
    use mesh, only: mesh_t
    use csr_matrix, only: csr_matrix_t, csr_from_element_dofs
    use strings, only: to_string
    use sorting, only: sort_by_key
    implicit none
    private
    public :: renumber_nodes, node_order, node_bandwidth
    public :: RENUMBER_NONE, RENUMBER_RCM, RENUMBER_METIS

    integer, parameter :: RENUMBER_NONE = 0    !! keep the numbering
    integer, parameter :: RENUMBER_RCM = 1     !! reverse Cuthill-McKee
    integer, parameter :: RENUMBER_METIS = 2   !! METIS_NodeND (nested dissection)

contains

    !> Renumber the nodes of `m` with `method` (RENUMBER_*): coordinates, cells and edges
    !> follow; cells and edges keep their order (and so their file lines).
    subroutine renumber_nodes(m, method, stat)
        type(mesh_t), intent(inout) :: m
        integer, intent(in) :: method
        type(status_t), intent(out) :: stat
        integer, allocatable :: new_of_old(:)
        real(wp), allocatable :: coords(:, :)
        integer :: node

        call node_order(m, method, new_of_old, stat)
        if (.not. stat%ok()) return
        allocate (coords, mold=m%coords)
        do node = 1, m%n_nodes()
            coords(:, new_of_old(node)) = m%coords(:, node)
        end do
        call move_alloc(coords, m%coords)
        m%cells = reshape(new_of_old(reshape(m%cells, [size(m%cells)])), shape(m%cells))
        if (allocated(m%edges)) then
            m%edges = reshape(new_of_old(reshape(m%edges, [size(m%edges)])), shape(m%edges))
        end if
    end subroutine renumber_nodes

    !> New number of each node under `method`: new_of_old(old) = new, a permutation of 1..n.
    subroutine node_order(m, method, new_of_old, stat)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: method
        integer, allocatable, intent(out) :: new_of_old(:)
        type(status_t), intent(out) :: stat
        type(csr_matrix_t) :: graph
        integer :: i

        select case (method)
        case (RENUMBER_NONE)
            new_of_old = [(i, i=1, m%n_nodes())]
        case (RENUMBER_RCM, RENUMBER_METIS)
            call csr_from_element_dofs(m%n_nodes(), m%cells, graph)
            if (method == RENUMBER_RCM) then
                new_of_old = rcm_order(graph)
            else
                call metis_order(graph, new_of_old, stat)
            end if
        case default
            call stat%fail(STATUS_INTERNAL, 'renumber: unknown method '//to_string(method))
        end select
    end subroutine node_order

    !> Largest difference of two node numbers in one cell: the half bandwidth of the node
    !> graph (of K, in nodes).
    pure integer function node_bandwidth(m)
        type(mesh_t), intent(in) :: m
        integer :: cell
        node_bandwidth = 0
        do cell = 1, m%n_cells()
            node_bandwidth = max(node_bandwidth, maxval(m%cells(:, cell)) - &
                                 minval(m%cells(:, cell)))
        end do
    end function node_bandwidth

    !> Reverse Cuthill-McKee on the node graph (diagonal entries ignored): breadth-first
    !> search from a pseudo-peripheral node of each connected component, neighbours taken
    !> by increasing degree, the whole order reversed (same bandwidth, less profile).
    function rcm_order(graph) result(new_of_old)
        type(csr_matrix_t), intent(in) :: graph
        integer, allocatable :: new_of_old(:)
        integer, allocatable :: degree(:), queue(:), level(:), order(:)
        logical, allocatable :: placed(:)
        integer :: n, node, root, n_ordered, head, tail, k, neighbour, first, i

        n = size(graph%row_start) - 1
        allocate (degree(n), queue(n), level(n), order(n), new_of_old(n))
        degree = graph%row_start(2:) - graph%row_start(:n) - 1
        allocate (placed(n), source=.false.)
        level = 0
        n_ordered = 0
        do node = 1, n
            if (placed(node)) cycle
            root = pseudo_peripheral(node)
            ! Cuthill-McKee breadth-first search of this component into order(:).
            head = n_ordered + 1
            tail = n_ordered + 1
            order(tail) = root
            placed(root) = .true.
            do while (head <= tail)
                first = tail + 1
                do k = graph%row_start(order(head)), graph%row_start(order(head) + 1) - 1
                    neighbour = graph%col(k)
                    if (placed(neighbour)) cycle
                    placed(neighbour) = .true.
                    tail = tail + 1
                    order(tail) = neighbour
                end do
                ! The new neighbours by increasing degree, ties in the order met.
                call sort_by_key(order(first:tail), degree)
                head = head + 1
            end do
            n_ordered = tail
        end do
        do i = 1, n
            new_of_old(order(i)) = n + 1 - i
        end do

    contains

        !> George and Liu's pseudo-peripheral node of the component of `start`: move to a
        !> least-degree node of the last level while the eccentricity grows.
        integer function pseudo_peripheral(start)
            integer, intent(in) :: start
            integer :: depth, new_depth, last_first, last_count, candidate, a
            pseudo_peripheral = start
            call levels(pseudo_peripheral, depth, last_first, last_count)
            do
                candidate = queue(last_first)
                do a = last_first, last_first + last_count - 1
                    if (degree(queue(a)) < degree(candidate)) candidate = queue(a)
                end do
                call levels(candidate, new_depth, last_first, last_count)
                if (new_depth <= depth) exit
                pseudo_peripheral = candidate
                depth = new_depth
            end do
        end function pseudo_peripheral

        !> Level structure rooted at `root` in queue(1:reached); `level` is reset afterwards.
        !> Returns the depth and where the last level starts in `queue` and its size.
        subroutine levels(root, depth, last_first, last_count)
            integer, intent(in) :: root
            integer, intent(out) :: depth, last_first, last_count
            integer :: front, back, slot, other, a
            front = 1
            back = 1
            queue(1) = root
            level(root) = 1
            do while (front <= back)
                do slot = graph%row_start(queue(front)), graph%row_start(queue(front) + 1) - 1
                    other = graph%col(slot)
                    if (level(other) /= 0) cycle
                    level(other) = level(queue(front)) + 1
                    back = back + 1
                    queue(back) = other
                end do
                front = front + 1
            end do
            depth = level(queue(back))
            last_first = back
            do while (last_first > 1)
                if (level(queue(last_first - 1)) /= depth) exit
                last_first = last_first - 1
            end do
            last_count = back - last_first + 1
            do a = 1, back
                level(queue(a)) = 0
            end do
        end subroutine levels
    end function rcm_order

    !> METIS nested-dissection order of the node graph (self loops removed, as METIS needs).
    subroutine metis_order(graph, new_of_old, stat)
        type(csr_matrix_t), intent(in) :: graph
        integer, allocatable, intent(out) :: new_of_old(:)
        type(status_t), intent(out) :: stat
        integer(IDX_T), allocatable :: xadj(:), adjncy(:), perm(:), iperm(:)
        integer(IDX_T) :: n_vertices
        integer :: n, row, k, pos
        integer :: code

        n = size(graph%row_start) - 1
        allocate (new_of_old(n))
        if (n < 3) then   ! nothing to order, and METIS wants a graph with edges
            new_of_old = [(row, row=1, n)]
            return
        end if
        allocate (xadj(n + 1), adjncy(size(graph%col) - n), perm(n), iperm(n))
        xadj(1) = 0
        pos = 0
        do row = 1, n
            do k = graph%row_start(row), graph%row_start(row + 1) - 1
                if (graph%col(k) == row) cycle
                pos = pos + 1
                adjncy(pos) = int(graph%col(k) - 1, IDX_T)
            end do
            xadj(row + 1) = int(pos, IDX_T)
        end do
        n_vertices = int(n, IDX_T)
        code = metis_nodend(n_vertices, xadj, adjncy, c_null_ptr, c_null_ptr, &
                            perm, iperm)
        if (code /= METIS_OK) then
            call stat%fail(STATUS_SOLVER, 'renumber: METIS_NodeND failed with code '// &
                           to_string(code))
            return
        end if
        new_of_old = int(iperm) + 1
    end subroutine metis_order
end module mesh_renumber
