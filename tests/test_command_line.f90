! SPDX-License-Identifier: MIT
!> The command line: the one-argument forms as before, --set options around one input file,
!> and each misuse refused with STATUS_BAD_INPUT.
program test_command_line
    use status, only: status_t, STATUS_BAD_INPUT
    use namelist_scan, only: text_t
    use command_line, only: command_t, read_command_line, parse_arguments
    use testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: t
    type(command_t) :: command
    type(status_t) :: stat

    t%name = 'test_command_line'

    ! ctest runs this program without arguments: the usage error of the program.
    call read_command_line(command, stat)
    call t%check('read_command_line: no argument is refused', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'one argument') > 0)

    call parse_arguments([text_t('--help')], command, stat)
    call t%check('parse_arguments: --help', stat%ok() .and. command%action == 'help')
    call parse_arguments([text_t('-V')], command, stat)
    call t%check('parse_arguments: -V', stat%ok() .and. command%action == 'version')
    call parse_arguments([text_t('a.nml')], command, stat)
    call t%check('parse_arguments: an input file alone', stat%ok() .and. &
                 command%action == 'run' .and. command%input == 'a.nml' .and. &
                 size(command%settings) == 0)
    call parse_arguments([text_t('a.nml'), text_t('b.nml')], command, stat)
    call t%check('parse_arguments: two files without --set keep the old message', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'one argument') > 0)
    call parse_arguments([text_t('--set'), text_t('mesh%nx=3'), text_t('a.nml'), &
                          text_t('--set'), text_t('analysis%lambda=2')], command, stat)
    call t%check('parse_arguments: settings in order, the file among them', stat%ok() .and. &
                 command%input == 'a.nml' .and. size(command%settings) == 2)
    if (size(command%settings) == 2) call t%check('parse_arguments: setting values', &
        command%settings(1)%text == 'mesh%nx=3' .and. &
        command%settings(2)%text == 'analysis%lambda=2')
    call parse_arguments([text_t('a.nml'), text_t('--set')], command, stat)
    call t%check('parse_arguments: --set without a value', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'needs a value') > 0)
    call parse_arguments([text_t('--set'), text_t('mesh%nx=3')], command, stat)
    call t%check('parse_arguments: --set without a file', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, 'input file') > 0)
    call parse_arguments([text_t('a.nml'), text_t('--sett'), text_t('--set'), &
                          text_t('mesh%nx=3')], command, stat)
    call t%check('parse_arguments: an unknown option with --set', &
                 stat%code == STATUS_BAD_INPUT .and. index(stat%message, '--sett') > 0)
    call t%report()
end program test_command_line
