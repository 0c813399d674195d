! SPDX-License-Identifier: MIT
!> A small assertion module: each check names what it asserts; a test program calls
!> `report` at the end, which stops with a non-zero code if any check failed.
module testing
    use kinds, only: wp
    use iso_fortran_env, only: output_unit
    implicit none
    private
    public :: test_suite_t

    type :: test_suite_t
        character(len=:), allocatable :: name
        integer :: n_passed = 0
        integer :: n_failed = 0
    contains
        procedure :: check => test_suite_check
        procedure :: check_close => test_suite_check_close
        procedure :: report => test_suite_report
    end type test_suite_t

contains

    !> Record one named assertion.
    subroutine test_suite_check(this, what, condition)
        class(test_suite_t), intent(inout) :: this
        character(len=*), intent(in) :: what
        logical, intent(in) :: condition
        if (condition) then
            this%n_passed = this%n_passed + 1
            write (output_unit, '(a)') 'PASS  '//what
        else
            this%n_failed = this%n_failed + 1
            write (output_unit, '(a)') 'FAIL  '//what
        end if
    end subroutine test_suite_check

    !> Assert |actual - expected| <= rel_tol |expected| + abs_tol, printing both on failure.
    subroutine test_suite_check_close(this, what, actual, expected, rel_tol, abs_tol)
        class(test_suite_t), intent(inout) :: this
        character(len=*), intent(in) :: what
        real(wp), intent(in) :: actual, expected, rel_tol
        real(wp), intent(in), optional :: abs_tol
        real(wp) :: bound
        bound = rel_tol*abs(expected)
        if (present(abs_tol)) bound = bound + abs_tol
        call this%check(what, abs(actual - expected) <= bound)
        if (.not. abs(actual - expected) <= bound) then
            write (output_unit, '(a, es24.16, a, es24.16, a, es10.3)') '      actual ', actual, &
                ' expected ', expected, ' rel err ', abs(actual - expected)/max(abs(expected), &
                tiny(1.0_wp))
        end if
    end subroutine test_suite_check_close

    !> Print the closing count line and stop with status 1 when anything failed.
    subroutine test_suite_report(this)
        class(test_suite_t), intent(in) :: this
        write (output_unit, '(a, i0, a, i0, a)') this%name//': ', this%n_passed, ' passed, ', &
            this%n_failed, ' failed'
        if (this%n_failed > 0) error stop 1
    end subroutine test_suite_report
end module testing
