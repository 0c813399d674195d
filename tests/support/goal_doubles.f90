! SPDX-License-Identifier: MIT
!> A goal of the adaptive loop for the tests of the refiners (a program cannot bind
!> procedures to its types): it solves nothing and marks every cell of the last level.
module goal_doubles
    use kinds, only: wp
    use status, only: status_t
    use timer, only: timings_t
    use scene, only: scene_t
    use problem, only: problem_t
    use adapt_driver, only: adapt_goal_t, adapt_level_t, refiner_t, built_check_t
    implicit none
    private
    public :: every_cell_t

    !> A goal that marks every cell of the last level (the refiner asks it).
    type, extends(adapt_goal_t) :: every_cell_t
        integer :: n_cells = 0
    contains
        procedure :: solve => every_solve
        procedure :: judge => every_judge
        procedure :: bar_text => every_bar_text
        procedure :: mark => every_mark
        procedure :: check => every_check
    end type every_cell_t

contains


    subroutine every_solve(this, scn, refiner, level, loop_start, timings, refused, stat)
        class(every_cell_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: level
        real(wp), intent(in) :: loop_start
        type(timings_t), intent(inout) :: timings
        character(len=:), allocatable, intent(out) :: refused
        type(status_t), intent(out) :: stat
        refused = ''
        this%n_cells = level%prob%mesh%n_cells()
    end subroutine every_solve

    subroutine every_judge(this, refiner, level, tolerance)
        class(every_cell_t), intent(inout) :: this
        class(refiner_t), intent(in) :: refiner
        integer, intent(in) :: level
        real(wp), intent(in) :: tolerance
    end subroutine every_judge

    function every_bar_text(this, i) result(text)
        class(every_cell_t), intent(in) :: this
        integer, intent(in) :: i
        character(len=:), allocatable :: text
        text = 'none'
    end function every_bar_text

    !> Nothing to check (it solves nothing).
    subroutine every_check(this, scn, start, refiner, last, tolerance, reopen, timings, stat, &
                           built)
        class(every_cell_t), intent(inout) :: this
        type(scene_t), intent(in) :: scn
        type(problem_t), intent(in) :: start
        class(refiner_t), intent(in) :: refiner
        type(adapt_level_t), intent(in) :: last
        real(wp), intent(in) :: tolerance
        logical, intent(in) :: reopen
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(built_check_t), intent(inout), target, optional :: built
    end subroutine every_check

    function every_mark(this, theta) result(marked)
        class(every_cell_t), intent(in) :: this
        real(wp), intent(in) :: theta
        integer, allocatable :: marked(:)
        integer :: c
        marked = [(c, c = 1, this%n_cells)]
    end function every_mark
end module goal_doubles
