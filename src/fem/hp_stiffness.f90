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
    use hp_basis, only: hp_triangle_shape, hp_local_count, hp_bubble_count, MAX_HP_DEGREE
    use elasticity, only: lame_coefficients
    use hp_space, only: hp_space_t
    implicit none
    private
    public :: hp_reference_gradients, hp_element_stiffness, hp_element_laplace, &
              condense_interior, assemble_hp_stiffness, hp_stiffness_rules

    integer, parameter :: HP_OK = 0, HP_INVERTED = 1
    public :: HP_OK, HP_INVERTED

contains

    !> The quadrature rules of the stiffness, rules(p) exact to degree 2p: the stiffness of
    !> an affine cell needs 2(p - 1), the mass 2p.
    pure function hp_stiffness_rules(p_max) result(rules)
        integer, intent(in) :: p_max
        type(gauss_rule_t) :: rules(p_max)
        integer :: p
        do p = 1, p_max
            rules(p) = triangle_rule_exact(2*p)
        end do
    end function hp_stiffness_rules

    !> Values and physical gradients of the local functions of the straight triangle xy(:,
    !> 1:3) at the points of `rule`, with the weights times det J; info = HP_INVERTED for a
    !> cell that is clockwise or flat.
    pure subroutine hp_reference_gradients(xy, edge_degree, p, flip, rule, values, grad_x, &
                                           grad_y, weights, info)
        real(wp), intent(in) :: xy(:, :)
        integer, intent(in) :: edge_degree(3), p
        logical, intent(in) :: flip(3)
        type(gauss_rule_t), intent(in) :: rule
        real(wp), allocatable, intent(out) :: values(:, :), grad_x(:, :), grad_y(:, :)  !! (nq, n)
        real(wp), allocatable, intent(out) :: weights(:)   !! (nq)
        integer, intent(out) :: info
        real(wp) :: jacobian(2, 2), det, inverse_t(2, 2)
        real(wp), allocatable :: v(:), g(:, :)
        integer :: n, nq, q

        n = hp_local_count(edge_degree, p)
        nq = rule%n_points()
        jacobian(:, 1) = xy(:, 2) - xy(:, 1)
        jacobian(:, 2) = xy(:, 3) - xy(:, 1)
        det = jacobian(1, 1)*jacobian(2, 2) - jacobian(1, 2)*jacobian(2, 1)
        info = HP_OK
        if (.not. det > 1.0e-14_wp*sum(jacobian**2)) info = HP_INVERTED
        allocate (values(nq, n), grad_x(nq, n), grad_y(nq, n), weights(nq), v(n), g(2, n))
        if (info /= HP_OK) return
        inverse_t = reshape([jacobian(2, 2), -jacobian(1, 2), -jacobian(2, 1), &
                             jacobian(1, 1)], [2, 2])/det
        do q = 1, nq
            call hp_triangle_shape(edge_degree, p, flip, rule%points(:, q), v, g)
            values(q, :) = v
            g = matmul(inverse_t, g)
            grad_x(q, :) = g(1, :)
            grad_y(q, :) = g(2, :)
        end do
        weights = rule%weights*det
    end subroutine hp_reference_gradients

    !> Plane-strain element stiffness of all local functions (interior ones included), in
    !> dof order (x_1, y_1, x_2, y_2, ...).
    pure subroutine hp_element_stiffness(xy, edge_degree, p, flip, rule, young, poisson, ke, &
                                         info)
        real(wp), intent(in) :: xy(:, :)
        integer, intent(in) :: edge_degree(3), p
        logical, intent(in) :: flip(3)
        type(gauss_rule_t), intent(in) :: rule
        real(wp), intent(in) :: young, poisson
        real(wp), allocatable, intent(out) :: ke(:, :)
        integer, intent(out) :: info
        real(wp), allocatable :: values(:, :), gx(:, :), gy(:, :), w(:), sxx(:, :), syy(:, :), &
                                 sxy(:, :)
        real(wp) :: lame_l, shear_g
        integer :: n, q

        call hp_reference_gradients(xy, edge_degree, p, flip, rule, values, gx, gy, w, info)
        n = size(gx, 2)
        allocate (ke(2*n, 2*n), source=0.0_wp)
        if (info /= HP_OK) return
        call lame_coefficients(young, poisson, lame_l, shear_g)
        ! S_xy = Gx' W Gy etc.: three products of (n x nq)(nq x n), BLAS-like matmul
        do q = 1, size(w)
            values(q, :) = w(q)*gx(q, :)   ! (reused as W Gx)
        end do
        sxx = matmul(transpose(values), gx)
        sxy = matmul(transpose(values), gy)
        do q = 1, size(w)
            values(q, :) = w(q)*gy(q, :)
        end do
        syy = matmul(transpose(values), gy)
        ! (a, b) blocks of B_a' D B_b: see elasticity's element_stiffness
        ke(1:2*n:2, 1:2*n:2) = (lame_l + 2.0_wp*shear_g)*sxx + shear_g*syy
        ke(2:2*n:2, 2:2*n:2) = (lame_l + 2.0_wp*shear_g)*syy + shear_g*sxx
        ke(1:2*n:2, 2:2*n:2) = lame_l*sxy + shear_g*transpose(sxy)
        ke(2:2*n:2, 1:2*n:2) = transpose(ke(1:2*n:2, 2:2*n:2))
    end subroutine hp_element_stiffness

    !> Scalar Laplace stiffness int grad u . grad v and mass int u v of all local functions.
    pure subroutine hp_element_laplace(xy, edge_degree, p, flip, rule, ke, me, info)
        real(wp), intent(in) :: xy(:, :)
        integer, intent(in) :: edge_degree(3), p
        logical, intent(in) :: flip(3)
        type(gauss_rule_t), intent(in) :: rule
        real(wp), allocatable, intent(out) :: ke(:, :), me(:, :)
        integer, intent(out) :: info
        real(wp), allocatable :: values(:, :), gx(:, :), gy(:, :), w(:), weighted(:, :)
        integer :: q
        call hp_reference_gradients(xy, edge_degree, p, flip, rule, values, gx, gy, w, info)
        allocate (weighted, mold=gx)
        do q = 1, size(w)
            weighted(q, :) = w(q)*gx(q, :)
        end do
        ke = matmul(transpose(weighted), gx)
        do q = 1, size(w)
            weighted(q, :) = w(q)*gy(q, :)
        end do
        ke = ke + matmul(transpose(weighted), gy)
        do q = 1, size(w)
            weighted(q, :) = w(q)*values(q, :)
        end do
        me = matmul(transpose(weighted), values)
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
        integer :: nc, nb, j, i
        nb = n_interior
        nc = size(ke, 1) - nb
        info = HP_OK
        kc = ke(1:nc, 1:nc)
        if (nb == 0) return
        l = ke(nc + 1:, nc + 1:)
        do j = 1, nb   ! lower Cholesky factor, column by column
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
        x = ke(nc + 1:, 1:nc)   ! X = L^-1 K_bc by forward substitution
        do j = 1, nb
            x(j, :) = (x(j, :) - matmul(l(j, 1:j - 1), x(1:j - 1, :)))/l(j, j)
        end do
        kc = kc - matmul(transpose(x), x)
        do j = 1, nc   ! exactly symmetric
            kc(j + 1:nc, j) = kc(j, j + 1:nc)
        end do
    end subroutine condense_interior

    !> K on the free dofs of `space` (mesh `m`, P1 vertices), interior functions condensed.
    !> Fails with STATUS_MESH naming the first clockwise or flat cell.
    subroutine assemble_hp_stiffness(m, space, young, poisson, k, stat)
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        real(wp), intent(in) :: young, poisson
        type(csr_matrix_t), intent(out) :: k
        type(status_t), intent(out) :: stat
        type(gauss_rule_t), allocatable :: rules(:)
        integer, allocatable :: element_dofs(:, :), dofs(:)
        real(wp), allocatable :: ke(:, :), kc(:, :)
        integer :: c, n_cells, info, p, n_dofs

        n_cells = m%n_cells()
        allocate (element_dofs(space%max_cell_dofs(), n_cells), source=0)
        do c = 1, n_cells
            dofs = space%cell_dofs(c, m%cells(1:3, c))
            element_dofs(1:size(dofs), c) = dofs
        end do
        call csr_from_element_dofs(space%n_free(), element_dofs, k)
        allocate (rules(min(MAX_HP_DEGREE, maxval(space%cell_degree))))
        rules = hp_stiffness_rules(size(rules))
        do c = 1, n_cells
            p = space%cell_degree(c)
            ! stiffness of an affine cell: degree 2(p - 1), the rule of degree p - 1's mass
            call hp_element_stiffness(m%coords(:, m%cells(1:3, c)), &
                space%edge_degrees_of(c), p, space%cell_flip(:, c), rules(max(1, p - 1)), &
                young, poisson, ke, info)
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
end module hp_stiffness
