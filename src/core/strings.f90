! SPDX-License-Identifier: MIT
!> Number-to-text conversions for messages and file names.
module strings
    use kinds, only: wp, i8
    implicit none
    private
    public :: to_string, zero_padded

    interface to_string
        module procedure integer_to_string, long_integer_to_string, real_to_string
    end interface to_string

contains

    pure function integer_to_string(i) result(text)
        integer, intent(in) :: i
        character(len=:), allocatable :: text
        character(len=24) :: buffer
        write (buffer, '(i0)') i
        text = trim(buffer)
    end function integer_to_string

    !> Counts that can pass 2**31: byte offsets, nnz of factors.
    pure function long_integer_to_string(i) result(text)
        integer(i8), intent(in) :: i
        character(len=:), allocatable :: text
        character(len=24) :: buffer
        write (buffer, '(i0)') i
        text = trim(buffer)
    end function long_integer_to_string

    !> Shortest readable form that still round-trips in messages: g0 with 17 digits is noisy,
    !> so use 10 significant digits, enough to name the offending value.
    pure function real_to_string(x) result(text)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: buffer
        write (buffer, '(g0.10)') x
        text = trim(adjustl(buffer))
    end function real_to_string

    !> `i` with leading zeros to `width` digits (mode_001.vtu).
    pure function zero_padded(i, width) result(text)
        integer, intent(in) :: i, width
        character(len=width) :: text
        character(len=16) :: fmt
        write (fmt, '(a, i0, a, i0, a)') '(i', width, '.', width, ')'
        write (text, fmt) i
    end function zero_padded
end module strings
