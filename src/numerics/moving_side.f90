! SPDX-License-Identifier: MIT
!> What a threshold run can tell about a side (lambda+ or lambda-) that does not converge
!> over hp levels (docs/thresholds.md): its values followed across the levels by their
!> vectors' profiles on Gamma_C (pencil_tracking), the verdict on that chain (converging or
!> moving, the fitted factor of its changes per level, Aitken's limit where the factor is
!> clear), the point of Gamma_C its last vector concentrates at, and, where that is an end,
!> the elastic wedge there (wedge_exponents): an exponent with a negative real part at the
!> side's value means the continuum's critical mode has infinite energy at that end, and the
!> pencil is not boundedly invertible there, so the continuum may have no isolated value.
module moving_side
    use kinds, only: wp
    use strings, only: short_real_text, to_string
    use real_format, only: real_to_text
    use problem, only: problem_t
    use pencil_tracking, only: N_PROFILE_BINS, pencil_value_t, level_values_t, &
                               track_verdict_t, track_chain, classify_chain, &
                               pencil_profile_bins, match_value, TRACK_CONVERGING, &
                               TRACK_MOVING, TRACK_SHORT
    use wedge_exponents, only: wedge_roots, contact_free_crossing, contact_clamped_crossing, &
                               WEDGE_CONTACT, WEDGE_FREE, WEDGE_CLAMPED
    implicit none
    private
    public :: moving_side_t, contact_ends_t, contact_ends, level_profile, track_side, &
              moving_words, FAR_NAMES, END_SHARE_AT, end_crossing, past_crossing_end, &
              end_words, unconfirmed_words

    real(wp), parameter :: PI = acos(-1.0_wp)
    !> a vector with at least this share of its forces within 2^-6 of an end sits at that end
    real(wp), parameter :: END_SHARE_AT = 0.5_wp
    !> the exponents searched: real parts in (RE_MIN, RE_MAX), imaginary parts below IM_BOX
    real(wp), parameter :: RE_MIN = -0.999_wp, RE_MAX = 1.5_wp, IM_BOX = 0.5_wp
    !> the other side's condition at an end, by WEDGE_FREE, WEDGE_CLAMPED (0: unknown)
    !> the side of a crossing is read from the exponent this far (in lambda) beyond it
    real(wp), parameter :: CROSSING_STEP = 0.1_wp
    !> an earlier value this much nearer the last one than the level before's is the last
    !> one back (track_side: alternation)
    real(wp), parameter :: RETURN_FACTOR = 10.0_wp
    character(len=*), parameter :: FAR_NAMES(0:2) = [character(len=7) :: 'unknown', 'free', &
                                                      'clamped']

    !> The two ends of Gamma_C (1: the one t points away from, s = 0; 2: the one it points
    !> to, s = 1), the interior angle of the body at each and the condition of the other side
    !> there (WEDGE_FREE or WEDGE_CLAMPED; 0: unknown, e.g. Gamma_C ends inside a side).
    type :: contact_ends_t
        real(wp) :: point(2, 2) = 0.0_wp       !! (x y, end)
        real(wp) :: angle(2) = 0.0_wp          !! radians
        integer :: far(2) = 0
        real(wp) :: s_min = 0.0_wp, s_max = 0.0_wp   !! positions along t of the ends
    end type contact_ends_t

    !> What is known about one side that did not converge (known: it has a value at the
    !> last level).
    type :: moving_side_t
        logical :: known = .false.
        type(track_verdict_t) :: verdict
        real(wp) :: length = 0.0_wp         !! of Gamma_C
        real(wp) :: s = 0.0_wp              !! where the last vector sits: distance from end 1
        integer :: end = 0                  !! the end it sits at (0: neither)
        real(wp) :: point(2) = 0.0_wp       !! that end, else the point at s
        !> the wedge at that end: its angle (degrees), the other side's condition, the
        !> wedge's own lambda (the side's value at end 2, its negative at end 1), its
        !> exponent nearest Re alpha = 0 in -1 < Re alpha < 1.5 (has_exponent: one was
        !> found), the lambda where a real exponent crosses 0 (has_crossing: the corner has
        !> one), and whether the wedge's lambda lies beyond it, away from 0, where an exponent
        !> has passed Re alpha = 0 (past_crossing: the pencil is not boundedly invertible at
        !> that end, docs/thresholds.md)
        real(wp) :: angle_degrees = 0.0_wp
        integer :: far = 0
        real(wp) :: wedge_lambda = 0.0_wp
        logical :: has_exponent = .false.
        real(wp) :: exponent = 0.0_wp
        logical :: has_crossing = .false.
        real(wp) :: crossing = 0.0_wp
        logical :: past_crossing = .false.
        !> the last value has no match at the level before, which has a value, but is back
        !> from an earlier level (track_side: alternation): the side's value trades places
        !> with another (`other`, the level before's) from level to level; `back`: how many
        !> levels back it was last, `shape_levels`: at how many of the `n_levels` levels it is
        logical :: alternates = .false.
        real(wp) :: other = 0.0_wp
        integer :: back = 0
        integer :: shape_levels = 0
        integer :: n_levels = 0
    end type moving_side_t

contains

    !> The ends of Gamma_C of `prob`, the body's angle at each and the other side's condition.
    function contact_ends(prob) result(ends)
        type(problem_t), intent(in) :: prob
        type(contact_ends_t) :: ends
        real(wp) :: s, inward(2), along(2), d(2)
        integer :: e, k, node(2), other, j
        ends%s_min = huge(1.0_wp)
        ends%s_max = -huge(1.0_wp)
        node = 0
        if (.not. allocated(prob%mesh%edge_part)) return   ! no mesh (a goal's rows alone)
        do e = 1, size(prob%mesh%edge_part)
            if (prob%mesh%edge_part(e) /= prob%contact_part) cycle
            do k = 1, 2
                s = dot_product(prob%mesh%coords(:, prob%mesh%edges(k, e)), prob%contact%tangent)
                if (s < ends%s_min) then
                    ends%s_min = s
                    node(1) = prob%mesh%edges(k, e)
                end if
                if (s > ends%s_max) then
                    ends%s_max = s
                    node(2) = prob%mesh%edges(k, e)
                end if
            end do
        end do
        if (any(node == 0)) return
        inward = -prob%contact%normal
        do j = 1, 2
            ends%point(:, j) = prob%mesh%coords(1:2, node(j))
            along = prob%contact%tangent*merge(1.0_wp, -1.0_wp, j == 1)   ! into Gamma_C
            do e = 1, size(prob%mesh%edge_part)
                if (prob%mesh%edge_part(e) == prob%contact_part) cycle
                if (all(prob%mesh%edges(1:2, e) /= node(j))) cycle
                other = merge(prob%mesh%edges(2, e), prob%mesh%edges(1, e), &
                              prob%mesh%edges(1, e) == node(j))
                d = prob%mesh%coords(1:2, other) - ends%point(:, j)
                ! the angle from Gamma_C to the other side through the body
                ends%angle(j) = atan2(dot_product(d, inward), dot_product(d, along))
                if (ends%angle(j) <= 0.0_wp) ends%angle(j) = ends%angle(j) + 2.0_wp*PI
                ends%far(j) = WEDGE_FREE
                if (allocated(prob%dirichlet_parts)) then
                    if (any(prob%dirichlet_parts == prob%mesh%edge_part(e))) &
                        ends%far(j) = WEDGE_CLAMPED
                end if
                exit
            end do
        end do
    end function contact_ends

    !> The profile of a level's vector `x` of one side (forces on the contact functions of
    !> `prob`; `vertex`: which are vertex functions, the others left out), with the level's
    !> smallest contact cell relative to the length of Gamma_C as its resolution.
    function level_profile(prob, ends, vertex, lambda, x) result(value)
        type(problem_t), intent(in) :: prob
        type(contact_ends_t), intent(in) :: ends
        logical, intent(in) :: vertex(:)
        real(wp), intent(in) :: lambda, x(:)
        type(pencil_value_t) :: value
        real(wp), allocatable :: s(:)
        real(wp) :: length, h
        integer :: a, e
        value%lambda = lambda
        length = ends%s_max - ends%s_min
        if (length <= 0.0_wp) return
        allocate (s(size(vertex)), source=0.0_wp)
        do a = 1, size(vertex)
            if (vertex(a)) s(a) = (dot_product(prob%mesh%coords(:, prob%contact%nodes(a)), &
                                               prob%contact%tangent) - ends%s_min)/length
        end do
        value%profile = pencil_profile_bins(pack(s, vertex), pack(x, vertex))
        h = length
        do e = 1, size(prob%mesh%edge_part)
            if (prob%mesh%edge_part(e) /= prob%contact_part) cycle
            h = min(h, norm2(prob%mesh%coords(:, prob%mesh%edges(2, e)) - &
                             prob%mesh%coords(:, prob%mesh%edges(1, e))))
        end do
        value%resolution = h/length
    end function level_profile

    !> The side's chain through `levels` (each level's value of this side, none where it had
    !> none; the last must have one), its verdict (`roundoff`: the last value's relative
    !> round-off bound) and the wedge of the end its last vector sits at, for Poisson's
    !> ratio `poisson`.
    function track_side(levels, ends, poisson, roundoff) result(side)
        type(level_values_t), intent(in) :: levels(:)
        type(contact_ends_t), intent(in) :: ends
        real(wp), intent(in) :: poisson, roundoff
        type(moving_side_t) :: side
        integer, allocatable :: chain(:)
        real(wp), allocatable :: values(:), profiles(:, :)
        complex(wp), allocatable :: roots(:)
        logical :: complete
        integer :: m, j, first, end
        m = size(levels)
        if (m == 0) return
        if (.not. allocated(levels(m)%values)) return
        if (size(levels(m)%values) == 0) return
        chain = track_chain(levels, 1)
        first = m - size(chain)
        allocate (values(size(chain)), profiles(N_PROFILE_BINS, size(chain)))
        do j = 1, size(chain)
            values(j) = levels(first + j)%values(chain(j))%lambda
            profiles(:, j) = levels(first + j)%values(chain(j))%profile
        end do
        side%known = .true.
        side%verdict = classify_chain(values, profiles, roundoff)
        if (side%verdict%kind == TRACK_SHORT .and. size(chain) == 1) call alternation(side)
        side%length = ends%s_max - ends%s_min
        side%s = max(side%verdict%where, 0.0_wp)*side%length
        side%point = ends%point(:, 1) + (ends%point(:, 2) - ends%point(:, 1))* &
                     max(side%verdict%where, 0.0_wp)
        end = maxloc(side%verdict%end_share, dim=1)
        if (side%verdict%end_share(end) < END_SHARE_AT .and. &
            .not. side%verdict%concentrating(end)) return
        side%end = end
        side%point = ends%point(:, end)
        side%angle_degrees = ends%angle(end)*180.0_wp/PI
        side%far = ends%far(end)
        if (side%far == 0) return
        ! t points to end 2: the wedge there sees the side's lambda, end 1 its mirror image
        side%wedge_lambda = merge(values(size(values)), -values(size(values)), end == 2)
        call wedge_roots(WEDGE_CONTACT, side%far, ends%angle(end), poisson, &
                         side%wedge_lambda, RE_MIN, RE_MAX, IM_BOX, roots, complete)
        side%has_exponent = size(roots) > 0
        if (side%has_exponent) side%exponent = real(roots(minloc(abs(real(roots, wp)), &
                                                                 dim=1)), wp)
        call end_crossing(ends, end, poisson, side%wedge_lambda, side%has_crossing, &
                          side%crossing, side%past_crossing)

    contains

        !> Where the level before has values but none of the last one's shape, whether an
        !> earlier level has it back: a value of its shape, or one nearer it than
        !> 1/RETURN_FACTOR of its distance to the level before's (the profiles of one value
        !> change as the levels grade an end: chamfered block, nu 0.3, hp from size 1: levels
        !> 5 and 8 agree to 6e-8, their profiles to |cos| 0.34). Then the side's value trades
        !> places with another, and the levels with it back say how often it is there.
        subroutine alternation(side)
            type(moving_side_t), intent(inout) :: side
            integer :: j
            real(wp) :: v, before
            if (m < 3) return
            if (.not. allocated(levels(m - 1)%values)) return
            if (size(levels(m - 1)%values) == 0) return
            v = levels(m)%values(1)%lambda
            before = minval(abs(levels(m - 1)%values%lambda - v))
            side%shape_levels = 1
            do j = m - 2, 1, -1
                if (.not. allocated(levels(j)%values)) cycle
                if (size(levels(j)%values) == 0) cycle
                if (match_value(levels(m)%values(1), levels(j)%values) == 0 .and. &
                    minval(abs(levels(j)%values%lambda - v)) > before/RETURN_FACTOR) cycle
                side%shape_levels = side%shape_levels + 1
                if (side%back == 0) side%back = m - j
            end do
            side%alternates = side%back > 0
            side%other = levels(m - 1)%values(1)%lambda
            side%n_levels = m
            if (.not. side%alternates) side%shape_levels = 0
        end subroutine alternation

    end function track_side

    !> The crossing of end `end` of `ends` (known far side), for Poisson's ratio `poisson`:
    !> the wedge's lambda where a real exponent crosses Re alpha = 0 (`has`: the corner has
    !> one), and whether the wedge's lambda `wedge_lambda` lies past it, away from 0, where an
    !> exponent has passed Re alpha = 0 (just before and just after the crossing the
    !> exponents with a negative real part differ in number; one that only touched 0 and
    !> turned back would not count).
    subroutine end_crossing(ends, end, poisson, wedge_lambda, has, crossing, past)
        type(contact_ends_t), intent(in) :: ends
        integer, intent(in) :: end
        real(wp), intent(in) :: poisson, wedge_lambda
        logical, intent(out) :: has, past
        real(wp), intent(out) :: crossing
        complex(wp), allocatable :: roots(:)
        logical :: complete
        past = .false.
        if (ends%far(end) == WEDGE_FREE) then
            crossing = contact_free_crossing(ends%angle(end))
        else
            crossing = contact_clamped_crossing(ends%angle(end), poisson)
        end if
        has = abs(crossing) < 0.5_wp*huge(1.0_wp)
        ! (no crossing: +-huge, whose product traps)
        if (.not. has) return
        if (crossing*wedge_lambda <= 0.0_wp .or. abs(wedge_lambda) <= abs(crossing)) return
        past = negative_exponents(-1.0_wp) /= negative_exponents(1.0_wp)

    contains

        !> The exponents with a negative real part (in the box searched) CROSSING_STEP before
        !> (`towards` -1) or after (+1) the crossing, going away from lambda = 0.
        integer function negative_exponents(towards) result(n)
            real(wp), intent(in) :: towards
            call wedge_roots(WEDGE_CONTACT, ends%far(end), ends%angle(end), poisson, &
                             crossing + towards*sign(CROSSING_STEP, crossing), RE_MIN, &
                             RE_MAX, IM_BOX, roots, complete)
            n = count(real(roots, wp) < 0.0_wp)
        end function negative_exponents
    end subroutine end_crossing

    !> Per end of Gamma_C (`ends`): whether the body's `lambda` lies past its crossing
    !> (end_crossing: the end the tangent points to sees lambda, the other -lambda), for
    !> Poisson's ratio `poisson`, and that crossing as the body's lambda (0 where none). With
    !> `side` (+1: lambda > 0, -1: lambda < 0) instead: whether the lambdas past its crossing
    !> lie on that side, whatever `lambda`. An end whose far side is unknown is past nothing.
    subroutine past_crossing_end(ends, poisson, lambda, past, crossing, side)
        type(contact_ends_t), intent(in) :: ends
        real(wp), intent(in) :: poisson, lambda
        logical, intent(out) :: past(2)
        real(wp), intent(out) :: crossing(2)
        integer, intent(in), optional :: side
        real(wp) :: wedge_lambda, c
        logical :: has
        integer :: e
        past = .false.
        crossing = 0.0_wp
        do e = 1, 2
            if (ends%far(e) == 0) cycle
            wedge_lambda = merge(lambda, -lambda, e == 2)
            if (present(side)) then
                call end_crossing(ends, e, poisson, 0.0_wp, has, c, past(e))
                if (.not. has) cycle
                ! the lambdas past it: beyond c on c's side (twice c is one of them)
                if (merge(c, -c, e == 2)*side <= 0.0_wp) cycle
                wedge_lambda = 2.0_wp*c
            end if
            call end_crossing(ends, e, poisson, wedge_lambda, has, c, past(e))
            if (past(e)) crossing(e) = merge(c, -c, e == 2)
        end do
    end subroutine past_crossing_end

    !> The words of end `end` of `ends`: 'the end (x, y) of Gamma_C, a D-degree corner
    !> beside a free side'.
    function end_words(ends, end) result(text)
        type(contact_ends_t), intent(in) :: ends
        integer, intent(in) :: end
        character(len=:), allocatable :: text
        text = 'the end ('//real_to_text(ends%point(1, end))//', '// &
            real_to_text(ends%point(2, end))//') of Gamma_C, a '// &
            to_string(nint(ends%angle(end)*180.0_wp/PI))//'-degree corner beside a '// &
            trim(FAR_NAMES(ends%far(end)))//' side'
    end function end_words

    !> Why levels without a value, graded toward end `end` of `ends`, do not confirm its
    !> absence: `past` says what lies past that end's crossing ('lambda = 9.78E+00 is past
    !> that end''s crossing 5.80E+00'); `h` for h levels (hp ones can see further there).
    function unconfirmed_words(ends, end, past, h) result(text)
        type(contact_ends_t), intent(in) :: ends
        integer, intent(in) :: end
        character(len=*), intent(in) :: past
        logical, intent(in) :: h
        character(len=:), allocatable :: text
        text = 'graded toward '//end_words(ends, end)//', its absence not confirmed: '// &
            past//', where a mode can concentrate below the '
        if (h) then
            text = text//'mesh''s scale (hp levels, graded toward the ends, can see it)'
        else
            text = text//'finest cells'' scale'
        end if
    end function unconfirmed_words

    !> One sentence on side `label` (lambda+, lambda-) for the warnings and stdout: how its
    !> value moved, where its vector sits, and what the wedge there says.
    function moving_words(label, side) result(text)
        character(len=*), intent(in) :: label
        type(moving_side_t), intent(in) :: side
        character(len=:), allocatable :: text
        text = ''
        if (.not. side%known) return
        associate (v => side%verdict)
            text = label//' = '//short_real_text(v%value, 6)
            select case (v%kind)
            case (TRACK_MOVING)
                text = text//' moves with the mesh over '//to_string(v%length)//' levels'
            case (TRACK_CONVERGING)
                if (v%rate >= 0.0_wp) then
                    text = text//' settles over '//to_string(v%length)//' levels'
                else   ! its last changes within round-off (classify_chain)
                    text = text//' has settled to round-off over '//to_string(v%length)// &
                        ' levels'
                end if
            case default
                if (side%alternates) then
                    text = text//' trades places with another value ('// &
                        short_real_text(side%other, 6)//' at the level before, of another '// &
                        'shape): it was there '//to_string(side%back)//' levels back and is '// &
                        'at '//to_string(side%shape_levels)//' of the '// &
                        to_string(side%n_levels)//' levels, not converged'
                else
                    text = text//' has no value of its shape at the level before (followed '// &
                        'over '//to_string(v%length)//' level'//trim(merge('s', ' ', &
                        v%length > 1))//')'
                end if
            end select
            if (v%rate >= 0.0_wp) then
                text = text//' (factor '//short_real_text(v%rate)//' per level'
                if (v%has_limit .and. v%kind == TRACK_MOVING) text = text// &
                    ', extrapolated limit '//short_real_text(v%limit, 6)//', not converged'
                text = text//')'
            end if
            if (side%end == 0) then
                text = text//'; its vector sits inside Gamma_C at ('// &
                    short_real_text(side%point(1))//', '//short_real_text(side%point(2))//')'
                return
            end if
            text = text//'; its vector sits at the end ('//real_to_text(side%point(1))// &
                ', '//real_to_text(side%point(2))//') of Gamma_C ('// &
                to_string(nint(100.0_wp*v%end_share(side%end)))//' % within 1/64 of it)'
            if (side%far > 0) text = text//', a '//to_string(nint(side%angle_degrees))// &
                '-degree corner beside a '//trim(FAR_NAMES(side%far))//' side'
            if (side%has_exponent) text = text//', wedge exponent '// &
                short_real_text(side%exponent)//' at lambda = '//short_real_text(side%wedge_lambda)
            ! past the crossing a threshold can still exist, ill-conditioned (docs/thresholds.md)
            if (side%past_crossing .and. v%kind == TRACK_CONVERGING) then
                text = text//', past its crossing '//short_real_text(side%crossing)// &
                    ': an ill-conditioned value there'
            else if (side%past_crossing) then
                text = text//', past its crossing '//short_real_text(side%crossing)// &
                    ': the continuum may have no isolated value there'
            else if (side%has_crossing) then   ! (no crossing: +-huge, whose product traps)
                if (side%crossing*side%wedge_lambda > 0.0_wp) text = text// &
                    ', before its crossing '//short_real_text(side%crossing)
            end if
        end associate
    end function moving_words
end module moving_side
