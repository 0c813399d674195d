! SPDX-License-Identifier: MIT
!> The enriched space of the goal-oriented error estimates: the element one degree higher on
!> the same cells (P1 -> P2, P2 -> P3, P3 -> P4), with its stiffness and contact, the maps
!> between the two spaces, and the cell-wise residual that the estimates weigh.
!>
!> Every estimate here has the same shape. A discrete eigenpair U_h of a problem
!> L(U, V) = s R(U, V) leaves the residual r_h(V) = s_h R(U_h, V) - L(U_h, V), which vanishes
!> on the discrete space. With Z+ the left eigenvector of the enriched problem (eigenvalue
!> s+) and I_h Z+ its interpolant, r_h(Z+ - I_h Z+) = (s_h - s+) R(U_h, Z+): the dual-weighted
!> residual equals the two-level difference s+ - s_h, and its split over the cells is the
!> refinement indicator. For the eigenproblem of mu (error_estimate) and for the threshold
!> pencil (threshold_estimate) the displacement part of r_h is the same:
!>     r_h(z) = int_C g (lambda t - n) . z ds - a(u_h, z),
!> with g the contact pressure the discrete pair puts on Gamma_C (mu_h u_h.n for mu, the
!> pencil's traction for the threshold), so one routine gives the cells' share of both.
module enrichment
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_SINGULAR
    use strings, only: to_string
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P2, ELEMENT_P3, ELEMENT_P4, &
                             element_nodes_per_cell, element_name
    use mesh_refine, only: refinable_mesh_t, build_refinable_mesh
    use shape_functions, only: evaluate_shape, reference_nodes, MAX_NODES
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use elasticity, only: stiffness_tables_t, stiffness_tables, element_energy
    use contact_boundary, only: contact_t, build_contact, edge_mass
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_contact_blocks
    use timer, only: timings_t
    use problem, only: problem_t
    implicit none
    private
    public :: enrichment_t, build_enrichment, enriched_element, enriched_mesh

    !> The problem of `prob` with elements one degree higher on the same cells, in the units
    !> of prob (prob%units).
    type, public :: enrichment_t
        integer :: element = 0
        type(mesh_t) :: mesh
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: k
        real(wp) :: young = 0.0_wp
    contains
        procedure :: prolonged => enrichment_prolonged
        procedure :: interpolant => enrichment_interpolant
        procedure :: cell_residuals => enrichment_cell_residuals
        procedure :: reduce => enrichment_reduce
    end type enrichment_t

contains

    !> The element of the enriched space for `element`, or 0 where there is none.
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

    !> The enriched problem of `prob`: mesh, dofs, K+ and contact. enr%element stays 0 (stat
    !> ok) where prob's element has none; `skipped` says why when the enriched contact has more
    !> than `max_contact` nodes (the estimates reduce it densely), and is '' otherwise.
    subroutine build_enrichment(prob, max_contact, enr, skipped, stat)
        type(problem_t), intent(in) :: prob
        integer, intent(in) :: max_contact
        type(enrichment_t), intent(out) :: enr
        character(len=:), allocatable, intent(out) :: skipped
        type(status_t), intent(out) :: stat

        skipped = ''
        if (enriched_element(prob%mesh%element) == 0) return
        call enriched_mesh(prob%mesh, enriched_element(prob%mesh%element), enr%mesh, stat)
        if (.not. stat%ok()) return
        ! the units of prob (see build_problem)
        enr%mesh%coords = prob%units%scaled_lengths(enr%mesh%coords)
        enr%young = prob%units%scaled_young(prob%young)
        call build_dof_map(enr%mesh, prob%dirichlet_parts, enr%dofs, stat)
        if (stat%ok()) call assemble_stiffness(enr%mesh, enr%dofs, enr%young, prob%poisson, &
                                               enr%k, stat)
        if (stat%ok()) call build_contact(enr%mesh, prob%contact_part, enr%dofs, enr%contact, &
                                          stat)
        if (.not. stat%ok()) return
        if (enr%contact%p() > max_contact) then
            skipped = 'not computed: the enriched problem has '//to_string(enr%contact%p())// &
                ' contact nodes, more than the '//to_string(max_contact)// &
                ' its dense reduction takes'
            return
        end if
        enr%element = enriched_element(prob%mesh%element)
    end subroutine build_enrichment

    !> Factor K+ with its contact dofs last and form its contact blocks Kt_nn+, Kt_nt+; `chol`
    !> stays factored for the caller's solves (free it), also when stat fails.
    subroutine enrichment_reduce(this, chol, kt_nn, kt_nt, stat)
        class(enrichment_t), intent(in) :: this
        type(cholesky_t), intent(inout) :: chol
        real(wp), allocatable, intent(out) :: kt_nn(:, :), kt_nt(:, :)
        type(status_t), intent(out) :: stat
        type(timings_t) :: ignored   ! the estimate's time is counted as a whole
        character(len=:), allocatable :: detail
        integer :: at
        call factor_contact_blocks(this%k, this%mesh, this%dofs, this%contact, chol, kt_nn, &
                                   kt_nt, ignored, stat)
        if (stat%code == STATUS_SINGULAR) then
            ! Not K's: factor_stiffness's hint (a Dirichlet boundary) cannot be the cause here.
            detail = ''
            at = index(stat%message, '(CHOLMOD')
            if (at > 0) detail = ' '//stat%message(at:)
            stat%message = 'the enriched stiffness matrix of the error estimate (one degree ' &
                //'higher on the same cells; K itself was factored) is numerically singular' &
                //', as a nearly incompressible material or a sliver cell make it first'//detail
        end if
    end subroutine enrichment_reduce

    !> The free-dof vector on V+ of a field of V_h (given on prob%dofs): each enriched cell
    !> node gets the coarse cell's interpolation at its reference point.
    function enrichment_prolonged(this, prob, x) result(x_plus)
        class(enrichment_t), intent(in) :: this
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: x(:)
        real(wp), allocatable :: x_plus(:)
        real(wp) :: nodal(prob%mesh%dim(), prob%mesh%n_nodes()), transfer(MAX_NODES, MAX_NODES), &
                    xi(2, MAX_NODES), gradients(2, MAX_NODES)
        integer :: c, j, n_coarse, node

        nodal = prob%dofs%nodal_field(x)
        n_coarse = element_nodes_per_cell(prob%mesh%element)
        ! (i, j): coarse shape function i at the reference point of enriched node j
        transfer = 0.0_wp
        call reference_nodes(this%element, xi)
        do j = 1, element_nodes_per_cell(this%element)
            call evaluate_shape(prob%mesh%element, xi(:, j), transfer(:, j), gradients)
        end do
        allocate (x_plus(this%dofs%n_free), source=0.0_wp)
        do c = 1, prob%mesh%n_cells()
            do j = 1, element_nodes_per_cell(this%element)
                node = this%mesh%cells(j, c)
                associate (values => matmul(nodal(:, prob%mesh%cells(:, c)), &
                                            transfer(1:n_coarse, j)))
                    if (this%dofs%free_dof(1, node) > 0) &
                        x_plus(this%dofs%free_dof(1, node)) = values(1)
                    if (this%dofs%free_dof(2, node) > 0) &
                        x_plus(this%dofs%free_dof(2, node)) = values(2)
                end associate
            end do
        end do
    end function enrichment_prolonged

    !> I_h x+ on prob%dofs: the enriched field evaluated at the coarse nodes.
    function enrichment_interpolant(this, prob, x_plus) result(x)
        class(enrichment_t), intent(in) :: this
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: x_plus(:)
        real(wp), allocatable :: x(:)
        real(wp) :: nodal(this%mesh%dim(), this%mesh%n_nodes()), xi(2, MAX_NODES), &
                    values(MAX_NODES), &
                    gradients(2, MAX_NODES), at(2)
        integer :: c, i, n_fine, node

        nodal = this%dofs%nodal_field(x_plus)
        n_fine = element_nodes_per_cell(this%element)
        call reference_nodes(prob%mesh%element, xi)
        allocate (x(prob%dofs%n_free), source=0.0_wp)
        do c = 1, prob%mesh%n_cells()
            do i = 1, element_nodes_per_cell(prob%mesh%element)
                node = prob%mesh%cells(i, c)
                call evaluate_shape(this%element, xi(:, i), values, gradients)
                at = matmul(nodal(:, this%mesh%cells(:, c)), values(1:n_fine))
                if (prob%dofs%free_dof(1, node) > 0) x(prob%dofs%free_dof(1, node)) = at(1)
                if (prob%dofs%free_dof(2, node) > 0) x(prob%dofs%free_dof(2, node)) = at(2)
            end do
        end do
    end function enrichment_interpolant

    !> r_K = int_{C in K} (w.n) (lambda t - n).z ds - a_K(u, z) for every cell K, fields of V+
    !> as free-dof vectors: u the discrete displacement, w a field whose normal trace on
    !> Gamma_C is the contact pressure g, z the weight. Their sum is r_h(z).
    function enrichment_cell_residuals(this, poisson, contact_part, lambda, u, w, z) &
        result(r_cell)
        class(enrichment_t), intent(in) :: this
        real(wp), intent(in) :: poisson, lambda
        integer, intent(in) :: contact_part
        real(wp), intent(in) :: u(:), w(:), z(:)
        real(wp), allocatable :: r_cell(:)
        real(wp), allocatable :: u_nodal(:, :), w_nodal(:, :), z_nodal(:, :), u_cell(:), &
                                 z_cell(:), xy(:, :), me(:, :)
        logical, allocatable :: in_contact(:)
        integer, allocatable :: cell_of_node(:)
        type(stiffness_tables_t) :: tables
        integer :: c, j, n_fine, e, i, l, per_edge, n_dim
        real(wp) :: row_factor(2)

        n_fine = element_nodes_per_cell(this%element)
        n_dim = this%mesh%dim()
        ! (allocated first: gfortran 12 warns of an unallocated one at -O3)
        allocate (u_nodal(n_dim, this%mesh%n_nodes()), w_nodal(n_dim, this%mesh%n_nodes()), &
                  z_nodal(n_dim, this%mesh%n_nodes()))
        u_nodal = this%dofs%nodal_field(u)
        w_nodal = this%dofs%nodal_field(w)
        z_nodal = this%dofs%nodal_field(z)
        allocate (u_cell(n_dim*n_fine), z_cell(n_dim*n_fine), xy(n_dim, n_fine))
        allocate (r_cell(this%mesh%n_cells()), source=0.0_wp)
        ! the cells of V+ are those of the coarse mesh, which the assembly has accepted
        tables = stiffness_tables(this%element)
        do c = 1, this%mesh%n_cells()
            do j = 1, n_fine
                xy(:, j) = this%mesh%coords(:, this%mesh%cells(j, c))
                u_cell(n_dim*(j - 1) + 1:n_dim*j) = u_nodal(:, this%mesh%cells(j, c))
                z_cell(n_dim*(j - 1) + 1:n_dim*j) = z_nodal(:, this%mesh%cells(j, c))
            end do
            r_cell(c) = -element_energy(tables, xy, this%young, poisson, u_cell, z_cell)
        end do
        ! the boundary term: each contact edge's part, given to its cell (found by the edge's
        ! first interior node, which belongs to no other cell)
        allocate (in_contact(this%mesh%n_nodes()), source=.false.)
        in_contact(this%contact%nodes) = .true.
        allocate (cell_of_node(this%mesh%n_nodes()), source=0)
        do c = 1, this%mesh%n_cells()
            cell_of_node(this%mesh%cells(4:, c)) = c
        end do
        per_edge = size(this%mesh%edges, 1)
        ! allocated before its first assignment: gfortran 12 reads the bounds of an
        ! unallocated left-hand side for the reallocation test, which UBSan reports
        allocate (me(per_edge, per_edge))
        row_factor = this%contact%slip_direction(lambda)
        do e = 1, size(this%mesh%edges, 2)
            if (this%mesh%edge_part(e) /= contact_part) cycle
            me = edge_mass(per_edge, norm2(this%mesh%coords(:, this%mesh%edges(2, e)) - &
                                           this%mesh%coords(:, this%mesh%edges(1, e))))
            c = cell_of_node(this%mesh%edges(3, e))
            do i = 1, per_edge
                if (.not. in_contact(this%mesh%edges(i, e))) cycle
                do l = 1, per_edge
                    if (.not. in_contact(this%mesh%edges(l, e))) cycle
                    r_cell(c) = r_cell(c) + &
                        dot_product(row_factor, z_nodal(:, this%mesh%edges(i, e)))*me(i, l)* &
                        dot_product(this%contact%normal, w_nodal(:, this%mesh%edges(l, e)))
                end do
            end do
        end do
    end function enrichment_cell_residuals
end module enrichment
