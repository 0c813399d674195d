! SPDX-License-Identifier: MIT
!> The contact eigenproblem K phi = mu B phi on an hp space. The factor of K uses the hp
!> space's ordering with the contact functions' dofs last (hp_ordering), then CHOLMOD, so
!> that contact_reduction reads K^-1 on the contact dofs off the trailing block, as
!> factor_stiffness does for the Lagrange elements: dense_spectrum and arpack_spectrum then
!> run unchanged on hp data. hp_dense_spectrum is the whole chain from a P1 mesh and its
!> degrees to the spectrum, what an analysis calls.
module hp_eigen
    use kinds, only: wp
    use status, only: status_t, STATUS_SINGULAR
    use strings, only: to_string
    use timer, only: wall_time, timings_t, PHASE_ORDERING, PHASE_FACTOR
    use mesh, only: mesh_t
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t, ORDERING_GIVEN
    use hp_space, only: hp_space_t
    use hp_ordering, only: hp_cholesky_permutation
    use hp_space, only: build_hp_space
    use hp_stiffness, only: assemble_hp_stiffness
    use contact_boundary, only: contact_t, assemble_b
    use hp_contact, only: build_hp_contact
    use spectrum, only: spectrum_t
    use dense_eigen, only: dense_spectrum
    use timer, only: PHASE_ASSEMBLY, PHASE_REDUCTION, PHASE_EIGEN
    implicit none
    private
    public :: factor_hp_stiffness, hp_dense_spectrum

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
        call timings%add(PHASE_ORDERING, wall_time() - start, ': METIS, hp contact last')
        start = wall_time()
        call chol%factor(k, stat, ordering=ORDERING_GIVEN, permutation=permutation, &
                         keep_last=2*contact%p())
        if (stat%code == STATUS_SINGULAR) then
            stat%message = 'the hp stiffness matrix K is singular: is there a Dirichlet '// &
                'boundary that stops every rigid motion? ('//stat%message//')'
            return
        else if (.not. stat%ok()) then
            stat%message = 'hp stiffness matrix K: '//stat%message
            return
        end if
        call timings%add(PHASE_FACTOR, wall_time() - start, ': CHOLMOD, '// &
                         to_string(k%n())//' hp dofs')
    end subroutine factor_hp_stiffness

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
        start = wall_time()
        call build_hp_space(m, degree, dirichlet_parts, space, stat)
        if (.not. stat%ok()) return
        call assemble_hp_stiffness(m, space, young, poisson, k, stat)
        if (.not. stat%ok()) return
        call build_hp_contact(m, space, contact_part, contact, stat)
        if (.not. stat%ok()) return
        call assemble_b(contact, space%n_free(), lambda, b, stat)
        if (.not. stat%ok()) return
        call timings%add(PHASE_ASSEMBLY, wall_time() - start, ': hp space, K, M, B')
        call factor_hp_stiffness(k, m, space, contact, chol, timings, stat)
        if (.not. stat%ok()) return
        start = wall_time()
        call dense_spectrum(k, b, chol, contact, lambda, n_keep, spec, stat, reduction_seconds)
        if (.not. stat%ok()) return
        call timings%add(PHASE_REDUCTION, reduction_seconds, ': contact blocks')
        call timings%add(PHASE_EIGEN, wall_time() - start - reduction_seconds, &
                         ': dense eigenvalues and residuals')
    end subroutine hp_dense_spectrum
end module hp_eigen
