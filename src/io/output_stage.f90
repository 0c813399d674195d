! SPDX-License-Identifier: MIT
!> Outputs appear whole or not at all. The files of a run are written into a private staging
!> folder next to the output directory, `<parent>/.<name>.nceig-staging-<pid>` (a name over
!> 220 bytes shortened with a hash, so that this fits NAME_MAX: name_key), and the
!> commit puts that folder in place of the directory in one step (Linux renameat2
!> RENAME_EXCHANGE), then removes the old set. At every instant the output directory holds
!> the previous complete set or the new one: a run that fails, is killed or runs out of disk
!> leaves the previous set as it was. Commits into one directory take turns (flock on
!> `<parent>/.<name>.nceig-lock`), so each final set is one run's.
!>
!> The set is the run's files (summary.json lists them); the output directory is replaced
!> as a whole. What else was in it: the previous set (the files its summary.json lists,
!> summary.json, and the names the caller gives begin as left unlisted by older sets)
!> goes; any other file or link (the user's notes, files of runs older than that) is kept,
!> as a hard link in the new directory, unless the new set has a file of that name. A subdirectory cannot be carried
!> that way: the commit then fails (STATUS_IO), and the previous set stays.
!>
!> The directory is known by its real path (links, '.', '..' resolved), so every spelling
!> of it gets the same staging name, lock and way of commit.
!> An existing directory that cannot be replaced by a rename (a mount point, a parent we
!> may not write) is committed in place instead: staged in
!> `<directory>/.nceig-partial-<pid>`, then, under the lock `<directory>/.nceig-lock`,
!> the old summary.json is deleted, the files renamed in one by one, the old set's other
!> files deleted, and summary.json renamed in last. Each rename is atomic, the set is not:
!> a commit cut short leaves no summary.json (the mark of an incomplete set). The working
!> directory (or one above it) is committed in place too, lest a swap leave the user's shell
!> in a removed directory, but staged and locked in the parent like any other.
module output_stage
    use iso_fortran_env, only: int64
    use status, only: status_t, STATUS_IO
    use filesystem, only: make_directories, rename_file, remove_directory, remove_file, &
                          can_replace, &
                          process_id, process_gone, is_real_directory, is_directory, &
                          file_exists, list_directory, MAX_NAME_LEN, sync_path, &
                          sync_filesystem, replace_directory, make_link, copy_mode, &
                          remove_tree, lock_file, unlock_file, real_path, cleanup_on_signal, &
                          canonical_path, may_write, link_target, &
                          hold_signals, end_cleanup_on_signal
    use text_file, only: read_line
    use strings, only: text_t, append_text, to_string
    implicit none
    private

    character(len=*), parameter :: STAGING_SUFFIX = '.nceig-staging-'
    character(len=*), parameter :: LOCK_SUFFIX = '.nceig-lock'
    !> Where the old directory goes where the file system cannot swap (see commit).
    character(len=*), parameter :: ASIDE_SUFFIX = '.nceig-old-'
    !> Staging folders inside the output directory: of a commit in place, or of nceig before
    !> the directory swap (dropped with the set).
    character(len=*), parameter :: IN_PLACE_PREFIX = '.nceig-partial-'
    character(len=*), parameter :: IN_PLACE_LOCK = '.nceig-lock'
    character(len=*), parameter :: SUMMARY_FILE = 'summary.json'
    !> The longest name key (see name_key): '.'//key//STAGING_SUFFIX//9 digits fits
    !> MAX_NAME_LEN (255) with room to spare.
    integer, parameter :: MAX_KEY_LEN = 220

    !> One staging area. Use: begin, add each file (add gives the path to write it to), then
    !> commit, or abort on any failure. Add the summary (summary.json) last: it lists the
    !> others.
    type, public :: output_stage_t
        character(len=:), allocatable :: directory   !! final output directory
        character(len=:), allocatable :: parent      !! its parent, where staging and lock go
        character(len=:), allocatable :: base        !! its last component
        character(len=:), allocatable :: key         !! base, or its shortened form: name_key
        character(len=:), allocatable :: staging     !! <parent>/.<base>.nceig-staging-<pid>
        character(len=:), allocatable :: aside       !! <parent>/.<base>.nceig-old-<pid>
        type(text_t), allocatable :: names(:) !! files registered through add()
        !> files of older sets that their summary.json did not list (begin's `unlisted_old`)
        type(text_t), allocatable :: unlisted_old(:)
        integer :: created_levels = 0                !! parents of `directory` begin made
        logical :: active = .false.                  !! between begin and commit/abort
        logical :: in_place = .false.                !! commit file by file (see the header)
        logical :: inside = .false.                  !! staging and lock inside `directory`
    contains
        procedure :: begin => output_stage_begin
        procedure :: add => output_stage_add
        procedure :: commit => output_stage_commit
        procedure :: abort => output_stage_abort
        procedure :: file_names => output_stage_file_names
        procedure :: scratch => output_stage_scratch
        procedure :: folder => output_stage_folder
    end type output_stage_t

contains

    !> Create the parents of `directory` if missing and an empty staging folder next to it
    !> (inside it for a commit in place), after removing the staging folders that runs
    !> killed earlier left there (see remove_stale_staging). `directory` itself appears only
    !> at commit. A link to a directory is followed: the directory it names is replaced.
    !> Fails with STATUS_IO naming the directory when it cannot be created or written; then
    !> nothing was created.
    subroutine output_stage_begin(this, directory, stat, unlisted_old)
        class(output_stage_t), intent(inout) :: this
        character(len=*), intent(in) :: directory
        type(status_t), intent(out) :: stat
        !> names an older build wrote into the directory without listing them in its set:
        !> removed with the previous set, never carried over as the user's
        type(text_t), intent(in), optional :: unlisted_old(:)
        character(len=32) :: pid_text
        integer :: slash

        if (this%active) call this%abort()
        ! One real directory, one lock and one staging name, however it is spelt ('out/.',
        ! './out', 'a/../out', a link): runs into two spellings must take turns.
        this%directory = canonical_path(trim(directory))
        if (allocated(this%names)) deallocate (this%names)
        allocate (this%names(0))
        if (allocated(this%unlisted_old)) deallocate (this%unlisted_old)
        allocate (this%unlisted_old(0))
        if (present(unlisted_old)) this%unlisted_old = unlisted_old
        this%created_levels = 0
        slash = index(this%directory, '/', back=.true.)
        this%base = this%directory(slash + 1:)
        if (len(this%base) > MAX_NAME_LEN) then
            call stat%fail(STATUS_IO, 'output directory '//this%directory//': its last ' &
                           //'component has '//to_string(len(this%base))//' bytes, more than ' &
                           //'the '//to_string(MAX_NAME_LEN)//' a file system allows: name ' &
                           //'too long')
            return
        end if
        this%key = name_key(this%base)
        if (slash == 0) then
            this%parent = '.'
        else if (slash == 1) then
            this%parent = '/'
        else
            this%parent = this%directory(:slash - 1)
        end if
        if (file_exists(this%directory)) then
            if (.not. is_directory(this%directory)) then
                call stat%fail(STATUS_IO, 'output directory '//this%directory// &
                               ': a file of that name is in the way')
                return
            end if
            ! A swap could replace it (its parent is what a rename needs): but read-only is
            ! the user's word, as for any directory we may not write.
            if (.not. may_write(this%directory)) then
                call stat%fail(STATUS_IO, 'output directory '//this%directory// &
                               ' is read-only (no write permission): expected a directory '// &
                               'nceig may write (chmod u+w), or another &output directory')
                return
            end if
            this%inside = .not. can_replace(this%directory, this%parent)
            ! A swap would leave the working directory (ours, the user's shell's) a removed one.
            this%in_place = this%inside
            if (.not. this%in_place) this%in_place = holds_working_directory(this%directory)
        else if (len(link_target(this%directory)) > 0) then
            ! canonical_path follows a link to nothing yet; one left is a loop of links
            call stat%fail(STATUS_IO, 'output directory '//this%directory// &
                           ': a loop of symbolic links (or more than 40 in a row)')
            return
        else
            this%inside = .false.
            this%in_place = .false.
        end if
        write (pid_text, '(i0)') process_id()
        if (this%inside) then
            this%staging = join(this%directory, IN_PLACE_PREFIX//trim(pid_text))
        else
            this%staging = join(this%parent, '.'//this%key//STAGING_SUFFIX//trim(pid_text))
        end if
        this%aside = join(this%parent, '.'//this%key//ASIDE_SUFFIX//trim(pid_text))
        ! Armed before anything is made, so that no signal finds it unregistered.
        call cleanup_on_signal(this%staging, 0, stat)
        if (stat%ok() .and. .not. this%inside) &
            call make_directories(this%parent, stat, this%created_levels)
        if (.not. stat%ok()) then
            call end_cleanup_on_signal()
            call stat%fail(STATUS_IO, 'output directory '//this%directory//': '//stat%message)
            return
        end if
        call cleanup_on_signal(this%staging, this%created_levels, stat)
        if (this%inside) then
            call remove_stale_staging(this%directory, IN_PLACE_PREFIX)
        else
            call remove_stale_staging(this%parent, '.'//this%key//ASIDE_SUFFIX, this%directory)
            call remove_stale_staging(this%parent, '.'//this%key//STAGING_SUFFIX)
        end if
        if (stat%ok()) call make_directories(this%staging, stat)
        if (.not. stat%ok()) then
            call end_cleanup_on_signal()
            call remove_directory(this%staging)
            call remove_created_parents(this)
            call stat%fail(STATUS_IO, 'output directory '//this%directory// &
                           ' is not writable: '//stat%message)
            return
        end if
        this%active = .true.
    end subroutine output_stage_begin

    !> True when the working directory is `directory` or below it: what '.' or '..' names.
    logical function holds_working_directory(directory)
        character(len=*), intent(in) :: directory
        character(len=:), allocatable :: here
        here = real_path('.')
        holds_working_directory = here == directory .or. directory == '/' .or. &
                                  index(here//'/', directory//'/') == 1
    end function holds_working_directory

    !> The name the staging, aside and lock names of directory `base` are derived from:
    !> `base` itself, or, when the derived names would exceed NAME_MAX (a name over
    !> MAX_KEY_LEN bytes), its first bytes, '~' and 8 hex digits of a hash of the whole
    !> (FNV-1a): recognisable, the same for every run into that directory, and short enough.
    pure function name_key(base) result(key)
        character(len=*), intent(in) :: base
        character(len=:), allocatable :: key
        integer(int64), parameter :: FNV_OFFSET = 2166136261_int64, FNV_PRIME = 16777619_int64
        integer(int64) :: hash
        character(len=8) :: hex
        integer :: i
        if (len(base) <= MAX_KEY_LEN) then
            key = base
            return
        end if
        hash = FNV_OFFSET
        do i = 1, len(base)
            ! stays below 2**32 before the product, below 2**57 after: no overflow
            hash = modulo(ieor(hash, int(iachar(base(i:i)), int64))*FNV_PRIME, 2_int64**32)
        end do
        write (hex, '(z8.8)') hash
        key = base(:MAX_KEY_LEN - 9)//'~'//hex
    end function name_key

    !> Remove the staging folders `<parent>/<prefix><pid>` whose process is gone: a run
    !> killed (SIGKILL) before or during its commit leaves its staging folder behind (holding
    !> its new set, or the old set it was removing). A folder named after our own pid is also
    !> stale (we have not made ours yet); those of live processes, other names, and links
    !> are left alone. Best effort: what cannot be removed stays. Process identifiers are
    !> those of this machine: see docs/reliability.md about shared output directories.
    !> With `restore`: the folders are old sets set aside by a commit without swap (see
    !> output_stage_commit); one killed before it put the new set in place leaves no
    !> `restore` directory, and its old set goes back there.
    subroutine remove_stale_staging(parent, prefix, restore)
        character(len=*), intent(in) :: parent, prefix
        character(len=*), intent(in), optional :: restore
        type(status_t) :: stat
        character(len=MAX_NAME_LEN), allocatable :: names(:)
        character(len=:), allocatable :: folder, digits
        integer :: i, pid

        call list_directory(parent, names)
        do i = 1, size(names)
            if (index(names(i), prefix) /= 1) cycle
            digits = trim(names(i)(len(prefix) + 1:))
            ! pids are below 2^22 on Linux: 9 digits cannot overflow an integer.
            if (len(digits) == 0 .or. len(digits) > 9) cycle
            if (verify(digits, '0123456789') /= 0) cycle
            read (digits, '(i9)') pid
            ! our own pid's folder is stale by definition; another pid's only if it is gone
            if (pid /= process_id()) then
                if (.not. process_gone(pid)) cycle
            end if
            folder = join(parent, trim(names(i)))
            ! Not through a link: its target is not ours to empty.
            if (.not. is_real_directory(folder)) cycle
            if (present(restore)) then
                if (.not. file_exists(restore)) then
                    call rename_file(folder, restore, stat)
                    if (stat%ok()) cycle
                end if
            end if
            call remove_tree(folder)
        end do
    end subroutine remove_stale_staging

    !> Add the output file `name` to the set and give the path to write it to while staging.
    !> Before begin (or after commit/abort) nothing is added and the path is simply
    !> <directory>/<name> or <name>.
    subroutine output_stage_add(this, name, file_path)
        class(output_stage_t), intent(inout) :: this
        character(len=*), intent(in) :: name
        character(len=:), allocatable, intent(out) :: file_path

        if (.not. this%active) then
            file_path = trim(name)
            if (allocated(this%directory)) file_path = this%directory//'/'//trim(name)
            return
        end if
        file_path = this%staging//'/'//trim(name)
        if (.not. is_listed(trim(name), this%names)) call append_text(this%names, trim(name))
    end subroutine output_stage_add

    !> Put the staged set in place of the output directory in one step, and remove the old
    !> set. Where the file system cannot swap directories (NFS), the old directory is
    !> renamed aside (<parent>/.<base>.nceig-old-<pid>) just before the staging folder takes
    !> its name: for that moment the directory is missing, never mixed; a run killed then
    !> leaves the old set aside, and the next run puts it back.
    !> Every file was checked at its close (close_output); here the file system is written
    !> to disk (syncfs: write errors found late fail the commit), then, holding the
    !> directory's lock: the other files of the old directory are linked into the staging
    !> folder (see the module header), the folders are swapped, the parent synced, and the
    !> old set removed. SIGTERM and SIGINT wait for
    !> the end of the commit. On failure the staged files are deleted, the previous set stays
    !> as it was, and STATUS_IO names the file or directory.
    subroutine output_stage_commit(this, stat, swap)
        class(output_stage_t), intent(inout) :: this
        type(status_t), intent(out) :: stat
        !> .false.: set the old directory aside instead of swapping, what a file system that
        !> cannot swap (NFS) gets anyway; default .true.
        logical, intent(in), optional :: swap
        type(status_t) :: sync_stat
        character(len=:), allocatable :: old
        integer :: lock
        logical :: linked

        if (.not. this%active) then
            call stat%fail(STATUS_IO, 'output stage: commit without begin')
            return
        end if
        call hold_signals()
        call sync_filesystem(this%staging, stat)
        if (.not. stat%ok()) then
            call this%abort()
            return
        end if
        if (this%inside) then
            call lock_file(join(this%directory, IN_PLACE_LOCK), lock, stat)
        else
            call lock_file(join(this%parent, '.'//this%key//LOCK_SUFFIX), lock, stat)
        end if
        if (.not. stat%ok()) then
            call this%abort()
            return
        end if
        if (this%in_place) then
            call commit_in_place(this, stat)
            call unlock_file(lock)
            if (.not. stat%ok()) then
                call this%abort()
                return
            end if
            call remove_tree(this%staging)
            call sync_path(this%directory, sync_stat)
            this%active = .false.
            call end_cleanup_on_signal()
            return
        end if
        if (is_real_directory(this%directory)) then
            call carry_over(this, linked, stat)
            if (stat%ok()) call copy_mode(this%directory, this%staging)
            ! the links are entries of the staging folder made after the sync
            if (stat%ok() .and. linked) call sync_path(this%staging, stat)
        end if
        if (stat%ok()) call replace_directory(this%staging, this%directory, this%aside, old, &
                                              stat, optional_true(swap))
        if (.not. stat%ok()) then
            call unlock_file(lock)
            call this%abort()
            return
        end if
        ! From here the new set is in place: a failure to sync or to remove the old set
        ! (now at the staging or aside path) loses nothing; a later run removes a leftover.
        call sync_path(this%parent, sync_stat)
        if (len(old) > 0) then
            call rescue_late_files(this, old)
            call remove_tree(old)
        end if
        call unlock_file(lock)
        this%active = .false.
        this%created_levels = 0
        call end_cleanup_on_signal()
    end subroutine output_stage_commit

    !> The staging folder itself (for a tool that writes its file there, e.g. a plot).
    function output_stage_folder(this) result(folder)
        class(output_stage_t), intent(in) :: this
        character(len=:), allocatable :: folder
        folder = this%staging
    end function output_stage_folder

    !> Where to put a scratch file while staging (a gnuplot script, a picture not yet known to
    !> be drawn): in the staging folder, NOT part of the set; remove it before the commit, or
    !> register it with path() once it is complete.
    function output_stage_scratch(this, name) result(file_path)
        class(output_stage_t), intent(in) :: this
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: file_path
        file_path = this%staging//'/'//trim(name)
    end function output_stage_scratch

    !> The commit in place (see the module header): the old summary.json goes first, the new
    !> one comes last; between them the new files replace the old set's.
    subroutine commit_in_place(this, stat)
        type(output_stage_t), intent(in) :: this
        type(status_t), intent(out) :: stat
        type(text_t), allocatable :: old_set(:)
        integer :: i

        call read_listed_files(join(this%directory, SUMMARY_FILE), old_set)
        call remove_file(join(this%directory, SUMMARY_FILE))
        do i = 1, size(this%names)
            if (this%names(i)%text == SUMMARY_FILE) cycle
            call rename_file(join(this%staging, this%names(i)%text), &
                             join(this%directory, this%names(i)%text), stat)
            if (.not. stat%ok()) return
        end do
        do i = 1, size(old_set)
            if (old_set(i)%text == SUMMARY_FILE) cycle
            if (is_listed(old_set(i)%text, this%names)) cycle
            ! only plain names: summary.json is data, not a licence to delete elsewhere
            if (index(old_set(i)%text, '/') > 0 .or. old_set(i)%text == '..') cycle
            call remove_file(join(this%directory, old_set(i)%text))
        end do
        do i = 1, size(this%unlisted_old)
            call remove_file(join(this%directory, this%unlisted_old(i)%text))
        end do
        if (is_listed(SUMMARY_FILE, this%names)) &
            call rename_file(join(this%staging, SUMMARY_FILE), &
                             join(this%directory, SUMMARY_FILE), stat)
    end subroutine commit_in_place

    !> Link into the staging folder each entry of the output directory that is neither in
    !> the old set nor in the new one, so that the swap keeps it. A subdirectory fails.
    subroutine carry_over(this, linked, stat)
        type(output_stage_t), intent(in) :: this
        logical, intent(out) :: linked   !! whether any entry was linked
        type(status_t), intent(out) :: stat
        character(len=MAX_NAME_LEN), allocatable :: entries(:)
        type(text_t), allocatable :: old_set(:)
        character(len=:), allocatable :: name
        integer :: i

        linked = .false.
        call read_listed_files(join(this%directory, SUMMARY_FILE), old_set)
        ! A listing cut short would leave the user's files out of the new directory.
        call list_directory(this%directory, entries, stat)
        if (.not. stat%ok()) then
            call stat%fail(STATUS_IO, stat%message//'; its other files could not be ' &
                           //'carried over, the previous set stays')
            return
        end if
        do i = 1, size(entries)
            name = trim(entries(i))
            if (name == SUMMARY_FILE .or. is_listed(name, this%unlisted_old)) cycle
            if (index(name, IN_PLACE_PREFIX) == 1) cycle
            if (is_listed(name, old_set) .or. is_listed(name, this%names)) cycle
            if (is_real_directory(join(this%directory, name))) then
                call stat%fail(STATUS_IO, 'output directory '//this%directory//' holds the ' &
                               //'folder '//name//', which nceig did not write: nceig ' &
                               //'replaces its output directory as a whole; move it')
                return
            end if
            call make_link(join(this%directory, name), join(this%staging, name), stat)
            if (.not. stat%ok()) return
            linked = .true.
        end do
    end subroutine carry_over

    !> Move back into the output directory what the user put into the old one after
    !> carry_over linked its files (the lock binds nceig runs only): entries of the old
    !> directory `old` that are neither of the old set nor in the new directory.
    subroutine rescue_late_files(this, old)
        type(output_stage_t), intent(in) :: this
        character(len=*), intent(in) :: old
        character(len=MAX_NAME_LEN), allocatable :: entries(:)
        type(text_t), allocatable :: old_set(:)
        type(status_t) :: stat
        character(len=:), allocatable :: name
        integer :: i

        call read_listed_files(join(old, SUMMARY_FILE), old_set)
        call list_directory(old, entries)
        do i = 1, size(entries)
            name = trim(entries(i))
            if (name == SUMMARY_FILE .or. is_listed(name, this%unlisted_old)) cycle
            if (index(name, IN_PLACE_PREFIX) == 1) cycle
            if (is_listed(name, old_set)) cycle
            if (file_exists(join(this%directory, name))) cycle
            call rename_file(join(old, name), join(this%directory, name), stat)
        end do
    end subroutine rescue_late_files

    !> The names in the "files" member of summary.json `path` (as json_writer writes it: on
    !> one line); none when the file is missing or has no such line.
    subroutine read_listed_files(path, names)
        character(len=*), intent(in) :: path
        type(text_t), allocatable, intent(out) :: names(:)
        character(len=*), parameter :: KEY = '"files": ['
        character(len=:), allocatable :: line
        character(len=512) :: msg
        integer :: unit, ios, start, first, last

        allocate (names(0))
        open (newunit=unit, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do
            call read_line(unit, line, ios, msg)
            if (ios /= 0) exit
            start = index(line, KEY)
            if (start == 0) cycle
            line = line(start + len(KEY):)
            do
                first = index(line, '"')
                if (first == 0) exit
                last = index(line(first + 1:), '"')
                if (last == 0) exit
                call append_text(names, line(first + 1:first + last - 1))
                line = line(first + last + 1:)
            end do
            exit
        end do
        close (unit, iostat=ios)
    end subroutine read_listed_files


    pure logical function is_listed(name, list)
        character(len=*), intent(in) :: name
        type(text_t), intent(in) :: list(:)
        integer :: i
        is_listed = .false.
        do i = 1, size(list)
            if (list(i)%text == name) is_listed = .true.
        end do
    end function is_listed

    !> `directory`/`name`, without doubling the '/' of the root.
    pure function join(directory, name) result(path)
        character(len=*), intent(in) :: directory, name
        character(len=:), allocatable :: path
        if (directory == '/') then
            path = '/'//name
        else
            path = directory//'/'//name
        end if
    end function join

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
            names(i) = this%names(i)%text
        end do
    end function output_stage_file_names

    !> Delete the staging folder with the staged files, and the parents begin created; the
    !> output directory is left alone. Safe to call twice and after a failed begin.
    subroutine output_stage_abort(this)
        class(output_stage_t), intent(inout) :: this

        if (.not. this%active) return
        call remove_tree(this%staging)
        call remove_created_parents(this)
        this%active = .false.
        call end_cleanup_on_signal()
    end subroutine output_stage_abort

    !> rmdir the last `created_levels` components of the parent, deepest first; one not
    !> empty (another run wrote there meanwhile) stops it.
    subroutine remove_created_parents(this)
        type(output_stage_t), intent(inout) :: this
        character(len=:), allocatable :: path
        integer :: level, slash

        path = this%parent
        do level = 1, this%created_levels
            if (is_directory(path)) then
                call remove_directory(path)
                if (is_directory(path)) exit
            end if
            slash = index(path, '/', back=.true.)
            if (slash <= 1) exit
            path = path(:slash - 1)
        end do
        this%created_levels = 0
    end subroutine remove_created_parents
    !> An optional flag, .true. when absent.
    pure logical function optional_true(flag)
        logical, intent(in), optional :: flag
        optional_true = .true.
        if (present(flag)) optional_true = flag
    end function optional_true
end module output_stage
