! SPDX-License-Identifier: MIT
!> Progress lines (console's print_progress): with stdout reconnected to a file, each line
!> is in the file as soon as the call returns (flushed, not buffered until exit), whole and
!> in order; with stdout not writable, the line is dropped and the program goes on. Stdout
!> is given back (/dev/stdout) before the checks print.
program test_console
    use iso_fortran_env, only: output_unit
    use testing, only: test_suite_t
    use console, only: print_progress
    use fixtures, only: file_text
    implicit none

    character(len=*), parameter :: LOG = 'test_console.log'
    type(test_suite_t) :: t
    character(len=:), allocatable :: after_first, after_second, after_refused
    integer :: unit, ios

    t%name = 'test_console'
    open (unit=output_unit, file=LOG, status='replace', action='write')
    call print_progress('assembly done: 12 dofs')
    after_first = file_text(LOG, '|')
    call print_progress('eigen done')
    after_second = file_text(LOG, '|')
    close (output_unit)
    open (unit=output_unit, file=LOG, status='old', action='read')
    call print_progress('a line stdout cannot take')
    close (output_unit)
    after_refused = file_text(LOG, '|')
    ! appended when stdout is a file (not written over from its start); a pipe cannot seek
    open (unit=output_unit, file='/dev/stdout', action='write', position='append', iostat=ios)
    if (ios /= 0) open (unit=output_unit, file='/dev/stdout', action='write')

    call t%check('the first line is in the file when the call returns', &
                 after_first == 'assembly done: 12 dofs|')
    call t%check('the second follows it, whole', &
                 after_second == 'assembly done: 12 dofs|eigen done|')
    call t%check('stdout not writable: the line dropped, the run goes on', &
                 after_refused == after_second)
    open (newunit=unit, file=LOG, status='old')
    close (unit, status='delete')
    ! the main program's allocatables are never freed by the runtime (LeakSanitizer)
    deallocate (after_first, after_second, after_refused)
    call t%report()
end program test_console
