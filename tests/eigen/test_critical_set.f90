! SPDX-License-Identifier: MIT
!> The boundary of {lambda : a positive mu exists} against mathematics: the count of positive
!> eigenvalues changes exactly at the points found, a pair point is a double eigenvalue (zero
!> discriminant), the reference scene gives its two pencil thresholds (mirror-symmetric on
!> Q1), and at a pencil threshold the limit mode is the Signorini-Coulomb eigenmode: no
!> normal displacement on Gamma_C and tangential nodal forces -lambda* times the normal ones.
!> Points carried from a coarser mesh are the finer mesh's own; a structure it lacks is refused.
!> Onsets followed from a scan are the scan's; a side that gained or lost its pencil value is
!> refused.
program test_critical_set
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use fixtures, only: contact_scene
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t
    use contact_boundary, only: contact_t
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: reduced_blocks_t, lambda_unit
    use lapack_interfaces, only: dgeev
    use critical_lambda, only: thresholds_t, pencil_thresholds, reduced_eigenvalues, &
                               count_positive, SIDE_PLUS, SIDE_MINUS
    use critical_set, only: critical_set_t, find_critical_set, carry_critical_set, &
                            pair_discriminant, MECHANISM_PENCIL, MECHANISM_COMPLEX_PAIR, &
                            track_onsets, onset_point, boundary_point_t
    implicit none

    !> The scan of the default &sweep: -20 to 20 by 0.1.
    integer, parameter :: N_SCAN = 401
    type(test_suite_t) :: t
    t%name = 'test_critical_set'
    call partial_contact_has_a_pair_point(t)
    call count_changes_exactly_at_the_points(t)
    call positive_at_agrees_with_the_count(t)
    call pair_point_is_a_double_eigenvalue(t)
    call reference_scene_points_are_the_thresholds(t)
    call quadrilaterals_give_symmetric_points(t)
    call threshold_mode_is_signorini_coulomb(t)
    call limit_of_the_modes_is_the_threshold_mode(t)
    call carried_points_are_the_scan_points(t)
    call carry_refuses_another_structure(t)
    call pair_carry_takes_the_pencil_afresh(t)
    call followed_onsets_are_the_scan_onsets(t)
    call following_through_a_changed_side(t)
    call t%report()

contains

    !> The unit square, top fixed, contact on the left half of the bottom only (the right half
    !> becomes a traction-free part 'bottom_free'); N x N P2 'right'.
    subroutine partial_contact_scene(n, blocks, thr, set)
        integer, intent(in) :: n
        type(reduced_blocks_t), intent(out) :: blocks
        type(thresholds_t), intent(out) :: thr
        type(critical_set_t), intent(out) :: set
        type(mesh_t) :: m
        type(status_t) :: stat
        integer :: e, bottom

        call structured_rectangle(1.0_wp, 1.0_wp, n, n, ELEMENT_P2, 'right', m, stat)
        bottom = m%part_index('bottom')
        m%part_names = [m%part_names, 'bottom_free' // repeat(' ', len(m%part_names) - 11)]
        do e = 1, size(m%edge_part)
            if (m%edge_part(e) /= bottom) cycle
            if (maxval(m%coords(1, m%edges(:, e))) > 0.5_wp) m%edge_part(e) = size(m%part_names)
        end do
        call contact_scene(m, [m%part_index('top')], bottom, 0.3_wp, blocks, stat)
        call require(stat)
        call scan_scene(blocks, thr, set)
    end subroutine partial_contact_scene

    !> The reference scene (contact on the whole bottom, top fixed), 8 x 8 'right', scanned.
    subroutine reference_scene(element, thr, set, blocks)
        integer, intent(in) :: element
        type(thresholds_t), intent(out) :: thr
        type(critical_set_t), intent(out) :: set
        type(reduced_blocks_t), intent(out) :: blocks
        type(mesh_t) :: m
        type(status_t) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, 8, 8, element, 'right', m, stat)
        call require(stat)
        call contact_scene(m, [m%part_index('top')], m%part_index('bottom'), 0.3_wp, blocks, &
                           stat)
        call require(stat)
        call scan_scene(blocks, thr, set)
    end subroutine reference_scene

    !> The pencil and the boundary points over the default &sweep range.
    subroutine scan_scene(blocks, thr, set)
        type(reduced_blocks_t), intent(in) :: blocks
        type(thresholds_t), intent(out) :: thr
        type(critical_set_t), intent(out) :: set
        type(status_t) :: stat
        integer :: i
        call pencil_thresholds(blocks%kt_nn, blocks%kt_nt, thr, stat)
        call require(stat)
        call find_critical_set(blocks, [(-20.0_wp + 0.1_wp*real(i, wp), i=0, N_SCAN - 1)], &
                               thr%real_lambdas, set, stat)
        call require(stat)
    end subroutine scan_scene

    subroutine require(stat)
        type(status_t), intent(in) :: stat
        if (stat%ok()) return
        call t%check('scene: '//stat%message, .false.)
        error stop 1
    end subroutine require

    integer function n_positive(blocks, lambda)
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: lambda
        real(wp), allocatable :: wr(:), wi(:)
        type(status_t) :: stat
        call reduced_eigenvalues(blocks, lambda, wr, wi, stat)
        call require(stat)
        n_positive = count_positive(wr, wi)
    end function n_positive

    !> With contact on half the side, a positive mu vanishes (for lambda < 0) where a complex
    !> pair leaves the positive axis, not at the pencil eigenvalue nearest zero, which lies
    !> inside the set (a positive mu on both sides of it, so its old check said NOT
    !> confirmed); on the other side a pencil point remains. Every point is confirmed.
    subroutine partial_contact_has_a_pair_point(t)
        type(test_suite_t), intent(inout) :: t
        type(reduced_blocks_t) :: blocks
        type(thresholds_t) :: thr
        type(critical_set_t) :: set
        integer :: outside, inside
        call partial_contact_scene(16, blocks, thr, set)
        call t%check('partial contact: at least one point', size(set%points) >= 1)
        call t%check('partial contact: a complex_pair point', &
                     any(set%points%mechanism == MECHANISM_COMPLEX_PAIR))
        call t%check('partial contact: every point confirmed', all(set%points%confirmed))
        outside = n_positive(blocks, thr%lambda(SIDE_MINUS)*(1.0_wp + 1.0e-6_wp))
        inside = n_positive(blocks, thr%lambda(SIDE_MINUS)*(1.0_wp - 1.0e-6_wp))
        call t%check('partial contact: lambda- of the pencil has a positive mu on both sides', &
                     outside > 0 .and. inside > 0)
    end subroutine partial_contact_has_a_pair_point

    !> Each point separates "a positive mu" from "none" already at 1e-9 relative distance:
    !> the pair point is located to round-off (about 1e-14 relative, the conditioning of the
    !> discriminant's root), the pencil point is QZ's (1e-15), so 1e-9 is far outside the
    !> error while a point off by a bisection step of the scan (1e-1) would fail. The count
    !> jumps by 2 at a pair point (both members of the pair) and by 1 at a pencil point.
    subroutine count_changes_exactly_at_the_points(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: DISTANCE = 1.0e-9_wp
        type(reduced_blocks_t) :: blocks
        type(thresholds_t) :: thr
        type(critical_set_t) :: set
        integer :: i, below, above
        character(len=60) :: what
        call partial_contact_scene(16, blocks, thr, set)
        do i = 1, size(set%points)
            associate (b => set%points(i))
                below = n_positive(blocks, b%lambda - DISTANCE*abs(b%lambda))
                above = n_positive(blocks, b%lambda + DISTANCE*abs(b%lambda))
                write (what, '(a, i0, a)') 'point ', i, ': '
                call t%check(trim(what)//'none on one side, some on the other', &
                             (below > 0) .neqv. (above > 0))
                call t%check(trim(what)//'the direction reported', b%appears .eqv. above > 0)
                if (b%mechanism == MECHANISM_PENCIL) then
                    call t%check(trim(what)//'pencil: the count changes by 1', &
                                 abs(above - below) == 1)
                else
                    call t%check(trim(what)//'complex pair: the count changes by 2', &
                                 abs(above - below) == 2)
                end if
            end associate
        end do
    end subroutine count_changes_exactly_at_the_points

    !> positive_at (which the sweep uses to choose ARPACK) against the count itself, on a
    !> grid of lambdas that avoids the points (spacing 0.37, not a multiple of the scan's).
    subroutine positive_at_agrees_with_the_count(t)
        type(test_suite_t), intent(inout) :: t
        type(reduced_blocks_t) :: blocks
        type(thresholds_t) :: thr
        type(critical_set_t) :: set
        real(wp) :: lambda
        logical :: agree
        integer :: i, count
        call partial_contact_scene(16, blocks, thr, set)
        agree = .true.
        do i = 0, 100
            lambda = -19.9_wp + 0.37_wp*real(i, wp)
            if (lambda > 20.0_wp) exit
            count = n_positive(blocks, lambda)
            agree = agree .and. (set%positive_at(lambda) .eqv. count > 0)
        end do
        call t%check('positive_at agrees with the count on a grid', agree)
    end subroutine positive_at_agrees_with_the_count

    !> At a pair point A(lambda*) has a double positive eigenvalue. The discriminant d of the
    !> pair is about linear in lambda there, so 1e-6 relative away it is about 1e-6 |lambda
    !> d'|, while at lambda* it is round-off: eps ||A||^2 / theta^2 amplified by the
    !> conditioning, measured below 1e-12. Requiring |d(lambda*)| < 1e-4 min |d(lambda* +-
    !> 1e-6 |lambda*|)| places the root within 1e-10 relative of lambda*, with margin over
    !> round-off. The pair's members, computed separately, agree to about sqrt(eps) there.
    subroutine pair_point_is_a_double_eigenvalue(t)
        type(test_suite_t), intent(inout) :: t
        type(reduced_blocks_t) :: blocks
        type(thresholds_t) :: thr
        type(critical_set_t) :: set
        real(wp) :: d(-1:1), theta(-1:1), guess
        real(wp), allocatable :: wr(:), wi(:)
        type(status_t) :: stat
        integer :: i, k
        call partial_contact_scene(16, blocks, thr, set)
        do i = 1, size(set%points)
            if (set%points(i)%mechanism /= MECHANISM_COMPLEX_PAIR) cycle
            associate (lambda => set%points(i)%lambda)
                guess = 1.0_wp/set%points(i)%mu_meet
                do k = -1, 1
                    call reduced_eigenvalues(blocks, lambda + k*1.0e-6_wp*abs(lambda), wr, wi, &
                                             stat)
                    call require(stat)
                    call pair_discriminant(wr*lambda_unit(lambda), wi*lambda_unit(lambda), &
                                           guess, d(k), theta(k))
                end do
            end associate
            call t%check('pair point: discriminant changes sign across it', d(-1)*d(1) < 0.0_wp)
            call t%check('pair point: discriminant vanishes there (1e-4 of the sides)', &
                         abs(d(0)) < 1.0e-4_wp*min(abs(d(-1)), abs(d(1))))
            call t%check('pair point: the double eigenvalue is positive', theta(0) > 0.0_wp)
        end do
        call t%check('pair point: at least one checked', &
                     any(set%points%mechanism == MECHANISM_COMPLEX_PAIR))
    end subroutine pair_point_is_a_double_eigenvalue

    !> Contact on the whole bottom (P1 'right', N = 8): the boundary is exactly lambda- and
    !> lambda+ of the pencil, both pencil points, confirmed, a positive mu outside them.
    subroutine reference_scene_points_are_the_thresholds(t)
        type(test_suite_t), intent(inout) :: t
        type(thresholds_t) :: thr
        type(critical_set_t) :: set
        type(reduced_blocks_t) :: blocks
        call reference_scene(ELEMENT_P1, thr, set, blocks)
        call t%check('reference: two points', size(set%points) == 2)
        if (size(set%points) /= 2) return
        call t%check('reference: both pencil, both confirmed', &
                     all(set%points%mechanism == MECHANISM_PENCIL) .and. all(set%points%confirmed))
        ! the very numbers of QZ: exactly equal
        call t%check('reference: the points are lambda- and lambda+', &
                     .not. (abs(set%points(1)%lambda - thr%lambda(SIDE_MINUS)) > 0.0_wp .or. &
                            abs(set%points(2)%lambda - thr%lambda(SIDE_PLUS)) > 0.0_wp))
        call t%check('reference: vanishes at lambda-, appears at lambda+', &
                     .not. set%points(1)%appears .and. set%points(2)%appears)
        call t%check('reference: a positive mu at both ends of the range', set%positive_at_min)
    end subroutine reference_scene_points_are_the_thresholds

    !> The Q1 square is its own mirror image (x -> 1 - x turns t into -t, lambda into -lambda):
    !> the points come in pairs lambda, -lambda, to round-off of the pencil (1e-10 relative,
    !> as test_critical_lambda).
    subroutine quadrilaterals_give_symmetric_points(t)
        type(test_suite_t), intent(inout) :: t
        type(thresholds_t) :: thr
        type(critical_set_t) :: set
        type(reduced_blocks_t) :: blocks
        integer :: n
        call reference_scene(ELEMENT_Q1, thr, set, blocks)
        n = size(set%points)
        call t%check('Q1: an even number of points, at least 2', n >= 2 .and. mod(n, 2) == 0)
        if (n < 2) return
        call t%check('Q1: lambda_i = -lambda_(n+1-i)', &
                     all(abs(set%points%lambda + set%points(n:1:-1)%lambda) <= &
                         1.0e-10_wp*abs(set%points%lambda)))
        call t%check('Q1: mirrored directions', &
                     all(set%points%appears .neqv. set%points(n:1:-1)%appears))
    end subroutine quadrilaterals_give_symmetric_points

    !> At lambda* (1/mu = 0) the limit mode is phi = K^-1 (lambda* T' - N') x with x the
    !> pencil eigenvector: then N phi = (lambda* Kt_nt - Kt_nn) x = 0, i.e. no normal
    !> displacement on Gamma_C (Signorini contact, closed), and the nodal forces K phi are
    !> -x normal and lambda* x tangential: sigma_t = -lambda* sigma_n at every contact node,
    !> Coulomb friction with coefficient |lambda*| slipping along s = -sgn(lambda*). Checked
    !> with the sparse K (matvec, not the factor): phi from one CHOLMOD solve has a relative
    !> error of about eps cond(K) (~ 1e-13 at N = 8; measured 2e-15 for phi_n and 8e-16 for
    !> the force balance), so 1e-10 of max|phi| for phi_n and 1e-10 of the largest force
    !> leave a margin of 1000 over that estimate.
    subroutine threshold_mode_is_signorini_coulomb(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(reduced_blocks_t) :: blocks
        type(thresholds_t) :: thr
        type(status_t) :: stat
        type(csr_matrix_t) :: k
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(cholesky_t) :: chol
        real(wp), allocatable :: rhs(:, :), phi(:, :), force(:), f_n(:), f_t(:), rest(:)
        logical, allocatable :: on_contact(:)
        real(wp) :: lambda, scale
        integer :: side
        character(len=12) :: what

        call structured_rectangle(1.0_wp, 1.0_wp, 8, 8, ELEMENT_P1, 'right', m, stat)
        call contact_scene(m, [m%part_index('top')], m%part_index('bottom'), 0.3_wp, blocks, &
                           stat, k=k, dofs=dofs, contact=contact, chol=chol)
        call require(stat)
        call pencil_thresholds(blocks%kt_nn, blocks%kt_nt, thr, stat)
        call require(stat)
        allocate (rhs(k%n(), 1), phi(k%n(), 1), force(k%n()), f_n(contact%p()), &
                  f_t(contact%p()), on_contact(k%n()))
        on_contact = .false.
        on_contact(pack(contact%dofs, .true.)) = .true.
        do side = SIDE_PLUS, SIDE_MINUS
            what = merge('lambda+: ', 'lambda-: ', side == SIDE_PLUS)
            lambda = thr%lambda(side)
            rhs = 0.0_wp
            call contact%scatter(lambda*contact%tangent, thr%vectors(:, side), rhs(:, 1))
            call contact%scatter(-contact%normal, thr%vectors(:, side), rhs(:, 1))
            call chol%solve(rhs, phi, stat)
            call require(stat)
            call contact%gather(contact%normal, phi(:, 1), f_n)
            call t%check(trim(what)//' phi_n = 0 on Gamma_C (1e-10 max|phi|)', &
                         maxval(abs(f_n)) <= 1.0e-10_wp*maxval(abs(phi)))
            call k%matvec(phi(:, 1), force)
            call contact%gather(contact%normal, force, f_n)
            call contact%gather(contact%tangent, force, f_t)
            scale = maxval(abs(force))
            call t%check(trim(what)//' sigma_t = -lambda* sigma_n at every contact node', &
                         maxval(abs(f_t + lambda*f_n)) <= 1.0e-10_wp*scale)
            call t%check(trim(what)//' normal forces not all zero', &
                         maxval(abs(f_n)) > 0.1_wp*scale/max(1.0_wp, abs(lambda)))
            rest = pack(force, .not. on_contact)
            call t%check(trim(what)//' no force off Gamma_C (equilibrium)', &
                         maxval(abs(rest)) <= 1.0e-10_wp*scale)
        end do
        call chol%free()
    end subroutine threshold_mode_is_signorini_coulomb

    !> The mechanics approaching lambda+ from outside: the eigenvector y of the reduced
    !> problem for the large positive mu gives contact tractions g = mu M y that turn into
    !> the pencil eigenvector x, with the angle shrinking like the distance d: 1 - |cos| is
    !> O(d^2), measured 1.4e-10 at d = 1e-6 and 1.3e-4 at d = 1e-3 (N = 8). The bound 1e-8
    !> at 1e-6 keeps a margin of 70; a limit other than x would leave 1 - |cos| of order 1.
    subroutine limit_of_the_modes_is_the_threshold_mode(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(reduced_blocks_t) :: blocks
        type(thresholds_t) :: thr
        type(status_t) :: stat
        real(wp) :: gap(2)
        real(wp), parameter :: DISTANCES(2) = [1.0e-6_wp, 1.0e-3_wp]
        integer :: i

        call structured_rectangle(1.0_wp, 1.0_wp, 8, 8, ELEMENT_P1, 'right', m, stat)
        call contact_scene(m, [m%part_index('top')], m%part_index('bottom'), 0.3_wp, blocks, &
                           stat)
        call require(stat)
        call pencil_thresholds(blocks%kt_nn, blocks%kt_nt, thr, stat)
        call require(stat)
        do i = 1, 2
            gap(i) = traction_gap(blocks, thr%lambda(SIDE_PLUS)*(1.0_wp + DISTANCES(i)), &
                                  thr%vectors(:, SIDE_PLUS))
        end do
        call t%check('tractions -> pencil vector: 1 - |cos| < 1e-8 at 1e-6', gap(1) < 1.0e-8_wp)
        call t%check('tractions -> pencil vector: farther at 1e-3', gap(2) > 100.0_wp*gap(1))

    end subroutine limit_of_the_modes_is_the_threshold_mode
    !> 1 - |cos(g, x)| for g = M y, y the eigenvector of the largest positive mu at lambda.
    real(wp) function traction_gap(blocks, lambda, x)
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: lambda, x(:)
        real(wp), allocatable :: a(:, :), wr(:), wi(:), vr(:, :), work(:), g(:)
        real(wp) :: vl(1, 1), query(1)
        integer :: p, info, j, best
        p = size(blocks%kt_nn, 1)
        allocate (a(p, p), wr(p), wi(p), vr(p, p), g(p))
        a(:, :) = blocks%matrix(lambda)
        call dgeev('N', 'V', p, a, p, wr, wi, vl, 1, vr, p, query, -1, info)
        allocate (work(int(query(1))))
        call dgeev('N', 'V', p, a, p, wr, wi, vl, 1, vr, p, work, size(work), info)
        best = 0   ! the smallest positive real theta: the largest mu
        do j = 1, p
            if (abs(wi(j)) > 0.0_wp .or. .not. wr(j) > 0.0_wp) cycle
            if (best == 0) then
                best = j
            else if (wr(j) < wr(best)) then
                best = j
            end if
        end do
        traction_gap = 1.0_wp
        if (best == 0 .or. info /= 0) return
        call blocks%mass%matvec(vr(:, best), g)
        traction_gap = 1.0_wp - abs(dot_product(g, x))/(norm2(g)*norm2(x))
    end function traction_gap

    !> The partial-contact points carried to the blocks that found them are the scan's points:
    !> a pencil point the same QZ number, a pair point the discriminant's root again (each
    !> to round-off, about 1e-14 relative: 1e-10 allows the bracket's width of the count
    !> bisection, BISECTION_WIDTH, should the refinement stop there); each confirmed; at
    !> fewer than half the scan's solves.
    subroutine carried_points_are_the_scan_points(t)
        type(test_suite_t), intent(inout) :: t
        type(reduced_blocks_t) :: blocks
        type(thresholds_t) :: thr
        type(critical_set_t) :: set, carried_set
        type(status_t) :: stat
        logical :: carried
        integer :: n
        call partial_contact_scene(16, blocks, thr, set)
        call carry_critical_set(blocks, set, thr%real_lambdas, carried_set, carried, stat)
        call require(stat)
        n = size(set%points)
        call t%check('carry: carried, as many points as the scan', &
                     carried .and. size(carried_set%points) == n .and. n >= 1)
        if (.not. carried .or. size(carried_set%points) /= n) return
        call t%check('carry: the same mechanisms and directions', &
                     all(carried_set%points%mechanism == set%points%mechanism) .and. &
                     all(carried_set%points%appears .eqv. set%points%appears))
        call t%check('carry: the same points (1e-10 relative)', &
                     all(abs(carried_set%points%lambda - set%points%lambda) <= &
                         1.0e-10_wp*abs(set%points%lambda)))
        call t%check('carry: every point confirmed', all(carried_set%points%confirmed))
        ! exactly: the carried set copies the range (<= 0: no real == for -Wcompare-reals)
        call t%check('carry: the range and its start', &
                     abs(carried_set%lambda_min - set%lambda_min) <= 0.0_wp .and. &
                     (carried_set%positive_at_min .eqv. set%positive_at_min))
        ! 73 to 98 of 496 to 517 over the kernels and threads of the follow's count below
        call t%check('carry: fewer than half the solves of the scan', &
                     2*carried_set%n_evaluations < set%n_evaluations)
    end subroutine carried_points_are_the_scan_points

    !> A structure the blocks do not have is refused: the 8 x 8 mesh's, whose last pair point
    !> (lambda near 8.7) lies at 12.0 on the 16 x 16 mesh, far outside its scan bracket (the
    !> mode that makes it is resolved by neither mesh); a point whose direction is flipped;
    !> and no point at all with a positive mu claimed everywhere (at lambda = 0 there is
    !> none: A(0) = -Kt_nn M has only negative eigenvalues, Kt_nn and M being SPD).
    subroutine carry_refuses_another_structure(t)
        type(test_suite_t), intent(inout) :: t
        type(reduced_blocks_t) :: blocks, coarse_blocks
        type(thresholds_t) :: thr, coarse_thr
        type(critical_set_t) :: set, wrong, carried_set, coarse
        type(status_t) :: stat
        logical :: carried
        call partial_contact_scene(8, coarse_blocks, coarse_thr, coarse)
        call partial_contact_scene(16, blocks, thr, set)
        call t%check('carry: the meshes disagree on the last point', &
                     abs(coarse%points(size(coarse%points))%lambda - &
                         set%points(size(set%points))%lambda) > 1.0_wp)
        call carry_critical_set(blocks, coarse, thr%real_lambdas, carried_set, carried, stat)
        call require(stat)
        call t%check('carry: the 8 x 8 structure is refused on 16 x 16', .not. carried)
        wrong = set
        wrong%points(1)%appears = .not. wrong%points(1)%appears
        call carry_critical_set(blocks, wrong, thr%real_lambdas, carried_set, carried, stat)
        call require(stat)
        call t%check('carry: a point with the other direction is refused', .not. carried)
        wrong = set
        deallocate (wrong%points)
        allocate (wrong%points(0))
        wrong%positive_at_min = .true.
        call carry_critical_set(blocks, wrong, thr%real_lambdas, carried_set, carried, stat)
        call require(stat)
        call t%check('carry: a positive mu everywhere is refused', .not. carried)
    end subroutine carry_refuses_another_structure

    !> On hp levels real pencil values appear and vanish with the mesh: the carry that takes
    !> the pencil points afresh (fresh_pencil) gives the scan's own points where the coarse
    !> set has a pair of pencil points the blocks do not have (a gap in the positive set at
    !> 10 to 12, as a spurious pair of values would make), which the carry of every point
    !> refuses; and it still refuses the 8 x 8 structure on 16 x 16 (its last pair point is
    !> elsewhere) and a set whose directions do not alternate.
    subroutine pair_carry_takes_the_pencil_afresh(t)
        type(test_suite_t), intent(inout) :: t
        type(reduced_blocks_t) :: blocks, coarse_blocks
        type(thresholds_t) :: thr, coarse_thr
        type(critical_set_t) :: set, gap, carried_set, coarse, wrong
        type(status_t) :: stat
        logical :: carried
        call reference_scene(ELEMENT_P1, thr, set, blocks)
        if (size(set%points) /= 2) return
        gap = set
        gap%points = [set%points, boundary_point_t(lambda=10.0_wp, appears=.false., &
                      confirmed=.true., bracket=[9.9_wp, 10.1_wp]), boundary_point_t( &
                      lambda=12.0_wp, appears=.true., confirmed=.true., bracket=[11.9_wp, 12.1_wp])]
        call carry_critical_set(blocks, gap, thr%real_lambdas, carried_set, carried, stat)
        call require(stat)
        call t%check('pair carry: the carry of every point refuses the vanished pair', &
                     .not. carried)
        call carry_critical_set(blocks, gap, thr%real_lambdas, carried_set, carried, stat, &
                                fresh_pencil=.true.)
        call require(stat)
        call t%check('pair carry: carried without the vanished pair', &
                     carried .and. size(carried_set%points) == 2)
        if (carried .and. size(carried_set%points) == 2) call t%check( &
            'pair carry: the scan''s points, exactly (the same QZ numbers)', &
            .not. any(abs(carried_set%points%lambda - set%points%lambda) > 0.0_wp) .and. &
            all(carried_set%points%appears .eqv. set%points%appears))
        call partial_contact_scene(8, coarse_blocks, coarse_thr, coarse)
        call partial_contact_scene(16, blocks, thr, set)
        call carry_critical_set(blocks, coarse, thr%real_lambdas, carried_set, carried, stat, &
                                fresh_pencil=.true.)
        call require(stat)
        call t%check('pair carry: the 8 x 8 structure is refused on 16 x 16', .not. carried)
        wrong = set
        wrong%points(1)%appears = .not. wrong%points(1)%appears
        call carry_critical_set(blocks, wrong, thr%real_lambdas, carried_set, carried, stat, &
                                fresh_pencil=.true.)
        call require(stat)
        call t%check('pair carry: directions that do not alternate are refused', .not. carried)
        call carry_critical_set(blocks, set, thr%real_lambdas, carried_set, carried, stat, &
                                fresh_pencil=.true.)
        call require(stat)
        call t%check('pair carry: the partial-contact scan carried to itself', &
                     carried .and. size(carried_set%points) == size(set%points))
        if (carried .and. size(carried_set%points) == size(set%points)) call t%check( &
            'pair carry: the same points (1e-10 relative, as the carry of every point)', &
            all(abs(carried_set%points%lambda - set%points%lambda) <= &
                1.0e-10_wp*abs(set%points%lambda)))
    end subroutine pair_carry_takes_the_pencil_afresh

    !> The onsets followed (track_onsets) from a scan to the same blocks are the scan's:
    !> lambda- of partial contact is a pair point (its pencil value has a positive mu on
    !> both sides), found again to 1e-10 relative (the count bisection's width); lambda+ is
    !> the pencil value, which the followed set does not list. From the scan of 8 x 8 to the
    !> 16 x 16 blocks, lambda- is the 16 x 16 scan's to 1e-10: its onset moved by less than
    !> the carry's first bracket. Either costs a small part of a scan.
    subroutine followed_onsets_are_the_scan_onsets(t)
        type(test_suite_t), intent(inout) :: t
        type(reduced_blocks_t) :: blocks, coarse_blocks
        type(thresholds_t) :: thr, coarse_thr
        type(critical_set_t) :: set, coarse, followed
        type(status_t) :: stat
        logical :: tracked
        integer :: i, j
        call partial_contact_scene(16, blocks, thr, set)
        i = onset_point(set, SIDE_MINUS)
        call t%check('follow: the scan has a lambda- onset', i > 0)
        if (i == 0) return
        call t%check('follow: the scan''s lambda- onset is a pair point', &
                     set%points(i)%mechanism == MECHANISM_COMPLEX_PAIR)
        call track_onsets(blocks, set, thr, followed, tracked, stat)
        call require(stat)
        j = onset_point(followed, SIDE_MINUS)
        call t%check('follow: followed on the same blocks', tracked .and. j > 0)
        if (.not. tracked .or. j == 0) return
        call t%check('follow: the same lambda- onset (1e-10 relative)', &
                     abs(followed%points(j)%lambda - set%points(i)%lambda) <= &
                     1.0e-10_wp*abs(set%points(i)%lambda))
        call t%check('follow: no pair listed on the plus side', &
                     onset_point(followed, SIDE_PLUS) == 0 .eqv. &
                     (onset_point(set, SIDE_PLUS) == 0 .or. &
                      set%points(max(onset_point(set, SIDE_PLUS), 1))%mechanism == &
                      MECHANISM_PENCIL))
        ! the counts move with the BLAS kernel's last digits through the discriminant's
        ! regula falsi (1 to 18 steps per point; the count bisection's halvings are fixed
        ! by the bracket): 34 to 52 of 496 to 517 solves over eleven OpenBLAS kernels
        ! (OPENBLAS_CORETYPE) on one and on two threads; a fifth leaves twice that and still
        ! fails a follow that scans (the scan alone is N_SCAN solves)
        call t%check('follow: under a fifth of the scan''s solves', &
                     5*followed%n_evaluations < set%n_evaluations)
        call partial_contact_scene(8, coarse_blocks, coarse_thr, coarse)
        call track_onsets(blocks, coarse, thr, followed, tracked, stat)
        call require(stat)
        j = onset_point(followed, SIDE_MINUS)
        call t%check('follow: 8 x 8 onsets followed on 16 x 16', tracked .and. j > 0)
        if (.not. tracked .or. j == 0) return
        call t%check('follow: the 16 x 16 scan''s lambda- onset (1e-10 relative)', &
                     abs(followed%points(j)%lambda - set%points(i)%lambda) <= &
                     1.0e-10_wp*abs(set%points(i)%lambda))
    end subroutine followed_onsets_are_the_scan_onsets

    !> A side whose pencil value appears or vanishes between levels is followed, not sent to
    !> a search of the whole range (graded hp levels make spurious ones, docs/thresholds.md):
    !> on the reference scene (both onsets pencil values, confirmed) a plus side that had
    !> no onset before and now has its pencil value is followed from it exactly as from the
    !> scan that lists it (no pair, the same solves); a plus onset that lost its value while
    !> a positive mu is still just outside it (the blocks still have lambda+) is refused;
    !> one that lost it with no positive mu outside where it was (a
    !> point halfway to lambda+, the range ending before lambda+) is followed as no onset.
    subroutine following_through_a_changed_side(t)
        type(test_suite_t), intent(inout) :: t
        type(reduced_blocks_t) :: blocks
        type(thresholds_t) :: thr, lost
        type(critical_set_t) :: set, before, followed, from_scan
        type(status_t) :: stat
        logical :: tracked, scan_tracked
        call reference_scene(ELEMENT_P1, thr, set, blocks)
        if (size(set%points) /= 2) return
        call track_onsets(blocks, set, thr, from_scan, scan_tracked, stat)
        call require(stat)
        call t%check('follow: pencil onsets kept, no pair listed', &
                     scan_tracked .and. size(from_scan%points) == 0)
        before = set
        before%points = set%points(1:1)   ! no onset on the plus side
        call track_onsets(blocks, before, thr, followed, tracked, stat)
        call require(stat)
        call t%check('follow: a side that gained a pencil value is followed as from the scan', &
                     tracked .and. size(followed%points) == 0 .and. &
                     followed%n_evaluations == from_scan%n_evaluations)
        lost = thr
        lost%found(SIDE_PLUS) = .false.
        call track_onsets(blocks, set, lost, followed, tracked, stat)
        call require(stat)
        call t%check('follow: a lost pencil onset with a positive mu outside it is refused', &
                     .not. tracked)
        before = set
        before%points(2)%lambda = 0.5_wp*set%points(2)%lambda
        before%lambda_max = 0.9_wp*set%points(2)%lambda
        call track_onsets(blocks, before, lost, followed, tracked, stat)
        call require(stat)
        call t%check('follow: a lost pencil onset with none outside it is followed as none', &
                     tracked .and. size(followed%points) == 0)
    end subroutine following_through_a_changed_side
end program test_critical_set
