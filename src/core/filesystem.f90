! SPDX-License-Identifier: MIT
!> Thin wrappers of the POSIX calls the output code needs (mkdir, rename, unlink, rmdir,
!> access, getpid, kill(pid, 0), readdir), which standard Fortran lacks. errno, stat(),
!> readdir() and ESRCH are reached through filesystem_c.c because none can be bound
!> portably from Fortran.
module filesystem
    use iso_c_binding, only: c_int, c_char, c_size_t, c_ptr, c_null_char, c_f_pointer, &
                             c_associated
    use status, only: status_t, STATUS_IO
    implicit none
    private
    public :: make_directories, rename_file, remove_file, remove_directory, file_exists, &
              is_directory, process_id, is_real_directory, process_gone, list_directory
    integer, parameter, public :: MAX_NAME_LEN = 255   !! NAME_MAX of Linux file systems

    integer(c_int), parameter :: DIRECTORY_MODE = int(o'777', c_int)  !! the umask trims it
    integer(c_int), parameter :: ACCESS_EXISTS = 0_c_int              !! F_OK of <unistd.h>

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
            integer(c_int) :: length           ! -1: no more entries, -2: name too long
        end function c_next_entry
    end interface

contains

    !> Create directory `path` and any missing parents, like `mkdir -p`. Succeeds when the
    !> directory exists already; fails with STATUS_IO naming the part that could not be
    !> made (e.g. because a regular file is in the way) and the system's reason.
    subroutine make_directories(path, stat)
        character(len=*), intent(in) :: path
        type(status_t), intent(out) :: stat
        character(len=:), allocatable :: full
        integer :: i

        full = trim(path)
        if (len(full) == 0) then
            call stat%fail(STATUS_IO, 'cannot create a directory with an empty name')
            return
        end if
        do i = 2, len(full)
            ! Each '/' ends a parent; a doubled '/' repeats one, which is harmless.
            if (full(i:i) == '/') call make_one(full(:i - 1))
            if (.not. stat%ok()) return
        end do
        call make_one(full)

    contains

        subroutine make_one(directory)
            character(len=*), intent(in) :: directory
            integer(c_int) :: errnum
            character(len=:), allocatable :: reason
            if (is_directory(directory)) return
            if (c_mkdir(c_path(directory), DIRECTORY_MODE) == 0) return
            errnum = c_errno()
            if (is_directory(directory)) return   ! made meanwhile by another process
            reason = error_text(errnum)
            ! 'File exists' would puzzle: say what is in the way.
            if (file_exists(directory)) reason = 'a file of that name is in the way'
            if (directory == full) then
                call stat%fail(STATUS_IO, 'cannot create directory '//directory//': '//reason)
            else
                call stat%fail(STATUS_IO, 'cannot create directory '//directory//' (for ' &
                               //full//'): '//reason)
            end if
        end subroutine make_one
    end subroutine make_directories

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

    !> Names of the entries of directory `path` but '.' and '..', in no particular order;
    !> none when it cannot be read. Best effort, like remove_file: names longer than
    !> MAX_NAME_LEN are left out.
    subroutine list_directory(path, names)
        character(len=*), intent(in) :: path
        character(len=MAX_NAME_LEN), allocatable, intent(out) :: names(:)
        character(len=MAX_NAME_LEN), allocatable :: grown(:)
        character(kind=c_char) :: name(MAX_NAME_LEN)
        type(c_ptr) :: handle
        integer :: n, length, i

        allocate (names(16))
        n = 0
        handle = c_open_directory(c_path(path))
        if (.not. c_associated(handle)) then
            names = names(:0)
            return
        end if
        do
            length = c_next_entry(handle, name, int(MAX_NAME_LEN, c_int))
            if (length == -1) exit
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
