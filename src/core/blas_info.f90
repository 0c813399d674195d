! SPDX-License-Identifier: MIT
!> The BLAS this run uses, as summary.json records it: the BLAS decides the speed of the
!> factorization by a factor of about 5 (reference BLAS against OpenBLAS).
module blas_info
    use iso_c_binding, only: c_char, c_int, c_null_char
    use strings, only: from_c_chars
    implicit none
    private
    public :: blas_in_use

    integer, parameter :: TEXT_CAPACITY = 1024

    interface
        subroutine nceig_blas_info(library, library_capacity, config, config_capacity, &
                                   threads) bind(C, name='nceig_blas_info')
            import :: c_char, c_int
            character(kind=c_char), intent(out) :: library(*), config(*)
            integer(c_int), value :: library_capacity, config_capacity
            integer(c_int), intent(out) :: threads
        end subroutine nceig_blas_info
    end interface

contains

    !> `library`: the path of the library providing dgemm ('' if unknown); `config`:
    !> OpenBLAS's configuration ('' for another BLAS); `threads`: the largest count
    !> blas_threads gave a factorization of this process, else OpenBLAS's thread count (the
    !> environment's), 1 for another BLAS.
    subroutine blas_in_use(library, config, threads)
        character(len=:), allocatable, intent(out) :: library, config
        integer, intent(out) :: threads
        character(kind=c_char) :: library_c(TEXT_CAPACITY), config_c(TEXT_CAPACITY)
        integer(c_int) :: threads_c
        call nceig_blas_info(library_c, TEXT_CAPACITY, config_c, TEXT_CAPACITY, threads_c)
        library = from_c_chars(library_c, index_of_nul(library_c))
        config = from_c_chars(config_c, index_of_nul(config_c))
        threads = int(threads_c)
    end subroutine blas_in_use

    !> The length of a NUL-terminated C string.
    pure integer function index_of_nul(text)
        character(kind=c_char), intent(in) :: text(:)
        index_of_nul = findloc(text, c_null_char, dim=1) - 1
        if (index_of_nul < 0) index_of_nul = size(text)
    end function index_of_nul

end module blas_info
