! SPDX-License-Identifier: MIT
!> moving_side: what an hp threshold run reports of a side that does not converge. The ends of
!> Gamma_C of the unit square (contact at the bottom, t = (-1, 0)) are its corners, 90
!> degrees, beside a free or a clamped side as the scene says; a value that moves
!> geometrically over the levels with its vector gathering at an end is followed over every
!> level, called moving with its factor and Aitken's limit (exact for a geometric sequence),
!> placed at that end, and the wedge there is judged with the side's value at the end t
!> points to and its mirror image at the other (docs/thresholds.md): past the contact-free
!> crossing -pi/2 of a 90-degree corner the exponent is negative (at -4 and nu = 0.3 below
!> -1, outside the exponents searched, and still past the crossing); a clamped corner's
!> crossing is positive; a 180-degree end has none. Two values of different shapes that
!> trade places from level to level are said to, not called too short.
program test_moving_side
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use fixtures, only: square_scene, problem_of
    use run_config, only: config_t
    use problem, only: problem_t
    use pencil_tracking, only: N_PROFILE_BINS, level_values_t, TRACK_MOVING, TRACK_SHORT
    use wedge_exponents, only: WEDGE_FREE, WEDGE_CLAMPED, contact_free_crossing, &
                               contact_clamped_crossing
    use moving_side, only: contact_ends_t, contact_ends, moving_side_t, track_side, &
                           moving_words, past_crossing_end, end_words
    implicit none
    real(wp), parameter :: PI = acos(-1.0_wp)
    type(test_suite_t) :: t

    t%name = 'test_moving_side'
    call check_square_ends()
    call check_geometric_at_an_end()
    call check_wedge_sides()
    call check_alternating()
    call check_past_crossing_end()
    call t%report()

contains

    !> The ends of the unit square's contact side: end 1 at (1, 0) (t points away from it),
    !> end 2 at (0, 0), both 90 degrees; beside free sides, or a clamped left side.
    subroutine check_square_ends()
        type(config_t) :: config
        type(problem_t) :: prob
        type(status_t) :: stat
        type(contact_ends_t) :: ends
        call square_scene(2, 'p1', 'right', config)
        call problem_of(config, prob, stat)
        call t%check('square: problem built', stat%ok())
        if (.not. stat%ok()) return
        ends = contact_ends(prob)
        call t%check('square: end 1 at (1, 0), end 2 at (0, 0)', &
                     all(abs(ends%point(:, 1) - [1.0_wp, 0.0_wp]) <= 1.0e-14_wp) .and. &
                     all(abs(ends%point(:, 2)) <= 1.0e-14_wp))
        call t%check('square: both corners 90 degrees', &
                     all(abs(ends%angle - 0.5_wp*PI) <= 1.0e-14_wp))
        call t%check('square: both beside free sides', all(ends%far == WEDGE_FREE))
        config%mesh%dirichlet = 'top left'
        config%mesh%neumann = 'right'
        call problem_of(config, prob, stat)
        if (.not. stat%ok()) return
        ends = contact_ends(prob)
        call t%check('square, left clamped: end 2 beside it', &
                     ends%far(1) == WEDGE_FREE .and. ends%far(2) == WEDGE_CLAMPED)
    end subroutine check_square_ends

    !> Unit-square ends (as contact_ends gives them, checked above) without a mesh.
    type(contact_ends_t) function square_ends() result(ends)
        ends%point(:, 1) = [1.0_wp, 0.0_wp]
        ends%point(:, 2) = [0.0_wp, 0.0_wp]
        ends%angle = 0.5_wp*PI
        ends%far = WEDGE_FREE
        ends%s_min = -1.0_wp
        ends%s_max = 0.0_wp
    end function square_ends

    !> `n` levels of one value each, v_k = limit + 0.5 q^k, whose profile puts a share growing
    !> from 0.6 to 0.9 into the last bin at end `end` (the rest spread evenly): the same
    !> shape at every level, so every level continues the one before.
    subroutine geometric_levels(n, limit, q, end, levels)
        integer, intent(in) :: n, end
        real(wp), intent(in) :: limit, q
        type(level_values_t), allocatable, intent(out) :: levels(:)
        real(wp) :: share
        integer :: k
        allocate (levels(n))
        do k = 1, n
            allocate (levels(k)%values(1))
            share = 0.6_wp + 0.3_wp*real(k - 1, wp)/real(n - 1, wp)
            levels(k)%values(1)%lambda = limit + 0.5_wp*q**k
            levels(k)%values(1)%profile = (1.0_wp - share)/real(N_PROFILE_BINS - 1, wp)
            levels(k)%values(1)%profile(merge(1, N_PROFILE_BINS, end == 1)) = share
            levels(k)%values(1)%resolution = 1.0e-6_wp
        end do
    end subroutine geometric_levels

    !> v_k = -3 + 0.5 * 0.7^k over 6 levels (0.7 > 0.5: too slow to call converging), its
    !> vector at end 2: moving over all 6, factor 0.7 (the relative changes' factor differs
    !> from 0.7 by the values' ratio, under 1e-2 here), Aitken's limit -3 to round-off,
    !> placed at (0, 0); a level with no value cuts the chain there.
    subroutine check_geometric_at_an_end()
        type(level_values_t), allocatable :: levels(:)
        type(moving_side_t) :: side
        call geometric_levels(6, -3.0_wp, 0.7_wp, 2, levels)
        side = track_side(levels, square_ends(), 0.3_wp, 0.0_wp)
        call t%check('geometric: known, moving over 6 levels', side%known .and. &
                     side%verdict%kind == TRACK_MOVING .and. side%verdict%length == 6)
        call t%check_close('geometric: factor 0.7', side%verdict%rate, 0.7_wp, 2.0e-2_wp)
        call t%check('geometric: Aitken''s limit -3', side%verdict%has_limit .and. &
                     abs(side%verdict%limit + 3.0_wp) <= 1.0e-13_wp)
        call t%check('geometric: at end 2, (0, 0), concentrating', side%end == 2 .and. &
                     all(abs(side%point) <= 0.0_wp) .and. side%verdict%concentrating(2))
        call t%check('geometric: the words give the limit as not converged', &
                     index(moving_words('lambda-', side), 'extrapolated limit -3.000000E+00, '// &
                           'not converged') > 0)
        deallocate (levels(3)%values)
        allocate (levels(3)%values(0))
        side = track_side(levels, square_ends(), 0.3_wp, 0.0_wp)
        call t%check('geometric, no value at level 3: followed over levels 4 to 6', &
                     side%verdict%length == 3)
    end subroutine check_geometric_at_an_end

    !> The wedge at end 2 (t points to it) sees the side's value, at end 1 its negative; a
    !> 90-degree contact-free corner crosses at -pi/2: -3 at end 2 and +3 at end 1 are past
    !> it (a negative exponent: no isolated value), +3 at end 2 is not.
    subroutine check_wedge_sides()
        type(level_values_t), allocatable :: levels(:)
        type(moving_side_t) :: side
        type(contact_ends_t) :: ends
        character(len=:), allocatable :: words
        call t%check_close('crossing of a 90-degree contact-free corner is -pi/2', &
                           contact_free_crossing(0.5_wp*PI), -0.5_wp*PI, 1.0e-14_wp)
        call geometric_levels(6, -3.0_wp, 0.7_wp, 2, levels)
        side = track_side(levels, square_ends(), 0.3_wp, 0.0_wp)
        call t%check('lambda = -3 at end 2: the wedge sees -3, exponent < 0', &
                     side%has_exponent .and. abs(side%wedge_lambda - levels(6)%values(1)%lambda) &
                     <= 0.0_wp .and. side%exponent < 0.0_wp .and. side%past_crossing .and. &
                     side%far == WEDGE_FREE .and. abs(side%angle_degrees - 90.0_wp) <= 1.0e-12_wp)
        call t%check('the words say it may have no isolated value', &
                     index(moving_words('lambda-', side), 'may have no isolated value') > 0)
        call geometric_levels(6, 3.0_wp, 0.7_wp, 2, levels)
        side = track_side(levels, square_ends(), 0.3_wp, 0.0_wp)
        call t%check('lambda = +3 at end 2: not past the crossing', side%has_crossing .and. &
                     .not. side%past_crossing)
        call geometric_levels(6, -4.0_wp, 0.7_wp, 2, levels)
        side = track_side(levels, square_ends(), 0.3_wp, 0.0_wp)
        call t%check('lambda = -4 at end 2: past the crossing, its exponent below -1', &
                     .not. side%has_exponent .and. side%past_crossing)
        ends = square_ends()
        ends%far(2) = WEDGE_CLAMPED
        call geometric_levels(6, 3.0_wp, 0.7_wp, 2, levels)
        side = track_side(levels, ends, 0.3_wp, 0.0_wp)
        call t%check('clamped 90 degrees, nu = 0.3: +3 is past its crossing 2.83', &
                     abs(side%crossing - contact_clamped_crossing(0.5_wp*PI, 0.3_wp)) <= &
                     0.0_wp .and. side%past_crossing)
        call geometric_levels(6, 2.5_wp, 0.7_wp, 2, levels)
        side = track_side(levels, ends, 0.3_wp, 0.0_wp)
        call t%check('clamped 90 degrees, nu = 0.3: +2.5 is before it', &
                     side%has_crossing .and. .not. side%past_crossing)
        ends%angle(2) = PI   ! Gamma_C ends inside a straight side: no crossing
        call geometric_levels(6, -3.0_wp, 0.7_wp, 2, levels)
        side = track_side(levels, ends, 0.3_wp, 0.0_wp)
        words = moving_words('lambda-', side)   ! once: an impure call twice in one expression
        call t%check('a 180-degree end has no crossing, and the words say so without one', &
                     .not. side%has_crossing .and. .not. side%past_crossing .and. &
                     index(words, '180-degree corner') > 0 .and. index(words, 'crossing') == 0)
        call geometric_levels(6, 3.0_wp, 0.7_wp, 1, levels)
        side = track_side(levels, square_ends(), 0.3_wp, 0.0_wp)
        call t%check('lambda = +3 at end 1: the wedge sees -3, exponent < 0', side%end == 1 &
                     .and. side%wedge_lambda < 0.0_wp .and. side%past_crossing)
    end subroutine check_wedge_sides

    !> A body's lambda past the crossing of an end (what an h-adaptive run's 'none' rests on):
    !> the square's 90-degree contact-free corners cross at -pi/2 (end 2 sees lambda, end 1
    !> -lambda), so lambda = -1.7 is past end 2's, +1.7 past end 1's (as the body's lambda
    !> +pi/2), +-1.5 past neither; with `side`, the lambdas past end 1's lie on the side
    !> lambda > 0 and end 2's on lambda < 0. A clamped end 1 crosses at +2.83 (nu = 0.3) in
    !> its wedge's lambda: past it the body's lambda < -2.83.
    subroutine check_past_crossing_end()
        type(contact_ends_t) :: ends
        logical :: past(2)
        real(wp) :: crossing(2)
        ends = square_ends()
        call past_crossing_end(ends, 0.3_wp, -1.7_wp, past, crossing)
        call t%check('lambda = -1.7: past end 2''s crossing -pi/2 only', &
                     (.not. past(1)) .and. past(2) .and. &
                     abs(crossing(2) + 0.5_wp*PI) <= 1.0e-14_wp)
        call past_crossing_end(ends, 0.3_wp, 1.7_wp, past, crossing)
        call t%check('lambda = +1.7: past end 1''s crossing, +pi/2 in the body''s lambda', &
                     past(1) .and. .not. past(2) .and. abs(crossing(1) - 0.5_wp*PI) <= 1.0e-14_wp)
        call past_crossing_end(ends, 0.3_wp, 1.5_wp, past, crossing)
        call t%check('lambda = +1.5: past neither', .not. any(past))
        call past_crossing_end(ends, 0.3_wp, -1.5_wp, past, crossing)
        call t%check('lambda = -1.5: past neither', .not. any(past))
        call past_crossing_end(ends, 0.3_wp, 0.0_wp, past, crossing, side=1)
        call t%check('side lambda > 0: end 1''s lambdas past its crossing', &
                     past(1) .and. .not. past(2))
        call past_crossing_end(ends, 0.3_wp, 0.0_wp, past, crossing, side=-1)
        call t%check('side lambda < 0: end 2''s', past(2) .and. .not. past(1))
        ends%far(1) = WEDGE_CLAMPED
        call past_crossing_end(ends, 0.3_wp, -3.0_wp, past, crossing)
        call t%check('clamped end 1, nu = 0.3: lambda = -3 past its crossing (body -2.83)', &
                     past(1) .and. abs(crossing(1) + contact_clamped_crossing(0.5_wp*PI, &
                     0.3_wp)) <= 1.0e-14_wp)
        call t%check('the words of end 1: its point, angle and far side', &
                     index(end_words(ends, 1), '(1.0, 0.0) of Gamma_C, a 90-degree corner '// &
                           'beside a clamped side') > 0)
        ends%far(1) = 0
        call past_crossing_end(ends, 0.3_wp, 1.7_wp, past, crossing)
        call t%check('an end beside an unknown side is past nothing', .not. past(1))
    end subroutine check_past_crossing_end

    !> Six levels whose one value alternates between two modes: at odd levels -3 - 0.01/k
    !> with the profile of geometric_levels (its force at end 2), at even levels -3.4 - 0.01/k
    !> with forces +1/2 in the first bin and -1/2 in the middle one (running sums 1/2 over
    !> the first half, 0 after: |cos| with the other's about 0.2, far below SAME_SHAPE). The
    !> values lie within MATCH_WINDOW of each other, so only the shapes tell them apart: the
    !> last (even) value has no match at level 5 but one at level 4, two levels back, and
    !> its shape is at levels 2, 4 and 6. With the even levels' profiles of a third shape
    !> (force +1 in the middle bin) the values still tell: those of levels 2 and 4 are
    !> within 2.5e-4 (relative) of the last, level 5's 0.12 away. With them moved out of
    !> the window too the last value is back nowhere: the plain 'too short'.
    subroutine check_alternating()
        type(level_values_t), allocatable :: levels(:)
        type(moving_side_t) :: side
        character(len=:), allocatable :: words
        integer :: k
        call geometric_levels(6, -3.0_wp, 0.7_wp, 2, levels)
        do k = 2, 6, 2
            levels(k)%values(1)%lambda = -3.4_wp - 0.01_wp/real(k, wp)
            levels(k)%values(1)%profile = 0.0_wp
            levels(k)%values(1)%profile(1) = 0.5_wp
            levels(k)%values(1)%profile(N_PROFILE_BINS/2) = -0.5_wp
        end do
        do k = 1, 5, 2
            levels(k)%values(1)%lambda = -3.0_wp - 0.01_wp/real(k, wp)
        end do
        side = track_side(levels, square_ends(), 0.3_wp, 0.0_wp)
        call t%check('trading places: no match at level 5, its shape 2 levels back, at 3 of 6', &
                     side%verdict%kind == TRACK_SHORT .and. side%verdict%length == 1 .and. &
                     side%alternates .and. side%back == 2 .and. side%shape_levels == 3 .and. &
                     side%n_levels == 6 .and. &
                     abs(side%other - levels(5)%values(1)%lambda) <= 0.0_wp)
        words = moving_words('lambda-', side)
        call t%check('trading places: the words say so', &
                     index(words, 'trades places with another value') > 0)
        do k = 2, 4, 2
            levels(k)%values(1)%profile = 0.0_wp
            levels(k)%values(1)%profile(N_PROFILE_BINS/2) = 1.0_wp
        end do
        side = track_side(levels, square_ends(), 0.3_wp, 0.0_wp)
        call t%check('trading places by value: another shape at levels 2 and 4', &
                     side%alternates .and. side%back == 2 .and. side%shape_levels == 3)
        levels(2)%values(1)%lambda = -5.0_wp
        levels(4)%values(1)%lambda = -5.0_wp
        side = track_side(levels, square_ends(), 0.3_wp, 0.0_wp)
        words = moving_words('lambda-', side)
        call t%check('back at no earlier level: too short, not trading places', &
                     side%verdict%kind == TRACK_SHORT .and. .not. side%alternates .and. &
                     index(words, 'has no value of its shape') > 0)
    end subroutine check_alternating
end program test_moving_side
