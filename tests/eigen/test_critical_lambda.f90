! SPDX-License-Identifier: MIT
!> The critical lambdas against mathematics: the single element's closed form, the mirror
!> symmetry of the structured meshes, the singular reduced matrix at a threshold, and the
!> pole of mu there; and the lambdas of a &sweep range.
program test_critical_lambda
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use fixtures, only: single_triangle, contact_scene, csr_to_dense
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use contact_boundary, only: contact_t, build_contact
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness, contact_flexibility, reduced_blocks_t
    use timer, only: timings_t
    use lapack_interfaces, only: dgeev
    use critical_lambda, only: thresholds_t, pencil_thresholds, lowest_positive_mu, &
                               confirm_thresholds, restricted_pencil, SIDE_PLUS, SIDE_MINUS
    use run_config, only: sweep_config_t, sweep_lambdas
    implicit none


    type(test_suite_t) :: t
    t%name = 'test_critical_lambda'
    call single_element_threshold(t)
    call mirror_symmetry_of_diagonals(t)
    call quadrilaterals_are_symmetric(t)
    call reduced_matrix_singular_at_thresholds(t)
    call mu_has_a_pole_at_the_threshold(t)
    call thresholds_are_confirmed(t)
    call sweep_lambda_lists(t)
    call every_force_kept_is_the_full_pencil(t)
    call defective_infinity_is_no_threshold(t)
    call t%report()

contains

    !> model.md section 8: mu = -6 G (L + 2G) / ((L (lambda + 1) + G (lambda + 3)) l) has its pole
    !> at lambda = -(L + 3G)/(L + G), and is positive only beyond it: one negative threshold,
    !> no positive one. With p = 1 the pencil is 1 x 1 (lambda = Kt_nn / Kt_nt), so round-off
    !> alone separates the result from the closed form: 1e-13 relative.
    subroutine single_element_threshold(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: SIZES(2) = [1.0_wp, 0.01_wp]
        real(wp), parameter :: POISSONS(3) = [0.0_wp, 0.3_wp, 0.45_wp]
        real(wp) :: lame_l, shear_g, expected
        type(mesh_t) :: m
        type(reduced_blocks_t) :: s
        type(thresholds_t) :: thr
        type(status_t) :: stat
        character(len=60) :: what
        integer :: i, j

        do i = 1, size(SIZES)
            do j = 1, size(POISSONS)
                lame_l = POISSONS(j)/((1.0_wp + POISSONS(j))*(1.0_wp - 2.0_wp*POISSONS(j)))
                shear_g = 1.0_wp/(2.0_wp*(1.0_wp + POISSONS(j)))
                expected = -(lame_l + 3.0_wp*shear_g)/(lame_l + shear_g)
                call single_triangle(SIZES(i), m)
                call build_scene(m, [2], 1, POISSONS(j), s)
                call pencil_thresholds(s%kt_nn, s%kt_nt, thr, stat)
                write (what, '(a, es8.1, a, f5.2)') 'single element, l =', SIZES(i), ', nu =', &
                    POISSONS(j)
                call t%check(trim(what)//': no positive threshold', &
                             stat%ok() .and. .not. thr%found(SIDE_PLUS))
                call t%check(trim(what)//': a negative threshold', thr%found(SIDE_MINUS))
                call t%check_close(trim(what)//': lambda- = -(L+3G)/(L+G)', &
                                   thr%lambda(SIDE_MINUS), expected, 1.0e-13_wp)
            end do
        end do
    end subroutine single_element_threshold

    !> Mirroring x -> 1 - x maps the 'right' mesh onto the 'left' one and flips t, so Kt_nt
    !> changes sign (up to the node order) and Kt_nn does not: the left mesh at lambda is the
    !> right mesh at -lambda. Both sides are computed from different (permuted) matrices, so
    !> they agree to round-off times the eigenvalue condition: 1e-10 relative.
    subroutine mirror_symmetry_of_diagonals(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: LAMBDAS(4) = [5.0_wp, -5.0_wp, 2.5_wp, -40.0_wp]
        integer, parameter :: ELEMENTS(2) = [ELEMENT_P1, ELEMENT_P2]
        type(mesh_t) :: m
        type(reduced_blocks_t) :: right, left
        type(thresholds_t) :: thr_right, thr_left
        type(status_t) :: stat
        real(wp) :: mu_right, mu_left
        logical :: found_right, found_left
        integer :: n_right, n_left, i, e
        character(len=60) :: what

        do e = 1, size(ELEMENTS)
            call structured_rectangle(1.0_wp, 1.0_wp, 6, 6, ELEMENTS(e), 'right', m, stat)
            call build_scene(m, [m%part_index('top')], m%part_index('bottom'), 0.3_wp, right)
            call structured_rectangle(1.0_wp, 1.0_wp, 6, 6, ELEMENTS(e), 'left', m, stat)
            call build_scene(m, [m%part_index('top')], m%part_index('bottom'), 0.3_wp, left)
            call pencil_thresholds(right%kt_nn, right%kt_nt, thr_right, stat)
            call pencil_thresholds(left%kt_nn, left%kt_nt, thr_left, stat)
            write (what, '(a, i0)') 'mirror, element ', e
            call t%check(trim(what)//': both meshes have both thresholds', &
                         all(thr_right%found) .and. all(thr_left%found))
            call t%check_close(trim(what)//': lambda+(left) = -lambda-(right)', &
                               thr_left%lambda(SIDE_PLUS), -thr_right%lambda(SIDE_MINUS), &
                               1.0e-10_wp)
            call t%check_close(trim(what)//': lambda-(left) = -lambda+(right)', &
                               thr_left%lambda(SIDE_MINUS), -thr_right%lambda(SIDE_PLUS), &
                               1.0e-10_wp)
            call t%check(trim(what)//': the diagonal breaks the symmetry lambda+ = -lambda-', &
                abs(thr_right%lambda(SIDE_PLUS) + thr_right%lambda(SIDE_MINUS)) > &
                1.0e-6_wp*abs(thr_right%lambda(SIDE_PLUS)))
            do i = 1, size(LAMBDAS)
                call lowest_positive_mu(left, LAMBDAS(i), mu_left, found_left, &
                                        n_left, stat)
                call lowest_positive_mu(right, -LAMBDAS(i), mu_right, &
                                        found_right, n_right, stat)
                write (what, '(a, i0, a, f6.1)') 'mirror, element ', e, ': mu, lambda =', &
                    LAMBDAS(i)
                call t%check(trim(what)//': both found', found_left .and. found_right .and. &
                             n_left == n_right)
                call t%check_close(trim(what)//': left(lambda) = right(-lambda)', mu_left, &
                                   mu_right, 1.0e-10_wp)
            end do
        end do
    end subroutine mirror_symmetry_of_diagonals

    !> A Q1 mesh of the square is its own mirror image: lambda+ = -lambda- (1e-10, as above).
    subroutine quadrilaterals_are_symmetric(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: SIZES(3) = [2, 5, 12]
        type(mesh_t) :: m
        type(reduced_blocks_t) :: s
        type(thresholds_t) :: thr
        type(status_t) :: stat
        character(len=40) :: what
        integer :: i

        do i = 1, size(SIZES)
            call structured_rectangle(1.0_wp, 1.0_wp, SIZES(i), SIZES(i), ELEMENT_Q1, 'right', &
                                      m, stat)
            call build_scene(m, [m%part_index('top')], m%part_index('bottom'), 0.3_wp, s)
            call pencil_thresholds(s%kt_nn, s%kt_nt, thr, stat)
            write (what, '(a, i0)') 'Q1 N = ', SIZES(i)
            call t%check(trim(what)//': both thresholds', all(thr%found))
            call t%check_close(trim(what)//': lambda+ = -lambda-', thr%lambda(SIDE_PLUS), &
                               -thr%lambda(SIDE_MINUS), 1.0e-10_wp)
        end do
    end subroutine quadrilaterals_are_symmetric

    !> Independent check with another LAPACK path: at lambda*, (lambda* Kt_nt - Kt_nn) M is
    !> singular, so dgeev finds an eigenvalue of modulus ~ eps ||A|| times its condition;
    !> 1e-11 ||A|| leaves room for a condition of 1e5. The pencil backward errors are at
    !> round-off (QZ is backward stable): below 1e-14.
    subroutine reduced_matrix_singular_at_thresholds(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(reduced_blocks_t) :: s
        type(thresholds_t) :: thr
        type(status_t) :: stat
        real(wp), allocatable :: a(:, :), wr(:), wi(:), work(:)
        real(wp) :: vl(1, 1), vr(1, 1), query(1), norm_a
        integer :: side, p, info

        call structured_rectangle(1.0_wp, 1.0_wp, 10, 10, ELEMENT_P1, 'right', m, stat)
        call build_scene(m, [m%part_index('top')], m%part_index('bottom'), 0.3_wp, s)
        call pencil_thresholds(s%kt_nn, s%kt_nt, thr, stat)
        p = size(s%kt_nn, 1)
        allocate (a(p, p), wr(p), wi(p))
        do side = SIDE_PLUS, SIDE_MINUS
            a = s%matrix(thr%lambda(side))
            norm_a = maxval(sum(abs(a), dim=2))
            call dgeev('N', 'N', p, a, p, wr, wi, vl, 1, vr, 1, query, -1, info)
            if (.not. allocated(work)) allocate (work(int(query(1))))
            call dgeev('N', 'N', p, a, p, wr, wi, vl, 1, vr, 1, work, size(work), info)
            call t%check('reduced matrix singular at threshold '//merge('+', '-', side == 1), &
                info == 0 .and. minval(abs(cmplx(wr, wi, wp))) < 1.0e-11_wp*norm_a)
            call t%check('pencil backward error below 1e-14 at threshold '// &
                         merge('+', '-', side == 1), thr%residual(side) < 1.0e-14_wp)
            ! the left null vector (inverse iteration with the transpose): the same bound
            associate (y => thr%left_vectors(:, side))
                call t%check('left vector backward error below 1e-14 at threshold '// &
                             merge('+', '-', side == 1), &
                             maxval(abs(matmul(y, s%kt_nn) - thr%lambda(side)* &
                                        matmul(y, s%kt_nt)))/ &
                             ((maxval(sum(abs(s%kt_nn), dim=1)) + abs(thr%lambda(side))* &
                               maxval(sum(abs(s%kt_nt), dim=1)))*maxval(abs(y))) < 1.0e-14_wp)
            end associate
        end do
    end subroutine reduced_matrix_singular_at_thresholds

    !> theta(lambda) = 1/mu crosses zero linearly at lambda+, so mu (lambda - lambda+) tends
    !> to the constant 1/theta'(lambda+) with an O(d) error at distance d, while mu grows
    !> without bound. theta at d = 1e-7 lambda+ carries a relative round-off error of about
    !> eps cond / 1e-7 ~ 1e-8, so successive products agree to 1e-4 at the smallest distances.
    subroutine mu_has_a_pole_at_the_threshold(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(reduced_blocks_t) :: s
        type(thresholds_t) :: thr
        type(status_t) :: stat
        real(wp) :: mu(2:7), product(2:7), lambda
        logical :: found, all_found, growing
        integer :: k, n_positive

        call structured_rectangle(1.0_wp, 1.0_wp, 10, 10, ELEMENT_P1, 'right', m, stat)
        call build_scene(m, [m%part_index('top')], m%part_index('bottom'), 0.3_wp, s)
        call pencil_thresholds(s%kt_nn, s%kt_nt, thr, stat)
        all_found = .true.
        do k = 2, 7
            lambda = thr%lambda(SIDE_PLUS)*(1.0_wp + 10.0_wp**(-k))
            call lowest_positive_mu(s, lambda, mu(k), found, n_positive, stat)
            all_found = all_found .and. found
            product(k) = mu(k)*(lambda - thr%lambda(SIDE_PLUS))
        end do
        call t%check('a positive mu at every distance outside lambda+', all_found)
        growing = all(mu(3:7) > 5.0_wp*mu(2:6))
        call t%check('mu grows about tenfold per decade towards lambda+', growing)
        call t%check('mu exceeds 1e4 times its value at 1e-2 once 1e-7 away', &
                     mu(7) > 1.0e4_wp*mu(2))
        call t%check_close('mu (lambda - lambda+) tends to a constant', product(7), product(6), &
                           1.0e-4_wp)
        call t%check('the product converges linearly (error shrinks tenfold per decade)', &
                     abs(product(4) - product(7)) < 0.2_wp*abs(product(3) - product(7)))
    end subroutine mu_has_a_pole_at_the_threshold

    !> On the reference scene both thresholds are confirmed: a large positive mu just outside,
    !> none just inside.
    subroutine thresholds_are_confirmed(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(reduced_blocks_t) :: s
        type(thresholds_t) :: thr
        type(status_t) :: stat

        call structured_rectangle(1.0_wp, 1.0_wp, 8, 8, ELEMENT_P1, 'right', m, stat)
        call build_scene(m, [m%part_index('top')], m%part_index('bottom'), 0.3_wp, s)
        call pencil_thresholds(s%kt_nn, s%kt_nt, thr, stat)
        call confirm_thresholds(s, thr, stat)
        call t%check('reference scene N=8: lambda+ > 0 > lambda-', all(thr%found) .and. &
                     thr%lambda(SIDE_PLUS) > 0.0_wp .and. thr%lambda(SIDE_MINUS) < 0.0_wp)
        call t%check('lambda+ confirmed', thr%confirmed(SIDE_PLUS))
        call t%check('lambda- confirmed', thr%confirmed(SIDE_MINUS))
        ! mu ~ C / (1e-6 lambda*): large compared with the O(1) mu at lambda = 5
        call t%check('mu just outside is large', all(thr%mu_outside > 1.0e4_wp))
    end subroutine thresholds_are_confirmed

    !> Ends exact, even steps for 'linear', a constant ratio for 'log', the list verbatim.
    subroutine sweep_lambda_lists(t)
        type(test_suite_t), intent(inout) :: t
        type(sweep_config_t) :: c
        real(wp), allocatable :: lambdas(:)

        allocate (lambdas(0))   ! gfortran -O3: false -Wuninitialized on a first assignment
        c%lambda_min = -3.0_wp
        c%lambda_max = 5.0_wp
        c%n_lambda = 5
        lambdas = sweep_lambdas(c)
        call t%check('linear sweep: -3, -1, 1, 3, 5', size(lambdas) == 5 .and. &
                     all(abs(lambdas - [-3.0_wp, -1.0_wp, 1.0_wp, 3.0_wp, 5.0_wp]) < 1.0e-15_wp))
        c%spacing = 'log'
        c%lambda_min = -1000.0_wp
        c%lambda_max = -1.0_wp
        c%n_lambda = 4
        lambdas = sweep_lambdas(c)
        call t%check('log sweep: -1000, -100, -10, -1', size(lambdas) == 4 .and. &
            all(abs(lambdas - [-1000.0_wp, -100.0_wp, -10.0_wp, -1.0_wp]) <= &
                4.0_wp*epsilon(1.0_wp)*abs(lambdas)))
        ! Ranges whose span (linear) or ratio (log) overflows binary64 (red-team report).
        c%spacing = 'linear'
        c%lambda_min = -9.0e307_wp
        c%lambda_max = 9.0e307_wp
        c%n_lambda = 5
        lambdas = sweep_lambdas(c)
        call t%check('linear sweep -9e307 to 9e307: finite, even steps', size(lambdas) == 5 &
            .and. all(abs(lambdas - [-9.0e307_wp, -4.5e307_wp, 0.0_wp, 4.5e307_wp, &
                                     9.0e307_wp]) <= 4.0_wp*epsilon(1.0_wp)*9.0e307_wp))
        c%spacing = 'log'
        c%lambda_min = 1.0e-200_wp
        c%lambda_max = 1.0e200_wp
        lambdas = sweep_lambdas(c)
        call t%check('log sweep 1e-200 to 1e200: ratio 1e100 per step', size(lambdas) == 5 &
            .and. all(abs(lambdas - [1.0e-200_wp, 1.0e-100_wp, 1.0_wp, 1.0e100_wp, &
                                     1.0e200_wp]) <= 1.0e-12_wp*abs(lambdas)))
        c%lambdas(1:3) = [7.0_wp, -2.0_wp, 0.0_wp]
        lambdas = sweep_lambdas(c)
        call t%check('a list wins over the range, in its order', size(lambdas) == 3 .and. &
                     all(abs(lambdas - [7.0_wp, -2.0_wp, 0.0_wp]) < tiny(1.0_wp)))
    end subroutine sweep_lambda_lists

    !> Kt_nn, Kt_nt from a Cholesky factor of K (E = 1), and both times M.
    subroutine build_scene(m, dirichlet_parts, contact_part, poisson, s)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: dirichlet_parts(:), contact_part
        real(wp), intent(in) :: poisson
        type(reduced_blocks_t), intent(out) :: s
        type(status_t) :: stat
        call contact_scene(m, dirichlet_parts, contact_part, poisson, s, stat)
        if (.not. stat%ok()) then
            call t%check('build_scene: '//stat%message, .false.)
            error stop 1
        end if
    end subroutine build_scene

    !> restricted_pencil keeping every contact function: C is the (scaled) contact mass,
    !> invertible, so det(C' (Kt_nn - lambda Kt_nt) C) = 0 exactly where the full pencil's
    !> determinant is: the same real eigenvalues (P2 8 x 8 of the reference scene; QZ on two
    !> pencils whose entries differ by the scaling agrees to a few 1e-13 here, 1e-10 allowed).
    subroutine every_force_kept_is_the_full_pencil(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(reduced_blocks_t) :: s
        type(thresholds_t) :: full, restricted
        type(status_t) :: stat
        real(wp), allocatable :: rn(:, :), rt(:, :), c(:, :), mass(:, :)
        integer :: side
        call structured_rectangle(1.0_wp, 1.0_wp, 8, 8, ELEMENT_P2, 'right', m, stat)
        call contact_scene(m, [m%part_index('top')], m%part_index('bottom'), 0.3_wp, s, stat)
        if (stat%ok()) call pencil_thresholds(s%kt_nn, s%kt_nt, full, stat)
        call t%check('every force kept: scene built', stat%ok())
        if (.not. stat%ok()) return
        mass = csr_to_dense(s%mass)
        call restricted_pencil(s%kt_nn, s%kt_nt, mass, [(.true., side=1, size(mass, 1))], rn, &
                               rt, c)
        call pencil_thresholds(rn, rt, restricted, stat)
        call t%check('every force kept: same count of real eigenvalues', stat%ok() .and. &
                     restricted%n_real == full%n_real)
        do side = SIDE_PLUS, SIDE_MINUS
            call t%check_close('every force kept: same threshold', restricted%lambda(side), &
                               full%lambda(side), 1.0e-10_wp)
        end do
    end subroutine every_force_kept_is_the_full_pencil
    !> A pencil Kt_nn x = lambda Kt_nt x with Kt_nn = W'W and Kt_nt = W'(J ++ D)W, W dense
    !> and well conditioned, J the 3 x 3 Jordan block at 0 and D = diag(0.5, 0.4, 0.25, 0.2,
    !> 0.1): exactly five finite eigenvalues, 1/d = 2, 2.5, 4, 5 and 10, and a triple infinite
    !> one with a single eigenvector (a defective one, as Kt_nt of a finely graded h level
    !> had: singular to 3.6e-16 of its norm). Round-off splits the triple one into values of
    !> size about eps^(-1/3), at least one of them real (the roots of a real cubic), whose
    !> beta passes QZ's p eps test of infinity; it is told from a finite value by its chordal
    !> error bound (pencil_value_finite). Expected: five real values, 2 to 10, each to 1e-10
    !> (W's condition is about 10, so theirs is about 100: 1e-14 expected, 1e-10 leaves any
    !> BLAS its margin), lambda+ = 2, no lambda- (before: a spurious real value counted, and a
    !> lambda- near -1e5 where it fell on that side).
    subroutine defective_infinity_is_no_threshold(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: P = 8
        real(wp), parameter :: FINITE(5) = [2.0_wp, 2.5_wp, 4.0_wp, 5.0_wp, 10.0_wp]
        real(wp) :: w(P, P), core(P, P), kt_nn(P, P), kt_nt(P, P)
        type(thresholds_t) :: thr
        type(status_t) :: stat
        integer :: i, j
        ! W = I + 0.3 cos(i j + 1/2): dense, well conditioned, its entries not representable,
        ! so that the products carry round-off of size eps that splits J
        do j = 1, P
            do i = 1, P
                w(i, j) = 0.3_wp*cos(real(i*j, wp) + 0.5_wp)
            end do
            w(j, j) = w(j, j) + 1.0_wp
        end do
        core = 0.0_wp
        core(1, 2) = 1.0_wp
        core(2, 3) = 1.0_wp
        do i = 1, 5
            core(3 + i, 3 + i) = 1.0_wp/FINITE(i)
        end do
        kt_nn = matmul(transpose(w), w)
        kt_nt = matmul(transpose(w), matmul(core, w))
        call pencil_thresholds(kt_nn, kt_nt, thr, stat)
        call t%check('defective infinity: five real values, none from the infinite one', &
                     stat%ok() .and. thr%n_real == 5 .and. size(thr%real_lambdas) == 5 .and. &
                     thr%n_real + thr%n_complex + thr%n_infinite == P)
        if (.not. stat%ok() .or. size(thr%real_lambdas) /= 5) return
        call t%check('defective infinity: the values 1/d, lambda+ = 2, no lambda-', &
                     all(abs(thr%real_lambdas - FINITE) <= 1.0e-10_wp*FINITE) .and. &
                     thr%found(1) .and. abs(thr%lambda(1) - 2.0_wp) <= 1.0e-10_wp*2.0_wp .and. &
                     .not. thr%found(2))
    end subroutine defective_infinity_is_no_threshold
end program test_critical_lambda
