! SPDX-License-Identifier: MIT
!> analysis = 'threshold' with &adapt tolerance > 0 and strategy = 'hp': the loop of
!> hp_threshold and its files, those of the h loop (threshold_run: adapt_threshold_run_t)
!> where the hp levels allow: eigenvalues.csv at &analysis lambda on the last level,
!> mode_NNN.vtu sampled on the hp field (as hp_adapt_run), adapt.csv with the h loop's
!> columns and layers, p_min, p_max, mesh.msh and degrees.csv; summary.json with the
!> threshold keys, the adapt keys and the hp ones.
module hp_threshold_run
    use status, only: status_t, STATUS_NOT_MET
    use strings, only: to_string
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t
    use hp_threshold, only: hp_thresholds_t, hp_adapt_thresholds
    use threshold_run, only: threshold_run_t, write_threshold_adapt_csv, add_threshold_keys, &
                             threshold_summary_lines, no_digit_verdict
    use pictures, only: draw_threshold_adapt
    use hp_adapt_run, only: write_hp_modes, write_degrees, add_hp_keys, hp_report_lines, &
                            DEGREES_FILE
    use eigen_files, only: eigen_summary_json, write_eigenvalues_csv
    use adapt_files, only: add_adapt_keys, write_adapted_mesh
    use output_stage, only: output_stage_t
    use json_writer, only: json_object_t
    implicit none
    private

    !> the columns adapt.csv adds to the h loop's
    character(len=*), parameter, public :: HP_THRESHOLD_COLUMNS = ',layers,p_min,p_max'

    type, extends(threshold_run_t), public :: hp_threshold_run_t
        !> allocatable, allocated by solve: gfortran 12 frees it whole (docs/testing.md)
        type(hp_thresholds_t), allocatable :: out
        integer :: start_dofs = 0   !! free dofs of the input mesh (as given)
    contains
        procedure :: solve => hp_threshold_solve
        procedure :: write_files => hp_threshold_write_files
        procedure :: summary => hp_threshold_summary
        procedure :: report => hp_threshold_report
    end type hp_threshold_run_t

contains

    subroutine hp_threshold_solve(this, config, prob, timings, stat)
        class(hp_threshold_run_t), intent(inout) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        this%start_dofs = prob%dofs%n_free
        if (.not. allocated(this%res)) allocate (this%res)
        if (.not. allocated(this%out)) allocate (this%out)
        call hp_adapt_thresholds(config, prob, this%out, this%res, timings, stat)
        if (stat%ok() .and. .not. this%out%adapted%converged) call this%verdict%fail( &
            STATUS_NOT_MET, config%input_file//': &adapt: '//this%out%adapted%outcome// &
            ' (the set of the last level is written)')
        if (stat%ok()) call no_digit_verdict(this, config)
    end subroutine hp_threshold_solve

    subroutine hp_threshold_write_files(this, stage, config, prob, stat)
        class(hp_threshold_run_t), intent(inout) :: this
        type(output_stage_t), intent(inout) :: stage
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: path
        character(len=40) :: extra(size(this%out%layers))
        integer :: i
        if (prob%mesh%n_cells() == 0 .or. size(this%out%layers) == 0) return   ! nothing solved
        call stage%add('eigenvalues.csv', path)
        call write_eigenvalues_csv(path, this%res%eigen%spec, stat, this%res%eigen%error)
        if (stat%ok() .and. config%output%vtk) call write_hp_modes(stage, config, &
            this%out%adapted%prob, this%out%space, this%res%eigen%spec, this%res%eigen%lambda, &
            stat)
        do i = 1, size(extra)
            extra(i) = ','//to_string(this%out%layers(i))//','// &
                       to_string(this%out%p_min(i))//','//to_string(this%out%p_max(i))
        end do
        if (stat%ok()) then
            call stage%add('adapt.csv', path)
            call write_threshold_adapt_csv(path, this%out%adapted, stat, HP_THRESHOLD_COLUMNS, &
                                           extra)
        end if
        if (stat%ok()) call write_adapted_mesh(stage, this%out%adapted%prob, stat)
        if (stat%ok()) then
            call stage%add(DEGREES_FILE, path)
            call write_degrees(path, this%out%space, stat)
        end if
        if (stat%ok()) call draw_threshold_adapt(stage, config, prob%mesh%element, &
            this%start_dofs, this%out%adapted%levels, this%picture_note, 'hp')
    end subroutine hp_threshold_write_files

    function hp_threshold_summary(this, config, prob) result(summary)
        class(hp_threshold_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        type(json_object_t) :: summary
        summary = eigen_summary_json(config, this%out%adapted%prob, this%res%eigen, this%timings)
        call add_threshold_keys(summary, this%res)
        call add_adapt_keys(summary, config, this%start_dofs, size(this%out%layers), &
                            this%out%adapted%converged, this%out%adapted%floor_reached, &
                            this%out%adapted%outcome)
        call add_hp_keys(summary, config, this%out%space, prob%mesh%n_cells())
    end function hp_threshold_summary

    function hp_threshold_report(this, config, prob) result(text)
        class(hp_threshold_run_t), intent(in) :: this
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        character(len=:), allocatable :: text
        text = threshold_summary_lines(config, this%out%adapted%prob, this%res, this%timings, '')
        text = text//hp_report_lines(config, size(this%out%layers), this%out%space, &
                                     prob%mesh%n_cells(), this%out%adapted%outcome)
        if (allocated(this%picture_note)) then
            if (len(this%picture_note) > 0) text = text//new_line('a')//'  adapt plot  '// &
                                                   this%picture_note
        end if
    end function hp_threshold_report
end module hp_threshold_run
