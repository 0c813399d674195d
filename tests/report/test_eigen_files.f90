! SPDX-License-Identifier: MIT
!> The report layer on a result built by hand, with no analysis run: eigenvalues.csv and
!> the summary.json keys of the lowest positive mu hold the result's own numbers. Exact
!> comparisons: real_to_text writes the shortest text that reads back to the same binary64,
!> so a value read back from a file equals the value written. The critical pair is
!> c_n = mu, c_t = |lambda| mu (the threshold of slip at the lowest positive mu).
program test_eigen_files
    use kinds, only: wp
    use run_inputs, only: run_inputs_t, translate_input
    use fixtures, only: problem_of
    use status, only: status_t
    use testing, only: test_suite_t
    use timer, only: timings_t
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use spectrum, only: spectrum_t, KIND_POSITIVE, KIND_NEGATIVE, KIND_COMPLEX
    use eigen_solve, only: eigen_result_t
    use eigen_files, only: write_eigenvalues_csv
    use run_report, only: record_problem, record_eigen, record_no_eigen
    use summary_record, only: run_summary_t, summary_json, summary_text
    use json_writer, only: json_object_t
    use fixtures, only: square_scene, file_text, index_of_newline, &
                        value_text => json_value, real_value => json_real
    implicit none

    character(len=*), parameter :: CSV_PATH = 'test_eigen_files.csv'
    type(test_suite_t) :: t
    type(spectrum_t) :: spec

    t%name = 'test_eigen_files'
    spec = hand_spectrum()
    call csv_rows_are_the_spectrum(t, spec)
    call summary_keys_are_the_result(t, spec)
    call t%report()

contains

    !> Five eigenvalues in output order: two positive (the lowest first), a complex pair and
    !> a negative one; the condition unknown (-1) for the second.
    function hand_spectrum() result(spec)
        type(spectrum_t) :: spec
        ! allocated first: gfortran 12's reallocation on assignment reads unset bounds
        allocate (spec%mu(5), spec%kind(5), spec%residual(5), spec%condition(5))
        spec%mu(:) = [(0.75_wp, 0.0_wp), (2.0_wp, 0.0_wp), (1.5_wp, 2.5_wp), (1.5_wp, -2.5_wp), &
                   (-3.0_wp, 0.0_wp)]
        spec%kind(:) = [KIND_POSITIVE, KIND_POSITIVE, KIND_COMPLEX, KIND_COMPLEX, KIND_NEGATIVE]
        spec%residual(:) = [1.0e-16_wp, 2.5e-15_wp, 3.0e-16_wp, 3.0e-16_wp, 4.0e-16_wp]
        spec%condition(:) = [1.5_wp, -1.0_wp, 7.25_wp, 7.25_wp, 2.0_wp]
    end function hand_spectrum

    !> Row i of eigenvalues.csv: index, re, im, kind, residual, condition (empty when
    !> unknown), of eigenvalue i.
    subroutine csv_rows_are_the_spectrum(t, spec)
        type(test_suite_t), intent(inout) :: t
        type(spectrum_t), intent(in) :: spec
        character(len=*), parameter :: KIND_TEXT(5) = [character(len=8) :: 'positive', &
            'positive', 'complex', 'complex', 'negative']
        character(len=:), allocatable :: text, row
        character(len=32) :: fields(8)
        type(status_t) :: stat
        real(wp) :: re, im, residual, condition
        integer :: i, row_index, start, newline, unit

        call write_eigenvalues_csv(CSV_PATH, spec, stat)
        call t%check('csv: written', stat%ok())
        if (.not. stat%ok()) return
        text = file_text(CSV_PATH, new_line('a'))
        newline = index_of_newline(text, 1)
        call t%check('csv: header', text(:newline - 1) == &
                     'index,re,im,kind,residual,condition,error_estimate,error_bar')
        do i = 1, spec%n()
            start = newline + 1
            newline = index_of_newline(text, start)
            row = text(start:newline - 1)
            call split_fields(row, fields)
            read (fields(1), *) row_index
            read (fields(2), *) re
            read (fields(3), *) im
            read (fields(5), *) residual
            call t%check('csv row '//trim(fields(1))//': index, re, im, kind, residual', &
                         row_index == i .and. same(re, real(spec%mu(i), wp)) .and. &
                         same(im, aimag(spec%mu(i))) .and. fields(4) == KIND_TEXT(i) .and. &
                         same(residual, spec%residual(i)))
            if (spec%condition(i) < 0.0_wp) then
                call t%check('csv row '//trim(fields(1))//': unknown condition left empty', &
                             len_trim(fields(6)) == 0)
            else
                read (fields(6), *) condition
                call t%check('csv row '//trim(fields(1))//': condition', &
                             same(condition, spec%condition(i)))
            end if
            call t%check('csv row '//trim(fields(1))//': no error estimate nor bar', &
                         len_trim(fields(7)) == 0 .and. len_trim(fields(8)) == 0)
        end do
        call t%check('csv: one row per eigenvalue', newline == len(text))
        open (newunit=unit, file=CSV_PATH, status='old')
        close (unit, status='delete')
    end subroutine csv_rows_are_the_spectrum

    !> summary.json of the reference scene's problem (2 x 2 P1 cells) with the hand
    !> spectrum at lambda = -5: the lowest positive mu and its pair, the sizes of the
    !> problem, the positive mu up to cn_max; without a result, the same keys are null.
    subroutine summary_keys_are_the_result(t, spec)
        type(test_suite_t), intent(inout) :: t
        type(spectrum_t), intent(in) :: spec
        type(config_t) :: config
        type(problem_t) :: prob
        type(eigen_result_t) :: res
        type(timings_t) :: timings
        type(json_object_t) :: summary
        type(run_inputs_t) :: inputs
        type(run_summary_t) :: rec
        type(status_t) :: stat
        character(len=:), allocatable :: text

        call square_scene(2, 'p1', 'right', config)
        config%eigen%cn_max = 2.0_wp
        call problem_of(config, prob, stat)
        call t%check('summary: problem built', stat%ok())
        if (.not. stat%ok()) return
        res%lambda = -5.0_wp
        res%spec = spec
        call translate_input(config, inputs)
        call record_problem(rec, inputs, prob)
        call record_eigen(rec%eigen, inputs, res)
        rec%timings = timings
        summary = summary_json(rec)
        text = summary%to_text()
        call t%check('summary: lambda', same(real_value(text, 'lambda'), res%lambda))
        call t%check('summary: lowest_positive_mu', &
                     same(real_value(text, 'lowest_positive_mu'), real(spec%mu(1), wp)))
        call t%check('summary: critical_c_n = mu', &
                     same(real_value(text, 'critical_c_n'), real(spec%mu(1), wp)))
        call t%check('summary: critical_c_t = |lambda| mu', &
                     same(real_value(text, 'critical_c_t'), 5.0_wp*real(spec%mu(1), wp)))
        call t%check('summary: lowest_positive_condition', &
                     same(real_value(text, 'lowest_positive_condition'), spec%condition(1)))
        call t%check('summary: lowest_positive_residual', &
                     same(real_value(text, 'lowest_positive_residual'), spec%residual(1)))
        call t%check('summary: max_residual', &
                     same(real_value(text, 'max_residual'), maxval(spec%residual)))
        call t%check('summary: n_eigenvalues', value_text(text, 'n_eigenvalues') == '5')
        call t%check('summary: critical_cn holds the positive mu up to cn_max', &
                     value_text(text, 'critical_cn') == '[0.75, 2.0]')
        call t%check('summary: n_dofs and n_contact of the problem', &
                     nint(real_value(text, 'n_dofs')) == prob%dofs%n_free .and. &
                     nint(real_value(text, 'n_contact')) == prob%contact%p())
        call t%check('summary: no error estimate, unknown round-off: null', &
                     value_text(text, 'lowest_positive_error_estimate') == 'null' .and. &
                     value_text(text, 'lowest_positive_roundoff') == 'null')

        call record_no_eigen(rec%eigen, inputs)
        summary = summary_json(rec)
        text = summary%to_text()
        call t%check('no result: lowest_positive_mu and critical_c_t null', &
                     value_text(text, 'lowest_positive_mu') == 'null' .and. &
                     value_text(text, 'critical_c_t') == 'null')
        call t%check('no result: n_eigenvalues 0, critical_cn empty', &
                     value_text(text, 'n_eigenvalues') == '0' .and. &
                     value_text(text, 'critical_cn') == '[]')
    end subroutine summary_keys_are_the_result

    !> a and b are the same number (exact: the text read back is the shortest of it).
    elemental logical function same(a, b)
        real(wp), intent(in) :: a, b
        same = abs(a - b) <= 0.0_wp
    end function same

    !> The comma-separated fields of a csv row (no quoting in eigenvalues.csv).
    pure subroutine split_fields(row, fields)
        character(len=*), intent(in) :: row
        character(len=*), intent(out) :: fields(:)
        integer :: i, start, comma
        fields = ''
        start = 1
        do i = 1, size(fields)
            comma = index(row(start:), ',')
            if (comma == 0) then
                fields(i) = row(start:)
                return
            end if
            fields(i) = row(start:start + comma - 2)
            start = start + comma
        end do
    end subroutine split_fields
end program test_eigen_files
