! SPDX-License-Identifier: MIT
!> Sparse Cholesky factorization A = P' L L' P of a symmetric positive definite CSR matrix,
!> through CHOLMOD behind the flat C shim `cholmod_shim.c`. The shim runs CHOLMOD's
!> long-index API: every index and count crosses as integer(c_int64_t), so a factor may hold
!> more than 2^31 entries (the matrix itself, a CSR of default integers, stays below).
!>
!> A `cholesky_t` owns a C handle. It frees itself when it goes out of scope (final) and
!> `free` may be called any number of times, but it must not be copied: an assigned copy
!> would share the handle. Pass it by reference or keep it in one place.
module sparse_cholesky
    use, intrinsic :: iso_c_binding, only: c_int, c_int64_t, c_double, c_ptr, c_null_ptr, &
                                           c_loc, c_associated
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_SINGULAR, STATUS_SOLVER
    use csr_matrix, only: csr_matrix_t
    use strings, only: to_string, short_real_text
    use blas_threads, only: blas_threads_for
    implicit none
    private
    public :: cholmod_status_message
    public :: ORDERING_DEFAULT, ORDERING_AMD, ORDERING_METIS, ORDERING_NATURAL, ORDERING_GIVEN

    !> Fill-reducing orderings; the values are those of the shim's `ordering` argument.
    integer, parameter :: ORDERING_DEFAULT = 0   !! CHOLMOD's choice: AMD, METIS if fill is high
    integer, parameter :: ORDERING_AMD = 1
    integer, parameter :: ORDERING_METIS = 2
    integer, parameter :: ORDERING_NATURAL = 3
    integer, parameter :: ORDERING_GIVEN = 4     !! the caller's `permutation`

    ! Return codes of the shim (see cholmod_shim.c).
    integer, parameter :: SHIM_OK = 0
    integer, parameter :: SHIM_NOT_POSDEF = 1
    integer, parameter :: SHIM_SINGULAR = 2
    integer, parameter :: SHIM_OUT_OF_MEMORY = 3
    integer, parameter :: SHIM_TOO_LARGE = 4
    integer, parameter :: SHIM_INVALID = 5
    integer, parameter :: SHIM_NOT_FACTORED = 6
    integer, parameter :: SHIM_FAILED = 7

    ! CHOLMOD's names for the ordering it used (cholmod_core.h).
    integer, parameter :: CHOLMOD_NATURAL = 0, CHOLMOD_GIVEN = 1, CHOLMOD_AMD = 2, &
                          CHOLMOD_METIS = 3, CHOLMOD_POSTORDERED = 6

    integer, parameter :: INFO_SIZE = 5   !! nnz(L), flops, ordering, failed column, rcond

    !> Cholesky factor of a symmetric positive definite matrix, owned through a C handle.
    type, public :: cholesky_t
        private
        type(c_ptr) :: handle = c_null_ptr
        integer :: n = 0
        real(c_double) :: info(INFO_SIZE) = 0.0_c_double
    contains
        procedure :: factor => cholesky_factor
        procedure :: solve => cholesky_solve
        procedure :: forward => cholesky_forward
        procedure :: backward => cholesky_backward
        procedure :: free => cholesky_free
        procedure :: factor_nnz => cholesky_factor_nnz
        procedure :: flops => cholesky_flops
        procedure :: ordering_used => cholesky_ordering_used
        procedure :: rcond => cholesky_rcond
        procedure :: is_factored => cholesky_is_factored
        procedure :: trailing_block => cholesky_trailing_block
        final :: cholesky_finalize
    end type cholesky_t

    interface
        function nceig_cholmod_factor(n, row_start0, col0, val, ordering, perm0, keep_last, &
                                      handle, info) bind(C, name='nceig_cholmod_factor') &
                result(code)
            import :: c_int, c_int64_t, c_double, c_ptr
            integer(c_int64_t), value :: n
            integer(c_int64_t), intent(in) :: row_start0(*), col0(*)   ! 0-based copies
            real(c_double), intent(in) :: val(*)
            integer(c_int), value :: ordering
            type(c_ptr), value :: perm0                      ! const int64_t *, may be NULL
            integer(c_int64_t), value :: keep_last           ! last pivots kept last
            type(c_ptr), intent(out) :: handle                     ! void **
            real(c_double), intent(out) :: info(*)
            integer(c_int) :: code
        end function nceig_cholmod_factor

        function nceig_cholmod_solve(handle, nrhs, b, x) &
                bind(C, name='nceig_cholmod_solve') result(code)
            import :: c_int, c_int64_t, c_double, c_ptr
            type(c_ptr), value :: handle
            integer(c_int64_t), value :: nrhs
            real(c_double), intent(in) :: b(*)
            real(c_double), intent(out) :: x(*)
            integer(c_int) :: code
        end function nceig_cholmod_solve

        function nceig_cholmod_forward(handle, nrhs, b, w) &
                bind(C, name='nceig_cholmod_forward') result(code)
            import :: c_int, c_int64_t, c_double, c_ptr
            type(c_ptr), value :: handle
            integer(c_int64_t), value :: nrhs
            real(c_double), intent(in) :: b(*)
            real(c_double), intent(out) :: w(*)
            integer(c_int) :: code
        end function nceig_cholmod_forward

        function nceig_cholmod_backward(handle, nrhs, w, x) &
                bind(C, name='nceig_cholmod_backward') result(code)
            import :: c_int, c_int64_t, c_double, c_ptr
            type(c_ptr), value :: handle
            integer(c_int64_t), value :: nrhs
            real(c_double), intent(in) :: w(*)
            real(c_double), intent(out) :: x(*)
            integer(c_int) :: code
        end function nceig_cholmod_backward

        function nceig_cholmod_trailing(handle, m, out, perm_tail) &
                bind(C, name='nceig_cholmod_trailing') result(code)
            import :: c_int, c_int64_t, c_double, c_ptr
            type(c_ptr), value :: handle
            integer(c_int64_t), value :: m
            real(c_double), intent(out) :: out(*)
            integer(c_int64_t), intent(out) :: perm_tail(*)        ! 0-based rows of A
            integer(c_int) :: code
        end function nceig_cholmod_trailing

        subroutine nceig_cholmod_free(handle) bind(C, name='nceig_cholmod_free')
            import :: c_ptr
            type(c_ptr), intent(inout) :: handle                   ! void **
        end subroutine nceig_cholmod_free
    end interface

contains

    !> Analyse and factorize the symmetric positive definite matrix `a` (full pattern, only
    !> its upper triangle is read). A previous factor is freed first. `ordering` is one of
    !> the ORDERING_* constants (default ORDERING_DEFAULT); ORDERING_GIVEN needs
    !> `permutation`, 1-based: row/column permutation(k) of A becomes the k-th pivot; with
    !> `keep_last` its last keep_last pivots stay the factor's last (CHOLMOD may otherwise
    !> reorder within its elimination tree), so that trailing_block(keep_last) holds them.
    subroutine cholesky_factor(this, a, stat, ordering, permutation, keep_last)
        class(cholesky_t), intent(inout) :: this
        type(csr_matrix_t), intent(in) :: a
        type(status_t), intent(out) :: stat
        integer, intent(in), optional :: ordering
        integer, intent(in), optional :: permutation(:)
        integer, intent(in), optional :: keep_last
        integer(c_int64_t), allocatable :: row_start0(:), col0(:)
        integer(c_int64_t), allocatable, target :: perm0(:)
        type(c_ptr) :: perm_address
        integer :: chosen, code, n, tail
        character(len=32) :: text

        call this%free()
        n = a%n()
        chosen = ORDERING_DEFAULT
        if (present(ordering)) chosen = ordering
        if (n < 1) then
            call stat%fail(STATUS_BAD_INPUT, 'sparse_cholesky: the matrix is empty')
            return
        end if
        if (chosen < ORDERING_DEFAULT .or. chosen > ORDERING_GIVEN) then
            call stat%fail(STATUS_BAD_INPUT, 'sparse_cholesky: unknown ordering '// &
                           to_string(chosen))
            return
        end if
        perm_address = c_null_ptr
        if (chosen == ORDERING_GIVEN) then
            if (.not. present(permutation)) then
                call stat%fail(STATUS_BAD_INPUT, &
                    'sparse_cholesky: ORDERING_GIVEN requires a permutation')
                return
            end if
            if (size(permutation) /= n) then
                write (text, '(i0, a, i0)') size(permutation), ' for n = ', n
                call stat%fail(STATUS_BAD_INPUT, &
                    'sparse_cholesky: permutation has length '//trim(text))
                return
            end if
            perm0 = int(permutation, c_int64_t) - 1_c_int64_t
            perm_address = c_loc(perm0)
        end if

        ! CHOLMOD wants 0-based indices; the caller's CSR stays as it is.
        row_start0 = int(a%row_start, c_int64_t) - 1_c_int64_t
        col0 = int(a%col, c_int64_t) - 1_c_int64_t
        tail = 0
        if (present(keep_last)) tail = max(0, min(keep_last, n))
        call blas_threads_for(n)   ! CHOLMOD's supernodes run on the BLAS
        code = nceig_cholmod_factor(int(n, c_int64_t), row_start0, col0, a%val, &
                                    int(chosen, c_int), perm_address, int(tail, c_int64_t), &
                                    this%handle, this%info)
        if (code /= SHIM_OK) then
            this%handle = c_null_ptr
            call stat%fail(status_code(code), cholmod_status_message(code, &
                column=nint(this%info(4)) + 1, rcond=real(this%info(5), wp)))
            return
        end if
        this%n = n
    end subroutine cholesky_factor

    !> Solve A X = B for the n x nrhs right-hand sides in the columns of `b`.
    subroutine cholesky_solve(this, b, x, stat)
        class(cholesky_t), intent(in) :: this
        real(wp), intent(in) :: b(:, :)
        real(wp), intent(out) :: x(:, :)
        type(status_t), intent(out) :: stat
        integer :: code
        if (.not. shapes_fit(this, b, x, 'solve', stat)) return
        code = nceig_cholmod_solve(this%handle, int(size(b, 2), c_int64_t), b, x)
        if (code /= SHIM_OK) call stat%fail(status_code(code), cholmod_status_message(code))
    end subroutine cholesky_solve

    !> W = L^{-1} P B, so that B1' A^{-1} B2 = W1' W2: small dense blocks N K^{-1} T' then
    !> cost one forward substitution per column instead of a full solve.
    subroutine cholesky_forward(this, b, w, stat)
        class(cholesky_t), intent(in) :: this
        real(wp), intent(in) :: b(:, :)
        real(wp), intent(out) :: w(:, :)
        type(status_t), intent(out) :: stat
        integer :: code
        if (.not. shapes_fit(this, b, w, 'forward', stat)) return
        code = nceig_cholmod_forward(this%handle, int(size(b, 2), c_int64_t), b, w)
        if (code /= SHIM_OK) call stat%fail(status_code(code), cholmod_status_message(code))
    end subroutine cholesky_forward

    !> X = P' L^{-T} W, the second half of a solve: with W = L^{-1} P B it gives A^{-1} B. For
    !> B supported on the unknowns pivoted last, W is zero but for its trailing rows, which the
    !> trailing block gives (trailing_block): then a solve costs one pass over L, not two.
    subroutine cholesky_backward(this, w, x, stat)
        class(cholesky_t), intent(in) :: this
        real(wp), intent(in) :: w(:, :)
        real(wp), intent(out) :: x(:, :)
        type(status_t), intent(out) :: stat
        integer :: code
        if (.not. shapes_fit(this, w, x, 'backward', stat)) return
        code = nceig_cholmod_backward(this%handle, int(size(w, 2), c_int64_t), w, x)
        if (code /= SHIM_OK) call stat%fail(status_code(code), cholmod_status_message(code))
    end subroutine cholesky_backward

    !> Release the factor. Safe to call on an object never factored or already freed.
    subroutine cholesky_free(this)
        class(cholesky_t), intent(inout) :: this
        call nceig_cholmod_free(this%handle)
        this%handle = c_null_ptr
        this%n = 0
        this%info = 0.0_c_double
    end subroutine cholesky_free

    subroutine cholesky_finalize(this)
        type(cholesky_t), intent(inout) :: this
        call this%free()
    end subroutine cholesky_finalize

    !> Nonzeros of L (without supernodal padding), 0 before a successful factorization.
    pure integer(i8) function cholesky_factor_nnz(this)
        class(cholesky_t), intent(in) :: this
        cholesky_factor_nnz = nint(this%info(1), i8)
    end function cholesky_factor_nnz

    !> Floating-point operations of the numeric factorization, as counted by CHOLMOD.
    pure real(wp) function cholesky_flops(this)
        class(cholesky_t), intent(in) :: this
        cholesky_flops = real(this%info(2), wp)
    end function cholesky_flops

    !> The ordering CHOLMOD actually used, as an ORDERING_* constant (never ORDERING_DEFAULT;
    !> a postordered natural ordering counts as natural), or -1 when not factored.
    pure integer function cholesky_ordering_used(this)
        class(cholesky_t), intent(in) :: this
        if (.not. c_associated(this%handle)) then
            cholesky_ordering_used = -1
            return
        end if
        select case (nint(this%info(3)))
        case (CHOLMOD_NATURAL, CHOLMOD_POSTORDERED)
            cholesky_ordering_used = ORDERING_NATURAL
        case (CHOLMOD_GIVEN)
            cholesky_ordering_used = ORDERING_GIVEN
        case (CHOLMOD_AMD)
            cholesky_ordering_used = ORDERING_AMD
        case (CHOLMOD_METIS)
            cholesky_ordering_used = ORDERING_METIS
        case default
            cholesky_ordering_used = -1
        end select
    end function cholesky_ordering_used

    !> CHOLMOD's cheap condition estimate (min L_jj / max L_jj)^2: an upper bound on
    !> 1/cond_2(A), often far above it. Useful only to spot near-singularity.
    pure real(wp) function cholesky_rcond(this)
        class(cholesky_t), intent(in) :: this
        cholesky_rcond = real(this%info(5), wp)
    end function cholesky_rcond

    pure logical function cholesky_is_factored(this)
        class(cholesky_t), intent(in) :: this
        cholesky_is_factored = c_associated(this%handle)
    end function cholesky_is_factored

    !> The last m rows and columns of L as a dense lower triangle `l_tail` (m x m), and the
    !> rows of A pivoted there (`rows`, 1-based, in pivot order). If those m unknowns were
    !> ordered last, L_tail L_tail' is the Schur complement of A onto them, so A^{-1}
    !> restricted to them is L_tail^{-T} L_tail^{-1}, at a cost independent of n.
    subroutine cholesky_trailing_block(this, m, l_tail, rows, stat)
        class(cholesky_t), intent(in) :: this
        integer, intent(in) :: m
        real(wp), allocatable, intent(out) :: l_tail(:, :)
        integer, allocatable, intent(out) :: rows(:)
        type(status_t), intent(out) :: stat
        integer(c_int64_t), allocatable :: rows0(:)
        integer :: code, ierr
        if (.not. c_associated(this%handle)) then
            call stat%fail(STATUS_BAD_INPUT, &
                'sparse_cholesky: trailing_block called before a successful factorization')
            return
        end if
        if (m < 1 .or. m > this%n) then
            call stat%fail(STATUS_BAD_INPUT, 'sparse_cholesky: trailing_block: m = '// &
                           to_string(m)//' for n = '//to_string(this%n))
            return
        end if
        allocate (l_tail(m, m), rows0(m), stat=ierr)
        if (ierr /= 0) then
            call stat%fail(STATUS_SOLVER, 'sparse_cholesky: trailing_block: cannot allocate '// &
                           'the '//to_string(m)//' x '//to_string(m)//' block: out of memory')
            return
        end if
        code = nceig_cholmod_trailing(this%handle, int(m, c_int64_t), l_tail, rows0)
        if (code /= SHIM_OK) then
            call stat%fail(status_code(code), cholmod_status_message(code))
            return
        end if
        ! allocate, then fill: gfortran 12's reallocation of an unallocated intent(out) array
        ! reads its undefined bounds first, which UBSan reports as an integer overflow
        allocate (rows(m))
        rows(:) = int(rows0 + 1_c_int64_t)
    end subroutine cholesky_trailing_block

    !> A sentence for each code of the shim. `column` (1-based, of A) names where a not
    !> positive definite matrix broke down; `rcond` is the pivot ratio of a singular one.
    pure function cholmod_status_message(code, column, rcond) result(message)
        integer, intent(in) :: code
        integer, intent(in), optional :: column
        real(wp), intent(in), optional :: rcond
        character(len=:), allocatable :: message
        select case (code)
        case (SHIM_OK)
            message = 'CHOLMOD: success'
        case (SHIM_NOT_POSDEF)
            message = 'CHOLMOD: the matrix is not positive definite'
            if (present(column)) then
                message = message//': a pivot <= 0 at row/column '//to_string(column)
            end if
        case (SHIM_SINGULAR)
            message = 'CHOLMOD: the matrix is numerically singular'
            if (present(rcond)) then
                message = message//': pivot ratio (rcond estimate) '// &
                          short_real_text(rcond)// &
                          ' < 1e3 eps'
            end if
        case (SHIM_OUT_OF_MEMORY)
            message = 'CHOLMOD: out of memory'
        case (SHIM_TOO_LARGE)
            message = 'CHOLMOD: the factor is too large (its size overflows CHOLMOD''s '// &
                      'integer arithmetic)'
        case (SHIM_INVALID)
            message = 'CHOLMOD: invalid input (size, ordering or permutation)'
        case (SHIM_NOT_FACTORED)
            message = 'CHOLMOD: solve requested before a successful factorization'
        case (SHIM_FAILED)
            message = 'CHOLMOD: the factorization or solve failed'
        case default
            message = 'CHOLMOD: unknown shim code '//to_string(code)
        end select
    end function cholmod_status_message

    !> The status code a shim code maps to.
    pure integer function status_code(code)
        integer, intent(in) :: code
        select case (code)
        case (SHIM_NOT_POSDEF, SHIM_SINGULAR)
            status_code = STATUS_SINGULAR
        case (SHIM_INVALID, SHIM_NOT_FACTORED)
            status_code = STATUS_BAD_INPUT
        case default
            status_code = STATUS_SOLVER
        end select
    end function status_code

    !> Check that b and its result are n x nrhs before handing raw memory to C.
    logical function shapes_fit(this, b, x, what, stat)
        class(cholesky_t), intent(in) :: this
        real(wp), intent(in) :: b(:, :), x(:, :)
        character(len=*), intent(in) :: what
        type(status_t), intent(inout) :: stat
        character(len=80) :: text
        shapes_fit = .false.
        if (.not. c_associated(this%handle)) then
            call stat%fail(STATUS_BAD_INPUT, 'sparse_cholesky: '//what// &
                           ' called before a successful factorization')
            return
        end if
        if (size(b, 1) /= this%n .or. any(shape(x) /= shape(b))) then
            write (text, '(4(a, i0))') 'b is ', size(b, 1), ' x ', size(b, 2), &
                ', result is ', size(x, 1), ' x ', size(x, 2)
            call stat%fail(STATUS_BAD_INPUT, 'sparse_cholesky: '//what//': '//trim(text)// &
                           ' for n = '//to_string(this%n))
            return
        end if
        shapes_fit = .true.
    end function shapes_fit
end module sparse_cholesky
