! SPDX-License-Identifier: MIT
!> A goal-oriented (dual-weighted residual) estimate of the error of the lowest positive
!> eigenvalue mu_h, with element indicators.
!>
!> Theory. With a(u, v) = v^T K u, b(u, v) = v^T B u (v the test function) and the residual
!> r_h(v) = mu_h b(phi_h, v) - a(phi_h, v) of the discrete pair, r_h(v_h) = 0 on the discrete
!> space V_h. For a left eigenvector psi (a(v, psi) = mu b(v, psi) for all v) and any v_h,
!>     r_h(psi - v_h) = r_h(psi) = (mu_h - mu) b(phi_h, psi),
!> so mu - mu_h = -r_h(psi - v_h) / b(phi_h, psi) exactly. The estimate takes psi+ from
!> the enriched space V+ (the next element order on the same mesh: P1 -> P2) and v_h =
!> I_h psi+, its interpolant in V_h. psi+ is the exact left eigenvector of the enriched pencil,
!> from its reduced problem (dual_eigen): psi+ = K+^-1 N+' w+. As V_h is in V+ (P1 is in P2,
!> the stiffness and the contact mass of P1 functions are integrated exactly by the P2
!> matrices), the estimate is mu+ - mu_h to round-off (tested): the two-level error, the
!> exact error of mu_h when mu+ is much closer to mu than mu_h is.
!>
!> Indicators: r_h(z), z = psi+ - I_h psi+, is a sum over cells of r_K(z) = mu_h b_K - a_K
!> (a_K the element stiffness, b_K the part of B on the cell's contact edges). eta_K =
!> |r_K(z)| / (|b(phi_h, psi+)| mu_h), so that sum eta_K >= |estimate| / mu_h (triangle
!> inequality), with equality when no cells cancel.
!>
!> Cost: the enriched problem is assembled and factored (about 4 times the dofs of P1), its
!> reduced matrix formed (p+ ~ 2p), one LU of it and one solve: a few times the P1 solve.
!> Computed where an enrichment exists: P1 now (P2 -> P3 needs only enriched_element and
!> enriched_mesh to learn the pair).
module error_estimate
    use kinds, only: wp, N_DIM
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_MESH, STATUS_SOLVER
    use strings, only: to_string
    use timer, only: wall_time, timings_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P2, ELEMENT_P3, ELEMENT_P4, &
                             element_nodes_per_cell, element_name
    use mesh_refine, only: refinable_mesh_t, build_refinable_mesh
    use shape_functions, only: evaluate_shape, reference_nodes, MAX_NODES
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use elasticity, only: stiffness_tables_t, stiffness_tables, element_energy
    use contact_boundary, only: contact_t, build_contact, assemble_b, edge_mass
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness, contact_flexibility, reduced_matrix, &
                                 lambda_unit
    use dual_eigen, only: reduced_left_eigenvector
    use problem, only: problem_t
    implicit none
    private
    public :: error_estimate_t, estimate_lowest_error, enriched_element, enriched_mesh
    public :: ENRICHED_CONTACT_MAX

    !> The largest enriched contact p+ estimated by default: the dense 2p+ x 2p+ inverse of
    !> the contact block (contact_flexibility, 16 p+^3 / 3 flops, 32 p+^2 bytes) stays about a
    !> second and 34 MB; P1 meshes with up to 512 contact cells.
    integer, parameter :: ENRICHED_CONTACT_MAX = 1025

    type, public :: error_estimate_t
        logical :: computed = .false.
        !> (mu+ - mu_h) / mu_h by the weighted residual: the signed relative error estimate
        real(wp) :: relative = 0.0_wp
        real(wp) :: mu_enriched = 0.0_wp         !! mu+, same units as mu_h
        real(wp), allocatable :: indicators(:)   !! (n_cells) eta_K, relative to mu_h
        integer :: element = 0                   !! the enriched element (ELEMENT_P2 for P1)
        real(wp) :: seconds = 0.0_wp             !! wall time of the estimate
        !> why it was not computed when &eigen estimate decided so ('' otherwise)
        character(len=:), allocatable :: skipped
    end type error_estimate_t

contains

    !> The element of the enriched space for `element`, or 0 where there is none yet.
    pure integer function enriched_element(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_P1); enriched_element = ELEMENT_P2
        case (ELEMENT_P2); enriched_element = ELEMENT_P3
        case (ELEMENT_P3); enriched_element = ELEMENT_P4
        case default; enriched_element = 0
        end select
    end function enriched_element

    !> The mesh of `m` with elements `element` on the same cells: cell c keeps its corners in
    !> order, so that cell-local prolongation needs no matching; the nodes of the higher
    !> order sit at their exact lattice points on straight sides (mesh_refine's to_mesh),
    !> boundary edges keep their order and parts.
    subroutine enriched_mesh(m, element, m_plus, stat)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: element
        type(mesh_t), intent(out) :: m_plus
        type(status_t), intent(out) :: stat
        type(refinable_mesh_t) :: corners

        if (enriched_element(m%element) /= element .or. element == 0) then
            call stat%fail(STATUS_BAD_INPUT, 'error estimate: no enrichment from '// &
                           element_name(m%element)//' to '//element_name(element))
            return
        end if
        call build_refinable_mesh(m, corners, stat, keep_corner_order=.true.)
        if (stat%ok()) call corners%to_mesh(element, m_plus, stat)
    end subroutine enriched_mesh

    !> The estimate for the lowest positive eigenpair (mu_h, phi_h) of `prob` at `lambda`:
    !> mu_h in the units of prob%k and prob%contact (before to_input_units), phi_h on
    !> prob%dofs. est%computed stays false (stat ok) where the element has no enrichment or
    !> the enriched contact has more than `max_contact` nodes (its dense p+ x p+ LU).
    subroutine estimate_lowest_error(prob, lambda, mu_h, phi_h, max_contact, est, stat)
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: lambda, mu_h
        real(wp), intent(in) :: phi_h(:)   !! (n_free)
        integer, intent(in) :: max_contact
        type(error_estimate_t), intent(out) :: est
        type(status_t), intent(out) :: stat
        type(mesh_t) :: m_plus
        type(dof_map_t) :: dofs_plus
        type(contact_t) :: contact_plus
        type(csr_matrix_t) :: k_plus, b_plus
        type(cholesky_t) :: chol
        type(timings_t) :: ignored
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), a(:, :), w(:), rhs(:, :), psi(:, :), &
                                 u(:), z(:), b_u(:), k_u(:)
        real(wp) :: start, theta, unit, young, b_phi_psi

        start = wall_time()
        est%element = enriched_element(prob%mesh%element)
        if (est%element == 0) return
        if (.not. mu_h > 0.0_wp) return
        call enriched_mesh(prob%mesh, est%element, m_plus, stat)
        if (.not. stat%ok()) return
        ! the units of prob (see build_problem): sizes / 2^length_exponent, E / 2^young_exponent
        m_plus%coords = scale(m_plus%coords, -prob%length_exponent)
        young = scale(prob%young, -prob%young_exponent)
        call build_dof_map(m_plus, prob%dirichlet_parts, dofs_plus, stat)
        if (stat%ok()) call assemble_stiffness(m_plus, dofs_plus, young, prob%poisson, k_plus, &
                                               stat)
        if (stat%ok()) call build_contact(m_plus, prob%contact_part, dofs_plus, contact_plus, &
                                          stat)
        if (.not. stat%ok()) return
        if (contact_plus%p() > max_contact) then
            est%skipped = 'not computed: the enriched problem has '// &
                to_string(contact_plus%p())//' contact nodes, more than the '// &
                to_string(max_contact)//' its dense reduction takes'
            return
        end if
        call assemble_b(contact_plus, dofs_plus%n_free, lambda, b_plus, stat)
        if (stat%ok()) call factor_stiffness(k_plus, m_plus, dofs_plus, contact_plus, chol, &
                                             ignored, stat)
        if (stat%ok()) call contact_flexibility(chol, contact_plus, kt_nn, kt_nt, stat)
        if (.not. stat%ok()) then
            call chol%free()
            return
        end if
        ! A / lambda_unit, as the dense solver: eigenvalues theta / lambda_unit
        unit = lambda_unit(lambda)
        a = reduced_matrix(kt_nn/unit, kt_nt, contact_plus%mass, lambda/unit)
        deallocate (kt_nn, kt_nt)
        call reduced_left_eigenvector(a, 1.0_wp/(mu_h*unit), w, theta, stat)
        if (.not. stat%ok()) then
            call chol%free()
            return
        end if
        est%mu_enriched = 1.0_wp/(theta*unit)
        ! psi+ = K+^-1 N+' w+ (the factor mu+ only scales it)
        allocate (rhs(dofs_plus%n_free, 1), source=0.0_wp)
        allocate (psi(dofs_plus%n_free, 1))
        call contact_plus%scatter(contact_plus%normal, w, rhs(:, 1))
        call chol%solve(rhs, psi, stat)
        call chol%free()
        if (.not. stat%ok()) return

        u = prolonged(phi_h)
        z = psi(:, 1) - prolonged(interpolant(psi(:, 1)))
        allocate (b_u(size(u)), k_u(size(u)))
        call b_plus%matvec(u, b_u)
        call k_plus%matvec(u, k_u)
        b_phi_psi = dot_product(psi(:, 1), b_u)
        if (.not. abs(b_phi_psi) > 0.0_wp) then
            call stat%fail(STATUS_SOLVER, 'error estimate: b(phi_h, psi+) = 0 (a defective '// &
                           'eigenvalue): no estimate')
            return
        end if
        ! mu - mu_h ~ -r_h(z) / b(phi_h, psi+), r_h(z) = z^T (mu_h B+ u - K+ u)
        est%relative = -(mu_h*dot_product(z, b_u) - dot_product(z, k_u))/(b_phi_psi*mu_h)
        call cell_indicators(est%indicators)
        est%computed = .true.
        est%seconds = wall_time() - start

    contains

        !> The free-dof vector on V+ of a field of V_h (given on prob%dofs): each enriched cell
        !> node gets the coarse cell's interpolation at its reference point.
        function prolonged(x) result(x_plus)
            real(wp), intent(in) :: x(:)
            real(wp), allocatable :: x_plus(:)
            real(wp) :: nodal(N_DIM, prob%mesh%n_nodes()), transfer_matrix(MAX_NODES, MAX_NODES)
            integer :: c, j, n_coarse, n_fine, node
            nodal = prob%dofs%nodal_field(x)
            n_coarse = element_nodes_per_cell(prob%mesh%element)
            n_fine = element_nodes_per_cell(est%element)
            transfer_matrix = coarse_at_fine_nodes()
            allocate (x_plus(dofs_plus%n_free), source=0.0_wp)
            do c = 1, prob%mesh%n_cells()
                do j = 1, n_fine
                    node = m_plus%cells(j, c)
                    associate (values => matmul(nodal(:, prob%mesh%cells(:, c)), &
                                                transfer_matrix(1:n_coarse, j)))
                        if (dofs_plus%free_dof(1, node) > 0) &
                            x_plus(dofs_plus%free_dof(1, node)) = values(1)
                        if (dofs_plus%free_dof(2, node) > 0) &
                            x_plus(dofs_plus%free_dof(2, node)) = values(2)
                    end associate
                end do
            end do
        end function prolonged

        !> (i, j): coarse shape function i at the reference point of enriched node j.
        function coarse_at_fine_nodes() result(t)
            real(wp) :: t(MAX_NODES, MAX_NODES), xi(2, MAX_NODES), gradients(2, MAX_NODES)
            integer :: j
            t = 0.0_wp
            call reference_nodes(est%element, xi)
            do j = 1, element_nodes_per_cell(est%element)
                call evaluate_shape(prob%mesh%element, xi(:, j), t(:, j), gradients)
            end do
        end function coarse_at_fine_nodes

        !> I_h x+ on prob%dofs: the enriched field evaluated at the coarse nodes.
        function interpolant(x_plus) result(x)
            real(wp), intent(in) :: x_plus(:)
            real(wp), allocatable :: x(:)
            real(wp) :: nodal(N_DIM, m_plus%n_nodes()), xi(2, MAX_NODES), &
                        values(MAX_NODES), gradients(2, MAX_NODES), at(2)
            integer :: c, i, n_fine, node
            nodal = dofs_plus%nodal_field(x_plus)
            n_fine = element_nodes_per_cell(est%element)
            call reference_nodes(prob%mesh%element, xi)
            allocate (x(prob%dofs%n_free), source=0.0_wp)
            do c = 1, prob%mesh%n_cells()
                do i = 1, element_nodes_per_cell(prob%mesh%element)
                    node = prob%mesh%cells(i, c)
                    call evaluate_shape(est%element, xi(:, i), values, gradients)
                    at = matmul(nodal(:, m_plus%cells(:, c)), values(1:n_fine))
                    if (prob%dofs%free_dof(1, node) > 0) x(prob%dofs%free_dof(1, node)) = at(1)
                    if (prob%dofs%free_dof(2, node) > 0) x(prob%dofs%free_dof(2, node)) = at(2)
                end do
            end do
        end function interpolant

        !> eta_K = |mu_h b_K(u, z) - a_K(u, z)| / (|b(phi_h, psi+)| mu_h) on the cells of V+.
        subroutine cell_indicators(eta)
            real(wp), allocatable, intent(out) :: eta(:)
            real(wp), allocatable :: u_nodal(:, :), z_nodal(:, :), u_cell(:), z_cell(:), &
                                     xy(:, :), me(:, :), r_cell(:)
            logical, allocatable :: in_contact(:)
            integer, allocatable :: cell_of_node(:)
            type(stiffness_tables_t) :: tables
            integer :: c, j, n_fine, e, i, l, per_edge
            real(wp) :: row_factor(2)

            n_fine = element_nodes_per_cell(est%element)
            ! (allocated first: gfortran 12 warns of an unallocated one at -O3)
            allocate (u_nodal(N_DIM, m_plus%n_nodes()), z_nodal(N_DIM, m_plus%n_nodes()))
            u_nodal = dofs_plus%nodal_field(u)
            z_nodal = dofs_plus%nodal_field(z)
            allocate (u_cell(N_DIM*n_fine), z_cell(N_DIM*n_fine), xy(N_DIM, n_fine))
            allocate (r_cell(m_plus%n_cells()), source=0.0_wp)
            ! the cells of V+ are those of prob%mesh, which the assembly has accepted
            tables = stiffness_tables(est%element)
            do c = 1, m_plus%n_cells()
                do j = 1, n_fine
                    xy(:, j) = m_plus%coords(:, m_plus%cells(j, c))
                    u_cell(N_DIM*j - 1:N_DIM*j) = u_nodal(:, m_plus%cells(j, c))
                    z_cell(N_DIM*j - 1:N_DIM*j) = z_nodal(:, m_plus%cells(j, c))
                end do
                r_cell(c) = -element_energy(tables, xy, young, prob%poisson, u_cell, z_cell)
            end do
            ! the boundary term: the part of B on each contact edge, given to its cell (found
            ! by the edge's first interior node, which belongs to no other cell)
            allocate (in_contact(m_plus%n_nodes()), source=.false.)
            in_contact(contact_plus%nodes) = .true.
            allocate (cell_of_node(m_plus%n_nodes()), source=0)
            do c = 1, m_plus%n_cells()
                cell_of_node(m_plus%cells(4:, c)) = c
            end do
            per_edge = size(m_plus%edges, 1)
            row_factor = lambda*contact_plus%tangent - contact_plus%normal
            do e = 1, size(m_plus%edges, 2)
                if (m_plus%edge_part(e) /= prob%contact_part) cycle
                me = edge_mass(per_edge, norm2(m_plus%coords(:, m_plus%edges(2, e)) - &
                                               m_plus%coords(:, m_plus%edges(1, e))))
                c = cell_of_node(m_plus%edges(3, e))
                do i = 1, per_edge
                    if (.not. in_contact(m_plus%edges(i, e))) cycle
                    do l = 1, per_edge
                        if (.not. in_contact(m_plus%edges(l, e))) cycle
                        r_cell(c) = r_cell(c) + mu_h* &
                            dot_product(row_factor, z_nodal(:, m_plus%edges(i, e)))*me(i, l)* &
                            dot_product(contact_plus%normal, u_nodal(:, m_plus%edges(l, e)))
                    end do
                end do
            end do
            eta = abs(r_cell)/(abs(b_phi_psi)*mu_h)
        end subroutine cell_indicators
    end subroutine estimate_lowest_error
end module error_estimate
