! SPDX-License-Identifier: MIT
!> The singular exponents of a plane-strain elastic wedge 0 < theta < omega: the alpha of the
!> displacement fields u = r^alpha f(theta) that satisfy given conditions on both faces
!> (Williams' eigenproblem in the angle). The near face (theta = 0) is free, clamped or in
!> frictional contact; the far face (theta = omega) free or clamped. Contact is the limit
!> condition of a pencil threshold of nceig (model.md section 7): no normal displacement,
!> u_theta = 0, and tangential traction -lambda times the normal one, sigma_r_theta =
!> -lambda sigma_theta_theta, with the tangent t = -e_r (pointing to the apex along the
!> face). At an end of Gamma_C of a body this is lambda itself at the end that t points to,
!> and -lambda at the other end (a mirror image maps lambda to -lambda): docs/thresholds.md.
!>
!> With the Airy function r^(alpha+1) F(theta), F = A cos((alpha+1) theta) + B sin((alpha+1)
!> theta) + C cos((alpha-1) theta) + D sin((alpha-1) theta), the four face conditions are a
!> 4 x 4 system whose determinant is (alpha + 1)^2 times the function `wedge_determinant`
!> returns (kappa = 3 - 4 nu):
!>   free-free        sin^2(alpha w) - alpha^2 sin^2 w
!>   clamped-clamped  kappa^2 sin^2(alpha w) - alpha^2 sin^2 w
!>   clamped-free     4 kappa sin^2(alpha w) - (kappa + 1)^2 + 4 alpha^2 sin^2 w
!>   contact-free     (kappa+1) (sin 2 alpha w + alpha sin 2w)
!>                    + 2 lambda (alpha (2 alpha + kappa + 1) sin^2 w + (kappa - 1) sin^2 alpha w)
!>   contact-clamped  (kappa+1) (alpha sin 2w - kappa sin 2 alpha w)
!>                    + 2 lambda (alpha (2 alpha + kappa + 1) sin^2 w
!>                                - kappa (kappa - 1) sin^2 alpha w)
!> (tests/numerics/test_wedge_exponents.f90 checks each against the 4 x 4 system built from
!> the fields). alpha = 0 is a root of all but clamped-free: the translations of a free or
!> contact face (for contact-clamped and clamped-clamped an artefact of the basis, whose
!> stresses vanish at alpha = 0); free-free also has alpha = 1, the rotation. wedge_roots
!> leaves these out. A field has finite energy near the apex when Re alpha > 0.
module wedge_exponents
    use kinds, only: wp
    use sorting, only: sort_index
    implicit none
    private
    public :: wedge_determinant, wedge_roots, contact_free_crossing, contact_clamped_crossing
    public :: WEDGE_FREE, WEDGE_CLAMPED, WEDGE_CONTACT

    integer, parameter :: WEDGE_FREE = 1, WEDGE_CLAMPED = 2, WEDGE_CONTACT = 3
    real(wp), parameter :: PI = acos(-1.0_wp)
    !> starting points of Newton's method: a grid of this spacing over the search box
    real(wp), parameter :: GRID_STEP = 0.125_wp
    !> roots closer than this are one (a double root converges to within sqrt(eps) only)
    real(wp), parameter :: SAME_ROOT = 1.0e-6_wp

contains

    !> The characteristic function of the wedge (module comment) and its derivative in alpha.
    pure subroutine characteristic(near, far, alpha, omega, poisson, lambda, d, d_alpha)
        integer, intent(in) :: near, far
        complex(wp), intent(in) :: alpha
        real(wp), intent(in) :: omega, poisson, lambda
        complex(wp), intent(out) :: d, d_alpha
        real(wp) :: kappa, s2
        complex(wp) :: sa, s2a, c2a
        kappa = 3.0_wp - 4.0_wp*poisson
        s2 = sin(omega)**2
        sa = sin(alpha*omega)
        s2a = sin(2.0_wp*alpha*omega)
        c2a = cos(2.0_wp*alpha*omega)
        d = 0.0_wp
        d_alpha = 0.0_wp
        select case (near*10 + far)
        case (WEDGE_FREE*10 + WEDGE_FREE)
            d = sa**2 - alpha**2*s2
            d_alpha = omega*s2a - 2.0_wp*alpha*s2
        case (WEDGE_CLAMPED*10 + WEDGE_CLAMPED)
            d = kappa**2*sa**2 - alpha**2*s2
            d_alpha = kappa**2*omega*s2a - 2.0_wp*alpha*s2
        case (WEDGE_CLAMPED*10 + WEDGE_FREE, WEDGE_FREE*10 + WEDGE_CLAMPED)
            d = 4.0_wp*kappa*sa**2 - (kappa + 1.0_wp)**2 + 4.0_wp*alpha**2*s2
            d_alpha = 4.0_wp*kappa*omega*s2a + 8.0_wp*alpha*s2
        case (WEDGE_CONTACT*10 + WEDGE_FREE)
            d = (kappa + 1.0_wp)*(s2a + alpha*sin(2.0_wp*omega)) + 2.0_wp*lambda* &
                (alpha*(2.0_wp*alpha + kappa + 1.0_wp)*s2 + (kappa - 1.0_wp)*sa**2)
            d_alpha = (kappa + 1.0_wp)*(2.0_wp*omega*c2a + sin(2.0_wp*omega)) + 2.0_wp*lambda* &
                      ((4.0_wp*alpha + kappa + 1.0_wp)*s2 + (kappa - 1.0_wp)*omega*s2a)
        case (WEDGE_CONTACT*10 + WEDGE_CLAMPED)
            d = (kappa + 1.0_wp)*(alpha*sin(2.0_wp*omega) - kappa*s2a) + 2.0_wp*lambda* &
                (alpha*(2.0_wp*alpha + kappa + 1.0_wp)*s2 - kappa*(kappa - 1.0_wp)*sa**2)
            d_alpha = (kappa + 1.0_wp)*(sin(2.0_wp*omega) - 2.0_wp*kappa*omega*c2a) + &
                      2.0_wp*lambda*((4.0_wp*alpha + kappa + 1.0_wp)*s2 - &
                                     kappa*(kappa - 1.0_wp)*omega*s2a)
        end select
    end subroutine characteristic

    !> The characteristic function of the wedge with faces `near` (theta = 0: WEDGE_FREE,
    !> WEDGE_CLAMPED or WEDGE_CONTACT) and `far` (theta = omega: WEDGE_FREE or
    !> WEDGE_CLAMPED), opening `omega` (radians, 0 < omega <= 2 pi), Poisson's ratio
    !> `poisson` (plane strain) and, for contact, the friction ratio `lambda` of the near
    !> face (see the module comment); zero exactly at the exponents. 0 for a pair of faces
    !> not listed.
    elemental complex(wp) function wedge_determinant(near, far, alpha, omega, poisson, lambda) &
        result(d)
        integer, intent(in) :: near, far
        complex(wp), intent(in) :: alpha
        real(wp), intent(in) :: omega, poisson, lambda
        complex(wp) :: d_alpha
        call characteristic(near, far, alpha, omega, poisson, lambda, d, d_alpha)
    end function wedge_determinant

    !> Every exponent alpha of the wedge with re_min < Re alpha < re_max and |Im alpha| <
    !> im_max, ascending by real part then imaginary part, each as often as its multiplicity
    !> (the number of times the characteristic function winds around 0 on a small circle
    !> about it), leaving out alpha = 0 (and alpha = 1 of free-free; module comment).
    !> `complete` says whether the argument principle on the box's boundary counts as many
    !> roots as were found (plus those left out): false means some may be missing, or one
    !> lies within 1e-3 of the boundary.
    subroutine wedge_roots(near, far, omega, poisson, lambda, re_min, re_max, im_max, &
                           roots, complete)
        integer, intent(in) :: near, far
        real(wp), intent(in) :: omega, poisson, lambda, re_min, re_max, im_max
        complex(wp), allocatable, intent(out) :: roots(:)
        logical, intent(out) :: complete
        complex(wp), allocatable :: found(:)
        integer, allocatable :: multiplicity(:)
        complex(wp) :: z, corners(4)
        real(wp) :: step, x, y
        integer :: i, j, k, n_total, refinements

        corners = [cmplx(re_min, -im_max, wp), cmplx(re_max, -im_max, wp), &
                   cmplx(re_max, im_max, wp), cmplx(re_min, im_max, wp)]
        n_total = winding(corners)
        step = GRID_STEP
        do refinements = 1, 4
            allocate (found(0))
            y = 0.0_wp
            do while (y <= im_max + 0.5_wp)
                x = re_min - 0.5_wp
                do while (x <= re_max + 0.5_wp)
                    call newton(cmplx(x, y, wp), z, i)
                    if (i == 0) then
                        call add_root(z)
                        call add_root(conjg(z))
                    end if
                    x = x + step
                end do
                y = y + step
            end do
            ! the trivial roots (alpha = 0; alpha = 1 for free-free) are counted, then left out
            allocate (multiplicity(size(found)))
            do k = 1, size(found)
                multiplicity(k) = max(1, winding(found(k) + 1.0e-3_wp*[(1.0_wp, -1.0_wp), &
                    (1.0_wp, 1.0_wp), (-1.0_wp, 1.0_wp), (-1.0_wp, -1.0_wp)]))
            end do
            complete = sum(multiplicity) == n_total
            ! the last grid's roots are kept, complete or not
            if (complete .or. refinements == 4) exit
            step = 0.5_wp*step
            deallocate (found, multiplicity)
        end do
        allocate (roots(0))
        do k = 1, size(found)
            if (is_trivial(found(k))) cycle
            roots = [roots, [(found(k), j=1, multiplicity(k))]]
        end do
        call sort_roots(roots)

    contains

        !> The number of roots in the polygon `path` (closed, anticlockwise), from the change
        !> of arg d along its sides, each cut until arg changes by less than 0.5 per piece.
        integer function winding(path) result(n)
            complex(wp), intent(in) :: path(:)
            real(wp) :: total
            integer :: s
            total = 0.0_wp
            do s = 1, size(path)
                total = total + arg_change(path(s), path(mod(s, size(path)) + 1), 0)
            end do
            n = nint(total/(2.0_wp*PI))
        end function winding

        recursive real(wp) function arg_change(a, b, depth) result(change)
            complex(wp), intent(in) :: a, b
            integer, intent(in) :: depth
            complex(wp) :: da, db
            da = wedge_determinant(near, far, a, omega, poisson, lambda)
            db = wedge_determinant(near, far, b, omega, poisson, lambda)
            change = 0.0_wp
            if (abs(da) <= 0.0_wp .or. abs(db) <= 0.0_wp) return   ! a root on the path
            change = atan2(aimag(db/da), real(db/da))
            if ((abs(change) > 0.5_wp .or. depth < 4) .and. depth < 40) &
                change = arg_change(a, 0.5_wp*(a + b), depth + 1) + &
                         arg_change(0.5_wp*(a + b), b, depth + 1)
        end function arg_change

        !> Newton's method from z0; fails (1) without convergence or outside the box.
        subroutine newton(z0, z, failed)
            complex(wp), intent(in) :: z0
            complex(wp), intent(out) :: z
            integer, intent(out) :: failed
            complex(wp) :: d, d_alpha, dz
            integer :: it
            z = z0
            failed = 1
            do it = 1, 100
                call characteristic(near, far, z, omega, poisson, lambda, d, d_alpha)
                if (abs(d_alpha) <= tiny(1.0_wp)) return
                dz = d/d_alpha
                z = z - dz
                ! far outside the box (sin 2 alpha omega would overflow beyond 700 / omega)
                if (abs(z) > 1.0e3_wp .or. abs(aimag(z))*omega > 300.0_wp) return
                if (abs(dz) <= 1.0e-14_wp*(1.0_wp + abs(z))) then
                    failed = 0
                    exit
                end if
            end do
            if (failed /= 0) then   ! slow linear convergence at a multiple root
                call characteristic(near, far, z, omega, poisson, lambda, d, d_alpha)
                if (abs(d) <= 1.0e-20_wp*(1.0_wp + abs(z))**2) failed = 0
            end if
            if (real(z) <= re_min .or. real(z) >= re_max .or. abs(aimag(z)) >= im_max) failed = 1
        end subroutine newton

        subroutine add_root(z)
            complex(wp), intent(in) :: z
            complex(wp) :: w
            w = z
            if (abs(aimag(w)) <= SAME_ROOT) w = cmplx(real(w), 0.0_wp, wp)
            if (any(abs(found - w) <= SAME_ROOT*(1.0_wp + abs(w)))) return
            found = [found, w]
        end subroutine add_root

        logical function is_trivial(z)
            complex(wp), intent(in) :: z
            is_trivial = abs(z) <= SAME_ROOT .or. (near == WEDGE_FREE .and. far == WEDGE_FREE &
                         .and. abs(z - 1.0_wp) <= SAME_ROOT)
        end function is_trivial
    end subroutine wedge_roots

    !> Ascending by real part, then imaginary part: two stable sorts (sorting: sort_index),
    !> the second key first.
    pure subroutine sort_roots(z)
        complex(wp), intent(inout) :: z(:)
        z = z(sort_index(aimag(z)))
        z = z(sort_index(real(z)))
    end subroutine sort_roots

    !> The lambda of a contact-free wedge of opening omega at which a real exponent passes
    !> through alpha = 0 (a double root there): -(2 omega + sin 2 omega) / (2 sin^2 omega),
    !> whatever nu. As lambda falls below it the exponent turns negative (an infinite-energy
    !> field); it is the only lambda at which an exponent crosses Re alpha = 0 (on that line
    !> the function is purely imaginary when its real-part coefficient of lambda, -2 tau^2
    !> sin^2 w - (kappa - 1) sinh^2 tau w, is not 0, which needs tau = 0). None for omega = pi
    !> or 2 pi (returns -huge).
    elemental real(wp) function contact_free_crossing(omega) result(lambda)
        real(wp), intent(in) :: omega
        if (abs(sin(omega)) <= 1.0e-12_wp) then
            lambda = -huge(1.0_wp)
        else
            lambda = -(2.0_wp*omega + sin(2.0_wp*omega))/(2.0_wp*sin(omega)**2)
        end if
    end function contact_free_crossing

    !> The lambda of a contact-clamped wedge at which a real exponent reaches alpha = 0:
    !> (2 kappa omega - sin 2 omega) / (2 sin^2 omega), kappa = 3 - 4 nu. At 90 degrees the
    !> exponent is negative below it and positive above; at 60 degrees it is positive on
    !> both sides, touching 0 there before it leaves the real axis (scripts/dev/wedge_table);
    !> huge for omega = pi or 2 pi.
    elemental real(wp) function contact_clamped_crossing(omega, poisson) result(lambda)
        real(wp), intent(in) :: omega, poisson
        if (abs(sin(omega)) <= 1.0e-12_wp) then
            lambda = huge(1.0_wp)
        else
            lambda = (2.0_wp*(3.0_wp - 4.0_wp*poisson)*omega - sin(2.0_wp*omega))/ &
                     (2.0_wp*sin(omega)**2)
        end if
    end function contact_clamped_crossing
end module wedge_exponents
