! SPDX-License-Identifier: MIT
!> analysis = 'eigen': the boundary eigenproblem K phi = mu B phi for one lambda, solved by
!> the solver the input asks for, with the phase timings of docs/outputs.md.
module eigen_analysis
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use timer, only: wall_time, timings_t, PHASE_ASSEMBLY, PHASE_REDUCTION, PHASE_EIGEN
    use strings, only: to_string, short_real_text
    use real_format, only: real_to_text
    use run_config, only: config_t
    use problem, only: problem_t, explain_singular_k
    use element_types, only: element_name
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness
    use memory_budget, only: check_contact_memory, contact_peak_blocks
    use contact_boundary, only: assemble_b
    use spectrum, only: spectrum_t, KIND_POSITIVE
    use dense_eigen, only: dense_spectrum
    use accuracy, only: accuracy_warnings, roundoff_warnings, WARNING_LEN, FORWARD_ERROR_BOUND
    use arpack_eigen, only: arpack_search, arpack_finish, arpack_search_t, arpack_options_t
    use error_estimate, only: error_estimate_t, estimate_lowest_error, ENRICHED_CONTACT_MAX, &
                              estimate_label
    use enrichment, only: enriched_element
    use mode_resolution, only: contact_mode_cells
    use error_bar, only: single_bar
    use halved_mesh, only: build_halved_problem
    implicit none
    private
    public :: eigen_result_t, solve_eigen, estimate_eigen, choose_solver, eigen_with_factor, &
              solver_name
    public :: operator_name, critical_cn
    public :: to_input_units, estimate_wanted
    public :: SOLVER_DENSE, SOLVER_ARPACK

    !> The eigensolver a run used (&eigen solver = 'auto' resolves to one of them).
    integer, parameter :: SOLVER_DENSE = 1    !! all p eigenpairs of the reduced problem
    integer, parameter :: SOLVER_ARPACK = 2   !! a few, by ARPACK, with the certificate
    !> &eigen estimate = 'auto' computes the error estimate up to this many free dofs: it
    !> assembles and factors the enriched (P2) problem, a few times the cost of the solve
    !> (measured 4-7x: 2.3 s at 33k dofs, 22 s at 525k), which beyond would break the speed
    !> a user expects of a plain run.
    integer, parameter, public :: ESTIMATE_AUTO_MAX_DOFS = 40000

    type, public :: eigen_result_t
        real(wp) :: lambda = 0.0_wp
        integer :: solver = SOLVER_DENSE          !! the solver actually used
        type(csr_matrix_t) :: b                   !! B for this lambda
        type(spectrum_t) :: spec
        !> accuracy lost or the result not certified, and why (empty when trustworthy)
        character(len=WARNING_LEN), allocatable :: warnings(:)
        !> the estimate of the error of the lowest positive mu (analysis 'eigen' only)
        type(error_estimate_t) :: error
        !> bound of the relative round-off error of the lowest positive mu (module roundoff),
        !> part of error%bar; < 0: unknown (no positive mu, or no left eigenvector)
        real(wp) :: roundoff = -1.0_wp
        !> the lowest positive mu is the Rayleigh quotient that never stores K (hp_rayleigh),
        !> and `roundoff` that quotient's bound
        logical :: quotient = .false.
    end type eigen_result_t

contains

    !> The solver &eigen solver names; 'auto' means dense while the p x p dense problem is
    !> cheap, and ARPACK always with &eigen operator = 'full' (an ARPACK operator).
    pure integer function choose_solver(requested, p, dense_max_contact, operator) &
        result(solver)
        character(len=*), intent(in) :: requested
        integer, intent(in) :: p, dense_max_contact
        character(len=*), intent(in), optional :: operator   !! &eigen operator
        solver = SOLVER_DENSE
        select case (trim(requested))
        case ('arpack')
            solver = SOLVER_ARPACK
        case ('auto')
            if (p > dense_max_contact) solver = SOLVER_ARPACK
            if (present(operator)) then
                if (trim(operator) == 'full') solver = SOLVER_ARPACK
            end if
        end select
    end function choose_solver

    !> 'reduced' or 'full': what the run's eigensolver worked on (the dense solver always
    !> works on the reduced p x p matrix), as summary.json names it.
    pure function operator_name(solver, operator) result(name)
        integer, intent(in) :: solver
        character(len=*), intent(in) :: operator   !! &eigen operator
        character(len=:), allocatable :: name
        name = 'reduced'
        if (solver == SOLVER_ARPACK .and. trim(operator) == 'full') name = 'full'
    end function operator_name

    !> 'dense' or 'arpack', as summary.json and the stdout summary name the solver.
    pure function solver_name(solver) result(name)
        integer, intent(in) :: solver
        character(len=:), allocatable :: name
        name = 'dense'
        if (solver == SOLVER_ARPACK) name = 'arpack'
    end function solver_name

    !> Assemble B for `lambda`, factor K (factor_stiffness: contact dofs last, which both
    !> solvers read the contact blocks from), and compute the spectrum.
    recursive subroutine solve_eigen(config, prob, lambda, res, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: lambda
        type(eigen_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(cholesky_t) :: chol
        real(wp) :: start
        logical :: contact_last

        res%lambda = lambda
        start = wall_time()
        call assemble_b(prob%contact, prob%dofs%n_free, lambda, res%b, stat)
        if (.not. stat%ok()) return
        call timings%add(PHASE_ASSEMBLY, wall_time() - start, ': B for lambda = '// &
                         real_to_text(lambda))

        res%solver = choose_solver(config%eigen%solver, prob%contact%p(), &
                                   config%eigen%dense_max_contact, config%eigen%operator)
        ! The full operator only solves with K: CHOLMOD's own ordering, without the dense
        ! 2p x 2p block of the contact dofs last, which costs O(p^3) and dominates when p is
        ! a large part of n (eigen_with_factor makes that factor only if the dense decision
        ! needs it). Every other run reads that block: factored so from the start.
        contact_last = operator_name(res%solver, config%eigen%operator) /= 'full'
        if (contact_last) then
            call check_contact_memory(config, prob%contact%p(), contact_peak_blocks( &
                res%solver == SOLVER_ARPACK .and. .not. abs(config%eigen%target) > 0.0_wp), stat)
            if (.not. stat%ok()) return
        end if
        call factor_stiffness(prob%k, prob%mesh, prob%dofs, prob%contact, chol, timings, stat, &
                              contact_last)
        call explain_singular_k(config, prob%mesh, stat)
        if (.not. stat%ok()) return
        call eigen_with_factor(config, prob, chol, res, timings, stat, contact_last=contact_last)
        call chol%free()
    end subroutine solve_eigen

    !> res%error of a spectrum solve_eigen found, as &eigen estimate asks: the enriched
    !> estimate, or the halved mesh's for an element without a degree above, and the
    !> resolution check; `res%error%skipped` says why none where 'auto' leaves it out. Only
    !> the eigen analyses call it (a threshold's spectra carry no estimate of mu).
    recursive subroutine estimate_eigen(config, prob, res, timings)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable :: why_not
        if (estimate_wanted(config, prob%dofs%n_free, why_not)) then
            if (enriched_element(prob%mesh%element) /= 0) then
                call add_error_estimate(prob, res, timings)
            else
                call add_halved_mesh_estimate(config, prob, res, timings)
            end if
            ! an adaptive run judges resolution by the change of mu between its levels
            if (.not. config%adapt%tolerance > 0.0_wp) call check_resolution(config, prob, &
                                                                             res, timings)
        else if (len(why_not) > 0) then
            res%error%skipped = why_not
        end if
        ! below FORWARD_ERROR_BOUND eigen_with_factor has not warned: only the bar's split
        if (res%error%computed .and. res%roundoff <= FORWARD_ERROR_BOUND) res%warnings = &
            [character(len=WARNING_LEN) :: res%warnings, roundoff_warnings(res%roundoff, &
                                                           res%error%bar - res%roundoff)]
        ! a bar of 1 or more: not one digit of c_n, not even its existence, is certain (it
        ! happens where lambda is near a critical value of this mesh: 1.94 on the reference
        ! scene at 32 x 32, whose lambda+ is 1.9334 there and 1.9447 in the continuum)
        if (res%error%computed .and. res%error%bar >= 1.0_wp) res%warnings = &
            [character(len=WARNING_LEN) :: res%warnings, 'no digit of the lowest positive '// &
            'mu is certain: its error bar is '//short_real_text(res%error%bar)//' relative, '// &
            'larger than mu itself; lambda = '//real_to_text(res%lambda)//' may be near a '// &
            'critical value, where mu passes through infinity and a finer mesh may leave no '// &
            'positive mu at all (kind = ''threshold'' gives the critical lambdas and their bars)']
    end subroutine estimate_eigen

    !> Whether &eigen estimate asks for the error estimates on a problem of `n_free` dofs:
    !> 'on', 'off', or 'auto' (up to ESTIMATE_AUTO_MAX_DOFS); `why_not` the sentence for a
    !> problem 'auto' leaves out ('' otherwise: 'off' is the user's own choice).
    logical function estimate_wanted(config, n_free, why_not)
        type(config_t), intent(in) :: config
        integer, intent(in) :: n_free
        character(len=:), allocatable, intent(out) :: why_not
        why_not = ''
        select case (trim(config%eigen%estimate))
        case ('on')
            estimate_wanted = .true.
        case ('auto')
            estimate_wanted = n_free <= ESTIMATE_AUTO_MAX_DOFS
            if (.not. estimate_wanted) why_not = 'not computed: '//to_string(n_free)// &
                ' dofs, more than the '//to_string(ESTIMATE_AUTO_MAX_DOFS)//' of &eigen '// &
                "estimate = 'auto' (it costs a few times the solve; 'on' computes it)"
        case default
            estimate_wanted = .false.
        end select
    end function estimate_wanted

    !> res%error for the lowest positive mu (error_estimate): computed where the element has
    !> an enrichment (P1) and the enriched contact has at most ENRICHED_CONTACT_MAX nodes; a
    !> failure only costs the estimate (a warning), never the run.
    subroutine add_error_estimate(prob, res, timings)
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t) :: stat
        integer :: lowest

        lowest = res%spec%lowest_positive()
        if (lowest == 0 .or. size(res%spec%vectors, 2) < lowest) return
        call estimate_lowest_error(prob, res%lambda, &
            prob%units%mu_to_scaled(real(res%spec%mu(lowest), wp)), &
            real(res%spec%vectors(:, lowest), wp), ENRICHED_CONTACT_MAX, res%error, stat)
        if (.not. stat%ok()) then
            res%error%failure = stat%message
            res%warnings = [character(len=WARNING_LEN) :: res%warnings, &
                            'no error estimate for the lowest positive mu: '//stat%message]
            return
        end if
        if (.not. res%error%computed) return
        res%error%bar = single_bar(abs(res%error%relative), res%roundoff)
        call timings%add(PHASE_EIGEN, res%error%seconds, ': error estimate ('// &
                         estimate_label(res%error)//')')
    end subroutine add_error_estimate

    !> res%error for an element with no degree above it (Q1, Q2, P4): the difference to the
    !> same element on the mesh of halved cells, whose space holds this one's,
    !> (mu_h/2 - mu_h) / mu_h; no cell indicators. It costs about four times the solve. A
    !> failure only costs the estimate (a warning), never the run.
    recursive subroutine add_halved_mesh_estimate(config, prob, res, timings)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        real(wp) :: start, mu, mu_fine, cells_fine
        character(len=:), allocatable :: why_not

        if (res%spec%lowest_positive() == 0) return
        start = wall_time()
        call halved_mesh_mu(config, prob, res, mu_fine, cells_fine, why_not)
        if (len(why_not) > 0) then
            res%error%skipped = 'not computed: '//why_not
            return
        end if
        mu = real(res%spec%mu(res%spec%lowest_positive()), wp)
        res%error%computed = .true.
        res%error%halved_mesh = .true.
        res%error%element = prob%mesh%element
        res%error%relative = (mu_fine - mu)/mu
        res%error%mu_enriched = prob%units%mu_to_scaled(mu_fine)   ! prob%k's units
        res%error%mode_cells_halved = cells_fine
        allocate (res%error%indicators(0))
        res%error%bar = single_bar(abs(res%error%relative), res%roundoff)
        res%error%seconds = wall_time() - start
        call timings%add(PHASE_EIGEN, res%error%seconds, ': error estimate ('// &
                         estimate_label(res%error)//')')
    end subroutine add_halved_mesh_estimate

    !> Whether the mesh resolves the mode of the lowest positive mu (mode_resolution): one
    !> narrower than RESOLVED_CELLS cells on Gamma_C is solved again on the halved mesh (the
    !> Q1, Q2, P4 estimate has done so). Its change of mu bounds the bar from below (the
    !> halved mesh's value is no closer to the continuum than the bar claims otherwise), and a
    !> mode that did not widen with the mesh (less than WIDENING times) while mu moved by more
    !> than MOVED moves with the mesh (mu ~ 1/h moves by O(1): 63 % and 41 % for contact on
    !> the middle of a side at h = 1/16, 1/32; the reference scene at 4 x 4, whose mode
    !> widens 1.43 times, moves 0.3 %): a warning says that the scene may have no converged
    !> value at this resolution.
    !> Coarse meshes of resolved scenes pay about four times the solve; the reference scene's
    !> mode spans 2 cells from N = 16 on.
    recursive subroutine check_resolution(config, prob, res, timings)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        real(wp), parameter :: RESOLVED_CELLS = 2.0_wp, WIDENING = 1.5_wp, MOVED = 0.1_wp
        real(wp) :: mu, mu_fine, cells_fine, change, start
        character(len=:), allocatable :: why_not
        integer :: lowest

        lowest = res%spec%lowest_positive()
        if (lowest == 0 .or. .not. res%error%computed) return
        res%error%mode_cells = contact_mode_cells(prob, real(res%spec%vectors(:, lowest), wp))
        if (.not. (res%error%mode_cells >= 0.0_wp .and. &
                   res%error%mode_cells < RESOLVED_CELLS)) return
        mu = real(res%spec%mu(lowest), wp)
        start = wall_time()
        if (res%error%halved_mesh) then
            mu_fine = mu*(1.0_wp + res%error%relative)
            cells_fine = res%error%mode_cells_halved
        else
            call halved_mesh_mu(config, prob, res, mu_fine, cells_fine, why_not)
            if (len(why_not) > 0) return
            res%error%mode_cells_halved = cells_fine
            call timings%add(PHASE_EIGEN, wall_time() - start, ': resolution check, the '// &
                             'mode spans '//short_real_text(res%error%mode_cells)//' cells')
        end if
        change = abs(mu_fine - mu)/abs(mu)
        res%error%bar = max(res%error%bar, change)
        if (cells_fine >= WIDENING*res%error%mode_cells .or. change <= MOVED) return
        res%warnings = [character(len=WARNING_LEN) :: res%warnings, &
            'the mode of the lowest positive mu spans '//short_real_text(res%error%mode_cells)// &
            ' cells of the contact segment and did not widen on the halved mesh ('// &
            short_real_text(cells_fine)//'), where mu moved by '//short_real_text(change)// &
            ' relative: it moves with the mesh, and this scene may have no converged c_n '// &
            'at this resolution']
    end subroutine check_resolution

    !> The lowest positive mu (input units) and its mode's width in cells
    !> (contact_mode_cells) on the mesh of `prob` with every cell halved: the rectangle with
    !> 2 nx x 2 ny cells, or a Gmsh triangle mesh (P1 to P3) bisected twice. `why_not`
    !> says why there is none ('' when computed).
    recursive subroutine halved_mesh_mu(config, prob, res, mu_fine, cells_fine, why_not)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(in) :: res
        real(wp), intent(out) :: mu_fine, cells_fine
        character(len=:), allocatable, intent(out) :: why_not
        type(config_t) :: halved
        type(problem_t) :: fine
        type(eigen_result_t) :: fine_res
        type(timings_t) :: quiet
        type(status_t) :: stat
        integer :: lowest

        mu_fine = 0.0_wp
        cells_fine = -1.0_wp
        call build_halved_problem(config, prob, halved, fine, why_not, stat)
        if (len(why_not) > 0) return
        if (stat%ok()) call solve_eigen(halved, fine, res%lambda, fine_res, quiet, stat)
        if (.not. stat%ok()) then
            why_not = 'the halved mesh failed: '//stat%message
            return
        end if
        lowest = fine_res%spec%lowest_positive()
        if (lowest == 0) then
            why_not = 'no positive mu on the halved mesh'
            return
        end if
        mu_fine = real(fine_res%spec%mu(lowest), wp)
        cells_fine = contact_mode_cells(fine, real(fine_res%spec%vectors(:, lowest), wp))
    end subroutine halved_mesh_mu

    !> The spectrum at res%lambda (res%b assembled, res%solver chosen) from a factor of K made
    !> by factor_stiffness, which stays allocated for the caller (the threshold analysis reads
    !> the contact blocks off the same factor; the full operator may use one without the
    !> contact dofs last). A caller that already has Kt_nn and Kt_nt
    !> passes them to spare the dense solver forming them again.
    subroutine eigen_with_factor(config, prob, chol, res, timings, stat, kt_nn, kt_nt, &
                                 contact_last)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(cholesky_t), intent(in) :: chol
        type(eigen_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: kt_nn(:, :), kt_nt(:, :)   !! (p, p) both
        !> `chol` has the contact dofs last (default); without, only the full operator runs,
        !> and the dense decision, if its search needs one, gets a contact-last factor here
        logical, intent(in), optional :: contact_last
        type(arpack_options_t) :: options
        type(arpack_search_t) :: search
        type(cholesky_t) :: ordered   !! contact dofs last, for the full operator's decision
        logical :: chol_contact_last
        real(wp) :: refactor_start, refactor_seconds
        real(wp) :: start, reduction_seconds
        character(len=:), allocatable :: certificate   !! why ARPACK's answer is not certified
        integer :: n_keep

        n_keep = max(1, config%output%modes)
        start = wall_time()
        certificate = ''
        if (res%solver == SOLVER_ARPACK) then
            ! the target in the units of prob%k; clamped where that overflows, which is far
            ! outside the accepted range anyway (arpack_eigen: TARGET_RANGE)
            options = arpack_options_t(nev=config%eigen%nev, ncv=config%eigen%ncv, &
                maxit=config%eigen%maxit, tol=config%eigen%tol, &
                target=prob%units%mu_to_scaled(config%eigen%target), &
                cn_max=prob%units%mu_to_scaled(config%eigen%cn_max), &
                full=config%eigen%operator == 'full', &
                units=prob%units, target_input=config%eigen%target)
            chol_contact_last = .true.
            if (present(contact_last)) chol_contact_last = contact_last
            refactor_seconds = 0.0_wp
            call arpack_search(prob%k, res%b, chol, prob%contact, res%lambda, options, search, &
                               stat)
            if (stat%ok()) then
                if (search%needs_dense_decision() .and. .not. chol_contact_last) then
                    refactor_start = wall_time()
                    call check_contact_memory(config, prob%contact%p(), contact_peak_blocks( &
                        .not. abs(config%eigen%target) > 0.0_wp), stat)
                    if (stat%ok()) call factor_stiffness(prob%k, prob%mesh, prob%dofs, &
                                                         prob%contact, ordered, timings, stat)
                    refactor_seconds = wall_time() - refactor_start
                    if (stat%ok()) call arpack_finish(prob%k, res%b, ordered, prob%contact, &
                        res%lambda, options, n_keep, search, res%spec, certificate, stat)
                else
                    call arpack_finish(prob%k, res%b, chol, prob%contact, res%lambda, options, &
                                       n_keep, search, res%spec, certificate, stat)
                end if
            end if
            if (stat%code == STATUS_BAD_INPUT) stat%message = config%input_file//': '// &
                                                              stat%message
            if (.not. stat%ok()) return
            call timings%add(PHASE_EIGEN, wall_time() - start - refactor_seconds, &
                             ': arpack on the '// &
                             operator_name(res%solver, config%eigen%operator)//' operator, '// &
                             to_string(res%spec%n())//' eigenvalues')
        else
            reduction_seconds = 0.0_wp
            if (present(kt_nn) .and. present(kt_nt)) then
                call dense_spectrum(prob%k, res%b, chol, prob%contact, res%lambda, n_keep, &
                                    res%spec, stat, kt_nn_given=kt_nn, kt_nt_given=kt_nt)
            else
                call dense_spectrum(prob%k, res%b, chol, prob%contact, res%lambda, n_keep, &
                                    res%spec, stat, reduction_seconds)
            end if
            if (.not. stat%ok()) return
            if (reduction_seconds > 0.0_wp) call timings%add(PHASE_REDUCTION, &
                reduction_seconds, ': contact blocks of K^-1, '//to_string(prob%contact%p())// &
                ' x '//to_string(prob%contact%p()))
            call timings%add(PHASE_EIGEN, wall_time() - start - reduction_seconds, ': dense, '// &
                             to_string(res%spec%n())//' eigenvalues')
        end if
        ! ARPACK's answer has no dense left vectors: the sensitivity of the lowest positive mu
        ! to lambda from its full left vector (the round-off bound's), so that a lambda near
        ! a critical value is said on every solver path
        if (.not. allocated(res%spec%lambda_sensitivity)) call add_lambda_sensitivity(prob, res)
        call to_input_units(config, prob, res%spec%mu, stat)
        if (.not. stat%ok()) return
        res%roundoff = -1.0_wp
        if (allocated(res%spec%roundoff) .and. res%spec%lowest_positive() > 0) &
            res%roundoff = res%spec%roundoff(res%spec%lowest_positive())
        res%warnings = accuracy_warnings(res%spec, element_name(prob%mesh%element), prob%poisson, &
                                         res%roundoff)
        if (len(certificate) > 0) res%warnings = [character(len=WARNING_LEN) :: certificate, &
                                                  res%warnings]
    end subroutine eigen_with_factor

    !> |lambda dmu/dlambda / mu| of the lowest positive mu (first in res%spec) from its right
    !> and left eigenvectors phi, psi on the free dofs (K phi = mu B phi, K psi = mu B^T psi):
    !> d mu / d lambda = -mu psi^T B' phi / psi^T B phi, and B(lambda) = lambda T' - N' is
    !> linear in lambda, so lambda B' = B(2 lambda) - B(lambda). The dense solver's value on
    !> the reduced problem is the same quantity. Left at -1 where psi is unknown or lambda = 0.
    subroutine add_lambda_sensitivity(prob, res)
        type(problem_t), intent(in) :: prob
        type(eigen_result_t), intent(inout) :: res
        type(csr_matrix_t) :: b_double
        type(status_t) :: stat
        real(wp), allocatable :: phi(:), b_phi(:), b_double_phi(:)
        real(wp) :: denominator
        allocate (res%spec%lambda_sensitivity(res%spec%n()), source=-1.0_wp)
        if (res%spec%lowest_positive() /= 1 .or. .not. allocated(res%spec%left)) return
        if (.not. abs(res%lambda) > 0.0_wp .or. size(res%spec%vectors, 2) < 1) return
        call assemble_b(prob%contact, prob%dofs%n_free, 2.0_wp*res%lambda, b_double, stat)
        if (.not. stat%ok()) return
        phi = real(res%spec%vectors(:, 1), wp)
        allocate (b_phi(size(phi)), b_double_phi(size(phi)))
        call res%b%matvec(phi, b_phi)
        call b_double%matvec(phi, b_double_phi)
        denominator = abs(dot_product(res%spec%left, b_phi))
        if (denominator > 0.0_wp) res%spec%lambda_sensitivity(1) = &
            abs(dot_product(res%spec%left, b_double_phi - b_phi))/denominator
    end subroutine add_lambda_sensitivity

    !> The critical c_n a run reports: every positive real mu of `spec` (input units) in
    !> (0, cn_max], ascending; with cn_max = 0 the lowest alone. Complete as certified by the
    !> solver (both solvers hold every positive real mu up to cn_max in their spectrum).
    pure function critical_cn(spec, cn_max) result(values)
        type(spectrum_t), intent(in) :: spec
        real(wp), intent(in) :: cn_max
        real(wp), allocatable :: values(:)
        integer :: lowest
        allocate (values(0))
        lowest = spec%lowest_positive()
        if (lowest == 0) return
        ! output order: positive real ascending first
        if (.not. cn_max > 0.0_wp) then
            values = [real(spec%mu(lowest), wp)]
        else
            values = pack(real(spec%mu, wp), spec%kind == KIND_POSITIVE .and. &
                          real(spec%mu, wp) <= cn_max)
        end if
    end function critical_cn

    !> Eigenvalues of (prob%k, B(prob%contact)) to those of the input problem (prob%units),
    !> exactly. Fails (STATUS_BAD_INPUT, naming &material young or the
    !> mesh size, whichever pushes further) when an |mu| would leave the normal binary64
    !> range [tiny, huge] = [2.2e-308, 1.8e308]: overflow, or digits lost to underflow.
    subroutine to_input_units(config, prob, mu, stat, sweep_lambda)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        complex(wp), intent(inout) :: mu(:)
        type(status_t), intent(out) :: stat
        !> the largest |lambda| of a sweep, when mu are its points (default: &analysis lambda)
        real(wp), intent(in), optional :: sweep_lambda
        integer :: i, worst, worst_exponent
        character(len=:), allocatable :: what, lambda_name
        real(wp) :: lambda

        if (size(mu) == 0) return
        worst = 0
        worst_exponent = 0
        do i = 1, size(mu)
            if (.not. abs(mu(i)) > 0.0_wp) cycle
            associate (x => prob%units%input_exponent(abs(mu(i))))
                if (x > maxexponent(1.0_wp) .or. x < minexponent(1.0_wp)) then
                    if (worst == 0 .or. abs(x) > abs(worst_exponent)) then
                        worst = i
                        worst_exponent = x
                    end if
                end if
            end associate
        end do
        if (worst > 0) then
            ! the input pushing furthest: E/size, or lambda (mu ~ 1/lambda for large |lambda|)
            lambda = config%analysis%lambda
            lambda_name = '&analysis: lambda = '
            if (present(sweep_lambda)) then
                lambda = sweep_lambda
                lambda_name = '&sweep: lambda = '
            end if
            if (worst_exponent < 0 .and. prob%units%lambda_dominates(lambda)) then
                what = lambda_name//real_to_text(lambda)//' (a point of the sweep)'
                if (.not. present(sweep_lambda)) what = lambda_name//real_to_text(lambda)
            else if (prob%units%young_dominates()) then
                what = '&material: young = '//real_to_text(prob%young)
            else if (config%mesh%source == 'rectangle') then
                what = '&mesh: width = '//real_to_text(config%mesh%width)//', height = '// &
                       real_to_text(config%mesh%height)
            else
                what = '&mesh: the mesh in '//trim(config%mesh%file)//' (size 2^'// &
                       to_string(prob%units%length_exponent)//')'
            end if
            call stat%fail(STATUS_BAD_INPUT, config%input_file//': '//what// &
                ': an eigenvalue mu would be about '// &
                decimal_text(prob%units%input_log10(abs(mu(worst))))// &
                ' (mu scales like young / size, '// &
                'and like 1 / lambda for large |lambda|), '// &
                'outside the 2.2e-308 to 1.8e308 that binary64 holds to full precision')
            return
        end if
        do i = 1, size(mu)
            mu(i) = cmplx(prob%units%mu_to_input(real(mu(i), wp)), &
                          prob%units%mu_to_input(aimag(mu(i))), wp)
        end do

    contains

        !> 10^x as 'm.me+n' text, for values beyond the binary64 range.
        function decimal_text(x) result(text)
            real(wp), intent(in) :: x
            character(len=:), allocatable :: text
            character(len=8) :: mantissa
            real(wp) :: m
            integer :: power
            power = floor(x)
            m = 10.0_wp**(x - power)
            if (m >= 9.95_wp) then   ! would print as 10.0
                m = 1.0_wp
                power = power + 1
            end if
            write (mantissa, '(f3.1)') m
            text = trim(mantissa)//'e'//to_string(power)
        end function decimal_text
    end subroutine to_input_units
end module eigen_analysis
