! SPDX-License-Identifier: MIT
!> The hp element and global stiffness against closed forms and independent computations:
!> the reference integrals of the vertex functions are those of P1 (mass (1/24)(1 + I),
!> constant gradients); an element stiffness holds the rigid motions in its kernel and
!> gives a linear field its exact energy |T| sigma : eps; degree 1 is the P1 element of
!> elasticity; the condensation is the Schur complement LAPACK forms and the recovered
!> interior the minimiser; the global K of degree 1 is assemble_stiffness's P1 K.
program test_hp_stiffness
    use kinds, only: wp
    use status, only: status_t, STATUS_MESH
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use elasticity, only: element_stiffness, lame_coefficients, ELEMENT_OK
    use csr_matrix, only: csr_matrix_t
    use hp_basis, only: hp_bubble_count
    use hp_space, only: hp_space_t, build_hp_space
    use hp_stiffness, only: hp_tables_t, hp_reference_tables, hp_element_stiffness, &
                            hp_element_laplace, condense_interior, recover_interior, &
                            hp_cell_fields, assemble_hp_stiffness, HP_OK, HP_INVERTED
    use lapack_interfaces, only: dgetrf, dgetrs
    use fixtures, only: csr_to_dense
    use testing, only: test_suite_t
    implicit none

    real(wp), parameter :: YOUNG = 2.5_wp, POISSON = 0.3_wp
    !> an anticlockwise triangle of area 0.795, no side along an axis
    real(wp), parameter :: XY(2, 3) = reshape([0.2_wp, 0.1_wp, 1.3_wp, 0.4_wp, 0.5_wp, &
                                               1.2_wp], [2, 3])
    !> the gradient of a linear displacement u = G x
    real(wp), parameter :: G(2, 2) = reshape([0.3_wp, -0.2_wp, 0.5_wp, 0.1_wp], [2, 2])
    type(test_suite_t) :: t
    real(wp) :: area

    t%name = 'test_hp_stiffness'
    area = 0.5_wp*((XY(1, 2) - XY(1, 1))*(XY(2, 3) - XY(2, 1)) - &
                   (XY(2, 2) - XY(2, 1))*(XY(1, 3) - XY(1, 1)))
    call check_tables()
    call check_element()
    call check_laplace()
    call check_condensation()
    call check_global()
    call t%report()

contains

    !> sigma : eps of u = G x, plane strain: L tr(eps)^2 + 2 G_shear eps : eps.
    real(wp) function linear_energy_density()
        real(wp) :: lame_l, shear_g, eps(2, 2)
        call lame_coefficients(YOUNG, POISSON, lame_l, shear_g)
        eps = 0.5_wp*(G + transpose(G))
        linear_energy_density = lame_l*(eps(1, 1) + eps(2, 2))**2 + 2.0_wp*shear_g*sum(eps*eps)
    end function linear_energy_density

    !> The local coefficients (x, y interleaved) of u = G x + shift: vertex functions take
    !> the vertex values, every higher function 0.
    function linear_coefficients(n, corners, shift) result(u)
        integer, intent(in) :: n
        real(wp), intent(in) :: corners(2, 3), shift(2)
        real(wp) :: u(2*n)
        integer :: a
        u = 0.0_wp
        do a = 1, 3
            u(2*a - 1:2*a) = matmul(G, corners(:, a)) + shift
        end do
    end function linear_coefficients

    subroutine check_tables()
        type(hp_tables_t) :: tables
        real(wp) :: p1_mass(3, 3), gradients(2, 3)
        integer :: a, b
        tables = hp_reference_tables([3, 2, 4], 4, [.false., .true., .false.])
        p1_mass = 1.0_wp/24.0_wp
        do a = 1, 3
            p1_mass(a, a) = 2.0_wp/24.0_wp
        end do
        gradients = reshape([-1.0_wp, -1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 3])
        call t%check('reference tables: local functions 3 + (2 + 1 + 3) + 3 interior, the key', &
                     size(tables%r, 1) == 12 .and. all(tables%key == [3, 2, 4, 4, 0, 1, 0]))
        call t%check('vertex functions: the P1 mass (1/24)(1 + I) on the reference triangle', &
                     maxval(abs(tables%r(1:3, 1:3, 4) - p1_mass)) <= 1.0e-15_wp)
        call t%check('vertex functions: constant gradients, int = gradient products / 2', &
                     all([(((abs(tables%r(a, b, 1) - 0.5_wp*gradients(1, a)*gradients(1, b)) &
                     <= 1.0e-15_wp .and. abs(tables%r(a, b, 3) - 0.5_wp*gradients(2, a)* &
                     gradients(2, b)) <= 1.0e-15_wp .and. abs(tables%r(a, b, 2) - 0.5_wp* &
                     gradients(1, a)*gradients(2, b)) <= 1.0e-15_wp), a=1, 3), b=1, 3)]))
        call t%check('mass and the xi-xi, eta-eta integrals symmetric', &
                     maxval(abs(tables%r(:, :, 4) - transpose(tables%r(:, :, 4)))) <= 1.0e-15_wp &
                     .and. maxval(abs(tables%r(:, :, 1) - transpose(tables%r(:, :, 1)))) &
                     <= 1.0e-14_wp)
    end subroutine check_tables

    subroutine check_element()
        type(hp_tables_t) :: tables
        real(wp), allocatable :: ke(:, :)
        real(wp) :: ke_p1(6, 6), u(30), scale, rotation(30)
        integer :: info, a
        tables = hp_reference_tables([4, 4, 4], 4, [.false., .false., .true.])
        call hp_element_stiffness(XY, tables, YOUNG, POISSON, ke, info)
        scale = maxval(abs(ke))
        rotation = 0.0_wp
        do a = 1, 3
            rotation(2*a - 1:2*a) = [-XY(2, a), XY(1, a)]
        end do
        call t%check('p = 4: translations and the rotation in the kernel (to 1e-13 of K)', &
                     info == HP_OK .and. size(ke, 1) == 30 .and. &
                     maxval(abs(matmul(ke, linear_coefficients(15, 0.0_wp*XY, [1.0_wp, &
                     0.0_wp])))) <= 1.0e-13_wp*scale .and. maxval(abs(matmul(ke, &
                     linear_coefficients(15, 0.0_wp*XY, [0.0_wp, 1.0_wp])))) <= &
                     1.0e-13_wp*scale .and. maxval(abs(matmul(ke, rotation))) <= 1.0e-13_wp*scale)
        u = linear_coefficients(15, XY, [0.1_wp, -0.4_wp])
        call t%check_close('p = 4: a linear field''s energy is |T| sigma : eps', &
                           dot_product(u, matmul(ke, u)), area*linear_energy_density(), &
                           1.0e-13_wp)
        tables = hp_reference_tables([1, 1, 1], 1, [.false., .false., .false.])
        call hp_element_stiffness(XY, tables, YOUNG, POISSON, ke, info)
        call element_stiffness(ELEMENT_P1, XY, YOUNG, POISSON, ke_p1, info)
        call t%check('p = 1: the P1 element of elasticity', info == ELEMENT_OK .and. &
                     maxval(abs(ke - ke_p1)) <= 1.0e-14_wp*maxval(abs(ke_p1)))
        call hp_element_stiffness(XY(:, [1, 3, 2]), tables, YOUNG, POISSON, ke, info)
        call t%check('a clockwise triangle is HP_INVERTED', info == HP_INVERTED)
    end subroutine check_element

    subroutine check_laplace()
        type(hp_tables_t) :: tables
        real(wp), allocatable :: ke(:, :), me(:, :)
        real(wp) :: ones(10)
        integer :: info
        tables = hp_reference_tables([3, 3, 3], 3, [.false., .false., .false.])
        call hp_element_laplace(XY, tables, ke, me, info)
        ones = 0.0_wp
        ones(1:3) = 1.0_wp   ! the constant: the vertex functions sum to one
        call t%check('Laplace: constants in the kernel, the mass of 1 is the area', &
                     info == HP_OK .and. maxval(abs(matmul(ke, ones))) <= &
                     1.0e-13_wp*maxval(abs(ke)) .and. &
                     abs(dot_product(ones, matmul(me, ones)) - area) <= 1.0e-14_wp)
    end subroutine check_laplace

    !> The condensed matrix against LAPACK's Schur complement; the recovered interior
    !> zeroes the interior rows of K u.
    subroutine check_condensation()
        type(hp_tables_t) :: tables
        real(wp), allocatable :: ke(:, :), kc(:, :), kbb(:, :), x(:, :), ub(:, :), uc(:, :)
        integer, allocatable :: pivots(:)
        integer :: info, nb, nc, j
        tables = hp_reference_tables([4, 3, 4], 5, [.true., .false., .false.])
        call hp_element_stiffness(XY, tables, YOUNG, POISSON, ke, info)
        nb = 2*hp_bubble_count(5)
        nc = size(ke, 1) - nb
        call condense_interior(ke, nb, kc, info)
        allocate (kbb, source=ke(nc + 1:, nc + 1:))
        allocate (x, source=ke(nc + 1:, 1:nc))
        allocate (pivots(nb))
        call dgetrf(nb, nb, kbb, nb, pivots, info)
        call dgetrs('N', nb, nc, kbb, nb, pivots, x, nb, info)   ! X = K_bb^-1 K_bc
        call t%check('condense_interior: K_cc - K_cb K_bb^-1 K_bc (to 1e-11 of K)', &
                     info == 0 .and. size(kc, 1) == nc .and. maxval(abs(kc - (ke(1:nc, 1:nc) &
                     - matmul(ke(1:nc, nc + 1:), x)))) <= 1.0e-11_wp*maxval(abs(ke)))
        allocate (uc(nc, 2))
        uc(:, 1) = [(sin(real(j, wp)), j=1, nc)]
        uc(:, 2) = [(cos(real(3*j, wp)), j=1, nc)]
        call recover_interior(ke, nb, uc, ub, info)
        call t%check('recover_interior: K_bc u_c + K_bb u_b = 0 (to 1e-12 of K u)', &
                     info == HP_OK .and. maxval(abs(matmul(ke(nc + 1:, 1:nc), uc) + &
                     matmul(ke(nc + 1:, nc + 1:), ub))) <= 1.0e-12_wp*maxval(abs(ke))* &
                     maxval(abs(uc)))
    end subroutine check_condensation

    subroutine check_global()
        type(mesh_t) :: m
        type(hp_space_t) :: space
        type(dof_map_t) :: dofs
        type(csr_matrix_t) :: k_hp, k_p1
        type(status_t) :: stat
        type(hp_tables_t), allocatable :: tables(:)
        real(wp), allocatable :: field(:, :), coefficients(:, :), u(:)
        integer :: c, n_tables, table, node
        call structured_rectangle(1.0_wp, 0.8_wp, 3, 2, ELEMENT_P1, 'right', m, stat)
        call build_hp_space(m, [(1, c=1, m%n_cells())], [m%part_index('top')], space, stat)
        call assemble_hp_stiffness(m, space, YOUNG, POISSON, k_hp, stat)
        call build_dof_map(m, [m%part_index('top')], dofs, stat)
        call assemble_stiffness(m, dofs, YOUNG, POISSON, k_p1, stat)
        call t%check('degree 1 everywhere: K is the P1 K, same numbering', stat%ok() .and. &
                     k_hp%n() == k_p1%n() .and. maxval(abs(csr_to_dense(k_hp) - &
                     csr_to_dense(k_p1))) <= 1.0e-14_wp*maxval(abs(k_p1%val)))

        ! degrees 2 to 4, nothing clamped: a linear field has the energy of the rectangle
        call build_hp_space(m, [(2 + mod(c, 3), c=1, m%n_cells())], [integer ::], space, stat)
        call assemble_hp_stiffness(m, space, YOUNG, POISSON, k_hp, stat)
        allocate (u(space%n_free()), source=0.0_wp)
        do node = 1, m%n_nodes()
            u(2*node - 1:2*node) = matmul(G, m%coords(:, node))
        end do
        call t%check_close('degrees 2 to 4: a linear field''s energy is the area times '// &
                           'sigma : eps', dot_product(u, matmul(csr_to_dense(k_hp), u)), &
                           0.8_wp*linear_energy_density(), 1.0e-13_wp)
        allocate (field(space%n_free(), 1))
        field(:, 1) = u
        allocate (tables(0))
        n_tables = 0
        call hp_cell_fields(m, space, 1, YOUNG, POISSON, field, tables, n_tables, &
                            coefficients, table, stat)
        call t%check('hp_cell_fields: a linear field has its vertex values and no interior '// &
                     'part', stat%ok() .and. n_tables == 1 .and. table == 1 .and. &
                     maxval(abs(coefficients(1:6, 1) - [(matmul(G, m%coords(:, &
                     m%cells(c, 1))), c=1, 3)])) <= 1.0e-15_wp .and. &
                     maxval(abs(coefficients(7:, 1))) <= 1.0e-13_wp)
        m%cells(:, 2) = m%cells([1, 3, 2], 2)
        call assemble_hp_stiffness(m, space, YOUNG, POISSON, k_hp, stat)
        call t%check('a clockwise cell fails with STATUS_MESH naming it', &
                     stat%code == STATUS_MESH .and. index(stat%message, 'cell 2') > 0)
    end subroutine check_global
end program test_hp_stiffness
