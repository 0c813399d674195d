! SPDX-License-Identifier: MIT
!> The boundary eigenproblem K phi = mu B_lambda phi of a problem at one lambda, solved by
!> the solver the options ask for (eigen_options_t), with its error estimate and the phase
!> timings of docs/outputs.md: what every analysis that solves the eigenproblem calls.
module eigen_solve
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use timer, only: wall_time, timings_t, PHASE_ASSEMBLY, PHASE_REDUCTION, PHASE_EIGEN
    use strings, only: to_string, short_real_text
    use real_format, only: real_to_text
    use scene, only: scene_t, MESH_RECTANGLE
    use unit_scaling, only: units_t
    use method_options, only: eigen_options_t, SOLVER_AUTO, SOLVER_DENSE, SOLVER_ARPACK, &
                              ESTIMATE_ON, ESTIMATE_AUTO, OPERATOR_FULL, operator_name
    use problem, only: problem_t, explain_singular_k
    use element_types, only: element_name
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness, scaled_reduced_matrix, lift_share_t
    use memory_budget, only: check_contact_memory, contact_peak_blocks
    use contact_boundary, only: assemble_b, fill_b
    use spectrum, only: spectrum_t
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
    public :: eigen_result_t, solve_eigen, estimate_eigen, choose_solver, eigen_with_factor
    public :: estimate_wanted, check_input_range, check_real_range
    !> &eigen estimate = 'auto' computes the error estimate up to this many free dofs: it
    !> assembles and factors the enriched (P2) problem, a few times the cost of the solve
    !> (measured 4-7x: 2.3 s at 33k dofs, 22 s at 525k), which beyond would break the speed
    !> a user expects of a plain run.
    integer, parameter, public :: ESTIMATE_AUTO_MAX_DOFS = 40000

    type, public :: eigen_result_t
        real(wp) :: lambda = 0.0_wp
        integer :: solver = SOLVER_DENSE          !! the solver actually used (SOLVER_*)
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

    !> The solver `options` name for a problem of `p` contact nodes; SOLVER_AUTO means dense
    !> while the p x p dense problem is cheap, and ARPACK always with the full operator (an
    !> ARPACK operator).
    pure integer function choose_solver(options, p) result(solver)
        type(eigen_options_t), intent(in) :: options
        integer, intent(in) :: p
        solver = SOLVER_DENSE
        select case (options%solver)
        case (SOLVER_ARPACK)
            solver = SOLVER_ARPACK
        case (SOLVER_AUTO)
            if (p > options%dense_max_contact) solver = SOLVER_ARPACK
            if (options%operator == OPERATOR_FULL) solver = SOLVER_ARPACK
        end select
    end function choose_solver

    !> Assemble B for `lambda`, factor K (factor_stiffness: contact dofs last, which both
    !> solvers read the contact blocks from), and compute the spectrum of `prob`, the problem
    !> of the scene `scn`.
    subroutine solve_eigen(scn, prob, lambda, options, res, timings, stat)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: lambda
        type(eigen_options_t), intent(in) :: options
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

        res%solver = choose_solver(options, prob%contact%p())
        ! The full operator only solves with K: CHOLMOD's own ordering, without the dense
        ! 2p x 2p block of the contact dofs last, which costs O(p^3) and dominates when p is
        ! a large part of n (eigen_with_factor makes that factor only if the dense decision
        ! needs it). Every other run reads that block: factored so from the start.
        contact_last = operator_name(res%solver, options%operator) /= 'full'
        if (contact_last) then
            call check_contact_memory(scn, prob%contact%p(), contact_peak_blocks( &
                res%solver == SOLVER_ARPACK .and. .not. abs(options%target) > 0.0_wp), stat)
            if (.not. stat%ok()) return
        end if
        call factor_stiffness(prob%k, prob%mesh, prob%dofs, prob%contact, chol, timings, stat, &
                              contact_last)
        call explain_singular_k(scn, prob%mesh, stat)
        if (.not. stat%ok()) return
        call eigen_with_factor(scn, prob, options, chol, res, timings, stat, &
                               contact_last=contact_last)
        call chol%free()
    end subroutine solve_eigen

    !> res%error of a spectrum solve_eigen found, as options%estimate asks: the enriched
    !> estimate, or the halved mesh's for an element without a degree above, and with
    !> `resolution` the resolution check (an adaptive run judges resolution by the change of
    !> mu between its levels instead); `res%error%skipped` says why none where ESTIMATE_AUTO
    !> leaves it out. Only the eigen analyses call it (a threshold's spectra carry no
    !> estimate of mu).
    subroutine estimate_eigen(scn, prob, options, resolution, res, timings)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(eigen_options_t), intent(in) :: options
        logical, intent(in) :: resolution
        type(eigen_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable :: why_not
        if (estimate_wanted(options, prob%dofs%n_free, why_not)) then
            if (enriched_element(prob%mesh%element) /= 0) then
                call add_error_estimate(prob, res, timings)
            else
                call add_halved_mesh_estimate(scn, prob, options, res, timings)
            end if
            if (resolution) call check_resolution(scn, prob, options, res, timings)
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

    !> Whether options%estimate asks for the error estimates on a problem of `n_free` dofs:
    !> ESTIMATE_ON, _OFF, or _AUTO (up to ESTIMATE_AUTO_MAX_DOFS); `why_not` the sentence for
    !> a problem _AUTO leaves out ('' otherwise: _OFF is the user's own choice).
    logical function estimate_wanted(options, n_free, why_not)
        type(eigen_options_t), intent(in) :: options
        integer, intent(in) :: n_free
        character(len=:), allocatable, intent(out) :: why_not
        why_not = ''
        select case (options%estimate)
        case (ESTIMATE_ON)
            estimate_wanted = .true.
        case (ESTIMATE_AUTO)
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
            real(res%spec%mu(lowest), wp), &
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
    subroutine add_halved_mesh_estimate(scn, prob, options, res, timings)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(eigen_options_t), intent(in) :: options
        type(eigen_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        real(wp) :: start, mu, mu_fine, cells_fine
        character(len=:), allocatable :: why_not

        if (res%spec%lowest_positive() == 0) return
        start = wall_time()
        call halved_mesh_mu(scn, prob, options, res, mu_fine, cells_fine, why_not)
        if (len(why_not) > 0) then
            res%error%skipped = 'not computed: '//why_not
            return
        end if
        mu = real(res%spec%mu(res%spec%lowest_positive()), wp)
        res%error%computed = .true.
        res%error%halved_mesh = .true.
        res%error%element = prob%mesh%element
        res%error%relative = (mu_fine - mu)/mu
        res%error%mu_enriched = mu_fine
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
    subroutine check_resolution(scn, prob, options, res, timings)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(eigen_options_t), intent(in) :: options
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
            call halved_mesh_mu(scn, prob, options, res, mu_fine, cells_fine, why_not)
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

    !> The lowest positive mu (in the units of `prob`, which the halved problem shares: the
    !> same E and extent) and its mode's width in cells
    !> (contact_mode_cells) on the mesh of `prob` with every cell halved: the rectangle with
    !> 2 nx x 2 ny cells, or a Gmsh triangle mesh (P1 to P3) bisected twice (halved_mesh),
    !> solved as `options` ask. `why_not` says why there is none ('' when computed).
    subroutine halved_mesh_mu(scn, prob, options, res, mu_fine, cells_fine, why_not)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(eigen_options_t), intent(in) :: options
        type(eigen_result_t), intent(in) :: res
        real(wp), intent(out) :: mu_fine, cells_fine
        character(len=:), allocatable, intent(out) :: why_not
        type(scene_t) :: halved
        type(problem_t) :: fine
        type(eigen_result_t) :: fine_res
        type(timings_t) :: quiet
        type(status_t) :: stat
        integer :: lowest

        mu_fine = 0.0_wp
        cells_fine = -1.0_wp
        call build_halved_problem(scn, prob, halved, fine, why_not, stat)
        if (len(why_not) > 0) return
        if (stat%ok()) call solve_eigen(halved, fine, res%lambda, options, fine_res, quiet, stat)
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
    !> passes them to spare the dense solver forming them again. `lowest_only`, for a
    !> caller that reports the lowest positive mu alone (an hp sweep's points): the search
    !> without shift on the reduced operator runs on the p x p matrix formed from the blocks
    !> when given (arpack_search), and only that mu gets its mode, backward error and
    !> round-off bound (arpack_finish), and so on the dense path (dense_spectrum). `share`, for
    !> a caller that solves many lambdas on `chol`: the lifts' data on it (lift_share_t),
    !> made once. Every other caller's path is unchanged.
    subroutine eigen_with_factor(scn, prob, options, chol, res, timings, stat, kt_nn, kt_nt, &
                                 contact_last, lowest_only, share)
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: prob
        type(eigen_options_t), intent(in) :: options
        type(cholesky_t), intent(in) :: chol
        type(eigen_result_t), intent(inout) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp), intent(in), optional :: kt_nn(:, :), kt_nt(:, :)   !! (p, p) both
        !> `chol` has the contact dofs last (default); without, only the full operator runs,
        !> and the dense decision, if its search needs one, gets a contact-last factor here
        logical, intent(in), optional :: contact_last
        logical, intent(in), optional :: lowest_only
        type(lift_share_t), intent(in), optional :: share
        type(arpack_options_t) :: arpack
        logical :: explicit
        type(arpack_search_t) :: search
        type(cholesky_t) :: ordered   !! contact dofs last, for the full operator's decision
        logical :: chol_contact_last
        real(wp) :: refactor_start, refactor_seconds
        real(wp) :: start, reduction_seconds
        character(len=:), allocatable :: certificate   !! why ARPACK's answer is not certified
        integer :: n_keep

        n_keep = max(1, options%modes)
        start = wall_time()
        certificate = ''
        if (res%solver == SOLVER_ARPACK) then
            ! the target in the units of prob%k; clamped where that overflows, which is far
            ! outside the accepted range anyway (arpack_eigen: TARGET_RANGE)
            arpack = arpack_options_t(nev=options%nev, ncv=options%ncv, &
                maxit=options%maxit, tol=options%tol, &
                target=prob%units%mu_to_scaled(options%target), &
                cn_max=prob%units%mu_to_scaled(options%cn_max), &
                full=options%operator == OPERATOR_FULL, &
                units=prob%units, target_input=options%target)
            chol_contact_last = .true.
            if (present(contact_last)) chol_contact_last = contact_last
            refactor_seconds = 0.0_wp
            explicit = .false.
            if (present(lowest_only)) explicit = lowest_only .and. present(kt_nn) .and. &
                                                 present(kt_nt) .and. .not. arpack%full
            if (explicit) then
                call arpack_search(prob%k, res%b, chol, prob%contact, res%lambda, arpack, &
                    search, stat, scaled_reduced_matrix(kt_nn, kt_nt, prob%contact%mass, &
                                                        res%lambda))
            else
                call arpack_search(prob%k, res%b, chol, prob%contact, res%lambda, arpack, &
                                   search, stat)
            end if
            if (stat%ok()) then
                if (search%needs_dense_decision() .and. .not. chol_contact_last) then
                    refactor_start = wall_time()
                    call check_contact_memory(scn, prob%contact%p(), contact_peak_blocks( &
                        .not. abs(options%target) > 0.0_wp), stat)
                    if (stat%ok()) call factor_stiffness(prob%k, prob%mesh, prob%dofs, &
                                                         prob%contact, ordered, timings, stat)
                    refactor_seconds = wall_time() - refactor_start
                    if (stat%ok()) call arpack_finish(prob%k, res%b, ordered, prob%contact, &
                        res%lambda, arpack, n_keep, search, res%spec, certificate, stat)
                else
                    call arpack_finish(prob%k, res%b, chol, prob%contact, res%lambda, arpack, &
                                       n_keep, search, res%spec, certificate, stat, lowest_only, &
                                       share)
                end if
            end if
            if (stat%code == STATUS_BAD_INPUT) stat%message = scn%name//': '//stat%message
            if (.not. stat%ok()) return
            call timings%add(PHASE_EIGEN, wall_time() - start - refactor_seconds, &
                             ': arpack on the '// &
                             operator_name(res%solver, options%operator)//' operator, '// &
                             to_string(res%spec%n())//' eigenvalues')
        else
            reduction_seconds = 0.0_wp
            if (present(kt_nn) .and. present(kt_nt)) then
                call dense_spectrum(prob%k, res%b, chol, prob%contact, res%lambda, n_keep, &
                                    res%spec, stat, kt_nn_given=kt_nn, kt_nt_given=kt_nt, &
                                    lowest_only=lowest_only, share=share)
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
        call check_input_range(scn, prob%units, res%lambda, .false., res%spec%mu, stat)
        if (.not. stat%ok()) return
        res%roundoff = -1.0_wp
        if (allocated(res%spec%roundoff) .and. res%spec%lowest_positive() > 0) &
            res%roundoff = res%spec%roundoff(res%spec%lowest_positive())
        res%warnings = accuracy_warnings(res%spec, prob%units, element_name(prob%mesh%element), &
                                         prob%poisson, res%roundoff)
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
        ! B(2 lambda) on res%b's sparsity: the values of assemble_b to the last bit (fill_b),
        ! without building the pattern again at every point of a sweep
        b_double = res%b
        call fill_b(prob%contact, 2.0_wp*res%lambda, b_double, stat)
        if (.not. stat%ok()) return
        phi = real(res%spec%vectors(:, 1), wp)
        allocate (b_phi(size(phi)), b_double_phi(size(phi)))
        call res%b%matvec(phi, b_phi)
        call b_double%matvec(phi, b_double_phi)
        denominator = abs(dot_product(res%spec%left, b_phi))
        if (denominator > 0.0_wp) res%spec%lambda_sensitivity(1) = &
            abs(dot_product(res%spec%left, b_double_phi - b_phi))/denominator
    end subroutine add_lambda_sensitivity

    !> Whether eigenvalues `mu` in the scaled `units` of a problem of the scene `scn` can be
    !> reported in the input's units (reported_units converts them, exactly): fails
    !> (STATUS_BAD_INPUT, naming &material young or the mesh size of the scene, or `lambda`,
    !> whichever pushes further) when an |mu| would leave the normal binary64 range [tiny,
    !> huge] = [2.2e-308, 1.8e308]: overflow, or digits lost to underflow. Checked as each
    !> result is computed, so that such a run stops at once. `lambda`: &analysis lambda, or
    !> with `of_sweep` the largest |lambda| of a sweep whose points `mu` are.
    subroutine check_input_range(scn, units, lambda, of_sweep, mu, stat)
        type(scene_t), intent(in) :: scn
        type(units_t), intent(in) :: units
        real(wp), intent(in) :: lambda
        logical, intent(in) :: of_sweep
        complex(wp), intent(in) :: mu(:)
        type(status_t), intent(out) :: stat
        integer :: i, worst, worst_exponent
        character(len=:), allocatable :: what, lambda_name

        if (size(mu) == 0) return
        worst = 0
        worst_exponent = 0
        do i = 1, size(mu)
            if (.not. abs(mu(i)) > 0.0_wp) cycle
            associate (x => units%input_exponent(abs(mu(i))))
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
            lambda_name = '&analysis: lambda = '
            if (of_sweep) lambda_name = '&sweep: lambda = '
            if (worst_exponent < 0 .and. units%lambda_dominates(lambda)) then
                what = lambda_name//real_to_text(lambda)//' (a point of the sweep)'
                if (.not. of_sweep) what = lambda_name//real_to_text(lambda)
            else if (units%young_dominates()) then
                what = '&material: young = '//real_to_text(scn%material%young)
            else if (scn%source == MESH_RECTANGLE) then
                what = '&mesh: width = '//real_to_text(scn%width)//', height = '// &
                       real_to_text(scn%height)
            else
                what = '&mesh: the mesh in '//scn%file//' (size 2^'// &
                       to_string(units%length_exponent)//')'
            end if
            call stat%fail(STATUS_BAD_INPUT, scn%name//': '//what// &
                ': an eigenvalue mu would be about '// &
                decimal_text(units%input_log10(abs(mu(worst))))// &
                ' (mu scales like young / size, '// &
                'and like 1 / lambda for large |lambda|), '// &
                'outside the 2.2e-308 to 1.8e308 that binary64 holds to full precision')
        end if

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
    end subroutine check_input_range

    !> check_input_range of real mu.
    subroutine check_real_range(scn, units, lambda, of_sweep, mu, stat)
        type(scene_t), intent(in) :: scn
        type(units_t), intent(in) :: units
        real(wp), intent(in) :: lambda
        logical, intent(in) :: of_sweep
        real(wp), intent(in) :: mu(:)
        type(status_t), intent(out) :: stat
        complex(wp) :: values(size(mu))
        values = cmplx(mu, 0.0_wp, wp)
        call check_input_range(scn, units, lambda, of_sweep, values, stat)
    end subroutine check_real_range
end module eigen_solve
