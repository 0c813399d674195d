! SPDX-License-Identifier: MIT
!> pencil_tracking: profiles are a property of the traction, not of the mesh (the same
!> singular traction on a uniform and on a graded mesh gives nearly the same profile); the
!> match follows the mode, not the nearest value; a geometric sequence is converging with its
!> own factor and a bar that covers its limit; a slow geometric sequence is moving, with
!> Aitken's limit exact; an erratic one is moving with no limit; a mode whose forces gather
!> at an end is seen concentrating there.
program test_pencil_tracking
    use kinds, only: wp
    use pencil_tracking, only: N_PROFILE_BINS, profile_breakpoints, pencil_profile_bins, &
                               profile_similarity, pencil_value_t, level_values_t, &
                               track_verdict_t, match_value, track_chain, classify_chain, &
                               profile_mean, profile_end_shares, TRACK_SHORT, &
                               TRACK_CONVERGING, TRACK_MOVING
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t

    t%name = 'test_pencil_tracking'
    call check_breakpoints()
    call check_profile_mesh_independent()
    call check_profile_sign_and_scale()
    call check_match_follows_the_mode()
    call check_chain()
    call check_converging()
    call check_moving_geometric()
    call check_moving_erratic()
    call check_floor()
    call check_concentrating()
    call t%report()

contains

    subroutine check_breakpoints()
        real(wp) :: b(N_PROFILE_BINS + 1)
        b = profile_breakpoints()
        call t%check('breakpoints: from 0 to 1, increasing, symmetric', abs(b(1)) <= 0.0_wp &
                     .and. abs(b(size(b)) - 1.0_wp) <= 0.0_wp .and. &
                     all(b(2:) > b(:size(b) - 1)) .and. &
                     all(abs(b + b(size(b):1:-1) - 1.0_wp) <= 1.0e-15_wp))
        call t%check_close('breakpoints: the smallest bin is 2^-13', b(2), 2.0_wp**(-13), &
                           1.0e-15_wp)
    end subroutine check_breakpoints

    !> The nodal forces of P1 hats, x_a = int g phi_a, of g(s) = s^-0.4 + 1 on [0, 1]
    !> (integrable, singular at s = 0 like a corner traction), on 4000 uniform cells and on
    !> 60 cells graded by 2 toward s = 0: the profiles (bin integrals of g up to the cells the
    !> bin ends cut) agree to better than 0.99, and each agrees with the exact bin integrals.
    subroutine check_profile_mesh_independent()
        real(wp) :: uniform(4001), graded(61)
        real(wp) :: exact(N_PROFILE_BINS), b(N_PROFILE_BINS + 1)
        integer :: k
        uniform = [(real(k, wp)/4000.0_wp, k=0, 4000)]
        graded = [0.0_wp, (2.0_wp**(-k), k=40, 1, -1), (0.5_wp + real(k, wp)/40.0_wp, k=1, 20)]
        b = profile_breakpoints()
        do k = 1, N_PROFILE_BINS
            exact(k) = antiderivative(b(k + 1)) - antiderivative(b(k))
        end do
        exact = exact/sum(abs(exact))
        call t%check('profile: uniform and graded meshes alike', profile_similarity( &
            pencil_profile_bins(uniform, hat_forces(uniform)), &
            pencil_profile_bins(graded, hat_forces(graded))) > 0.99_wp)
        call t%check('profile: graded mesh against the exact bin integrals', &
                     profile_similarity(pencil_profile_bins(graded, hat_forces(graded)), &
                                        exact) > 0.99_wp)
        call t%check_close('profile: moduli sum to 1', &
                           sum(abs(pencil_profile_bins(graded, hat_forces(graded)))), 1.0_wp, &
                           1.0e-14_wp)
    end subroutine check_profile_mesh_independent

    pure real(wp) function antiderivative(s)
        real(wp), intent(in) :: s
        antiderivative = s**0.6_wp/0.6_wp + s
    end function antiderivative

    !> x_a = int g phi_a for the hats of the nodes z (exact for the linear part of each cell:
    !> Gauss-Jacobi would be exact; 40-point midpoint sums per cell are accurate enough for
    !> profiles compared to 1e-2, except the singular first cell, integrated exactly).
    pure function hat_forces(z) result(x)
        real(wp), intent(in) :: z(:)
        real(wp) :: x(size(z)), h, s, g
        integer :: c, q
        x = 0.0_wp
        do c = 1, size(z) - 1
            h = z(c + 1) - z(c)
            if (c == 1) then
                ! int_0^h (s^-0.4 + 1) (1 - s/h) ds and ... s/h ds, in closed form
                x(1) = x(1) + h**0.6_wp/0.6_wp - h**0.6_wp/1.6_wp + 0.5_wp*h
                x(2) = x(2) + h**0.6_wp/1.6_wp + 0.5_wp*h
                cycle
            end if
            do q = 1, 40
                s = z(c) + (q - 0.5_wp)*h/40.0_wp
                g = s**(-0.4_wp) + 1.0_wp
                x(c) = x(c) + g*(z(c + 1) - s)/h*h/40.0_wp
                x(c + 1) = x(c + 1) + g*(s - z(c))/h*h/40.0_wp
            end do
        end do
    end function hat_forces

    subroutine check_profile_sign_and_scale()
        real(wp) :: s(5), x(5), a(N_PROFILE_BINS), b(N_PROFILE_BINS)
        s = [0.1_wp, 0.3_wp, 0.5_wp, 0.7_wp, 0.9_wp]
        x = [1.0_wp, -2.0_wp, 3.0_wp, 0.5_wp, 0.0_wp]
        a = pencil_profile_bins(s, x)
        b = pencil_profile_bins(s, -7.0_wp*x)
        call t%check('profile: independent of the sign and scale of x', &
                     maxval(abs(a - b)) <= 1.0e-15_wp)
        call t%check('profile: largest bin positive', a(maxloc(abs(a), dim=1)) > 0.0_wp)
        call t%check('profile: zero forces give a zero profile', &
                     maxval(abs(pencil_profile_bins(s, 0.0_wp*x))) <= 0.0_wp)
    end subroutine check_profile_sign_and_scale

    !> Level k - 1 holds a value at 4.35 with its mode at the s = 0 end; level k a value at
    !> 4.3501 with the same mode and a closer one at 4.3500005 whose forces alternate in the
    !> middle: the match is the first, and a value with no alike profile matches nothing.
    subroutine check_match_follows_the_mode()
        type(pencil_value_t) :: previous, candidates(2), stranger
        previous = value_at(4.35_wp, end_mode(0.9_wp))
        candidates(1) = value_at(4.3500005_wp, zigzag_mode())
        candidates(2) = value_at(4.3501_wp, end_mode(0.88_wp))
        call t%check('match: the alike mode, not the nearest value', &
                     match_value(previous, candidates) == 2)
        stranger = value_at(4.351_wp, zigzag_mode())
        call t%check('match: no alike mode, no match', match_value(previous, [stranger]) == 0)
        call t%check('match: too far in value, no match', &
                     match_value(previous, [value_at(6.0_wp, end_mode(0.9_wp))]) == 0)
    end subroutine check_match_follows_the_mode

    subroutine check_chain()
        type(level_values_t) :: levels(4)
        integer, allocatable :: chain(:)
        levels(1)%values = [value_at(4.2_wp, end_mode(0.85_wp))]
        levels(2)%values = [value_at(3.7_wp, zigzag_mode())]   ! no alike mode: the chain stops
        levels(3)%values = [value_at(4.36_wp, end_mode(0.9_wp)), value_at(3.6_wp, zigzag_mode())]
        levels(4)%values = [value_at(3.5_wp, zigzag_mode()), value_at(4.353_wp, end_mode(0.9_wp))]
        allocate (chain(0))   ! (gfortran 12 warns of an unallocated one at -O3)
        chain = track_chain(levels, 2)
        call t%check('chain: back to level 3 only', size(chain) == 2 .and. chain(1) == 1)
        chain = track_chain(levels, 1)
        call t%check('chain: the zig-zag mode from level 2 on', size(chain) == 3)
    end subroutine check_chain

    !> v_k = 4 + 0.3 * 0.2^k (k = 1..6): converging, factor 0.2, bar >= the true error
    !> |v_6 - 4| / 4 and at most 3 / (1 - 0.2) times it; the limit 4 to round-off.
    subroutine check_converging()
        type(track_verdict_t) :: v
        real(wp) :: values(6), error
        integer :: k
        values = [(4.0_wp + 0.3_wp*0.2_wp**k, k=1, 6)]
        v = classify_chain(values, spread(end_mode(0.9_wp), 2, 6))
        error = abs(values(6) - 4.0_wp)/4.0_wp
        call t%check('converging: verdict', v%kind == TRACK_CONVERGING)
        call t%check_close('converging: factor 0.2', v%rate, 0.2_wp, 1.0e-3_wp)
        call t%check('converging: bar covers the error, within 3.75 times',  &
                     v%bar >= error .and. v%bar <= 3.76_wp*error)
        call t%check('converging: limit', v%has_limit .and. abs(v%limit - 4.0_wp) <= 1.0e-12_wp)
        v = classify_chain(values(1:3), spread(end_mode(0.9_wp), 2, 3))
        call t%check('three values: too short', v%kind == TRACK_SHORT)
    end subroutine check_converging

    !> v_k = -3 - 0.4 * 0.8^k: moving (factor 0.8 > 0.5), Aitken's limit -3 exactly.
    subroutine check_moving_geometric()
        type(track_verdict_t) :: v
        real(wp) :: values(7)
        integer :: k
        values = [(-3.0_wp - 0.4_wp*0.8_wp**k, k=1, 7)]
        v = classify_chain(values, spread(end_mode(0.9_wp), 2, 7))
        call t%check('slow geometric: moving', v%kind == TRACK_MOVING)
        call t%check_close('slow geometric: factor 0.8', v%rate, 0.8_wp, 2.0e-2_wp)
        call t%check('slow geometric: limit -3 (Aitken)', &
                     v%has_limit .and. abs(v%limit + 3.0_wp) <= 1.0e-12_wp)
    end subroutine check_moving_geometric

    !> The issue's chamfer lambda+ over levels: 8.41, 12.9, 18.4, 2.7, 9.1: no pattern.
    subroutine check_moving_erratic()
        type(track_verdict_t) :: v
        v = classify_chain([8.41_wp, 12.9_wp, 18.4_wp, 2.7_wp, 9.1_wp], &
                           spread(end_mode(0.9_wp), 2, 5))
        call t%check('erratic: moving, no limit', v%kind == TRACK_MOVING .and. .not. v%has_limit)
    end subroutine check_moving_erratic

    !> Values that converge geometrically to 2 and then wander at 1e-12 relative, with a
    !> round-off bound of 1e-12: converged at the floor, the bar above the wandering; without
    !> the bound the wandering is movement.
    subroutine check_floor()
        type(track_verdict_t) :: v
        real(wp) :: values(7)
        values = [2.1_wp, 2.01_wp, 2.001_wp, 2.0_wp + 1.0e-12_wp, 2.0_wp - 2.0e-12_wp, &
                  2.0_wp + 1.5e-12_wp, 2.0_wp]
        v = classify_chain(values, spread(end_mode(0.9_wp), 2, 7), 1.0e-12_wp)
        call t%check('floor: converged', v%kind == TRACK_CONVERGING)
        call t%check('floor: bar covers the wandering, not the early changes', &
                     v%bar >= 1.75e-12_wp .and. v%bar <= 3.0e-11_wp)
        v = classify_chain(values, spread(end_mode(0.9_wp), 2, 7))
        call t%check('no round-off bound: moving', v%kind == TRACK_MOVING)
    end subroutine check_floor

    !> Profiles whose share at s = 0 grows level by level: concentrating at s = 0, mean near 0.
    subroutine check_concentrating()
        type(track_verdict_t) :: v
        real(wp) :: profiles(N_PROFILE_BINS, 4)
        integer :: k
        do k = 1, 4
            profiles(:, k) = end_mode(0.6_wp + 0.1_wp*k)
        end do
        v = classify_chain([1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp], profiles)
        call t%check('concentrating at s = 0', v%concentrating(1) .and. .not. v%concentrating(2))
        call t%check('concentrating: end share and mean', v%end_share(1) >= 0.99_wp .and. &
                     v%where < 0.01_wp .and. abs(profile_mean(profiles(:, 4)) - v%where) <= 0.0_wp)
        call t%check('end shares of a middle mode', &
                     all(profile_end_shares(zigzag_mode()) <= 0.0_wp))
    end subroutine check_concentrating

    pure function value_at(lambda, profile) result(v)
        real(wp), intent(in) :: lambda, profile(N_PROFILE_BINS)
        type(pencil_value_t) :: v
        v%lambda = lambda
        v%profile = profile
    end function value_at

    !> Forces gathering at s = 0 geometrically: bin k (from the end) holds c^k.
    pure function end_mode(c) result(profile)
        real(wp), intent(in) :: c
        real(wp) :: profile(N_PROFILE_BINS)
        integer :: k
        profile = 0.0_wp
        do k = 1, 12
            profile(k) = (1.0_wp - c)**(k - 1)
        end do
        profile = profile/sum(abs(profile))
    end function end_mode

    !> Forces alternating in sign over the middle bins.
    pure function zigzag_mode() result(profile)
        real(wp) :: profile(N_PROFILE_BINS)
        integer :: k
        profile = 0.0_wp
        do k = 10, 17
            profile(k) = (-1.0_wp)**k
        end do
        profile = profile/sum(abs(profile))
    end function zigzag_mode
end program test_pencil_tracking
