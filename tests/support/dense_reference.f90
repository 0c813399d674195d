! SPDX-License-Identifier: MIT
!> Dense references for the contact tests, formed without the code under test: K^-1 by
!> LAPACK's LU, the p x n rows N and T of the contact (row a holds n, resp. t, at the two
!> dofs of contact node a), and A = (lambda N K^-1 T' - N K^-1 N') M (docs/model.md,
!> section 6) from them.
module dense_reference
    use kinds, only: wp
    use contact_boundary, only: contact_t
    use lapack_interfaces, only: dgetrf, dgetrs
    implicit none
    private
    public :: dense_inverse, dense_solve, contact_rows, dense_reduced_matrix

contains

    !> a^-1 by LU with partial pivoting (a square and non-singular).
    function dense_inverse(a) result(inverse)
        real(wp), intent(in) :: a(:, :)
        real(wp), allocatable :: inverse(:, :)
        integer :: i
        allocate (inverse(size(a, 1), size(a, 1)), source=0.0_wp)
        do i = 1, size(a, 1)
            inverse(i, i) = 1.0_wp
        end do
        call dense_solve(a, inverse, .false.)
    end function dense_inverse

    !> b := a^-1 b, or a^-T b with `transposed`, by LU with partial pivoting.
    subroutine dense_solve(a, b, transposed)
        real(wp), intent(in) :: a(:, :)
        real(wp), intent(inout) :: b(:, :)
        logical, intent(in) :: transposed
        real(wp), allocatable :: lu(:, :)
        integer, allocatable :: pivots(:)
        integer :: n, info
        n = size(a, 1)
        allocate (lu, source=a)
        allocate (pivots(n))
        call dgetrf(n, n, lu, n, pivots, info)
        call dgetrs(merge('T', 'N', transposed), n, size(b, 2), lu, n, pivots, b, n, info)
    end subroutine dense_solve

    !> N and T (p x n_free) of `contact`.
    subroutine contact_rows(contact, n_free, normal_rows, tangent_rows)
        type(contact_t), intent(in) :: contact
        integer, intent(in) :: n_free
        real(wp), allocatable, intent(out) :: normal_rows(:, :), tangent_rows(:, :)
        integer :: a
        allocate (normal_rows(contact%p(), n_free), tangent_rows(contact%p(), n_free), &
                  source=0.0_wp)
        do a = 1, contact%p()
            normal_rows(a, contact%dofs(:, a)) = contact%normal
            tangent_rows(a, contact%dofs(:, a)) = contact%tangent
        end do
    end subroutine contact_rows

    !> A = (lambda N K^-1 T' - N K^-1 N') M from the dense K^-1.
    function dense_reduced_matrix(contact, k_inverse, lambda) result(a)
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: k_inverse(:, :), lambda
        real(wp), allocatable :: a(:, :)
        real(wp), allocatable :: normal_rows(:, :), tangent_rows(:, :)
        call contact_rows(contact, size(k_inverse, 1), normal_rows, tangent_rows)
        a = matmul(matmul(normal_rows, k_inverse), transpose(lambda*tangent_rows - &
                   normal_rows))
        a = matmul(a, contact%mass_dense())
    end function dense_reduced_matrix
end module dense_reference
