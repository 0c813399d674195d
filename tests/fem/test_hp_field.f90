! SPDX-License-Identifier: MIT
!> hp_field and hp_stiffness's recover_interior: the interior coefficients recovered from
!> the condensed ones solve the interior rows of the cell stiffness and give the condensed
!> energy back; an affine displacement, which no interior function changes (K_bc u_c = 0:
!> its stress is constant and the interior functions vanish on the cell's sides), is
!> sampled exactly on the sub-triangulation of a mesh of mixed degrees.
program test_hp_field
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use mesh_structured, only: structured_rectangle
    use hp_basis, only: hp_bubble_count
    use hp_space, only: hp_space_t, build_hp_space
    use hp_stiffness, only: hp_tables_t, hp_reference_tables, hp_element_stiffness, &
                            condense_interior, recover_interior, HP_OK
    use hp_field, only: sample_hp_field
    implicit none
    type(test_suite_t) :: t

    t%name = 'test_hp_field'
    call recovered_interior_solves_its_rows(t)
    call affine_field_is_sampled_exactly(t)
    call t%report()

contains

    !> A degree-6 cell with distinct edge degrees: K_bb u_b + K_bc u_c = 0 to round-off of
    !> the products, and u' K u = u_c' (K_cc - K_cb K_bb^-1 K_bc) u_c (the minimum energy).
    subroutine recovered_interior_solves_its_rows(t)
        type(test_suite_t), intent(inout) :: t
        type(hp_tables_t) :: tables
        real(wp), allocatable :: ke(:, :), kc(:, :), uc(:), ub(:, :), u(:), residual(:)
        real(wp) :: xy(2, 3)
        integer :: info, nb, nc, i
        tables = hp_reference_tables([4, 6, 5], 6, [.false., .true., .false.])
        xy = reshape([0.1_wp, 0.0_wp, 1.3_wp, 0.2_wp, 0.4_wp, 0.9_wp], [2, 3])
        call hp_element_stiffness(xy, tables, 1.0_wp, 0.3_wp, ke, info)
        nb = 2*hp_bubble_count(6)
        nc = size(ke, 1) - nb
        uc = [(sin(real(i, wp)), i=1, nc)]
        call recover_interior(ke, nb, reshape(uc, [nc, 1]), ub, info)
        call t%check('recover: positive definite interior block', info == HP_OK)
        u = [uc, ub(:, 1)]
        residual = matmul(ke(nc + 1:, :), u)
        call t%check('recover: the interior rows of K u vanish', maxval(abs(residual)) <= &
                     1.0e-12_wp*maxval(matmul(abs(ke(nc + 1:, :)), abs(u))))
        call condense_interior(ke, nb, kc, info)
        call t%check_close('recover: the energy is the condensed one', &
                           dot_product(u, matmul(ke, u)), dot_product(uc, matmul(kc, uc)), &
                           1.0e-12_wp)
    end subroutine recovered_interior_solves_its_rows

    !> u = (a + b x + c y, d + e x + f y) on a 3 x 2 mesh with degrees 1 to 6: vertex
    !> coefficients its values, every edge and interior coefficient 0.
    subroutine affine_field_is_sampled_exactly(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m, sub
        type(hp_space_t) :: space
        type(status_t) :: stat
        real(wp), allocatable :: u(:), values(:, :), degree(:)
        integer, allocatable :: degrees(:)
        integer :: v, k, c, expected_cells
        call structured_rectangle(1.5_wp, 1.0_wp, 3, 2, ELEMENT_P1, 'right', m, stat)
        degrees = [(mod(c, 6) + 1, c=1, m%n_cells())]
        call build_hp_space(m, degrees, [integer ::], space, stat)
        call t%check('affine: space built', stat%ok())
        allocate (u(space%n_free()), source=0.0_wp)
        do v = 1, m%n_nodes()
            k = space%free_function(v)
            u(2*k - 1:2*k) = affine(m%coords(:, v))
        end do
        call sample_hp_field(m, space, 1.0_wp, 0.3_wp, u, sub, values, degree, stat)
        call t%check('affine: sampled', stat%ok())
        expected_cells = sum(degrees**2)
        call t%check('affine: p^2 sub-cells per cell', sub%n_cells() == expected_cells .and. &
                     size(degree) == expected_cells)
        call t%check('affine: the sub-cells carry their cell degree', &
                     nint(maxval(degree)) == 6 .and. nint(minval(degree)) == 1)
        do v = 1, sub%n_nodes()
            values(:, v) = values(:, v) - affine(sub%coords(:, v))
        end do
        call t%check('affine: exact at every sub-point', maxval(abs(values)) <= 1.0e-13_wp)
    end subroutine affine_field_is_sampled_exactly

    pure function affine(x) result(u)
        real(wp), intent(in) :: x(2)
        real(wp) :: u(2)
        u = [0.3_wp + 1.1_wp*x(1) - 0.7_wp*x(2), -0.2_wp + 0.4_wp*x(1) + 0.9_wp*x(2)]
    end function affine
end program test_hp_field
