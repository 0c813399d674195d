! SPDX-License-Identifier: MIT
!> Reads the namelist input file into a validated `config_t`: scans its groups
!> (namelist_scan), reads each through its record (input_records), then checks the values
!> (input_validation) and resolves the paths; values of `--set` go through the same records
!> and rules. Every default lives in `run_config`.
module input_config
    use status, only: status_t, STATUS_BAD_INPUT
    use run_config, only: config_t
    use namelist_scan, only: group_text_t, text_t, scan_groups, group_body, has_group, &
                             split_assignments, group_list
    use input_records, only: read_record, expectation, is_text_variable, KNOWN_GROUPS
    use strings, only: lowercase
    use input_validation, only: validate_config
    use iso_fortran_env, only: iostat_end
    use filesystem, only: is_directory
    implicit none
    private
    public :: read_input, default_output_directory, resolve_relative

    integer, parameter :: MSG_LEN = 1024     !! iomsg buffers

contains

    !> Read and validate the namelist file `path`. Groups are read in the order of
    !> KNOWN_GROUPS; an absent group keeps its defaults. Names (source, element, side
    !> lists, kind, solver) are stored trimmed and lowercased. The mesh `file` is resolved
    !> relative to the input file's folder, and an empty output `directory` becomes
    !> default_output_directory(path). Any problem gives STATUS_BAD_INPUT with a one-line
    !> message naming the file, the group and the variable.
    !> `settings` ('group%variable=value', the --set options) then override the file, in
    !> order, as one-assignment records; a path so given stays relative to the working
    !> directory. Their problems name '--set' instead of the file, and so does a broken rule
    !> when the file alone keeps every rule.
    subroutine read_input(path, config, stat, settings)
        character(len=*), intent(in) :: path
        type(config_t), intent(out) :: config
        type(status_t), intent(out) :: stat
        type(text_t), intent(in), optional :: settings(:)
        type(group_text_t), allocatable :: groups(:)
        type(config_t) :: file_config
        type(status_t) :: file_stat, set_stat
        character(len=:), allocatable :: input
        character(len=MSG_LEN) :: msg
        integer :: unit, ios, i

        input = trim(path)
        config%input_file = input
        ! Opening a directory succeeds and reads as an empty file: all defaults, silently.
        if (is_directory(input)) then
            call stat%fail(STATUS_BAD_INPUT, input//': is a directory: expected a namelist ' &
                           //'input file')
            return
        end if
        open (newunit=unit, file=input, status='old', action='read', iostat=ios, iomsg=msg)
        if (ios /= 0) then
            call stat%fail(STATUS_BAD_INPUT, input//': cannot open input file: '//trim(msg))
            return
        end if
        call scan_groups(unit, input, KNOWN_GROUPS, groups, stat)
        do i = 1, size(KNOWN_GROUPS)
            if (stat%ok()) call read_group(input, trim(KNOWN_GROUPS(i)), groups, config, stat)
        end do
        close (unit)
        if (.not. stat%ok()) return
        ! Only the file's own path is relative to its folder (validation never shows it).
        if (len_trim(config%mesh%file) > 0) then
            config%mesh%file = resolve_relative(input, config%mesh%file)
        end if

        if (present(settings)) then
            file_config = config
            do i = 1, size(settings)
                call apply_setting(settings(i)%text, config, stat)
                if (.not. stat%ok()) return
            end do
        end if
        call validate_config(config, input, stat)
        if (.not. stat%ok() .and. present(settings)) then
            call validate_config(file_config, input, file_stat)
            if (file_stat%ok()) then
                call validate_config(config, '--set', set_stat)
                stat = set_stat
            end if
        end if
        if (.not. stat%ok()) return

        if (len_trim(config%output%directory) == 0) then
            config%output%directory = default_output_directory(input)
        end if
    end subroutine read_input

    ! ------------------------------------------------------------------ reading groups

    !> Read group `group` (when the file has it) through its record, from the text
    !> scan_groups collected. On failure, re-read its assignments one at a time on a scratch
    !> copy to name the culprit and what it expects.
    subroutine read_group(path, group, groups, config, stat)
        character(len=*), intent(in) :: path, group
        type(group_text_t), intent(in) :: groups(:)
        type(config_t), intent(inout) :: config
        type(status_t), intent(inout) :: stat
        type(config_t) :: scratch
        type(text_t), allocatable :: pieces(:)
        character(len=MSG_LEN) :: msg
        integer :: i, ios
        if (.not. has_group(groups, group)) return
        msg = ''
        call read_record(group, '&'//group//' '//group_body(groups, group)//' /', config, &
                         ios, msg)
        if (ios == 0) return
        call stat%fail(STATUS_BAD_INPUT, read_failure(path, group, ios, msg))
        pieces = split_assignments(group_body(groups, group))
        scratch = config
        do i = 1, size(pieces)
            msg = ''
            call read_record(group, '&'//group//' '//pieces(i)%text//' /', scratch, ios, msg)
            if (ios /= 0) then
                call stat%fail(STATUS_BAD_INPUT, path//': &'//group//': '//pieces(i)%text &
                               //': '//trim(msg)//expectation(group, pieces(i)%text))
                exit
            end if
        end do
    end subroutine read_group

    !> Message for a failed read of group `group` when no single assignment was to blame.
    function read_failure(path, group, ios, msg) result(text)
        character(len=*), intent(in) :: path, group, msg
        integer, intent(in) :: ios
        character(len=:), allocatable :: text
        text = path//': &'//group//': '//trim(msg)
        if (ios == iostat_end) text = text//" (is the closing '/' of the group missing?)"
    end function read_failure

    !> Override one variable of `config` with `setting`, 'group%variable=value': read as the
    !> record '&group variable = value /', quotes added around a text value given without.
    subroutine apply_setting(setting, config, stat)
        character(len=*), intent(in) :: setting
        type(config_t), intent(inout) :: config
        type(status_t), intent(inout) :: stat
        character(len=:), allocatable :: label, group, variable, value, assignment
        type(text_t), allocatable :: pieces(:)
        character(len=MSG_LEN) :: msg
        integer :: equals, percent, ios

        label = '--set '//setting
        equals = index(setting, '=')
        percent = index(setting(:max(equals - 1, 0)), '%')
        if (percent <= 1 .or. equals <= percent + 1) then
            call malformed()
            return
        end if
        group = lowercase(trim(adjustl(setting(:percent - 1))))
        variable = trim(adjustl(setting(percent + 1:equals - 1)))
        value = trim(adjustl(setting(equals + 1:)))
        if (len(value) == 0) then
            call malformed()
            return
        end if
        if (.not. any(KNOWN_GROUPS == group)) then
            call stat%fail(STATUS_BAD_INPUT, label//': unknown namelist group &'//group &
                           //' (known groups: '//group_list(KNOWN_GROUPS)//')')
            return
        end if
        if (is_text_variable(group, variable) .and. index('"'//"'", value(1:1)) == 0) then
            value = '"'//doubled_quotes(value)//'"'
        end if
        assignment = variable//' = '//value
        if (index('"'//"'", value(1:1)) == 0 .and. scan(value, '/&$!') > 0) then
            ! They would end the record early or start a comment: part of the value lost.
            call stat%fail(STATUS_BAD_INPUT, label//': &'//group//': '//assignment &
                           //": expected one value, without '/', '&', '$' or '!'")
            return
        end if
        pieces = split_assignments(assignment)
        if (size(pieces) /= 1) then
            call stat%fail(STATUS_BAD_INPUT, label//': &'//group//': '//variable &
                           //': expected one variable per --set')
            return
        end if
        msg = ''
        call read_record(group, '&'//group//' '//assignment//' /', config, ios, msg)
        if (ios /= 0) then
            call stat%fail(STATUS_BAD_INPUT, label//': &'//group//': '//assignment//': ' &
                           //trim(msg)//expectation(group, assignment))
        end if

    contains

        subroutine malformed()
            call stat%fail(STATUS_BAD_INPUT, label//': expected group%variable=value (such ' &
                           //'as analysis%lambda=2.5)')
        end subroutine malformed

        !> `text` with each double quote doubled, as a double-quoted namelist value needs.
        pure function doubled_quotes(text) result(escaped)
            character(len=*), intent(in) :: text
            character(len=:), allocatable :: escaped
            integer :: k
            escaped = ''
            do k = 1, len(text)
                escaped = escaped//text(k:k)
                if (text(k:k) == '"') escaped = escaped//'"'
            end do
        end function doubled_quotes
    end subroutine apply_setting

    ! -------------------------------------------------------------------------- paths

    !> Default output directory of a run: output/<input file name without extension>,
    !> relative to the working directory.
    function default_output_directory(input_path) result(directory)
        character(len=*), intent(in) :: input_path
        character(len=:), allocatable :: directory
        character(len=:), allocatable :: base
        integer :: dot

        base = trim(input_path)
        base = base(index(base, '/', back=.true.) + 1:)
        dot = index(base, '.', back=.true.)
        if (dot > 1) base = base(:dot - 1)   ! a leading dot starts a hidden name, not a suffix
        if (len(base) == 0) base = 'nceig'
        directory = 'output/'//base
    end function default_output_directory

    !> `path` as seen from the working directory when written relative to the folder of
    !> `base_file`; absolute and empty paths are returned unchanged.
    function resolve_relative(base_file, path) result(resolved)
        character(len=*), intent(in) :: base_file, path
        character(len=:), allocatable :: resolved
        integer :: slash

        resolved = trim(adjustl(path))
        if (len(resolved) == 0) return
        if (resolved(1:1) == '/') return
        slash = index(trim(base_file), '/', back=.true.)
        if (slash > 0) resolved = base_file(:slash)//resolved
    end function resolve_relative
end module input_config
