! SPDX-License-Identifier: MIT
!> The pictures of a run, drawn from the results the report holds: adapt.png (per level of
!> an adaptive run, the relative error against the free dofs above the goal with its bar),
!> lambda_sweep.png (critical c_n and c_t against lambda) and mode_001.png (io/mode_plot; of
!> an hp run, sampled). The gnuplot text is built by functions that only build text, the
!> data inline and every path a quoted string, so that a test reads it without running
!> anything; draw_picture runs gnuplot on it (an argument vector, no shell) into the staging
!> folder. Optional: without gnuplot, or when it fails, the run goes on and the note says
!> why there is no picture.
module pictures
    use kinds, only: wp
    use ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
    use strings, only: to_string, short_real_text
    use real_format, only: real_to_text
    use filesystem, only: remove_file
    use gnuplot, only: not_drawable_note, gnuplot_string, path_argument, run_gnuplot
    use output_stage, only: output_stage_t
    use eigen_goal, only: eigen_level_t
    use eigen_solve, only: eigen_result_t
    use hp_space, only: hp_space_t
    use threshold_goal, only: threshold_level_t
    use threshold_analysis, only: threshold_result_t
    use critical_point, only: critical_c_t
    use run_inputs, only: run_inputs_t
    use scene, only: MESH_RECTANGLE
    use problem, only: problem_t
    use element_types, only: element_name, element_corners
    use mesh, only: mesh_t
    use hp_field, only: sample_hp_field
    use status, only: status_t
    use mode_plot, only: plot_mode
    implicit none
    private
    public :: adapt_script, sweep_script, draw_picture
    public :: eigen_adapt_curves, threshold_adapt_curves, hp_adapt_curves, hp_degree_labels
    public :: draw_eigen_adapt, draw_threshold_adapt, draw_hp_adapt, draw_sweep, draw_hp_mode
    public :: draw_mode

    character(len=*), parameter :: NL = new_line('a')
    !> pngcairo with enhanced text ({/Symbol l}, c_n): the fixed labels use it; a path never
    !> reaches a label.
    character(len=*), parameter :: TERMINAL = &
        'set terminal pngcairo size 1000,800 enhanced font ''sans,11'''
    character(len=*), parameter :: PLUS_MINUS = ' {/Symbol \261} error bar'
    character(len=*), parameter :: ADAPT_PNG = 'adapt.png', SWEEP_PNG = 'lambda_sweep.png', &
                                   MODE_PNG = 'mode_001.png'
    character(len=*), parameter :: MU_GOAL = &
        'lowest positive {/Symbol m} = critical c_n  [E / length]'

    !> One goal of adapt.png, a value per level: `value` as drawn (a side's sign applied),
    !> its relative `bar` and `estimate` (the top panel; `estimate_name` says what the dashed
    !> curve is); NaN where a level has none.
    type, public :: adapt_curve_t
        character(len=32) :: name = ''
        character(len=32) :: estimate_name = 'estimate'
        character(len=7) :: colour = '#1f77b4'
        real(wp), allocatable :: value(:), estimate(:), bar(:)
    end type adapt_curve_t

contains

    !> NaN: a value a level or point does not have, which gnuplot leaves out (a line breaks
    !> there).
    pure real(wp) function missing()
        missing = ieee_value(1.0_wp, ieee_quiet_nan)
    end function missing

    !> `x` where `known`, else NaN.
    elemental real(wp) function known_or_nan(known, x)
        logical, intent(in) :: known
        real(wp), intent(in) :: x
        known_or_nan = ieee_value(1.0_wp, ieee_quiet_nan)
        if (known) known_or_nan = x
    end function known_or_nan

    !> A negative bar or estimate means none: NaN.
    elemental real(wp) function relative_or_nan(x)
        real(wp), intent(in) :: x
        relative_or_nan = known_or_nan(x >= 0.0_wp, x)
    end function relative_or_nan

    !> The h loop of analysis 'eigen': the lowest positive mu.
    pure subroutine eigen_adapt_curves(levels, curves)
        type(eigen_level_t), intent(in) :: levels(:)
        type(adapt_curve_t), allocatable, intent(out) :: curves(:)
        integer :: i, n
        n = size(levels)
        allocate (curves(1))
        curves(1)%name = '{/Symbol m}'
        allocate (curves(1)%value(n), curves(1)%estimate(n), curves(1)%bar(n))
        do i = 1, n
            curves(1)%value(i) = known_or_nan(levels(i)%has_mu, levels(i)%mu)
            curves(1)%estimate(i) = known_or_nan(levels(i)%estimated, levels(i)%error_estimate)
            curves(1)%bar(i) = relative_or_nan(levels(i)%error_bar)
        end do
    end subroutine eigen_adapt_curves

    !> The threshold loop: lambda+ and |lambda-| (drawn as -lambda-), then the collision
    !> onsets of the sides that have one at some level (adapt.csv's collision_* columns).
    pure subroutine threshold_adapt_curves(levels, curves)
        type(threshold_level_t), intent(in) :: levels(:)
        type(adapt_curve_t), allocatable, intent(out) :: curves(:)
        character(len=*), parameter :: NAMES(2) = ['lambda+ ', '-lambda-'], &
            COLLISION_NAMES(2) = ['collision+ ', '-collision-']
        character(len=7), parameter :: COLOURS(2) = ['#1f77b4', '#ff7f0e'], &
            COLLISION_COLOURS(2) = ['#2ca02c', '#9467bd']
        real(wp), parameter :: SIGN(2) = [1.0_wp, -1.0_wp]
        logical :: collides(2)
        integer :: i, side, n, k
        n = size(levels)
        do side = 1, 2
            collides(side) = any([(levels(i)%collision(side), i = 1, n)])
        end do
        ! filled in place: a constructor of this type would leave its arrays allocated
        allocate (curves(2 + count(collides)))
        do side = 1, 2
            associate (c => curves(side))
                c%name = trim(NAMES(side))
                c%colour = COLOURS(side)
                c%value = [(known_or_nan(levels(i)%found(side), &
                                         SIGN(side)*levels(i)%lambda(side)), i = 1, n)]
                c%estimate = [(known_or_nan(levels(i)%estimated(side), &
                                            levels(i)%error_estimate(side)), i = 1, n)]
                c%bar = [(relative_or_nan(levels(i)%error_bar(side)), i = 1, n)]
            end associate
        end do
        k = 2
        do side = 1, 2
            if (.not. collides(side)) cycle
            k = k + 1
            associate (c => curves(k))
                c%name = trim(COLLISION_NAMES(side))
                c%colour = COLLISION_COLOURS(side)
                c%value = [(known_or_nan(levels(i)%collision(side), &
                                         SIGN(side)*levels(i)%collision_lambda(side)), i = 1, n)]
                c%estimate = [(relative_or_nan(levels(i)%collision_estimate(side)), i = 1, n)]
                c%bar = [(relative_or_nan(levels(i)%collision_bar(side)), i = 1, n)]
            end associate
        end do
    end subroutine threshold_adapt_curves

    !> The hp loop: mu with its bar, and in place of an estimate the change from the previous
    !> level, |mu_k - mu_(k-1)| / |mu_k| (known where both levels have a mu).
    pure subroutine hp_adapt_curves(levels, curves)
        type(eigen_level_t), intent(in) :: levels(:)
        type(adapt_curve_t), allocatable, intent(out) :: curves(:)
        integer :: i, n
        n = size(levels)
        allocate (curves(1))
        curves(1)%name = '{/Symbol m}'
        curves(1)%estimate_name = 'change per level'
        allocate (curves(1)%value(n), curves(1)%estimate(n), curves(1)%bar(n))
        do i = 1, n
            curves(1)%value(i) = known_or_nan(levels(i)%has_mu, levels(i)%mu)
            curves(1)%bar(i) = relative_or_nan(levels(i)%error_bar)
            curves(1)%estimate(i) = relative_or_nan(levels(i)%change)
        end do
    end subroutine hp_adapt_curves

    !> The degree range of each hp level, 'p 1-4' (or 'p 2' when all cells have one).
    pure function hp_degree_labels(levels) result(labels)
        type(eigen_level_t), intent(in) :: levels(:)
        character(len=16) :: labels(size(levels))
        integer :: i
        do i = 1, size(levels)
            labels(i) = 'p '//to_string(levels(i)%p_min)
            if (levels(i)%p_max /= levels(i)%p_min) &
                labels(i) = trim(labels(i))//'-'//to_string(levels(i)%p_max)
        end do
    end function hp_degree_labels

    !> adapt.png of `curves` against `dofs` (free dofs per level): above, each curve's
    !> relative bar (solid) and estimate (dashed) on log-log axes with the tolerance; below,
    !> the values with their bars against the dofs (log x), with `labels` per level (the hp
    !> degrees) when given. Data block $levels: dofs, then per curve value, absolute bar
    !> |value| bar, estimate, bar.
    function adapt_script(png, title, goal, tolerance, dofs, curves, labels) result(text)
        character(len=*), intent(in) :: png, title, goal
        real(wp), intent(in) :: tolerance
        integer, intent(in) :: dofs(:)
        type(adapt_curve_t), intent(in) :: curves(:)
        character(len=*), intent(in), optional :: labels(:)
        character(len=:), allocatable :: text, estimate_plot, value_plot, row, name, colour
        real(wp) :: lowest
        integer :: i, k, v

        text = preamble(png)//'$levels << EOD'//NL
        do i = 1, size(dofs)
            row = to_string(dofs(i))
            do k = 1, size(curves)
                associate (c => curves(k))
                    row = row//' '//real_to_text(c%value(i))//' '// &
                        real_to_text(abs(c%value(i))*c%bar(i))//' '// &
                        real_to_text(c%estimate(i))//' '//real_to_text(c%bar(i))
                end associate
            end do
            text = text//row//NL
        end do
        text = text//'EOD'//NL
        if (present(labels)) then
            ! at the first curve's value, where every level with a value has a point; a
            ! data file's strings are in double quotes (the labels are ours: no quote in them)
            text = text//'$labels << EOD'//NL
            do i = 1, size(dofs)
                text = text//to_string(dofs(i))//' '//real_to_text(curves(1)%value(i))//' "'// &
                    trim(labels(i))//'"'//NL
            end do
            text = text//'EOD'//NL
        end if

        ! the lower end of the error axis: a third below the smallest of the tolerance and
        ! the plotted errors, so that the tolerance line never sits on the frame
        lowest = tolerance
        do k = 1, size(curves)
            do i = 1, size(dofs)
                if (.not. ieee_is_nan(curves(k)%estimate(i))) &
                    lowest = min(lowest, curves(k)%estimate(i))
                if (.not. ieee_is_nan(curves(k)%bar(i))) lowest = min(lowest, curves(k)%bar(i))
            end do
        end do
        if (.not. lowest > 0.0_wp) lowest = tolerance

        estimate_plot = ''
        value_plot = ''
        do k = 1, size(curves)
            v = 2 + 4*(k - 1)   ! the curve's value column
            ! plain locals: gfortran 12 frees an associated character expression twice
            name = trim(curves(k)%name)
            colour = ''''//curves(k)%colour//''''
            estimate_plot = estimate_plot//'$levels using 1:'//to_string(v + 3)// &
                ' with linespoints pt 7 ps 0.6 lw 1.5 lc rgb '//colour//' title '// &
                gnuplot_string(name//': error bar')//', $levels using 1:'// &
                to_string(v + 2)//' with lines dt 2 lw 1 lc rgb '//colour//' title '// &
                gnuplot_string(name//': '//trim(curves(k)%estimate_name))//', '
            value_plot = value_plot//'$levels using 1:'//to_string(v)// &
                ' with linespoints pt 7 ps 0.6 lw 1.5 lc rgb '//colour//' title '// &
                gnuplot_string(name//PLUS_MINUS)//', $levels using 1:'//to_string(v)// &
                ':'//to_string(v + 1)//' with yerrorbars pt 7 ps 0.6 lw 1.5 lc rgb '// &
                colour//' notitle, '
        end do
        if (present(labels)) value_plot = value_plot// &
            '$labels using 1:2:3 with labels offset 0,1 textcolor rgb ''#404040'' notitle, '

        text = text//'set multiplot layout 2, 1 title '// &
            gnuplot_string('nceig adaptive refinement: '//title)//' font '',13'''//NL// &
            'set grid xtics ytics mxtics mytics lc rgb ''#dddddd'''//NL// &
            'set logscale x'//NL//'set xlabel ''free degrees of freedom'''//NL// &
            'set logscale y'//NL//'set format y ''10^{%L}'''//NL//'set key top right'//NL// &
            'set ylabel ''relative error  (dimensionless)'''//NL// &
            'set yrange ['//real_to_text(lowest/3.0_wp)//':*]'//NL// &
            'plot '//estimate_plot//real_to_text(tolerance)// &
            ' with lines dashtype 2 lw 1.5 lc rgb ''#c0392b'' title '// &
            gnuplot_string('tolerance '//real_to_text(tolerance))//NL// &
            'unset logscale y'//NL//'set yrange [*:*]'//NL//'set format y ''%.10g'''//NL// &
            'set ylabel '//gnuplot_string(goal)//NL// &
            'plot '//value_plot(:len(value_plot) - 2)//NL//'unset multiplot'//NL
    end function adapt_script

    !> lambda_sweep.png: critical c_n = mu and c_t = mu |lambda| against lambda (log y), a
    !> point's bar where the sweep was adapted (`bar` >= 0), the thresholds (`threshold`
    !> where `found`, plus then minus) as dashed vertical lines. `log_x`: a 'log' sweep, of
    !> one sign, drawn against |lambda| on a log axis with its one threshold. Data block
    !> $points: x, c_n, c_t, c_n bar, c_t bar (absolute).
    function sweep_script(png, title, lambda, mu, found, bar, log_x, threshold, &
                               threshold_found) result(text)
        character(len=*), intent(in) :: png, title
        real(wp), intent(in) :: lambda(:), mu(:), bar(:), threshold(2)
        logical, intent(in) :: found(:), log_x, threshold_found(2)
        character(len=:), allocatable :: text, style, cn_bar, ct_bar, bar_title, x_label
        real(wp) :: x, c_n, c_t, b
        logical :: bars
        integer :: i

        bars = any(bar >= 0.0_wp)
        text = preamble(png)//'$points << EOD'//NL
        do i = 1, size(lambda)
            x = lambda(i)
            if (log_x) x = abs(x)
            c_n = missing()
            c_t = missing()
            if (found(i)) then
                c_n = mu(i)
                c_t = critical_c_t(mu(i), lambda(i))
            end if
            b = relative_or_nan(bar(i))
            text = text//real_to_text(x)//' '//real_to_text(c_n)//' '//real_to_text(c_t)// &
                ' '//real_to_text(c_n*b)//' '//real_to_text(c_t*b)//NL
        end do
        text = text//'EOD'//NL

        style = 'linespoints'
        cn_bar = ''
        ct_bar = ''
        bar_title = ''
        if (bars) then
            style = 'yerrorlines'
            cn_bar = ':4'
            ct_bar = ':5'
            bar_title = PLUS_MINUS
        end if
        x_label = '{/Symbol l}  (dimensionless)'
        if (log_x) x_label = '|{/Symbol l}|  (dimensionless)'

        text = text//'set multiplot layout 2, 1 title '// &
            gnuplot_string('nceig lambda sweep: '//title)//' font '',13'''//NL// &
            'set grid xtics ytics mytics lc rgb ''#dddddd'''//NL//'set logscale y'//NL
        if (log_x) text = text//'set logscale x'//NL
        text = text//'set key top right'//NL//'set xlabel '//gnuplot_string(x_label)//NL
        if (.not. log_x) then
            text = text//mark(1, .true.)//mark(2, .false.)
        else if (minval(lambda) < 0.0_wp) then   ! one sign: its threshold
            text = text//mark(2, .true.)
        else
            text = text//mark(1, .true.)
        end if
        text = text// &
            'set ylabel ''critical c_n = lowest positive {/Symbol m}  [E / length]'''//NL// &
            'plot $points using 1:2'//cn_bar//' with '//style// &
            ' pt 7 ps 0.4 lw 1.5 lc rgb ''#1f77b4'' title '// &
            gnuplot_string('c_n'//bar_title)//NL// &
            'set ylabel ''critical c_t = {/Symbol m} |{/Symbol l}|  [E / length]'''//NL// &
            'plot $points using 1:3'//ct_bar//' with '//style// &
            ' pt 7 ps 0.4 lw 1.5 lc rgb ''#2ca02c'' title '// &
            gnuplot_string('c_t'//bar_title)//NL//'unset multiplot'//NL

    contains

        !> The dashed line of threshold `side` with its value, the label `right` of it or left.
        function mark(side, right) result(lines)
            integer, intent(in) :: side
            logical, intent(in) :: right
            character(len=:), allocatable :: lines, at, where
            character(len=*), parameter :: NAMES(2) = ['{/Symbol l}_+', '{/Symbol l}_-']
            lines = ''
            if (.not. threshold_found(side)) return
            at = real_to_text(threshold(side))
            if (log_x) at = real_to_text(abs(threshold(side)))
            where = ' left offset 0.6, 0'
            if (.not. right) where = ' right offset -0.6, 0'
            lines = 'set arrow from '//at//', graph 0 to '//at//', graph 1 nohead '// &
                'dashtype 2 linewidth 1.5 lc rgb ''#c0392b'' front'//NL// &
                'set label sprintf('''//NAMES(side)//' = %.6g'', '// &
                real_to_text(threshold(side))//') at '//at//', graph 0.93'//where// &
                ' textcolor rgb ''#c0392b'' front'//NL
        end function mark
    end function sweep_script

    !> The first lines of every picture: the terminal and the picture's path, quoted.
    pure function preamble(png) result(text)
        character(len=*), intent(in) :: png
        character(len=:), allocatable :: text
        text = TERMINAL//NL//'set output '//gnuplot_string(path_argument(png))//NL
    end function preamble

    !> Draw `file` (a .png in the staging folder, joined to the set when drawn) by running
    !> gnuplot on `script`, built for the path stage%scratch(file). `note`: where the
    !> picture is (`directory`/`file`), or why it is not drawn.
    subroutine draw_picture(stage, directory, file, script, note)
        type(output_stage_t), intent(inout) :: stage
        character(len=*), intent(in) :: directory, file
        character(len=*), intent(in) :: script   !! from adapt_script or sweep_script
        character(len=:), allocatable, intent(out) :: note
        character(len=:), allocatable :: png, script_path, path
        character(len=512) :: msg
        integer :: unit, ios
        logical :: drawn

        png = stage%scratch(file)
        note = not_drawable_note(png, 'the CSV holds the data')
        if (len(note) > 0) return
        script_path = stage%scratch('.'//file//'.gp')
        open (newunit=unit, file=script_path, status='replace', action='write', &
              access='stream', form='unformatted', iostat=ios, iomsg=msg)
        if (ios == 0) write (unit, iostat=ios, iomsg=msg) script
        if (ios == 0) close (unit, iostat=ios, iomsg=msg)
        if (ios /= 0) then
            call remove_file(script_path)
            note = 'not drawn: '//script_path//': '//trim(msg)
            return
        end if
        call run_gnuplot(script_path, png, drawn, note)
        if (.not. drawn) return
        call stage%add(file, path)   ! drawn there: part of the committed set
        note = directory//'/'//file
    end subroutine draw_picture
    !> adapt.png of the h loop of analysis 'eigen' (`element`, at `lambda`, from
    !> `start_dofs`), when &output plot is on.
    subroutine draw_eigen_adapt(stage, inputs, element, lambda, start_dofs, levels, note)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        integer, intent(in) :: element, start_dofs
        real(wp), intent(in) :: lambda
        type(eigen_level_t), intent(in) :: levels(:)
        character(len=:), allocatable, intent(out) :: note
        type(adapt_curve_t), allocatable :: curves(:)
        integer :: i
        call eigen_adapt_curves(levels, curves)
        call draw_adapt(stage, inputs, element_name(element)//', lambda = '// &
            real_to_text(lambda)//', start '//to_string(start_dofs)//' dofs', MU_GOAL, &
            [(levels(i)%n_dofs, i = 1, size(levels))], curves, note)
    end subroutine draw_eigen_adapt

    !> adapt.png of the threshold loop: both critical lambdas, and the collision onsets.
    subroutine draw_threshold_adapt(stage, inputs, element, start_dofs, levels, note, method)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        integer, intent(in) :: element, start_dofs
        type(threshold_level_t), intent(in) :: levels(:)
        character(len=:), allocatable, intent(out) :: note
        character(len=*), intent(in), optional :: method   !! the title's (default: element)
        type(adapt_curve_t), allocatable :: curves(:)
        character(len=:), allocatable :: by
        integer :: i
        by = element_name(element)
        if (present(method)) by = method
        call threshold_adapt_curves(levels, curves)
        call draw_adapt(stage, inputs, by//', the critical lambdas, start '// &
            to_string(start_dofs)//' dofs', 'critical {/Symbol l}  (dimensionless)', &
            [(levels(i)%n_dofs, i = 1, size(levels))], curves, note)
    end subroutine draw_threshold_adapt

    !> adapt.png of the hp loop: the bar and the change per level, each level labelled with
    !> its degrees.
    subroutine draw_hp_adapt(stage, inputs, lambda, start_dofs, levels, note)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        real(wp), intent(in) :: lambda
        integer, intent(in) :: start_dofs
        type(eigen_level_t), intent(in) :: levels(:)
        character(len=:), allocatable, intent(out) :: note
        type(adapt_curve_t), allocatable :: curves(:)
        integer :: i
        call hp_adapt_curves(levels, curves)
        call draw_adapt(stage, inputs, 'hp, lambda = '//real_to_text(lambda)//', start '// &
            to_string(start_dofs)//' dofs, each level labelled with its degrees', &
            MU_GOAL, [(levels(i)%n_dofs, i = 1, size(levels))], curves, note, &
            hp_degree_labels(levels))
    end subroutine draw_hp_adapt

    !> adapt.png when &output plot is on and some level has an error to draw.
    subroutine draw_adapt(stage, inputs, title, goal, dofs, curves, note, labels)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        character(len=*), intent(in) :: title, goal
        integer, intent(in) :: dofs(:)
        type(adapt_curve_t), intent(in) :: curves(:)
        character(len=:), allocatable, intent(out) :: note
        character(len=*), intent(in), optional :: labels(:)
        logical :: any_error
        integer :: k
        note = ''
        if (.not. inputs%output%plot) return
        any_error = .false.
        do k = 1, size(curves)
            any_error = any_error .or. .not. all(ieee_is_nan(curves(k)%estimate)) .or. &
                        .not. all(ieee_is_nan(curves(k)%bar))
        end do
        if (.not. any_error) then
            note = 'not drawn: no level has an error estimate'
            return
        end if
        call draw_picture(stage, trim(inputs%output%directory), ADAPT_PNG, &
            adapt_script(stage%scratch(ADAPT_PNG), title, goal, inputs%adapt%tolerance, dofs, &
                         curves, labels), note)
    end subroutine draw_adapt

    !> lambda_sweep.png of a sweep on `prob` (its starting mesh where the points were
    !> adapted), when &sweep plot and &output plot (every picture's switch) are on; `note`
    !> stays unallocated when either is off.
    subroutine draw_sweep(stage, inputs, prob, res, note)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(threshold_result_t), intent(in) :: res
        character(len=:), allocatable, intent(inout) :: note
        character(len=:), allocatable :: title
        character(len=2) :: element
        logical :: log_x
        if (.not. (inputs%sweep_plot .and. inputs%output%plot)) return
        if (.not. any(res%sweep%found)) then   ! gnuplot would fail on an empty curve
            note = 'not drawn: no lambda has a positive mu'
            return
        end if
        element = element_name(prob%mesh%element)
        title = element//' '//inputs%scene%source_name()
        if (inputs%scene%source == MESH_RECTANGLE) then
            title = title//' '//to_string(inputs%scene%nx)//'x'//to_string(inputs%scene%ny)
            if (element(1:1) == 'p') &   ! triangles only
                title = title//' '//trim(inputs%scene%diagonal)
        end if
        associate (curve => res%sweep)
            ! an adapted sweep solves each lambda on its own mesh: `prob` is where all started
            if (inputs%adapt%tolerance > 0.0_wp) then
                title = title//' start, each lambda adapted'
                if (any(curve%error_estimate >= 0.0_wp)) title = title//' (largest estimate '// &
                    short_real_text(maxval(curve%error_estimate), 1)//')'
            else
                title = title//', '//to_string(prob%contact%p())//' contact nodes'
            end if
            ! a list of lambdas is drawn as a linear sweep
            log_x = inputs%sweep_spacing == 'log'
            call draw_picture(stage, trim(inputs%output%directory), SWEEP_PNG, &
                sweep_script(stage%scratch(SWEEP_PNG), title, curve%lambda, curve%mu, &
                             curve%found, curve%error_bar, log_x, res%thresholds%lambda, &
                             res%thresholds%found), note)
        end associate
    end subroutine draw_sweep

    !> mode_001.png of an hp run: the first mode of `res` (input units) on the hp level `prob`
    !> with space `space`, its real part sampled on the linear sub-triangulation of hp_field,
    !> when &output plot is on.
    subroutine draw_hp_mode(stage, inputs, prob, space, res, note, stat)
        type(output_stage_t), intent(inout) :: stage
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(hp_space_t), intent(in) :: space
        type(eigen_result_t), intent(in) :: res
        character(len=:), allocatable, intent(out) :: note
        type(status_t), intent(out) :: stat
        type(mesh_t) :: sub
        real(wp), allocatable :: values(:, :), degree(:), mode(:)
        note = ''
        if (.not. inputs%output%plot .or. inputs%output%modes < 1 .or. &
            size(res%spec%vectors, 2) < 1) return
        mode = real(res%spec%vectors(:, 1), wp)
        call sample_hp_field(prob%mesh, space, prob%young, prob%poisson, mode, &
                             sub, values, degree, stat)
        if (.not. stat%ok()) return
        call draw_mode(stage, trim(inputs%output%directory), 'mode 1: mu = '// &
            real_to_text(real(res%spec%mu(1), wp))//', lambda = '// &
            real_to_text(res%lambda)//' (hp, sampled)', sub%coords, sub%cells, &
            element_corners(sub%element), values, note)
    end subroutine draw_hp_mode

    !> mode_001.png (io/mode_plot) of the nodal field `u` on the cells (`n_corners` each),
    !> joined to the set when drawn; `note`: where it is (in `directory`), or why not.
    subroutine draw_mode(stage, directory, title, coords, cells, n_corners, u, note)
        type(output_stage_t), intent(inout) :: stage
        character(len=*), intent(in) :: directory, title
        real(wp), intent(in) :: coords(:, :), u(:, :)
        integer, intent(in) :: cells(:, :), n_corners
        character(len=:), allocatable, intent(out) :: note
        character(len=:), allocatable :: path
        logical :: drawn
        call plot_mode(stage%scratch(MODE_PNG), stage%scratch('.'//MODE_PNG//'.gp'), title, &
                       coords, cells, n_corners, u, drawn, note)
        if (.not. drawn) return
        call stage%add(MODE_PNG, path)   ! drawn there: part of the committed set
        note = directory//'/'//MODE_PNG
    end subroutine draw_mode
end module pictures
