! SPDX-License-Identifier: MIT
!> Staged output: the set appears in the directory only at commit, as one directory swap;
!> abort and failures leave the previous set and nothing else; the user's files survive a
!> swap; begin removes the staging folders of dead runs only; a directory that cannot be
!> created is reported as STATUS_IO and leaves no directory behind.
program test_output_stage
    use status, only: status_t, STATUS_IO
    use output_stage, only: output_stage_t
    use strings, only: text_t
    use filesystem, only: file_exists, is_directory, process_id, make_directories, &
                          remove_file, remove_directory, process_gone, list_directory, &
                          remove_tree, close_output, MAX_NAME_LEN
    use testing, only: test_suite_t
    use iso_c_binding, only: c_int, c_char, c_null_char
    implicit none
    type(test_suite_t) :: t
    type(output_stage_t) :: stage
    type(text_t) :: unlisted(1)   ! named: a constructor's allocatable components would leak
    type(status_t) :: stat
    character(len=:), allocatable :: dir, staging, a_path, b_path, long_name, committed_a
    character(len=16) :: pid
    character(len=256) :: msg
    integer :: created, unit, ios

    t%name = 'test_output_stage'
    write (pid, '(i0)') process_id()
    dir = 'stage_out/run'
    staging = 'stage_out/.run.nceig-staging-'//trim(pid)
    call remove_tree('stage_out')

    call make_directories('stage_out/a/b/c', stat, created)
    call t%check('make_directories succeeds', stat%ok())
    call t%check('make_directories creates parents', is_directory('stage_out/a/b/c'))
    call t%check('make_directories counts what it made', created == 4)
    call make_directories('stage_out/a/b/c', stat, created)
    call t%check('make_directories accepts an existing directory', stat%ok() .and. created == 0)
    long_name = repeat('n', 300)
    call make_directories('stage_out/m1/m2/'//long_name//'/z', stat)
    call t%check('make_directories: a name too long fails', stat%code == STATUS_IO)
    call t%check('make_directories: a failure removes what it made', &
                 .not. file_exists('stage_out/m1'))
    call t%check('make_directories: a failure keeps what existed', is_directory('stage_out'))

    ! begin / path / commit: nothing visible before commit, everything after.
    call stage%begin(dir, stat)
    call t%check('begin succeeds', stat%ok())
    call t%check('begin does not create the directory itself', .not. file_exists(dir))
    call t%check('staging folder next to the directory', is_directory(staging))
    call stage%add('a.txt', a_path)
    call stage%add('b.txt', b_path)
    call t%check('path points into the staging folder', &
                 index(a_path, '/'//staging//'/a.txt', back=.true.) == len(a_path) - len(staging) - 6)
    call write_text(a_path, 'new a')
    call write_text(b_path, 'new b')
    call write_staged('summary.json', '  "files": ["a.txt", "b.txt"],')
    call stage%commit(stat)
    call t%check('commit succeeds', stat%ok())
    call t%check('a.txt committed', file_exists(dir//'/a.txt'))
    call t%check('b.txt committed', file_exists(dir//'/b.txt'))
    call t%check('content committed', first_line(dir//'/a.txt') == 'new a')
    call t%check('staging folder removed', .not. file_exists(staging))

    ! A second run replaces the set: its files, the user's files, not the older set's.
    call write_text(dir//'/notes.txt', 'mine')
    call stage%begin(dir, stat)
    call write_staged('a.txt', 'newer a')
    call write_staged('summary.json', '  "files": ["a.txt"],')
    call stage%commit(stat)
    call t%check('commit replaces an older file', first_line(dir//'/a.txt') == 'newer a')
    call t%check('the older set''s other file is gone', .not. file_exists(dir//'/b.txt'))
    call t%check('the user''s file is kept', first_line(dir//'/notes.txt') == 'mine')
    call t%check('no staging folder after a swap', .not. file_exists(staging))

    ! A file an older build left unlisted (begin's unlisted_old) goes with the old set; the
    ! user's file stays.
    call write_text(dir//'/old.png', 'unlisted')
    unlisted(1)%text = 'old.png'
    call stage%begin(dir, stat, unlisted)
    call write_staged('a.txt', 'newer a')
    call write_staged('summary.json', '  "files": ["a.txt"],')
    call stage%commit(stat)
    call t%check('commit with unlisted_old succeeds', stat%ok())
    call t%check('an unlisted file of an older build is removed', &
                 .not. file_exists(dir//'/old.png'))
    call t%check('beside it the user''s file is kept', first_line(dir//'/notes.txt') == 'mine')

    call stage%begin(dir, stat)
    call write_staged('a.txt', 'aborted a')
    call write_staged('c.txt', 'aborted c')
    call stage%abort()
    call t%check('abort leaves the older file', first_line(dir//'/a.txt') == 'newer a')
    call t%check('abort leaves no new file', .not. file_exists(dir//'/c.txt'))
    call t%check('abort removes the staging folder', .not. file_exists(staging))
    call stage%abort()
    call t%check('abort twice is harmless', .not. file_exists(staging))

    ! A folder of the user's cannot be carried over: the commit fails, nothing changes.
    call make_directories(dir//'/plots', stat)
    call stage%begin(dir, stat)
    call write_staged('a.txt', 'refused a')
    call stage%commit(stat)
    call t%check('a foreign folder: STATUS_IO', stat%code == STATUS_IO)
    if (allocated(stat%message)) print '(a)', '      '//stat%message
    call t%check('a foreign folder: the set is unchanged', first_line(dir//'/a.txt') == 'newer a')
    call t%check('a foreign folder: the folder stays', is_directory(dir//'/plots'))
    call t%check('a foreign folder: no staging folder left', .not. file_exists(staging))
    call remove_directory(dir//'/plots')

    call check_stale_staging()
    call check_without_swap()
    call check_in_place()
    call check_long_names()

    ! A regular file where a parent directory should be; a path too long: nothing is left.
    committed_a = first_line(dir//'/a.txt')
    call write_text('stage_out/plain', 'not a directory')
    call stage%begin('stage_out/plain/sub/run', stat)
    call t%check('directory under a file: STATUS_IO', stat%code == STATUS_IO)
    call t%check('directory under a file: message names it', allocated(stat%message))
    if (allocated(stat%message)) then
        print '(a)', '      '//stat%message
        call t%check('message names the directory', &
                     index(stat%message, 'stage_out/plain/sub/run') > 0)
    end if
    ! The failed begin left the stage inactive, still holding the staging path of the run
    ! before: abort must then touch nothing on disk. A folder at that path stands for
    ! another run's staging.
    call make_directories(staging, stat)
    call stage%abort()
    call t%check('abort after a failed begin keeps the file in the way', &
                 first_line('stage_out/plain') == 'not a directory')
    call t%check('abort after a failed begin keeps the committed set', &
                 first_line(dir//'/a.txt') == committed_a .and. len(committed_a) > 0)
    call t%check('abort after a failed begin leaves the earlier staging path alone', &
                 is_directory(staging))
    call t%check('abort after a failed begin creates nothing under the file', &
                 .not. file_exists('stage_out/plain/sub'))
    call remove_directory(staging)
    call stage%begin('stage_out/p1/p2/'//long_name//'/run', stat)
    call t%check('a name too long: STATUS_IO', stat%code == STATUS_IO)
    call t%check('a name too long: no directory left', .not. file_exists('stage_out/p1'))
    call stage%begin('stage_out/q1/q2/run', stat)
    call stage%abort()
    call t%check('abort removes the parents begin made', .not. file_exists('stage_out/q1'))
    call stage%commit(stat)
    call t%check('commit without begin fails', .not. stat%ok())

    ! close_output: a complete file passes.
    open (newunit=unit, file='stage_out/closed.txt', status='replace', action='write')
    write (unit, '(a)') 'twelve bytes'
    call close_output(unit, 'stage_out/closed.txt', ios, msg)
    call t%check('close_output of a complete file: ios = 0', ios == 0)

    call remove_tree('stage_out')
    ! gfortran 12 keeps main-program allocatables in a frame gone before LeakSanitizer
    ! looks: free them here so a sanitizer build reports only real leaks.
    deallocate (dir, staging, a_path, b_path, long_name, committed_a, unlisted(1)%text)
    call t%report()

contains

    subroutine write_text(path, text)
        character(len=*), intent(in) :: path, text
        integer :: unit
        open (newunit=unit, file=path, status='replace', action='write')
        write (unit, '(a)') text
        close (unit)
    end subroutine write_text

    !> `text` as the file `name` of the stage's set.
    subroutine write_staged(name, text)
        character(len=*), intent(in) :: name, text
        character(len=:), allocatable :: path
        call stage%add(name, path)
        call write_text(path, text)
    end subroutine write_staged

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
        character(len=*), parameter :: PREFIX = 'stage_out/.run.nceig-staging-'
        character(len=MAX_NAME_LEN), allocatable :: names(:)
        character(len=:), allocatable :: dead, live, odd
        dead = PREFIX//'999999999'
        live = PREFIX//'1'
        odd = PREFIX//'12ab'
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
        call list_directory(dead//'/none', names, stat)
        call t%check('list_directory of a missing directory: STATUS_IO naming it', &
                     stat%code == STATUS_IO .and. index(stat%message, dead//'/none') > 0)
        call stage%begin(dir, stat)
        call t%check('begin after killed runs succeeds', stat%ok())
        call t%check('staging folder of a gone process removed', .not. file_exists(dead))
        call t%check('staging folder of a live process kept', &
                     first_line(live//'/mode_001.vtu') == 'being written')
        call t%check('folder not named after a pid kept', is_directory(odd))
        call t%check('our pid''s leftover folder reused', is_directory(staging))
        call t%check('our pid''s leftover emptied', .not. file_exists(staging//'/old.txt'))
        call stage%abort()
        call remove_tree(live)
        call remove_directory(odd)
    end subroutine check_stale_staging

    !> Where the file system cannot swap (NFS), the old directory is set aside for a moment:
    !> same result. A run killed in that moment leaves no directory and the old set aside;
    !> the next run puts it back before anything else.
    subroutine check_without_swap()
        character(len=*), parameter :: ASIDE = 'stage_out/.run.nceig-old-999999999'
        call stage%begin(dir, stat)
        call write_staged('a.txt', 'set aside a')
        call write_staged('summary.json', '  "files": ["a.txt"],')
        call stage%commit(stat, swap=.false.)
        call t%check('without swap: commit succeeds', stat%ok())
        call t%check('without swap: the new set is in place', &
                     first_line(dir//'/a.txt') == 'set aside a')
        call t%check('without swap: the user''s file is kept', &
                     first_line(dir//'/notes.txt') == 'mine')
        call t%check('without swap: the old set is removed', &
                     .not. file_exists('stage_out/.run.nceig-old-'//trim(pid)))

        call make_directories(ASIDE, stat)
        call write_text(ASIDE//'/a.txt', 'old a')
        call remove_tree(dir)
        call stage%begin(dir, stat)
        call t%check('killed while set aside: the next run puts the old set back', &
                     first_line(dir//'/a.txt') == 'old a')
        call t%check('killed while set aside: no aside folder left', .not. file_exists(ASIDE))
        call stage%abort()
    end subroutine check_without_swap

    !> A directory that holds the working directory ('.' here; as for a mount point or an
    !> unwritable parent, a rename cannot replace it) is committed in place, file by file,
    !> summary.json last: the same set in the end. Another spelling of it from elsewhere
    !> ('stage_out/here/.') names the same directory: the same staging name and lock.
    subroutine check_in_place()
        character(len=*), parameter :: HERE = 'stage_out/here'
        character(len=:), allocatable :: outside
        interface
            function c_chdir(path) bind(C, name='chdir') result(status)
                import :: c_int, c_char
                character(kind=c_char), intent(in) :: path(*)
                integer(c_int) :: status
            end function c_chdir
        end interface
        call make_directories(HERE//'/plots', stat)
        call write_text(HERE//'/notes.txt', 'mine')
        call stage%begin(HERE//'/.', stat)
        outside = stage%folder()
        call t%check('another spelling: the same staging folder as the plain name', &
                     stat%ok() .and. index(outside, '/stage_out/.here.nceig-staging-'//trim(pid)) > 0)
        call stage%abort()
        call stage%begin('stage_out/x/../here/', stat)
        call t%check('a spelling with ..: the same staging folder', stage%folder() == outside)
        call stage%abort()
        call t%check('chdir into the directory', c_chdir(HERE//c_null_char) == 0)
        call stage%begin('.', stat)
        call t%check('in place: begin succeeds', stat%ok())
        call t%check('in place: the same staging folder as from outside', &
                     stage%folder() == outside)
        call t%check('in place: the staging folder exists', is_directory(outside))
        call write_staged('a.txt', 'first a')
        call write_staged('b.txt', 'first b')
        call write_staged('summary.json', '  "files": ["a.txt", "b.txt"],')
        call stage%commit(stat)
        call t%check('in place: commit succeeds', stat%ok())
        call stage%begin('.', stat)
        call write_staged('a.txt', 'second a')
        call write_staged('summary.json', '  "files": ["a.txt"],')
        call stage%commit(stat)
        call t%check('in place: the working directory is still the directory', &
                     first_line('notes.txt') == 'mine')
        call t%check('back from the directory', c_chdir('../..'//c_null_char) == 0)
        call t%check('in place: the new file is in', first_line(HERE//'/a.txt') == 'second a')
        call t%check('in place: the old set''s other file is gone', &
                     .not. file_exists(HERE//'/b.txt'))
        call t%check('in place: the user''s file and folder stay', &
                     first_line(HERE//'/notes.txt') == 'mine')
        call t%check('in place: the user''s folder stays', is_directory(HERE//'/plots'))
        call t%check('in place: no staging folder left', .not. file_exists(outside))
    end subroutine check_in_place

    !> Names of 221 to 255 bytes are legal; the staging and lock names derived from them
    !> are shortened to fit NAME_MAX, and the stale staging folders of such a directory are
    !> still found. A name over 255 bytes is refused as too long.
    subroutine check_long_names()
        character(len=:), allocatable :: long_dir, folder, dead
        integer :: n, dash
        do n = 236, 255, 19
            long_dir = 'stage_out/'//repeat('l', n)
            call stage%begin(long_dir, stat)
            call t%check('a '//trim(str(n))//'-byte name: begin succeeds', stat%ok())
            if (.not. stat%ok()) then
                print '(a)', '      '//stat%message
                cycle
            end if
            folder = stage%folder()
            call t%check('a '//trim(str(n))//'-byte name: the staging name fits NAME_MAX', &
                         len(folder) - index(folder, '/', back=.true.) <= MAX_NAME_LEN)
            call t%check('a '//trim(str(n))//'-byte name: the staging folder exists', &
                         is_directory(folder))
            call write_staged('a.txt', 'long a')
            call write_staged('summary.json', '  "files": ["a.txt"],')
            call stage%commit(stat)
            call t%check('a '//trim(str(n))//'-byte name: commit succeeds', stat%ok())
            call t%check('a '//trim(str(n))//'-byte name: the file is in', &
                         first_line(long_dir//'/a.txt') == 'long a')
            ! a dead run's staging folder of that directory: the next begin removes it
            dash = index(folder, '-', back=.true.)
            dead = folder(:dash)//'999999999'
            call make_directories(dead, stat)
            call stage%begin(long_dir, stat)
            call t%check('a '//trim(str(n))//'-byte name: begin after a dead run', stat%ok())
            call t%check('a '//trim(str(n))//'-byte name: a dead run''s staging folder is ' &
                         //'removed', .not. file_exists(dead))
            call stage%abort()
            call remove_tree(long_dir)
        end do
        call stage%begin('stage_out/'//repeat('l', 256), stat)
        call t%check('a 256-byte name: refused as too long', &
                     stat%code == STATUS_IO .and. index(stat%message, 'too long') > 0)
        if (allocated(stat%message)) print '(a)', '      '//stat%message(:min(len(stat%message), 60))//'...'
        call t%check('a 256-byte name: nothing created', &
                     .not. file_exists('stage_out/'//repeat('l', 256)))
    end subroutine check_long_names

    function str(n) result(text)
        integer, intent(in) :: n
        character(len=12) :: text
        write (text, '(i0)') n
    end function str
end program test_output_stage
