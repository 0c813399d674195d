! SPDX-License-Identifier: MIT
!> pictures: the gnuplot text of adapt.png and lambda_sweep.png, read back without running
!> gnuplot. The inline data are the results (a level's or point's values, its bar times its
!> value, the signs of the minus side, NaN where a result is missing), the hp change per
!> level is |mu_k - mu_(k-1)| / |mu_k|, the threshold lines stand at the thresholds, and the
!> picture's path is one quoted gnuplot string on the `set output` line, whatever it holds.
program test_pictures
    use kinds, only: wp, i8
    use ieee_arithmetic, only: ieee_is_nan
    use pictures, only: adapt_script, sweep_script, adapt_curve_t, eigen_adapt_curves, &
                        threshold_adapt_curves, hp_adapt_curves, hp_degree_labels
    use eigen_goal, only: eigen_level_t
    use threshold_goal, only: threshold_level_t
    use gnuplot, only: gnuplot_string
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t
    character(len=*), parameter :: NL = new_line('a')

    t%name = 'test_pictures'
    call check_eigen_adapt()
    call check_threshold_adapt()
    call check_threshold_without_collision()
    call check_hp_adapt()
    call check_linear_sweep()
    call check_log_sweep()
    call check_quoting()
    call t%report()

contains

    !> Three levels: an estimate without a bar, then both, then no positive mu.
    subroutine check_eigen_adapt()
        type(eigen_level_t) :: levels(3)
        type(adapt_curve_t), allocatable :: curves(:)
        real(wp), allocatable :: rows(:, :)
        character(len=:), allocatable :: text
        levels(:)%n_dofs = [40, 160, 640]
        levels(1:2)%has_mu = .true.
        levels(1:2)%mu = [2.5_wp, 2.25_wp]
        levels(1:2)%estimated = .true.
        levels(1:2)%error_estimate = [0.1_wp, 0.01_wp]
        levels(2)%error_bar = 0.02_wp
        call eigen_adapt_curves(levels, curves)
        text = adapt_script('out/adapt.png', 'p1, lambda = 5', 'mu', 1.0e-3_wp, &
                            [40, 160, 640], curves)
        call read_block(text, '$levels', rows)
        call t%check('eigen adapt: one row per level, dofs and 4 columns', &
                     size(rows, 1) == 3 .and. size(rows, 2) == 5)
        call t%check('eigen adapt: dofs and mu as the levels', &
                     all(same(rows(:, 1), [40.0_wp, 160.0_wp, 640.0_wp])) .and. &
                     all(same(rows(1:2, 2), [2.5_wp, 2.25_wp])) .and. ieee_is_nan(rows(3, 2)))
        call t%check('eigen adapt: absolute bar = mu times the bar, where there is a bar', &
                     ieee_is_nan(rows(1, 3)) .and. same(rows(2, 3), 2.25_wp*0.02_wp) .and. &
                     ieee_is_nan(rows(3, 3)))
        call t%check('eigen adapt: estimates and bars as the levels, NaN where none', &
                     all(same(rows(1:2, 4), [0.1_wp, 0.01_wp])) .and. &
                     ieee_is_nan(rows(3, 4)) .and. &
                     ieee_is_nan(rows(1, 5)) .and. same(rows(2, 5), 0.02_wp))
        call t%check('eigen adapt: log-log error axis, the tolerance line', &
                     has_line(text, 'set logscale x') .and. &
                     has_line(text, 'set logscale y') .and. &
                     index(text, "0.001 with lines dashtype 2") > 0)
    end subroutine check_eigen_adapt

    !> Two levels; the minus side's onset is a collision at the second level only.
    subroutine check_threshold_adapt()
        type(threshold_level_t) :: levels(2)
        type(adapt_curve_t), allocatable :: curves(:)
        real(wp), allocatable :: rows(:, :)
        integer :: i
        levels(:)%n_dofs = [100, 400]
        do i = 1, 2
            levels(i)%found = [.true., .true.]
            levels(i)%lambda = [1.5_wp + i, -2.0_wp - i]
            levels(i)%estimated = [.true., i == 2]
            levels(i)%error_estimate = [0.05_wp/i, 0.07_wp]
            levels(i)%error_bar = [0.06_wp/i, -1.0_wp]
        end do
        levels(2)%collision = [.false., .true.]
        levels(2)%collision_lambda(2) = -3.75_wp
        levels(2)%collision_estimate(2) = 0.004_wp
        levels(2)%collision_bar(2) = 0.005_wp
        call threshold_adapt_curves(levels, curves)
        call t%check('threshold adapt: lambda+, -lambda-, then the one side with a collision', &
                     size(curves) == 3 .and. curves(1)%name == 'lambda+' .and. &
                     curves(2)%name == '-lambda-' .and. curves(3)%name == '-collision-')
        call read_block(adapt_script('adapt.png', 'p1', 'lambda', 1.0e-2_wp, [100, 400], &
                                       curves), '$levels', rows)
        call t%check('threshold adapt: 1 + 4 x 3 columns', &
                     size(rows, 1) == 2 .and. size(rows, 2) == 13)
        call t%check('threshold adapt: lambda+ as is, lambda- negated (drawn as |lambda-|)', &
                     all(same(rows(:, 2), [2.5_wp, 3.5_wp])) .and. &
                     all(same(rows(:, 6), [3.0_wp, 4.0_wp])))
        call t%check('threshold adapt: bars and estimates per side', &
                     all(same(rows(:, 5), [0.06_wp, 0.03_wp])) .and. &
                     all(ieee_is_nan(rows(:, 9))) .and. &
                     ieee_is_nan(rows(1, 8)) .and. same(rows(2, 8), 0.07_wp) .and. &
                     same(rows(1, 3), 2.5_wp*0.06_wp))
        call t%check('threshold adapt: the collision onset negated, its estimate and bar', &
                     ieee_is_nan(rows(1, 10)) .and. same(rows(2, 10), 3.75_wp) .and. &
                     same(rows(2, 11), 3.75_wp*0.005_wp) .and. same(rows(2, 12), 0.004_wp) .and. &
                     same(rows(2, 13), 0.005_wp))
    end subroutine check_threshold_adapt

    subroutine check_threshold_without_collision()
        type(threshold_level_t) :: levels(1)
        type(adapt_curve_t), allocatable :: curves(:)
        levels(1)%found = [.true., .false.]
        levels(1)%lambda(1) = 2.0_wp
        call threshold_adapt_curves(levels, curves)
        call t%check('threshold adapt: no collision at any level, two curves', size(curves) == 2)
    end subroutine check_threshold_without_collision

    !> The change per level as the levels carry it (eigen_goal forms it: error_bar's
    !> hp_run_bar), none at level 1, and the degree labels.
    subroutine check_hp_adapt()
        type(eigen_level_t) :: levels(3)
        type(adapt_curve_t), allocatable :: curves(:)
        character(len=16) :: labels(3)
        real(wp), allocatable :: rows(:, :)
        character(len=:), allocatable :: text
        levels(:)%n_dofs = [50, 120, 300]
        levels(:)%has_mu = .true.
        levels(:)%mu = [4.0_wp, 3.0_wp, 2.5_wp]
        levels(2:3)%error_bar = [0.3_wp, 0.2_wp]
        levels(2:3)%change = [1.0_wp/3.0_wp, 0.5_wp/2.5_wp]
        levels(:)%p_min = [1, 1, 2]
        levels(:)%p_max = [1, 3, 2]
        call hp_adapt_curves(levels, curves)
        labels = hp_degree_labels(levels)
        call t%check('hp adapt: labels p 1, p 1-3, p 2', labels(1) == 'p 1' .and. &
                     labels(2) == 'p 1-3' .and. labels(3) == 'p 2')
        text = adapt_script('adapt.png', 'hp', 'mu', 1.0e-2_wp, [50, 120, 300], curves, labels)
        call read_block(text, '$levels', rows)
        call t%check('hp adapt: the change as the levels carry it, none at level 1', &
                     ieee_is_nan(rows(1, 4)) .and. same(rows(2, 4), 1.0_wp/3.0_wp) .and. &
                     same(rows(3, 4), 0.5_wp/2.5_wp))
        call t%check('hp adapt: bars as the levels', ieee_is_nan(rows(1, 5)) .and. &
                     all(same(rows(2:3, 5), [0.3_wp, 0.2_wp])))
        call t%check('hp adapt: a label per level at its dofs and mu', &
                     has_line(text, '120 3.0 "p 1-3"') .and. has_line(text, '300 2.5 "p 2"'))
    end subroutine check_hp_adapt

    !> Linear sweep: c_n = mu, c_t = mu |lambda|, NaN where no mu; both threshold lines.
    subroutine check_linear_sweep()
        real(wp), allocatable :: rows(:, :)
        character(len=:), allocatable :: text
        text = sweep_script('lambda_sweep.png', 'p1 rectangle', [-4.0_wp, 0.5_wp, 3.0_wp], &
                            [2.0_wp, 0.0_wp, 1.5_wp], [.true., .false., .true.], &
                            [-1.0_wp, -1.0_wp, -1.0_wp], .false., [2.5_wp, -3.5_wp], &
                            [.true., .true.])
        call read_block(text, '$points', rows)
        call t%check('linear sweep: lambda, c_n, c_t per point', size(rows, 1) == 3 .and. &
                     all(same(rows(:, 1), [-4.0_wp, 0.5_wp, 3.0_wp])) .and. &
                     same(rows(1, 2), 2.0_wp) .and. same(rows(3, 2), 1.5_wp) .and. &
                     same(rows(1, 3), 2.0_wp*4.0_wp) .and. same(rows(3, 3), 1.5_wp*3.0_wp))
        call t%check('linear sweep: no mu, no point', &
                     ieee_is_nan(rows(2, 2)) .and. ieee_is_nan(rows(2, 3)))
        call t%check('linear sweep: no bars, lines and points, log y only', &
                     index(text, 'yerrorlines') == 0 .and. all(ieee_is_nan(rows(:, 4:5))) .and. &
                     has_line(text, 'set logscale y') .and. .not. has_line(text, 'set logscale x'))
        call t%check('linear sweep: dashed lines at lambda+ and lambda-', &
                     index(text, 'set arrow from 2.5, graph 0 to 2.5, graph 1') > 0 .and. &
                     index(text, 'set arrow from -3.5, graph 0 to -3.5, graph 1') > 0)
    end subroutine check_linear_sweep

    !> Log sweep of negative lambdas: |lambda| on a log axis, the minus threshold only, bars.
    subroutine check_log_sweep()
        real(wp), allocatable :: rows(:, :)
        character(len=:), allocatable :: text
        text = sweep_script('lambda_sweep.png', 'p1', [-10.0_wp, -1.0_wp], [3.0_wp, 1.0_wp], &
                            [.true., .true.], [0.25_wp, -1.0_wp], .true., [2.5_wp, -3.5_wp], &
                            [.true., .true.])
        call read_block(text, '$points', rows)
        call t%check('log sweep: x = |lambda|, c_t = mu |lambda|', &
                     all(same(rows(:, 1), [10.0_wp, 1.0_wp])) .and. &
                     all(same(rows(:, 3), [30.0_wp, 1.0_wp])))
        call t%check('log sweep: the absolute bars c_n bar, c_t bar where adapted', &
                     same(rows(1, 4), 0.75_wp) .and. same(rows(1, 5), 7.5_wp) .and. &
                     ieee_is_nan(rows(2, 4)) .and. index(text, 'using 1:2:4 with yerrorlines') > 0)
        call t%check('log sweep: log x, the line at |lambda-| only', &
                     has_line(text, 'set logscale x') .and. &
                     index(text, 'set arrow from 3.5, graph 0') > 0 .and. &
                     index(text, 'set arrow from 2.5,') == 0)
    end subroutine check_log_sweep

    !> Quotes, gnuplot's system() and a leading '-' in the picture's path, and a quote in a
    !> title: each stays inside one string.
    subroutine check_quoting()
        character(len=*), parameter :: EVIL = "out/Bob's x'; system('touch INJECTED') #/adapt.png"
        character(len=:), allocatable :: text
        type(eigen_level_t) :: levels(1)
        type(adapt_curve_t), allocatable :: curves(:)
        levels(1)%estimated = .true.
        levels(1)%error_estimate = 0.5_wp
        call eigen_adapt_curves(levels, curves)
        text = adapt_script(EVIL, "it's", 'mu', 0.1_wp, [10], curves)
        call t%check('quoting: set output holds the path as one quoted string', &
                     has_line(text, 'set output '//gnuplot_string(EVIL)) .and. &
                     one_string("'Bob''s x''; system(''touch INJECTED'') #/adapt.png'"))
        call t%check('quoting: the path is nowhere else', count_of(text, "system(''touch") == 1 &
                     .and. index(text, "system('touch") == 0)
        call t%check("quoting: a title's quote is doubled", &
                     index(text, "'nceig adaptive refinement: it''s'") > 0)
        text = sweep_script('-dash/lambda_sweep.png', 't', [1.0_wp], [1.0_wp], [.true.], &
                            [-1.0_wp], .false., [0.0_wp, 0.0_wp], [.false., .false.])
        call t%check("quoting: a relative path starting with '-' gets './'", &
                     has_line(text, "set output './-dash/lambda_sweep.png'"))
    end subroutine check_quoting

    !> Whether `quoted` is one gnuplot single-quoted string: it closes at its last character.
    logical function one_string(quoted)
        character(len=*), intent(in) :: quoted
        integer :: i
        one_string = .false.
        if (len(quoted) < 2 .or. quoted(1:1) /= "'") return
        i = 2
        do while (i <= len(quoted))
            if (quoted(i:i) == "'") then
                if (i == len(quoted)) then
                    one_string = .true.
                    return
                end if
                if (quoted(i + 1:i + 1) /= "'") return   ! closed before the end
                i = i + 1
            end if
            i = i + 1
        end do
    end function one_string

    !> The numbers of the data block `name` (`name << EOD` ... `EOD`), one row per line.
    subroutine read_block(text, name, rows)
        character(len=*), intent(in) :: text, name
        real(wp), allocatable, intent(out) :: rows(:, :)
        character(len=:), allocatable :: body, line
        integer :: first, last, n_rows, n_cols, i, start, stop_at, ios

        first = index(text, name//' << EOD'//NL) + len(name//' << EOD'//NL)
        last = first - 1 + index(text(first:), NL//'EOD'//NL)
        body = text(first:last)   ! each row ends in a line feed
        n_rows = count_of(body, NL)
        n_cols = 0
        if (n_rows > 0) n_cols = words(body(:index(body, NL) - 1))
        allocate (rows(n_rows, n_cols))
        start = 1
        do i = 1, n_rows
            stop_at = start - 1 + index(body(start:), NL)
            line = body(start:stop_at - 1)
            read (line, *, iostat=ios) rows(i, :)
            if (ios /= 0) error stop 'test_pictures: a data row did not read back'
            start = stop_at + 1
        end do
    end subroutine read_block

    !> Exact equality, stated as such: the text holds each real to its last bit.
    elemental logical function same(a, b)
        real(wp), intent(in) :: a, b
        same = transfer(a, 0_i8) == transfer(b, 0_i8)
    end function same

    pure integer function words(line)
        character(len=*), intent(in) :: line
        integer :: i
        words = 0
        do i = 1, len(line)
            if (line(i:i) /= ' ' .and. (i == 1 .or. line(max(i - 1, 1):max(i - 1, 1)) == ' ')) &
                words = words + 1
        end do
    end function words

    pure integer function count_of(text, part)
        character(len=*), intent(in) :: text, part
        integer :: at, k
        count_of = 0
        at = 1
        do
            k = index(text(at:), part)
            if (k == 0) exit
            count_of = count_of + 1
            at = at + k + len(part) - 1
        end do
    end function count_of

    logical function has_line(text, line)
        character(len=*), intent(in) :: text, line
        has_line = index(NL//text, NL//line//NL) > 0
    end function has_line
end program test_pictures
