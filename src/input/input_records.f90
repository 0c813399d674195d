! SPDX-License-Identifier: MIT
!> The namelist records of the input file, one group at a time: the namelist of each
!> (whose variables are those of its `run_config` type, as input_table lists them), read
!> into a config_t or written from one. Values are read, not judged: see input_validation.
!> The readers are generated with the types and the table from one line per variable in
!> src/input/input_variables.cmake (how to add one: input_table).
module input_records
    use kinds, only: wp
    use run_config, only: config_t, MAX_SWEEP_LAMBDAS, PATH_LEN
    use strings, only: lowercase, normalized_list, NAME_LEN, LIST_LEN
    use input_table, only: KNOWN_GROUPS
    use ieee_exceptions, only: ieee_status_type, ieee_get_status, ieee_set_status, &
                               ieee_set_halting_mode, ieee_support_halting, ieee_overflow
    implicit none
    private
    public :: read_record, reader_variables, reader_defaults, LISTING_LINE_LEN

    integer, parameter :: LISTING_LINE_LEN = 4*PATH_LEN   !! a line of a namelist write

contains

    !> Read one '&group assignment ... /' record of group `group` into `config` (whose
    !> group is unchanged when the read fails: ios /= 0, msg the runtime's message). With
    !> `listing_unit`, write the group's namelist with the values of `config` there instead.
    subroutine read_record(group, record, config, ios, msg, listing_unit)
        character(len=*), intent(in) :: group, record
        type(config_t), intent(inout) :: config
        integer, intent(out) :: ios
        character(len=*), intent(inout) :: msg
        integer, intent(in), optional :: listing_unit
        type(ieee_status_type) :: saved
        ! '1e999' overflows inside the runtime's strtod: in a build that traps overflow
        ! (Debug) that is a crash, so the read runs without; the value becomes Inf and
        ! validation refuses it as not finite. Flags and modes are restored after.
        call ieee_get_status(saved)
        if (ieee_support_halting(ieee_overflow)) call ieee_set_halting_mode(ieee_overflow, &
                                                                            .false.)
        include 'input_records_dispatch.inc'   ! select case (group): call mesh_record(...), ...
        call ieee_set_status(saved)
    end subroutine read_record

    !> The variables of group `group` as its namelist declares them, lowercased, in order:
    !> taken from a namelist write, so that they can be checked against input_table and
    !> the help text. Empty for an unknown group.
    function reader_variables(group) result(names)
        character(len=*), intent(in) :: group
        character(len=NAME_LEN), allocatable :: names(:)
        character(len=LISTING_LINE_LEN), allocatable :: values(:)
        call reader_defaults(group, names, values)
    end function reader_variables

    !> The variables of group `group` (as reader_variables) and their default values as a
    !> namelist write of a default config_t gives them ('1.0000000000000000', '"p1   "',
    !> 'T'), so that the help shows run_config's defaults without naming each one.
    subroutine reader_defaults(group, names, values)
        character(len=*), intent(in) :: group
        character(len=NAME_LEN), allocatable, intent(out) :: names(:)
        character(len=LISTING_LINE_LEN), allocatable, intent(out) :: values(:)
        type(config_t) :: defaults
        character(len=LISTING_LINE_LEN) :: line
        character(len=256) :: msg
        integer :: unit, ios, equals, last

        allocate (names(0), values(0))
        open (newunit=unit, status='scratch', action='readwrite', delim='quote', &
              recl=LISTING_LINE_LEN, iostat=ios)
        if (ios /= 0) return
        msg = ''
        call read_record(group, '', defaults, ios, msg, listing_unit=unit)
        if (ios == 0) then
            rewind (unit)
            do
                read (unit, '(a)', iostat=ios) line
                if (ios /= 0) exit
                ! 'NAME=value' starts a variable; other lines continue an array's values.
                line = adjustl(line)
                equals = index(line, '=')
                if (equals < 2) cycle
                if (verify(line(:equals - 1), 'abcdefghijklmnopqrstuvwxyz' &
                           //'ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') /= 0) cycle
                names = [character(len=NAME_LEN) :: names, lowercase(line(:equals - 1))]
                last = len_trim(line)
                if (line(last:last) == ',') last = last - 1
                values = [character(len=LISTING_LINE_LEN) :: values, &
                          adjustl(line(equals + 1:last))]
            end do
        end if
        close (unit)
    end subroutine reader_defaults

    ! The readers of the groups, generated from
    ! src/input/input_variables.cmake: each copies the current values into locals named like
    ! the namelist variables, reads the record from the internal file `record`, and only on
    ! success copies them back, normalising names (trimmed, lowercased), paths and lists.
    include 'input_records_readers.inc'
end module input_records
