! SPDX-License-Identifier: MIT
!> hp_contact's force space for the threshold pencil (half_degree_forces): every vertex
!> function and, per contact edge of degree p_e, the edge functions up to degree ceil(p_e/2);
!> and its pencil (critical_lambda: restricted_pencil) on the hp levels of the reference
!> scene converges to the continuum thresholds as the full pencil does.
program test_hp_contact_forces
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use mesh, only: mesh_t
    use fixtures, only: square_hp_level, REF_LAMBDA_PLUS
    use hp_space, only: hp_space_t
    use hp_eigen, only: hp_factored_problem
    use hp_contact, only: half_degree_forces
    use contact_boundary, only: contact_t
    use contact_reduction, only: contact_flexibility
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use timer, only: timings_t
    use critical_lambda, only: thresholds_t, pencil_thresholds, restricted_pencil, SIDE_PLUS, &
                               SIDE_MINUS
    implicit none
    !> REF_LAMBDA_PLUS: the graded-P4 continuum value of the reference scene's lambda+
    !> (tests/data/truths.csv, uncertain by 5.6e-10 relative); lambda- is its mirror image
    type(test_suite_t) :: t

    t%name = 'test_hp_contact_forces'
    call forces_kept_by_degree()
    call half_degree_thresholds_converge()
    call t%report()

contains

    !> The reference scene's hp level `level` from 2 x 2 squares (sigma 0.15, degrees 1 +
    !> layer up to level + 1), factored, with its contact blocks.
    subroutine reference_level(level, space, contact, kt_nn, kt_nt, stat, bottom)
        integer, intent(in) :: level
        type(hp_space_t), intent(out) :: space
        type(contact_t), intent(out) :: contact
        real(wp), allocatable, intent(out) :: kt_nn(:, :), kt_nt(:, :)
        type(status_t), intent(out) :: stat
        integer, intent(out), optional :: bottom   !! the part index of Gamma_C
        type(mesh_t) :: m, graded
        type(csr_matrix_t) :: k
        type(cholesky_t) :: chol
        type(timings_t) :: timings
        integer, allocatable :: degree(:)
        call square_hp_level(level, level + 1, m, graded, degree, stat)
        if (.not. stat%ok()) return
        if (present(bottom)) bottom = m%part_index('bottom')
        call hp_factored_problem(graded, degree, [m%part_index('top')], m%part_index('bottom'), &
                                 1.0_wp, 0.3_wp, space, contact, k, chol, timings, stat)
        if (stat%ok()) call contact_flexibility(chol, contact, kt_nn, kt_nt, stat)
        call chol%free()
    end subroutine reference_level

    !> Every vertex function is kept, and of each contact edge's functions Lhat_2 .. Lhat_pe
    !> those of degree at most ceil(p_e / 2): p_e - 1 - (ceil(p_e / 2) - 1) = floor(p_e / 2)
    !> of them are left out per edge.
    subroutine forces_kept_by_degree()
        type(hp_space_t) :: space
        type(contact_t) :: contact
        type(status_t) :: stat
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :)
        logical, allocatable :: keep(:)
        integer :: e, left_out, a, bottom
        call reference_level(5, space, contact, kt_nn, kt_nt, stat, bottom)
        call t%check('level 5 built', stat%ok())
        if (.not. stat%ok()) return
        keep = half_degree_forces(space, contact)
        left_out = 0
        do e = 1, space%n_edges()
            if (space%edge_part(e) == bottom) left_out = left_out + space%edge_degree(e)/2
        end do
        call t%check('forces: floor(p_e / 2) functions left out per contact edge', &
                     count(.not. keep) == left_out .and. left_out > 0)
        call t%check('forces: every vertex function kept', all(pack(keep, &
                     contact%nodes <= space%n_vertices)))
        a = count(contact%nodes <= space%n_vertices)
        call t%check('forces: the kept edge functions are the low degrees', &
                     count(keep) == a + sum(max(0, (pack(space%edge_degree, &
                     space%edge_part == bottom) + 1)/2 - 1)))
    end subroutine forces_kept_by_degree

    !> At hp levels 6 and 8 the half-degree pencil's lambda+ and lambda- approach the
    !> continuum values as the full pencil's do: within 1e-6 at level 6 and within the
    !> truth's own uncertainty plus 1e-9 at level 8 (the full pencil: 2e-7 and 1e-11 off;
    !> hp levels gain a factor of about ten per level), and the two sides are mirror images
    !> (the square and its levels are symmetric under x -> 1 - x) to 1e-9.
    subroutine half_degree_thresholds_converge()
        type(hp_space_t) :: space
        type(contact_t) :: contact
        type(status_t) :: stat
        type(thresholds_t) :: thr
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), rn(:, :), rt(:, :), c(:, :)
        real(wp) :: tolerance
        integer :: level
        character(len=40) :: what
        do level = 6, 8, 2
            call reference_level(level, space, contact, kt_nn, kt_nt, stat)
            if (.not. stat%ok()) exit
            call restricted_pencil(kt_nn, kt_nt, contact%mass_dense(), &
                                   half_degree_forces(space, contact), rn, rt, c)
            call pencil_thresholds(rn, rt, thr, stat)
            if (.not. stat%ok()) exit
            tolerance = merge(1.0e-6_wp, 5.6e-10_wp + 1.0e-9_wp, level == 6)
            write (what, '(a, i0)') 'half-degree forces, level ', level
            call t%check(trim(what)//': both thresholds', all(thr%found))
            if (.not. all(thr%found)) cycle
            call t%check_close(trim(what)//': lambda+', thr%lambda(SIDE_PLUS), REF_LAMBDA_PLUS, &
                               tolerance)
            call t%check_close(trim(what)//': lambda-', thr%lambda(SIDE_MINUS), -REF_LAMBDA_PLUS, &
                               tolerance)
            call t%check_close(trim(what)//': mirror image', -thr%lambda(SIDE_MINUS), &
                               thr%lambda(SIDE_PLUS), 1.0e-9_wp)
        end do
        call t%check('levels built and solved', stat%ok())
    end subroutine half_degree_thresholds_converge
end program test_hp_contact_forces
