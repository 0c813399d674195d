! SPDX-License-Identifier: MIT
!> Element matrices of the hierarchical hp elements (hp_basis) on straight triangles and the
!> assembly of the plane-strain stiffness K on an hp space (hp_space), with the interior
!> (bubble) functions condensed cell by cell: K_cc - K_cb K_bb^-1 K_bc. Condensation is
!> exact for the contact eigenproblem K phi = mu B phi, whose B involves only functions with
!> a trace on Gamma_C, never interior ones: the Schur complement of K onto the contact dofs,
!> hence every mu, is unchanged, and the factor shrinks by the interior dofs (about half of
!> them at degree 8). Material conventions are elasticity.f90's (lame_coefficients).
module hp_stiffness
    use kinds, only: wp
    use status, only: status_t, STATUS_MESH, STATUS_INTERNAL
    use strings, only: to_string
    use mesh, only: mesh_t
    use csr_matrix, only: csr_matrix_t, csr_from_element_dofs
    use gauss_rules, only: gauss_rule_t, triangle_rule_exact
    use hp_basis, only: hp_triangle_shape, hp_local_count, hp_bubble_count
    use elasticity, only: lame_coefficients
    use hp_space, only: hp_space_t
    implicit none
    private
    public :: hp_reference_tables, hp_element_stiffness, hp_element_laplace, &
              condense_interior, recover_interior, hp_cell_fields, assemble_hp_stiffness

    integer, parameter :: HP_OK = 0, HP_INVERTED = 1
    public :: HP_OK, HP_INVERTED

    !> The reference integrals of one cell configuration (edge degrees, interior degree, edge
    !> directions), shared by all cells of that configuration: on an affine cell the physical
    !> gradients are J^-T times the reference ones, so every element matrix is a combination
    !> of these four with the entries of J^-T and det J. A mesh has few configurations (a
    !> degree per layer, eight direction patterns), so the basis is evaluated a few dozen
    !> times instead of once per cell.
    type, public :: hp_tables_t
        integer :: key(7) = 0   !! edge degrees, interior degree, directions (0/1)
        !> (n, n, 4): int d_xi phi_a d_xi phi_b, int d_xi phi_a d_eta phi_b,
        !> int d_eta phi_a d_eta phi_b, int phi_a phi_b over the reference triangle
        real(wp), allocatable :: r(:, :, :)
        !> the rule they were integrated with, and (n, 2 n_points): d_xi phi_a at its
        !> points, then d_eta phi_a, with their absolute values: for forms evaluated point
        !> by point instead of from r (hp_rayleigh)
        type(gauss_rule_t) :: rule
        real(wp), allocatable :: g(:, :), g_abs(:, :)
    end type hp_tables_t

contains

    !> Key of a configuration, for hp_tables_t%key.
    pure function configuration_key(edge_degree, p, flip) result(key)
        integer, intent(in) :: edge_degree(3), p
        logical, intent(in) :: flip(3)
        integer :: key(7)
        key = [edge_degree, p, merge(1, 0, flip)]
    end function configuration_key

    !> The reference integrals of a configuration, by the collapsed Gauss rule exact to
    !> degree 2p (the mass; the stiffness needs 2(p - 1)).
    pure function hp_reference_tables(edge_degree, p, flip) result(tables)
        integer, intent(in) :: edge_degree(3), p
        logical, intent(in) :: flip(3)
        type(hp_tables_t) :: tables
        type(gauss_rule_t) :: rule
        real(wp), allocatable :: v(:, :), gxi(:, :), geta(:, :), weighted(:, :), &
                                 value(:), gradient(:, :)
        integer :: n, q
        tables%key = configuration_key(edge_degree, p, flip)
        rule = triangle_rule_exact(2*p)
        n = hp_local_count(edge_degree, p)
        allocate (v(rule%n_points(), n), gxi(rule%n_points(), n), geta(rule%n_points(), n), &
                  value(n), gradient(2, n))
        do q = 1, rule%n_points()
            call hp_triangle_shape(edge_degree, p, flip, rule%points(:, q), value, gradient)
            v(q, :) = value
            gxi(q, :) = gradient(1, :)
            geta(q, :) = gradient(2, :)
        end do
        allocate (tables%r(n, n, 4))
        ! sourced allocation: the reallocation of the unallocated array read an extent that
        ! -fsanitize=undefined reported as an overflow
        allocate (weighted, source=gxi)
        do q = 1, rule%n_points()
            weighted(q, :) = rule%weights(q)*gxi(q, :)
        end do
        tables%r(:, :, 1) = matmul(transpose(weighted), gxi)
        tables%r(:, :, 2) = matmul(transpose(weighted), geta)
        do q = 1, rule%n_points()
            weighted(q, :) = rule%weights(q)*geta(q, :)
        end do
        tables%r(:, :, 3) = matmul(transpose(weighted), geta)
        do q = 1, rule%n_points()
            weighted(q, :) = rule%weights(q)*v(q, :)
        end do
        tables%r(:, :, 4) = matmul(transpose(weighted), v)
        allocate (tables%g(n, 2*rule%n_points()))
        tables%g(:, 1:rule%n_points()) = transpose(gxi)
        tables%g(:, rule%n_points() + 1:) = transpose(geta)
        tables%g_abs = abs(tables%g)
        tables%rule = rule
    end function hp_reference_tables

    !> J^-T and det J of the straight triangle xy(:, 1:3); info = HP_INVERTED when it is
    !> clockwise or flat (det J not above 1e-14 |J|^2).
    pure subroutine affine_map(xy, inverse_t, det, info)
        real(wp), intent(in) :: xy(:, :)
        real(wp), intent(out) :: inverse_t(2, 2), det
        integer, intent(out) :: info
        real(wp) :: jacobian(2, 2)
        jacobian(:, 1) = xy(:, 2) - xy(:, 1)
        jacobian(:, 2) = xy(:, 3) - xy(:, 1)
        det = jacobian(1, 1)*jacobian(2, 2) - jacobian(1, 2)*jacobian(2, 1)
        info = HP_OK
        inverse_t = 0.0_wp
        if (.not. det > 1.0e-14_wp*sum(jacobian**2)) then
            info = HP_INVERTED
            return
        end if
        inverse_t = reshape([jacobian(2, 2), -jacobian(1, 2), -jacobian(2, 1), &
                             jacobian(1, 1)], [2, 2])/det
    end subroutine affine_map

    !> int (d phi_a/d x_i)(d phi_b/d x_j) over the cell, from the reference integrals: with
    !> C = J^-T, d/dx_i = C(i, 1) d/dxi + C(i, 2) d/deta.
    pure function physical_products(r, c, det, i, j) result(s)
        real(wp), intent(in) :: r(:, :, :), c(2, 2), det
        integer, intent(in) :: i, j
        real(wp) :: s(size(r, 1), size(r, 2))
        s = det*(c(i, 1)*c(j, 1)*r(:, :, 1) + c(i, 1)*c(j, 2)*r(:, :, 2) + &
                 c(i, 2)*c(j, 1)*transpose(r(:, :, 2)) + c(i, 2)*c(j, 2)*r(:, :, 3))
    end function physical_products

    !> Plane-strain element stiffness of all local functions (interior ones included) of the
    !> straight triangle xy(:, 1:3) with the reference integrals `tables` of its
    !> configuration, in dof order (x_1, y_1, x_2, y_2, ...).
    pure subroutine hp_element_stiffness(xy, tables, young, poisson, ke, info)
        real(wp), intent(in) :: xy(:, :)
        type(hp_tables_t), intent(in) :: tables
        real(wp), intent(in) :: young, poisson
        real(wp), allocatable, intent(out) :: ke(:, :)
        integer, intent(out) :: info
        real(wp), allocatable :: sxx(:, :), syy(:, :), sxy(:, :)
        real(wp) :: c(2, 2), det, lame_l, shear_g
        integer :: n
        n = size(tables%r, 1)
        allocate (ke(2*n, 2*n), source=0.0_wp)
        call affine_map(xy, c, det, info)
        if (info /= HP_OK) return
        call lame_coefficients(young, poisson, lame_l, shear_g)
        ! allocated first: as in condense_interior (-fsanitize=undefined saw an overflow in
        ! the extent gfortran computed for the unallocated sxy)
        allocate (sxx(n, n), syy(n, n), sxy(n, n))
        sxx = physical_products(tables%r, c, det, 1, 1)
        syy = physical_products(tables%r, c, det, 2, 2)
        sxy = physical_products(tables%r, c, det, 1, 2)
        ! (a, b) blocks of B_a' D B_b: see elasticity's element_stiffness
        ke(1:2*n:2, 1:2*n:2) = (lame_l + 2.0_wp*shear_g)*sxx + shear_g*syy
        ke(2:2*n:2, 2:2*n:2) = (lame_l + 2.0_wp*shear_g)*syy + shear_g*sxx
        ke(1:2*n:2, 2:2*n:2) = lame_l*sxy + shear_g*transpose(sxy)
        ke(2:2*n:2, 1:2*n:2) = transpose(ke(1:2*n:2, 2:2*n:2))
    end subroutine hp_element_stiffness

    !> Scalar Laplace stiffness int grad u . grad v and mass int u v of all local functions.
    pure subroutine hp_element_laplace(xy, tables, ke, me, info)
        real(wp), intent(in) :: xy(:, :)
        type(hp_tables_t), intent(in) :: tables
        real(wp), allocatable, intent(out) :: ke(:, :), me(:, :)
        integer, intent(out) :: info
        real(wp) :: c(2, 2), det
        call affine_map(xy, c, det, info)
        ke = physical_products(tables%r, c, det, 1, 1) + physical_products(tables%r, c, det, 2, 2)
        me = det*tables%r(:, :, 4)
    end subroutine hp_element_laplace

    !> Static condensation of the last n_interior rows and columns of the symmetric positive
    !> definite `ke`: K_cc - K_cb K_bb^-1 K_bc, by a Cholesky factor of K_bb (its own small
    !> dense one: K_bb is at most 2 x 171 wide at degree 20). info = HP_INVERTED when K_bb
    !> is not positive definite.
    pure subroutine condense_interior(ke, n_interior, kc, info)
        real(wp), intent(in) :: ke(:, :)
        integer, intent(in) :: n_interior
        real(wp), allocatable, intent(out) :: kc(:, :)
        integer, intent(out) :: info
        real(wp), allocatable :: l(:, :), x(:, :)
        integer :: nc, j
        nc = size(ke, 1) - n_interior
        info = HP_OK
        kc = ke(1:nc, 1:nc)
        if (n_interior == 0) return
        call interior_factor(ke(nc + 1:, nc + 1:), l, info)
        if (info /= HP_OK) return
        ! allocated first: assigning to the unallocated x made gfortran compute its extent
        ! from an empty descriptor, which -fsanitize=undefined reports as an overflow
        allocate (x(n_interior, nc))
        x = forward_solve(l, ke(nc + 1:, 1:nc))   ! X = L^-1 K_bc
        kc = kc - matmul(transpose(x), x)
        do j = 1, nc   ! exactly symmetric
            kc(j + 1:nc, j) = kc(j, j + 1:nc)
        end do
    end subroutine condense_interior

    !> The interior coefficients the condensation eliminated, from the others `uc` (one
    !> field per column): u_b = -K_bb^-1 K_bc u_c (the minimiser of the energy with u_c
    !> fixed), the last n_interior rows of `ke` being the interior ones; one factor of K_bb
    !> for all columns. info as condense_interior's.
    pure subroutine recover_interior(ke, n_interior, uc, ub, info)
        real(wp), intent(in) :: ke(:, :), uc(:, :)
        integer, intent(in) :: n_interior
        real(wp), allocatable, intent(out) :: ub(:, :)
        integer, intent(out) :: info
        real(wp), allocatable :: l(:, :), y(:, :)
        integer :: nc, j
        nc = size(ke, 1) - n_interior
        info = HP_OK
        allocate (ub(n_interior, size(uc, 2)))
        if (n_interior == 0) return
        call interior_factor(ke(nc + 1:, nc + 1:), l, info)
        if (info /= HP_OK) return
        allocate (y(n_interior, size(uc, 2)))   ! as in condense_interior
        y = forward_solve(l, -matmul(ke(nc + 1:, 1:nc), uc))
        do j = n_interior, 1, -1   ! back substitution with L'
            ub(j, :) = (y(j, :) - matmul(l(j + 1:, j), ub(j + 1:, :)))/l(j, j)
        end do
    end subroutine recover_interior

    !> The coefficients of all local functions of a cell (its full element stiffness `ke`,
    !> the last n_interior rows interior) for each free-dof field, a column of `fields`:
    !> the condensed ones fields(dofs, :) (0 where dofs, from hp_space%cell_dofs, is 0:
    !> clamped), the interior ones recovered (recover_interior). info as its.
    pure subroutine cell_coefficients(ke, n_interior, dofs, fields, coefficients, info)
        real(wp), intent(in) :: ke(:, :), fields(:, :)
        integer, intent(in) :: n_interior, dofs(:)
        real(wp), allocatable, intent(out) :: coefficients(:, :)
        integer, intent(out) :: info
        real(wp), allocatable :: ub(:, :)
        integer :: n_condensed, i
        n_condensed = size(dofs)
        allocate (coefficients(size(ke, 1), size(fields, 2)), source=0.0_wp)
        do i = 1, n_condensed
            if (dofs(i) > 0) coefficients(i, :) = fields(dofs(i), :)
        end do
        call recover_interior(ke, n_interior, coefficients(1:n_condensed, :), ub, info)
        if (info == HP_OK) coefficients(n_condensed + 1:, :) = ub
    end subroutine cell_coefficients

    !> The lower Cholesky factor of the interior block K_bb, column by column;
    !> info = HP_INVERTED when it is not positive definite.
    pure subroutine interior_factor(kbb, l, info)
        real(wp), intent(in) :: kbb(:, :)
        real(wp), allocatable, intent(out) :: l(:, :)
        integer, intent(out) :: info
        integer :: nb, i, j
        nb = size(kbb, 1)
        info = HP_OK
        l = kbb
        do j = 1, nb
            l(j, j) = l(j, j) - dot_product(l(j, 1:j - 1), l(j, 1:j - 1))
            if (.not. l(j, j) > 0.0_wp) then
                info = HP_INVERTED
                return
            end if
            l(j, j) = sqrt(l(j, j))
            do i = j + 1, nb
                l(i, j) = (l(i, j) - dot_product(l(i, 1:j - 1), l(j, 1:j - 1)))/l(j, j)
            end do
        end do
    end subroutine interior_factor

    !> L^-1 B by forward substitution (L lower triangular).
    pure function forward_solve(l, b) result(x)
        real(wp), intent(in) :: l(:, :), b(:, :)
        real(wp) :: x(size(b, 1), size(b, 2))
        integer :: j
        x = b
        ! the first row apart: gfortran's inlined matmul of the empty row l(1, 1:0) computes
        ! bounds that overflow, which -fsanitize=undefined reports
        if (size(b, 1) > 0) x(1, :) = x(1, :)/l(1, 1)
        do j = 2, size(b, 1)
            x(j, :) = (x(j, :) - matmul(l(j, 1:j - 1), x(1:j - 1, :)))/l(j, j)
        end do
    end function forward_solve

    !> K on the free dofs of `space` (mesh `m`, P1 vertices), interior functions condensed.
    !> Fails with STATUS_MESH naming the first clockwise or flat cell.
    subroutine assemble_hp_stiffness(m, space, young, poisson, k, stat)
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        real(wp), intent(in) :: young, poisson
        type(csr_matrix_t), intent(out) :: k
        type(status_t), intent(out) :: stat
        type(hp_tables_t), allocatable :: tables(:)
        integer, allocatable :: element_dofs(:, :), dofs(:)
        real(wp), allocatable :: ke(:, :), kc(:, :)
        integer :: c, n_cells, info, p, n_dofs, n_tables, t

        n_cells = m%n_cells()
        allocate (element_dofs(space%max_cell_dofs(), n_cells), source=0)
        do c = 1, n_cells
            dofs = space%cell_dofs(c, m%cells(1:3, c))
            element_dofs(1:size(dofs), c) = dofs
        end do
        call csr_from_element_dofs(space%n_free(), element_dofs, k)
        allocate (tables(16))
        n_tables = 0
        do c = 1, n_cells
            p = space%cell_degree(c)
            call hp_cell_stiffness(m, space, c, young, poisson, tables, n_tables, ke, info, t)
            if (info == HP_OK) call condense_interior(ke, 2*hp_bubble_count(p), kc, info)
            if (info /= HP_OK) then
                call stat%fail(STATUS_MESH, 'hp stiffness: cell '//to_string(c)// &
                               ' is clockwise or flat; expected anticlockwise cells')
                return
            end if
            n_dofs = size(kc, 1)
            call k%add_block(element_dofs(1:n_dofs, c), kc, stat)
            if (.not. stat%ok()) then
                stat%code = STATUS_INTERNAL
                return
            end if
        end do

    end subroutine assemble_hp_stiffness

    !> The full element stiffness (interior functions included) of cell c of `space` on the
    !> P1 mesh `m`, its configuration's reference integrals from the cache tables(1:n_tables)
    !> (cached_table). info as hp_element_stiffness's.
    subroutine hp_cell_stiffness(m, space, c, young, poisson, tables, n_tables, ke, info, t)
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        integer, intent(in) :: c
        real(wp), intent(in) :: young, poisson
        type(hp_tables_t), allocatable, intent(inout) :: tables(:)
        integer, intent(inout) :: n_tables
        real(wp), allocatable, intent(out) :: ke(:, :)
        integer, intent(out) :: info
        integer, intent(out) :: t   !! the cell's entry of tables
        t = cached_table(tables, n_tables, configuration_key(space%edge_degrees_of(c), &
                         space%cell_degree(c), space%cell_flip(:, c)))
        call hp_element_stiffness(m%coords(:, m%cells(1:3, c)), tables(t), young, poisson, ke, &
                                  info)
    end subroutine hp_cell_stiffness

    !> The coefficients of all local functions of cell c of `space` on the P1 mesh `m` for
    !> each free-dof field, a column of `fields` (cell_coefficients with the cell's element
    !> stiffness, hp_cell_stiffness), and the cell's entry t of the cache tables. Fails
    !> with STATUS_MESH naming a clockwise or flat cell.
    subroutine hp_cell_fields(m, space, c, young, poisson, fields, tables, n_tables, &
                              coefficients, t, stat)
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        integer, intent(in) :: c
        real(wp), intent(in) :: young, poisson, fields(:, :)
        type(hp_tables_t), allocatable, intent(inout) :: tables(:)
        integer, intent(inout) :: n_tables
        real(wp), allocatable, intent(out) :: coefficients(:, :)
        integer, intent(out) :: t
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: ke(:, :)
        integer :: info
        call hp_cell_stiffness(m, space, c, young, poisson, tables, n_tables, ke, info, t)
        if (info == HP_OK) call cell_coefficients(ke, 2*hp_bubble_count(space%cell_degree(c)), &
            space%cell_dofs(c, m%cells(1:3, c)), fields, coefficients, info)
        if (info /= HP_OK) call stat%fail(STATUS_MESH, 'cell '//to_string(c)// &
                                          ' is clockwise or flat')
    end subroutine hp_cell_fields

    !> Index in tables(1:n_tables) of the configuration `key`, its reference integrals
    !> computed and appended (the array grown) on first use.
    integer function cached_table(tables, n_tables, key) result(t)
        type(hp_tables_t), allocatable, intent(inout) :: tables(:)
        integer, intent(inout) :: n_tables
        integer, intent(in) :: key(7)
        type(hp_tables_t), allocatable :: grown(:)
        do t = 1, n_tables
            if (all(tables(t)%key == key)) return
        end do
        if (.not. allocated(tables)) allocate (tables(16))
        if (n_tables == size(tables)) then
            allocate (grown(max(16, 2*n_tables)))   ! (an empty cache grows too)
            grown(1:n_tables) = tables
            call move_alloc(grown, tables)
        end if
        n_tables = n_tables + 1
        t = n_tables
        tables(n_tables) = hp_reference_tables(key(1:3), key(4), key(5:7) == 1)
    end function cached_table
end module hp_stiffness
