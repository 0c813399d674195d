! SPDX-License-Identifier: MIT
!> The namelist lexer: groups found with their text and line, comments and quoted text
!> handled, unknown, repeated and unclosed groups refused with their line, and a group's
!> text split into its assignments.
program test_namelist_scan
    use status, only: status_t, STATUS_BAD_INPUT
    use namelist_scan, only: group_text_t, text_t, scan_groups, group_body, has_group, &
                             split_assignments, group_list
    use testing, only: test_suite_t
    implicit none
    character(len=*), parameter :: KNOWN(2) = [character(len=4) :: 'mesh', 'eig']
    type(test_suite_t) :: t
    type(group_text_t), allocatable :: groups(:)
    type(text_t), allocatable :: pieces(:)
    type(status_t) :: stat

    t%name = 'test_namelist_scan'

    call scan([character(len=60) :: '! comment', '&MESH nx = 3, file = ''a/b!c'' ! note', &
                                    '  ny = 4 /', '&eig /'])
    call t%check('scan_groups: two groups, names lowercased, lines kept', stat%ok() .and. &
                 size(groups) == 2)
    if (size(groups) == 2) call t%check('scan_groups: line of each group', &
                                        groups(1)%line == 2 .and. groups(2)%line == 4)
    call t%check('group_body: comments gone, quoted text kept, lines joined', &
                 group_body(groups, 'mesh') == " nx = 3, file = 'a/b!c'    ny = 4 ")
    call t%check('has_group: present and absent groups', has_group(groups, 'eig') .and. &
                 .not. has_group(groups, 'solve'))

    ! gfortran's namelist read takes a tab right after a number as part of it.
    call scan([character(len=40) :: '&mesh nx = 3'//achar(9), achar(9)//'ny = 4'//achar(9) &
               //'! c', 'file = ''a'//achar(9)//'b'' /'])
    call t%check('scan_groups: tabs outside quotes become blanks, inside kept', stat%ok() &
                 .and. group_body(groups, 'mesh') == ' nx = 3   ny = 4  file = ''a' &
                 //achar(9)//'b'' ')

    call scan([character(len=20) :: '&mesh /', '&solve /'])
    call t%check('scan_groups: an unknown group names its line and the known ones', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'line 2') > 0 .and. &
                 index(stat%message, '&mesh, &eig') > 0)
    call scan([character(len=20) :: '&mesh nx = 1', '&eig /'])
    call t%check('scan_groups: a group without its closing slash', &
                 index(stat%message, 'no closing') > 0)
    call scan([character(len=20) :: '&mesh /', '&mesh /'])
    call t%check('scan_groups: a repeated group', index(stat%message, 'appears twice') > 0)

    allocate (pieces(0))   ! avoids a false -Wuninitialized at -O3 (see split_names)
    pieces = split_assignments(" nx = 3, file = 'x=y', lambdas(2) = 1, 2")
    call t%check('split_assignments: one piece per variable, quotes respected', &
                 size(pieces) == 3)
    if (size(pieces) == 3) call t%check('split_assignments: separators dropped', &
                                        pieces(2)%text == "file = 'x=y'" .and. &
                                        pieces(3)%text == 'lambdas(2) = 1, 2')
    call t%check('group_list: for messages', group_list(KNOWN) == '&mesh, &eig')
    ! gfortran 12 never frees main-program allocatables: LeakSanitizer would report them.
    deallocate (groups, pieces)
    call t%report()

contains

    !> scan_groups on a file of `lines`.
    subroutine scan(lines)
        character(len=*), intent(in) :: lines(:)
        integer :: unit, i
        open (newunit=unit, status='scratch', action='readwrite')
        do i = 1, size(lines)
            write (unit, '(a)') trim(lines(i))
        end do
        rewind (unit)
        call scan_groups(unit, 'test.nml', KNOWN, groups, stat)
        close (unit)
    end subroutine scan
end program test_namelist_scan
