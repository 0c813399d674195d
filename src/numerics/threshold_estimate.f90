! SPDX-License-Identifier: MIT
!> A goal-oriented (dual-weighted residual) estimate of the error of the critical lambdas
!> lambda+ and lambda-, the pencil eigenvalues Kt_nn x = lambda Kt_nt x nearest zero, with
!> element indicators for each: what `kind = 'threshold'` with &adapt refines for.
!>
!> The threshold as a problem on the whole body (model.md section 7): find lambda, a
!> displacement u and a contact traction g (a function on Gamma_C of the trace space of the
!> elements) with
!>     a(u, v) + int_C g v_n ds + int_C q u_n ds = lambda int_C g v_t ds
!> for all v and q: u_n = 0 on Gamma_C and the nodal tractions M g = x are the pencil
!> eigenvector. Discretely u_h = K^-1 (lambda_h T' - N') x_h, g_h = M^-1 x_h, which is
!> exactly the pencil solution, and the spaces are nested (the traces of P_k are among those
!> of P_k+1). So the argument of module enrichment applies with s = lambda: the residual
!>     r_h(z) = int_C g_h (lambda_h t - n) . z ds - a(u_h, z)
!> (its multiplier part vanishes: u_h.n = 0 on Gamma_C) weighted with z = z+ - I_h z+, z+
!> the displacement of the left eigenvector of the enriched pencil (Kt_nn+ y = lambda Kt_nt+' y,
!> z+ = K+^-1 N+' y), gives lambda+ - lambda_h = -r_h(z) / R(U_h, Z+), R = int_C g_h z+_t ds:
!> the two-level difference, to round-off (tested), split over the cells as indicators.
!> Both sides share one enriched factor.
module threshold_estimate
    use kinds, only: wp
    use error_bar, only: single_bar
    use status, only: status_t, STATUS_SOLVER
    use strings, only: to_string
    use timer, only: wall_time
    use sparse_cholesky, only: cholesky_t
    use contact_boundary, only: contact_t
    use critical_lambda, only: thresholds_t, pencil_thresholds, SIDE_PLUS, SIDE_MINUS
    use lapack_interfaces, only: dgetrf, dgetrs
    use problem, only: problem_t
    use enrichment, only: enrichment_t, build_enrichment
    use moving_side, only: moving_side_t
    implicit none
    private
    public :: threshold_estimate_t, threshold_displacements, estimate_threshold_errors

    type, public :: threshold_estimate_t
        logical :: computed(2) = .false.            !! per side (SIDE_PLUS, SIDE_MINUS)
        !> (lambda+ - lambda_h) / lambda_h by the weighted residual, signed
        real(wp) :: relative(2) = 0.0_wp
        !> the relative error bars quoted (error_bar); negative: none
        real(wp) :: bar(2) = -1.0_wp
        real(wp) :: lambda_enriched(2) = 0.0_wp     !! the enriched (or halved) pencil's threshold
        !> hp: the level whose value and bar are quoted, the one where that side met the
        !> tolerance (0: not hp, or no bar)
        integer :: met_level(2) = 0
        !> the estimate is the difference to the same element on the mesh of halved cells
        !> (elements with no degree above them: Q1, Q2, P4 on a rectangle), no cell indicators
        logical :: halved_mesh = .false.
        real(wp), allocatable :: indicators(:, :)   !! (n_cells, 2) eta_K relative to lambda_h
        integer :: element = 0                      !! the enriched element
        !> the estimate's name where it is neither enrichment nor halving ('': one of them)
        character(len=40) :: method = ''
        real(wp) :: seconds = 0.0_wp
        !> per side, why it was not computed ('' where it was, or where there is no threshold)
        character(len=200) :: skipped(2) = ''
        !> hp: per side that did not converge, its values followed over the levels, where its
        !> vector sits and the wedge there (moving_side; known false: none)
        type(moving_side_t) :: moving(2)
    contains
        procedure :: record => threshold_estimate_record
    end type threshold_estimate_t

contains

    !> u(:, side) = K^-1 (lambda T' - N') x for each threshold found (zero otherwise), with the
    !> factor of K of `contact`'s problem: the displacement of the limit mode of section 7.
    subroutine threshold_displacements(chol, contact, n_free, thr, u, stat)
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        integer, intent(in) :: n_free
        type(thresholds_t), intent(in) :: thr
        real(wp), allocatable, intent(out) :: u(:, :)   !! (n_free, 2)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: rhs(:, :)
        integer :: side

        allocate (rhs(n_free, 2), source=0.0_wp)
        allocate (u(n_free, 2))
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. thr%found(side)) cycle
            call contact%scatter(contact%slip_direction(thr%lambda(side)), &
                                 thr%vectors(:, side), rhs(:, side))
        end do
        call chol%solve(rhs, u, stat)
    end subroutine threshold_displacements

    !> The estimate of each threshold found in `thr` (computed on `prob`, with the
    !> displacements `u_h` of threshold_displacements). Not computed (stat ok, a reason in
    !> est%skipped) where prob's element has no enrichment, the enriched contact has more
    !> than `max_contact` nodes, or the enriched pencil has no real eigenvalue on that side.
    subroutine estimate_threshold_errors(prob, thr, u_h, max_contact, est, stat)
        type(problem_t), intent(in) :: prob
        type(thresholds_t), intent(in) :: thr
        real(wp), intent(in) :: u_h(:, :)
        integer, intent(in) :: max_contact
        type(threshold_estimate_t), intent(out) :: est
        type(status_t), intent(out) :: stat
        type(enrichment_t) :: enr
        type(thresholds_t) :: left
        type(cholesky_t) :: chol
        character(len=:), allocatable :: skipped
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), g_h(:, :), w_h(:), rhs(:, :), &
                                 z_plus(:, :), u(:), w(:), z(:), r_cell(:), g(:), z_t(:), &
                                 m_z_t(:)
        real(wp) :: start, r_weight
        integer :: side

        start = wall_time()
        if (.not. any(thr%found)) return
        call build_enrichment(prob, max_contact, enr, skipped, stat)
        if (.not. stat%ok()) return
        if (enr%element == 0) return
        if (len(skipped) > 0) then
            est%skipped = skipped
            return
        end if
        est%element = enr%element
        call enr%reduce(chol, kt_nn, kt_nt, stat)
        ! the left eigenvectors y: the right ones of the transposed pencil
        if (stat%ok()) call pencil_thresholds(kt_nn, transpose(kt_nt), left, stat)
        if (.not. stat%ok()) then
            call chol%free()
            return
        end if
        deallocate (kt_nn, kt_nt)
        allocate (rhs(enr%dofs%n_free, 2), source=0.0_wp)
        allocate (z_plus(enr%dofs%n_free, 2))
        do side = SIDE_PLUS, SIDE_MINUS
            if (left%found(side)) call enr%contact%scatter(enr%contact%normal, &
                                                           left%vectors(:, side), rhs(:, side))
        end do
        call chol%solve(rhs, z_plus, stat)
        call chol%free()
        if (.not. stat%ok()) return

        call contact_tractions(prob%contact, thr%vectors, g_h, stat)
        if (.not. stat%ok()) return
        allocate (est%indicators(prob%mesh%n_cells(), 2), source=0.0_wp)
        allocate (w_h(prob%dofs%n_free), g(enr%contact%p()), z_t(enr%contact%p()), &
                  m_z_t(enr%contact%p()))
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. thr%found(side)) cycle
            if (.not. left%found(side)) then
                est%skipped(side) = 'not computed: the enriched pencil has no real eigenvalue '// &
                    merge('> 0', '< 0', side == SIDE_PLUS)
                cycle
            end if
            est%lambda_enriched(side) = left%lambda(side)
            ! the traction g_h as the normal trace of a field of V_h, then on V+
            w_h = 0.0_wp
            call prob%contact%scatter(prob%contact%normal, g_h(:, side), w_h)
            w = enr%prolonged(prob, w_h)
            u = enr%prolonged(prob, u_h(:, side))
            z = z_plus(:, side) - enr%prolonged(prob, enr%interpolant(prob, z_plus(:, side)))
            ! R(U_h, Z+) = int_C g_h z+_t ds = g' M+ T+ z+
            call enr%contact%gather(enr%contact%normal, w, g)
            call enr%contact%gather(enr%contact%tangent, z_plus(:, side), z_t)
            call enr%contact%mass%matvec(z_t, m_z_t)
            r_weight = dot_product(g, m_z_t)*thr%lambda(side)
            if (.not. abs(r_weight) > 0.0_wp) then
                est%skipped(side) = 'not computed: int_C g z_t ds = 0 (a defective pencil '// &
                    'eigenvalue)'
                cycle
            end if
            r_cell = enr%cell_residuals(prob%poisson, prob%contact_part, thr%lambda(side), u, &
                                        w, z)
            call est%record(side, -sum(r_cell)/r_weight)
            est%indicators(:, side) = abs(r_cell)/abs(r_weight)
        end do
        est%seconds = wall_time() - start
    end subroutine estimate_threshold_errors

    !> Side `side` estimated (enriched or halved mesh): its signed relative estimate and the
    !> one-mesh bar from it (single_bar, no round-off part), the same for both estimates.
    pure subroutine threshold_estimate_record(this, side, relative)
        class(threshold_estimate_t), intent(inout) :: this
        integer, intent(in) :: side
        real(wp), intent(in) :: relative
        this%relative(side) = relative
        this%computed(side) = .true.
        this%bar(side) = single_bar(abs(relative), -1.0_wp)
    end subroutine threshold_estimate_record

    !> g(:, side) = M^-1 x(:, side): the nodal values of the traction whose nodal forces are
    !> the pencil eigenvector (M the contact mass, SPD; one LU, p^3 / 3 flops).
    subroutine contact_tractions(contact, x, g, stat)
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: x(:, :)   !! (p, 2)
        real(wp), allocatable, intent(out) :: g(:, :)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: lu(:, :)
        integer, allocatable :: pivot(:)
        integer :: p, info

        p = contact%p()
        lu = contact%mass_dense()
        allocate (g, source=x)   ! not g = x: UBSan read the unset extent of g (Asan build)
        allocate (pivot(p))
        call dgetrf(p, p, lu, p, pivot, info)
        if (info == 0) call dgetrs('N', p, size(g, 2), lu, p, pivot, g, p, info)
        if (info /= 0) call stat%fail(STATUS_SOLVER, 'threshold estimate: the contact mass '// &
                                      'matrix is singular (dgetrf/dgetrs info = '// &
                                      to_string(info)//')')
    end subroutine contact_tractions
end module threshold_estimate
