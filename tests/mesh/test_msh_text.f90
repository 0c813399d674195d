! SPDX-License-Identifier: MIT
!> The mesh file in memory and the Gmsh reader's one-line failures: lines come out without
!> their line feed or carriage return (the last one without a line feed too) and are
!> counted; every failure reads 'path:line: problem' on one printable line; a count that
!> the rest of the file cannot hold fails before anything is allocated.
program test_msh_text
    use status, only: status_t, STATUS_MESH
    use msh_text, only: text_file_t, load_file, next_line, require_line, truncated, &
                        fail_here, check_announced, read_counts, shortened, printable
    use fixtures, only: write_text
    use testing, only: test_suite_t
    implicit none

    character(len=*), parameter :: PATH = 'test_msh_text.msh'
    character(len=*), parameter :: LF = new_line('a'), CR = achar(13)
    type(test_suite_t) :: t
    type(text_file_t) :: f
    type(status_t) :: stat
    character(len=:), allocatable :: line, a, b, c
    integer :: values(3)
    logical :: got_a, got_b, got_c, got_more

    t%name = 'test_msh_text'
    call write_text(PATH, 'first'//CR//LF//LF//'third')
    call load_file(PATH, f, stat)
    call t%check('load_file: the whole file, its path kept', stat%ok() .and. f%path == PATH &
                 .and. len(f%text) == 13)
    got_a = next_line(f, a)
    got_b = next_line(f, b)
    got_c = next_line(f, c)
    got_more = next_line(f, line)
    call t%check('next_line: CR LF and LF ends dropped, an empty line, the last without '// &
                 'a line feed, then the end', got_a .and. got_b .and. got_c .and. &
                 .not. got_more .and. a == 'first' .and. len(b) == 0 .and. c == 'third' &
                 .and. f%line == 3)
    call reset()
    call require_line(f, line, 'the version line', stat)
    call t%check('require_line at the end: unexpected end of file at the last line, '// &
                 'what was expected', stat%code == STATUS_MESH .and. stat%message == &
                 PATH//':3: unexpected end of file (truncated?); expected the version line')
    call load_file('no_such_file.msh', f, stat)
    call t%check('load_file: a missing file named', stat%code == STATUS_MESH .and. &
                 index(stat%message, 'no_such_file.msh: cannot open mesh file') == 1)

    call from_text('a'//LF//'b'//LF//'c'//LF)
    line = 'x'
    if (next_line(f, line)) continue
    call reset()
    call truncated(f, 'coordinates', stat)
    call t%check('truncated: path, line, what was expected', stat%message == &
                 PATH//':1: unexpected end of file (truncated?); expected coordinates')
    call reset()
    call fail_here(f, stat, 'bad'//LF//'value'//achar(27))
    call t%check('fail_here: path:line: message, control characters as ?', &
                 stat%code == STATUS_MESH .and. stat%message == PATH//':1: bad?value?')
    call reset()
    call check_announced(f, 2, 1, 'nodes', stat)
    call t%check('check_announced: 2 lines left for 2 one-line entries', stat%ok())
    call reset()
    call check_announced(f, 2, 2, 'nodes (two lines each)', stat)
    call t%check('check_announced: not for 2 two-line entries, before any allocation', &
                 stat%code == STATUS_MESH .and. index(stat%message, 'announces 2 nodes (two '// &
                 'lines each), but the file ends 2 lines later') > 0)

    call from_text('3 4 5'//LF//'1 -2 3'//LF//'7 x'//LF//'-1'//LF)
    call reset()
    call read_counts(f, 3, 'three counts', values, stat)
    call t%check('read_counts: three non-negative integers', stat%ok() .and. &
                 all(values == [3, 4, 5]))
    call reset()
    call read_counts(f, 3, 'three counts', values, stat)
    call t%check('read_counts: a negative count fails at its line', index(stat%message, &
                 PATH//':2: expected three counts, found negative counts') == 1)
    call reset()
    call read_counts(f, 2, 'two counts', values(1:2), stat)
    call t%check('read_counts: not integers fails quoting the line', stat%message == &
                 PATH//':3: expected two counts, found ''7 x''')
    call reset()
    call read_counts(f, 1, 'one count', values(1:1), stat)
    call t%check('read_counts: one negative count fails too', index(stat%message, &
                 PATH//':4: expected one count') == 1)
    call reset()
    call read_counts(f, 1, 'one count', values(1:1), stat)
    call t%check('read_counts: at the end of the file, truncated', index(stat%message, &
                 'unexpected end of file') > 0)

    call t%check('shortened: 60 characters at most, ending in ...', &
                 len(shortened(repeat('y', 100))) == 60 .and. &
                 shortened(repeat('y', 100)) == repeat('y', 57)//'...' .and. &
                 shortened('short') == 'short')
    call t%check('shortened: bytes beyond ASCII and controls as ?', &
                 shortened('a'//char(200)//achar(9)//'b') == 'a??b')
    call t%check('printable: the same length, controls and DEL as ?', &
                 printable('x'//achar(0)//achar(127)//'y') == 'x??y')
    call execute_command_line('rm -f '//PATH)
    deallocate (line, a, b, c)   ! (AddressSanitizer reports a main program's allocatables)
    call t%report()

contains

    !> A status that has not failed: these procedures only record a failure in the status
    !> they are given (the reader's own), so each case starts from a fresh one.
    subroutine reset()
        type(status_t) :: fresh
        stat = fresh
    end subroutine reset

    subroutine from_text(text)
        character(len=*), intent(in) :: text
        type(text_file_t) :: fresh
        f = fresh
        f%path = PATH
        f%text = text
    end subroutine from_text
end program test_msh_text
