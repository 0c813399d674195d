! SPDX-License-Identifier: MIT
!> Thin wrappers of the POSIX calls the output code needs (mkdir, rename, unlink, rmdir,
!> access, getpid, kill(pid, 0), readdir, link, fsync, flock, renameat2), which standard
!> Fortran lacks, and the closing of output units that checks the bytes reached the disk.
!> errno, stat(), readdir(), ESRCH, flock and signal handlers are reached through
!> filesystem_c.c because none can be bound portably from Fortran.
module filesystem
    use iso_c_binding, only: c_int, c_char, c_size_t, c_ptr, c_null_char, c_f_pointer, &
                             c_associated, c_long_long
    use status, only: status_t, STATUS_IO
    use strings, only: from_c_chars
    implicit none
    private
    public :: make_directories, rename_file, remove_file, remove_directory, file_exists, &
              is_directory, process_id, is_real_directory, process_gone, list_directory
    public :: close_output, end_output, sync_path, sync_filesystem, replace_directory, make_link, &
              copy_mode, remove_tree, lock_file, unlock_file, real_path, can_replace, &
              canonical_path, may_write, link_target
    public :: cleanup_on_signal, hold_signals, end_cleanup_on_signal
    integer, parameter, public :: MAX_NAME_LEN = 255   !! NAME_MAX of Linux file systems

    integer(c_int), parameter :: DIRECTORY_MODE = int(o'777', c_int)  !! the umask trims it
    integer(c_int), parameter :: ACCESS_EXISTS = 0_c_int              !! F_OK of <unistd.h>
    integer, parameter :: EIO = 5   !! errno of <errno.h>: the iostat of a short file
    integer, parameter :: EBUSY = 16, EXDEV = 18   !! errno (Linux) of renaming a mount point
    integer, parameter :: MAX_PATH_LEN = 4096   !! PATH_MAX of Linux

    interface
        function c_mkdir(path, mode) bind(C, name='mkdir') result(status)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: mode      ! mode_t: unsigned int on Linux
            integer(c_int) :: status
        end function c_mkdir

        function c_rename(from, to) bind(C, name='rename') result(status)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: from(*), to(*)
            integer(c_int) :: status
        end function c_rename

        function c_unlink(path) bind(C, name='unlink') result(status)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: status
        end function c_unlink

        function c_rmdir(path) bind(C, name='rmdir') result(status)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: status
        end function c_rmdir

        function c_access(path, mode) bind(C, name='access') result(status)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: mode
            integer(c_int) :: status
        end function c_access

        function c_getpid() bind(C, name='getpid') result(pid)
            import :: c_int
            integer(c_int) :: pid              ! pid_t: int on Linux
        end function c_getpid

        function c_strerror(errnum) bind(C, name='strerror') result(text)
            import :: c_int, c_ptr
            integer(c_int), value :: errnum
            type(c_ptr) :: text                ! char *, owned by the C library
        end function c_strerror

        function c_strlen(text) bind(C, name='strlen') result(length)
            import :: c_ptr, c_size_t
            type(c_ptr), value :: text
            integer(c_size_t) :: length
        end function c_strlen

        function c_errno() bind(C, name='nceig_errno') result(errnum)
            import :: c_int
            integer(c_int) :: errnum
        end function c_errno

        function c_is_directory(path) bind(C, name='nceig_is_directory') result(answer)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: answer
        end function c_is_directory

        function c_is_real_directory(path) bind(C, name='nceig_is_real_directory') &
                result(answer)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: answer
        end function c_is_real_directory

        function c_process_gone(pid) bind(C, name='nceig_process_gone') result(answer)
            import :: c_int
            integer(c_int), value :: pid
            integer(c_int) :: answer
        end function c_process_gone

        function c_open_directory(path) bind(C, name='nceig_open_directory') result(handle)
            import :: c_char, c_ptr
            character(kind=c_char), intent(in) :: path(*)
            type(c_ptr) :: handle              ! DIR *, NULL on failure
        end function c_open_directory

        subroutine c_close_directory(handle) bind(C, name='nceig_close_directory')
            import :: c_ptr
            type(c_ptr), value :: handle
        end subroutine c_close_directory

        function c_next_entry(handle, name, capacity) bind(C, name='nceig_next_entry') &
                result(length)
            import :: c_ptr, c_char, c_int
            type(c_ptr), value :: handle
            character(kind=c_char), intent(out) :: name(*)
            integer(c_int), value :: capacity
            integer(c_int) :: length           ! -1: no more entries, -2: name too long, -3: errno
        end function c_next_entry

        function c_check_written(path, expected, actual) bind(C, name='nceig_check_written') &
                result(status)
            import :: c_int, c_char, c_long_long
            character(kind=c_char), intent(in) :: path(*)
            integer(c_long_long), value :: expected
            integer(c_long_long), intent(out) :: actual
            integer(c_int) :: status           ! 0, -1 (errno), -2 (size differs)
        end function c_check_written

        function c_sync_filesystem(path) bind(C, name='nceig_sync_filesystem') result(status)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: status
        end function c_sync_filesystem

        function c_sync_path(path) bind(C, name='nceig_sync_path') result(status)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: status
        end function c_sync_path

        function c_replace_directory(from, to, aside, exchange) &
                bind(C, name='nceig_replace_directory') result(status)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: from(*), to(*), aside(*)
            integer(c_int), value :: exchange  ! 0: do not try RENAME_EXCHANGE
            integer(c_int) :: status           ! 1 swapped, 2 set aside, 0 renamed, -1 (errno)
        end function c_replace_directory

        function c_can_replace(path, parent) bind(C, name='nceig_can_replace') result(answer)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*), parent(*)
            integer(c_int) :: answer
        end function c_can_replace

        function c_link_target(path, buffer, capacity) bind(C, name='nceig_link_target') &
                result(length)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            character(kind=c_char), intent(out) :: buffer(*)
            integer(c_int), value :: capacity
            integer(c_int) :: length           ! -1: not a link
        end function c_link_target

        function c_may_write(path) bind(C, name='nceig_may_write') result(answer)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: answer
        end function c_may_write

        function c_link(from, to) bind(C, name='nceig_link') result(status)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: from(*), to(*)
            integer(c_int) :: status
        end function c_link

        subroutine c_copy_mode(from, to) bind(C, name='nceig_copy_mode')
            import :: c_char
            character(kind=c_char), intent(in) :: from(*), to(*)
        end subroutine c_copy_mode

        subroutine c_remove_tree(path) bind(C, name='nceig_remove_tree')
            import :: c_char
            character(kind=c_char), intent(in) :: path(*)
        end subroutine c_remove_tree

        function c_lock(path) bind(C, name='nceig_lock') result(handle)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: handle           ! file descriptor, -1 (errno)
        end function c_lock

        subroutine c_unlock(handle) bind(C, name='nceig_unlock')
            import :: c_int
            integer(c_int), value :: handle
        end subroutine c_unlock

        function c_real_path(path, buffer, capacity) bind(C, name='nceig_real_path') &
                result(length)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            character(kind=c_char), intent(out) :: buffer(*)
            integer(c_int), value :: capacity
            integer(c_int) :: length           ! -1 on failure
        end function c_real_path

        function c_cleanup_arm(path, levels) bind(C, name='nceig_cleanup_arm') result(status)
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: levels
            integer(c_int) :: status
        end function c_cleanup_arm

        subroutine c_cleanup_hold() bind(C, name='nceig_cleanup_hold')
        end subroutine c_cleanup_hold

        subroutine c_cleanup_disarm() bind(C, name='nceig_cleanup_disarm')
        end subroutine c_cleanup_disarm
    end interface

contains

    !> Create directory `path` and any missing parents, like `mkdir -p`. Succeeds when the
    !> directory exists already; fails with STATUS_IO naming the part that could not be
    !> made (e.g. because a regular file is in the way, or the path is too long) and the
    !> system's reason, after removing the directories this call made: a failure leaves
    !> nothing behind. `created`: how many of the last components of `path` this call made.
    subroutine make_directories(path, stat, created)
        character(len=*), intent(in) :: path
        type(status_t), intent(out) :: stat
        integer, intent(out), optional :: created
        character(len=:), allocatable :: full
        integer, allocatable :: made(:)   !! ends of the prefixes made, shortest first
        integer :: i

        if (present(created)) created = 0
        full = trim(path)
        if (len(full) == 0) then
            call stat%fail(STATUS_IO, 'cannot create a directory with an empty name')
            return
        end if
        allocate (made(0))
        do i = 2, len(full)
            ! Each '/' ends a parent; a doubled '/' repeats one, which is harmless.
            if (full(i:i) == '/') call make_one(full(:i - 1), i - 1)
            if (.not. stat%ok()) exit
        end do
        if (stat%ok()) call make_one(full, len(full))
        if (.not. stat%ok()) then
            do i = size(made), 1, -1
                call remove_directory(full(:made(i)))
            end do
            return
        end if
        if (present(created)) created = size(made)

    contains

        subroutine make_one(directory, last)
            character(len=*), intent(in) :: directory
            integer, intent(in) :: last
            integer(c_int) :: errnum
            character(len=:), allocatable :: reason
            if (is_directory(directory)) return
            if (c_mkdir(c_path(directory), DIRECTORY_MODE) == 0) then
                made = [made, last]
                return
            end if
            errnum = c_errno()
            if (is_directory(directory)) return   ! made meanwhile by another process
            reason = error_text(errnum)
            ! 'File exists' would puzzle: say what is in the way.
            if (file_exists(directory)) reason = 'a file of that name is in the way'
            if (directory == full) then
                call stat%fail(STATUS_IO, 'cannot create directory '//directory//': '//reason)
            else
                call stat%fail(STATUS_IO, 'cannot create directory '//short(directory)// &
                               ' (for '//short(full)//'): '//reason)
            end if
        end subroutine make_one
    end subroutine make_directories

    !> `path` shortened for a one-line message: its start and end around '...'.
    pure function short(path) result(text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text
        integer, parameter :: KEEP = 60
        if (len(path) <= 2*KEEP + 3) then
            text = path
        else
            text = path(:KEEP)//'...'//path(len(path) - KEEP + 1:)
        end if
    end function short

    !> Close `unit`, an output just written to `path`, and check that the file holds as many
    !> bytes as were written (INQUIRE SIZE, taken before the close). libgfortran 12 drops a
    !> failed write(2) (ENOSPC, EIO) when it flushes its buffer, even at CLOSE, so the iostat
    !> of WRITE and CLOSE cannot be trusted alone. Errors found only when the data go to the
    !> disk are reported by sync_filesystem, before the commit.
    !> `ios` is 0 on success, else non-zero with `msg` saying why, as an iostat would.
    subroutine close_output(unit, path, ios, msg)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: path
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer(c_long_long) :: expected, actual
        integer :: status

        inquire (unit=unit, size=expected, iostat=ios, iomsg=msg)
        if (ios /= 0) then
            close (unit, iostat=status)
            return
        end if
        close (unit, iostat=ios, iomsg=msg)
        if (ios /= 0) then
            ! libgfortran keeps a unit whose final flush failed (ENOSPC) connected: a second
            ! close frees it (closing an unconnected unit is a no-op)
            close (unit, iostat=status)
            return
        end if
        status = c_check_written(c_path(path), expected, actual)
        if (status == -1) then
            ios = c_errno()
            if (ios == 0) ios = EIO
            msg = error_text(int(ios, c_int))
        else if (status == -2) then
            ios = EIO
            write (msg, '(a, i0, a, i0, a)') 'the file holds ', actual, ' of the ', expected, &
                ' bytes written (disk full, or over the file size limit?)'
        end if
    end subroutine close_output

    !> Close `unit`, written to `path`: checked by close_output while `ios` is 0; after a
    !> failed write (`ios` non-zero) closed quietly, `ios` and `msg` keeping that failure.
    subroutine end_output(unit, path, ios, msg)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: path
        integer, intent(inout) :: ios
        character(len=*), intent(inout) :: msg
        integer :: ignored
        if (ios /= 0) then
            close (unit, iostat=ignored)
        else
            call close_output(unit, path, ios, msg)
        end if
    end subroutine end_output

    !> Write the file system holding `path` to disk (syncfs on Linux); fails with STATUS_IO
    !> when the system reports a write error there.
    subroutine sync_filesystem(path, stat)
        character(len=*), intent(in) :: path
        type(status_t), intent(out) :: stat
        if (c_sync_filesystem(c_path(path)) /= 0) &
            call stat%fail(STATUS_IO, 'cannot write '//short(path)//' to disk: ' &
                           //error_text(c_errno()))
    end subroutine sync_filesystem

    !> fsync the file or directory `path` (a directory: to make the renames in it durable).
    subroutine sync_path(path, stat)
        character(len=*), intent(in) :: path
        type(status_t), intent(out) :: stat
        if (c_sync_path(c_path(path)) /= 0) &
            call stat%fail(STATUS_IO, 'cannot sync '//short(path)//': '//error_text(c_errno()))
    end subroutine sync_path

    !> Put directory `from` at `to`. When `to` exists, the two are swapped in one atomic
    !> step (Linux renameat2 RENAME_EXCHANGE) and `old` is `from`, which now names the old
    !> directory; where the file system cannot swap (NFS: EINVAL), or when `exchange` is
    !> false (tests), `to` is renamed `aside` first, then `from` renamed `to`: `old` is
    !> `aside`. When `to` did not exist, `from` is renamed and `old` is ''.
    subroutine replace_directory(from, to, aside, old, stat, exchange)
        character(len=*), intent(in) :: from, to, aside
        character(len=:), allocatable, intent(out) :: old
        type(status_t), intent(out) :: stat
        logical, intent(in), optional :: exchange
        integer(c_int) :: status, try_exchange, errnum
        character(len=:), allocatable :: hint
        try_exchange = 1
        if (present(exchange)) try_exchange = merge(1, 0, exchange)
        status = c_replace_directory(c_path(from), c_path(to), c_path(aside), try_exchange)
        select case (status)
        case (1)
            old = from
        case (2)
            old = aside
        case (0)
            old = ''
        case default
            old = ''
            errnum = c_errno()
            hint = ''
            if (errnum == EBUSY .or. errnum == EXDEV) &
                hint = ' (a mount point? name a directory inside it)'
            call stat%fail(STATUS_IO, 'cannot put '//short(from)//' in place of '//short(to) &
                           //': '//error_text(errnum)//hint)
        end select
    end subroutine replace_directory

    !> True when directory `path` can be replaced by a rename in `parent`: not a mount point
    !> nor '/', and `parent` writable.
    logical function can_replace(path, parent)
        character(len=*), intent(in) :: path, parent
        can_replace = c_can_replace(c_path(path), c_path(parent)) /= 0
    end function can_replace

    !> Make `to` another name (hard link) of the file `from`.
    subroutine make_link(from, to, stat)
        character(len=*), intent(in) :: from, to
        type(status_t), intent(out) :: stat
        if (c_link(c_path(from), c_path(to)) /= 0) &
            call stat%fail(STATUS_IO, 'cannot link '//short(from)//' as '//short(to)//': ' &
                           //error_text(c_errno()))
    end subroutine make_link

    !> Give `to` the permission bits of `from`. Best effort.
    subroutine copy_mode(from, to)
        character(len=*), intent(in) :: from, to
        call c_copy_mode(c_path(from), c_path(to))
    end subroutine copy_mode

    !> Remove `path` with everything below it, like `rm -r`, never following a link.
    !> Best effort, like remove_file.
    subroutine remove_tree(path)
        character(len=*), intent(in) :: path
        call c_remove_tree(c_path(path))
    end subroutine remove_tree

    !> Take an exclusive lock (flock) on file `path`, created if missing, waiting while
    !> another process holds it; `handle` is for unlock_file. The lock ends at process exit.
    subroutine lock_file(path, handle, stat)
        character(len=*), intent(in) :: path
        integer, intent(out) :: handle
        type(status_t), intent(out) :: stat
        handle = int(c_lock(c_path(path)))
        if (handle < 0) call stat%fail(STATUS_IO, 'cannot lock '//short(path)//': ' &
                                       //error_text(c_errno()))
    end subroutine lock_file

    subroutine unlock_file(handle)
        integer, intent(in) :: handle
        call c_unlock(int(handle, c_int))
    end subroutine unlock_file

    !> The absolute path of `path` with links resolved; `path` itself when that fails.
    function real_path(path) result(resolved)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: resolved
        character(kind=c_char) :: buffer(MAX_PATH_LEN)
        integer :: length
        length = int(c_real_path(c_path(path), buffer, int(MAX_PATH_LEN, c_int)))
        if (length < 0) then
            resolved = trim(path)
            return
        end if
        resolved = from_c_chars(buffer, length)
    end function real_path

    !> The absolute path of `path` with links, '.', '..' and repeated '/'
    !> resolved: realpath where it exists, else that of its nearest existing ancestor
    !> followed by the rest, resolved as written. A link to nothing yet (dangling) is
    !> followed too, to the path it names (as the kernel would, at most 40 links deep), so
    !> that a directory made there leaves the link a link.
    recursive function canonical_path(path, depth) result(canonical)
        character(len=*), intent(in) :: path
        integer, intent(in), optional :: depth   !! links followed so far (internal)
        character(len=:), allocatable :: canonical
        character(len=:), allocatable :: rest, last, up, target
        integer :: slash, links
        rest = path
        links = 0
        if (present(depth)) links = depth
        do while (len(rest) > 1)
            if (rest(len(rest):) /= '/') exit
            rest = rest(:len(rest) - 1)
        end do
        if (len(rest) == 0) rest = '.'
        if (file_exists(rest) .or. rest == '/') then
            canonical = real_path(rest)
            if (canonical(1:1) == '/') return
        end if
        slash = index(rest, '/', back=.true.)
        target = link_target(rest)
        if (len(target) > 0 .and. links < 40) then
            if (target(1:1) /= '/' .and. slash > 0) target = rest(:slash)//target
            canonical = canonical_path(target, links + 1)
            return
        end if
        last = rest(slash + 1:)
        if (slash == 0) then
            up = real_path('.')
        else if (slash == 1) then
            up = '/'
        else
            up = canonical_path(rest(:slash - 1))
        end if
        select case (last)
        case ('', '.')
            canonical = up
        case ('..')
            slash = index(up, '/', back=.true.)
            canonical = up(:max(slash - 1, 1))
        case default
            canonical = up//'/'//last
            if (up == '/') canonical = '/'//last
        end select
    end function canonical_path

    !> The target of the symbolic link `path` as stored in the link; '' when `path` is none.
    function link_target(path) result(target)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: target
        character(kind=c_char) :: buffer(MAX_PATH_LEN)
        integer :: length
        length = int(c_link_target(c_path(path), buffer, int(MAX_PATH_LEN, c_int)))
        target = ''
        if (length > 0) target = from_c_chars(buffer, length)
    end function link_target

    !> Whether `path` has a write permission bit and the caller may write it (a directory
    !> made read-only with chmod a-w is read-only for root too).
    logical function may_write(path)
        character(len=*), intent(in) :: path
        may_write = c_may_write(c_path(path)) /= 0
    end function may_write

    !> Until end_cleanup_on_signal, SIGTERM, SIGINT, SIGHUP and SIGXCPU remove the staging folder
    !> `staging` (its files, then itself) and the last `created_levels` directories of its
    !> parent, then end the process by that signal (see filesystem_c.c).
    subroutine cleanup_on_signal(staging, created_levels, stat)
        character(len=*), intent(in) :: staging
        integer, intent(in) :: created_levels
        type(status_t), intent(out) :: stat
        if (c_cleanup_arm(c_path(staging), int(created_levels, c_int)) /= 0) &
            call stat%fail(STATUS_IO, 'staging folder path too long: '//short(staging))
    end subroutine cleanup_on_signal

    !> From now until end_cleanup_on_signal, a signal only waits (the commit runs on).
    subroutine hold_signals()
        call c_cleanup_hold()
    end subroutine hold_signals

    !> Restore the handlers found at cleanup_on_signal; a signal held meanwhile is raised
    !> now and ends the process.
    subroutine end_cleanup_on_signal()
        call c_cleanup_disarm()
    end subroutine end_cleanup_on_signal

    !> Rename `from` to `to`, replacing `to` if it is a file; atomic within one file system.
    subroutine rename_file(from, to, stat)
        character(len=*), intent(in) :: from, to
        type(status_t), intent(out) :: stat
        if (c_rename(c_path(from), c_path(to)) /= 0) then
            call stat%fail(STATUS_IO, 'cannot rename '//trim(from)//' to '//trim(to)//': ' &
                           //error_text(c_errno()))
        end if
    end subroutine rename_file

    !> Delete file `path` if it exists. Best effort: used only to clean up after a failure,
    !> when the first error is the one worth reporting.
    subroutine remove_file(path)
        character(len=*), intent(in) :: path
        integer(c_int) :: ignored
        ignored = c_unlink(c_path(path))
    end subroutine remove_file

    !> Delete directory `path` if it exists and is empty. Best effort, like remove_file.
    subroutine remove_directory(path)
        character(len=*), intent(in) :: path
        integer(c_int) :: ignored
        ignored = c_rmdir(c_path(path))
    end subroutine remove_directory

    !> True when anything (file, directory, ...) exists at `path`.
    logical function file_exists(path)
        character(len=*), intent(in) :: path
        file_exists = c_access(c_path(path), ACCESS_EXISTS) == 0
    end function file_exists

    !> True when `path` is a directory (or a link to one).
    logical function is_directory(path)
        character(len=*), intent(in) :: path
        is_directory = c_is_directory(c_path(path)) /= 0
    end function is_directory

    !> True when `path` is a directory and not a symbolic link to one.
    logical function is_real_directory(path)
        character(len=*), intent(in) :: path
        is_real_directory = c_is_real_directory(c_path(path)) /= 0
    end function is_real_directory

    !> True when no process of identifier `pid` exists (on this machine, in this PID
    !> namespace); false when one does, even of another user, or when `pid` <= 0.
    logical function process_gone(pid)
        integer, intent(in) :: pid
        process_gone = c_process_gone(int(pid, c_int)) /= 0
    end function process_gone

    !> Names of the entries of directory `path` but '.' and '..', in no particular order.
    !> Names longer than MAX_NAME_LEN are left out. With `stat`, a directory that cannot be
    !> opened or read (out of descriptors, no permission) fails with STATUS_IO naming it;
    !> without, the listing is best effort (what was read, possibly nothing).
    subroutine list_directory(path, names, stat)
        character(len=*), intent(in) :: path
        character(len=MAX_NAME_LEN), allocatable, intent(out) :: names(:)
        type(status_t), intent(out), optional :: stat
        character(len=MAX_NAME_LEN), allocatable :: grown(:)
        character(kind=c_char) :: name(MAX_NAME_LEN)
        type(c_ptr) :: handle
        integer :: n, length, i
        integer(c_int) :: errnum

        allocate (names(16))
        n = 0
        handle = c_open_directory(c_path(path))
        if (.not. c_associated(handle)) then
            errnum = c_errno()
            names = names(:0)
            if (present(stat)) call stat%fail(STATUS_IO, 'cannot list directory '//short(path) &
                                              //': '//error_text(errnum))
            return
        end if
        do
            length = c_next_entry(handle, name, int(MAX_NAME_LEN, c_int))
            if (length == -1) exit
            if (length == -3) then
                errnum = c_errno()
                if (present(stat)) call stat%fail(STATUS_IO, 'cannot list directory ' &
                                                  //short(path)//': '//error_text(errnum))
                exit
            end if
            if (length < 0) cycle
            if (n == size(names)) then
                allocate (grown(2*n))
                grown(:n) = names
                call move_alloc(grown, names)
            end if
            n = n + 1
            names(n) = ''
            do i = 1, length
                names(n)(i:i) = name(i)
            end do
        end do
        call c_close_directory(handle)
        names = names(:n)
    end subroutine list_directory

    !> Identifier of this process, to give temporary names no other run can share.
    integer function process_id()
        process_id = int(c_getpid())
    end function process_id

    !> NUL-terminated copy of a Fortran path; trailing blanks are padding, not part of it.
    pure function c_path(path) result(text)
        character(len=*), intent(in) :: path
        character(kind=c_char, len=:), allocatable :: text
        text = trim(path)//c_null_char
    end function c_path

    !> The system's sentence for error number `errnum` ('No such file or directory').
    function error_text(errnum) result(text)
        integer(c_int), intent(in) :: errnum
        character(len=:), allocatable :: text
        type(c_ptr) :: c_text
        character(kind=c_char), pointer :: chars(:)
        integer :: i
        c_text = c_strerror(errnum)
        if (.not. c_associated(c_text)) then
            text = 'unknown error'
            return
        end if
        call c_f_pointer(c_text, chars, [int(c_strlen(c_text))])
        allocate (character(len=size(chars)) :: text)
        do i = 1, size(chars)
            text(i:i) = chars(i)
        end do
    end function error_text
end module filesystem
