! SPDX-License-Identifier: MIT
!> A JSON object (string, number, logical and null members, arrays of them, and objects of
!> such members on one line), kept in insertion order and written in one go: enough for
!> summary.json, with no JSON library to depend on.
module json_writer
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_IO
    use real_format, only: real_to_text
    use strings, only: to_string
    use ieee_arithmetic, only: ieee_is_finite
    use filesystem, only: end_output
    implicit none
    private

    !> One member: its key and its value already rendered as JSON text.
    type :: json_member_t
        character(len=:), allocatable :: key
        character(len=:), allocatable :: value
    end type json_member_t

    !> Members keep the order of their first addition; adding a key again replaces its value.
    type, public :: json_object_t
        type(json_member_t), allocatable :: members(:)
    contains
        procedure :: add_string => json_object_add_string
        procedure, private :: json_object_add_integer
        procedure, private :: json_object_add_integer_i8
        generic :: add_integer => json_object_add_integer, json_object_add_integer_i8
        procedure :: add_real => json_object_add_real
        procedure :: add_real_or_null => json_object_add_real_or_null
        procedure :: add_logical => json_object_add_logical
        procedure :: add_null => json_object_add_null
        procedure :: add_string_array => json_object_add_string_array
        procedure :: add_real_array => json_object_add_real_array
        procedure :: add_integer_array => json_object_add_integer_array
        procedure :: add_logical_array => json_object_add_logical_array
        procedure :: add_object => json_object_add_object
        procedure :: to_text => json_object_to_text
        procedure :: write => json_object_write
    end type json_object_t

contains

    subroutine json_object_add_string(this, key, value)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key, value
        call add_member(this, key, '"'//escaped(value)//'"')
    end subroutine json_object_add_string

    subroutine json_object_add_integer(this, key, value)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key
        integer, intent(in) :: value
        call this%add_integer(key, int(value, i8))
    end subroutine json_object_add_integer

    subroutine json_object_add_integer_i8(this, key, value)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key
        integer(i8), intent(in) :: value
        character(len=24) :: buffer
        write (buffer, '(i0)') value
        call add_member(this, key, trim(buffer))
    end subroutine json_object_add_integer_i8

    !> A real as the shortest decimal that reads back exactly; NaN and infinities, which
    !> JSON cannot represent, become null.
    subroutine json_object_add_real(this, key, value)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key
        real(wp), intent(in) :: value
        if (ieee_is_finite(value)) then
            call add_member(this, key, real_to_text(value))
        else
            call add_member(this, key, 'null')
        end if
    end subroutine json_object_add_real

    !> `value` when `present_flag` is true (e.g. "a positive eigenvalue was found"), else null.
    subroutine json_object_add_real_or_null(this, key, value, present_flag)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key
        real(wp), intent(in) :: value
        logical, intent(in) :: present_flag
        if (present_flag) then
            call this%add_real(key, value)
        else
            call this%add_null(key)
        end if
    end subroutine json_object_add_real_or_null

    subroutine json_object_add_logical(this, key, value)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key
        logical, intent(in) :: value
        if (value) then
            call add_member(this, key, 'true')
        else
            call add_member(this, key, 'false')
        end if
    end subroutine json_object_add_logical

    subroutine json_object_add_null(this, key)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key
        call add_member(this, key, 'null')
    end subroutine json_object_add_null

    !> An array of strings, each trimmed of trailing blanks; [] when `values` is empty.
    subroutine json_object_add_string_array(this, key, values)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key, values(:)
        character(len=:), allocatable :: text
        integer :: i
        text = '['
        do i = 1, size(values)
            call append_item(text, '"'//escaped(trim(values(i)))//'"')
        end do
        call add_member(this, key, text//']')
    end subroutine json_object_add_string_array

    !> An array of reals, each as add_real writes it (null for NaN and infinities).
    subroutine json_object_add_real_array(this, key, values)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key
        real(wp), intent(in) :: values(:)
        character(len=:), allocatable :: text
        integer :: i
        text = '['
        do i = 1, size(values)
            if (ieee_is_finite(values(i))) then
                call append_item(text, real_to_text(values(i)))
            else
                call append_item(text, 'null')
            end if
        end do
        call add_member(this, key, text//']')
    end subroutine json_object_add_real_array

    subroutine json_object_add_integer_array(this, key, values)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key
        integer, intent(in) :: values(:)
        character(len=:), allocatable :: text
        integer :: i
        text = '['
        do i = 1, size(values)
            call append_item(text, to_string(values(i)))
        end do
        call add_member(this, key, text//']')
    end subroutine json_object_add_integer_array

    subroutine json_object_add_logical_array(this, key, values)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key
        logical, intent(in) :: values(:)
        character(len=:), allocatable :: text
        integer :: i
        text = '['
        do i = 1, size(values)
            call append_item(text, trim(merge('true ', 'false', values(i))))
        end do
        call add_member(this, key, text//']')
    end subroutine json_object_add_logical_array

    !> Append an element to an array's text that starts with '['.
    pure subroutine append_item(text, item)
        character(len=:), allocatable, intent(inout) :: text
        character(len=*), intent(in) :: item
        if (len(text) > 1) text = text//', '
        text = text//item
    end subroutine append_item

    !> The object as text: one member per line, two-space indent, no final line feed;
    !> an empty object is '{}'.
    function json_object_to_text(this) result(text)
        class(json_object_t), intent(in) :: this
        character(len=:), allocatable :: text
        character(len=*), parameter :: NL = new_line('a')
        integer :: i

        if (.not. allocated(this%members)) then
            text = '{}'
            return
        else if (size(this%members) == 0) then
            text = '{}'
            return
        end if
        text = '{'
        do i = 1, size(this%members)
            if (i > 1) text = text//','
            text = text//NL//'  "'//escaped(this%members(i)%key)//'": '//this%members(i)%value
        end do
        text = text//NL//'}'
    end function json_object_to_text

    !> A member whose value is the object `value`, written on one line.
    subroutine json_object_add_object(this, key, value)
        class(json_object_t), intent(inout) :: this
        character(len=*), intent(in) :: key
        type(json_object_t), intent(in) :: value
        character(len=:), allocatable :: text
        integer :: i
        text = '{'
        if (allocated(value%members)) then
            do i = 1, size(value%members)
                if (i > 1) text = text//', '
                text = text//'"'//escaped(value%members(i)%key)//'": '//value%members(i)%value
            end do
        end if
        call add_member(this, key, text//'}')
    end subroutine json_object_add_object

    !> Write the object to file `path` (replacing it), ending with a line feed.
    subroutine json_object_write(this, path, stat)
        class(json_object_t), intent(in) :: this
        character(len=*), intent(in) :: path
        type(status_t), intent(out) :: stat
        character(len=1024) :: msg
        integer :: unit, ios

        ! Formatted stream access turns each new_line('a') in the text into a line end.
        open (newunit=unit, file=path, status='replace', action='write', access='stream', &
              form='formatted', iostat=ios, iomsg=msg)
        if (ios == 0) then
            write (unit, '(a)', iostat=ios, iomsg=msg) this%to_text()
            call end_output(unit, path, ios, msg)
        end if
        if (ios /= 0) call stat%fail(STATUS_IO, trim(path)//': cannot write JSON: '//trim(msg))
    end subroutine json_object_write

    subroutine add_member(object, key, value)
        type(json_object_t), intent(inout) :: object
        character(len=*), intent(in) :: key, value
        type(json_member_t), allocatable :: grown(:)
        integer :: i
        if (.not. allocated(object%members)) allocate (object%members(0))
        do i = 1, size(object%members)
            if (object%members(i)%key == key) then
                object%members(i)%value = value
                return
            end if
        end do
        ! Grown by hand: gfortran 12 leaks the allocatable components of the temporaries
        ! of [object%members, json_member_t(key, value)] (LeakSanitizer).
        allocate (grown(size(object%members) + 1))
        do i = 1, size(object%members)
            call move_alloc(object%members(i)%key, grown(i)%key)
            call move_alloc(object%members(i)%value, grown(i)%value)
        end do
        grown(size(grown))%key = key
        grown(size(grown))%value = value
        call move_alloc(grown, object%members)
    end subroutine add_member

    !> `text` with quotes, backslashes and control characters escaped as JSON requires.
    pure function escaped(text) result(json)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: json
        character(len=*), parameter :: HEX = '0123456789abcdef'
        integer :: i, code

        json = ''
        do i = 1, len(text)
            code = iachar(text(i:i))
            select case (code)
            case (iachar('"'))
                json = json//'\"'
            case (iachar('\'))
                json = json//'\\'
            case (8)
                json = json//'\b'
            case (9)
                json = json//'\t'
            case (10)
                json = json//'\n'
            case (12)
                json = json//'\f'
            case (13)
                json = json//'\r'
            case (0:7, 11, 14:31)
                json = json//'\u00'//HEX(code/16 + 1:code/16 + 1) &
                       //HEX(mod(code, 16) + 1:mod(code, 16) + 1)
            case default
                json = json//text(i:i)
            end select
        end do
    end function escaped
end module json_writer
