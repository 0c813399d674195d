! SPDX-License-Identifier: MIT
!> analysis = 'threshold' and 'lambda_sweep', one type each: the files of an eigen run at
!> &analysis lambda, lambda_sweep.csv for a sweep (and lambda_sweep.png), summary.json with
!> the threshold and sweep keys; and the lines they add to the stdout summary. The adaptive
!> 'threshold' (&adapt tolerance > 0, a type of its own) adapts the mesh to the thresholds
!> first (adaptive_threshold) and reports on the final mesh, with adapt.csv, adapt.png and
!> mesh.msh as an adaptive eigen run does.
module threshold_run
    use kinds, only: wp
    use status, only: status_t, STATUS_NOT_MET, STATUS_NO_DIGIT
    use strings, only: to_string, short_real_text
    use real_format, only: real_to_text, known_text
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t
    use threshold_analysis, only: threshold_result_t, sweep_curve_t, solve_thresholds
    use adaptive_threshold, only: adaptive_thresholds_t, solve_adapted_thresholds
    use adapt_files, only: add_adapt_keys, adapt_report_lines, write_adapted_mesh
    use pictures, only: draw_sweep, draw_threshold_adapt
    use element_types, only: element_name
    use critical_lambda, only: SIDE_PLUS, SIDE_MINUS, SIDE_NAMES, SIDE_LABELS, CONFIRM_OFFSET
    use critical_set, only: critical_set_t, MECHANISM_NAMES, MECHANISM_COMPLEX_PAIR, &
                            onset_point
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use critical_point, only: slip_sign, critical_c_t
    use analysis_base, only: analysis_t
    use eigen_files, only: eigen_summary_json, summary_lines, write_eigen_files
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    use csv_writer, only: csv_writer_t
    use hp_adaptive, only: HP_ESTIMATE
    use process_exit, only: naming_file
    implicit none
    private
    public :: write_sweep_csv, no_digit_verdict, write_threshold_adapt_csv, add_threshold_keys, &
              threshold_summary_lines, boundary_lines

    character(len=*), parameter :: SWEEP_FILE = 'lambda_sweep.csv'
    character(len=*), parameter :: SWEEP_HEADER = &
        'lambda,critical_c_n,critical_c_t,slip_sign,n_positive,error_estimate,n_dofs,error_bar'

    character(len=*), parameter, public :: THRESHOLD_ADAPT_HEADER = 'level,n_dofs,'// &
        'n_contact,n_cells,lambda_plus,error_estimate_plus,lambda_minus,'// &
        'error_estimate_minus,time_s,error_bar_plus,error_bar_minus,collision_plus,'// &
        'error_estimate_collision_plus,error_bar_collision_plus,collision_minus,'// &
        'error_estimate_collision_minus,error_bar_collision_minus'

    !> 'threshold': the thresholds on the mesh of &mesh.
    type, extends(analysis_t), public :: threshold_run_t
        !> allocatable, allocated by every solve: gfortran 12 frees it whole (docs/testing.md)
        type(threshold_result_t), allocatable :: res
        character(len=:), allocatable :: plot_note   !! mode_001.png: where, or why not
    contains
        procedure :: solve => threshold_run_solve
        procedure :: write_files => threshold_run_write_files
        procedure :: summary => threshold_run_summary
        procedure :: report => threshold_run_report
    end type threshold_run_t

    !> 'lambda_sweep': the thresholds and the lowest positive mu at every lambda of &sweep.
    type, extends(threshold_run_t), public :: sweep_run_t
    contains
        procedure :: solve => sweep_run_solve
        procedure :: write_files => sweep_run_write_files
        procedure :: summary => sweep_run_summary
        procedure :: report => sweep_run_report
    end type sweep_run_t

    !> 'threshold' with &adapt: the loop, whose final problem the files describe.
    type, extends(threshold_run_t), public :: adapt_threshold_run_t
        !> allocatable, allocated by solve: gfortran 12 frees it whole (docs/testing.md)
        type(adaptive_thresholds_t), allocatable :: adapted
    contains
        procedure :: solve => adapt_threshold_run_solve
        procedure :: write_files => adapt_threshold_run_write_files
        procedure :: summary => adapt_threshold_run_summary
        procedure :: report => adapt_threshold_run_report
    end type adapt_threshold_run_t

contains

    subroutine threshold_run_solve(this, config, prob, timings, stat)
        class(threshold_run_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        call solve_thresholds(config, prob, .false., this%res, timings, stat)
        if (stat%ok()) call no_digit_verdict(this, config)
    end subroutine threshold_run_solve

    !> The verdict STATUS_NO_DIGIT (after the outputs: the set shows what was computed)
    !> where round-off leaves no correct digit of a critical lambda or of a collision
    !> point: its round-off bound is 1 or more.
    subroutine no_digit_verdict(this, config)
        class(threshold_run_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        real(wp) :: worst
        integer :: side, i
        character(len=:), allocatable :: what
        worst = -1.0_wp
        what = ''
        do side = SIDE_PLUS, SIDE_MINUS
            if (.not. this%res%thresholds%found(side)) cycle
            if (this%res%thresholds%roundoff(side) <= worst) cycle
            worst = this%res%thresholds%roundoff(side)
            what = trim(SIDE_LABELS(side))
        end do
        do i = 1, size(this%res%set%points)
            if (this%res%set%points(i)%roundoff <= worst) cycle
            worst = this%res%set%points(i)%roundoff
            what = 'the collision point lambda = '// &
                short_real_text(this%res%set%points(i)%lambda, 12)
        end do
        if (worst >= 1.0_wp) call this%verdict%fail(STATUS_NO_DIGIT, config%input_file// &
            ': round-off leaves no correct digit of '//what//' (bound '// &
            short_real_text(worst)//' relative); the output set is written')
    end subroutine no_digit_verdict

    subroutine sweep_run_solve(this, config, prob, timings, stat)
        class(sweep_run_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        call solve_thresholds(config, prob, .true., this%res, timings, stat)
        if (.not. stat%ok()) return
        ! a point's loop failed: its failure is the run's, after the partial set is written
        associate (curve => this%res%sweep)
            if (.not. curve%failure%ok()) then
                call this%verdict%fail(curve%failure%code, naming_file( &
                    curve%failure%message, config%input_file)//' (the sweep stopped there: '// &
                    'a partial set of the '//to_string(count(curve%complete))//' of '// &
                    to_string(size(curve%lambda))//' points complete is written)')
                return
            end if
        end associate
        call no_digit_verdict(this, config)
        if (.not. this%verdict%ok()) return
        if (this%res%sweep%n_not_met > 0) call this%verdict%fail(STATUS_NOT_MET, &
            config%input_file//': &adapt: '//to_string(this%res%sweep%n_not_met)// &
            ' of the sweep''s points with a positive mu did not meet the tolerance, '// &
            'the first at '//this%res%sweep%not_met//' (the set is written)')
    end subroutine sweep_run_solve

    subroutine adapt_threshold_run_solve(this, config, prob, timings, stat)
        class(adapt_threshold_run_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        if (.not. allocated(this%res)) allocate (this%res)
        if (.not. allocated(this%adapted)) allocate (this%adapted)
        call solve_adapted_thresholds(config, prob, this%adapted, this%res, timings, stat)
        if (stat%ok() .and. .not. this%adapted%converged) call this%verdict%fail( &
            STATUS_NOT_MET, config%input_file//': &adapt: '//this%adapted%outcome// &
            ' (the set of the last level is written)')
        if (stat%ok()) call no_digit_verdict(this, config)
    end subroutine adapt_threshold_run_solve

    subroutine threshold_run_write_files(this, stage, config, prob, stat)
        class(threshold_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        call write_eigen_files(stage, config, prob, this%res%eigen, stat, this%plot_note)
    end subroutine threshold_run_write_files

    subroutine sweep_run_write_files(this, stage, config, prob, stat)
        class(sweep_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: path
        call this%threshold_run_t%write_files(stage, config, prob, stat)
        if (stat%ok() .and. allocated(this%res%sweep%lambda)) then
            call stage%add(SWEEP_FILE, path)
            call write_sweep_csv(path, this%res%sweep, stat)
        end if
        if (stat%ok() .and. allocated(this%res%sweep%lambda)) &
            call draw_sweep(stage, config, prob, this%res, this%picture_note)
    end subroutine sweep_run_write_files

    subroutine adapt_threshold_run_write_files(this, stage, config, prob, stat)
        class(adapt_threshold_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: path
        call write_eigen_files(stage, config, this%adapted%prob, this%res%eigen, stat, &
                               this%plot_note)
        if (stat%ok()) then
            call stage%add('adapt.csv', path)
            call write_threshold_adapt_csv(path, this%adapted, stat)
        end if
        if (stat%ok()) call write_adapted_mesh(stage, this%adapted%prob, stat)
        ! the files describe the final level; of the starting problem `prob` only its dofs
        if (stat%ok()) call draw_threshold_adapt(stage, config, &
            this%adapted%prob%mesh%element, prob%dofs%n_free, this%adapted%levels, &
            this%picture_note)
    end subroutine adapt_threshold_run_write_files

    function threshold_run_summary(this, config, prob) result(summary)
        class(threshold_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(json_object_t) :: summary
        summary = eigen_summary_json(config, prob, this%res%eigen, this%timings)
        call add_threshold_keys(summary, this%res)
    end function threshold_run_summary

    function sweep_run_summary(this, config, prob) result(summary)
        class(sweep_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(json_object_t) :: summary
        summary = this%threshold_run_t%summary(config, prob)
        if (allocated(this%res%sweep%lambda)) call add_sweep_keys(summary, config, this%res)
    end function sweep_run_summary

    function adapt_threshold_run_summary(this, config, prob) result(summary)
        class(adapt_threshold_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(json_object_t) :: summary
        summary = eigen_summary_json(config, this%adapted%prob, this%res%eigen, this%timings)
        call add_threshold_keys(summary, this%res)
        call add_adapt_keys(summary, config, prob%dofs%n_free, &
            size(this%adapted%levels) - 1, this%adapted%converged, this%adapted%floor_reached, &
            this%adapted%outcome)
    end function adapt_threshold_run_summary

    function threshold_run_report(this, config, prob) result(text)
        class(threshold_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        text = threshold_summary_lines(config, prob, this%res, this%timings, this%plot_note)
    end function threshold_run_report

    function sweep_run_report(this, config, prob) result(text)
        class(sweep_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        text = this%threshold_run_t%report(config, prob)
        if (allocated(this%picture_note)) text = text//new_line('a')//'  plot        '// &
                                                  this%picture_note
    end function sweep_run_report

    function adapt_threshold_run_report(this, config, prob) result(text)
        class(adapt_threshold_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        text = threshold_summary_lines(config, this%adapted%prob, this%res, this%timings, &
                                       this%plot_note)
        text = text//adapt_report_lines(config, prob%dofs%n_free, &
            size(this%adapted%levels) - 1, this%adapted%outcome, this%picture_note)
    end function adapt_threshold_run_report

    !> level,n_dofs,n_contact,n_cells,lambda_plus,error_estimate_plus,lambda_minus,
    !> error_estimate_minus,time_s,error_bar_plus,error_bar_minus, then per side the collision
    !> onset, its estimate and bar; a side's cells empty where it has no threshold (collision
    !> onset) or no estimate.
    !> `extra_header`, `extra`: columns appended to the header and to each row (hp).
    subroutine write_threshold_adapt_csv(path, out, stat, extra_header, extra)
        character(len=*), intent(in) :: path
        type(adaptive_thresholds_t), intent(in) :: out
        type(status_t), intent(out) :: stat
        character(len=*), intent(in), optional :: extra_header, extra(:)
        type(csv_writer_t) :: csv
        character(len=:), allocatable :: line
        integer :: i, side

        if (present(extra_header)) then
            call csv%open(path, THRESHOLD_ADAPT_HEADER//extra_header)
        else
            call csv%open(path, THRESHOLD_ADAPT_HEADER)
        end if
        do i = 1, size(out%levels)
            associate (row => out%levels(i))
                line = to_string(row%level)//','//to_string(row%n_dofs)//','// &
                    to_string(row%n_contact)//','//to_string(row%n_cells)
                do side = SIDE_PLUS, SIDE_MINUS
                    line = line//','
                    if (row%found(side)) line = line//real_to_text(row%lambda(side))
                    line = line//','
                    if (row%estimated(side)) line = line//real_to_text(row%error_estimate(side))
                end do
                line = line//','//real_to_text(row%time_s)
                do side = SIDE_PLUS, SIDE_MINUS
                    line = line//','
                    if (row%error_bar(side) >= 0.0_wp) line = line// &
                        real_to_text(row%error_bar(side))
                end do
                ! a side whose onset is a collision of two real mu: its lambda, estimate, bar
                do side = SIDE_PLUS, SIDE_MINUS
                    line = line//','
                    if (row%collision(side)) line = line//real_to_text(row%collision_lambda(side))
                    line = line//','
                    if (row%collision_estimate(side) >= 0.0_wp) line = line// &
                        real_to_text(row%collision_estimate(side))
                    line = line//','
                    if (row%collision_bar(side) >= 0.0_wp) line = line// &
                        real_to_text(row%collision_bar(side))
                end do
                if (present(extra)) line = line//trim(extra(i))
                call csv%row(line)
            end associate
        end do
        call csv%close(stat)
    end subroutine write_threshold_adapt_csv


    !> lambda_critical_plus/minus (null where none), the backward error of each on the pencil,
    !> the pencil's eigenvalue counts, and the confirming solves on each side.
    subroutine add_threshold_keys(summary, res)
        type(json_object_t), intent(inout) :: summary
        type(threshold_result_t), intent(in) :: res
        integer :: side
        character(len=:), allocatable :: s

        associate (thr => res%thresholds)
            do side = SIDE_PLUS, SIDE_MINUS
                s = trim(SIDE_NAMES(side))
                call summary%add_real_or_null('lambda_critical_'//s, thr%lambda(side), &
                                              thr%found(side))
            end do
            do side = SIDE_PLUS, SIDE_MINUS
                s = trim(SIDE_NAMES(side))
                call summary%add_real_or_null('lambda_critical_'//s//'_residual', &
                                              thr%residual(side), thr%found(side))
                ! |dlambda| / |lambda| from floating point (roundoff: threshold_roundoff)
                call summary%add_real_or_null('lambda_critical_'//s//'_roundoff', &
                    thr%roundoff(side), thr%found(side) .and. thr%roundoff(side) >= 0.0_wp)
                call summary%add_logical('lambda_critical_'//s//'_confirmed', &
                                         thr%confirmed(side))
                call summary%add_real_or_null('lambda_'//s//'_outside', &
                                              thr%lambda_outside(side), thr%found(side))
                call summary%add_real_or_null('mu_'//s//'_outside', thr%mu_outside(side), &
                                              thr%has_mu_outside(side))
                call summary%add_real_or_null('lambda_'//s//'_inside', &
                                              thr%lambda_inside(side), thr%found(side))
                call summary%add_real_or_null('mu_'//s//'_inside', thr%mu_inside(side), &
                                              thr%has_mu_inside(side))
            end do
            ! |lambda_h - lambda| / |lambda_h| estimated (threshold_estimate); null where not
            do side = SIDE_PLUS, SIDE_MINUS
                call summary%add_real_or_null('lambda_critical_'//trim(SIDE_NAMES(side))// &
                    '_error_estimate', abs(res%estimate%relative(side)), &
                    res%estimate%computed(side))
            end do
            ! the relative bars quoted with them (error_bar); null where none
            do side = SIDE_PLUS, SIDE_MINUS
                call summary%add_real_or_null('lambda_critical_'//trim(SIDE_NAMES(side))// &
                    '_error_bar', res%estimate%bar(side), &
                    res%estimate%computed(side) .and. res%estimate%bar(side) >= 0.0_wp)
            end do
            ! |lambda*| is the friction coefficient of the Signorini-Coulomb eigenproblem
            ! (model.md section 7), whether or not a positive mu appears there
            do side = SIDE_PLUS, SIDE_MINUS
                call summary%add_real_or_null('critical_friction_coefficient_'// &
                                              trim(SIDE_NAMES(side)), abs(thr%lambda(side)), &
                                              thr%found(side))
            end do
            call summary%add_real('confirm_offset', CONFIRM_OFFSET)
            call summary%add_integer('pencil_n_real', thr%n_real)
            call summary%add_integer('pencil_n_complex', thr%n_complex)
            call summary%add_integer('pencil_n_infinite', thr%n_infinite)
        end associate
        call add_boundary_keys(summary, res%set)
        call summary%add_real('time_threshold_s', res%time_threshold)
    end subroutine add_threshold_keys

    !> The boundary points of {lambda : a positive mu exists} in the searched range, one
    !> array entry per point (ascending lambda), and the intervals they bound.
    subroutine add_boundary_keys(summary, set)
        type(json_object_t), intent(inout) :: summary
        type(critical_set_t), intent(in) :: set
        real(wp), allocatable :: lower(:), upper(:), lambdas(:), discriminants(:), mu_meets(:), &
                                 bars(:), roundoffs(:)
        integer, allocatable :: below(:), above(:)
        logical, allocatable :: confirmed(:)
        character(len=len(MECHANISM_NAMES)), allocatable :: mechanisms(:)
        character(len=8), allocatable :: directions(:)
        integer :: i, n, side

        ! Plain arrays, filled point by point: a component of an array of derived type
        ! passed as an array makes a temporary (a runtime warning under -fcheck=all).
        n = size(set%points)
        allocate (lambdas(n), discriminants(n), mu_meets(n), below(n), above(n), confirmed(n), &
                  mechanisms(n), directions(n), bars(n), roundoffs(n))
        do i = 1, n
            ! the relative bar of each point (boundary_estimate); NaN is written as null
            bars(i) = set%points(i)%error_bar
            if (bars(i) < 0.0_wp) bars(i) = ieee_value(1.0_wp, ieee_quiet_nan)
            roundoffs(i) = set%points(i)%roundoff   ! its round-off part
            if (roundoffs(i) < 0.0_wp) roundoffs(i) = ieee_value(1.0_wp, ieee_quiet_nan)
            associate (b => set%points(i))
                lambdas(i) = b%lambda
                below(i) = b%n_below
                above(i) = b%n_above
                confirmed(i) = b%confirmed
                mechanisms(i) = MECHANISM_NAMES(b%mechanism)
                directions(i) = merge('appears ', 'vanishes', b%appears)
                ! null for pencil points, where no pair meets
                discriminants(i) = ieee_value(1.0_wp, ieee_quiet_nan)
                mu_meets(i) = discriminants(i)
                if (b%mechanism == MECHANISM_COMPLEX_PAIR) then
                    discriminants(i) = b%discriminant
                    mu_meets(i) = b%mu_meet
                end if
            end associate
        end do
        ! where a positive mu first exists going out from lambda = 0 (where none does)
        do side = SIDE_PLUS, SIDE_MINUS
            i = onset_point(set, side)
            if (i > 0) then
                call summary%add_real('lambda_onset_'//trim(SIDE_NAMES(side)), &
                                      set%points(i)%lambda)
                call summary%add_string('lambda_onset_'//trim(SIDE_NAMES(side))// &
                                        '_mechanism', trim(mechanisms(i)))
            else
                call summary%add_null('lambda_onset_'//trim(SIDE_NAMES(side)))
                call summary%add_null('lambda_onset_'//trim(SIDE_NAMES(side))//'_mechanism')
            end if
        end do
        call summary%add_real('boundary_lambda_min', set%lambda_min)
        call summary%add_real('boundary_lambda_max', set%lambda_max)
        call summary%add_integer('boundary_n_points', n)
        call summary%add_real_array('boundary_lambda', lambdas)
        call summary%add_string_array('boundary_mechanism', mechanisms)
        call summary%add_real_array('boundary_error_bar', bars)
        call summary%add_real_array('boundary_roundoff', roundoffs)
        call summary%add_string_array('boundary_direction', directions)
        call summary%add_logical_array('boundary_confirmed', confirmed)
        call summary%add_integer_array('boundary_n_positive_below', below)
        call summary%add_integer_array('boundary_n_positive_above', above)
        call summary%add_real_array('boundary_discriminant', discriminants)
        call summary%add_real_array('boundary_mu_meet', mu_meets)
        call positive_intervals(set, lower, upper)
        call summary%add_real_array('positive_mu_intervals_lower', lower)
        call summary%add_real_array('positive_mu_intervals_upper', upper)
        call summary%add_integer('boundary_n_evaluations', set%n_evaluations)
        call summary%add_integer('boundary_scan_contact', set%scan_contact)
    end subroutine add_boundary_keys

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

    !> What a sweep ran: its file, size, range and spacing, and how many points had a mu.
    subroutine add_sweep_keys(summary, config, res)
        type(json_object_t), intent(inout) :: summary
        type(config_t), intent(in) :: config
        type(threshold_result_t), intent(in) :: res
        character(len=:), allocatable :: spacing

        spacing = 'list'
        if (.not. config%sweep%lambdas(1) < huge(1.0_wp)) spacing = trim(config%sweep%spacing)
        call summary%add_string('sweep_file', SWEEP_FILE)
        call summary%add_string('sweep_spacing', spacing)
        call summary%add_integer('sweep_n_lambda', size(res%sweep%lambda))
        call summary%add_real('sweep_lambda_min', minval(res%sweep%lambda))
        call summary%add_real('sweep_lambda_max', maxval(res%sweep%lambda))
        call summary%add_integer('sweep_n_with_positive_mu', count(res%sweep%found))
        call summary%add_integer('sweep_n_arpack', res%sweep%n_arpack)
        call summary%add_integer('sweep_n_dense', res%sweep%n_dense)
        ! with &adapt: the points adapted (every one), those whose mesh needed no refinement
        ! (the previous point's served), the largest estimate met
        if (config%adapt%tolerance > 0.0_wp) then
            call summary%add_integer('sweep_n_adapted', size(res%sweep%lambda))
            call summary%add_integer('sweep_n_mesh_reused', res%sweep%n_reused)
            call summary%add_integer('sweep_n_not_met', res%sweep%n_not_met)
            call summary%add_logical('adapt_converged', res%sweep%n_not_met == 0 .and. &
                                     res%sweep%failure%ok())
            ! a point's loop failed: the rows are those of the points complete before
            call summary%add_logical('sweep_partial', .not. res%sweep%failure%ok())
            call summary%add_integer('sweep_n_complete', count(res%sweep%complete))
            call summary%add_real_or_null('sweep_max_error_estimate', &
                maxval(res%sweep%error_estimate), any(res%sweep%error_estimate >= 0.0_wp))
            call summary%add_real_or_null('sweep_max_error_bar', &
                maxval(res%sweep%error_bar), any(res%sweep%error_bar >= 0.0_wp))
        end if
        call summary%add_real('time_sweep_s', res%time_sweep)
    end subroutine add_sweep_keys

    !> lambda,critical_c_n,critical_c_t,slip_sign,n_positive,error_estimate,n_dofs: one row
    !> per lambda in input order (of a partial set, per complete point); c_n and c_t are
    !> empty where no positive real mu exists, error_estimate where none was computed
    !> (always without &adapt).
    subroutine write_sweep_csv(path, curve, stat)
        character(len=*), intent(in) :: path
        type(sweep_curve_t), intent(in) :: curve
        type(status_t), intent(out) :: stat
        type(csv_writer_t) :: csv
        character(len=:), allocatable :: values
        integer :: i

        call csv%open(path, SWEEP_HEADER)
        do i = 1, size(curve%lambda)
            if (allocated(curve%complete)) then
                if (.not. curve%complete(i)) cycle   ! a partial set: its complete points
            end if
            values = ','
            if (curve%found(i)) values = real_to_text(curve%mu(i))//','// &
                real_to_text(critical_c_t(curve%mu(i), curve%lambda(i)))
            call csv%row(real_to_text(curve%lambda(i))//','//values//','// &
                to_string(slip_sign(curve%lambda(i)))//','//to_string(curve%n_positive(i))// &
                ','//known_text(curve%error_estimate(i) >= 0.0_wp, curve%error_estimate(i))// &
                ','//to_string(curve%n_dofs(i))//','// &
                known_text(curve%error_bar(i) >= 0.0_wp, curve%error_bar(i)))
        end do
        call csv%close(stat)
    end subroutine write_sweep_csv

    !> The eigen summary, then the thresholds with their confirmations and the sweep.
    function threshold_summary_lines(config, prob, res, timings, plot_note) result(text)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(threshold_result_t), intent(in) :: res
        type(timings_t), intent(in) :: timings
        character(len=*), intent(in) :: plot_note
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        integer :: side

        text = summary_lines(config, prob, res%eigen, timings, plot_note)
        associate (thr => res%thresholds)
            do side = SIDE_PLUS, SIDE_MINUS
                text = text//NL//'  '//SIDE_LABELS(side)//'     '
                if (.not. thr%found(side)) then
                    text = text//'none (no real eigenvalue of Kt_nn x = lambda Kt_nt x ' &
                        //merge('> 0', '< 0', side == SIDE_PLUS)//')'
                    cycle
                end if
                text = text//real_to_text(thr%lambda(side))
                ! the headline quotes its bar, absolute: lambda = X +- B
                if (res%estimate%computed(side) .and. res%estimate%bar(side) >= 0.0_wp) &
                    text = text//' +- '//short_real_text(res%estimate%bar(side)* &
                                                         abs(thr%lambda(side)))
                text = text//' (pencil backward error '// &
                    short_real_text(thr%residual(side))//'), '// &
                    trim(merge('confirmed    ', 'NOT confirmed', thr%confirmed(side)))// &
                    estimate_text(side)//NL// &
                    '              just outside, lambda = '// &
                    real_to_text(thr%lambda_outside(side))//': lowest positive mu = '// &
                    known_text(thr%has_mu_outside(side), thr%mu_outside(side), 'none')//NL// &
                    '              just inside,  lambda = '// &
                    real_to_text(thr%lambda_inside(side))//': lowest positive mu = '// &
                    known_text(thr%has_mu_inside(side), thr%mu_inside(side), 'none')
            end do
        end associate
        text = text//boundary_lines(res%set)
        text = text//NL//'  time [s]    thresholds '//short_real_text(res%time_threshold)
        if (allocated(res%sweep%lambda)) then
            text = text//', sweep '//short_real_text(res%time_sweep)//NL//'  sweep       '// &
                to_string(size(res%sweep%lambda))//' lambdas from '// &
                real_to_text(minval(res%sweep%lambda))//' to '// &
                real_to_text(maxval(res%sweep%lambda))//', a positive mu at '// &
                to_string(count(res%sweep%found))//' of them: '//SWEEP_FILE
        end if

    contains

        !> the line of the relative error estimate, or of why there is none ('' when neither)
        function estimate_text(side) result(s)
            integer, intent(in) :: side
            character(len=:), allocatable :: s
            s = ''
            if (res%estimate%computed(side)) then
                if (len_trim(res%estimate%method) > 0) then
                    s = trim(res%estimate%method)
                else
                    s = ' enrichment'
                    if (res%estimate%halved_mesh) s = ', halved mesh'
                    s = element_name(res%estimate%element)//s
                end if
                if (s == HP_ESTIMATE) then
                    ! the change is the previous level's error: the bar may be below it
                    s = NL//'              relative change to the previous hp level '// &
                        short_real_text(abs(res%estimate%relative(side)))// &
                        ' (the error of that level); error bar '// &
                        short_real_text(res%estimate%bar(side))
                else
                    s = NL//'              relative error estimate '// &
                        short_real_text(abs(res%estimate%relative(side)))//' ('//s// &
                        '); error bar '//short_real_text(res%estimate%bar(side))
                end if
            else if (len_trim(res%estimate%skipped(side)) > 0) then
                s = NL//'              relative error estimate '//trim(res%estimate%skipped(side))
            end if
        end function estimate_text
    end function threshold_summary_lines

    !> One line per boundary point, then the intervals with a positive mu.
    function boundary_lines(set) result(text)
        type(critical_set_t), intent(in) :: set
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        real(wp), allocatable :: lower(:), upper(:)
        integer :: i

        text = NL//'  boundary    of {lambda : a positive mu exists} in ['// &
            real_to_text(set%lambda_min)//', '//real_to_text(set%lambda_max)//']: '// &
            to_string(size(set%points))//trim(merge(' point ', ' points', size(set%points) == 1))
        if (set%scan_contact /= set%contact) text = text//' (scanned on a coarser level, '// &
            to_string(set%scan_contact)//' contact functions; located on this one)'
        do i = 1, size(set%points)
            associate (b => set%points(i))
                text = text//NL//'              lambda = '//real_to_text(b%lambda)
                if (b%error_bar >= 0.0_wp) text = text//' +- '// &
                    short_real_text(b%error_bar*abs(b%lambda))
                text = text//' '//trim(MECHANISM_NAMES(b%mechanism))//', '
                if (b%n_below == b%n_above) then
                    ! no change of the count across it: neither appears nor vanishes
                    text = text//'the count of positive mu is '//to_string(b%n_below)// &
                        ' on both sides, '
                else
                    text = text//'positive mu '// &
                        trim(merge('appears ', 'vanishes', b%appears))// &
                        ' as lambda increases ('//to_string(b%n_below)//' -> '// &
                        to_string(b%n_above)//'), '
                end if
                text = text//trim(merge('confirmed    ', 'NOT confirmed', b%confirmed))
            end associate
        end do
        call positive_intervals(set, lower, upper)
        text = text//NL//'              positive mu on'
        if (size(lower) == 0) text = text//' no part of the range'
        do i = 1, size(lower)
            text = text//' ['//real_to_text(lower(i))//', '//real_to_text(upper(i))//']'
        end do
    end function boundary_lines
end module threshold_run
