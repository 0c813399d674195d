! SPDX-License-Identifier: MIT
!> Error status that library routines fill and return to their caller. Only the main
!> program turns a failed status into a message on standard error and an exit code.
module status
    implicit none
    private
    public :: status_t
    public :: STATUS_SUCCESS, STATUS_BAD_INPUT, STATUS_MESH, STATUS_IO, STATUS_SOLVER, &
              STATUS_SINGULAR, STATUS_INTERNAL, STATUS_NOT_MET, STATUS_NO_DIGIT

    integer, parameter :: STATUS_SUCCESS = 0
    integer, parameter :: STATUS_BAD_INPUT = 2   !! input file or command line is wrong
    integer, parameter :: STATUS_MESH = 3        !! mesh file unreadable or mesh invalid
    integer, parameter :: STATUS_IO = 4          !! an output could not be written
    integer, parameter :: STATUS_SOLVER = 5      !! a numerical library reported failure
    integer, parameter :: STATUS_SINGULAR = 6    !! K is singular (e.g. no Dirichlet boundary)
    integer, parameter :: STATUS_INTERNAL = 7    !! a broken invariant: a bug, not bad input
    !> An adaptive run ended without meeting &adapt tolerance (a limit reached, or no error
    !> estimate): its set, of the last level, is written, but no script may take it for
    !> a success.
    integer, parameter :: STATUS_NOT_MET = 8
    !> The round-off bound of the lowest positive mu is 1 or more: not one digit of it, not
    !> even its sign, is certain. Its set is written, but no script may take the value.
    integer, parameter :: STATUS_NO_DIGIT = 9

    type :: status_t
        integer :: code = STATUS_SUCCESS
        character(len=:), allocatable :: message
    contains
        procedure :: ok => status_ok
        procedure :: fail => status_fail
    end type status_t

contains

    !> True unless a failure was recorded.
    elemental logical function status_ok(this)
        class(status_t), intent(in) :: this
        status_ok = this%code == STATUS_SUCCESS
    end function status_ok

    !> Record a failure: code and a one-line message naming place, problem and value.
    subroutine status_fail(this, code, message)
        class(status_t), intent(inout) :: this
        integer, intent(in) :: code
        character(len=*), intent(in) :: message
        this%code = code
        this%message = message
    end subroutine status_fail
end module status
