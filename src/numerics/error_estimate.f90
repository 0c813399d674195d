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
!> Computed where an enrichment exists (P1, P2, P3: module enrichment).
module error_estimate
    use kinds, only: wp
    use error_bar, only: single_bar
    use element_types, only: element_name
    use status, only: status_t, STATUS_SOLVER
    use timer, only: wall_time
    use contact_boundary, only: assemble_b
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: scaled_reduced_matrix, lambda_unit, mu_of_theta
    use dual_eigen, only: reduced_left_eigenvector
    use problem, only: problem_t
    use enrichment, only: enrichment_t, build_enrichment
    implicit none
    private
    public :: error_estimate_t, estimate_lowest_error
    public :: ENRICHED_CONTACT_MAX

    !> The largest enriched contact p+ estimated by default: the dense 2p+ x 2p+ inverse of
    !> the contact block (contact_flexibility, 16 p+^3 / 3 flops, 32 p+^2 bytes) stays about a
    !> second and 34 MB; P1 meshes with up to 512 contact cells.
    integer, parameter :: ENRICHED_CONTACT_MAX = 1025

    type, public :: error_estimate_t
        logical :: computed = .false.
        !> (mu+ - mu_h) / mu_h by the weighted residual: the signed relative error estimate
        real(wp) :: relative = 0.0_wp
        !> the relative error bar quoted with mu (error_bar: from this estimate; an adaptive
        !> run's from its levels); negative: none
        real(wp) :: bar = -1.0_wp
        real(wp) :: mu_enriched = 0.0_wp         !! mu+, same units as mu_h
        real(wp), allocatable :: indicators(:)   !! (n_cells) eta_K, relative to mu_h
        integer :: element = 0                   !! the enriched element (ELEMENT_P2 for P1)
        !> the estimate is the difference to the same element on the mesh of halved cells
        !> (elements with no degree above them: Q1, Q2, P4 on a rectangle), no cell indicators
        logical :: halved_mesh = .false.
        !> the width of the mode on Gamma_C in cells (mode_resolution) on this mesh and on the
        !> halved one (negative: not measured): a mode that does not widen with the mesh is
        !> not resolved by it
        real(wp) :: mode_cells = -1.0_wp
        real(wp) :: mode_cells_halved = -1.0_wp
        real(wp) :: seconds = 0.0_wp             !! wall time of the estimate
        !> why it was not computed when &eigen estimate decided so ('' otherwise)
        character(len=:), allocatable :: skipped
        !> why the estimate failed (the run goes on with a warning); unallocated otherwise
        character(len=:), allocatable :: failure
        !> what the estimate is when no enrichment made it (an hp run's level differences)
        character(len=:), allocatable :: method
        !> hp, the last level: |mu - mu with every degree raised by one| / |mu|, folded into
        !> the bar (error_bar: checked_bar); < 0: no check
        real(wp) :: check = -1.0_wp
    end type error_estimate_t

    public :: estimate_label

contains

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
        type(enrichment_t) :: enr
        type(csr_matrix_t) :: b_plus
        type(cholesky_t) :: chol
        character(len=:), allocatable :: skipped
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), a(:, :), w(:), rhs(:, :), psi(:, :), &
                                 u(:), z(:), b_u(:), r_cell(:)
        real(wp) :: start, theta, unit, b_phi_psi

        start = wall_time()
        if (.not. mu_h > 0.0_wp) return
        call build_enrichment(prob, max_contact, enr, skipped, stat)
        if (len(skipped) > 0) est%skipped = skipped
        if (.not. stat%ok() .or. enr%element == 0) return
        est%element = enr%element
        call assemble_b(enr%contact, enr%dofs%n_free, lambda, b_plus, stat)
        if (stat%ok()) call enr%reduce(chol, kt_nn, kt_nt, stat)
        if (.not. stat%ok()) then
            call chol%free()
            return
        end if
        ! A / lambda_unit, as the dense solver: eigenvalues theta / lambda_unit
        unit = lambda_unit(lambda)
        a = scaled_reduced_matrix(kt_nn, kt_nt, enr%contact%mass, lambda)
        deallocate (kt_nn, kt_nt)
        call reduced_left_eigenvector(a, 1.0_wp/(mu_h*unit), w, theta, stat)
        if (.not. stat%ok()) then
            call chol%free()
            return
        end if
        est%mu_enriched = mu_of_theta(theta, unit)
        ! psi+ = K+^-1 N+' w+ (the factor mu+ only scales it)
        allocate (rhs(enr%dofs%n_free, 1), source=0.0_wp)
        allocate (psi(enr%dofs%n_free, 1))
        call enr%contact%scatter(enr%contact%normal, w, rhs(:, 1))
        call chol%solve(rhs, psi, stat)
        call chol%free()
        if (.not. stat%ok()) return

        u = enr%prolonged(prob, phi_h)
        z = psi(:, 1) - enr%prolonged(prob, enr%interpolant(prob, psi(:, 1)))
        allocate (b_u(size(u)))
        call b_plus%matvec(u, b_u)
        b_phi_psi = dot_product(psi(:, 1), b_u)
        if (.not. abs(b_phi_psi) > 0.0_wp) then
            call stat%fail(STATUS_SOLVER, 'error estimate: b(phi_h, psi+) = 0 (a defective '// &
                           'eigenvalue): no estimate')
            return
        end if
        ! mu - mu_h ~ -r_h(z) / b(phi_h, psi+), r_h(z) = z^T (mu_h B+ u - K+ u): the contact
        ! pressure of the pair is mu_h u.n
        r_cell = enr%cell_residuals(prob%poisson, prob%contact_part, lambda, u, mu_h*u, z)
        est%relative = -sum(r_cell)/(b_phi_psi*mu_h)
        est%indicators = abs(r_cell)/(abs(b_phi_psi)*mu_h)
        est%computed = .true.
        est%bar = single_bar(abs(est%relative), -1.0_wp)
        est%seconds = wall_time() - start
    end subroutine estimate_lowest_error

    !> How the estimate was made, for the stdout lines: 'p2 enrichment', 'q2, halved mesh'.
    function estimate_label(est) result(label)
        type(error_estimate_t), intent(in) :: est
        character(len=:), allocatable :: label
        label = element_name(est%element)//' enrichment'
        if (est%halved_mesh) label = element_name(est%element)//', halved mesh'
        if (allocated(est%method)) label = est%method
    end function estimate_label
end module error_estimate
