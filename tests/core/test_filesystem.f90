! SPDX-License-Identifier: MIT
!> The POSIX wrappers the output commit rests on, each against what the file system then
!> holds: directories made and removed whole, renames and swaps of folders, hard links,
!> permission bits, locks, listings, paths resolved, processes found or gone. Everything
!> happens in a folder of this process's own (named by its pid), removed at the end. The
!> signal handlers are armed and disarmed without a signal (cli_signals sends them).
program test_filesystem
    use status, only: status_t, STATUS_IO
    use strings, only: to_string
    use filesystem, only: make_directories, rename_file, remove_file, remove_directory, &
                          file_exists, is_directory, process_id, is_real_directory, &
                          process_gone, list_directory, close_output, end_output, sync_path, &
                          sync_filesystem, replace_directory, make_link, copy_mode, &
                          remove_tree, lock_file, unlock_file, real_path, can_replace, &
                          canonical_path, cleanup_on_signal, hold_signals, &
                          end_cleanup_on_signal, MAX_NAME_LEN
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t
    character(len=:), allocatable :: root, cwd

    t%name = 'test_filesystem'
    root = 'test_filesystem_'//to_string(process_id())
    call remove_tree(root)
    cwd = real_path('.')
    call check_directories()
    call check_files()
    call check_replace()
    call check_paths()
    call check_processes()
    call check_signals()
    call remove_tree(root)
    call t%check('remove_tree: the whole test folder gone', .not. file_exists(root))
    deallocate (root, cwd)   ! (AddressSanitizer reports a main program's allocatables)
    call t%report()

contains

    subroutine check_directories()
        type(status_t) :: stat
        character(len=MAX_NAME_LEN), allocatable :: names(:)
        integer :: created, unit
        call make_directories(root//'/a/b/c', stat, created)
        call t%check('make_directories: a/b/c and the root made, created = 4', &
                     all([stat%ok(), created == 4, is_directory(root//'/a/b/c')]))
        call make_directories(root//'/a/b/c', stat, created)
        call t%check('make_directories: an existing directory is success, created = 0', &
                     stat%ok() .and. created == 0)
        open (newunit=unit, file=root//'/a/file', status='replace')
        close (unit)
        call make_directories(root//'/a/file/x/y', stat, created)
        call t%check('make_directories: a file in the way fails with STATUS_IO naming it, '// &
                     'nothing made', all([stat%code == STATUS_IO, index(stat%message, 'file') &
                     > 0, created == 0, .not. file_exists(root//'/a/file/x')]))
        call list_directory(root//'/a', names, stat)
        call t%check('list_directory: b and file, not . and ..', stat%ok() .and. &
                     size(names) == 2 .and. any(names == 'b') .and. any(names == 'file'))
        call list_directory(root//'/missing', names, stat)
        call t%check('list_directory: a missing folder fails with STATUS_IO', &
                     stat%code == STATUS_IO .and. size(names) == 0)
        call remove_directory(root//'/a/b')
        call t%check('remove_directory: a non-empty one stays', is_directory(root//'/a/b'))
        call remove_directory(root//'/a/b/c')
        call t%check('remove_directory: an empty one goes', .not. file_exists(root//'/a/b/c'))
        call t%check('is_directory: a file is none', .not. is_directory(root//'/a/file'))
        call t%check('is_real_directory: a directory, not a file', &
                     all([is_real_directory(root//'/a'), &
                          .not. is_real_directory(root//'/a/file')]))
    end subroutine check_directories

    subroutine check_files()
        type(status_t) :: stat
        character(len=256) :: msg
        integer :: unit, ios, handle, exit_status
        character(len=:), allocatable :: first, second
        first = root//'/first.txt'
        second = root//'/second.txt'
        open (newunit=unit, file=first, status='replace', action='write')
        write (unit, '(a)') 'hello'
        call close_output(unit, first, ios, msg)
        call t%check('close_output: the bytes written reached the file', &
                     all([ios == 0, file_exists(first)]))
        open (newunit=unit, file=second, status='replace', action='write')
        write (unit, '(a)') 'old'
        ios = 5
        msg = 'an earlier failure'
        call end_output(unit, second, ios, msg)
        call t%check('end_output: after a failure, closes quietly and keeps it', ios == 5 .and. &
                     msg == 'an earlier failure')
        call rename_file(first, second, stat)
        call t%check('rename_file: replaces the target, the source gone', &
                     all([stat%ok(), .not. file_exists(first), first_line(second) == 'hello']))
        call rename_file(first, second, stat)
        call t%check('rename_file: a missing source fails with STATUS_IO', &
                     stat%code == STATUS_IO)
        call make_link(second, first, stat)
        call t%check('make_link: another name of the same file', &
                     all([stat%ok(), first_line(first) == 'hello']))
        call remove_file(second)
        call t%check('remove_file: one name gone, the other still reads', &
                     all([.not. file_exists(second), first_line(first) == 'hello']))
        call execute_command_line('chmod 640 '//first//' && touch '//second//' && chmod 600 ' &
                                  //second)
        call copy_mode(first, second)
        call execute_command_line('test "$(stat -c %a '//second//')" = 640', &
                                  exitstat=exit_status)
        call t%check('copy_mode: the permission bits carried over', exit_status == 0)
        call sync_path(first, stat)
        call t%check('sync_path: a file syncs', stat%ok())
        call sync_path(root//'/missing', stat)
        call t%check('sync_path: a missing path fails with STATUS_IO', stat%code == STATUS_IO)
        call sync_filesystem(root, stat)
        call t%check('sync_filesystem: the file system of the folder syncs', stat%ok())
        call lock_file(root//'/lock', handle, stat)
        call t%check('lock_file: made and locked', &
                     all([stat%ok(), handle >= 0, file_exists(root//'/lock')]))
        call unlock_file(handle)
        call lock_file(root//'/lock', handle, stat)
        call t%check('unlock_file: the lock can be taken again (no wait)', stat%ok())
        call unlock_file(handle)
    end subroutine check_files

    !> Two folders swapped or renamed aside, each keeping its own file.
    subroutine check_replace()
        type(status_t) :: stat
        character(len=:), allocatable :: old, new, current, aside, staged
        integer :: pass
        current = root//'/current'
        aside = root//'/aside'
        staged = root//'/staged'
        call make_folder_with(staged, 'one')
        call replace_directory(staged, current, aside, old, stat)
        call t%check('replace_directory: to a new place, no old folder', &
                     all([stat%ok(), old == '', first_line(current//'/marker') == 'one', &
                     .not. file_exists(staged)]))
        do pass = 1, 2   ! the atomic exchange, then rename aside and in
            call make_folder_with(staged, 'two')
            call replace_directory(staged, current, aside, old, stat, exchange=pass == 1)
            new = first_line(current//'/marker')
            call t%check('replace_directory ('//trim(merge('exchange', 'aside   ', &
                         pass == 1))//'): the new folder in place, the old one at old', &
                         all([stat%ok(), new == 'two', first_line(old//'/marker') == 'one']))
            call remove_tree(old)
            call make_folder_with(staged, 'one')
            call replace_directory(staged, current, aside, old, stat)
            call remove_tree(old)
        end do
        call t%check('can_replace: a folder in a writable parent, not /', &
                     all([can_replace(current, root), .not. can_replace('/', '/')]))
    end subroutine check_replace

    subroutine check_paths()
        call t%check('real_path: ., .. and links resolved to an absolute path', &
                     real_path(root//'/../'//root//'/.') == cwd//'/'//root)
        call t%check('real_path: a missing path comes back as given', &
                     real_path(root//'/missing/x') == root//'/missing/x')
        call t%check('canonical_path: the missing part resolved as written', &
                     canonical_path(root//'/missing/./a/../b//') == cwd//'/'//root//'/missing/b')
    end subroutine check_paths

    subroutine check_processes()
        call t%check('process_id: this process, which is not gone', &
                     all([process_id() > 0, .not. process_gone(process_id())]))
        ! beyond Linux's largest pid_max (2^22)
        call t%check('process_gone: no process 99999999', process_gone(99999999))
        call t%check('process_gone: pid <= 0 is never gone', &
                     all([.not. process_gone(0), .not. process_gone(-1)]))
    end subroutine check_processes

    !> Armed and disarmed without a signal: the staging folder is left alone.
    subroutine check_signals()
        type(status_t) :: stat
        call make_folder_with(root//'/staging', 'kept')
        call cleanup_on_signal(root//'/staging', 0, stat)
        call hold_signals()
        call end_cleanup_on_signal()
        call t%check('cleanup_on_signal, hold_signals, end_cleanup_on_signal: no signal, '// &
                     'nothing removed', all([stat%ok(), first_line(root//'/staging/marker') &
                     == 'kept']))
        call cleanup_on_signal(repeat('x', 5000), 0, stat)
        call end_cleanup_on_signal()
        call t%check('cleanup_on_signal: a path too long is refused', stat%code == STATUS_IO)
    end subroutine check_signals

    subroutine make_folder_with(path, text)
        character(len=*), intent(in) :: path, text
        type(status_t) :: stat
        integer :: unit
        call make_directories(path, stat)
        open (newunit=unit, file=path//'/marker', status='replace', action='write')
        write (unit, '(a)') text
        close (unit)
    end subroutine make_folder_with

    function first_line(path) result(text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text
        character(len=256) :: line
        integer :: unit, ios
        text = '(none)'
        open (newunit=unit, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        read (unit, '(a)', iostat=ios) line
        close (unit)
        if (ios == 0) text = trim(line)
    end function first_line
end program test_filesystem
