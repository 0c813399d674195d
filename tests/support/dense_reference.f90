! SPDX-License-Identifier: MIT
!> Dense references for the contact tests, formed without the code under test: K^-1 by
!> LAPACK's LU, the p x n rows N and T of the contact (row a holds n, resp. t, at the two
!> dofs of contact node a), and A = (lambda N K^-1 T' - N K^-1 N') M (docs/model.md,
!> section 6) from them; and the tiny scene they are formed on.
module dense_reference
    use kinds, only: wp
    use status, only: status_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P2
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use csr_matrix, only: csr_matrix_t
    use contact_boundary, only: contact_t, build_contact, assemble_b
    use lapack_interfaces, only: dgetrf, dgetrs
    implicit none
    private
    public :: dense_inverse, dense_solve, contact_rows, dense_reduced_matrix, tiny_scene

contains

    !> The reference scene (unit square, E = 1, nu = 0.3, top clamped, contact on the
    !> bottom) on 3 x 3 squares of P2 triangles: 84 free dofs, 7 contact nodes; K and B at
    !> `lambda`.
    subroutine tiny_scene(lambda, m, dofs, contact, k, b, stat)
        real(wp), intent(in) :: lambda
        type(mesh_t), intent(out) :: m
        type(dof_map_t), intent(out) :: dofs
        type(contact_t), intent(out) :: contact
        type(csr_matrix_t), intent(out) :: k, b
        type(status_t), intent(out) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, 3, 3, ELEMENT_P2, 'right', m, stat)
        if (stat%ok()) call build_dof_map(m, [m%part_index('top')], dofs, stat)
        if (stat%ok()) call build_contact(m, m%part_index('bottom'), dofs, contact, stat)
        if (stat%ok()) call assemble_stiffness(m, dofs, 1.0_wp, 0.3_wp, k, stat)
        if (stat%ok()) call assemble_b(contact, dofs%n_free, lambda, b, stat)
    end subroutine tiny_scene

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
