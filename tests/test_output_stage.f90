! SPDX-License-Identifier: MIT
!> Staged output: files appear in the directory only at commit, abort leaves nothing, begin
!> removes the staging folders of dead runs only, and a directory that cannot be created is
!> reported as STATUS_IO.
program test_output_stage
    use status, only: status_t, STATUS_IO
    use output_stage, only: output_stage_t
    use filesystem, only: file_exists, is_directory, process_id, make_directories, &
                          remove_file, remove_directory, process_gone, list_directory, &
                          MAX_NAME_LEN
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t
    type(output_stage_t) :: stage
    type(status_t) :: stat
    character(len=:), allocatable :: dir, staging, a_path, b_path
    character(len=16) :: pid

    t%name = 'test_output_stage'
    write (pid, '(i0)') process_id()
    dir = 'stage_out/run'
    staging = dir//'/.nceig-partial-'//trim(pid)
    call clean()

    call make_directories('stage_out/a/b/c', stat)
    call t%check('make_directories succeeds', stat%ok())
    call t%check('make_directories creates parents', is_directory('stage_out/a/b/c'))
    call make_directories('stage_out/a/b/c', stat)
    call t%check('make_directories accepts an existing directory', stat%ok())

    ! begin / path / commit: nothing visible before commit, everything after.
    call stage%begin(dir, stat)
    call t%check('begin succeeds', stat%ok())
    call t%check('begin creates the directory and its parent', is_directory(dir))
    call t%check('staging folder exists during the run', is_directory(staging))
    a_path = stage%path('a.txt')
    b_path = stage%path('b.txt')
    call t%check('path points into the staging folder', a_path == staging//'/a.txt')
    call write_text(a_path, 'new a')
    call write_text(b_path, 'new b')
    call t%check('staged file not yet in the directory', .not. file_exists(dir//'/a.txt'))
    call stage%commit(stat)
    call t%check('commit succeeds', stat%ok())
    call t%check('a.txt committed', file_exists(dir//'/a.txt'))
    call t%check('b.txt committed', file_exists(dir//'/b.txt'))
    call t%check('content committed', first_line(dir//'/a.txt') == 'new a')
    call t%check('staging folder removed', .not. file_exists(staging))

    ! A second run replaces older files; abort keeps the old ones and leaves no staging.
    call stage%begin(dir, stat)
    call write_text(stage%path('a.txt'), 'newer a')
    call stage%commit(stat)
    call t%check('commit replaces an older file', first_line(dir//'/a.txt') == 'newer a')

    call stage%begin(dir, stat)
    call write_text(stage%path('a.txt'), 'aborted a')
    call write_text(stage%path('c.txt'), 'aborted c')
    call stage%abort()
    call t%check('abort leaves the older file', first_line(dir//'/a.txt') == 'newer a')
    call t%check('abort leaves no new file', .not. file_exists(dir//'/c.txt'))
    call t%check('abort removes the staging folder', .not. file_exists(staging))
    call stage%abort()
    call t%check('abort twice is harmless', .not. file_exists(staging))

    call check_stale_staging()

    ! A regular file where a parent directory should be.
    call write_text('stage_out/plain', 'not a directory')
    call stage%begin('stage_out/plain/sub', stat)
    call t%check('directory under a file: STATUS_IO', stat%code == STATUS_IO)
    call t%check('directory under a file: message names it', allocated(stat%message))
    if (allocated(stat%message)) then
        print '(a)', '      '//stat%message
        call t%check('message names the directory', index(stat%message, 'stage_out/plain/sub') > 0)
    end if
    ! The failed begin left the stage inactive, still holding the staging path of the run
    ! before: abort must then touch nothing on disk. A folder at that path stands for
    ! another run's staging.
    call make_directories(staging, stat)
    call stage%abort()
    call t%check('abort after a failed begin keeps the file in the way', &
                 first_line('stage_out/plain') == 'not a directory')
    call t%check('abort after a failed begin keeps the committed a.txt', &
                 first_line(dir//'/a.txt') == 'newer a')
    call t%check('abort after a failed begin keeps the committed b.txt', &
                 first_line(dir//'/b.txt') == 'new b')
    call t%check('abort after a failed begin leaves the earlier staging path alone', &
                 is_directory(staging))
    call t%check('abort after a failed begin creates nothing under the file', &
                 .not. file_exists('stage_out/plain/sub'))
    call remove_directory(staging)
    call stage%commit(stat)
    call t%check('commit without begin fails', .not. stat%ok())

    call clean()
    ! gfortran 12 keeps main-program allocatables in a frame gone before LeakSanitizer
    ! looks: free them here so a sanitizer build reports only real leaks.
    deallocate (dir, staging, a_path, b_path)
    call t%report()

contains

    subroutine write_text(path, text)
        character(len=*), intent(in) :: path, text
        integer :: unit
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') text
        close (unit)
    end subroutine write_text

    function first_line(path) result(line)
        character(len=*), intent(in) :: path
        character(len=80) :: line
        integer :: unit, ios
        line = ''
        open (newunit=unit, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        read (unit, '(a)', iostat=ios) line
        close (unit)
    end function first_line

    !> Staging folders left by killed runs: begin removes those of gone processes (pid
    !> 999999999 exceeds any Linux pid_max, 4194304) and one of our own pid (a dead run's);
    !> it keeps that of a live process (pid 1, init) and names that are not a pid.
    subroutine check_stale_staging()
        character(len=*), parameter :: PREFIX = '/.nceig-partial-'
        character(len=MAX_NAME_LEN), allocatable :: names(:)
        character(len=:), allocatable :: dead, live, odd
        dead = dir//PREFIX//'999999999'
        live = dir//PREFIX//'1'
        odd = dir//PREFIX//'12ab'
        call t%check('pid 999999999 is gone', process_gone(999999999))
        call t%check('pid 1 (init) is not gone', .not. process_gone(1))
        call t%check('our own pid is not gone', .not. process_gone(process_id()))
        call make_directories(dead, stat)
        call make_directories(live, stat)
        call make_directories(odd, stat)
        call make_directories(staging, stat)
        call write_text(dead//'/mode_001.vtu', 'partial')
        call write_text(dead//'/summary.json', 'partial')
        call write_text(live//'/mode_001.vtu', 'being written')
        call write_text(staging//'/old.txt', 'left by a dead run with our pid')
        call list_directory(dead, names)
        call t%check('list_directory lists the two files', size(names) == 2 .and. &
                     any(names == 'mode_001.vtu') .and. any(names == 'summary.json'))
        call stage%begin(dir, stat)
        call t%check('begin after killed runs succeeds', stat%ok())
        call t%check('staging folder of a gone process removed', .not. file_exists(dead))
        call t%check('staging folder of a live process kept', &
                     first_line(live//'/mode_001.vtu') == 'being written')
        call t%check('folder not named after a pid kept', is_directory(odd))
        call t%check('our pid''s leftover folder reused', is_directory(staging))
        call t%check('our pid''s leftover emptied', .not. file_exists(staging//'/old.txt'))
        call stage%abort()
        call remove_file(live//'/mode_001.vtu')
        call remove_directory(live)
        call remove_directory(odd)
    end subroutine check_stale_staging

    !> Leave the build folder as found (best effort; every name we might have made).
    subroutine clean()
        call remove_file(dir//'/a.txt')
        call remove_file(dir//'/b.txt')
        call remove_file(dir//'/c.txt')
        call remove_file(staging//'/a.txt')
        call remove_file(staging//'/c.txt')
        call remove_directory(staging)
        call remove_directory(dir)
        call remove_file('stage_out/plain')
        call remove_directory('stage_out/a/b/c')
        call remove_directory('stage_out/a/b')
        call remove_directory('stage_out/a')
        call remove_directory('stage_out')
    end subroutine clean
end program test_output_stage
