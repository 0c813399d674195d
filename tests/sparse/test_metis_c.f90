! SPDX-License-Identifier: MIT
!> The METIS binding: its messages, and the behaviour it wraps called through it as nceig
!> calls it (0-based CSR graph, default options): METIS_NodeND returns a permutation and
!> its inverse, and the order is a fill-reducing one: eliminating the 5-point graph of a
!> 15 x 15 grid in it (the elimination game, counted here) fills less than the row-by-row
!> order, whose fill is the band's.
program test_metis_c
    use, intrinsic :: iso_c_binding, only: c_null_ptr
    use metis_c, only: metis_nodend, metis_status_message, IDX_T, METIS_OK, &
                       METIS_ERROR_INPUT, METIS_ERROR_MEMORY
    use fixtures, only: is_permutation
    use testing, only: test_suite_t
    implicit none

    integer, parameter :: SIDE = 15, N = SIDE*SIDE
    type(test_suite_t) :: t
    integer(IDX_T), allocatable :: xadj(:), adjncy(:), perm(:), iperm(:)
    integer :: code, i, natural_fill, nested_fill

    t%name = 'test_metis_c'
    call t%check('metis_status_message: a sentence per code', &
                 metis_status_message(METIS_OK) == 'success' .and. &
                 index(metis_status_message(METIS_ERROR_INPUT), 'METIS_ERROR_INPUT') > 0 .and. &
                 index(metis_status_message(METIS_ERROR_MEMORY), 'out of memory') > 0 .and. &
                 metis_status_message(-4) == 'METIS failed (code -4)')

    call grid_graph(xadj, adjncy)
    allocate (perm(N), iperm(N))
    code = metis_nodend(int(N, IDX_T), xadj, adjncy, c_null_ptr, c_null_ptr, perm, iperm)
    call t%check('METIS_NodeND: METIS_OK, perm a 0-based permutation, iperm its inverse', &
                 code == METIS_OK .and. is_permutation(int(perm) + 1, N) .and. &
                 all([(iperm(perm(i) + 1) == i - 1, i=1, N)]))
    natural_fill = fill([(i, i=1, N)])
    nested_fill = fill(perm + 1)
    call t%check('METIS_NodeND: less fill than the band of the row-by-row order', &
                 nested_fill < natural_fill)
    ! (AddressSanitizer reports a main program's allocatables)
    deallocate (xadj, adjncy, perm, iperm)
    call t%report()

contains

    !> The 5-point graph of a SIDE x SIDE grid, 0-based CSR, no self loops.
    subroutine grid_graph(xadj, adjncy)
        integer(IDX_T), allocatable, intent(out) :: xadj(:), adjncy(:)
        integer :: i, j, v, k, d
        integer :: neighbour(4)
        logical :: inside(4)
        allocate (xadj(N + 1), adjncy(4*N))
        k = 0
        xadj(1) = 0
        do j = 1, SIDE
            do i = 1, SIDE
                v = i + (j - 1)*SIDE
                neighbour = [v - SIDE, v - 1, v + 1, v + SIDE]   ! ascending
                inside = [j > 1, i > 1, i < SIDE, j < SIDE]
                do d = 1, 4
                    if (.not. inside(d)) cycle
                    k = k + 1
                    adjncy(k) = int(neighbour(d) - 1, IDX_T)
                end do
                xadj(v + 1) = int(k, IDX_T)
            end do
        end do
        adjncy = adjncy(:k)
    end subroutine grid_graph

    !> nnz of the Cholesky factor's lower triangle when the vertices are eliminated in
    !> `order` (order(k) = the k-th eliminated): each eliminated vertex joins its remaining
    !> neighbours into a clique.
    integer function fill(order)
        integer, intent(in) :: order(:)
        logical, allocatable :: adjacent(:, :)
        integer :: position(N), k, v, a, b, e
        integer, allocatable :: later(:)
        allocate (adjacent(N, N), source=.false.)
        do v = 1, N
            do e = xadj(v) + 1, xadj(v + 1)
                adjacent(v, adjncy(e) + 1) = .true.
            end do
        end do
        position(order) = [(k, k=1, N)]
        fill = 0
        do k = 1, N
            v = order(k)
            later = pack([(a, a=1, N)], adjacent(v, :) .and. position > k)
            fill = fill + 1 + size(later)
            do a = 1, size(later)
                do b = 1, size(later)
                    if (a /= b) adjacent(later(a), later(b)) = .true.
                end do
            end do
        end do
    end function fill
end program test_metis_c
