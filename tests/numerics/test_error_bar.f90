! SPDX-License-Identifier: MIT
!> error_bar: the bar is BAR_FACTOR times the estimate plus the round-off part, and along
!> adaptive levels level_bar_factor(degree) times the envelope of the window's estimates
!> (the last BAR_WINDOW levels and those before with at least 1 / WINDOW_GROWTH of the
!> dofs) carried at the optimal rate, so that a single dip of the estimate cannot make the
!> bar small, and at least the change of the value over those levels.
program test_error_bar
    use kinds, only: wp
    use error_bar, only: single_bar, level_bar, hp_level_bar, hp_run_bar, three_mesh_bar, &
                         level_bar_factor, BAR_FACTOR, LEVEL_FACTOR, BAR_WINDOW, HP_FASTEST, &
                         checked_bar, CHECK_FACTOR, settled_floor
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t

    t%name = 'test_error_bar'
    call check_single()
    call check_dip_bridged()
    call check_moving_value()
    call check_window_forgets()
    call check_window_spans_dofs()
    call check_missing()
    call check_hp_geometric()
    call check_hp_dip()
    call check_hp_stagnation()
    call check_hp_start()
    call check_hp_run()
    call check_hp_stall()
    call check_three_mesh_orders()
    call check_three_mesh_limits()
    call check_checked_bar()
    call check_settled_floor()
    call t%report()

contains

    !> The floor of a settled value, on the slanted scene's lambda+ at levels 9 to 11 (1e-8):
    !> changes 4.4e-9 and 2.1e-8 within round-off bounds 4.9e-8 and 1.5e-7, which alone
    !> exceed the tolerance. Not settled: one change above its level's bound (levels 8 to
    !> 10: 7.3e-8 > 1.7e-8), a round-off part below the tolerance (more levels may still
    !> meet it), or a bound unknown (negative).
    subroutine check_settled_floor()
        real(wp), parameter :: V(4) = [4.352952465738_wp, 4.352952782296_wp, &
                                       4.352952763034_wp, 4.352952671534_wp]
        real(wp), parameter :: R(4) = [5.02e-9_wp, 1.69e-8_wp, 4.94e-8_wp, 1.48e-7_wp]
        call t%check('settled: changes within round-off above the tolerance', &
                     settled_floor(V(2:4), R(2:4), R(4), 1.0e-8_wp))
        call t%check('settled: not with a change above its bound', &
                     .not. settled_floor(V(1:3), R(1:3), R(3), 1.0e-8_wp))
        call t%check('settled: not while the round-off part is below the tolerance', &
                     .not. settled_floor(V(2:4), R(2:4), R(4), 1.0e-6_wp))
        call t%check('settled: not with a bound unknown', &
                     .not. settled_floor(V(2:4), [R(2), -1.0_wp, R(4)], R(4), 1.0e-8_wp))
    end subroutine check_settled_floor

    !> The check one degree higher: a level whose changes vanish (series bar 1e-12) while it
    !> is 2e-3 from the check gets CHECK_FACTOR times that plus both round-off parts; a
    !> check that agrees leaves the series bar; no series bar or no check value: none. And
    !> the factor's claim: a level error e with the check's error q e, q <= 2/3 of either
    !> sign, is covered (|e| <= CHECK_FACTOR |d|, d = e - q e).
    subroutine check_checked_bar()
        real(wp), parameter :: RATIOS(5) = [-0.66_wp, -0.5_wp, 0.0_wp, 0.5_wp, 0.66_wp]
        real(wp) :: q, e
        integer :: i
        call t%check_close('checked: the difference decides', checked_bar(1.0e-12_wp, 1.0_wp, &
                           .true., 1.002_wp, 1.0e-13_wp, 2.0e-13_wp), &
                           CHECK_FACTOR*2.0e-3_wp + 3.0e-13_wp, 1.0e-15_wp)
        call t%check_close('checked: an agreeing check leaves the series bar', &
                           checked_bar(1.0e-6_wp, 2.0_wp, .true., 2.0_wp + 2.0e-9_wp, -1.0_wp, &
                                       -1.0_wp), 1.0e-6_wp, 1.0e-20_wp)
        call t%check('checked: no series bar, none', checked_bar(-1.0_wp, 1.0_wp, .true., &
                     1.5_wp, 0.0_wp, 0.0_wp) < 0.0_wp)
        call t%check('checked: no check value, none', checked_bar(1.0e-6_wp, 1.0_wp, .false., &
                     0.0_wp, 0.0_wp, 0.0_wp) < 0.0_wp)
        do i = 1, size(RATIOS)
            q = RATIOS(i)
            e = 1.0e-3_wp
            call t%check('checked: covers a check error q e, |q| <= 2/3', &
                         checked_bar(0.0_wp, 1.0_wp + e, .true., 1.0_wp + q*e, -1.0_wp, &
                                     -1.0_wp) >= e/(1.0_wp + e))
        end do
    end subroutine check_checked_bar

    subroutine check_single()
        call t%check_close('one mesh: BAR_FACTOR times the estimate', &
                           single_bar(1.0e-3_wp, -1.0_wp), BAR_FACTOR*1.0e-3_wp, 1.0e-15_wp)
        call t%check_close('one mesh: the round-off part added', &
                           single_bar(1.0e-3_wp, 2.0e-4_wp), BAR_FACTOR*1.0e-3_wp + 2.0e-4_wp, &
                           1.0e-15_wp)
        call t%check('one mesh: no estimate, no bar', single_bar(-1.0_wp, 1.0e-4_wp) < 0.0_wp)
    end subroutine check_single

    !> Estimates 1e-6, 1e-6, then a dip to 1e-9 at 1.1 times the dofs (values that agree):
    !> the bar keeps the previous level's 1e-6 carried by (1/1.1)^3 for degree 3.
    subroutine check_dip_bridged()
        real(wp) :: bar
        bar = level_bar([1.0e-6_wp, 1.0e-6_wp, 1.0e-9_wp], [1.0_wp, 1.0_wp, 1.0_wp], &
                        [1000, 1000, 1100], 3, -1.0_wp)
        call t%check_close('a dip: the previous level carried at the rate', bar, &
                           level_bar_factor(3)*1.0e-6_wp/1.1_wp**3, 1.0e-14_wp)
    end subroutine check_dip_bridged

    !> Small estimates but a value that moved by 40 % over the window (a mode that moves with
    !> the mesh): the bar is at least that change.
    subroutine check_moving_value()
        real(wp) :: bar
        bar = level_bar([0.03_wp, 0.03_wp, 0.03_wp], [100.0_wp, 150.0_wp, 250.0_wp], &
                        [1000, 2000, 4000], 2, -1.0_wp)
        call t%check_close('a value still moving: the bar is its change', bar, &
                           150.0_wp/250.0_wp, 1.0e-14_wp)
    end subroutine check_moving_value

    !> A level older than BAR_WINDOW levels, with fewer than 1 / WINDOW_GROWTH of the last
    !> level's dofs, no longer counts: dofs doubling per level, the last estimate 1e-9 is
    !> the largest of the window once carried.
    subroutine check_window_forgets()
        real(wp) :: estimates(BAR_WINDOW + 1), bar
        integer :: dofs(BAR_WINDOW + 1), i
        estimates = 1.0e-9_wp
        estimates(1) = 1.0_wp
        dofs = [(100*2**i, i=0, BAR_WINDOW)]
        bar = level_bar(estimates, [(1.0_wp, i=1, BAR_WINDOW + 1)], dofs, 2, -1.0_wp)
        call t%check_close('a level older than the window is forgotten', bar, &
                           level_bar_factor(2)*1.0e-9_wp, 1.0e-14_wp)
    end subroutine check_window_forgets

    !> Levels that add 1 % of the dofs each (a small &adapt theta): the window reaches back
    !> over a growth of WINDOW_GROWTH, not only BAR_WINDOW levels, so the first level's
    !> estimate 1, ten levels back at 1000 / 1100 of the dofs, carried by (1/1.1)^2 for
    !> degree 2, is the bar; with 1000 / 1500 of the dofs it is out of the window.
    subroutine check_window_spans_dofs()
        real(wp) :: estimates(11)
        integer :: dofs(11), i
        estimates = 1.0e-9_wp
        estimates(1) = 1.0_wp
        dofs = [(1000 + 10*i, i=0, 10)]
        call t%check_close('a window over a growth of the dofs', &
                           level_bar(estimates, [(1.0_wp, i=1, 11)], dofs, 2, -1.0_wp), &
                           level_bar_factor(2)*(1000.0_wp/1100.0_wp)**2, 1.0e-13_wp)
        dofs = [(1000 + 50*i, i=0, 10)]
        call t%check_close('a level beyond that growth is forgotten', &
                           level_bar(estimates, [(1.0_wp, i=1, 11)], dofs, 2, -1.0_wp), &
                           level_bar_factor(2)*1.0e-9_wp, 1.0e-13_wp)
    end subroutine check_window_spans_dofs

    subroutine check_missing()
        call t%check('no estimate at the last level: no bar', &
                     level_bar([1.0e-3_wp, -1.0_wp], [1.0_wp, 1.0_wp], [10, 20], 1, -1.0_wp) &
                     < 0.0_wp)
        call t%check_close('a level without an estimate is skipped', &
                           level_bar([-1.0_wp, 1.0e-3_wp], [2.0_wp, 1.0_wp], [10, 20], 1, &
                                     -1.0_wp), level_bar_factor(1)*1.0e-3_wp, 1.0e-15_wp)
    end subroutine check_missing

    !> hp levels converging tenfold per level, v_j = 1 + 10^-j: at the fourth level the
    !> bar is LEVEL_FACTOR r d_4 = 3 0.1 9 10^-4, 2.7 times the true error 10^-4 of the
    !> last value; at the third (one ratio seen) still the last change d_3 = 9 10^-3, 9
    !> times its error; the round-off part is added.
    subroutine check_hp_geometric()
        real(wp) :: values(4)
        integer :: j
        values = [(1.0_wp + 10.0_wp**(-j), j=1, 4)]
        call t%check_close('hp: tenfold convergence, LEVEL_FACTOR r d_k', &
                           hp_level_bar(values, -1.0_wp), LEVEL_FACTOR*0.1_wp*9.0e-4_wp/values(4), &
                           1.0e-12_wp)
        call t%check('hp: at least the true error 1e-4 of the last value', &
                     hp_level_bar(values, -1.0_wp) >= 1.0e-4_wp/values(4))
        call t%check_close('hp: the round-off part added', hp_level_bar(values, 1.0e-5_wp), &
                           LEVEL_FACTOR*0.1_wp*9.0e-4_wp/values(4) + 1.0e-5_wp, 1.0e-12_wp)
        call t%check_close('hp: at the third level still the last change', &
                           hp_level_bar(values(1:3), -1.0_wp), 9.0e-3_wp/values(3), 1.0e-12_wp)
    end subroutine check_hp_geometric

    !> The last change dips to 1e-9 by cancellation after changes falling tenfold: the
    !> previous change 9e-3 carried twice at the rate 0.1 (LEVEL_FACTOR times) is the bar.
    subroutine check_hp_dip()
        real(wp) :: values(4)
        values = [1.1_wp, 1.01_wp, 1.001_wp, 1.001_wp + 1.0e-9_wp]
        call t%check_close('hp: a dip is bridged at the observed rate', &
                           hp_level_bar(values, -1.0_wp), &
                           LEVEL_FACTOR*(0.009_wp/values(4))*(0.009_wp/0.09_wp)**2, 1.0e-9_wp)
    end subroutine check_hp_dip

    !> Third level after a stagnation: 1 + 3.7e-3, then 1 + 1.0e-4 twice (the error 1e-4
    !> unchanged, d_3 = 1e-8 of d_2 = 3.6e-3): the one ratio would give a bar of 1e-8; the
    !> bar is HP_FASTEST d_2 = 1.8e-4, above the error; on a tenfold sequence it stays d_3.
    subroutine check_hp_stagnation()
        real(wp) :: values(3)
        integer :: j
        values = [1.0037_wp, 1.0001_wp, 1.0001_wp + 1.0e-12_wp]
        call t%check_close('hp: a third level after a stagnation, HP_FASTEST d_2', &
                           hp_level_bar(values, -1.0_wp), &
                           HP_FASTEST*(values(1) - values(2))/values(3), 1.0e-6_wp)
        call t%check('hp: that bar above the true error 1e-4', &
                     hp_level_bar(values, -1.0_wp) >= 1.0e-4_wp)
        values = [(1.0_wp + 10.0_wp**(-j), j=1, 3)]
        call t%check_close('hp: a tenfold third level keeps d_3', hp_level_bar(values, -1.0_wp), &
                           9.0e-3_wp/values(3), 1.0e-12_wp)
    end subroutine check_hp_stagnation

    !> One level: no bar; two: no rate yet (1), so LEVEL_FACTOR times the change.
    subroutine check_hp_start()
        call t%check('hp: no bar at the first level', hp_level_bar([2.0_wp], 0.0_wp) < 0.0_wp)
        call t%check_close('hp: two levels, LEVEL_FACTOR times the change', &
                           hp_level_bar([2.0_wp, 1.0_wp], -1.0_wp), LEVEL_FACTOR, 1.0e-15_wp)
    end subroutine check_hp_start

    !> The trailing run: levels 3 and 4 of (have, not, have, have) give hp_level_bar of those
    !> two values (exactly: the same call on the same values) and the change |2.5 - 3| / 2.5;
    !> a run of one level, or a last level without the value, gives neither.
    subroutine check_hp_run()
        real(wp), parameter :: VALUES(4) = [4.0_wp, 9.0_wp, 3.0_wp, 2.5_wp]
        real(wp) :: bar, change
        logical :: stalled
        call hp_run_bar([.true., .false., .true., .true.], VALUES, -1.0_wp, bar, change, stalled)
        call t%check('hp run: the bar of the last two levels, the change 0.5 / 2.5', &
                     abs(bar - hp_level_bar(VALUES(3:4), -1.0_wp)) <= 0.0_wp .and. &
                     abs(change - 0.2_wp) <= 1.0e-15_wp)
        call hp_run_bar([.true., .true., .false., .true.], VALUES, -1.0_wp, bar, change, stalled)
        call t%check('hp run: one level long, none', bar < 0.0_wp .and. change < 0.0_wp)
        call hp_run_bar([.true., .true., .true., .false.], VALUES, -1.0_wp, bar, change, stalled)
        call t%check('hp run: the last level without, none', bar < 0.0_wp .and. change < 0.0_wp)
    end subroutine check_hp_run

    !> Stalled where the changes fall by less than HP_STALL = 0.1 in four levels: a geometric
    !> rate r per level gives r^4, so r = 0.5 (0.0625) converges and r = 0.6 (0.1296) has
    !> stalled; an algebraic 1 + 1/k (changes 1/(k (k - 1)): max(d8, d7) / max(d4, d3) =
    !> (1/42) / (1/6) = 0.14, where seven levels give (1/30) / (1/2) = 0.067) and a value that
    !> grows by one per level (a mode that moves with the mesh) have stalled; a value
    !> converged at level 4 whose later changes are round-off (1e-13: below ten times its
    !> round-off part 1e-13) has not, but stalls when the round-off part is 1e-17 (then
    !> 100 eps = 2.2e-14 is the noise level). A stalled run has no bar.
    subroutine check_hp_stall()
        integer, parameter :: N = 12
        logical, parameter :: ALL(N) = .true.
        real(wp) :: v(N), bar, change
        logical :: stalled
        integer :: k
        v = [(1.0_wp + 0.5_wp**k, k=1, N)]
        call hp_run_bar(ALL, v, -1.0_wp, bar, change, stalled)
        call t%check('hp stall: rate 0.5 per level converges, with a bar', &
                     .not. stalled .and. bar > 0.0_wp)
        v = [(1.0_wp + 0.6_wp**k, k=1, N)]
        call hp_run_bar(ALL, v, -1.0_wp, bar, change, stalled)
        call t%check('hp stall: rate 0.6 per level has stalled, no bar', stalled .and. bar < 0.0_wp)
        v = [(1.0_wp + 1.0_wp/real(k, wp), k=1, N)]
        call hp_run_bar(ALL(:8), v(:8), -1.0_wp, bar, change, stalled)
        call t%check('hp stall: 1 + 1/k has stalled at the eighth level', stalled)
        call hp_run_bar(ALL(:7), v(:7), -1.0_wp, bar, change, stalled)
        call t%check('hp stall: 1 + 1/k not yet at the seventh', .not. stalled .and. bar > 0.0_wp)
        v = [(real(k, wp), k=1, N)]
        call hp_run_bar(ALL, v, -1.0_wp, bar, change, stalled)
        call t%check('hp stall: a value growing with every level has stalled', stalled)
        v(1:4) = [(1.0_wp + 0.1_wp**k, k=1, 4)]
        v(5:N) = [(1.0_wp + 5.0e-14_wp*(-1.0_wp)**k, k=5, N)]
        call hp_run_bar(ALL, v, 1.0e-13_wp, bar, change, stalled)
        call t%check('hp stall: round-off changes at the floor are no stall', .not. stalled)
        call hp_run_bar(ALL, v, 1.0e-17_wp, bar, change, stalled)
        call t%check('hp stall: the same changes above ten times the round-off part stall', &
                     stalled)
    end subroutine check_hp_stall
    !> v(h) = 1 + c h^r on h = 1, 1/2, 1/4: for every order r between 0.1 and 2 the
    !> three-mesh error d1 / (1 - q) is c exactly, so the bar is LEVEL_FACTOR c / v0; the
    !> slow order 0.2 (a change a seventh of the error) included.
    subroutine check_three_mesh_orders()
        real(wp), parameter :: C = 1.0e-4_wp, ORDERS(4) = [0.2_wp, 0.5_wp, 1.0_wp, 2.0_wp]
        real(wp) :: v(3), bar
        integer :: i
        logical :: exact
        exact = .true.
        do i = 1, size(ORDERS)
            v = 1.0_wp + C*[1.0_wp, 0.5_wp**ORDERS(i), 0.25_wp**ORDERS(i)]
            bar = three_mesh_bar(v(1), v(2), v(3), -1.0_wp)
            exact = exact .and. abs(bar - LEVEL_FACTOR*C/v(1)) <= 1.0e-9_wp*bar
        end do
        call t%check('three meshes: the error of orders 0.2 to 2 found, times LEVEL_FACTOR', exact)
    end subroutine check_three_mesh_orders

    !> Order 4 is counted as 2 (the bar stays above the error: 3.75 c), a change that grows
    !> (no convergence) as order 0.1 (the error taken 15 times the larger change), an unknown
    !> third mesh as order 0.4 (q = 0.75: 4 times), and the round-off part is added.
    subroutine check_three_mesh_limits()
        real(wp), parameter :: C = 1.0e-4_wp
        real(wp) :: bar
        bar = three_mesh_bar(1.0_wp + C, 1.0_wp + C/16.0_wp, 1.0_wp + C/256.0_wp, -1.0_wp)
        call t%check_close('three meshes, order 4: counted as order 2', bar*(1.0_wp + C), &
                           LEVEL_FACTOR*C*(15.0_wp/16.0_wp)/0.75_wp, 1.0e-9_wp)
        bar = three_mesh_bar(1.0_wp, 1.0_wp + C, 1.0_wp - C, -1.0_wp)
        call t%check_close('three meshes, a growing change: the slowest order', bar, &
                           LEVEL_FACTOR*2.0_wp*C/(1.0_wp - 0.933_wp), 1.0e-9_wp)
        bar = three_mesh_bar(1.0_wp, 1.0_wp + C, huge(1.0_wp), 1.0e-6_wp)
        call t%check_close('three meshes, no third: 12 times the change, round-off added', bar, &
                           12.0_wp*C + 1.0e-6_wp, 1.0e-9_wp)
    end subroutine check_three_mesh_limits
end program test_error_bar
