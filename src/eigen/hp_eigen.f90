! SPDX-License-Identifier: MIT
!> The contact eigenproblem K phi = mu B phi on an hp space. The factor of K uses the hp
!> space's ordering with the contact functions' dofs last (hp_ordering), then CHOLMOD, so
!> that contact_reduction reads K^-1 on the contact dofs off the trailing block, as
!> factor_stiffness does for the Lagrange elements: dense_spectrum and arpack_search then
!> run unchanged on hp data. hp_dense_spectrum is the whole chain from a P1 mesh and its
!> degrees to the spectrum, what an analysis calls.
module hp_eigen
    use kinds, only: wp
    use status, only: status_t
    use timer, only: wall_time, timings_t
    use mesh, only: mesh_t
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use hp_space, only: hp_space_t
    use hp_ordering, only: hp_cholesky_permutation
    use hp_space, only: build_hp_space
    use hp_stiffness, only: assemble_hp_stiffness
    use contact_boundary, only: contact_t, assemble_b
    use hp_contact, only: build_hp_contact
    use spectrum, only: spectrum_t
    use dense_eigen, only: dense_spectrum, contact_flexibility
    use contact_reduction, only: scaled_reduced_matrix, lambda_unit, factor_permuted
    use arpack_eigen, only: arpack_options_t, arpack_lowest_positive
    use lapack_interfaces, only: dgeev, lapack_info_message
    use status, only: STATUS_SOLVER
    use timer, only: PHASE_ASSEMBLY, PHASE_REDUCTION, PHASE_EIGEN
    implicit none
    private
    public :: factor_hp_stiffness, hp_factored_problem, hp_assembled_problem, &
              hp_dense_spectrum, hp_lowest_positive, lowest_positive_of

contains

    !> Factor K of the hp space `space` on the P1 mesh `m` with the dofs of `contact`'s
    !> functions pivoted last; adds the ordering and factor times to `timings`.
    subroutine factor_hp_stiffness(k, m, space, contact, chol, timings, stat)
        type(csr_matrix_t), intent(in) :: k
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        type(contact_t), intent(in) :: contact
        type(cholesky_t), intent(inout) :: chol
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        integer, allocatable :: permutation(:)
        real(wp) :: start
        start = wall_time()
        call hp_cholesky_permutation(m, space, contact%nodes, permutation, stat)
        if (.not. stat%ok()) return
        call factor_permuted(k, permutation, contact, 'hp contact last', 'hp ', start, chol, &
                             timings, stat)
    end subroutine factor_hp_stiffness

    !> The hp space of the P1 mesh `m` with cell degrees `degree` and `dirichlet_parts`
    !> clamped, its stiffness K (interior condensed), the contact data of part
    !> `contact_part`, and K's factor with the contact dofs last: what every hp eigensolve
    !> starts from. Adds the assembly, ordering and factor times to `timings`.
    subroutine hp_factored_problem(m, degree, dirichlet_parts, contact_part, young, poisson, &
                                   space, contact, k, chol, timings, stat)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: degree(:), dirichlet_parts(:), contact_part
        real(wp), intent(in) :: young, poisson
        type(hp_space_t), intent(out) :: space
        type(contact_t), intent(out) :: contact
        type(csr_matrix_t), intent(out) :: k
        type(cholesky_t), intent(inout) :: chol
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        call build_hp_space(m, degree, dirichlet_parts, space, stat)
        if (stat%ok()) call hp_assembled_problem(m, space, contact_part, young, poisson, &
                                                 contact, k, timings, stat)
        if (stat%ok()) call factor_hp_stiffness(k, m, space, contact, chol, timings, stat)
    end subroutine hp_factored_problem

    !> K (interior condensed) and the contact data of part `contact_part` on the hp space
    !> `space` of the P1 mesh `m`, not factored: a caller that must check the contact
    !> blocks' memory first (p is known only now) factors after (factor_hp_stiffness).
    subroutine hp_assembled_problem(m, space, contact_part, young, poisson, contact, k, &
                                    timings, stat)
        type(mesh_t), intent(in) :: m
        type(hp_space_t), intent(in) :: space
        integer, intent(in) :: contact_part
        real(wp), intent(in) :: young, poisson
        type(contact_t), intent(out) :: contact
        type(csr_matrix_t), intent(out) :: k
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp) :: start
        start = wall_time()
        call assemble_hp_stiffness(m, space, young, poisson, k, stat)
        if (.not. stat%ok()) return
        call build_hp_contact(m, space, contact_part, contact, stat)
        if (.not. stat%ok()) return
        call timings%add(PHASE_ASSEMBLY, wall_time() - start, ': hp space, K, M')
    end subroutine hp_assembled_problem

    !> All nonzero eigenvalues of K phi = mu B phi (B for `lambda`) on the hp space of the P1
    !> mesh `m` with cell degrees `degree`, `dirichlet_parts` clamped and Gamma_C the part
    !> `contact_part`, by the dense reduced solver; the modes of the first `n_keep` kept.
    !> Returns the space and contact data too (for output), and the times of each phase.
    subroutine hp_dense_spectrum(m, degree, dirichlet_parts, contact_part, young, poisson, &
                                 lambda, n_keep, space, contact, spec, timings, stat)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: degree(:), dirichlet_parts(:), contact_part
        real(wp), intent(in) :: young, poisson, lambda
        integer, intent(in) :: n_keep
        type(hp_space_t), intent(out) :: space
        type(contact_t), intent(out) :: contact
        type(spectrum_t), intent(out) :: spec
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(csr_matrix_t) :: k, b
        type(cholesky_t) :: chol
        real(wp) :: start, reduction_seconds
        call hp_factored_problem(m, degree, dirichlet_parts, contact_part, young, poisson, &
                                 space, contact, k, chol, timings, stat)
        if (.not. stat%ok()) return
        call assemble_b(contact, space%n_free(), lambda, b, stat)
        if (.not. stat%ok()) return
        start = wall_time()
        call dense_spectrum(k, b, chol, contact, lambda, n_keep, spec, stat, reduction_seconds)
        if (.not. stat%ok()) return
        call timings%add(PHASE_REDUCTION, reduction_seconds, ': contact blocks')
        call timings%add(PHASE_EIGEN, wall_time() - start - reduction_seconds, &
                         ': dense eigenvalues and residuals')
    end subroutine hp_dense_spectrum

    !> The lowest positive mu of K phi = mu B phi on the hp space (arguments as
    !> hp_dense_spectrum), eigenvalues only: the reduced matrix A from the trailing block of
    !> the factor, then ARPACK's certified search on A, or all of A's eigenvalues by dgeev
    !> (no vectors) when ARPACK cannot decide. What a convergence study of the critical c_n
    !> needs, at a fraction of the spectrum's cost (no lift, no residuals). `found` is false
    !> when no positive mu exists.
    subroutine hp_lowest_positive(m, degree, dirichlet_parts, contact_part, young, poisson, &
                                  lambda, space, mu, found, timings, stat)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: degree(:), dirichlet_parts(:), contact_part
        real(wp), intent(in) :: young, poisson, lambda
        type(hp_space_t), intent(out) :: space
        real(wp), intent(out) :: mu
        logical, intent(out) :: found
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(contact_t) :: contact
        type(csr_matrix_t) :: k
        type(cholesky_t) :: chol
        type(arpack_options_t) :: options
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), a(:, :)
        real(wp) :: start, scale
        logical :: certified
        integer :: n_operator

        mu = 0.0_wp
        found = .false.
        call hp_factored_problem(m, degree, dirichlet_parts, contact_part, young, poisson, &
                                 space, contact, k, chol, timings, stat)
        if (.not. stat%ok()) return
        start = wall_time()
        call contact_flexibility(chol, contact, kt_nn, kt_nt, stat)
        if (.not. stat%ok()) return
        call chol%free()
        scale = lambda_unit(lambda)   ! A / lambda_unit has eigenvalues theta / lambda_unit
        a = scaled_reduced_matrix(kt_nn, kt_nt, contact%mass, lambda)
        call timings%add(PHASE_REDUCTION, wall_time() - start, ': contact blocks')
        start = wall_time()
        call arpack_lowest_positive(a, options, mu, found, certified, n_operator, stat)
        if (.not. stat%ok()) return
        if (.not. certified) call lowest_positive_of(a, mu, found, stat)
        if (found) mu = mu/scale
        call timings%add(PHASE_EIGEN, wall_time() - start, ': lowest positive mu')
    end subroutine hp_lowest_positive

    !> The lowest positive real mu = 1/theta over the eigenvalues theta of the square matrix
    !> `a` (LAPACK dgeev, eigenvalues only; real means an exactly zero imaginary part, as
    !> LAPACK returns for real eigenvalues).
    subroutine lowest_positive_of(a, mu, found, stat)
        real(wp), intent(in) :: a(:, :)
        real(wp), intent(out) :: mu
        logical, intent(out) :: found
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: work_a(:, :), wr(:), wi(:), work(:)
        real(wp) :: vl(1, 1), vr(1, 1), query(1)
        logical, allocatable :: positive(:)
        integer :: p, info
        p = size(a, 1)
        allocate (work_a, source=a)
        allocate (wr(p), wi(p))
        call dgeev('N', 'N', p, work_a, p, wr, wi, vl, 1, vr, 1, query, -1, info)
        allocate (work(max(1, int(query(1)))))
        call dgeev('N', 'N', p, work_a, p, wr, wi, vl, 1, vr, 1, work, size(work), info)
        found = .false.
        mu = 0.0_wp
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, lapack_info_message('dgeev', info))
            return
        end if
        positive = .not. abs(wi) > 0.0_wp .and. wr > 0.0_wp   ! real (wi exactly 0), positive
        found = any(positive)
        if (found) mu = 1.0_wp/maxval(wr, mask=positive)
    end subroutine lowest_positive_of
end module hp_eigen
