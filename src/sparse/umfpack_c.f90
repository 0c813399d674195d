! SPDX-License-Identifier: MIT
!> Interfaces to the int/double ("di") UMFPACK routines, typed exactly like the C headers
!> of SuiteSparse 5 (umfpack_*.h), the constants of umfpack.h that we use, and a sentence
!> for each of its status codes.
module umfpack_c
    use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr
    use strings, only: to_string
    implicit none
    private
    public :: umfpack_di_symbolic, umfpack_di_numeric, umfpack_di_solve, &
              umfpack_di_free_symbolic, umfpack_di_free_numeric, umfpack_di_defaults
    public :: UMFPACK_CONTROL, UMFPACK_INFO, UMFPACK_A, UMFPACK_At
    public :: UMFPACK_PRL, UMFPACK_ORDERING, UMFPACK_STATUS, UMFPACK_LNZ, UMFPACK_UNZ, &
              UMFPACK_FLOPS, UMFPACK_RCOND, UMFPACK_ORDERING_USED, UMFPACK_IRSTEP
    public :: UMFPACK_ORDERING_CHOLMOD, UMFPACK_ORDERING_AMD, UMFPACK_ORDERING_METIS, &
              UMFPACK_ORDERING_NONE
    public :: UMFPACK_OK, UMFPACK_WARNING_singular_matrix, umfpack_status_message

    ! Array sizes. The C arrays are 0-based: Fortran element k + 1 holds C index k.
    integer, parameter :: UMFPACK_CONTROL = 20
    integer, parameter :: UMFPACK_INFO = 90

    ! Systems for umfpack_di_solve.
    integer(c_int), parameter :: UMFPACK_A = 0    !! A x = b
    integer(c_int), parameter :: UMFPACK_At = 1   !! A' x = b

    ! C indices into Control and Info (add 1 in Fortran).
    integer, parameter :: UMFPACK_PRL = 0            !! Control: print level
    integer, parameter :: UMFPACK_ORDERING = 10      !! Control: fill-reducing ordering
    integer, parameter :: UMFPACK_IRSTEP = 7         !! Control: iterative refinement steps
    integer, parameter :: UMFPACK_STATUS = 0         !! Info: status of the last call
    integer, parameter :: UMFPACK_ORDERING_USED = 19 !! Info
    integer, parameter :: UMFPACK_FLOPS = 42         !! Info: flops of the numeric phase
    integer, parameter :: UMFPACK_LNZ = 43           !! Info: nnz(L), diagonal included
    integer, parameter :: UMFPACK_UNZ = 44           !! Info: nnz(U), diagonal included
    integer, parameter :: UMFPACK_RCOND = 67         !! Info: min |U_ii| / max |U_ii|

    ! Values of Control(UMFPACK_ORDERING) and Info(UMFPACK_ORDERING_USED).
    integer, parameter :: UMFPACK_ORDERING_CHOLMOD = 0   !! AMD/COLAMD, then METIS
    integer, parameter :: UMFPACK_ORDERING_AMD = 1       !! the default: AMD or COLAMD
    integer, parameter :: UMFPACK_ORDERING_METIS = 3
    integer, parameter :: UMFPACK_ORDERING_NONE = 5

    ! Status codes: > 0 warnings (the object was created), < 0 errors.
    integer(c_int), parameter :: UMFPACK_OK = 0
    integer(c_int), parameter :: UMFPACK_WARNING_singular_matrix = 1
    integer(c_int), parameter :: UMFPACK_WARNING_determinant_underflow = 2
    integer(c_int), parameter :: UMFPACK_WARNING_determinant_overflow = 3
    integer(c_int), parameter :: UMFPACK_ERROR_out_of_memory = -1
    integer(c_int), parameter :: UMFPACK_ERROR_invalid_Numeric_object = -3
    integer(c_int), parameter :: UMFPACK_ERROR_invalid_Symbolic_object = -4
    integer(c_int), parameter :: UMFPACK_ERROR_argument_missing = -5
    integer(c_int), parameter :: UMFPACK_ERROR_n_nonpositive = -6
    integer(c_int), parameter :: UMFPACK_ERROR_invalid_matrix = -8
    integer(c_int), parameter :: UMFPACK_ERROR_different_pattern = -11
    integer(c_int), parameter :: UMFPACK_ERROR_invalid_system = -13
    integer(c_int), parameter :: UMFPACK_ERROR_invalid_permutation = -15
    integer(c_int), parameter :: UMFPACK_ERROR_internal_error = -911
    integer(c_int), parameter :: UMFPACK_ERROR_file_IO = -17
    integer(c_int), parameter :: UMFPACK_ERROR_ordering_failed = -18

    interface
        function umfpack_di_symbolic(n_row, n_col, ap, ai, ax, symbolic, control, info) &
                bind(C, name='umfpack_di_symbolic') result(status)
            import :: c_int, c_double, c_ptr
            integer(c_int), value :: n_row, n_col
            integer(c_int), intent(in) :: ap(*), ai(*)
            real(c_double), intent(in) :: ax(*)
            type(c_ptr), intent(out) :: symbolic            ! void **Symbolic
            real(c_double), intent(in) :: control(*)
            real(c_double), intent(out) :: info(*)
            integer(c_int) :: status
        end function umfpack_di_symbolic

        function umfpack_di_numeric(ap, ai, ax, symbolic, numeric, control, info) &
                bind(C, name='umfpack_di_numeric') result(status)
            import :: c_int, c_double, c_ptr
            integer(c_int), intent(in) :: ap(*), ai(*)
            real(c_double), intent(in) :: ax(*)
            type(c_ptr), value :: symbolic                  ! void *Symbolic
            type(c_ptr), intent(out) :: numeric             ! void **Numeric
            real(c_double), intent(in) :: control(*)
            real(c_double), intent(out) :: info(*)
            integer(c_int) :: status
        end function umfpack_di_numeric

        function umfpack_di_solve(sys, ap, ai, ax, x, b, numeric, control, info) &
                bind(C, name='umfpack_di_solve') result(status)
            import :: c_int, c_double, c_ptr
            integer(c_int), value :: sys
            integer(c_int), intent(in) :: ap(*), ai(*)
            real(c_double), intent(in) :: ax(*)
            real(c_double), intent(out) :: x(*)
            real(c_double), intent(in) :: b(*)
            type(c_ptr), value :: numeric                   ! void *Numeric
            real(c_double), intent(in) :: control(*)
            real(c_double), intent(out) :: info(*)
            integer(c_int) :: status
        end function umfpack_di_solve

        subroutine umfpack_di_free_symbolic(symbolic) bind(C, name='umfpack_di_free_symbolic')
            import :: c_ptr
            type(c_ptr), intent(inout) :: symbolic          ! void **Symbolic
        end subroutine umfpack_di_free_symbolic

        subroutine umfpack_di_free_numeric(numeric) bind(C, name='umfpack_di_free_numeric')
            import :: c_ptr
            type(c_ptr), intent(inout) :: numeric           ! void **Numeric
        end subroutine umfpack_di_free_numeric

        subroutine umfpack_di_defaults(control) bind(C, name='umfpack_di_defaults')
            import :: c_double
            real(c_double), intent(out) :: control(*)
        end subroutine umfpack_di_defaults
    end interface

contains

    !> A sentence for each status documented in umfpack.h.
    pure function umfpack_status_message(code) result(message)
        integer, intent(in) :: code
        character(len=:), allocatable :: message
        select case (code)
        case (UMFPACK_OK)
            message = 'UMFPACK: success'
        case (UMFPACK_WARNING_singular_matrix)
            message = 'UMFPACK: the matrix is singular (an exactly zero pivot)'
        case (UMFPACK_WARNING_determinant_underflow)
            message = 'UMFPACK: the determinant underflows'
        case (UMFPACK_WARNING_determinant_overflow)
            message = 'UMFPACK: the determinant overflows'
        case (UMFPACK_ERROR_out_of_memory)
            message = 'UMFPACK: out of memory'
        case (UMFPACK_ERROR_invalid_Numeric_object)
            message = 'UMFPACK: invalid Numeric object'
        case (UMFPACK_ERROR_invalid_Symbolic_object)
            message = 'UMFPACK: invalid Symbolic object'
        case (UMFPACK_ERROR_argument_missing)
            message = 'UMFPACK: a required argument is missing'
        case (UMFPACK_ERROR_n_nonpositive)
            message = 'UMFPACK: the matrix dimension is not positive'
        case (UMFPACK_ERROR_invalid_matrix)
            message = 'UMFPACK: invalid matrix (unsorted, duplicate or out-of-range indices)'
        case (UMFPACK_ERROR_different_pattern)
            message = 'UMFPACK: the pattern changed since the symbolic analysis'
        case (UMFPACK_ERROR_invalid_system)
            message = 'UMFPACK: invalid system requested (or A is not square)'
        case (UMFPACK_ERROR_invalid_permutation)
            message = 'UMFPACK: invalid permutation'
        case (UMFPACK_ERROR_internal_error)
            message = 'UMFPACK: internal error'
        case (UMFPACK_ERROR_file_IO)
            message = 'UMFPACK: file input/output error'
        case (UMFPACK_ERROR_ordering_failed)
            message = 'UMFPACK: the fill-reducing ordering failed'
        case default
            message = 'UMFPACK: unknown status '//to_string(code)
        end select
    end function umfpack_status_message
end module umfpack_c
