! SPDX-License-Identifier: MIT
!> The report of a run: from its analysis's result, by the analysis's type, the values in the
!> input's units (reported_units: the one conversion, before anything is written), every
!> file of the analysis staged, the summary record filled once (summary_record) and written as
!> summary.json, the set committed, and the stdout summary rendered from the same record.
!> Every output goes to the output directory, or none of them: the files are staged,
!> pictures included; summary.json is built once, after the timings are final, registered
!> last as the commit's completion marker and lists the files of its set (an older run may
!> have left other mode_NNN.vtu), and the set moves into place together. The output time
!> covers every file but summary.json.
module run_report
    use kinds, only: wp
    use status, only: status_t
    use timer, only: wall_time, timings_t, PHASE_OUTPUT
    use version, only: NCEIG_VERSION
    use filesystem, only: MAX_NAME_LEN
    use strings, only: text_t
    use blas_info, only: blas_in_use
    use blas_threads, only: blas_threads_source
    use element_types, only: element_name
    use run_inputs, only: run_inputs_t
    use scene, only: scene_t
    use method_options, only: solver_name, operator_name, REFINE_HP, REFINE_NONE
    use problem, only: problem_t
    use unit_scaling, only: units_t
    use eigen_solve, only: eigen_result_t
    use error_estimate, only: estimate_label
    use critical_point, only: slip_sign, critical_c_t
    use critical_lambda, only: SIDE_PLUS, SIDE_MINUS, CONFIRM_OFFSET
    use critical_set, only: critical_set_t, onset_point, MECHANISM_NAMES, MECHANISM_COMPLEX_PAIR
    use threshold_analysis, only: threshold_result_t
    use eigen_goal, only: adapted_eigen_t, eigen_level_t, HP_ESTIMATE
    use threshold_goal, only: adaptive_thresholds_t
    use normal_compliance, only: STATE_SEPARATED, STATE_STICK, STATE_SLIP_PLUS, STATE_SLIP_MINUS
    use analysis_base, only: analysis_t
    use eigen_run, only: eigen_run_t, adapt_eigen_run_t
    use threshold_run, only: threshold_run_t, sweep_run_t, adapt_threshold_run_t, &
                             joint_sweep_run_t
    use compliance_run, only: branch_run_t, solve_run_t
    use reported_units, only: to_input_units, critical_cn
    use summary_record, only: run_summary_t, eigen_facts_t, threshold_facts_t, sweep_facts_t, &
                              adapt_facts_t, branch_facts_t, solve_facts_t, summary_json, &
                              summary_text
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use eigen_files, only: write_eigen_files, write_eigenvalues_csv, write_hp_modes
    use adapt_files, only: write_adapted_mesh, write_adapt_csv, write_hp_adapt_csv, &
                           write_degrees, write_threshold_adapt_csv, MESH_FILE, DEGREES_FILE
    use sweep_files, only: write_sweep_csv, SWEEP_FILE
    use compliance_files, only: write_branch_files, write_solve_files
    use matrix_market, only: write_matrix_market
    use pictures, only: draw_eigen_adapt, draw_hp_adapt, draw_hp_mode, draw_threshold_adapt, &
                        draw_sweep
    implicit none
    private
    public :: report_run, record_problem, record_eigen, record_no_eigen

    !> Files older builds wrote into the output directory unlisted in their sets (they drew
    !> lambda_sweep.png after the commit); now every file is staged and listed, and these go
    !> with the previous set.
    character(len=*), parameter :: OLD_UNLISTED = 'lambda_sweep.png'

contains

    !> Write the outputs of `analysis`, solved on `prob` (the problem of inputs%scene; the
    !> starting problem of an adaptive run) into &output directory, and `text`, the stdout
    !> summary. `run_start`: wall_time() at the start of the run; `timings` get the output's.
    subroutine report_run(analysis, inputs, prob, run_start, timings, text, stat)
        class(analysis_t), intent(in) :: analysis
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: run_start
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable, intent(out) :: text
        type(status_t), intent(out) :: stat
        type(output_stage_t) :: stage
        type(run_summary_t) :: rec
        type(json_object_t) :: summary
        character(len=:), allocatable :: summary_path
        real(wp) :: start

        text = ''
        select type (a => analysis)
        type is (eigen_run_t)
            call report_eigen(a, inputs, prob, stage, rec, start, stat)
        type is (adapt_eigen_run_t)
            call report_adapt_eigen(a, inputs, prob, stage, rec, start, stat)
        type is (threshold_run_t)
            call report_thresholds(a%res, inputs, prob, prob, stage, rec, start, stat)
        type is (sweep_run_t)
            call report_thresholds(a%res, inputs, prob, prob, stage, rec, start, stat, &
                                   sweep=.true.)
        type is (adapt_threshold_run_t)
            call report_thresholds(a%res, inputs, prob, a%adapted%prob, stage, rec, start, &
                                   stat, adapted=a%adapted)
        type is (joint_sweep_run_t)
            call report_thresholds(a%res, inputs, prob, a%adapted%prob, stage, rec, start, &
                                   stat, sweep=.true., adapted=a%adapted)
        type is (branch_run_t)
            call report_branch(a, inputs, prob, stage, rec, start, stat)
        type is (solve_run_t)
            call report_solve(a, inputs, prob, stage, rec, start, stat)
        end select
        if (.not. stat%ok()) then
            call stage%abort()
            return
        end if
        call timings%add(PHASE_OUTPUT, wall_time() - start, ': '//trim(inputs%output%directory))
        timings%total = wall_time() - run_start
        rec%timings = timings
        summary = summary_json(rec)
        call stage%add('summary.json', summary_path)
        call summary%add_string_array('files', stage%file_names(MAX_NAME_LEN))
        call summary%write(summary_path, stat)
        if (stat%ok()) call stage%commit(stat)
        if (.not. stat%ok()) then
            call stage%abort()
            return
        end if
        text = summary_text(rec)

    end subroutine report_run

    !> The output directory staged (its failure names the input); the output time starts
    !> (`start`).
    subroutine begin(stage, inputs, start, stat)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        real(wp), intent(out) :: start
        type(status_t), intent(out) :: stat
        ! a named array, not a constructor: gfortran 12 does not free a constructor's
        ! allocatable components (LeakSanitizer reports them)
        type(text_t) :: unlisted(1)
        unlisted(1)%text = OLD_UNLISTED
        start = wall_time()
        call stage%begin(trim(inputs%output%directory), stat, unlisted)
        ! output_stage knows the directory, not the input file that named it.
        if (.not. stat%ok()) call stat%fail(stat%code, inputs%scene%name// &
                                            ': &output directory: '//stat%message)
    end subroutine begin

    subroutine report_eigen(a, inputs, prob, stage, rec, start, stat)
        type(eigen_run_t), intent(in) :: a
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(output_stage_t), intent(inout) :: stage
        type(run_summary_t), intent(inout) :: rec
        real(wp), intent(out) :: start   !! wall_time() when the output began
        type(status_t), intent(out) :: stat
        type(eigen_result_t) :: eig
        character(len=:), allocatable :: mode_plot
        call shown_spectrum(a%res, prob%units, eig)
        call begin(stage, inputs, start, stat)
        if (.not. stat%ok()) return
        call write_eigen_files(stage, inputs, prob, eig, stat, mode_plot)
        if (.not. stat%ok()) return
        call record_problem(rec, inputs, prob)
        call record_eigen(rec%eigen, inputs, eig)
        rec%mode_plot = mode_plot
    end subroutine report_eigen

    !> adaptive 'eigen': the files of the last level (on h levels those of an eigen run,
    !> on hp levels the hp field's), adapt.csv, mesh.msh (and degrees.csv), adapt.png.
    subroutine report_adapt_eigen(a, inputs, prob, stage, rec, start, stat)
        type(adapt_eigen_run_t), intent(in) :: a
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(output_stage_t), intent(inout) :: stage
        type(run_summary_t), intent(inout) :: rec
        real(wp), intent(out) :: start   !! wall_time() when the output began
        type(status_t), intent(out) :: stat
        type(eigen_result_t) :: eig
        type(eigen_level_t), allocatable :: levels(:)
        character(len=:), allocatable :: path, mode_plot, adapt_plot
        logical :: hp
        hp = inputs%adapt%refine == REFINE_HP
        associate (o => a%out(1))
            call shown_spectrum(o%res, o%units, eig)
            call shown_levels(o, levels)
            call begin(stage, inputs, start, stat)
            if (.not. stat%ok()) return
            if (.not. hp) then
                call write_eigen_files(stage, inputs, o%prob, eig, stat, mode_plot)
                if (stat%ok()) then
                    call stage%add('adapt.csv', path)
                    call write_adapt_csv(path, levels, stat)
                end if
                if (stat%ok()) call write_adapted_mesh(stage, o%prob, stat)
                ! the files describe the final level; of the starting problem its dofs
                if (stat%ok()) call draw_eigen_adapt(stage, inputs, o%prob%mesh%element, &
                    eig%lambda, prob%dofs%n_free, levels, adapt_plot)
            else if (prob%mesh%n_cells() > 0) then   ! (no input mesh: nothing solved)
                call write_hp_files(o, eig, levels, stat)
            end if
            if (.not. stat%ok()) return
            call record_problem(rec, inputs, o%prob)
            call record_eigen(rec%eigen, inputs, eig)
            if (allocated(mode_plot)) rec%mode_plot = mode_plot
            if (allocated(adapt_plot)) rec%adapt_plot = adapt_plot
            allocate (rec%adapt)
            call record_adapt(rec%adapt, inputs, prob, o%converged, o%floor_reached, &
                              o%outcome, size(levels), hp)
            if (hp) call record_hp(rec%adapt, inputs, o%space%cell_degree, prob)
        end associate

    contains

        subroutine write_hp_files(o, eig, levels, stat)
            type(adapted_eigen_t), intent(in) :: o
            type(eigen_result_t), intent(in) :: eig
            type(eigen_level_t), intent(in) :: levels(:)
            type(status_t), intent(out) :: stat
            call stage%add('eigenvalues.csv', path)
            call write_eigenvalues_csv(path, eig%spec, stat, eig%error)
            if (stat%ok() .and. inputs%output%vtk) call write_hp_modes(stage, inputs, &
                o%prob, o%space, eig%spec, eig%lambda, stat)
            if (stat%ok()) then
                call stage%add('adapt.csv', path)
                call write_hp_adapt_csv(path, levels, stat)
            end if
            if (stat%ok()) call write_adapted_mesh(stage, o%prob, stat)
            if (stat%ok()) then
                call stage%add(DEGREES_FILE, path)
                call write_degrees(path, o%space, stat)
            end if
            ! the condensed hp system (vertex and edge functions), in the input's units
            if (stat%ok() .and. inputs%output%matrices) then
                call stage%add('K.mtx', path)
                call write_matrix_market(path, o%prob%k, stat)
            end if
            if (stat%ok() .and. inputs%output%matrices) then
                call stage%add('B.mtx', path)
                call write_matrix_market(path, eig%b, stat)
            end if
            if (.not. stat%ok()) return
            call draw_hp_mode(stage, inputs, o%prob, o%space, eig, mode_plot, stat)
            if (stat%ok()) call draw_hp_adapt(stage, inputs, eig%lambda, &
                                              prob%dofs%n_free, levels, adapt_plot)
        end subroutine write_hp_files
    end subroutine report_adapt_eigen

    !> 'threshold', 'lambda_sweep' (`sweep`) and the adaptive 'threshold' (`adapted`):
    !> the files of an eigen run at &analysis lambda on `last` (the final level's problem
    !> of an adaptive run, else `prob`), lambda_sweep.csv and .png, adapt.csv, mesh.msh
    !> (and degrees.csv), adapt.png.
    subroutine report_thresholds(res, inputs, prob, last, stage, rec, start, stat, sweep, adapted)
        type(threshold_result_t), intent(in) :: res
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob, last
        type(output_stage_t), intent(inout) :: stage
        type(run_summary_t), intent(inout) :: rec
        real(wp), intent(out) :: start   !! wall_time() when the output began
        type(status_t), intent(out) :: stat
        logical, intent(in), optional :: sweep
        type(adaptive_thresholds_t), intent(in), optional :: adapted
        type(threshold_result_t) :: shown
        character(len=:), allocatable :: path, mode_plot, picture
        logical :: hp, with_sweep
        with_sweep = .false.
        if (present(sweep)) with_sweep = sweep
        hp = .false.
        if (present(adapted)) hp = inputs%adapt%refine == REFINE_HP
        call shown_thresholds(res, last%units, shown)
        call begin(stage, inputs, start, stat)
        if (.not. stat%ok()) return
        if (.not. hp) then
            call write_eigen_files(stage, inputs, last, shown%eigen, stat, mode_plot)
        else if (prob%mesh%n_cells() > 0 .and. size(adapted%levels) > 0) then
            call stage%add('eigenvalues.csv', path)
            call write_eigenvalues_csv(path, shown%eigen%spec, stat, shown%eigen%error)
            if (stat%ok() .and. inputs%output%vtk) call write_hp_modes(stage, inputs, &
                adapted%prob, adapted%space, shown%eigen%spec, shown%eigen%lambda, stat)
        end if
        if (stat%ok() .and. with_sweep .and. allocated(shown%sweep%lambda)) then
            call stage%add(SWEEP_FILE, path)
            call write_sweep_csv(path, shown%sweep, stat)
            if (stat%ok()) call draw_sweep(stage, inputs, prob, shown, picture)
            if (allocated(picture)) rec%sweep_plot = picture
        end if
        if (stat%ok() .and. present(adapted)) call write_adapt_files(adapted, stat)
        if (.not. stat%ok()) return
        call record_problem(rec, inputs, last)
        call record_eigen(rec%eigen, inputs, shown%eigen)
        if (allocated(mode_plot)) rec%mode_plot = mode_plot
        allocate (rec%thresholds)
        call record_thresholds(rec%thresholds, shown)
        if (with_sweep .and. allocated(shown%sweep%lambda)) then
            allocate (rec%sweep)
            call record_sweep(rec%sweep, inputs, shown)
        end if
        if (.not. present(adapted)) return
        allocate (rec%adapt)
        call record_adapt(rec%adapt, inputs, prob, adapted%converged, &
                          adapted%floor_reached, adapted%outcome, size(adapted%levels), hp)
        if (hp) call record_hp(rec%adapt, inputs, adapted%space%cell_degree, prob)

    contains

        subroutine write_adapt_files(adapted, stat)
            type(adaptive_thresholds_t), intent(in) :: adapted
            type(status_t), intent(out) :: stat
            character(len=:), allocatable :: adapt_plot
            if (hp .and. (prob%mesh%n_cells() == 0 .or. size(adapted%levels) == 0)) return
            call stage%add('adapt.csv', path)
            call write_threshold_adapt_csv(path, adapted%levels, hp, stat)
            if (stat%ok()) call write_adapted_mesh(stage, adapted%prob, stat)
            if (stat%ok() .and. hp) then
                call stage%add(DEGREES_FILE, path)
                call write_degrees(path, adapted%space, stat)
            end if
            if (.not. stat%ok()) return
            ! the files describe the final level; of the starting problem its dofs
            if (hp) then
                call draw_threshold_adapt(stage, inputs, prob%mesh%element, &
                    prob%dofs%n_free, adapted%levels, adapt_plot, 'hp')
            else
                call draw_threshold_adapt(stage, inputs, adapted%prob%mesh%element, &
                    prob%dofs%n_free, adapted%levels, adapt_plot)
            end if
            rec%adapt_plot = adapt_plot
        end subroutine write_adapt_files
    end subroutine report_thresholds

    !> 'branch': in the input's units already (its problem's).
    subroutine report_branch(a, inputs, prob, stage, rec, start, stat)
        type(branch_run_t), intent(in) :: a
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(output_stage_t), intent(inout) :: stage
        type(run_summary_t), intent(inout) :: rec
        real(wp), intent(out) :: start   !! wall_time() when the output began
        type(status_t), intent(out) :: stat
        call begin(stage, inputs, start, stat)
        if (.not. stat%ok()) return
        call write_branch_files(stage, inputs, prob, a%res, stat)
        if (.not. stat%ok()) return
        call record_problem(rec, inputs, prob)
        call record_eigen(rec%eigen, inputs, a%res%critical%eig)
        allocate (rec%branch)
        associate (res => a%res, f => rec%branch)
            f%alpha = res%critical%alpha
            f%beta = res%critical%beta
            f%c_n = res%cp%c_n
            f%c_t = res%cp%c_t
            f%delta_max = res%delta_max
            f%n_delta = size(res%deltas)
            f%residual_base = res%residual_base
            f%max_residual = res%max_residual
            f%load_norm = res%cp%load_norm
            f%time_branch = res%time_branch
        end associate
    end subroutine report_branch

    !> 'solve': in the input's units already (its problem's).
    subroutine report_solve(a, inputs, prob, stage, rec, start, stat)
        type(solve_run_t), intent(in) :: a
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(output_stage_t), intent(inout) :: stage
        type(run_summary_t), intent(inout) :: rec
        real(wp), intent(out) :: start   !! wall_time() when the output began
        type(status_t), intent(out) :: stat
        call begin(stage, inputs, start, stat)
        if (.not. stat%ok()) return
        call write_solve_files(stage, inputs, prob, a%res, stat)
        if (.not. stat%ok()) return
        call record_problem(rec, inputs, prob)
        if (a%res%has_critical) then
            call record_eigen(rec%eigen, inputs, a%res%critical%eig)
        else
            call record_no_eigen(rec%eigen, inputs)
        end if
        allocate (rec%solve)
        associate (res => a%res, f => rec%solve)
            f%data = trim(inputs%solve%data)
            f%start = trim(inputs%solve%start)
            f%c_n = res%cp%c_n
            f%c_t = res%cp%c_t
            f%converged = res%report%converged
            f%newton_stop = res%report%reason
            f%iterations = res%report%iterations
            f%residual = res%report%residual(size(res%report%residual))
            f%tol = inputs%solve%tol
            f%load_norm = res%cp%load_norm
            f%n_state = [res%n_state(STATE_SEPARATED), res%n_state(STATE_STICK), &
                         res%n_state(STATE_SLIP_PLUS), res%n_state(STATE_SLIP_MINUS)]
            f%on_branch = res%on_branch_data
            f%branch_delta = res%branch_delta
            f%branch_distance = res%branch_distance
            f%time_newton = res%time_newton
        end associate
    end subroutine report_solve

    !> `shown`: `res` with its spectrum in the input's units (`units`: its problem's).
    subroutine shown_spectrum(res, units, shown)
        type(eigen_result_t), intent(in) :: res
        type(units_t), intent(in) :: units
        type(eigen_result_t), intent(out) :: shown
        shown = res
        call to_input_units(units, shown%spec%mu)
    end subroutine shown_spectrum

    !> `levels`: those of the loop `o` with mu in the input's units.
    subroutine shown_levels(o, levels)
        type(adapted_eigen_t), intent(in) :: o
        type(eigen_level_t), allocatable, intent(out) :: levels(:)
        integer :: i
        allocate (levels, source=o%levels)
        do i = 1, size(levels)
            levels(i)%mu = o%units%mu_to_input(levels(i)%mu)
        end do
    end subroutine shown_levels

    !> `shown`: `res` with every mu in the input's units (`units`: its problem's; the sweep's
    !> points: their own).
    subroutine shown_thresholds(res, units, shown)
        type(threshold_result_t), intent(in) :: res
        type(units_t), intent(in) :: units
        type(threshold_result_t), intent(out) :: shown
        integer :: i
        shown = res
        call to_input_units(units, shown%eigen%spec%mu)
        call to_input_units(units, shown%thresholds%mu_outside)
        call to_input_units(units, shown%thresholds%mu_inside)
        do i = 1, size(shown%set%points)
            shown%set%points(i)%mu_meet = units%mu_to_input(shown%set%points(i)%mu_meet)
        end do
        if (allocated(shown%sweep%mu)) call to_input_units(res%sweep%units, shown%sweep%mu)
    end subroutine shown_thresholds

    !> The run, its mesh and problem sizes (of `prob`: the last level's of an adaptive run)
    !> and the BLAS.
    subroutine record_problem(rec, inputs, prob)
        type(run_summary_t), intent(inout) :: rec
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        integer :: threads, largest
        character(len=:), allocatable :: blas_library, blas_config, threads_source
        rec%version = NCEIG_VERSION
        rec%input = inputs%scene%name
        rec%analysis = inputs%analysis_name
        rec%directory = trim(inputs%output%directory)
        ! an hp run's graded mesh carries a degree per cell: the p1 of its geometry is not
        ! the element solved
        rec%element = element_name(prob%mesh%element)
        if (inputs%adapt%refine == REFINE_HP) rec%element = 'hp'
        rec%mesh_source = inputs%scene%source_name()
        rec%nx = inputs%scene%nx
        rec%ny = inputs%scene%ny
        rec%diagonal = trim(inputs%scene%diagonal)
        if (allocated(inputs%scene%file)) rec%mesh_file = inputs%scene%file
        rec%young = prob%young
        rec%poisson = prob%poisson
        rec%n_nodes = prob%mesh%n_nodes()
        rec%n_cells = prob%mesh%n_cells()
        rec%n_dofs = prob%dofs%n_free
        rec%nnz_k = prob%k%nnz()
        rec%n_contact = prob%contact%p()
        call blas_in_use(blas_library, blas_config, threads)
        rec%blas_library = blas_library
        rec%blas_config = blas_config
        rec%blas_threads = threads
        call blas_threads_source(threads_source, largest)
        rec%blas_threads_source = threads_source
    end subroutine record_problem

    !> The facts of a spectrum `res` in the input's units.
    subroutine record_eigen(f, inputs, res)
        type(eigen_facts_t), intent(out) :: f
        type(run_inputs_t), intent(in) :: inputs
        type(eigen_result_t), intent(in) :: res
        integer :: lowest
        f%solved = .true.
        f%lambda = res%lambda
        f%slip_sign = slip_sign(res%lambda)
        f%solver = solver_name(res%solver)
        f%operator = operator_name(res%solver, inputs%eigen%operator)
        f%n_eigenvalues = res%spec%n()
        f%max_residual = res%spec%max_residual()
        f%n_operator = res%spec%n_operator
        f%dense_decision = res%spec%dense_decision
        f%roundoff_seconds = res%spec%roundoff_seconds
        lowest = res%spec%lowest_positive()
        f%has_lowest = lowest > 0
        if (f%has_lowest) then
            f%mu = real(res%spec%mu(lowest), wp)
            f%c_t = critical_c_t(f%mu, res%lambda)
            f%condition = res%spec%condition(lowest)
            f%residual = res%spec%residual(lowest)
        end if
        f%estimated = res%error%computed
        if (f%estimated) then
            f%estimate = abs(res%error%relative)
            f%estimate_label = estimate_label(res%error)
            f%level_change = f%estimate_label == HP_ESTIMATE
            f%check = res%error%check
        end if
        f%bar = res%error%bar
        if (allocated(res%error%skipped)) f%skipped = res%error%skipped
        f%roundoff = res%roundoff
        f%quotient = res%quotient
        f%cn_max = inputs%eigen%cn_max
        f%critical = critical_cn(res%spec, inputs%eigen%cn_max)
        if (allocated(res%warnings)) f%warnings = res%warnings
    end subroutine record_eigen

    !> No spectrum: its keys null, lambda the input's.
    subroutine record_no_eigen(f, inputs)
        type(eigen_facts_t), intent(out) :: f
        type(run_inputs_t), intent(in) :: inputs
        f%lambda = inputs%point%lambda
        f%slip_sign = slip_sign(f%lambda)
        allocate (f%critical(0))
    end subroutine record_no_eigen

    !> The thresholds, their confirmations and estimates, and the boundary of the positive
    !> set, from `res` in the input's units.
    subroutine record_thresholds(f, res)
        type(threshold_facts_t), intent(out) :: f
        type(threshold_result_t), intent(in) :: res
        integer :: side, i, n
        associate (thr => res%thresholds, est => res%estimate, set => res%set)
            do side = SIDE_PLUS, SIDE_MINUS
                associate (d => f%side(side))
                    d%found = thr%found(side)
                    d%lambda = thr%lambda(side)
                    d%residual = thr%residual(side)
                    d%roundoff = thr%roundoff(side)
                    d%confirmed = thr%confirmed(side)
                    d%lambda_outside = thr%lambda_outside(side)
                    d%lambda_inside = thr%lambda_inside(side)
                    d%has_mu_outside = thr%has_mu_outside(side)
                    d%has_mu_inside = thr%has_mu_inside(side)
                    d%mu_outside = thr%mu_outside(side)
                    d%mu_inside = thr%mu_inside(side)
                    d%estimated = est%computed(side)
                    d%estimate = abs(est%relative(side))
                    d%bar = est%bar(side)
                    if (len_trim(est%method) > 0) then
                        d%estimate_label = trim(est%method)
                    else if (est%halved_mesh) then
                        d%estimate_label = element_name(est%element)//', halved mesh'
                    else
                        d%estimate_label = element_name(est%element)//' enrichment'
                    end if
                    d%level_change = d%estimate_label == HP_ESTIMATE
                    d%met_level = est%met_level(side)
                    d%skipped = trim(est%skipped(side))
                    d%moving = est%moving(side)
                end associate
            end do
            f%confirm_offset = CONFIRM_OFFSET
            f%n_real = thr%n_real
            f%n_complex = thr%n_complex
            f%n_infinite = thr%n_infinite
            f%lambda_min = set%lambda_min
            f%lambda_max = set%lambda_max
            n = size(set%points)
            allocate (f%points(n))
            do i = 1, n
                associate (b => set%points(i), p => f%points(i))
                    p%lambda = b%lambda
                    p%mechanism = MECHANISM_NAMES(b%mechanism)
                    p%appears = b%appears
                    p%n_below = b%n_below
                    p%n_above = b%n_above
                    p%confirmed = b%confirmed
                    p%bar = b%error_bar
                    p%roundoff = b%roundoff
                    p%pair = b%mechanism == MECHANISM_COMPLEX_PAIR
                    p%discriminant = b%discriminant
                    p%mu_meet = b%mu_meet
                end associate
            end do
            do side = SIDE_PLUS, SIDE_MINUS
                f%onset(side) = onset_point(set, side)
            end do
            call positive_intervals(set, f%lower, f%upper)
            f%n_evaluations = set%n_evaluations
            f%scan_contact = set%scan_contact
            f%contact = set%contact
        end associate
        f%time_threshold = res%time_threshold
    end subroutine record_thresholds

    !> The intervals of the searched range where a positive mu exists: between consecutive
    !> boundary points, and from or to the ends of the range.
    pure subroutine positive_intervals(set, lower, upper)
        type(critical_set_t), intent(in) :: set
        real(wp), allocatable, intent(out) :: lower(:), upper(:)
        real(wp), allocatable :: ends(:)
        integer :: n
        ! the sequence of switches: the range start when positive there, every boundary point,
        ! the range end when positive there; consecutive pairs are the intervals
        allocate (ends(size(set%points)))   ! then filled: no false -Wuninitialized
        ends(:) = set%points%lambda
        if (set%positive_at_min) ends = [set%lambda_min, ends]
        n = size(ends)
        if (mod(n, 2) == 1) ends = [ends, set%lambda_max]
        lower = ends(1::2)
        upper = ends(2::2)
    end subroutine positive_intervals

    !> What a sweep ran (`res`, in the input's units).
    subroutine record_sweep(f, inputs, res)
        type(sweep_facts_t), intent(out) :: f
        type(run_inputs_t), intent(in) :: inputs
        type(threshold_result_t), intent(in) :: res
        associate (c => res%sweep)
            f%file = SWEEP_FILE
            f%spacing = inputs%sweep_spacing
            f%n_lambda = size(c%lambda)
            f%lambda_min = minval(c%lambda)
            f%lambda_max = maxval(c%lambda)
            f%n_with_mu = count(c%found)
            f%n_arpack = c%n_arpack
            f%n_dense = c%n_dense
            f%adapted = inputs%adapt%refine /= REFINE_NONE
            f%n_reused = c%n_reused
            f%n_not_met = c%n_not_met
            f%partial = .not. c%failure%ok()
            f%n_complete = count(c%complete)
            if (any(c%error_estimate >= 0.0_wp)) f%max_estimate = maxval(c%error_estimate)
            if (any(c%error_bar >= 0.0_wp)) f%max_bar = maxval(c%error_bar)
        end associate
        f%time_sweep = res%time_sweep
    end subroutine record_sweep

    !> An adaptive loop from `prob` (the starting problem) of `n_levels` levels: h counts the
    !> refinements after the starting mesh, hp the levels.
    subroutine record_adapt(f, inputs, prob, converged, floor_reached, outcome, n_levels, hp)
        type(adapt_facts_t), intent(inout) :: f
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        logical, intent(in) :: converged, floor_reached, hp
        character(len=*), intent(in) :: outcome
        integer, intent(in) :: n_levels
        f%tolerance = inputs%adapt%tolerance
        f%theta = inputs%adapt%theta
        f%levels = n_levels
        if (.not. hp) f%levels = n_levels - 1
        f%start_dofs = prob%dofs%n_free
        f%converged = converged
        f%floor_reached = floor_reached
        f%outcome = outcome
        f%mesh_file = MESH_FILE
    end subroutine record_adapt

    !> hp levels: the grading, the degrees of the last level (`degree`), the input mesh.
    subroutine record_hp(f, inputs, degree, prob)
        type(adapt_facts_t), intent(inout) :: f
        type(run_inputs_t), intent(in) :: inputs
        integer, intent(in) :: degree(:)
        type(problem_t), intent(in) :: prob
        f%hp = .true.
        f%sigma = inputs%adapt%sigma
        f%p_max = inputs%adapt%p_max
        f%degrees_file = DEGREES_FILE
        f%has_degrees = size(degree) > 0
        if (f%has_degrees) then
            f%degree_min = minval(degree)
            f%degree_max = maxval(degree)
        end if
        f%start_cells = prob%mesh%n_cells()
    end subroutine record_hp
end module run_report
