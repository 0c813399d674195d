! SPDX-License-Identifier: MIT
!> Sparse LU factorization of a general square CSR matrix with UMFPACK, for the shifted,
!> non-symmetric operators K - sigma B.
!>
!> An `lu_t` owns the UMFPACK Numeric object and 0-based copies of the matrix (UMFPACK's
!> iterative refinement in the solve reads A again). It frees itself when it goes out of
!> scope (final) and `free` may be called repeatedly, but it must not be copied: an
!> assigned copy would share the Numeric handle.
module sparse_lu
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_null_ptr, c_associated
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_SINGULAR, STATUS_SOLVER
    use csr_matrix, only: csr_matrix_t
    use strings, only: to_string
    use blas_threads, only: blas_threads_for
    use umfpack_c, only: umfpack_di_symbolic, umfpack_di_numeric, umfpack_di_solve, &
                         umfpack_di_free_symbolic, umfpack_di_free_numeric, umfpack_di_defaults, &
                         umfpack_status_message, UMFPACK_CONTROL, UMFPACK_INFO, UMFPACK_A, &
                         UMFPACK_At, UMFPACK_PRL, UMFPACK_ORDERING, UMFPACK_IRSTEP, UMFPACK_LNZ, &
                         UMFPACK_UNZ, UMFPACK_FLOPS, UMFPACK_RCOND, UMFPACK_ORDERING_AMD, &
                         UMFPACK_ORDERING_METIS, UMFPACK_ORDERING_CHOLMOD, UMFPACK_ORDERING_NONE, &
                         UMFPACK_OK, UMFPACK_WARNING_singular_matrix
    implicit none
    private
    public :: LU_ORDERING_DEFAULT, LU_ORDERING_METIS, LU_ORDERING_NATURAL, LU_ORDERING_CHOLMOD

    !> Fill-reducing orderings for `factor`; the values are UMFPACK's.
    integer, parameter :: LU_ORDERING_DEFAULT = UMFPACK_ORDERING_AMD   !! AMD or COLAMD
    integer, parameter :: LU_ORDERING_METIS = UMFPACK_ORDERING_METIS
    integer, parameter :: LU_ORDERING_NATURAL = UMFPACK_ORDERING_NONE
    integer, parameter :: LU_ORDERING_CHOLMOD = UMFPACK_ORDERING_CHOLMOD !! AMD, then METIS

    !> LU factors of a square sparse matrix, owned through UMFPACK's Numeric handle.
    type, public :: lu_t
        private
        type(c_ptr) :: numeric = c_null_ptr
        integer(c_int), allocatable :: ap(:)   !! (n + 1), 0-based row starts of our CSR
        integer(c_int), allocatable :: ai(:)   !! 0-based columns of our CSR
        real(c_double), allocatable :: ax(:)   !! values, copied so the caller may change a
        real(c_double) :: control(UMFPACK_CONTROL) = 0.0_c_double
        real(c_double) :: info(UMFPACK_INFO) = 0.0_c_double
    contains
        procedure :: factor => lu_factor
        procedure :: factor_shifted => lu_factor_shifted
        procedure :: solve => lu_solve
        procedure :: free => lu_free
        procedure :: rcond => lu_rcond
        procedure :: factor_nnz => lu_factor_nnz
        procedure :: is_factored => lu_is_factored
        final :: lu_finalize
    end type lu_t

contains

    !> Factorize the square matrix `a`; a previous factorization is freed first. A matrix
    !> UMFPACK finds singular (an exactly zero pivot) is a failure with STATUS_SINGULAR.
    !> `ordering` is one of the LU_ORDERING_* constants (default LU_ORDERING_DEFAULT).
    subroutine lu_factor(this, a, stat, ordering)
        class(lu_t), intent(inout) :: this
        type(csr_matrix_t), intent(in) :: a
        type(status_t), intent(out) :: stat
        integer, intent(in), optional :: ordering

        call this%free()
        if (a%n() < 1) then
            call stat%fail(STATUS_BAD_INPUT, 'sparse_lu: the matrix is empty')
            return
        end if
        this%ap = int(a%row_start - 1, c_int)
        this%ai = int(a%col - 1, c_int)
        this%ax = real(a%val, c_double)
        call factor_copies(this, stat, ordering)
    end subroutine lu_factor

    !> Factorize a - sigma b, where the pattern of b lies within that of a (so K - sigma B
    !> for the contact matrix B, whose couplings are those of contact edges, all inside K's
    !> elements): the difference is formed straight into the copies UMFPACK needs, with no
    !> other copy of a. A b entry outside a's pattern fails with STATUS_BAD_INPUT.
    !> `refinement_steps`: UMFPACK's iterative refinement per solve (its default 2; each step
    !> costs another solve and product, and 0 leaves a backward-stable LU solve).
    subroutine lu_factor_shifted(this, a, b, sigma, stat, ordering, refinement_steps)
        class(lu_t), intent(inout) :: this
        type(csr_matrix_t), intent(in) :: a, b
        real(wp), intent(in) :: sigma
        type(status_t), intent(out) :: stat
        integer, intent(in), optional :: ordering, refinement_steps
        integer :: i, k, slot

        call this%free()
        if (a%n() < 1 .or. b%n() /= a%n()) then
            call stat%fail(STATUS_BAD_INPUT, 'sparse_lu: shifted matrix of order '// &
                           to_string(a%n())//' with b of order '//to_string(b%n()))
            return
        end if
        this%ap = int(a%row_start - 1, c_int)
        this%ai = int(a%col - 1, c_int)
        this%ax = real(a%val, c_double)
        do i = 1, b%n()
            do k = b%row_start(i), b%row_start(i + 1) - 1
                slot = a%slot(i, b%col(k))
                if (slot == 0) then
                    call stat%fail(STATUS_BAD_INPUT, 'sparse_lu: entry ('//to_string(i)// &
                        ', '//to_string(b%col(k))//') of b is outside the pattern of a')
                    call this%free()
                    return
                end if
                this%ax(slot) = this%ax(slot) - real(sigma*b%val(k), c_double)
            end do
        end do
        call factor_copies(this, stat, ordering, refinement_steps)
    end subroutine lu_factor_shifted

    !> Symbolic and numeric factorization of the copies this%ap, ai, ax.
    subroutine factor_copies(this, stat, ordering, refinement_steps)
        class(lu_t), intent(inout) :: this
        type(status_t), intent(inout) :: stat
        integer, intent(in), optional :: ordering, refinement_steps
        type(c_ptr) :: symbolic
        integer(c_int) :: code, n

        n = int(size(this%ap) - 1, c_int)
        call umfpack_di_defaults(this%control)
        this%control(UMFPACK_PRL + 1) = 0.0_c_double   ! silent: statuses travel up instead
        if (present(refinement_steps)) this%control(UMFPACK_IRSTEP + 1) = &
            real(max(0, refinement_steps), c_double)
        if (present(ordering)) then
            select case (ordering)
            case (LU_ORDERING_DEFAULT, LU_ORDERING_METIS, LU_ORDERING_NATURAL, &
                  LU_ORDERING_CHOLMOD)
                this%control(UMFPACK_ORDERING + 1) = real(ordering, c_double)
            case default
                call stat%fail(STATUS_BAD_INPUT, 'sparse_lu: unknown ordering '// &
                               to_string(ordering))
                call this%free()
                return
            end select
        end if

        ! Our CSR arrays are the CSC arrays of the transpose, so UMFPACK factorizes A'.
        call blas_threads_for(int(n))   ! UMFPACK's frontal matrices run on the BLAS
        symbolic = c_null_ptr
        code = umfpack_di_symbolic(n, n, this%ap, this%ai, this%ax, symbolic, &
                                     this%control, this%info)
        if (code /= UMFPACK_OK) then
            call stat%fail(STATUS_SOLVER, 'sparse_lu: symbolic analysis: '// &
                           umfpack_status_message(code))
            call umfpack_di_free_symbolic(symbolic)
            call this%free()
            return
        end if
        code = umfpack_di_numeric(this%ap, this%ai, this%ax, symbolic, this%numeric, &
                                    this%control, this%info)
        call umfpack_di_free_symbolic(symbolic)
        if (code /= UMFPACK_OK) then
            ! A singular matrix still yields a Numeric object, but its solves divide by zero.
            call fail_umfpack(stat, 'numeric factorization', code)
            call this%free()
            return
        end if
    end subroutine factor_copies

    !> stat for the UMFPACK status `code` of step `what`: STATUS_SINGULAR for a singular
    !> matrix, STATUS_SOLVER for every other failure.
    subroutine fail_umfpack(stat, what, code)
        type(status_t), intent(inout) :: stat
        character(len=*), intent(in) :: what
        integer(c_int), intent(in) :: code
        call stat%fail(merge(STATUS_SINGULAR, STATUS_SOLVER, &
                             code == UMFPACK_WARNING_singular_matrix), &
                       'sparse_lu: '//what//': '//umfpack_status_message(code))
    end subroutine fail_umfpack

    !> Solve A x = b for one right-hand side; A' x = b with `transposed` (the same factors).
    subroutine lu_solve(this, b, x, stat, transposed)
        class(lu_t), intent(inout) :: this
        real(wp), intent(in) :: b(:)
        real(wp), intent(out) :: x(:)
        type(status_t), intent(out) :: stat
        logical, intent(in), optional :: transposed
        integer(c_int) :: code, system
        character(len=80) :: text
        if (.not. c_associated(this%numeric)) then
            call stat%fail(STATUS_BAD_INPUT, &
                           'sparse_lu: solve called before a successful factorization')
            return
        end if
        if (size(b) /= size(this%ap) - 1 .or. size(x) /= size(b)) then
            write (text, '(3(a, i0))') 'size(b) = ', size(b), ', size(x) = ', size(x), &
                ' for n = ', size(this%ap) - 1
            call stat%fail(STATUS_BAD_INPUT, 'sparse_lu: solve: '//trim(text))
            return
        end if
        ! UMFPACK holds the factors of our transpose (CSR read as CSC): A x = b is its
        ! transposed system, UMFPACK_At, and A' x = b is UMFPACK_A.
        system = UMFPACK_At
        if (present(transposed)) then
            if (transposed) system = UMFPACK_A
        end if
        code = umfpack_di_solve(system, this%ap, this%ai, this%ax, x, b, this%numeric, &
                                  this%control, this%info)
        if (code /= UMFPACK_OK) call fail_umfpack(stat, 'solve', code)
    end subroutine lu_solve

    !> Release the Numeric object and the copies. Safe on an unfactored or freed object.
    subroutine lu_free(this)
        class(lu_t), intent(inout) :: this
        if (c_associated(this%numeric)) call umfpack_di_free_numeric(this%numeric)
        this%numeric = c_null_ptr
        if (allocated(this%ap)) deallocate (this%ap)
        if (allocated(this%ai)) deallocate (this%ai)
        if (allocated(this%ax)) deallocate (this%ax)
    end subroutine lu_free

    subroutine lu_finalize(this)
        type(lu_t), intent(inout) :: this
        call this%free()
    end subroutine lu_finalize

    !> UMFPACK's estimate min |U_ii| / max |U_ii| after scaling: tiny values flag a nearly
    !> singular matrix, which shift-invert may use on purpose, so it is not an error here.
    pure real(wp) function lu_rcond(this)
        class(lu_t), intent(in) :: this
        lu_rcond = real(this%info(UMFPACK_RCOND + 1), wp)
    end function lu_rcond

    !> nnz(L) + nnz(U), the diagonal counted once; 0 before a factorization.
    pure real(wp) function lu_factor_nnz(this)
        class(lu_t), intent(in) :: this
        lu_factor_nnz = 0.0_wp
        if (c_associated(this%numeric)) lu_factor_nnz = real(this%info(UMFPACK_LNZ + 1) &
            + this%info(UMFPACK_UNZ + 1) - (size(this%ap) - 1), wp)
    end function lu_factor_nnz

    pure logical function lu_is_factored(this)
        class(lu_t), intent(in) :: this
        lu_is_factored = c_associated(this%numeric)
    end function lu_is_factored
end module sparse_lu
