! SPDX-License-Identifier: MIT
!> Square sparse matrix in compressed sparse row form. The pattern is built once from the
!> element connectivity (sorted columns, no duplicates); assembly then only adds into slots.
module csr_matrix
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_INTERNAL
    use sorting, only: sort, sorted_position
    implicit none
    private
    public :: csr_from_element_dofs

    type, public :: csr_matrix_t
        integer, allocatable :: row_start(:)   !! (n + 1), 1-based
        integer, allocatable :: col(:)         !! column of each stored entry, sorted in a row
        real(wp), allocatable :: val(:)
    contains
        procedure :: n => csr_matrix_n
        procedure :: nnz => csr_matrix_nnz
        procedure :: slot => csr_matrix_slot
        procedure :: add_to => csr_matrix_add_to
        procedure :: add_block => csr_matrix_add_block
        procedure :: matvec => csr_matrix_matvec
        procedure :: norm_inf => csr_matrix_norm_inf
        procedure :: restrict => csr_matrix_restrict
    end type csr_matrix_t

contains

    !> Pattern of the matrix coupling every pair of dofs that share an element. `element_dofs`
    !> holds the dofs of each element in a column; zero entries (eliminated dofs) are skipped.
    !> Values start at zero.
    subroutine csr_from_element_dofs(n, element_dofs, a)
        integer, intent(in) :: n
        integer, intent(in) :: element_dofs(:, :)   !! (dofs_per_element, n_elements)
        type(csr_matrix_t), intent(out) :: a
        integer, allocatable :: elem_start(:), elem_of_dof(:), marker(:), row_len(:)
        integer :: e, i, row, found

        ! Incidence dof -> elements, in CSR form.
        allocate (elem_start(n + 1), source=0)
        do e = 1, size(element_dofs, 2)
            do i = 1, size(element_dofs, 1)
                row = element_dofs(i, e)
                if (row > 0) elem_start(row + 1) = elem_start(row + 1) + 1
            end do
        end do
        elem_start(1) = 1
        do row = 1, n
            elem_start(row + 1) = elem_start(row + 1) + elem_start(row)
        end do
        allocate (elem_of_dof(elem_start(n + 1) - 1))
        allocate (row_len(n), source=0)
        do e = 1, size(element_dofs, 2)
            do i = 1, size(element_dofs, 1)
                row = element_dofs(i, e)
                if (row > 0) then
                    elem_of_dof(elem_start(row) + row_len(row)) = e
                    row_len(row) = row_len(row) + 1
                end if
            end do
        end do

        ! Two passes over the rows: count distinct columns, then fill them.
        allocate (marker(n), source=0)
        allocate (a%row_start(n + 1))
        a%row_start(1) = 1
        do row = 1, n
            call distinct_columns(row, row_len(row))
            a%row_start(row + 1) = a%row_start(row) + row_len(row)
        end do
        allocate (a%col(a%row_start(n + 1) - 1))
        marker = 0
        do row = 1, n
            call distinct_columns(row, found, a%col(a%row_start(row):a%row_start(row + 1) - 1))
            call sort(a%col(a%row_start(row):a%row_start(row + 1) - 1))
        end do
        allocate (a%val(size(a%col)), source=0.0_wp)

    contains

        !> The `n_found` distinct columns of row `row` (the dofs of the elements at dof `row`)
        !> into `columns` in the order met, or only counted without it; marks them in
        !> `marker` with the row.
        subroutine distinct_columns(row, n_found, columns)
            integer, intent(in) :: row
            integer, intent(out) :: n_found
            integer, intent(inout), optional :: columns(:)
            integer :: k, j, column
            n_found = 0
            do k = elem_start(row), elem_start(row + 1) - 1
                do j = 1, size(element_dofs, 1)
                    column = element_dofs(j, elem_of_dof(k))
                    if (column <= 0) cycle
                    if (marker(column) == row) cycle
                    marker(column) = row
                    n_found = n_found + 1
                    if (present(columns)) columns(n_found) = column
                end do
            end do
        end subroutine distinct_columns
    end subroutine csr_from_element_dofs

    pure integer function csr_matrix_n(this)
        class(csr_matrix_t), intent(in) :: this
        csr_matrix_n = size(this%row_start) - 1
    end function csr_matrix_n

    pure integer(i8) function csr_matrix_nnz(this)
        class(csr_matrix_t), intent(in) :: this
        csr_matrix_nnz = size(this%col, kind=i8)
    end function csr_matrix_nnz

    !> Position of entry (i, j) in `col`/`val`, or 0 when it is outside the pattern.
    pure integer function csr_matrix_slot(this, i, j)
        class(csr_matrix_t), intent(in) :: this
        integer, intent(in) :: i, j
        integer :: first
        first = this%row_start(i)
        csr_matrix_slot = sorted_position(this%col(first:this%row_start(i + 1) - 1), j)
        if (csr_matrix_slot > 0) csr_matrix_slot = first - 1 + csr_matrix_slot
    end function csr_matrix_slot

    !> a(i, j) += value; (i, j) must be in the pattern.
    subroutine csr_matrix_add_to(this, i, j, value, stat)
        class(csr_matrix_t), intent(inout) :: this
        integer, intent(in) :: i, j
        real(wp), intent(in) :: value
        type(status_t), intent(inout) :: stat
        integer :: k
        k = this%slot(i, j)
        if (k == 0) then
            call stat%fail(STATUS_INTERNAL, 'csr_matrix: entry outside the sparsity pattern')
            return
        end if
        this%val(k) = this%val(k) + value
    end subroutine csr_matrix_add_to

    !> Scatter an element matrix: a(dofs(i), dofs(j)) += block(i, j), skipping zero dofs.
    subroutine csr_matrix_add_block(this, dofs, block, stat)
        class(csr_matrix_t), intent(inout) :: this
        integer, intent(in) :: dofs(:)
        real(wp), intent(in) :: block(:, :)
        type(status_t), intent(inout) :: stat
        integer :: i, j
        do j = 1, size(dofs)
            if (dofs(j) == 0) cycle
            do i = 1, size(dofs)
                if (dofs(i) == 0) cycle
                call this%add_to(dofs(i), dofs(j), block(i, j), stat)
                if (.not. stat%ok()) return
            end do
        end do
    end subroutine csr_matrix_add_block

    !> y = A x
    pure subroutine csr_matrix_matvec(this, x, y)
        class(csr_matrix_t), intent(in) :: this
        real(wp), intent(in) :: x(:)
        real(wp), intent(out) :: y(:)
        integer :: i, k
        do i = 1, size(this%row_start) - 1
            y(i) = 0.0_wp
            do k = this%row_start(i), this%row_start(i + 1) - 1
                y(i) = y(i) + this%val(k)*x(this%col(k))
            end do
        end do
    end subroutine csr_matrix_matvec

    !> Largest absolute row sum.
    pure real(wp) function csr_matrix_norm_inf(this)
        class(csr_matrix_t), intent(in) :: this
        integer :: i
        csr_matrix_norm_inf = 0.0_wp
        do i = 1, size(this%row_start) - 1
            csr_matrix_norm_inf = max(csr_matrix_norm_inf, &
                sum(abs(this%val(this%row_start(i):this%row_start(i + 1) - 1))))
        end do
    end function csr_matrix_norm_inf

    !> The submatrix of the rows and columns i with new_index(i) > 0, renumbered by new_index,
    !> which must be increasing on them (so columns stay sorted): K on the free dofs from K on
    !> all dofs, with the same values, so nothing is assembled twice.
    pure function csr_matrix_restrict(this, new_index) result(sub)
        class(csr_matrix_t), intent(in) :: this
        integer, intent(in) :: new_index(:)   !! (n) new number of each row/column, or 0
        type(csr_matrix_t) :: sub
        integer :: i, k, row, n_entries

        n_entries = 0
        do i = 1, this%n()
            if (new_index(i) <= 0) cycle
            do k = this%row_start(i), this%row_start(i + 1) - 1
                if (new_index(this%col(k)) > 0) n_entries = n_entries + 1
            end do
        end do
        allocate (sub%row_start(count(new_index > 0) + 1), sub%col(n_entries), &
                  sub%val(n_entries))
        sub%row_start(1) = 1
        n_entries = 0
        row = 0
        do i = 1, this%n()
            if (new_index(i) <= 0) cycle
            row = row + 1
            do k = this%row_start(i), this%row_start(i + 1) - 1
                if (new_index(this%col(k)) <= 0) cycle
                n_entries = n_entries + 1
                sub%col(n_entries) = new_index(this%col(k))
                sub%val(n_entries) = this%val(k)
            end do
            sub%row_start(row + 1) = n_entries + 1
        end do
    end function csr_matrix_restrict
end module csr_matrix
