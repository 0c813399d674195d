! SPDX-License-Identifier: MIT
!> Outputs appear whole or not at all: files are written into a private staging folder
!> inside the output directory and renamed into place only once all of them are complete.
!> Staging inside the target keeps every rename on one file system, hence atomic per file.
module output_stage
    use status, only: status_t, STATUS_IO
    use filesystem, only: make_directories, rename_file, remove_file, remove_directory, &
                          process_id, process_gone, is_real_directory, list_directory, &
                          MAX_NAME_LEN
    implicit none
    private

    character(len=*), parameter :: STAGING_PREFIX = '.nceig-partial-'

    !> A file name registered through `path`.
    type :: staged_name_t
        character(len=:), allocatable :: name
    end type staged_name_t

    !> One staging area. Use: begin, write each file to path(name), then commit, or abort
    !> on any failure. A run that dies in between leaves only the hidden staging folder.
    !> Register the completion marker (e.g. summary.json) last: see commit.
    type, public :: output_stage_t
        character(len=:), allocatable :: directory   !! final output directory
        character(len=:), allocatable :: staging     !! <directory>/.nceig-partial-<pid>
        type(staged_name_t), allocatable :: names(:) !! files registered through path()
        logical :: active = .false.                  !! between begin and commit/abort
    contains
        procedure :: begin => output_stage_begin
        procedure :: path => output_stage_path
        procedure :: commit => output_stage_commit
        procedure :: abort => output_stage_abort
        procedure :: file_names => output_stage_file_names
        procedure :: scratch => output_stage_scratch
    end type output_stage_t

contains

    !> Create `directory` (and its parents) and an empty staging folder inside it, after
    !> removing the staging folders that runs killed earlier left there (see
    !> remove_stale_staging). Fails with STATUS_IO naming the directory when it cannot be
    !> created or written.
    subroutine output_stage_begin(this, directory, stat)
        class(output_stage_t), intent(inout) :: this
        character(len=*), intent(in) :: directory
        type(status_t), intent(out) :: stat
        character(len=32) :: pid_text

        if (this%active) call this%abort()
        this%directory = trim(directory)
        if (allocated(this%names)) deallocate (this%names)
        allocate (this%names(0))
        call make_directories(this%directory, stat)
        if (.not. stat%ok()) then
            call stat%fail(STATUS_IO, 'output directory '//this%directory//': ' &
                           //stat%message)
            return
        end if
        call remove_stale_staging(this%directory)
        write (pid_text, '(i0)') process_id()
        this%staging = this%directory//'/'//STAGING_PREFIX//trim(pid_text)
        call make_directories(this%staging, stat)
        if (.not. stat%ok()) then
            call stat%fail(STATUS_IO, 'output directory '//this%directory// &
                           ' is not writable: '//stat%message)
            return
        end if
        this%active = .true.
    end subroutine output_stage_begin

    !> Remove the staging folders in `directory` whose process is gone: a run killed (e.g.
    !> SIGKILL) between begin and commit leaves <directory>/.nceig-partial-<pid> behind.
    !> A folder named after our own pid is also stale (we have not made ours yet); those of
    !> live processes, other names, and links are left alone. Best effort: what cannot be
    !> removed stays. Process identifiers are those of this machine: see README (Nothing
    !> lost) about output directories shared between machines.
    subroutine remove_stale_staging(directory)
        character(len=*), intent(in) :: directory
        character(len=MAX_NAME_LEN), allocatable :: names(:), files(:)
        character(len=:), allocatable :: folder, digits
        integer :: i, j, pid

        call list_directory(directory, names)
        do i = 1, size(names)
            if (index(names(i), STAGING_PREFIX) /= 1) cycle
            digits = trim(names(i)(len(STAGING_PREFIX) + 1:))
            ! pids are below 2^22 on Linux: 9 digits cannot overflow an integer.
            if (len(digits) == 0 .or. len(digits) > 9) cycle
            if (verify(digits, '0123456789') /= 0) cycle
            read (digits, '(i9)') pid
            ! our own pid's folder is stale by definition; another pid's only if it is gone
            if (pid /= process_id()) then
                if (.not. process_gone(pid)) cycle
            end if
            folder = directory//'/'//trim(names(i))
            ! Not through a link: its target is not ours to empty.
            if (.not. is_real_directory(folder)) cycle
            call list_directory(folder, files)
            do j = 1, size(files)
                call remove_file(folder//'/'//trim(files(j)))
            end do
            call remove_directory(folder)
        end do
    end subroutine remove_stale_staging

    !> Where to write the output file `name` while staging, registering it for commit.
    !> Before begin (or after commit/abort) this is simply <directory>/<name> or <name>.
    function output_stage_path(this, name) result(file_path)
        class(output_stage_t), intent(inout) :: this
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: file_path
        type(staged_name_t), allocatable :: grown(:)
        integer :: i

        if (.not. this%active) then
            file_path = trim(name)
            if (allocated(this%directory)) file_path = this%directory//'/'//trim(name)
            return
        end if
        file_path = this%staging//'/'//trim(name)
        do i = 1, size(this%names)
            if (this%names(i)%name == trim(name)) return
        end do
        ! Grown by hand: gfortran 12 leaks the allocatable components of the temporaries
        ! of [this%names, staged_name_t(name)] (LeakSanitizer).
        allocate (grown(size(this%names) + 1))
        do i = 1, size(this%names)
            call move_alloc(this%names(i)%name, grown(i)%name)
        end do
        grown(size(grown))%name = trim(name)
        call move_alloc(grown, this%names)
    end function output_stage_path

    !> Move every staged file into the output directory, replacing older files of the same
    !> name, and remove the staging folder. On failure the remaining staged files are
    !> deleted and STATUS_IO names the file.
    !> Each rename is atomic, the set is not: the last file registered is the set's
    !> completion marker. Its older copy is deleted before anything moves and it moves last,
    !> so a commit cut short (killed) leaves no marker next to a mixed set of files.
    subroutine output_stage_commit(this, stat)
        class(output_stage_t), intent(inout) :: this
        type(status_t), intent(out) :: stat
        integer :: i

        if (.not. this%active) then
            call stat%fail(STATUS_IO, 'output stage: commit without begin')
            return
        end if
        if (size(this%names) > 0) &
            call remove_file(this%directory//'/'//this%names(size(this%names))%name)
        do i = 1, size(this%names)
            call rename_file(this%staging//'/'//this%names(i)%name, &
                             this%directory//'/'//this%names(i)%name, stat)
            if (.not. stat%ok()) then
                call this%abort()
                return
            end if
        end do
        call remove_directory(this%staging)
        this%active = .false.
    end subroutine output_stage_commit

    !> Where to put a scratch file while staging (a plot script, a picture not yet known to
    !> be drawn): in the staging folder, NOT part of the set; remove it before the commit, or
    !> register it with path() once it is complete.
    function output_stage_scratch(this, name) result(file_path)
        class(output_stage_t), intent(in) :: this
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: file_path
        file_path = this%staging//'/'//trim(name)
    end function output_stage_scratch

    !> The names registered so far, in order (one per element, blank-padded to `length`).
    pure function output_stage_file_names(this, length) result(names)
        class(output_stage_t), intent(in) :: this
        integer, intent(in) :: length
        character(len=length), allocatable :: names(:)
        integer :: i
        allocate (names(0))
        if (.not. allocated(this%names)) return
        deallocate (names)
        allocate (names(size(this%names)))
        do i = 1, size(this%names)
            names(i) = this%names(i)%name
        end do
    end function output_stage_file_names

    !> Delete the staged files and the staging folder; files already in the output
    !> directory are left alone. Safe to call twice and after a failed begin.
    subroutine output_stage_abort(this)
        class(output_stage_t), intent(inout) :: this
        integer :: i

        if (.not. this%active) return
        do i = 1, size(this%names)
            call remove_file(this%staging//'/'//this%names(i)%name)
        end do
        call remove_directory(this%staging)
        this%active = .false.
    end subroutine output_stage_abort
end module output_stage
