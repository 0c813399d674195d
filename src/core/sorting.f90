! SPDX-License-Identifier: MIT
!> The stable sorts of the program: columns of a sparse row, nodes along the contact segment,
!> node tags of a mesh file, nodes by degree in a renumbering, mesh sizes of a study; and the
!> binary search in what they sorted (a column in its row, a node tag).
!> Short runs use insertion sort, which needs no work array; longer ones a bottom-up merge
!> sort, O(n log n), since node counts reach millions. Both are stable, so equal keys keep
!> their input order whichever path runs, and the result does not depend on the length.
module sorting
    use kinds, only: wp
    implicit none
    private
    public :: sort, sort_index, sort_by_key, sorted_position

    !> Longest run sorted by insertion: its n^2/4 moves stay below the merge's set-up cost.
    integer, parameter :: INSERTION_MAX = 32

    !> order = sort_index(keys): the stable permutation with keys(order) ascending.
    !> For descending order pass -keys (negation reverses the order and keeps ties tied).
    interface sort_index
        module procedure sort_index_real, sort_index_integer
    end interface sort_index

contains

    !> Sort integers ascending in place.
    pure subroutine sort(values)
        integer, intent(inout) :: values(:)
        integer :: i, j, key
        if (size(values) > INSERTION_MAX) then
            values = values(sort_index_integer(values))
            return
        end if
        do i = 2, size(values)
            key = values(i)
            j = i - 1
            do while (j >= 1)
                if (values(j) <= key) exit
                values(j + 1) = values(j)
                j = j - 1
            end do
            values(j + 1) = key
        end do
    end subroutine sort

    !> Reorder `items` in place, stably, so that keys(items) ascends (nodes by degree).
    pure subroutine sort_by_key(items, keys)
        integer, intent(inout) :: items(:)
        integer, intent(in) :: keys(:)   !! indexed by the values of items
        integer :: i, j, item
        if (size(items) > INSERTION_MAX) then
            items = items(sort_index_integer(keys(items)))
            return
        end if
        do i = 2, size(items)
            item = items(i)
            j = i - 1
            do while (j >= 1)
                if (keys(items(j)) <= keys(item)) exit
                items(j + 1) = items(j)
                j = j - 1
            end do
            items(j + 1) = item
        end do
    end subroutine sort_by_key

    !> The position of `key` in `sorted` (ascending, without repeats), 0 when it is absent:
    !> a binary search, O(log n).
    pure integer function sorted_position(sorted, key) result(position)
        integer, intent(in) :: sorted(:)
        integer, intent(in) :: key
        integer :: low, high, middle
        position = 0
        low = 1
        high = size(sorted)
        do while (low <= high)
            middle = (low + high)/2
            if (sorted(middle) == key) then
                position = middle
                return
            else if (sorted(middle) < key) then
                low = middle + 1
            else
                high = middle - 1
            end if
        end do
    end function sorted_position

    !> Integer keys go through the real merge sort: default integers are exact in binary64,
    !> so the comparisons, and hence the permutation, are those of the integers.
    pure function sort_index_integer(keys) result(order)
        integer, intent(in) :: keys(:)
        integer, allocatable :: order(:)
        order = sort_index_real(real(keys, wp))
    end function sort_index_integer

    !> Bottom-up merge sort of the index; a left element goes first on ties (stability).
    pure function sort_index_real(keys) result(order)
        real(wp), intent(in) :: keys(:)
        integer, allocatable :: order(:), work(:)
        integer :: width, low, middle, high, i, j, k, n
        logical :: take_left
        n = size(keys)
        order = [(i, i=1, n)]
        allocate (work(n))
        width = 1
        do while (width < n)
            do low = 1, n, 2*width
                middle = min(low + width, n + 1)
                high = min(low + 2*width, n + 1)
                i = low
                j = middle
                do k = low, high - 1
                    take_left = i < middle
                    if (take_left .and. j < high) take_left = keys(order(i)) <= keys(order(j))
                    if (take_left) then
                        work(k) = order(i)
                        i = i + 1
                    else
                        work(k) = order(j)
                        j = j + 1
                    end if
                end do
            end do
            order(:) = work
            width = 2*width
        end do
    end function sort_index_real
end module sorting
