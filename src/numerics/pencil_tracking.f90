! SPDX-License-Identifier: MIT
!> Tracking one side's pencil value (a threshold lambda+ or lambda-, a real eigenvalue of
!> Kt_nn x = lambda Kt_nt x) across the levels of a refinement, and telling a value that
!> converges from one that moves with the mesh (docs/thresholds.md). Pure: the caller hands
!> in, per level, the real pencil values of one side with their profiles; nothing here knows
!> meshes, loops or solvers.
!>
!> Profiles. The vectors of two levels live on different meshes; they are compared through a
!> common representation, their profile: the contact forces x (x_a = int_C g phi_a ds, g
!> the traction of the limit mode) of the vertex functions, each shared among N_PROFILE_BINS
!> fixed bins of the normalised position s in [0, 1] along Gamma_C as its hat's area is (the
!> bins graded geometrically toward both ends, where modes concentrate), scaled to a sum of
!> moduli 1 and signed so that the largest bin is positive: the bin integrals of g where g
!> changes little over a hat. Edge functions' forces are left out.
!>
!> Matching. A value of level k continues a value of level k - 1 when their profiles are
!> alike (|cos| >= SAME_SHAPE between their running sums, the force on [0, s], at the
!> breakpoints both levels resolve: a genuine mode past a crossing gathers a growing share of
!> its force in the smallest cells at an end, which moves between the end bins from level to
!> level) and their values within MATCH_WINDOW relative of each other; of several, the most
!> alike. A chain is followed back from the last level's value.
!>
!> Verdict on a chain of values v_1 .. v_m (relative changes d_j = |v_j - v_j-1| / |v_j|):
!> - converging: at least three changes, each of the last three at most FASTEST_FACTOR
!>   times the one before (a geometric fall), fitted factor q (least squares on log d over
!>   the last three changes) at most CONVERGING_RATE; bar = LEVEL_FACTOR d_m q / (1 - q)
!>   (the geometric tail, times the margin of the hp level bar), extrapolated limit v_m +
!>   (v_m - v_m-1) r / (1 - r), r = (v_m - v_m-1) / (v_m-1 - v_m-2) (Aitken's);
!> - moving with the mesh: otherwise, with the fitted factor of the last three changes and,
!>   where their two ratios agree within RATE_AGREEMENT and the factor is below MOVING_RATE,
!>   the extrapolated limit (Aitken's, exact for a geometric sequence); plus where the last
!>   profile concentrates (its |x|-weighted mean s, its shares within 2^-6 of each end) and
!>   whether an end share grew at every one of the last three levels;
!> - at the floating-point floor (the last two changes within FLOOR_FACTOR of the values'
!>   round-off bound, when given): converging, with the bar of classify_chain;
!> - too short: fewer than three changes.
module pencil_tracking
    use kinds, only: wp
    implicit none
    private
    public :: N_PROFILE_BINS, profile_breakpoints, pencil_profile_bins, profile_similarity
    public :: pencil_value_t, level_values_t, track_verdict_t
    public :: match_value, track_chain, classify_chain, profile_mean, profile_end_shares
    public :: TRACK_SHORT, TRACK_CONVERGING, TRACK_MOVING, TRACK_NAMES
    public :: SAME_SHAPE, MATCH_WINDOW, CONVERGING_RATE

    !> bins per half of the segment: the smallest is 2^-(N_HALF) of its length at each end
    integer, parameter :: N_HALF = 13
    integer, parameter :: N_PROFILE_BINS = 2*N_HALF
    !> bins within 2^-6 of an end count as "at the end" (7 bins of each half)
    integer, parameter :: END_BINS = 7
    !> profiles at least this alike (|cos|) are the same mode; a genuine value's profile at
    !> two hp levels of the issue's bodies agrees to 0.99 and better, a spurious one's with
    !> the genuine one below 0.5 (docs/thresholds.md)
    real(wp), parameter :: SAME_SHAPE = 0.9_wp
    !> at most this relative distance between matched values of consecutive levels
    real(wp), parameter :: MATCH_WINDOW = 0.25_wp
    real(wp), parameter :: CONVERGING_RATE = 0.5_wp   !! fastest factor per level to converge
    real(wp), parameter :: FASTEST_FACTOR = 0.9_wp    !! each change at most this times the last
    real(wp), parameter :: MOVING_RATE = 0.95_wp      !! an extrapolation needs a factor below
    real(wp), parameter :: RATE_AGREEMENT = 0.3_wp    !! ... and ratios agreeing within this
    real(wp), parameter :: LEVEL_FACTOR = 3.0_wp      !! the margin of the hp level bar
    real(wp), parameter :: FLOOR_FACTOR = 10.0_wp     !! changes this near round-off: the floor

    integer, parameter :: TRACK_SHORT = 0, TRACK_CONVERGING = 1, TRACK_MOVING = 2
    character(len=*), parameter :: TRACK_NAMES(0:2) = [character(len=10) :: 'too short', &
                                                        'converging', 'moving']

    !> One real pencil value of a level with the profile of its vector, and the size of the
    !> level's smallest cells at the ends of Gamma_C relative to its length (bins finer than
    !> that hold what the level cannot resolve: they are not compared).
    type :: pencil_value_t
        real(wp) :: lambda = 0.0_wp
        real(wp) :: profile(N_PROFILE_BINS) = 0.0_wp
        real(wp) :: resolution = 0.0_wp
    end type pencil_value_t

    !> The real pencil values of one side at one level (any order).
    type :: level_values_t
        type(pencil_value_t), allocatable :: values(:)
    end type level_values_t

    !> What a chain of matched values says.
    type :: track_verdict_t
        integer :: kind = TRACK_SHORT
        integer :: length = 0                 !! values in the chain
        real(wp) :: value = 0.0_wp            !! the last one
        real(wp) :: rate = -1.0_wp            !! fitted factor of the changes per level (-1: none)
        real(wp) :: bar = -1.0_wp             !! relative bar of a converging value (-1: none)
        logical :: has_limit = .false.
        real(wp) :: limit = 0.0_wp            !! extrapolated limit where the rate is clear
        real(wp) :: where = -1.0_wp           !! |x|-weighted mean position s of the last profile
        real(wp) :: end_share(2) = 0.0_wp     !! its shares within 2^-6 of s = 0 and of s = 1
        logical :: concentrating(2) = .false. !! that share grew at each of the last 3 levels
    end type track_verdict_t

contains

    !> The N_PROFILE_BINS + 1 breakpoints of the profile bins in [0, 1]: 0, 2^-13, ...,
    !> 2^-2, 1/2, 1 - 2^-2, ..., 1 - 2^-13, 1.
    pure function profile_breakpoints() result(b)
        real(wp) :: b(N_PROFILE_BINS + 1)
        integer :: k
        b(1) = 0.0_wp
        do k = 1, N_HALF
            b(k + 1) = 2.0_wp**(k - N_HALF - 1)
        end do
        do k = 1, N_HALF
            b(N_PROFILE_BINS + 2 - k) = 1.0_wp - b(k)
        end do
    end function profile_breakpoints

    !> The profile of the forces `x` of the vertex (hat) functions at the ascending positions
    !> `s` in [0, 1] along Gamma_C. Each force is shared among the bins as its hat's area is,
    !> the hat spanning the neighbouring positions (0 and 1 beyond the first and the last):
    !> the bin integrals of g where g changes little over a hat's support. Zero when x is.
    pure function pencil_profile_bins(s, x) result(bins)
        real(wp), intent(in) :: s(:), x(:)
        real(wp) :: bins(N_PROFILE_BINS)
        real(wp) :: b(N_PROFILE_BINS + 1), total, left, right, area
        integer :: a, k, n
        b = profile_breakpoints()
        bins = 0.0_wp
        n = size(s)
        do a = 1, n
            left = 0.0_wp
            right = 1.0_wp
            if (a > 1) left = s(max(1, a - 1))   ! (max: gfortran warns of s(0) otherwise)
            if (a < n) right = s(min(n, a + 1))
            area = 0.5_wp*(right - left)
            if (area <= 0.0_wp) then   ! a hat of no width: its force at its point
                k = min(N_PROFILE_BINS, max(1, count(b(2:N_PROFILE_BINS) <= s(a)) + 1))
                bins(k) = bins(k) + x(a)
                cycle
            end if
            do k = 1, N_PROFILE_BINS
                if (b(k + 1) <= left .or. b(k) >= right) cycle
                bins(k) = bins(k) + x(a)*(hat_area(b(k + 1)) - hat_area(b(k)))/area
            end do
        end do
        total = sum(abs(bins))
        if (total <= 0.0_wp) return
        bins = bins/total
        k = maxloc(abs(bins), dim=1)
        if (bins(k) < 0.0_wp) bins = -bins

    contains

        !> The area of hat a (peak 1 at s(a), zero at left and right) over [left, t].
        pure real(wp) function hat_area(t)
            real(wp), intent(in) :: t
            real(wp) :: c, u
            c = s(a)
            u = min(max(t, left), right)
            if (u <= c) then
                hat_area = 0.0_wp
                if (c > left) hat_area = 0.5_wp*(u - left)**2/(c - left)
            else
                hat_area = 0.5_wp*(c - left) + 0.5_wp*((right - c)**2 - (right - u)**2)/(right - c)
            end if
        end function hat_area
    end function pencil_profile_bins

    !> |cos| of the angle between two profiles (1: the same shape up to sign and scale; 0
    !> when either is zero).
    pure real(wp) function profile_similarity(a, b)
        real(wp), intent(in) :: a(:), b(:)
        real(wp) :: na, nb
        na = norm2(a)
        nb = norm2(b)
        profile_similarity = 0.0_wp
        if (na > 0.0_wp .and. nb > 0.0_wp) profile_similarity = abs(dot_product(a, b))/(na*nb)
    end function profile_similarity

    !> The |profile|-weighted mean position of a profile (bin midpoints); -1 for a zero one.
    pure real(wp) function profile_mean(profile)
        real(wp), intent(in) :: profile(N_PROFILE_BINS)
        real(wp) :: b(N_PROFILE_BINS + 1)
        b = profile_breakpoints()
        profile_mean = -1.0_wp
        if (sum(abs(profile)) > 0.0_wp) profile_mean = &
            sum(abs(profile)*0.5_wp*(b(1:N_PROFILE_BINS) + b(2:)))/sum(abs(profile))
    end function profile_mean

    !> The shares of |profile| within 2^-6 of s = 0 and of s = 1.
    pure function profile_end_shares(profile) result(share)
        real(wp), intent(in) :: profile(N_PROFILE_BINS)
        real(wp) :: share(2), total
        share = 0.0_wp
        total = sum(abs(profile))
        if (total <= 0.0_wp) return
        share(1) = sum(abs(profile(1:END_BINS)))/total
        share(2) = sum(abs(profile(N_PROFILE_BINS - END_BINS + 1:)))/total
    end function profile_end_shares

    !> The candidate of `candidates` that continues `previous` (module comment), 0 if none.
    pure integer function match_value(previous, candidates) result(best)
        type(pencil_value_t), intent(in) :: previous
        type(pencil_value_t), intent(in) :: candidates(:)
        real(wp) :: alike, best_alike
        logical :: resolved(N_PROFILE_BINS)
        integer :: i
        best = 0
        best_alike = -1.0_wp
        do i = 1, size(candidates)
            if (abs(candidates(i)%lambda - previous%lambda) > &
                MATCH_WINDOW*max(abs(candidates(i)%lambda), abs(previous%lambda))) cycle
            resolved = resolved_breakpoints(max(previous%resolution, candidates(i)%resolution))
            alike = profile_similarity(pack(cumulative(previous%profile), resolved), &
                                       pack(cumulative(candidates(i)%profile), resolved))
            if (alike < SAME_SHAPE) cycle
            if (alike > best_alike) then
                best = i
                best_alike = alike
            end if
        end do
    end function match_value

    !> The chain of values that ends at value `last` of the last level of `levels`, followed
    !> back while each has a match at the level before: chain(j) is the index of the value at
    !> level size(levels) - size(chain) + j.
    pure function track_chain(levels, last) result(chain)
        type(level_values_t), intent(in) :: levels(:)
        integer, intent(in) :: last
        integer, allocatable :: chain(:)
        integer :: k, here, before
        chain = [last]
        here = last
        do k = size(levels), 2, -1
            if (.not. allocated(levels(k - 1)%values)) exit
            before = match_value(levels(k)%values(here), levels(k - 1)%values)
            if (before == 0) exit
            chain = [before, chain]
            here = before
        end do
    end function track_chain

    !> The verdict on a chain of values (module comment) and its last profiles; `roundoff`
    !> (relative, default 0) the round-off bound of the values: the last two changes both
    !> within FLOOR_FACTOR of it are the floating-point floor, converged, with a bar of
    !> LEVEL_FACTOR times the largest of the last three changes plus the round-off.
    pure function classify_chain(values, profiles, roundoff) result(verdict)
        real(wp), intent(in) :: values(:)
        real(wp), intent(in) :: profiles(:, :)   !! (N_PROFILE_BINS, size(values))
        real(wp), intent(in), optional :: roundoff
        type(track_verdict_t) :: verdict
        real(wp) :: floor
        real(wp), allocatable :: d(:)
        real(wp) :: shares(2, 4), q, r1, r2
        integer :: m, j, n_shares
        m = size(values)
        verdict%length = m
        verdict%value = values(m)
        verdict%where = profile_mean(profiles(:, m))
        verdict%end_share = profile_end_shares(profiles(:, m))
        n_shares = min(4, m)
        do j = 1, n_shares
            shares(:, j) = profile_end_shares(profiles(:, m - n_shares + j))
        end do
        if (n_shares == 4) verdict%concentrating = shares(:, 2) > shares(:, 1) .and. &
            shares(:, 3) > shares(:, 2) .and. shares(:, 4) > shares(:, 3)
        if (m < 4) return
        allocate (d(m - 1))
        do j = 2, m
            d(j - 1) = abs(values(j) - values(j - 1))/max(abs(values(j)), tiny(1.0_wp))
        end do
        floor = 0.0_wp
        if (present(roundoff)) floor = max(0.0_wp, roundoff)
        if (floor > 0.0_wp .and. all(d(m - 2:m - 1) <= FLOOR_FACTOR*floor)) then
            verdict%kind = TRACK_CONVERGING
            verdict%bar = LEVEL_FACTOR*maxval(d(m - 3:m - 1)) + floor
            verdict%has_limit = .true.
            verdict%limit = values(m)
            return
        end if
        ! fitted factor of the last three changes (least squares slope of log d on j), and
        ! the ratios of the last two differences (Aitken's, exact for a geometric sequence)
        q = fitted_factor(d(m - 3:m - 1))
        verdict%rate = q
        r1 = -1.0_wp
        r2 = -1.0_wp
        if (abs(values(m - 2) - values(m - 3)) > 0.0_wp) &
            r1 = (values(m - 1) - values(m - 2))/(values(m - 2) - values(m - 3))
        if (abs(values(m - 1) - values(m - 2)) > 0.0_wp) &
            r2 = (values(m) - values(m - 1))/(values(m - 1) - values(m - 2))
        if (all(d(m - 2:m - 1) <= FASTEST_FACTOR*d(m - 3:m - 2)) .and. q <= CONVERGING_RATE) then
            verdict%kind = TRACK_CONVERGING
            verdict%bar = LEVEL_FACTOR*d(m - 1)*q/(1.0_wp - q)
            verdict%has_limit = .true.
            if (r2 > 0.0_wp .and. r2 < 1.0_wp) then
                verdict%limit = values(m) + (values(m) - values(m - 1))*r2/(1.0_wp - r2)
            else   ! alternating changes: the last value
                verdict%limit = values(m)
            end if
            return
        end if
        verdict%kind = TRACK_MOVING
        if (r1 > 0.0_wp .and. r2 > 0.0_wp .and. r2 < MOVING_RATE .and. &
            abs(r2 - r1) <= RATE_AGREEMENT*max(r1, r2)) then
            verdict%has_limit = .true.
            verdict%limit = values(m) + (values(m) - values(m - 1))*r2/(1.0_wp - r2)
        end if
    end function classify_chain

    !> Which running sums (at the inner breakpoints 2 .. N_PROFILE_BINS + 1, the last one the
    !> total) lie at least `resolution` from both ends: those two levels both resolve.
    pure function resolved_breakpoints(resolution) result(resolved)
        real(wp), intent(in) :: resolution
        logical :: resolved(N_PROFILE_BINS)
        real(wp) :: b(N_PROFILE_BINS + 1)
        b = profile_breakpoints()
        resolved = b(2:) >= resolution .and. b(2:) <= 1.0_wp - resolution
        resolved(N_PROFILE_BINS) = .true.   ! the total force
    end function resolved_breakpoints

    !> The running sums of a profile: the force on [0, s] at the breakpoints, which a mode that
    !> sharpens into an end (its forces moving between the end bins) changes little.
    pure function cumulative(profile) result(total)
        real(wp), intent(in) :: profile(N_PROFILE_BINS)
        real(wp) :: total(N_PROFILE_BINS)
        integer :: k
        total(1) = profile(1)
        do k = 2, N_PROFILE_BINS
            total(k) = total(k - 1) + profile(k)
        end do
    end function cumulative

    !> exp of the least-squares slope of log(d) against its index; 1 if a change is zero
    !> (nothing to fit: no claim of convergence).
    pure real(wp) function fitted_factor(d) result(q)
        real(wp), intent(in) :: d(:)
        real(wp) :: x(size(d)), y(size(d))
        integer :: j
        q = 1.0_wp
        if (any(d <= 0.0_wp)) return
        x = [(real(j, wp), j=1, size(d))]
        y = log(d)
        q = exp(sum((x - sum(x)/size(x))*(y - sum(y)/size(y)))/sum((x - sum(x)/size(x))**2))
    end function fitted_factor
end module pencil_tracking
