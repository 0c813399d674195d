! SPDX-License-Identifier: MIT
!> sorting against the definition of a stable sort: element i goes to position
!> 1 + #(keys < keys(i)) + #(j < i with keys(j) = keys(i)). Keys have many ties, and the
!> lengths straddle the switch from insertion to merge sort (32), so both paths are checked
!> to give the same permutation. sorted_position against a linear search (findloc) for
!> every key from below the first to above the last. Everything is exact integer logic: no
!> tolerances.
program test_sorting
    use kinds, only: wp, i8
    use sorting, only: sort, sort_index, sort_by_key, sorted_position
    use testing, only: test_suite_t
    implicit none

    integer, parameter :: LENGTHS(9) = [0, 1, 2, 7, 31, 32, 33, 100, 1000]
    type(test_suite_t) :: t
    integer, allocatable :: keys(:), order(:), values(:), items(:), degree(:), k(:), ascending(:)
    real(wp), allocatable :: x(:)
    integer :: c, n, i, state
    logical :: ok_index, ok_sort, ok_key, ok_real, ok_descending, ok_large, ok_search
    character(len=8) :: n_text

    t%name = 'test_sorting'
    state = 12345
    do c = 1, size(LENGTHS)
        n = LENGTHS(c)
        write (n_text, '(i0)') n
        ! Keys in [0, n/4]: about four copies of each, so stability is tested.
        keys = random_integers(n, n/4 + 1, state)
        order = sort_index(keys)
        ok_index = size(order) == n
        if (ok_index) ok_index = all(order == stable_order(keys))
        call t%check('sort_index, n = '//trim(n_text)//': the stable permutation', ok_index)

        values = keys
        call sort(values)
        ok_sort = all(values == keys(stable_order(keys)))
        call t%check('sort, n = '//trim(n_text)//': ascending, same values', ok_sort)

        ! Items are a shuffled subset of node numbers; keys are their degrees.
        degree = random_integers(2*n + 1, 6, state)
        items = random_integers(n, 2*n + 1, state) + 1
        values = items(stable_order(degree(items)))
        call sort_by_key(items, degree)
        ok_key = all(items == values)
        call t%check('sort_by_key, n = '//trim(n_text)//': stable by key', ok_key)

        ! Real keys k/3 with ties, negative values and a signed zero (-0.0 ties with 0.0):
        ! dividing by 3 keeps the order of the integers k, so theirs is the expected one.
        k = random_integers(n, n/4 + 1, state) - n/8
        if (n > 0) k(n) = 0
        x = real(k, wp)/3.0_wp
        if (n > 0) x(n) = -0.0_wp
        order = sort_index(x)
        ok_real = all(order == stable_order(k))
        call t%check('sort_index real, n = '//trim(n_text)//': the stable permutation', ok_real)
        order = sort_index(-x)
        ok_descending = all(order == stable_order(-k))
        if (n > 1) ok_descending = ok_descending .and. all(x(order(:n - 1)) >= x(order(2:)))
        call t%check('sort_index(-x), n = '//trim(n_text)//': stable descending', ok_descending)

        ! Ascending without repeats, with gaps: the keys in between must be absent.
        ascending = [(3*i + mod(i, 2), i=1, n)]
        ok_search = .true.
        do i = -1, 3*n + 3
            if (sorted_position(ascending, i) /= findloc(ascending, i, 1)) ok_search = .false.
        end do
        call t%check('sorted_position, n = '//trim(n_text)//': as a linear search', ok_search)
    end do

    ! Many merge levels (2^17 < n): linear checks of order, permutation and stability.
    n = 200001
    keys = random_integers(n, 1000, state)
    order = sort_index(keys)
    values = [(0, i=1, n)]
    values(order) = 1
    ok_large = all(values == 1)
    do i = 2, n
        if (keys(order(i - 1)) > keys(order(i))) ok_large = .false.
        if (keys(order(i - 1)) == keys(order(i)) .and. order(i - 1) > order(i)) &
            ok_large = .false.
    end do
    call t%check('sort_index, n = 200001: a stable permutation', ok_large)

    ! gfortran 12 keeps main-program allocatables in a frame gone before LeakSanitizer
    ! looks: free them here so a sanitizer build reports only real leaks.
    deallocate (keys, order, values, items, degree, k, x, ascending)
    call t%report()

contains

    !> The definition, in O(n^2): where a stable sort puts each element, inverted.
    pure function stable_order(keys) result(order)
        integer, intent(in) :: keys(:)
        integer :: order(size(keys))
        integer :: i, position
        do i = 1, size(keys)
            position = 1 + count(keys < keys(i)) + count(keys(:i - 1) == keys(i))
            order(position) = i
        end do
    end function stable_order

    !> n integers in [0, range) from a Park-Miller generator (reproducible everywhere).
    function random_integers(n, range, state) result(r)
        integer, intent(in) :: n, range
        integer, intent(inout) :: state
        integer :: r(n)
        integer :: i
        do i = 1, n
            state = int(mod(48271_i8*int(state, i8), 2147483647_i8))
            r(i) = mod(state, range)
        end do
    end function random_integers
end program test_sorting
