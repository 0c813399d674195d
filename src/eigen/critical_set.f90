! SPDX-License-Identifier: MIT
!> The set of lambdas at which a positive real mu exists, over a range, and every point of its
!> boundary with the mechanism that makes it (model.md section 7). A positive eigenvalue
!> theta = 1/mu of the reduced matrix A(lambda) can appear or vanish in two generic ways:
!> - 'pencil': a real theta crosses zero (mu through infinity); then det A = 0, so lambda is a
!>   real eigenvalue of the pencil Kt_nn x = lambda Kt_nt x, known to round-off from QZ;
!> - 'complex_pair': two real theta > 0 meet and leave the axis as a conjugate pair (or a pair
!>   lands on it), a double eigenvalue of A(lambda); the count of positive theta jumps by 2.
!> The count of positive theta is evaluated on a scan (the &sweep lambdas) and on both sides
!> of every pencil eigenvalue in range; where the count goes from zero to non-zero between two
!> points without a pencil eigenvalue between them, the point is bracketed by bisection on
!> that count and then refined as the root of the discriminant of the meeting pair
!> (pair_discriminant), a smooth function of lambda with a simple root, to round-off.
!> Two boundary points closer together than the scan spacing, with no pencil eigenvalue
!> between, can be missed (the count is the same at both ends): the scan sets the resolution.
!> A finer discretisation of the same scene can take the points of a coarser one's scan
!> (carry_critical_set): each located again on the finer blocks, the structure checked there,
!> at a few p x p solves instead of the scan's hundred.
module critical_set
    use kinds, only: wp
    use status, only: status_t
    use sorting, only: sort_index
    use contact_reduction, only: reduced_blocks_t, lambda_unit
    use critical_lambda, only: reduced_eigenvalues, count_positive, CONFIRM_OFFSET, SIDE_PLUS, &
                               SIDE_MINUS, thresholds_t
    implicit none
    private
    public :: search_critical_set, find_critical_set, carry_critical_set, pair_discriminant, &
              side_offset, onset_point, track_onsets

    integer, parameter, public :: MECHANISM_PENCIL = 1
    integer, parameter, public :: MECHANISM_COMPLEX_PAIR = 2
    character(len=*), parameter, public :: MECHANISM_NAMES(2) = &
        [character(len=12) :: 'pencil', 'complex_pair']
    !> The count bisection stops at this relative width: there the meeting pair is still
    !> split by about sqrt(1e-10) ~ 1e-5 relative, far above dgeev's sqrt(eps) ~ 1e-8 error
    !> for a near-double eigenvalue, so the count is still right; the discriminant does the rest.
    real(wp), parameter :: BISECTION_WIDTH = 1.0e-10_wp
    integer, parameter :: MAX_REFINE = 200   !! Illinois steps; about 10 are used
    !> A carried collision point is first bracketed this close (relative): a coarse point is
    !> nearer than that to the fine one where the coarse thresholds have a few digits.
    real(wp), parameter :: CARRY_WIDTH = 1.0e-3_wp
    !> The count bisection from a bracket `near` a carried point stops here: the pair is
    !> still split by about sqrt(1e-6) = 1e-3 relative, plenty to tell it from the other
    !> eigenvalues, and the discriminant's regula falsi, superlinear on its simple root,
    !> does the rest in fewer solves than the bisection's 13 halvings to BISECTION_WIDTH.
    real(wp), parameter :: NEAR_BISECTION_WIDTH = 1.0e-6_wp

    !> One boundary point of {lambda : a positive real mu exists}.
    type, public :: boundary_point_t
        real(wp) :: lambda = 0.0_wp
        integer :: mechanism = MECHANISM_PENCIL
        !> a positive mu exists just above lambda (it appears as lambda increases), else
        !> just below (it vanishes as lambda increases)
        logical :: appears = .true.
        !> positive real eigenvalues at lambda -+ CONFIRM_OFFSET |lambda|
        integer :: n_below = 0, n_above = 0
        !> complex_pair: the scaled discriminant of the meeting pair at lambda -+ offset and at
        !> lambda; mu where the pair meets (1/theta there, in the units of the blocks)
        real(wp) :: discriminant_below = 0.0_wp, discriminant_above = 0.0_wp
        real(wp) :: discriminant = 0.0_wp
        real(wp) :: mu_meet = 0.0_wp
        !> the counts just below and above differ by one from/to zero (pencil) or by two
        !> with the discriminant changing sign (complex_pair)
        logical :: confirmed = .false.
        !> where the search bracketed it: the scan points around a complex_pair point, the
        !> confirming sides of a pencil point
        real(wp) :: bracket(2) = 0.0_wp
        !> the relative error bar of lambda against the continuum (filled by the analysis:
        !> boundary_estimate); negative: none
        real(wp) :: error_bar = -1.0_wp
        !> complex_pair: the round-off part of that bar (roundoff: collision_roundoff);
        !> negative: unknown
        real(wp) :: roundoff = -1.0_wp
        !> complex_pair: located on the very blocks a carry takes it to (the last hp level's
        !> own follow), so carry_pairs keeps it as it is instead of locating it again
        logical :: located_here = .false.
    end type boundary_point_t

    !> The last few spectra of reduced_eigenvalues on one set of blocks, by their exact
    !> lambda: a bracket end, the located point and the counts beside it are solved once.
    integer, parameter :: MEMO_SIZE = 8
    type :: spectrum_memo_t
        integer :: n = 0, next = 1
        real(wp) :: lambda(MEMO_SIZE) = 0.0_wp
        real(wp), allocatable :: wr(:, :), wi(:, :)
    contains
        procedure :: find => memo_find
        procedure :: keep => memo_keep
    end type spectrum_memo_t

    type, public :: critical_set_t
        real(wp) :: lambda_min = 0.0_wp, lambda_max = 0.0_wp   !! the range searched
        logical :: positive_at_min = .false.   !! a positive mu exists at lambda_min
        integer :: n_evaluations = 0           !! p x p eigen-solves used
        !> p of the blocks the points were located on, and of those whose scan found them:
        !> the same, or a coarser discretisation's where the points were carried
        !> (carry_critical_set); 0: no search
        integer :: contact = 0, scan_contact = 0
        !> counts known before the search (the confirmations of the thresholds, at the very
        !> lambdas that bracket their pencil points): not solved again
        real(wp), allocatable :: known_lambda(:)
        integer, allocatable :: known_count(:)
        type(boundary_point_t), allocatable :: points(:)   !! ascending lambda
    contains
        procedure :: positive_at => critical_set_positive_at
    end type critical_set_t

contains

    !> The spectrum kept for exactly `lambda` (true), in wr, wi.
    logical function memo_find(this, lambda, wr, wi) result(found)
        class(spectrum_memo_t), intent(in) :: this
        real(wp), intent(in) :: lambda
        real(wp), allocatable, intent(inout) :: wr(:), wi(:)
        integer :: k
        found = .false.
        do k = 1, this%n
            if (abs(this%lambda(k) - lambda) > 0.0_wp) cycle
            if (allocated(wr)) deallocate (wr)
            if (allocated(wi)) deallocate (wi)
            allocate (wr, source=this%wr(:, k))
            allocate (wi, source=this%wi(:, k))
            found = .true.
            return
        end do
    end function memo_find

    !> Keep the spectrum wr, wi at `lambda`, over the oldest kept once the memo is full.
    subroutine memo_keep(this, lambda, wr, wi)
        class(spectrum_memo_t), intent(inout) :: this
        real(wp), intent(in) :: lambda, wr(:), wi(:)
        if (.not. allocated(this%wr)) allocate (this%wr(size(wr), MEMO_SIZE), &
                                                 this%wi(size(wi), MEMO_SIZE))
        this%lambda(this%next) = lambda
        this%wr(:, this%next) = wr
        this%wi(:, this%next) = wi
        this%n = max(this%n, this%next)
        this%next = mod(this%next, MEMO_SIZE) + 1
    end subroutine memo_keep

    !> A positive mu exists at `lambda` (in the range searched) as far as the search saw:
    !> each boundary point below `lambda` switches the answer at lambda_min.
    pure logical function critical_set_positive_at(this, lambda)
        class(critical_set_t), intent(in) :: this
        real(wp), intent(in) :: lambda
        integer :: i, n_below
        n_below = 0
        do i = 1, size(this%points)
            if (this%points(i)%lambda < lambda) n_below = n_below + 1
        end do
        critical_set_positive_at = this%positive_at_min .neqv. (mod(n_below, 2) == 1)
    end function critical_set_positive_at

    !> The index of the boundary point nearest zero on `side` (0 when none): the onset of a
    !> positive mu as |lambda| grows from 0 on that side.
    pure integer function onset_point(set, side)
        type(critical_set_t), intent(in) :: set
        integer, intent(in) :: side
        integer :: i
        onset_point = 0
        do i = 1, size(set%points)
            if ((set%points(i)%lambda > 0.0_wp) .neqv. (side == SIDE_PLUS)) cycle
            if (onset_point == 0) then
                onset_point = i
            else if (abs(set%points(i)%lambda) < abs(set%points(onset_point)%lambda)) then
                onset_point = i
            end if
        end do
    end function onset_point

    !> The distance CONFIRM_OFFSET |lambda| of the confirming solves from a boundary point.
    elemental real(wp) function side_offset(lambda)
        real(wp), intent(in) :: lambda
        side_offset = CONFIRM_OFFSET*abs(lambda)
    end function side_offset

    !> The boundary points of {lambda : A(lambda) has a positive real eigenvalue} in
    !> [minval(scan), maxval(scan)], from the scan points and the pencil's real eigenvalues.
    !> `known_lambda`, `known_count`: counts already solved (critical_set_t%known_lambda).
    subroutine find_critical_set(blocks, scan, pencil_lambdas, set, stat, known_lambda, &
                                 known_count)
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: scan(:)             !! any order, at least one point
        real(wp), intent(in) :: pencil_lambdas(:)   !! ascending
        type(critical_set_t), intent(out) :: set
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: known_lambda(:)
        integer, intent(in), optional :: known_count(:)
        real(wp), allocatable :: x(:)
        integer, allocatable :: counts(:)
        logical, allocatable :: pencil_left(:)   !! x(i), x(i+1) bracket a pencil eigenvalue
        type(boundary_point_t) :: point
        integer :: i

        call take_known(set, known_lambda, known_count)
        call scan_points(scan, pencil_lambdas, x, pencil_left)
        set%lambda_min = x(1)
        set%lambda_max = x(size(x))
        set%contact = size(blocks%kt_nn, 1)
        set%scan_contact = set%contact
        allocate (set%points(0), counts(size(x)))
        do i = 1, size(x)
            call positive_count(blocks, x(i), counts(i), set, stat)
            if (.not. stat%ok()) return
        end do
        set%positive_at_min = counts(1) > 0
        do i = 1, size(x) - 1
            if ((counts(i) > 0) .eqv. (counts(i + 1) > 0)) cycle
            if (pencil_left(i)) then
                call pencil_point(blocks, pencil_lambdas, x(i), x(i + 1), point, set, stat)
            else
                call pair_point(blocks, x(i), x(i + 1), counts(i), counts(i + 1), point, set, &
                                stat)
            end if
            if (.not. stat%ok()) return
            point%bracket = [x(i), x(i + 1)]
            set%points = [set%points, point]
        end do
    end subroutine find_critical_set

    !> The points of `coarse` (find_critical_set on a coarser discretisation of the same
    !> scene) located on `blocks`: each pencil point at the nearest of `pencil_lambdas`, each
    !> complex_pair point by bisection from a bracket `near` (relative, where given) around
    !> it, else CARRY_WIDTH around it, else its scan bracket: on hp levels the points move
    !> by about the change between the levels, and each halving of the bracket is a solve. `carried` is false, and `set` is to be searched afresh, where the finer
    !> blocks disagree with the coarse structure: another answer at the range's start or
    !> in the middle of an interval between points, a point that moves the other way, is
    !> not bracketed, is not confirmed where it was, or does not lie above the point before
    !> it. A change inside an interval that leaves its middle as it was (two points that only
    !> the finer blocks have) is not seen.
    subroutine carry_critical_set(blocks, coarse, pencil_lambdas, set, carried, stat, &
                                  known_lambda, known_count, near, fresh_pencil)
        type(reduced_blocks_t), intent(in) :: blocks
        type(critical_set_t), intent(in) :: coarse
        real(wp), intent(in) :: pencil_lambdas(:)   !! ascending
        type(critical_set_t), intent(out) :: set
        logical, intent(out) :: carried
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: known_lambda(:)   !! as find_critical_set's
        integer, intent(in), optional :: known_count(:)
        real(wp), intent(in), optional :: near
        !> carry only the complex_pair points, the pencil points taken afresh (carry_pairs)
        logical, intent(in), optional :: fresh_pencil
        type(boundary_point_t) :: point
        real(wp) :: lambda_c, lambda_f, a, b, middle
        integer :: i, n_start, count_a

        carried = .false.
        if (present(fresh_pencil)) then
            if (fresh_pencil) then
                call carry_pairs(blocks, coarse, pencil_lambdas, set, carried, stat, &
                                 known_lambda, known_count, near)
                return
            end if
        end if
        call take_known(set, known_lambda, known_count)
        set%lambda_min = coarse%lambda_min
        set%lambda_max = coarse%lambda_max
        set%contact = size(blocks%kt_nn, 1)
        set%scan_contact = coarse%scan_contact
        allocate (set%points(0))
        call positive_count(blocks, set%lambda_min, n_start, set, stat)
        if (.not. stat%ok()) return
        set%positive_at_min = n_start > 0
        if (set%positive_at_min .neqv. coarse%positive_at_min) return
        ! the middle of every interval between the points (and the range's ends)
        do i = 0, size(coarse%points)
            a = set%lambda_min
            b = set%lambda_max
            if (i > 0) a = coarse%points(i)%lambda
            if (i < size(coarse%points)) b = coarse%points(i + 1)%lambda
            middle = a + 0.5_wp*(b - a)
            call positive_count(blocks, middle, count_a, set, stat)
            if (.not. stat%ok()) return
            if ((count_a > 0) .neqv. coarse%positive_at(middle)) return
        end do
        do i = 1, size(coarse%points)
            lambda_c = coarse%points(i)%lambda
            if (coarse%points(i)%mechanism == MECHANISM_PENCIL) then
                if (size(pencil_lambdas) == 0) return
                lambda_f = pencil_lambdas(minloc(abs(pencil_lambdas - lambda_c), dim=1))
                a = lambda_f - side_offset(lambda_f)
                b = lambda_f + side_offset(lambda_f)
                call pencil_point(blocks, [lambda_f], a, b, point, set, stat)
                if (.not. stat%ok()) return
                point%bracket = [a, b]
            else
                call locate_pair(blocks, coarse%points(i), set, point, stat, near)
                if (.not. stat%ok() .or. point%mechanism /= MECHANISM_COMPLEX_PAIR) return
            end if
            if (point%appears .neqv. coarse%points(i)%appears) return
            if (coarse%points(i)%confirmed .and. .not. point%confirmed) return
            ! two coarse points that became one (the same nearest pencil eigenvalue)
            if (size(set%points) > 0) then
                if (.not. point%lambda > set%points(size(set%points))%lambda) return
            end if
            set%points = [set%points, point]
        end do
        carried = .true.
    end subroutine carry_critical_set

    !> The coarse complex_pair point `coarse_point` located on `blocks` by bisection from the
    !> tightest bracket around it whose ends differ: `near` (relative), CARRY_WIDTH, its scan
    !> bracket. point%mechanism is MECHANISM_PENCIL (never a pair point's) where none does.
    subroutine locate_pair(blocks, coarse_point, set, point, stat, near)
        type(reduced_blocks_t), intent(in) :: blocks
        type(boundary_point_t), intent(in) :: coarse_point
        type(critical_set_t), intent(inout) :: set
        type(boundary_point_t), intent(out) :: point
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: near
        real(wp) :: widths(3), width, a, b, lambda_c
        integer :: try, count_a, count_b
        type(spectrum_memo_t) :: memo   !! the bracket's ends, for pair_point

        point%mechanism = MECHANISM_PENCIL
        lambda_c = coarse_point%lambda
        widths = [0.0_wp, CARRY_WIDTH, 1.0_wp]
        if (present(near)) then
            if (near < CARRY_WIDTH) widths(1) = max(near, 0.0_wp)
        end if
        count_a = 0
        count_b = 0
        do try = 1, 3
            if (.not. widths(try) > 0.0_wp) cycle
            a = coarse_point%bracket(1)
            b = coarse_point%bracket(2)
            if (try < 3) then
                width = widths(try)*max(1.0_wp, abs(lambda_c))
                a = max(lambda_c - width, a)
                b = min(lambda_c + width, b)
            end if
            call positive_count(blocks, a, count_a, set, stat, memo)
            if (stat%ok()) call positive_count(blocks, b, count_b, set, stat, memo)
            if (.not. stat%ok()) return
            if ((count_a > 0) .neqv. (count_b > 0)) exit
        end do
        if ((count_a > 0) .eqv. (count_b > 0)) return
        if (try == 1) then
            call pair_point(blocks, a, b, count_a, count_b, point, set, stat, &
                            NEAR_BISECTION_WIDTH, solved=memo)
        else
            call pair_point(blocks, a, b, count_a, count_b, point, set, stat, solved=memo)
        end if
        if (stat%ok()) point%bracket = coarse_point%bracket
    end subroutine locate_pair

    !> carry_critical_set where the pencil points may differ between the levels: on graded
    !> hp levels real pencil values appear and vanish with the mesh (docs/thresholds.md),
    !> and each such change made the carry fail and the level scan afresh. The pencil points
    !> are exact on any blocks (QZ, then the counts on both sides: the scan's own test), so
    !> only the complex_pair points need the coarse brackets. Here: the coarse set must be a
    !> boundary (its directions alternate from its start); its complex_pair points are
    !> located again (locate_pair), every real pencil eigenvalue in the range whose sides'
    !> counts differ from/to zero is a point, and the points in order must alternate from
    !> the answer at the range's start, with the middle of every interval between them (and
    !> the range's ends) answering as the alternation says. What it cannot see is what
    !> carry_critical_set cannot: two points that only the finer blocks have, both inside one
    !> interval.
    subroutine carry_pairs(blocks, coarse, pencil_lambdas, set, carried, stat, known_lambda, &
                           known_count, near)
        type(reduced_blocks_t), intent(in) :: blocks
        type(critical_set_t), intent(in) :: coarse
        real(wp), intent(in) :: pencil_lambdas(:)   !! ascending
        type(critical_set_t), intent(out) :: set
        logical, intent(out) :: carried
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: known_lambda(:)
        integer, intent(in), optional :: known_count(:)
        real(wp), intent(in), optional :: near
        type(boundary_point_t) :: point
        type(boundary_point_t), allocatable :: found(:)
        real(wp) :: a, b, below, above, last_above
        logical :: positive
        integer :: i, count_m
        integer, allocatable :: order(:)
        real(wp), allocatable :: lambdas(:)

        carried = .false.
        call take_known(set, known_lambda, known_count)
        set%lambda_min = coarse%lambda_min
        set%lambda_max = coarse%lambda_max
        set%contact = size(blocks%kt_nn, 1)
        set%scan_contact = coarse%scan_contact
        allocate (set%points(0), found(0))
        positive = coarse%positive_at_min
        do i = 1, size(coarse%points)
            if (coarse%points(i)%appears .eqv. positive) return   ! not a boundary
            positive = .not. positive
        end do
        call positive_count(blocks, set%lambda_min, count_m, set, stat)
        if (.not. stat%ok()) return
        set%positive_at_min = count_m > 0
        if (set%positive_at_min .neqv. coarse%positive_at_min) return
        do i = 1, size(coarse%points)
            if (coarse%points(i)%mechanism /= MECHANISM_COMPLEX_PAIR) cycle
            if (coarse%points(i)%located_here) then
                point = coarse%points(i)
                point%located_here = .false.
            else
                call locate_pair(blocks, coarse%points(i), set, point, stat, near)
            end if
            if (.not. stat%ok() .or. point%mechanism /= MECHANISM_COMPLEX_PAIR) return
            if (point%appears .neqv. coarse%points(i)%appears) return
            if (coarse%points(i)%confirmed .and. .not. point%confirmed) return
            found = [found, point]
        end do
        ! the pencil points, as scan_points brackets them (one per overlapping bracket)
        last_above = -huge(1.0_wp)
        do i = 1, size(pencil_lambdas)
            below = pencil_lambdas(i) - side_offset(pencil_lambdas(i))
            above = pencil_lambdas(i) + side_offset(pencil_lambdas(i))
            if (.not. (below > set%lambda_min .and. above < set%lambda_max)) cycle
            if (.not. below > last_above) cycle
            last_above = above
            call pencil_point(blocks, [pencil_lambdas(i)], below, above, point, set, stat)
            if (.not. stat%ok()) return
            if ((point%n_below > 0) .eqv. (point%n_above > 0)) cycle   ! not a boundary point
            point%bracket = [below, above]
            found = [found, point]
        end do
        allocate (lambdas(size(found)))   ! a plain array: no temporary for the call
        do i = 1, size(found)
            lambdas(i) = found(i)%lambda
        end do
        order = sort_index(lambdas)
        found = found(order)
        positive = set%positive_at_min
        do i = 0, size(found)
            if (i > 0) then
                if ((found(i)%n_below > 0) .neqv. positive) return
                if (i > 1) then
                    if (.not. found(i)%lambda > found(i - 1)%lambda) return
                end if
                positive = .not. positive
            end if
            a = set%lambda_min
            b = set%lambda_max
            if (i > 0) a = found(i)%lambda
            if (i < size(found)) b = found(i + 1)%lambda
            call positive_count(blocks, a + 0.5_wp*(b - a), count_m, set, stat)
            if (.not. stat%ok()) return
            if ((count_m > 0) .neqv. positive) return
        end do
        set%points = found
        carried = .true.
    end subroutine carry_pairs

    !> The boundary points over `scan`: those of `coarse` carried (carry_critical_set) where
    !> it was searched (scan_contact > 0) and the finer blocks keep its structure, else found
    !> afresh (find_critical_set); set%n_evaluations counts the solves of both tries.
    subroutine search_critical_set(blocks, scan, pencil_lambdas, set, stat, coarse, &
                                   known_lambda, known_count, near)
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: scan(:), pencil_lambdas(:)   !! as find_critical_set's
        type(critical_set_t), intent(out) :: set
        type(status_t), intent(out) :: stat
        type(critical_set_t), intent(in), optional :: coarse
        real(wp), intent(in), optional :: known_lambda(:)
        integer, intent(in), optional :: known_count(:)
        real(wp), intent(in), optional :: near   !! carry_critical_set's first bracket
        logical :: carried
        integer :: tried
        carried = .false.
        ! the pair points alone: pencil values appear and vanish between hp levels
        if (present(coarse)) then
            if (coarse%scan_contact > 0) call carry_critical_set(blocks, coarse, &
                pencil_lambdas, set, carried, stat, known_lambda, known_count, near, &
                fresh_pencil=.true.)
        end if
        if (.not. stat%ok() .or. carried) return
        tried = set%n_evaluations
        call find_critical_set(blocks, scan, pencil_lambdas, set, stat, known_lambda, known_count)
        set%n_evaluations = set%n_evaluations + tried
    end subroutine search_critical_set

    !> Each side's onset (onset_point) followed from `previous` (the set of the level before:
    !> searched, carried or followed) to `blocks` without the structure of the whole range:
    !> a complex_pair onset located again from a bracket `near` (relative) around it
    !> (locate_pair); where that fails, or the onset was a pencil value, the side's pencil
    !> value of `thr` is the onset if no positive mu exists just inside it, else the pair
    !> that landed inside is located from halfway to just inside (as a scan brackets it);
    !> no onset where the side had none and the pencil has none on that side. A side that
    !> gained a pencil value in the range is followed from it the same way; one that lost
    !> the pencil value that was its onset has none if no positive mu is just outside where
    !> it was (graded hp levels make spurious pencil values appear and vanish far from the
    !> onsets: each such level carried the whole range, 54 solves at p = 81 on the
    !> half-contact scene where following takes 20). On each side one count halfway from 0
    !> to the onset (or to the range's end) must find no positive mu. `set` holds the
    !> complex_pair onsets (scan_contact 0: not a search of the range). `tracked` is false
    !> (search instead) where anything else is seen: a pair turned, is no longer confirmed
    !> or cannot be found with no pencil value beside it, a lost pencil onset with a
    !> positive mu still outside it. On hp levels this is what the bars need of every level
    !> but the last, at a fraction of the solves of a carry of the whole range.
    subroutine track_onsets(blocks, previous, thr, set, tracked, stat, near)
        type(reduced_blocks_t), intent(in) :: blocks
        type(critical_set_t), intent(in) :: previous
        type(thresholds_t), intent(in) :: thr
        type(critical_set_t), intent(out) :: set
        logical, intent(out) :: tracked
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: near
        type(boundary_point_t) :: point
        real(wp) :: probe
        integer :: side, i, count_m, count_0
        logical :: located, gained

        tracked = .false.
        set%lambda_min = previous%lambda_min
        set%lambda_max = previous%lambda_max
        set%positive_at_min = previous%positive_at_min
        set%contact = size(blocks%kt_nn, 1)
        set%scan_contact = 0
        allocate (set%points(0))
        ! no search before, or a range without both sides
        if (.not. (previous%lambda_min < 0.0_wp .and. previous%lambda_max > 0.0_wp)) return
        do side = SIDE_MINUS, SIDE_PLUS, SIDE_PLUS - SIDE_MINUS
            i = onset_point(previous, side)
            probe = merge(previous%lambda_max, previous%lambda_min, side == SIDE_PLUS)
            located = .false.
            if (i > 0 .and. .not. thr%found(side)) then
                if (previous%points(i)%mechanism == MECHANISM_PENCIL) then
                    ! the side lost the pencil value that was its onset: none now, unless
                    ! a positive mu is still just outside where it was
                    probe = previous%points(i)%lambda
                    call positive_count(blocks, probe + sign(side_offset(probe), probe), &
                                        count_m, set, stat)
                    if (.not. stat%ok() .or. count_m > 0) return
                    probe = merge(previous%lambda_max, previous%lambda_min, side == SIDE_PLUS)
                    i = 0
                end if
            end if
            ! a side that gained a pencil value in the range (with no onset before, or a
            ! pencil onset, which a followed level does not keep) is followed from it as below
            gained = .false.
            if (i == 0 .and. thr%found(side)) gained = thr%lambda(side) > set%lambda_min .and. &
                                                        thr%lambda(side) < set%lambda_max
            if (i > 0 .or. gained) then
                if (i == 0) then
                    continue
                else if (previous%points(i)%mechanism == MECHANISM_COMPLEX_PAIR) then
                    call locate_pair(blocks, previous%points(i), set, point, stat, near)
                    if (.not. stat%ok()) return
                    located = point%mechanism == MECHANISM_COMPLEX_PAIR .and. &
                              (point%appears .eqv. side == SIDE_PLUS) .and. &
                              (point%confirmed .or. .not. previous%points(i)%confirmed)
                    if (located .and. thr%found(side)) located = &
                        abs(thr%lambda(side)) >= abs(point%lambda)
                end if
                if (.not. located) then
                    ! the onset is the pencil value, or a pair just inside it
                    if (.not. thr%found(side)) return
                    probe = thr%lambda(side) - sign(side_offset(thr%lambda(side)), &
                                                    thr%lambda(side))
                    call positive_count(blocks, probe, count_m, set, stat)
                    if (.not. stat%ok()) return
                    if (count_m == 0) then
                        probe = thr%lambda(side)
                    else
                        ! bracketed by halfway and just inside, as the scan brackets a pair
                        ! by its neighbouring scan points
                        call positive_count(blocks, 0.5_wp*probe, count_0, set, stat)
                        if (.not. stat%ok() .or. count_0 > 0) return
                        if (side == SIDE_PLUS) then
                            call pair_point(blocks, 0.5_wp*probe, probe, count_0, count_m, &
                                            point, set, stat)
                        else
                            call pair_point(blocks, probe, 0.5_wp*probe, count_m, count_0, &
                                            point, set, stat)
                        end if
                        if (.not. stat%ok() .or. (point%appears .neqv. side == SIDE_PLUS)) return
                        point%bracket = [min(0.5_wp*probe, probe), max(0.5_wp*probe, probe)]
                        located = .true.
                    end if
                end if
                if (located) then
                    set%points = [set%points, point]
                    probe = point%lambda
                end if
            end if
            call positive_count(blocks, 0.5_wp*probe, count_m, set, stat)
            if (.not. stat%ok() .or. count_m > 0) return
        end do
        tracked = .true.
    end subroutine track_onsets

    !> Counts already solved, for positive_count to take (both arguments or none).
    pure subroutine take_known(set, known_lambda, known_count)
        type(critical_set_t), intent(inout) :: set
        real(wp), intent(in), optional :: known_lambda(:)
        integer, intent(in), optional :: known_count(:)
        if (.not. (present(known_lambda) .and. present(known_count))) return
        set%known_lambda = known_lambda
        set%known_count = known_count
    end subroutine take_known

    !> The scan sorted, with both sides lambda -+ side_offset of every pencil eigenvalue inside
    !> it; scan points inside such a bracket are dropped, and so is a bracket that would
    !> overlap the previous one (two pencil eigenvalues within 2e-6 relative: one point).
    pure subroutine scan_points(scan, pencil_lambdas, x, pencil_left)
        real(wp), intent(in) :: scan(:), pencil_lambdas(:)
        real(wp), allocatable, intent(out) :: x(:)
        logical, allocatable, intent(out) :: pencil_left(:)
        real(wp), allocatable :: sorted(:), lower(:), upper(:)
        integer :: i, j, n
        real(wp) :: lo, hi
        logical :: take_bracket, fits

        allocate (sorted(size(scan)))   ! then filled: no false -Wuninitialized
        sorted(:) = scan(sort_index(scan))
        lo = sorted(1)
        hi = sorted(size(sorted))
        allocate (lower(size(pencil_lambdas)), upper(size(pencil_lambdas)))
        n = 0
        do j = 1, size(pencil_lambdas)
            associate (below => pencil_lambdas(j) - side_offset(pencil_lambdas(j)), &
                       above => pencil_lambdas(j) + side_offset(pencil_lambdas(j)))
                if (.not. (below > lo .and. above < hi)) cycle
                n = n + 1
                lower(n) = below
                upper(n) = above
            end associate
        end do
        lower = lower(1:n)
        upper = upper(1:n)
        allocate (x(size(sorted) + 2*size(lower)), pencil_left(size(sorted) + 2*size(lower)))
        pencil_left = .false.
        n = 0
        i = 1
        j = 1
        do while (i <= size(sorted) .or. j <= size(lower))
            ! the next item in order: scan point i, or bracket j (its lower end)
            take_bracket = j <= size(lower)
            if (take_bracket .and. i <= size(sorted)) take_bracket = lower(j) <= sorted(i)
            if (take_bracket) then
                if (n == 0) then
                    fits = .true.
                else
                    fits = lower(j) > x(n)
                end if
                if (fits) then
                    pencil_left(n + 1) = .true.
                    x(n + 1:n + 2) = [lower(j), upper(j)]
                    n = n + 2
                end if
                j = j + 1
            else
                if (n == 0) then
                    fits = .true.
                else
                    fits = sorted(i) > x(n)   ! not a duplicate, not inside the last bracket
                end if
                if (fits) then
                    n = n + 1
                    x(n) = sorted(i)
                end if
                i = i + 1
            end if
        end do
        x = x(1:n)
        pencil_left = pencil_left(1:n)
    end subroutine scan_points

    subroutine positive_count(blocks, lambda, n_positive, set, stat, memo)
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: lambda
        integer, intent(out) :: n_positive
        type(critical_set_t), intent(inout) :: set
        type(status_t), intent(out) :: stat
        !> spectra solved on `blocks` before: read where it has `lambda`, else given this one
        type(spectrum_memo_t), intent(inout), optional :: memo
        real(wp), allocatable :: wr(:), wi(:)
        integer :: k
        n_positive = 0
        if (allocated(set%known_lambda)) then
            do k = 1, size(set%known_lambda)
                if (abs(set%known_lambda(k) - lambda) > 0.0_wp) cycle
                n_positive = set%known_count(k)
                return
            end do
        end if
        if (present(memo)) then
            if (memo%find(lambda, wr, wi)) then
                n_positive = count_positive(wr, wi)
                return
            end if
        end if
        call reduced_eigenvalues(blocks, lambda, wr, wi, stat)
        if (stat%ok()) n_positive = count_positive(wr, wi)
        set%n_evaluations = set%n_evaluations + 1
        if (stat%ok() .and. present(memo)) call memo%keep(lambda, wr, wi)
    end subroutine positive_count

    !> A pencil eigenvalue bracketed by [below, above]: the point itself is the QZ value; the
    !> counts at the bracket ends are its confirmation (a change by one: a simple theta
    !> crossing zero).
    subroutine pencil_point(blocks, pencil_lambdas, below, above, point, set, stat)
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: pencil_lambdas(:), below, above
        type(boundary_point_t), intent(out) :: point
        type(critical_set_t), intent(inout) :: set
        type(status_t), intent(out) :: stat
        point%mechanism = MECHANISM_PENCIL
        point%lambda = pencil_lambdas(minloc(abs(pencil_lambdas - 0.5_wp*(below + above)), &
                                             dim=1))
        call positive_count(blocks, below, point%n_below, set, stat)
        if (stat%ok()) call positive_count(blocks, above, point%n_above, set, stat)
        if (.not. stat%ok()) return
        point%appears = point%n_above > 0
        point%confirmed = ((point%n_below > 0) .neqv. (point%n_above > 0)) .and. &
                          abs(point%n_above - point%n_below) == 1
    end subroutine pencil_point

    !> A boundary point inside [a, b] with no pencil eigenvalue: a pair meeting the real axis.
    !> Bisection on the count to BISECTION_WIDTH, then the Illinois variant of regula falsi on
    !> the discriminant of the meeting pair down to adjacent floating-point numbers.
    subroutine pair_point(blocks, a_in, b_in, count_a_in, count_b_in, point, set, stat, width, &
                          solved)
        type(reduced_blocks_t), intent(in) :: blocks
        real(wp), intent(in) :: a_in, b_in
        integer, intent(in) :: count_a_in, count_b_in
        type(boundary_point_t), intent(out) :: point
        type(critical_set_t), intent(inout) :: set
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: width   !! of the bisection; BISECTION_WIDTH
        !> spectra the caller solved on `blocks` (the bracket's ends): not solved again
        type(spectrum_memo_t), intent(in), optional :: solved
        real(wp), allocatable :: wr(:), wi(:)
        real(wp) :: a, b, m, fa, fb, fm, theta0, theta_m, stop_width, below, above
        integer :: count_a, count_b, count_m, last_kept, step
        !> the spectra solved here, by lambda: the discriminant at a bracket end, the point
        !> and the counts beside it are read from a solve already made at the same lambda
        !> (the same blocks, so the same numbers)
        type(spectrum_memo_t) :: memo

        point%mechanism = MECHANISM_COMPLEX_PAIR
        if (present(solved)) memo = solved
        a = a_in
        b = b_in
        count_a = count_a_in
        count_b = count_b_in
        stop_width = BISECTION_WIDTH
        if (present(width)) stop_width = width
        do while (b - a > stop_width*max(1.0_wp, abs(a), abs(b)))
            m = a + 0.5_wp*(b - a)
            call positive_count(blocks, m, count_m, set, stat, memo)
            if (.not. stat%ok()) return
            if ((count_m > 0) .eqv. (count_a > 0)) then
                a = m
                count_a = count_m
            else
                b = m
                count_b = count_m
            end if
        end do
        ! the pair: on the side without a positive theta, the complex pair nearest the
        ! positive real axis; its real part is where it meets the axis, to about the bracket
        m = merge(a, b, count_a == 0)
        call spectrum_at(m, wr, wi)
        if (.not. stat%ok()) return
        theta0 = meeting_estimate(wr*lambda_unit(m), wi*lambda_unit(m))
        point%lambda = a + 0.5_wp*(b - a)
        if (.not. theta0 > 0.0_wp) return   ! no such pair: not confirmed
        call discriminant_at(a, theta0, fa, theta_m)
        if (stat%ok()) call discriminant_at(b, theta0, fb, theta_m)
        if (.not. stat%ok()) return
        if (fa*fb < 0.0_wp) then
            last_kept = 0
            do step = 1, MAX_REFINE
                m = (a*fb - b*fa)/(fb - fa)
                if (.not. (m > a .and. m < b)) m = a + 0.5_wp*(b - a)
                call discriminant_at(m, theta0, fm, theta_m)
                if (.not. stat%ok()) return
                theta0 = theta_m
                if (.not. abs(fm) > 0.0_wp) then
                    a = m
                    b = m
                    exit
                end if
                if ((fm > 0.0_wp) .eqv. (fa > 0.0_wp)) then
                    a = m
                    fa = fm
                    if (last_kept == -1) fb = 0.5_wp*fb   ! Illinois: b kept twice
                    last_kept = -1
                else
                    b = m
                    fb = fm
                    if (last_kept == 1) fa = 0.5_wp*fa
                    last_kept = 1
                end if
                if (b - a <= 2.0_wp*spacing(max(abs(a), abs(b)))) exit
            end do
            point%lambda = merge(a, b, abs(fa) <= abs(fb))
        end if
        call discriminant_at(point%lambda, theta0, point%discriminant, theta_m)
        if (.not. stat%ok()) return
        point%mu_meet = 1.0_wp/theta_m   ! theta_m is unscaled: see discriminant_at
        below = point%lambda - side_offset(point%lambda)
        above = point%lambda + side_offset(point%lambda)
        call discriminant_at(below, theta0, point%discriminant_below, theta_m)
        if (stat%ok()) call positive_count(blocks, below, point%n_below, set, stat, memo)
        if (stat%ok()) call discriminant_at(above, theta0, point%discriminant_above, theta_m)
        if (stat%ok()) call positive_count(blocks, above, point%n_above, set, stat, memo)
        if (.not. stat%ok()) return
        point%appears = point%n_above > 0
        ! real pair (discriminant > 0) on the side with positive theta, complex on the other
        point%confirmed = ((point%n_below > 0) .neqv. (point%n_above > 0)) .and. &
                          abs(point%n_above - point%n_below) == 2 .and. &
                          ((point%discriminant_above > 0.0_wp) .eqv. point%appears) .and. &
                          ((point%discriminant_below > 0.0_wp) .neqv. point%appears) .and. &
                          point%discriminant_above*point%discriminant_below < 0.0_wp

    contains

        !> The eigenvalues times lambda_unit, so that theta keeps one scale across the powers
        !> of two where lambda_unit jumps.
        subroutine discriminant_at(lambda, theta_guess, d, theta_mean)
            real(wp), intent(in) :: lambda, theta_guess
            real(wp), intent(out) :: d, theta_mean
            call spectrum_at(lambda, wr, wi)
            if (stat%ok()) call pair_discriminant(wr*lambda_unit(lambda), wi*lambda_unit(lambda), &
                                                  theta_guess, d, theta_mean)
        end subroutine discriminant_at

        !> The spectrum at `lambda`: from the memo where it was solved here, else solved
        !> (one evaluation) and kept.
        subroutine spectrum_at(lambda, wr_at, wi_at)
            real(wp), intent(in) :: lambda
            real(wp), allocatable, intent(inout) :: wr_at(:), wi_at(:)
            if (memo%find(lambda, wr_at, wi_at)) return
            call reduced_eigenvalues(blocks, lambda, wr_at, wi_at, stat)
            if (.not. stat%ok()) return
            set%n_evaluations = set%n_evaluations + 1
            call memo%keep(lambda, wr_at, wi_at)
        end subroutine spectrum_at
    end subroutine pair_point

    !> The real part of the conjugate pair with positive real part nearest to the real axis
    !> (smallest |Im| / |Re|); 0 when there is none.
    pure real(wp) function meeting_estimate(wr, wi)
        real(wp), intent(in) :: wr(:), wi(:)
        real(wp) :: best
        integer :: j
        meeting_estimate = 0.0_wp
        best = huge(1.0_wp)
        do j = 1, size(wr)
            if (abs(wi(j)) <= 0.0_wp .or. .not. wr(j) > 0.0_wp) cycle
            if (abs(wi(j))/wr(j) < best) then
                best = abs(wi(j))/wr(j)
                meeting_estimate = wr(j)
            end if
        end do
    end function meeting_estimate

    !> The discriminant (theta1 - theta2)^2 / theta_mean^2 of the two eigenvalues of A nearest
    !> `theta_guess`: positive for a real pair, negative for a conjugate pair (-4 Im^2), zero
    !> for a double eigenvalue. As a symmetric function of the pair it is smooth in lambda
    !> across the meeting point, and it is accurate to about eps ||A||^2 / theta^2 because the
    !> 2 x 2 block of the real Schur form that dgeev reads it from is backward stable, even
    !> where the two eigenvalues themselves are only accurate to sqrt(eps).
    pure subroutine pair_discriminant(wr, wi, theta_guess, d, theta_mean)
        real(wp), intent(in) :: wr(:), wi(:), theta_guess
        real(wp), intent(out) :: d, theta_mean
        real(wp) :: distance(size(wr))
        integer :: first, second

        distance = abs(cmplx(wr - theta_guess, wi, wp))
        first = minloc(distance, dim=1)
        if (abs(wi(first)) > 0.0_wp) then
            theta_mean = wr(first)
            d = -4.0_wp*(wi(first)/theta_mean)**2
            return
        end if
        ! a real one: its partner is the nearest other real eigenvalue
        distance(first) = huge(1.0_wp)
        where (abs(wi) > 0.0_wp) distance = huge(1.0_wp)
        second = minloc(distance, dim=1)
        if (.not. distance(second) < huge(1.0_wp)) then   ! only one real eigenvalue
            theta_mean = wr(first)
            d = huge(1.0_wp)
            return
        end if
        theta_mean = 0.5_wp*(wr(first) + wr(second))
        d = ((wr(first) - wr(second))/theta_mean)**2
    end subroutine pair_discriminant
end module critical_set
