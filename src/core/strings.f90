! SPDX-License-Identifier: MIT
!> Number-to-text conversions for messages, file names and the stdout summaries, and the
!> handling of names (case, blank-separated lists) shared by the input file, the Gmsh reader
!> and the Matrix Market reader. Every module uses these rather than a local twin, so a
!> count or a time reads the same everywhere and a name is compared the same way everywhere.
module strings
    use kinds, only: wp, i8
    use ieee_arithmetic, only: ieee_is_nan
    implicit none
    private
    public :: to_string, zero_padded, short_real_text, given_real_text, seconds_text
    public :: lowercase, split_names, split_words, count_names, normalized_list
    public :: quoted, one_of, joined, from_c_chars, printable, append_text
    public :: NAME_LEN, LIST_LEN, SHOWN_LEN

    !> A piece of text, for arrays of strings of different lengths.
    type, public :: text_t
        character(len=:), allocatable :: text
    end type text_t

    !> Names of elements, solvers, analyses and boundary parts (input file and mesh alike),
    !> so that a part name read from a mesh always fits the variable that names it.
    integer, parameter :: NAME_LEN = 64
    integer, parameter :: LIST_LEN = 512    !! blank-separated lists of names
    character(len=*), parameter :: BLANKS = ' '//achar(9)   !! separators in name lists
    integer, parameter :: SHOWN_LEN = 80    !! characters of a value echoed in a message

    interface to_string
        module procedure integer_to_string, long_integer_to_string, real_to_string
    end interface to_string

contains

    pure function integer_to_string(i) result(text)
        integer, intent(in) :: i
        character(len=:), allocatable :: text
        text = long_integer_to_string(int(i, i8))
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

    !> `x` in scientific notation with `digits` decimals (2 unless given), no blanks:
    !> '1.23E-05' for backward errors, times and rcond in messages; digits = 5 names an
    !> offending input value ('2.00000E+11').
    pure function short_real_text(x, digits) result(text)
        real(wp), intent(in) :: x
        integer, intent(in), optional :: digits
        character(len=:), allocatable :: text
        character(len=48) :: buffer
        character(len=16) :: edit
        integer :: d
        logical :: wide
        d = 2
        if (present(digits)) d = digits
        ! es(d+7).d is the narrowest field that holds a sign and a 2-digit exponent; a
        ! 3-digit exponent needs e3, or the 'E' is dropped ('1.49+284')
        ! (NaN first: an ordered comparison with it traps in debug builds)
        wide = .false.
        if (.not. ieee_is_nan(x)) wide = abs(x) >= 1.0e98_wp .or. &
                                         (abs(x) > 0.0_wp .and. abs(x) < 1.0e-98_wp)
        if (wide) then
            write (edit, '(a, i0, a, i0, a)') '(es', d + 8, '.', d, 'e3)'
        else
            write (edit, '(a, i0, a, i0, a)') '(es', d + 7, '.', d, ')'
        end if
        write (buffer, edit) x
        text = trim(adjustl(buffer))
    end function short_real_text

    !> short_real_text with the fewest digits (three at least, as short_real_text gives) that
    !> read back to `x` exactly: for a value the user gave, such as a tolerance, which three
    !> digits may round to another ('9.99999E-01', not '1.00E+00'; 1e-8 stays '1.00E-08').
    pure function given_real_text(x) result(text)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        real(wp) :: back
        integer :: d, ios
        text = short_real_text(x, 16)   ! 17 digits: every binary64 reads back from them
        ! (a shorter text of a value near huge may round past it: reading it would overflow)
        if (.not. abs(x) < 0.1_wp*huge(x)) return
        do d = 2, 15
            text = short_real_text(x, d)
            read (text, *, iostat=ios) back
            if (ios == 0 .and. abs(back - x) <= 0.0_wp) return
        end do
        text = short_real_text(x, 16)
    end function given_real_text

    !> Seconds with three decimals and a leading zero ('0.042', '12.500') for the summaries.
    pure function seconds_text(t) result(text)
        real(wp), intent(in) :: t
        character(len=:), allocatable :: text
        character(len=16) :: buffer
        write (buffer, '(f0.3)') t
        text = trim(buffer)
        if (text(1:1) == '.') text = '0'//text
    end function seconds_text

    !> `text` with ASCII capitals turned to small letters.
    elemental function lowercase(text) result(lower)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: lower
        integer :: i, code
        lower = text
        do i = 1, len(text)
            code = iachar(text(i:i))
            if (code >= iachar('A') .and. code <= iachar('Z')) then
                lower(i:i) = achar(code - iachar('A') + iachar('a'))
            end if
        end do
    end function lowercase

    !> The blank-separated names of `list`, in order, each at most NAME_LEN characters
    !> (longer ones are cut; read_input rejects them). gfortran 12 -O3 falsely warns of an
    !> uninitialised descriptor when the result is the first value of an allocatable:
    !> allocate that empty beforehand.
    pure function split_names(list) result(names)
        character(len=*), intent(in) :: list
        character(len=NAME_LEN), allocatable :: names(:)
        character(len=LIST_LEN), allocatable :: words(:)
        integer :: i
        call split_words(list, words)
        allocate (names(size(words)))
        do i = 1, size(words)
            names(i) = words(i)(:NAME_LEN)
        end do
    end function split_names

    !> The blank-separated words of `list`, uncut (lists are at most LIST_LEN long).
    !> A subroutine with a fixed length: a function result of length len(list) crashes
    !> gfortran 12, and assigning a function result draws false -Wuninitialized at -O3.
    pure subroutine split_words(list, words)
        character(len=*), intent(in) :: list
        character(len=LIST_LEN), allocatable, intent(out) :: words(:)
        integer :: i, n_words
        logical :: in_word

        n_words = 0
        in_word = .false.
        do i = 1, len(list)
            if (index(BLANKS, list(i:i)) > 0) then
                in_word = .false.
            else if (.not. in_word) then
                in_word = .true.
                n_words = n_words + 1
            end if
        end do
        allocate (words(n_words))
        words = ''
        n_words = 0
        in_word = .false.
        do i = 1, len(list)
            if (index(BLANKS, list(i:i)) > 0) then
                in_word = .false.
                cycle
            else if (.not. in_word) then
                in_word = .true.
                n_words = n_words + 1
            end if
            words(n_words) = trim(words(n_words))//list(i:i)
        end do
    end subroutine split_words

    !> Number of blank-separated names in `list`.
    pure integer function count_names(list)
        character(len=*), intent(in) :: list
        character(len=LIST_LEN), allocatable :: words(:)
        call split_words(list, words)
        count_names = size(words)
    end function count_names

    !> `list` lowercased, its names separated by single blanks.
    pure function normalized_list(list) result(normal)
        character(len=*), intent(in) :: list
        character(len=len(list)) :: normal
        character(len=LIST_LEN), allocatable :: words(:)
        integer :: i
        call split_words(lowercase(list), words)
        normal = ''
        do i = 1, size(words)
            if (i == 1) then
                normal = words(i)
            else
                normal = trim(normal)//' '//words(i)
            end if
        end do
    end function normalized_list

    !> `text` trimmed, in single quotes: how a name is shown in messages and help.
    pure function quoted(text) result(q)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: q
        q = "'"//trim(text)//"'"
    end function quoted

    !> "'a', 'b', 'c'": the accepted values of a choice, for messages and help.
    pure function one_of(choices) result(text)
        character(len=*), intent(in) :: choices(:)
        character(len=:), allocatable :: text
        text = joined(choices, before="'", after="'")
    end function one_of

    !> The words, trimmed, each between `before` and `after`, separated by ', ':
    !> "a, b, c" for messages listing names.
    pure function joined(words, before, after) result(text)
        character(len=*), intent(in) :: words(:)
        character(len=*), intent(in), optional :: before, after
        character(len=:), allocatable :: text
        integer :: i
        text = ''
        do i = 1, size(words)
            if (i > 1) text = text//', '
            if (present(before)) text = text//before
            text = text//trim(words(i))
            if (present(after)) text = text//after
        end do
    end function joined

    !> texts = [texts, text_t(text)], grown by hand: gfortran 12 leaks the allocatable
    !> components of the array constructor's temporaries (LeakSanitizer).
    pure subroutine append_text(texts, text)
        type(text_t), allocatable, intent(inout) :: texts(:)
        character(len=*), intent(in) :: text
        type(text_t), allocatable :: grown(:)
        integer :: i
        allocate (grown(size(texts) + 1))
        do i = 1, size(texts)
            call move_alloc(texts(i)%text, grown(i)%text)
        end do
        grown(size(grown))%text = text
        call move_alloc(grown, texts)
    end subroutine append_text

    !> The first `length` characters of a C character array as a Fortran string.
    pure function from_c_chars(chars, length) result(text)
        character(len=1), intent(in) :: chars(:)
        integer, intent(in) :: length
        character(len=:), allocatable :: text
        integer :: i
        allocate (character(len=max(0, length)) :: text)
        do i = 1, length
            text(i:i) = chars(i)
        end do
    end function from_c_chars

    !> `text` fit for a one-line message: control bytes (NUL, line feed, escape, ...) become
    !> '?', so that none reaches a terminal or a log; beyond `max_len` characters (SHOWN_LEN
    !> unless given) it is cut and ends in '...', so that a huge value is named, not dumped.
    pure function printable(text, max_len) result(shown)
        character(len=*), intent(in) :: text
        integer, intent(in), optional :: max_len
        character(len=:), allocatable :: shown
        integer :: limit, n, i, code
        limit = SHOWN_LEN
        if (present(max_len)) limit = max(max_len, 4)
        n = len(text)
        if (n > limit) n = limit - 3
        allocate (character(len=n) :: shown)
        do i = 1, n
            code = iachar(text(i:i))
            if (code < 32 .or. code == 127) then
                shown(i:i) = '?'
            else
                shown(i:i) = text(i:i)
            end if
        end do
        if (n < len(text)) shown = shown//'...'
    end function printable
end module strings
