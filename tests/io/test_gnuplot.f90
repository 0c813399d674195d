! SPDX-License-Identifier: MIT
!> gnuplot: how paths reach gnuplot. A quote is doubled inside a single-quoted gnuplot string
!> (its one escape), a control byte is refused (no string can hold it), a relative path that
!> gnuplot or a program would read as an option or a home folder gets './', and the note of a
!> program that did not run tells missing from not started.
program test_gnuplot
    use gnuplot, only: gnuplot_string, quotable, path_argument, not_run_note
    use process, only: PROGRAM_NOT_FOUND, PROGRAM_NOT_STARTED
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_gnuplot'

    call t%check("gnuplot_string: Bob's results -> 'Bob''s results'", &
                 gnuplot_string("Bob's results") == "'Bob''s results'")
    call t%check("gnuplot_string: s'.system('x').' stays one string", &
                 gnuplot_string("s'.system('x').'") == "'s''.system(''x'').'''")
    call t%check('gnuplot_string: backslashes and double quotes as they are', &
                 gnuplot_string('a\b"c') == "'a\b""c'")
    call t%check("gnuplot_string: '' -> ''''", gnuplot_string('') == "''")

    call t%check('quotable: printable text', quotable("Bob's results/a;b $(c)"))
    call t%check('quotable: a line feed is refused', .not. quotable('a'//achar(10)//'b'))
    call t%check('quotable: a tab and DEL are refused', &
                 .not. quotable('a'//achar(9)) .and. .not. quotable(achar(127)))

    call t%check('path_argument: -dash/x -> ./-dash/x', path_argument('-dash/x') == './-dash/x')
    call t%check('path_argument: ~x -> ./~x', path_argument('~x') == './~x')
    call t%check('path_argument: absolute and plain relative paths unchanged', &
                 path_argument('/tmp/-x') == '/tmp/-x' .and. path_argument('out/a') == 'out/a')

    call t%check('not_run_note: not found -> "not installed"', &
                 not_run_note('gnuplot', PROGRAM_NOT_FOUND, 'No such file or directory') == &
                 'not drawn: gnuplot is not installed')
    call t%check('not_run_note: not started -> the reason', &
                 not_run_note('gnuplot', PROGRAM_NOT_STARTED, 'Too many open files') == &
                 'not drawn: gnuplot could not be started: Too many open files')
    call t%check('not_run_note: a program that ran (any exit status) -> ""', &
                 not_run_note('gnuplot', 0, '') == '' .and. not_run_note('gnuplot', 1, '') == '')

    call t%report()
end program test_gnuplot
