! SPDX-License-Identifier: MIT
!> blas_in_use names the shared object that really provides dgemm (a file that exists, a
!> BLAS by its name), and for OpenBLAS its configuration and a thread count of at least 1.
!> Nothing depends on which BLAS the machine has: each claim is checked against the file
!> system or against the other claims. The program calls dgemm itself, as nceig does: a
!> program that never calls the BLAS has none loaded (the linker drops it), and then no
!> library is named.
program test_blas_info
    use kinds, only: wp
    use lapack_interfaces, only: dgemm
    use blas_info, only: blas_in_use
    use strings, only: lowercase
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t
    character(len=:), allocatable :: library, config
    integer :: threads
    logical :: exists, openblas
    real(wp) :: a(2, 2), c(2, 2)

    t%name = 'test_blas_info'
    a = reshape([1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp], [2, 2])
    c = 0.0_wp
    call dgemm('N', 'N', 2, 2, 2, 1.0_wp, a, 2, a, 2, 0.0_wp, c, 2)
    call t%check('dgemm: A^2 of [1 3; 2 4] is [7 15; 10 22] (small integers: exact)', &
                 all(abs(c - reshape([7.0_wp, 10.0_wp, 15.0_wp, 22.0_wp], [2, 2])) <= 0.0_wp))
    call blas_in_use(library, config, threads)
    inquire (file=library, exist=exists)
    call t%check('the library providing dgemm is a file that exists: '//library, &
                 len(library) > 0 .and. exists)
    call t%check('its name says BLAS (libblas, libopenblas, mkl, blis)', &
                 index(lowercase(library), 'blas') > 0 .or. &
                 index(lowercase(library), 'mkl') > 0 .or. index(lowercase(library), 'blis') > 0)
    openblas = index(lowercase(library), 'openblas') > 0
    call t%check('OpenBLAS has a configuration, another BLAS none: '//config, &
                 openblas .eqv. len(config) > 0)
    call t%check('at least one thread', threads >= 1)
    call t%check('texts without their C terminator', index(library, achar(0)) == 0 .and. &
                 index(config, achar(0)) == 0)
    deallocate (library, config)   ! (AddressSanitizer reports a main program's allocatables)
    call t%report()
end program test_blas_info
