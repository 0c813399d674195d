! SPDX-License-Identifier: MIT
!> The BLAS this run uses, as summary.json records it: the BLAS decides the speed of the
!> factorization by a factor of about 5 (reference BLAS against OpenBLAS).
module blas_info
    use iso_c_binding, only: c_char, c_int, c_null_char
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
    !> OpenBLAS's configuration ('' for another BLAS); `threads`: OpenBLAS's thread count,
    !> 1 for another BLAS.
    subroutine blas_in_use(library, config, threads)
        character(len=:), allocatable, intent(out) :: library, config
        integer, intent(out) :: threads
        character(kind=c_char) :: library_c(TEXT_CAPACITY), config_c(TEXT_CAPACITY)
        integer(c_int) :: threads_c
        call nceig_blas_info(library_c, TEXT_CAPACITY, config_c, TEXT_CAPACITY, threads_c)
        library = from_c(library_c)
        config = from_c(config_c)
        threads = int(threads_c)
    end subroutine blas_in_use

    pure function from_c(text) result(s)
        character(kind=c_char), intent(in) :: text(:)
        character(len=:), allocatable :: s
        integer :: i, n
        n = 0
        do i = 1, size(text)
            if (text(i) == c_null_char) exit
            n = i
        end do
        allocate (character(len=n) :: s)
        do i = 1, n
            s(i:i) = text(i)
        end do
    end function from_c
end module blas_info
