! SPDX-License-Identifier: MIT
!> wedge_exponents: the characteristic functions against the 4 x 4 system of the Airy fields
!> built here from the fields themselves, and the exponents against closed forms: Williams'
!> free-free wedge (the crack, 1/2; the re-entrant 270 degree corner, 0.5444837 and 0.9085292),
!> clamped-free at 180 degrees (1/2 +- i ln(kappa) / (2 pi)), frictionless contact as half of a
!> symmetric wedge, the sliding flat punch's edge (contact-free at 180 degrees: 1/2 +
!> atan(lambda beta) / pi, beta = (1 - 2 nu) / (2 - 2 nu)), and the lambda at which a real
!> exponent crosses 0.
program test_wedge_exponents
    use kinds, only: wp
    use wedge_exponents, only: wedge_determinant, wedge_roots, contact_free_crossing, &
                               contact_clamped_crossing, WEDGE_FREE, WEDGE_CLAMPED, WEDGE_CONTACT
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t
    real(wp), parameter :: PI = acos(-1.0_wp)

    t%name = 'test_wedge_exponents'
    call check_against_fields()
    call check_crack()
    call check_reentrant_corner()
    call check_clamped_free_half_plane()
    call check_frictionless_contact_is_half_a_symmetric_wedge()
    call check_sliding_punch_edge()
    call check_contact_free_crossing()
    call check_contact_clamped_crossing()
    call check_quarter_plane_table()
    call check_reflex_contact_corner()
    call t%report()

contains

    !> The face conditions of the field with Airy function r^(alpha+1) F(theta), as rows over
    !> (A, B, C, D): u_r and u_theta times 2G r^-alpha, sigma_tt and sigma_rt times
    !> r^(1-alpha) / alpha, from sigma_tt = alpha (alpha+1) F, sigma_rt = -alpha F' and the
    !> plane-strain displacements of each term (kappa = 3 - 4 nu).
    pure function field_rows(alpha, theta, kappa) result(rows)
        complex(wp), intent(in) :: alpha
        real(wp), intent(in) :: theta, kappa
        complex(wp) :: rows(4, 4)   !! rows: u_r, u_theta, sigma_tt, sigma_rt
        complex(wp) :: c1, s1, c2, s2
        c1 = cos((alpha + 1)*theta)
        s1 = sin((alpha + 1)*theta)
        c2 = cos((alpha - 1)*theta)
        s2 = sin((alpha - 1)*theta)
        rows(1, :) = [-(alpha + 1)*c1, -(alpha + 1)*s1, (kappa - alpha)*c2, (kappa - alpha)*s2]
        rows(2, :) = [(alpha + 1)*s1, -(alpha + 1)*c1, (kappa + alpha)*s2, -(kappa + alpha)*c2]
        rows(3, :) = [(alpha + 1)*c1, (alpha + 1)*s1, (alpha + 1)*c2, (alpha + 1)*s2]
        rows(4, :) = [(alpha + 1)*s1, -(alpha + 1)*c1, (alpha - 1)*s2, -(alpha - 1)*c2]
    end function field_rows

    !> Determinant of a 4 x 4 complex matrix by elimination with partial pivoting.
    pure complex(wp) function det4(a_in) result(d)
        complex(wp), intent(in) :: a_in(4, 4)
        complex(wp) :: a(4, 4), row(4)
        integer :: i, k, pivot
        a = a_in
        d = 1.0_wp
        do k = 1, 4
            pivot = k - 1 + maxloc(abs(a(k:, k)), dim=1)
            if (pivot /= k) then
                row = a(k, :)
                a(k, :) = a(pivot, :)
                a(pivot, :) = row
                d = -d
            end if
            d = d*a(k, k)
            if (abs(a(k, k)) <= 0.0_wp) return
            do i = k + 1, 4
                a(i, :) = a(i, :) - a(i, k)/a(k, k)*a(k, :)
            end do
        end do
    end function det4

    !> The face rows of `face` at angle theta (contact: u_theta and sigma_rt + lambda sigma_tt).
    pure function face(kind, alpha, theta, kappa, lambda) result(rows)
        integer, intent(in) :: kind
        complex(wp), intent(in) :: alpha
        real(wp), intent(in) :: theta, kappa, lambda
        complex(wp) :: rows(2, 4), all(4, 4)
        all = field_rows(alpha, theta, kappa)
        select case (kind)
        case (WEDGE_FREE)
            rows = all(3:4, :)
        case (WEDGE_CLAMPED)
            rows = all(1:2, :)
        case default
            rows(1, :) = all(2, :)
            rows(2, :) = all(4, :) + lambda*all(3, :)
        end select
    end function face

    !> At five complex alpha and several angles, nu and lambda, the 4 x 4 determinant of the
    !> fields is (alpha + 1)^2 times the characteristic function up to one constant factor per
    !> pair of faces (the factor is checked constant: its spread is round-off, 1e-10 allowed
    !> for determinants of entries up to e^(|Im alpha| omega) ~ 1e3).
    subroutine check_against_fields()
        integer, parameter :: pairs(2, 5) = reshape([WEDGE_FREE, WEDGE_FREE, WEDGE_CLAMPED, &
            WEDGE_CLAMPED, WEDGE_CLAMPED, WEDGE_FREE, WEDGE_CONTACT, WEDGE_FREE, &
            WEDGE_CONTACT, WEDGE_CLAMPED], [2, 5])
        complex(wp), parameter :: alphas(5) = [(0.37_wp, 0.0_wp), (1.3_wp, 0.8_wp), &
            (-0.6_wp, 0.2_wp), (2.1_wp, -1.1_wp), (0.05_wp, 1.7_wp)]
        real(wp), parameter :: omegas(3) = [0.9_wp, 1.5_wp*PI/2.0_wp, 1.9_wp*PI]
        real(wp), parameter :: nus(2) = [0.1_wp, 0.45_wp], lambdas(2) = [-3.7_wp, 1.3_wp]
        complex(wp) :: m(4, 4), ratio(size(alphas)), ratio0
        real(wp) :: kappa
        integer :: p, i, j, k, l
        logical :: ok
        ok = .true.
        do p = 1, size(pairs, 2)
            do j = 1, size(omegas)
                do k = 1, size(nus)
                    do l = 1, size(lambdas)
                        kappa = 3.0_wp - 4.0_wp*nus(k)
                        do i = 1, size(alphas)
                            m(1:2, :) = face(pairs(1, p), alphas(i), 0.0_wp, kappa, lambdas(l))
                            m(3:4, :) = face(pairs(2, p), alphas(i), omegas(j), kappa, lambdas(l))
                            ratio(i) = det4(m)/((alphas(i) + 1)**2* &
                                wedge_determinant(pairs(1, p), pairs(2, p), alphas(i), &
                                                  omegas(j), nus(k), lambdas(l)))
                        end do
                        ratio0 = ratio(1)
                        if (any(abs(ratio - ratio0) > 1.0e-10_wp*abs(ratio0))) ok = .false.
                    end do
                end do
            end do
        end do
        call t%check('characteristic functions: the 4 x 4 field determinant / (alpha+1)^2 '// &
                     'up to a constant', ok)
    end subroutine check_against_fields

    !> Free-free at omega = 2 pi (a crack): the exponents are k / 2, the lowest 1/2.
    subroutine check_crack()
        complex(wp), allocatable :: r(:)
        logical :: complete
        call wedge_roots(WEDGE_FREE, WEDGE_FREE, 2.0_wp*PI, 0.3_wp, 0.0_wp, 0.01_wp, 2.2_wp, &
                         1.0_wp, r, complete)
        call t%check('crack: the box counted whole', complete)
        call t%check_close('crack: lowest exponent 1/2', real(r(1)), 0.5_wp, 1.0e-12_wp)
        ! sin^2(2 pi alpha) = 0: 1/2 and 3/2 double (both symmetries), 1 left out, 2 double
        call t%check('crack: 1/2, 1/2, 3/2, 3/2, 2, 2', size(r) == 6)
    end subroutine check_crack

    !> Free-free at 3 pi / 2: Williams' 0.5444837 (symmetric) and 0.9085292 (antisymmetric),
    !> the roots of sin(3 pi alpha / 2) = -+ alpha, solved here by bisection.
    subroutine check_reentrant_corner()
        complex(wp), allocatable :: r(:)
        logical :: complete
        call wedge_roots(WEDGE_FREE, WEDGE_FREE, 1.5_wp*PI, 0.3_wp, 0.0_wp, 0.01_wp, 1.2_wp, &
                         1.0_wp, r, complete)
        call t%check('270 degrees: two exponents below 1.2', complete .and. size(r) == 2)
        call t%check_close('270 degrees: symmetric exponent', real(r(1)), &
                           bisect(-1, 0.4_wp, 0.7_wp), 1.0e-12_wp)
        call t%check_close('270 degrees: antisymmetric exponent', real(r(2)), &
                           bisect(1, 0.8_wp, 0.99_wp), 1.0e-12_wp)
        call t%check_close('270 degrees: 0.5444837 (Williams)', real(r(1)), 0.5444837_wp, &
                           1.0e-6_wp)
    end subroutine check_reentrant_corner

    !> The root of sin(3 pi x / 2) + sign x in [a0, b0] by bisection (a sign change there).
    real(wp) function bisect(sign, a0, b0)
        integer, intent(in) :: sign
        real(wp), intent(in) :: a0, b0
        real(wp) :: a, b, c
        integer :: it
        a = a0
        b = b0
        do it = 1, 200
            c = 0.5_wp*(a + b)
            if (reentrant(a, sign)*reentrant(c, sign) <= 0.0_wp) then
                b = c
            else
                a = c
            end if
        end do
        bisect = 0.5_wp*(a + b)
    end function bisect

    real(wp) function reentrant(x, sign)
        real(wp), intent(in) :: x
        integer, intent(in) :: sign
        reentrant = sin(1.5_wp*PI*x) + sign*x
    end function reentrant

    !> Clamped-free at 180 degrees: 4 kappa sin^2(pi alpha) = (kappa + 1)^2 gives alpha =
    !> 1/2 +- i ln(kappa) / (2 pi), the oscillating exponent of a crack face bonded to a
    !> rigid body.
    subroutine check_clamped_free_half_plane()
        complex(wp), allocatable :: r(:)
        logical :: complete
        real(wp) :: kappa
        kappa = 3.0_wp - 4.0_wp*0.3_wp
        call wedge_roots(WEDGE_CLAMPED, WEDGE_FREE, PI, 0.3_wp, 0.0_wp, 0.01_wp, 1.0_wp, &
                         1.0_wp, r, complete)
        call t%check('clamped-free 180: one pair below 1', complete .and. size(r) == 2)
        call t%check_close('clamped-free 180: real part 1/2', real(r(2)), 0.5_wp, 1.0e-12_wp)
        call t%check_close('clamped-free 180: imaginary part ln(kappa)/(2 pi)', aimag(r(2)), &
                           log(kappa)/(2.0_wp*PI), 1.0e-12_wp)
    end subroutine check_clamped_free_half_plane

    !> lambda = 0: contact is a symmetry plane, so contact-free at omega has the symmetric
    !> exponents of free-free at 2 omega (those of contact-clamped: clamped-clamped at 2
    !> omega); at 135 degrees Williams' 0.5444837, at 90 degrees 1 (no singularity).
    subroutine check_frictionless_contact_is_half_a_symmetric_wedge()
        complex(wp), allocatable :: contact(:), whole(:)
        logical :: complete, complete_whole
        call wedge_roots(WEDGE_CONTACT, WEDGE_FREE, 0.75_wp*PI, 0.2_wp, 0.0_wp, 0.01_wp, &
                         1.2_wp, 1.0_wp, contact, complete)
        call wedge_roots(WEDGE_FREE, WEDGE_FREE, 1.5_wp*PI, 0.2_wp, 0.0_wp, 0.01_wp, 1.2_wp, &
                         1.0_wp, whole, complete_whole)
        call t%check('frictionless 135: one exponent, the symmetric one of 270', &
                     complete .and. complete_whole .and. size(contact) == 1)
        call t%check_close('frictionless 135 = free-free 270 symmetric', real(contact(1)), &
                           real(whole(1)), 1.0e-12_wp)
        call wedge_roots(WEDGE_CONTACT, WEDGE_FREE, 0.5_wp*PI, 0.2_wp, 0.0_wp, 0.01_wp, &
                         1.5_wp, 1.0_wp, contact, complete)
        call t%check_close('frictionless 90: exponent 1', real(contact(1)), 1.0_wp, 1.0e-12_wp)
        call wedge_roots(WEDGE_CONTACT, WEDGE_CLAMPED, 0.5_wp*PI, 0.2_wp, 0.0_wp, 0.01_wp, &
                         1.5_wp, 1.0_wp, contact, complete)
        call t%check_close('frictionless contact-clamped 90: exponent 1', real(contact(1)), &
                           1.0_wp, 1.0e-12_wp)
    end subroutine check_frictionless_contact_is_half_a_symmetric_wedge

    !> Contact-free at 180 degrees is the edge of a flat rigid punch sliding on a half-plane:
    !> cot(pi alpha) = -lambda beta, alpha = 1/2 + atan(lambda beta) / pi (Muskhelishvili's
    !> and Galin's sliding punch; the pressure ~ r^(alpha - 1)), for both signs of lambda.
    subroutine check_sliding_punch_edge()
        complex(wp), allocatable :: r(:)
        logical :: complete
        real(wp) :: beta, lambda
        integer :: k
        beta = (1.0_wp - 2.0_wp*0.25_wp)/(2.0_wp - 2.0_wp*0.25_wp)
        do k = -1, 1, 2
            lambda = 2.0_wp*k
            call wedge_roots(WEDGE_CONTACT, WEDGE_FREE, PI, 0.25_wp, lambda, 0.01_wp, 0.99_wp, &
                             1.0_wp, r, complete)
            call t%check('sliding punch: one exponent in (0, 1)', complete .and. size(r) == 1)
            call t%check_close('sliding punch: 1/2 + atan(lambda beta)/pi', real(r(1)), &
                               0.5_wp + atan(lambda*beta)/PI, 1.0e-12_wp)
        end do
    end subroutine check_sliding_punch_edge

    !> Contact-free: at contact_free_crossing(omega) the function and its derivative vanish
    !> at alpha = 0 (a double root), and the real exponent near 0 has the sign of lambda -
    !> crossing on either side (positive above, negative below), whatever nu.
    subroutine check_contact_free_crossing()
        complex(wp), allocatable :: above(:), below(:)
        logical :: c1, c2
        real(wp) :: omega, lambda, h
        omega = 0.75_wp*PI
        lambda = contact_free_crossing(omega)
        call t%check_close('contact-free 135: crossing at -(3 pi/2 - 1)', lambda, &
                           -(1.5_wp*PI - 1.0_wp), 1.0e-14_wp)
        h = 1.0e-6_wp
        call t%check('contact-free: derivative at 0 vanishes at the crossing', &
                     abs(wedge_determinant(WEDGE_CONTACT, WEDGE_FREE, cmplx(h, 0.0_wp, wp), &
                         omega, 0.1_wp, lambda)) <= 1.0e-10_wp)
        call wedge_roots(WEDGE_CONTACT, WEDGE_FREE, omega, 0.1_wp, lambda + 0.2_wp, -0.5_wp, &
                         0.5_wp, 0.5_wp, above, c1)
        call wedge_roots(WEDGE_CONTACT, WEDGE_FREE, omega, 0.1_wp, lambda - 0.2_wp, -0.5_wp, &
                         0.5_wp, 0.5_wp, below, c2)
        call t%check('contact-free: one real exponent near 0 on each side', c1 .and. c2 .and. &
                     size(above) == 1 .and. size(below) == 1)
        call t%check('contact-free: positive above the crossing, negative below', &
                     real(above(1)) > 0.0_wp .and. real(below(1)) < 0.0_wp)
    end subroutine check_contact_free_crossing

    !> Contact-clamped: a real exponent negative below contact_clamped_crossing turns
    !> positive above it (90 degrees, nu = 0.3: kappa pi / 2 = 2.8274).
    subroutine check_contact_clamped_crossing()
        complex(wp), allocatable :: above(:), below(:)
        logical :: c1, c2
        real(wp) :: lambda
        lambda = contact_clamped_crossing(0.5_wp*PI, 0.3_wp)
        call t%check_close('contact-clamped 90: crossing at kappa pi / 2', lambda, &
                           1.8_wp*PI/2.0_wp, 1.0e-14_wp)
        call wedge_roots(WEDGE_CONTACT, WEDGE_CLAMPED, 0.5_wp*PI, 0.3_wp, lambda - 0.1_wp, &
                         -0.2_wp, 0.2_wp, 0.5_wp, below, c1)
        call wedge_roots(WEDGE_CONTACT, WEDGE_CLAMPED, 0.5_wp*PI, 0.3_wp, lambda + 0.01_wp, &
                         -0.2_wp, 0.2_wp, 0.5_wp, above, c2)
        call t%check('contact-clamped: one real exponent near 0 on each side', c1 .and. c2 &
                     .and. size(above) == 1 .and. size(below) == 1)
        call t%check('contact-clamped: negative below the crossing, positive above', &
                     real(below(1)) < 0.0_wp .and. real(above(1)) > 0.0_wp)
    end subroutine check_contact_clamped_crossing

    !> The quarter plane of the reference scene (contact-free, 90 degrees): the exponent
    !> that is 1 at lambda = 0 falls to 0 at lambda = -pi/2 (contact_free_crossing) and below;
    !> every root is a root (|d| at it is round-off against the terms' size).
    subroutine check_quarter_plane_table()
        complex(wp), allocatable :: r(:)
        logical :: complete
        integer :: k
        real(wp) :: lambdas(4) = [-1.0_wp, -2.0_wp, 1.0_wp, 5.0_wp]
        call t%check_close('quarter plane: crossing at -pi/2', &
                           contact_free_crossing(0.5_wp*PI), -0.5_wp*PI, 1.0e-14_wp)
        do k = 1, size(lambdas)
            call wedge_roots(WEDGE_CONTACT, WEDGE_FREE, 0.5_wp*PI, 0.3_wp, lambdas(k), &
                             -1.5_wp, 3.0_wp, 3.0_wp, r, complete)
            call t%check('quarter plane: the box counted whole', complete)
            call t%check('quarter plane: roots of the function', all(abs(wedge_determinant( &
                WEDGE_CONTACT, WEDGE_FREE, r, 0.5_wp*PI, 0.3_wp, lambdas(k))) <= 1.0e-10_wp))
        end do
    end subroutine check_quarter_plane_table

    !> A 225-degree contact-free end (a random body's, nu = 0.1225) just beyond its crossing,
    !> in the box moving_side searches: no grid of starting points accounts for every root
    !> the argument principle counts there, and Newton's iterates from some of them run far
    !> up the imaginary axis (sin(2 alpha omega) overflowed under Debug's traps). The search
    !> still returns, incomplete, with roots that are roots (|d| at round-off of the terms,
    !> which are O(1) in the box) and inside the box.
    subroutine check_reflex_contact_corner()
        complex(wp), allocatable :: roots(:)
        logical :: complete
        real(wp) :: omega, lambda
        integer :: towards
        omega = 225.374_wp*PI/180.0_wp
        do towards = -1, 1, 2
            lambda = contact_free_crossing(omega) - towards*0.1_wp
            call wedge_roots(WEDGE_CONTACT, WEDGE_FREE, omega, 0.1225_wp, lambda, -0.999_wp, &
                             1.5_wp, 0.5_wp, roots, complete)
            call t%check('225 degrees, lambda = crossing '//trim(merge('+ 0.1', '- 0.1', &
                         towards < 0))//': the roots returned are roots inside the box', &
                         all(abs(wedge_determinant(WEDGE_CONTACT, WEDGE_FREE, roots, omega, &
                                 0.1225_wp, lambda)) <= 1.0e-8_wp) .and. &
                         all(real(roots) > -0.999_wp .and. real(roots) < 1.5_wp .and. &
                             abs(aimag(roots)) < 0.5_wp))
        end do
    end subroutine check_reflex_contact_corner
end program test_wedge_exponents
