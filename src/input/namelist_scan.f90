! SPDX-License-Identifier: MIT
!> The lexer of a namelist file: finds its groups ('&name ... /') with their text and line,
!> before any namelist read, so that a misspelt, repeated or unclosed group is reported
!> with its line; and splits a group's text into its assignments, so that a failed read
!> can be retried one assignment at a time to name the culprit.
module namelist_scan
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: to_string, lowercase
    use text_file, only: read_line
    use iso_fortran_env, only: iostat_end
    implicit none
    private
    public :: group_text_t, text_t, scan_groups, group_body, has_group, split_assignments, &
              group_list

    integer, parameter :: MSG_LEN = 1024     !! iomsg buffers
    character(len=*), parameter :: NAME_CHARS = &
        'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_'
    character(len=*), parameter :: BLANKS = ' '//achar(9)   !! blanks outside groups

    !> One namelist group as found in the file: lines joined by blanks, comments removed.
    type :: group_text_t
        character(len=:), allocatable :: name   !! lowercased, without the '&'
        character(len=:), allocatable :: body   !! text between '&name' and the closing '/'
        integer :: line = 0                     !! line of the '&name'
    end type group_text_t

    !> A piece of text, for arrays of strings of different lengths.
    type :: text_t
        character(len=:), allocatable :: text
    end type text_t

contains

    !> List the groups of the file before reading them, so that an absent group is told
    !> apart from a broken one (both end a namelist read at end of file), and a misspelt
    !> group name, which the runtime would silently skip, is an error: a group not among
    !> `known_groups` (lowercase names) or named twice.
    subroutine scan_groups(unit, path, known_groups, groups, stat)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: path
        character(len=*), intent(in) :: known_groups(:)
        type(group_text_t), allocatable, intent(out) :: groups(:)
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: line, name, body
        character(len=MSG_LEN) :: msg
        character(len=1) :: c, quote
        integer :: ios, line_number, group_line, i, j
        logical :: inside

        allocate (groups(0))
        inside = .false.
        quote = ' '
        line_number = 0
        group_line = 0
        body = ''
        rewind (unit)
        do
            call read_line(unit, line, ios, msg)
            if (ios == iostat_end) exit
            if (ios /= 0) then
                call stat%fail(STATUS_BAD_INPUT, path//': cannot read input file: '//trim(msg))
                return
            end if
            line_number = line_number + 1
            i = 1
            do while (i <= len(line))
                c = line(i:i)
                if (quote /= ' ') then
                    ! Inside a quoted value: '&', '/' and '!' are text ('' toggles twice).
                    if (c == quote) quote = ' '
                    body = body//c
                else if (c == '!') then
                    exit
                else if (inside .and. (c == '"' .or. c == "'")) then
                    quote = c
                    body = body//c
                else if (c == '&' .or. c == '$') then
                    j = i + 1
                    do while (j <= len(line))
                        if (index(NAME_CHARS, line(j:j)) == 0) exit
                        j = j + 1
                    end do
                    name = lowercase(line(i + 1:j - 1))
                    ! '&end' closes a group; a new '&name' inside one means a missing '/'.
                    if (inside .and. name == 'end') then
                        call close_group()
                    else if (inside) then
                        call unclosed()
                        return
                    end if
                    if (name /= 'end' .and. len(name) > 0) then
                        inside = .true.
                        group_line = line_number
                        body = ''
                        call append_group(groups, name, group_line)
                    end if
                    i = j
                    cycle
                else if (inside .and. c == '/') then
                    call close_group()
                else if (inside) then
                    body = body//c
                else if (index(BLANKS//achar(13), c) == 0) then
                    ! The runtime would skip it; it is garbage or a group without its '&'.
                    call stat%fail(STATUS_BAD_INPUT, path//': line '//to_string(line_number) &
                        //', column '//to_string(i)//': text outside any namelist group: ' &
                        //"expected '&group name = value ... /' or a '!' comment")
                    return
                end if
                i = i + 1
            end do
            if (inside) body = body//' '
        end do
        if (inside) then
            call unclosed()
            return
        end if

        do i = 1, size(groups)
            if (.not. any(known_groups == groups(i)%name)) then
                call stat%fail(STATUS_BAD_INPUT, path//': line '//to_string(groups(i)%line) &
                               //': unknown namelist group &'//groups(i)%name &
                               //' (known groups: '//group_list(known_groups)//')')
                return
            end if
            do j = 1, i - 1
                if (groups(j)%name == groups(i)%name) then
                    call stat%fail(STATUS_BAD_INPUT, path//': line ' &
                                   //to_string(groups(i)%line)//': namelist group &' &
                                   //groups(i)%name//' appears twice (first on line ' &
                                   //to_string(groups(j)%line)//'); merge them')
                    return
                end if
            end do
        end do

    contains

        subroutine close_group()
            groups(size(groups))%body = body
            inside = .false.
            quote = ' '
        end subroutine close_group

        subroutine unclosed()
            character(len=:), allocatable :: why
            why = ''
            if (quote /= ' ') why = ' (a quoted value is not closed)'
            call stat%fail(STATUS_BAD_INPUT, path//': line '//to_string(group_line)//': &' &
                           //groups(size(groups))%name//": the group has no closing '/'"//why)
        end subroutine unclosed
    end subroutine scan_groups

    !> groups = [groups, group_text_t(name, '', line)] without the array constructor, whose
    !> temporary copies of allocatable components gfortran 12 never frees (LeakSanitizer).
    subroutine append_group(groups, name, line)
        type(group_text_t), allocatable, intent(inout) :: groups(:)
        character(len=*), intent(in) :: name
        integer, intent(in) :: line
        type(group_text_t), allocatable :: grown(:)
        integer :: i
        allocate (grown(size(groups) + 1))
        do i = 1, size(groups)
            call move_alloc(groups(i)%name, grown(i)%name)
            call move_alloc(groups(i)%body, grown(i)%body)
            grown(i)%line = groups(i)%line
        end do
        grown(size(grown))%name = name
        grown(size(grown))%body = ''
        grown(size(grown))%line = line
        call move_alloc(grown, groups)
    end subroutine append_group

    !> Text of group `name` as scanned, or '' when the file lacks it.
    function group_body(groups, name) result(body)
        type(group_text_t), intent(in) :: groups(:)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: body
        integer :: i
        body = ''
        do i = 1, size(groups)
            if (groups(i)%name == name) then
                body = groups(i)%body
                return
            end if
        end do
    end function group_body

    !> Whether the file has group `name`: an absent group keeps its defaults.
    pure logical function has_group(groups, name)
        type(group_text_t), intent(in) :: groups(:)
        character(len=*), intent(in) :: name
        integer :: i
        has_group = .false.
        do i = 1, size(groups)
            if (groups(i)%name == name) has_group = .true.
        end do
    end function has_group

    !> The assignments 'name = value' of a group body, to find the one a failed read
    !> choked on: the runtime's message alone does not always name the variable.
    function split_assignments(body) result(pieces)
        character(len=*), intent(in) :: body
        type(text_t), allocatable :: pieces(:)
        integer, allocatable :: starts(:)
        character(len=1) :: quote
        integer :: i, j, last

        allocate (starts(0))
        quote = ' '
        do i = 1, len(body)
            if (quote /= ' ') then
                if (body(i:i) == quote) quote = ' '
            else if (body(i:i) == '"' .or. body(i:i) == "'") then
                quote = body(i:i)
            else if (body(i:i) == '=') then
                j = len_trim(body(:i - 1))
                do while (j >= 1)
                    if (index(NAME_CHARS//'%()', body(j:j)) == 0) exit
                    j = j - 1
                end do
                if (j + 1 <= len_trim(body(:i - 1))) starts = [starts, j + 1]
            end if
        end do
        allocate (pieces(size(starts)))
        do i = 1, size(starts)
            last = len(body)
            if (i < size(starts)) last = starts(i + 1) - 1
            pieces(i)%text = trim(body(starts(i):last))
            ! Drop the value separator that ends all but the last assignment.
            j = len(pieces(i)%text)
            if (j > 0) then
                if (pieces(i)%text(j:j) == ',') pieces(i)%text = trim(pieces(i)%text(:j - 1))
            end if
        end do
    end function split_assignments


    !> "&mesh, &material, ...": the known groups, for messages.
    pure function group_list(known_groups) result(text)
        character(len=*), intent(in) :: known_groups(:)
        character(len=:), allocatable :: text
        integer :: i
        text = ''
        do i = 1, size(known_groups)
            if (i > 1) text = text//', '
            text = text//'&'//trim(known_groups(i))
        end do
    end function group_list
end module namelist_scan
