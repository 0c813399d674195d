! SPDX-License-Identifier: MIT
!> The lexer of a namelist file: finds its groups ('&name ... /') with their text and line,
!> before any namelist read, so that a misspelt, repeated or unclosed group is reported
!> with its line; and splits a group's text into its assignments, so that a failed read
!> can be retried one assignment at a time to name the culprit.
module namelist_scan
    use status, only: status_t, STATUS_BAD_INPUT
    use strings, only: to_string, lowercase, printable, text_t
    use text_file, only: read_line, TOO_LONG
    use iso_fortran_env, only: iostat_end
    implicit none
    private
    public :: group_text_t, text_t, scan_groups, group_body, has_group, split_assignments, &
              group_list, assignment_starts, body_line, MAX_INPUT_BYTES

    integer, parameter :: MSG_LEN = 1024     !! iomsg buffers
    !> Largest input file: 1 MiB, thousands of times a real input, and small enough that
    !> a wrong file (a mesh, /dev/zero) is refused at once.
    integer, parameter :: MAX_INPUT_BYTES = 1048576
    integer, parameter :: PATH_SHOWN_LEN = 256  !! of a file name in a message
    character(len=*), parameter :: NAME_CHARS = &
        'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_'
    character(len=*), parameter :: BLANKS = ' '//achar(9)   !! blanks outside groups

    !> One namelist group as found in the file: lines joined by blanks, comments removed.
    type :: group_text_t
        character(len=:), allocatable :: name   !! lowercased, without the '&'
        character(len=:), allocatable :: body   !! text between '&name' and the closing '/'
        integer :: line = 0                     !! line of the '&name'
        integer, allocatable :: line_offsets(:) !! where the body's later lines start
    end type group_text_t

contains

    !> List the groups of the file before reading them, so that an absent group is told
    !> apart from a broken one (both end a namelist read at end of file), and a misspelt
    !> group name, which the runtime would silently skip, is an error: a group not among
    !> `known_groups` (lowercase names) or named twice. The file is read once, from where
    !> `unit` stands (never rewound: a pipe cannot be), in time linear in its size,
    !> and refused beyond MAX_INPUT_BYTES, so that /dev/zero or a huge file ends with a
    !> message instead of filling the memory.
    subroutine scan_groups(unit, path, known_groups, groups, stat)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: path
        character(len=*), intent(in) :: known_groups(:)
        type(group_text_t), allocatable, intent(out) :: groups(:)
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: line, name, body, shown
        integer, allocatable :: offsets(:)
        character(len=MSG_LEN) :: msg
        character(len=1) :: c, quote
        integer :: ios, line_number, group_line, i, j, k, body_len, n_offsets, n_bytes
        logical :: inside

        allocate (groups(0))
        allocate (character(len=256) :: body)
        allocate (offsets(16))
        inside = .false.
        quote = ' '
        line_number = 0
        group_line = 0
        body_len = 0
        n_offsets = 0
        n_bytes = 0
        shown = printable(path, PATH_SHOWN_LEN)
        ! No rewind: on a pipe, even with iostat=, gfortran 12 leaves the unit locked and
        ! the next read waits forever.
        do
            msg = ''
            call read_line(unit, line, ios, msg, max_len=MAX_INPUT_BYTES - n_bytes)
            if (ios == iostat_end) exit
            if (ios == TOO_LONG) then
                call too_large()
                return
            end if
            if (ios /= 0) then
                call stat%fail(STATUS_BAD_INPUT, shown//': cannot read input file: ' &
                               //printable(trim(msg)))
                return
            end if
            n_bytes = n_bytes + len(line) + 1
            if (n_bytes > MAX_INPUT_BYTES) then
                call too_large()
                return
            end if
            line_number = line_number + 1
            if (inside .and. line_number > group_line) call add_offset()
            i = 1
            do while (i <= len(line))
                c = line(i:i)
                if (quote /= ' ') then
                    ! Inside a quoted value: '&', '/' and '!' are text ('' toggles twice).
                    if (c == quote) quote = ' '
                    call add(c)
                else if (c == '!') then
                    exit
                else if (inside .and. (c == '"' .or. c == "'")) then
                    quote = c
                    call add(c)
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
                        ! Checked at once: the file holds at most one group of each name.
                        if (.not. any(known_groups == name)) then
                            call stat%fail(STATUS_BAD_INPUT, shown//': line ' &
                                           //to_string(line_number) &
                                           //': unknown namelist group &'//printable(name) &
                                           //' (known groups: '//group_list(known_groups)//')')
                            return
                        end if
                        do k = 1, size(groups)
                            if (groups(k)%name == name) then
                                call stat%fail(STATUS_BAD_INPUT, shown//': line ' &
                                               //to_string(line_number)//': namelist group &' &
                                               //name//' appears twice (first on line ' &
                                               //to_string(groups(k)%line)//'); merge them')
                                return
                            end if
                        end do
                        inside = .true.
                        group_line = line_number
                        body_len = 0
                        n_offsets = 0
                        call append_group(groups, name, group_line)
                    end if
                    i = j
                    cycle
                else if (inside .and. c == '/') then
                    call close_group()
                else if (inside .and. c == achar(9)) then
                    ! A tab is a blank, but gfortran's namelist read takes one right after
                    ! a number ('lambda = 2.5<TAB>') as part of it: a space instead.
                    call add(' ')
                else if (inside) then
                    call add(c)
                else if (index(BLANKS//achar(13), c) == 0) then
                    ! The runtime would skip it; it is garbage or a group without its '&'.
                    call stat%fail(STATUS_BAD_INPUT, shown//': line '//to_string(line_number) &
                        //', column '//to_string(i)//': text outside any namelist group: ' &
                        //"expected '&group name = value ... /' or a '!' comment")
                    return
                end if
                i = i + 1
            end do
            if (inside) call add(' ')
        end do
        if (inside) then
            call unclosed()
            return
        end if

    contains

        !> body = body//text in amortised constant time: a character at a time would
        !> otherwise copy the whole body each time (quadratic in a long value).
        subroutine add(text)
            character(len=*), intent(in) :: text
            character(len=:), allocatable :: larger
            if (body_len + len(text) > len(body)) then
                allocate (character(len=2*len(body) + len(text)) :: larger)
                larger(:body_len) = body(:body_len)
                call move_alloc(larger, body)
            end if
            body(body_len + 1:body_len + len(text)) = text
            body_len = body_len + len(text)
        end subroutine add

        !> A new line of the group starts at the next character of its body.
        subroutine add_offset()
            integer, allocatable :: larger(:)
            if (n_offsets == size(offsets)) then
                allocate (larger(2*size(offsets)))
                larger(:n_offsets) = offsets(:n_offsets)
                call move_alloc(larger, offsets)
            end if
            n_offsets = n_offsets + 1
            offsets(n_offsets) = body_len + 1
        end subroutine add_offset

        subroutine close_group()
            groups(size(groups))%body = body(:body_len)
            groups(size(groups))%line_offsets = offsets(:n_offsets)
            inside = .false.
            quote = ' '
        end subroutine close_group

        subroutine unclosed()
            character(len=:), allocatable :: why
            why = ''
            if (quote /= ' ') why = ' (a quoted value is not closed)'
            call stat%fail(STATUS_BAD_INPUT, shown//': line '//to_string(group_line)//': &' &
                           //groups(size(groups))%name//": the group has no closing '/'"//why)
        end subroutine unclosed

        subroutine too_large()
            call stat%fail(STATUS_BAD_INPUT, shown//': the input file is larger than ' &
                           //to_string(MAX_INPUT_BYTES)//' bytes (1 MiB, the limit of an ' &
                           //'input file; is it a namelist file?)')
        end subroutine too_large
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
            call move_alloc(groups(i)%line_offsets, grown(i)%line_offsets)
            grown(i)%line = groups(i)%line
        end do
        grown(size(grown))%name = name
        grown(size(grown))%body = ''
        allocate (grown(size(grown))%line_offsets(0))
        grown(size(grown))%line = line
        call move_alloc(grown, groups)
    end subroutine append_group

    !> Line of the file on which character `offset` of the body of `group` stands.
    pure integer function body_line(group, offset)
        type(group_text_t), intent(in) :: group
        integer, intent(in) :: offset
        body_line = group%line
        if (allocated(group%line_offsets)) &
            body_line = group%line + count(group%line_offsets <= offset)
    end function body_line

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
        integer :: i, j, last

        allocate (starts(0))   ! avoids a false -Wuninitialized at -O3 (see split_names)
        starts = assignment_starts(body)
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

    !> Where each assignment of `body` starts (the first character of its name), in order:
    !> split_assignments cuts there, and body_line turns one into a line of the file.
    pure function assignment_starts(body) result(starts)
        character(len=*), intent(in) :: body
        integer, allocatable :: starts(:)
        integer :: n, pass
        allocate (starts(0))
        ! Two passes, count then fill: growing the array by one per '=' would be quadratic.
        do pass = 1, 2
            call walk(n, pass == 2)
            if (pass == 1) then
                deallocate (starts)
                allocate (starts(n))
            end if
        end do

    contains

        pure subroutine walk(n, fill)
            integer, intent(out) :: n
            logical, intent(in) :: fill
            character(len=1) :: quote
            integer :: i, j, last
            n = 0
            quote = ' '
            do i = 1, len(body)
                if (quote /= ' ') then
                    if (body(i:i) == quote) quote = ' '
                else if (body(i:i) == '"' .or. body(i:i) == "'") then
                    quote = body(i:i)
                else if (body(i:i) == '=') then
                    last = len_trim(body(:i - 1))
                    j = last
                    do while (j >= 1)
                        if (index(NAME_CHARS//'%()', body(j:j)) == 0) exit
                        j = j - 1
                    end do
                    if (j + 1 <= last) then
                        n = n + 1
                        if (fill) starts(n) = j + 1
                    end if
                end if
            end do
        end subroutine walk
    end function assignment_starts

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
