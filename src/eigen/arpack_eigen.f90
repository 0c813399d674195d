! SPDX-License-Identifier: MIT
!> The sparse solver: a few eigenvalues of K phi = mu B phi with ARPACK (dnaupd/dneupd,
!> reverse communication, standard mode bmat = 'I'), and the search for the lowest positive
!> real one without knowing where it is.
!>
!> Operator. B = X' M N with X' = lambda T' - N' (model.md sections 4-7) has rank p, so the nonzero
!> eigenvalues theta = 1/mu of OP = K^-1 B are those of the p x p operator
!> A = N K^-1 X' M, with the same eigenvectors y = N phi and phi = K^-1 X' M y. With the
!> contact dofs ordered last in the Cholesky factor P K P' = L L', the trailing 2p x 2p
!> block L_c of L gives (K^-1) on the contact dofs as L_c^-T L_c^-1, so one application of
!> A costs two dense triangular solves of order 2p, independent of n: ARPACK runs in
!> dimension p, not n. With a shift sigma = target /= 0, ARPACK runs on the shift-inverted
!> OP = (K - sigma B)^-1 B, whose reduced form (Sherman-Morrison-Woodbury) is
!> (I - sigma A)^-1 A: a dense LU of order p replaces a sparse LU of K - sigma B, and
!> mu = sigma + 1/nu as usual.
!>
!> The full operator (&eigen operator = 'full') is that OP itself in the n free dofs: one
!> UMFPACK factorization of the non-symmetric K - sigma B (sigma /= 0), or the Cholesky
!> factor of K for sigma = 0, and one sparse product with B per application. It costs a
!> sparse solve per step where the reduced operator costs O(p^2), but needs nothing of
!> order p^2 or p^3 of its own: the search, the certificate and the dense decision are the
!> same for both.
!>
!> ARPACK keeps `save`d state inside dnaupd/dneupd: one solve at a time per process.
module arpack_eigen
    use kinds, only: wp
    use status, only: status_t, STATUS_SOLVER, STATUS_BAD_INPUT
    use strings, only: to_string
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_boundary, only: contact_t
    use sorting, only: sort_index
    use spectrum, only: spectrum_t, order_eigenvalues, backward_error, normalise_mode
    use lapack_interfaces, only: dgeev, lapack_info_message, lapack_eigenvector
    use contact_reduction, only: lift_eigenvectors, lift_share_t
    use arpack_interfaces, only: dnaupd, dneupd, arpack_info_message
    use roundoff, only: left_from_reduced, lowest_roundoff
    use timer, only: wall_time
    use contact_operator, only: contact_operator_t, reduced_operator_t, full_operator_t, &
                                explicit_operator_t
    use unit_scaling, only: units_t
    implicit none
    private
    public :: arpack_options_t, arpack_search, arpack_finish, is_real_ritz
    public :: certify_lowest, CERTIFIED_FOUND, CERTIFIED_NONE, UNDECIDED
    public :: arpack_lowest_positive, wanted_values

    !> Outcomes of the certificate on one ARPACK run (see certify_lowest).
    integer, parameter :: CERTIFIED_FOUND = 1   !! the lowest positive mu is in the set
    integer, parameter :: CERTIFIED_NONE = 2    !! no positive real mu exists
    integer, parameter :: UNDECIDED = 3         !! more eigenvalues are needed to tell

    !> ARPACK runs before the dense decision; the loop also stops once nev passes p/4.
    integer, parameter :: MAX_ATTEMPTS = 8

    !> Past this nev an undecided search goes dense: ARPACK's own work grows like ncv^2 p
    !> per restart, and the dense decision costs under 2 s for p up to about 1000.
    integer, parameter :: NEV_SEARCH_MAX = 48

    !> Largest p for the dense decision on the reduced p x p matrix: LAPACK dgeev with
    !> vectors costs about 25 p^3 flops, a few seconds at p = 2000 on two cores, a minute
    !> at 4000 (measured: eigenvalues alone take 0.54 s at p = 1025).
    integer, parameter :: DENSE_FALLBACK_MAX = 4000

    !> Two runs agree on the lowest positive mu when they match to this relative accuracy:
    !> both are converged to ~eps relative residual, and a simple eigenvalue with condition
    !> below 1e6 is then accurate to 1e-10; 1e-8 leaves room and still tells eigenvalues
    !> apart (neighbouring eigenvalues of the reference scene differ by more than 1e-3).
    real(wp), parameter :: AGREE_TOL = 1.0e-8_wp

    type, public :: arpack_options_t
        integer :: nev = 6               !! eigenvalues per run (first attempt)
        integer :: ncv = 0               !! Krylov dimension, 0: max(2 nev + 1, 20)
        integer :: maxit = 1000          !! restarts per run
        real(wp) :: tol = 0.0_wp         !! relative residual tolerance, 0: machine epsilon
        real(wp) :: target = 0.0_wp      !! shift sigma; 0: no shift
        !> also every positive real mu in (0, cn_max], certified complete; 0: the lowest only
        real(wp) :: cn_max = 0.0_wp
        !> ARPACK on (K - sigma B)^-1 B in the n free dofs instead of the p x p reduction
        logical :: full = .false.
        !> For messages: the problem solved is the input one in the scaled `units`
        !> (problem_t), and `target_input` is &eigen target as given.
        type(units_t) :: units
        real(wp) :: target_input = 0.0_wp
    end type arpack_options_t

    !> One ARPACK run's result: the converged Ritz values nu of the operator and their
    !> vectors y (p), as complex numbers (conjugate pairs both present).
    type :: ritz_t
        complex(wp), allocatable :: nu(:)
        complex(wp), allocatable :: y(:, :)
        logical, allocatable :: is_real(:)
        integer :: info = 0
        integer :: n_operator = 0
        !> left eigenvector (p) of the lowest positive mu, when the dense decision found it
        real(wp), allocatable :: left(:)
    end type ritz_t

    !> A certified ARPACK search (arpack_search), kept for arpack_finish: the operator it
    !> ran on (full_operator_t or reduced_operator_t, as options%full chose), the last run
    !> and its mu, and whether two runs confirmed the answer.
    type, public :: arpack_search_t
        private
        class(contact_operator_t), allocatable :: op
        type(ritz_t) :: run
        complex(wp), allocatable :: mu(:)
        logical :: confirmed = .false.
        logical :: found_before = .false.
        integer :: n_operator = 0
        !> left eigenvector (p, or n for the full operator) of the lowest positive mu from
        !> the search's first run, on the transposed operator, and that run's mu for it
        real(wp), allocatable :: left(:)
        real(wp) :: left_mu = 0.0_wp
    contains
        procedure :: needs_dense_decision => search_needs_dense_decision
    end type arpack_search_t

contains

    !> Is a Ritz value nu real? ARPACK reads eigenvalues off a real Schur form, where a real
    !> eigenvalue normally has an exactly zero imaginary part. But two close real eigenvalues
    !> (or a double one) perturbed by a backward error of relative size tol can split into a
    !> complex pair with imaginary part up to about sqrt(tol) |nu|; below that the data
    !> cannot tell a complex pair from two real eigenvalues, so they count as real (their
    !> backward errors on the pencil are reported, so a wrong call would show).
    elemental logical function is_real_ritz(nu, tol)
        complex(wp), intent(in) :: nu
        real(wp), intent(in) :: tol   !! ARPACK's relative tolerance (>= epsilon)
        is_real_ritz = abs(aimag(nu)) <= sqrt(tol)*abs(nu)
    end function is_real_ritz

    !> Certificate of one set of eigenvalues mu, the ones nearest sigma (ARPACK's 'LM' on
    !> nu = 1/(mu - sigma); sigma = 0 gives the smallest |mu|, theta = 1/mu of largest
    !> modulus). Every mu outside the set is at distance >= r = max |mu - sigma| over the set
    !> from sigma. The lowest positive real mu_+ in the set is then the lowest overall when
    !> the disc |mu - sigma| <= r covers ]0, mu_+], i.e. sigma - r <= 0 (always so for
    !> sigma = 0): any positive real mu below mu_+ would be nearer sigma than r. With
    !> `complete` (the set is the whole spectrum) no positive real mu in it means none
    !> exists. Returns CERTIFIED_FOUND (`lowest` its index), CERTIFIED_NONE or UNDECIDED.
    !> With cn_max > 0 the disc must also reach cn_max (sigma + r >= cn_max), so that the set
    !> holds every positive real mu in (0, cn_max].
    pure subroutine certify_lowest(mu, is_real, sigma, complete, outcome, lowest, cn_max)
        complex(wp), intent(in) :: mu(:)
        logical, intent(in) :: is_real(:)
        real(wp), intent(in) :: sigma
        logical, intent(in) :: complete
        integer, intent(out) :: outcome, lowest
        real(wp), intent(in), optional :: cn_max
        real(wp) :: radius, reach
        integer :: i
        lowest = 0
        do i = 1, size(mu)
            if (.not. is_real(i) .or. .not. real(mu(i), wp) > 0.0_wp) cycle
            if (lowest == 0) then
                lowest = i
            else if (real(mu(i), wp) < real(mu(lowest), wp)) then
                lowest = i
            end if
        end do
        outcome = UNDECIDED
        if (complete) then
            outcome = merge(CERTIFIED_FOUND, CERTIFIED_NONE, lowest > 0)
        else if (size(mu) > 0 .and. lowest > 0) then
            radius = maxval(abs(mu - sigma))
            reach = 0.0_wp
            if (present(cn_max)) reach = cn_max
            if (sigma - radius <= 0.0_wp .and. sigma + radius >= reach) outcome = CERTIFIED_FOUND
        end if
    end subroutine certify_lowest

    !> The positive real mu a run must report, ascending: the lowest, and every one up to
    !> cn_max. Two runs agree when these lists match (certified_search).
    pure function wanted_values(mu, is_real, cn_max) result(values)
        complex(wp), intent(in) :: mu(:)
        logical, intent(in) :: is_real(:)
        real(wp), intent(in) :: cn_max
        real(wp), allocatable :: values(:)
        logical :: positive(size(mu))
        positive = is_real .and. real(mu, wp) > 0.0_wp
        values = pack(real(mu, wp), positive)
        if (size(values) == 0) return
        values = values(sort_index(values))
        values = pack(values, values <= cn_max .or. values <= values(1))
    end function wanted_values

    !> The first step towards the eigenvalues of K phi = mu B phi nearest the target (0:
    !> smallest in modulus), always including the lowest positive real one when it is
    !> found; arpack_finish then gives them in output order, with full eigenvectors of the
    !> first `n_keep`, the backward error of every pair on (K, B), and a `warning` that is
    !> empty when the lowest positive eigenvalue (or its absence) is certified.
    !> Strategy (docs/numerics.md, "ARPACK solver"): ARPACK on nev eigenvalues nearest the target;
    !> a certified answer is confirmed by a second run from another start vector; nev
    !> doubles while undecided; past p/4 (or if runs keep disagreeing) all p eigenvalues of
    !> the reduced matrix are computed densely (arpack_finish), which decides every case.
    !> The same holds for both operators (options%full); the full one's eigenvectors come
    !> from ARPACK itself. `chol` is a factor of K: the full operator only solves with it
    !> (any ordering), the reduced one reads its trailing block (contact dofs last).
    !> `reduced`, A / lambda_unit(lambda) formed from contact blocks the caller shares
    !> between lambdas (scaled_reduced_matrix), replaces the reduced operator without shift
    !> by one dense product per step (2 p^2 flops against two triangular solves of order 2p,
    !> 8 p^2): the same matrix, the same search and certificate.
    subroutine arpack_search(k, b, chol, contact, lambda, options, search, stat, reduced)
        type(csr_matrix_t), intent(in) :: k, b
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda
        type(arpack_options_t), intent(in) :: options
        type(arpack_search_t), intent(out) :: search
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: reduced(:, :)   !! (p, p)
        integer :: p

        p = contact%p()
        if (p - 2 < 1) then   ! ARPACK needs nev + 2 <= ncv <= n
            call stat%fail(STATUS_BAD_INPUT, 'arpack: '//to_string(p)//' contact nodes: '// &
                'ARPACK needs at least 3 (nev + 2 <= ncv <= p); use solver = ''dense''')
            return
        end if
        if (options%full) then
            allocate (full_operator_t :: search%op)
        else if (present(reduced) .and. .not. abs(options%target) > 0.0_wp) then
            allocate (explicit_operator_t :: search%op)
        else
            allocate (reduced_operator_t :: search%op)
        end if
        select type (op => search%op)
        type is (full_operator_t)
            call op%setup(k, b, chol, contact, lambda, options%target, stat, &
                          options%target_input, options%units)
        type is (reduced_operator_t)
            call op%setup(chol, contact, lambda, options%target, stat, options%target_input, &
                          options%units)
        type is (explicit_operator_t)
            call op%setup(reduced, lambda)
        end select
        if (.not. stat%ok()) return
        ! the first run on the transposed operator gives the left vector as it certifies,
        ! where an undecided search always ends in the dense decision (which overwrites it)
        if (p <= DENSE_FALLBACK_MAX) then
            call certified_search(search%op, chol, options, search%run, search%mu, &
                                  search%confirmed, search%found_before, search%n_operator, &
                                  stat, search%left, search%left_mu)
        else
            call certified_search(search%op, chol, options, search%run, search%mu, &
                                  search%confirmed, search%found_before, search%n_operator, &
                                  stat)
        end if
    end subroutine arpack_search

    !> Whether arpack_finish decides densely: the search is unconfirmed and p is small enough.
    !> The dense decision reads the trailing block of a factor with the contact dofs last.
    pure logical function search_needs_dense_decision(this)
        class(arpack_search_t), intent(in) :: this
        search_needs_dense_decision = .false.
        if (.not. allocated(this%op)) return   ! the search failed before its operator
        search_needs_dense_decision = .not. this%confirmed .and. &
                                      this%op%p <= DENSE_FALLBACK_MAX
    end function search_needs_dense_decision

    !> The spectrum from a finished search (arpack_search): the dense decision when the
    !> search is undecided, the eigenvectors and the round-off bound of the lowest. `chol`
    !> is the search's factor, or one with the contact dofs last when
    !> search%needs_dense_decision() and the search's factor is not (the full operator's).
    !> `lowest_only` (reduced operators): only the lowest positive mu is lifted, with its
    !> backward error and round-off bound; the other eigenvalues keep their values, their
    !> backward errors unknown (-1), for a caller that reports that one mu alone (an hp
    !> sweep's points): the lift and the backward errors of all the others were most of it.
    !> `share`: the lifts' data on `chol` made once for many lambdas (lift_share_t).
    subroutine arpack_finish(k, b, chol, contact, lambda, options, n_keep, search, spec, &
                             warning, stat, lowest_only, share)
        type(csr_matrix_t), intent(in) :: k, b
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda
        type(arpack_options_t), intent(in) :: options
        integer, intent(in) :: n_keep
        type(arpack_search_t), intent(inout) :: search
        type(spectrum_t), intent(out) :: spec
        character(len=:), allocatable, intent(out) :: warning
        type(status_t), intent(out) :: stat
        logical, intent(in), optional :: lowest_only
        type(lift_share_t), intent(in), optional :: share
        type(reduced_operator_t) :: decision
        real(wp) :: radius
        integer :: cap
        logical :: lifted

        warning = ''
        cap = search%op%p - 2
        ! reduced eigenvectors y are lifted to phi; the full operator's are phi already
        select type (op => search%op)
        type is (full_operator_t)
            lifted = .false.
        class default
            lifted = .true.
        end select
        if (search%needs_dense_decision()) then
            ! all p eigenvalues of the reduced p x p matrix decide (O(p^3))
            select type (op => search%op)
            type is (reduced_operator_t)
                call dense_ritz(op, options%nev, options%cn_max, search%run, stat)
                if (.not. stat%ok()) return
                search%mu = op%mu_of(search%run%nu)
            class default
                call decision%setup(chol, contact, lambda, options%target, stat, &
                                    options%target_input, options%units)
                if (.not. stat%ok()) return
                call dense_ritz(decision, options%nev, options%cn_max, search%run, stat)
                if (.not. stat%ok()) return
                search%mu = decision%mu_of(search%run%nu)
                lifted = .true.
            end select
        else if (.not. search%confirmed) then
            radius = 0.0_wp
            if (size(search%mu) > 0) radius = maxval(abs(search%mu - options%target))
            if (search%found_before) then
                warning = 'the lowest positive eigenvalue is not certified: ARPACK runs '// &
                    'from different start vectors disagree on it'
            else
                warning = 'the lowest positive eigenvalue is not certified: none found '// &
                    'with |mu - target| <= '//to_string(radius)
            end if
            if (search%run%info /= 0) warning = warning//'; '// &
                arpack_info_message('dnaupd', search%run%info)
        end if
        if (size(search%run%nu) == 0) then
            call stat%fail(STATUS_SOLVER, 'arpack: no Ritz value converged ('// &
                arpack_info_message('dnaupd', search%run%info)//'); raise maxit or ncv')
            return
        end if
        if (lifted) then
            call fill_spectrum(k, b, chol, contact, lambda, search%mu, search%run, n_keep, &
                               spec, stat, lowest_only, share)
        else
            call fill_full_spectrum(k, b, search%mu, search%run, n_keep, spec)
        end if
        if (.not. stat%ok()) return
        spec%n_operator = search%n_operator
        spec%dense_decision = search%needs_dense_decision()
        call add_roundoff(max(options%nev, size(search%run%nu)))
    contains

        !> spec%roundoff of the lowest positive mu (module roundoff)
        !> from its left eigenvector: of the dense decision's reduced matrix when it decided,
        !> else the search's first run's (on the transposed operator) where that run certified
        !> the same mu, else from one ARPACK run on the transposed operator (the last run's
        !> nev). A failure only leaves them unknown.
        subroutine add_roundoff(nev)
            integer, intent(in) :: nev
            real(wp), allocatable :: w(:), y(:)
            type(status_t) :: left_stat
            real(wp) :: start
            allocate (spec%roundoff(spec%n()), source=-1.0_wp)
            if (spec%lowest_positive() /= 1 .or. size(spec%vectors, 2) < 1) return
            start = wall_time()
            if (spec%dense_decision) then
                if (allocated(search%run%left)) call left_from_reduced(chol, contact, k%n(), &
                    search%run%left, y, left_stat, share)
            else
                ! the operator's left vector (reduced, or of the full operator)
                if (search_left_agrees()) then
                    w = search%left
                else
                    call left_eigenvector(search%op, chol, options, min(nev, cap), &
                                          real(spec%mu(1), wp), w, left_stat)
                end if
                if (.not. lifted) then
                    call move_alloc(w, y)
                else if (left_stat%ok() .and. allocated(w)) then
                    call left_from_reduced(chol, contact, k%n(), w, y, left_stat, share)
                end if
            end if
            if (left_stat%ok()) call lowest_roundoff(k, b, contact, lambda, real(spec%mu(1), wp), &
                real(spec%vectors(:, 1), wp), y, spec%roundoff(1))
            if (spec%roundoff(1) >= 0.0_wp) call move_alloc(y, spec%left)
            spec%roundoff_seconds = wall_time() - start
        end subroutine add_roundoff

        !> Whether the search's transposed run certified the mu reported as lowest (to the
        !> agreement of two runs): its vector is then that mu's left eigenvector.
        logical function search_left_agrees()
            real(wp) :: mu
            search_left_agrees = .false.
            if (.not. allocated(search%left) .or. .not. search%confirmed) return
            mu = real(spec%mu(1), wp)
            search_left_agrees = abs(search%left_mu - mu) <= AGREE_TOL*abs(mu)
        end function search_left_agrees
    end subroutine arpack_finish

    !> The eigenvector of the transposed operator for the real eigenvalue
    !> nearest `mu_lowest`, from one ARPACK run of `nev` values: the left eigenvector of
    !> the lowest positive mu (reduced: w with A' w = theta w; full: y with K y = mu B' y).
    !> Unallocated when no real Ritz value converged.
    subroutine left_eigenvector(op, factor, options, nev, mu_lowest, left, stat)
        class(contact_operator_t), intent(inout) :: op
        type(cholesky_t), intent(in) :: factor   !! of K, for the operator's apply
        type(arpack_options_t), intent(in) :: options
        integer, intent(in) :: nev
        real(wp), intent(in) :: mu_lowest
        real(wp), allocatable, intent(out) :: left(:)
        type(status_t), intent(out) :: stat
        type(ritz_t) :: run
        complex(wp), allocatable :: mu(:)
        integer :: pick, i
        call run_arpack(op, factor, nev, options, 1, run, stat, transposed=.true.)
        if (.not. stat%ok()) return
        mu = op%mu_of(run%nu)
        pick = 0
        do i = 1, size(mu)
            if (.not. run%is_real(i)) cycle
            if (pick == 0) then
                pick = i
            else if (abs(mu(i) - mu_lowest) < abs(mu(pick) - mu_lowest)) then
                pick = i
            end if
        end do
        if (pick > 0) left = real(run%y(:, pick), wp)
    end subroutine left_eigenvector

    !> ARPACK runs on `op` until the lowest positive real mu (and with options%cn_max every
    !> one up to it) is certified (certify_lowest) by two runs from different start vectors
    !> that agree on them (`confirmed`, wanted_values), doubling nev
    !> while undecided; stops undecided past nev > p/4 or NEV_SEARCH_MAX. `run` and `mu` are
    !> the last run's Ritz values and mu = target + 1/nu; `found_before`: the last run
    !> certified a value that the one before did not confirm.
    !> With `left`: the first run is on the transposed operator, which has the same
    !> eigenvalues, so its certified lowest positive mu counts as the first of the two
    !> agreeing runs; its vector, the left eigenvector of that mu, is returned in `left`
    !> (its mu in left_mu; unallocated when that run certified nothing). One run fewer than
    !> two runs and a third on the transposed operator for the left vector.
    subroutine certified_search(op, factor, options, run, mu, confirmed, found_before, &
                                n_operator, stat, left, left_mu)
        class(contact_operator_t), intent(inout) :: op
        type(cholesky_t), intent(in) :: factor   !! of K, for the operator's apply
        type(arpack_options_t), intent(in) :: options
        type(ritz_t), intent(out) :: run
        complex(wp), allocatable, intent(out) :: mu(:)
        logical, intent(out) :: confirmed, found_before
        integer, intent(out) :: n_operator
        type(status_t), intent(out) :: stat
        real(wp), allocatable, intent(out), optional :: left(:)
        real(wp), intent(out), optional :: left_mu
        real(wp), allocatable :: values_now(:), values_before(:)
        integer :: p, nev, cap, attempt, outcome, lowest
        logical :: transposed

        p = op%p
        cap = p - 2
        nev = min(options%nev, cap)
        n_operator = 0
        found_before = .false.
        confirmed = .false.
        if (present(left_mu)) left_mu = 0.0_wp
        do attempt = 1, MAX_ATTEMPTS
            transposed = present(left) .and. attempt == 1
            call run_arpack(op, factor, nev, options, attempt, run, stat, transposed)
            if (.not. stat%ok()) return
            n_operator = n_operator + run%n_operator
            mu = op%mu_of(run%nu)
            call certify_lowest(mu, run%is_real, options%target, .false., outcome, lowest, &
                                options%cn_max)
            ! with info = 1 (maxit) only some wanted values converged: nearer ones may be
            ! missing, so the disc argument does not hold
            if (run%info /= 0) outcome = UNDECIDED
            if (outcome == CERTIFIED_FOUND) then
                values_now = wanted_values(mu, run%is_real, options%cn_max)
                if (found_before) then
                    confirmed = size(values_now) == size(values_before)
                    if (confirmed) confirmed = all(abs(values_now - values_before) <= &
                                                   AGREE_TOL*abs(values_now))
                    if (confirmed) exit
                    nev = min(2*nev, cap)   ! two runs disagree: look wider
                end if
                found_before = .true.
                values_before = values_now
                if (transposed) then
                    left = real(run%y(:, lowest), wp)
                    if (present(left_mu)) left_mu = real(mu(lowest), wp)
                end if
            else
                found_before = .false.
                nev = min(2*nev, cap)
            end if
            if (.not. found_before .and. (4*nev > p .or. nev > NEV_SEARCH_MAX)) exit
        end do
    end subroutine certified_search

    !> The lowest positive real mu of the reduced problem A y = (1/mu) y for an explicit
    !> p x p matrix `a` = (lambda Kt_nt - Kt_nn) M (a lambda sweep has the Kt blocks already),
    !> by the certified ARPACK search without shift (options%target is ignored: the disc
    !> certificate needs sigma <= 0, see certify_lowest). `certified` is false when ARPACK
    !> could not decide (in particular when no positive mu exists, which only the complete
    !> spectrum can show): the caller then decides densely; `found` and `mu` are meaningful
    !> only when certified. `n_operator` counts the products with A.
    subroutine arpack_lowest_positive(a, options, mu, found, certified, n_operator, stat)
        real(wp), intent(in) :: a(:, :)
        type(arpack_options_t), intent(in) :: options
        real(wp), intent(out) :: mu
        logical, intent(out) :: found, certified
        integer, intent(out) :: n_operator
        type(status_t), intent(out) :: stat
        type(explicit_operator_t) :: op
        type(cholesky_t) :: no_factor   ! the explicit operator solves nothing
        type(arpack_options_t) :: unshifted
        type(ritz_t) :: run
        complex(wp), allocatable :: mu_all(:)
        integer :: outcome, lowest
        logical :: found_before

        mu = 0.0_wp
        found = .false.
        certified = .false.
        n_operator = 0
        if (size(a, 1) - 2 < 1) return   ! too small for ARPACK: the caller goes dense
        call op%setup(a)
        unshifted = options
        unshifted%target = 0.0_wp
        call certified_search(op, no_factor, unshifted, run, mu_all, certified, found_before, n_operator, &
                              stat)
        if (.not. stat%ok() .or. .not. certified) return
        call certify_lowest(mu_all, run%is_real, 0.0_wp, .false., outcome, lowest)
        found = .true.
        mu = real(mu_all(lowest), wp)
    end subroutine arpack_lowest_positive

    !> All p eigenvalues of the reduced operator by LAPACK dgeev, as a run would give them
    !> (nu of the operator), keeping the `n_report` of largest |nu| (nearest the target) and
    !> the lowest positive real mu, and every positive real mu up to cn_max; the rest are
    !> dropped before eigenvectors are formed.
    subroutine dense_ritz(op, n_report, cn_max, run, stat)
        type(reduced_operator_t), intent(in) :: op
        integer, intent(in) :: n_report
        real(wp), intent(in) :: cn_max
        type(ritz_t), intent(out) :: run
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: a(:, :), wr(:), wi(:), vr(:, :), work(:), vl(:, :), size_nu(:)
        complex(wp), allocatable :: nu(:), mu(:)
        logical, allocatable :: keep(:), is_real(:), chosen(:)
        real(wp) :: query(1)
        integer :: p, info, j, i, outcome, lowest

        p = op%p
        call op%dense_a(a, stat)
        if (.not. stat%ok()) return
        ! left eigenvectors too: the round-off bound of the lowest positive mu needs its own
        allocate (wr(p), wi(p), vr(p, p), vl(p, p))
        call dgeev('V', 'V', p, a, p, wr, wi, vl, p, vr, p, query, -1, info)
        allocate (work(max(1, int(query(1)))))
        call dgeev('V', 'V', p, a, p, wr, wi, vl, p, vr, p, work, size(work), info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, lapack_info_message('dgeev', info))
            return
        end if
        ! theta -> nu = theta/(1 - sigma theta) = 1/(mu - sigma); theta = 0 is mu = infinity
        nu = cmplx(wr, wi, wp)
        keep = abs(nu) > 0.0_wp
        is_real = .not. (abs(wi) > 0.0_wp)
        where (keep) nu = nu/(1.0_wp - (op%sigma*op%lambda_scale)*nu)
        allocate (mu(p), source=(0.0_wp, 0.0_wp))
        where (keep) mu = op%mu_of(nu)
        call certify_lowest(mu, is_real .and. keep, op%sigma, .true., outcome, lowest)
        ! the n_report largest |nu|, the lowest positive mu, and the partners of pairs
        allocate (chosen(p), source=.false.)
        size_nu = merge(abs(nu), -1.0_wp, keep)
        do i = 1, min(n_report, count(keep))
            j = maxloc(size_nu, dim=1, mask=.not. chosen)
            chosen(j) = .true.
        end do
        if (lowest > 0) then
            chosen(lowest) = .true.
            run%left = vl(:, lowest)   ! real: the lowest positive mu is real
        end if
        chosen = chosen .or. (is_real .and. keep .and. real(mu, wp) > 0.0_wp .and. &
                              real(mu, wp) <= cn_max)
        do j = 1, p
            if (.not. chosen(j) .or. is_real(j)) cycle
            if (wi(j) > 0.0_wp .and. j < p) chosen(j + 1) = .true.
            if (wi(j) < 0.0_wp .and. j > 1) chosen(j - 1) = .true.
        end do
        allocate (run%nu(count(chosen)), run%y(p, count(chosen)), run%is_real(count(chosen)))
        i = 0
        do j = 1, p
            if (.not. chosen(j)) cycle
            i = i + 1
            run%nu(i) = nu(j)
            run%is_real(i) = is_real(j)
            run%y(:, i) = lapack_eigenvector(vr, wi, j)
        end do
    end subroutine dense_ritz

    !> One ARPACK run: standard mode on `op`, nev wanted ('LR' without shift, 'LM' with),
    !> from a deterministic start vector that differs between attempts; on the transposed
    !> operator with `transposed` (default false).
    subroutine run_arpack(op, factor, nev_wanted, options, attempt, run, stat, transposed)
        class(contact_operator_t), intent(inout) :: op
        type(cholesky_t), intent(in) :: factor   !! of K, for the operator's apply
        integer, intent(in) :: nev_wanted, attempt
        type(arpack_options_t), intent(in) :: options
        type(ritz_t), intent(out) :: run
        type(status_t), intent(out) :: stat
        logical, intent(in), optional :: transposed
        real(wp), allocatable :: resid(:), v(:, :), workd(:), workl(:), dr(:), di(:), z(:, :), &
                                 workev(:), start(:)
        logical, allocatable :: select(:)
        logical :: left
        integer :: iparam(11), ipntr(14), ido, info, n, ncv, lworkl, nconv, j, i, nev
        character(len=2) :: which
        real(wp) :: tol

        ! ARPACK may adjust nev in place to keep a conjugate pair together (seen with arpack-ng
        ! 3.8 on tiny n): give it a private copy.
        nev = nev_wanted
        left = .false.
        if (present(transposed)) left = transposed
        n = op%n
        ncv = options%ncv
        if (ncv == 0) ncv = max(2*nev + 1, 20)
        ! at most p: the full operator has rank p, and a longer Krylov basis would only add
        ! null vectors of B (Ritz values nu ~ 0, mu ~ 1/eps)
        ncv = min(max(ncv, nev + 2), op%p)
        which = 'LM'
        tol = options%tol
        lworkl = 3*ncv**2 + 6*ncv
        allocate (resid(n), v(n, ncv), workd(3*n), workl(lworkl))
        ! Start vector: smooth plus oscillating parts, nonzero in every component and in
        ! every eigendirection generically; the phase changes with the attempt.
        resid = [(1.0_wp + 0.5_wp*sin(real(i*attempt, wp)*0.7548776662466927_wp), i=1, n)]
        if (op%start_in_range) then
            start = resid
            call op%apply(factor, start, resid, left, stat)
            if (.not. stat%ok()) return
            run%n_operator = 1
        end if
        iparam = 0
        iparam(1) = 1               ! exact shifts
        iparam(3) = options%maxit
        iparam(7) = 1               ! mode 1: the operator is already shift-inverted
        ipntr = 0
        ido = 0
        info = 1                    ! use resid as the start vector
        do
            call dnaupd(ido, 'I', n, which, nev, tol, resid, ncv, v, n, iparam, ipntr, &
                        workd, workl, lworkl, info)
            if (ido /= 1 .and. ido /= -1) exit   ! 99: done; no other request in mode 1
            run%n_operator = run%n_operator + 1
            call op%apply(factor, workd(ipntr(1):ipntr(1) + n - 1), &
                          workd(ipntr(2):ipntr(2) + n - 1), left, stat)
            if (.not. stat%ok()) return
        end do
        run%info = info
        if (info < 0) then
            call stat%fail(STATUS_SOLVER, arpack_info_message('dnaupd', info))
            return
        end if
        nconv = iparam(5)
        allocate (run%nu(0), run%y(n, 0), run%is_real(0))
        if (nconv == 0) return

        allocate (select(ncv), dr(nev + 1), di(nev + 1), z(n, nev + 1), workev(3*ncv))
        call dneupd(.true., 'A', select, dr, di, z, n, 0.0_wp, 0.0_wp, workev, 'I', n, which, &
                    nev, tol, resid, ncv, v, n, iparam, ipntr, workd, workl, lworkl, info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, arpack_info_message('dneupd', info))
            return
        end if
        nconv = min(iparam(5), nev + 1)
        ! dneupd's layout: a complex pair is dr(j) +- i di(j) with di(j) > 0 first, its vector
        ! in columns j (real part) and j + 1 (imaginary part). A pair cut by nconv is dropped,
        ! and so is a zero Ritz value (mu infinite, only exactly at a critical lambda).
        deallocate (run%nu, run%y, run%is_real)
        allocate (run%nu(nconv), run%y(n, nconv))
        i = 0
        j = 1
        do while (j <= nconv)
            if (.not. (abs(di(j)) > 0.0_wp)) then
                if (abs(dr(j)) > 0.0_wp) then
                    i = i + 1
                    run%nu(i) = cmplx(dr(j), 0.0_wp, wp)
                    run%y(:, i) = cmplx(z(:, j), 0.0_wp, wp)
                end if
                j = j + 1
            else if (j < nconv) then
                run%nu(i + 1) = cmplx(dr(j), abs(di(j)), wp)
                run%nu(i + 2) = conjg(run%nu(i + 1))
                run%y(:, i + 1) = cmplx(z(:, j), sign(1.0_wp, di(j))*z(:, j + 1), wp)
                run%y(:, i + 2) = conjg(run%y(:, i + 1))
                i = i + 2
                j = j + 2
            else
                j = j + 1
            end if
        end do
        run%nu = run%nu(1:i)
        run%y = run%y(:, 1:i)
        nconv = i
        run%is_real = is_real_ritz(run%nu, max(tol, epsilon(1.0_wp)))
        ! a pair judged real: two real eigenvalues sharing a 2-d invariant subspace
        do j = 1, nconv
            if (run%is_real(j) .and. abs(aimag(run%nu(j))) > 0.0_wp) then
                if (aimag(run%nu(j)) > 0.0_wp) then
                    run%y(:, j) = real(run%y(:, j), wp)
                else
                    run%y(:, j) = cmplx(-aimag(run%y(:, j)), 0.0_wp, wp)
                end if
                run%nu(j) = real(run%nu(j), wp)
            end if
        end do
    end subroutine run_arpack

    !> The spectrum of the final run, in output order: full eigenvectors
    !> phi = K^-1 (lambda T' - N') M y, backward errors on (K, B) for every pair, modes of the
    !> first n_keep (contact_reduction's lift, as for the dense solver). With `lowest_only`
    !> the lowest positive pair alone (first in output order; none when there is none): its
    !> mode and backward error, the others' backward errors -1 (not computed).
    subroutine fill_spectrum(k, b, chol, contact, lambda, mu, run, n_keep, spec, stat, &
                             lowest_only, share)
        type(csr_matrix_t), intent(in) :: k, b
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda
        complex(wp), intent(in) :: mu(:)
        type(ritz_t), intent(in) :: run
        integer, intent(in) :: n_keep
        type(spectrum_t), intent(out) :: spec
        type(status_t), intent(out) :: stat
        logical, intent(in), optional :: lowest_only
        type(lift_share_t), intent(in), optional :: share
        integer, allocatable :: order(:)
        real(wp), allocatable :: residual(:)
        integer :: lift

        call ordered_values(mu, run, spec, order)
        lift = size(mu)
        if (present(lowest_only)) then
            if (lowest_only) lift = min(1, spec%lowest_positive())
        end if
        call lift_eigenvectors(k, b, chol, contact, lambda, spec%mu(1:lift), &
                               run%y(:, order(1:lift)), n_keep, residual, spec%vectors, stat, &
                               share)
        if (.not. stat%ok()) return
        allocate (spec%residual(size(mu)), source=-1.0_wp)
        spec%residual(1:lift) = residual
    end subroutine fill_spectrum

    !> spec%mu, kind and condition (unknown: -1) of a run's eigenvalues `mu` in output order,
    !> and `order`, the permutation from the run's order to it.
    subroutine ordered_values(mu, run, spec, order)
        complex(wp), intent(in) :: mu(:)
        type(ritz_t), intent(in) :: run
        type(spectrum_t), intent(inout) :: spec
        integer, allocatable, intent(out) :: order(:)
        integer, allocatable :: kinds(:)
        allocate (order(size(mu)), kinds(size(mu)))
        call order_eigenvalues(mu, run%is_real, order, kinds)
        spec%mu = mu(order)
        where (run%is_real(order)) spec%mu = real(spec%mu, wp)
        spec%kind = kinds
        allocate (spec%condition(size(mu)), source=-1.0_wp)
    end subroutine ordered_values

    !> The spectrum of the final run of the full operator, in output order: ARPACK's Ritz
    !> vectors are the eigenvectors phi of the pencil; the backward error of every pair on
    !> (K, B), the first n_keep normalised and kept.
    subroutine fill_full_spectrum(k, b, mu, run, n_keep, spec)
        type(csr_matrix_t), intent(in) :: k, b
        complex(wp), intent(in) :: mu(:)
        type(ritz_t), intent(in) :: run
        integer, intent(in) :: n_keep
        type(spectrum_t), intent(out) :: spec
        integer, allocatable :: order(:)
        real(wp) :: k_norm, b_norm
        integer :: n_ev, i

        n_ev = size(mu)
        call ordered_values(mu, run, spec, order)
        allocate (spec%residual(n_ev), spec%vectors(k%n(), min(n_keep, n_ev)))
        k_norm = k%norm_inf()
        b_norm = b%norm_inf()
        do i = 1, n_ev
            spec%residual(i) = backward_error(k, b, spec%mu(i), run%y(:, order(i)), k_norm, &
                                              b_norm)
            if (i > size(spec%vectors, 2)) cycle
            spec%vectors(:, i) = run%y(:, order(i))
            call normalise_mode(spec%vectors(:, i))
        end do
    end subroutine fill_full_spectrum
end module arpack_eigen
