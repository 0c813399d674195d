! SPDX-License-Identifier: MIT
!> naming_file: a failure's message gets the input file in front unless it names a file
!> already ('left eigenvector ... did not converge' and a generated mesh's inverted cell
!> named none). Exact text comparisons.
program test_process_exit
    use process_exit, only: naming_file
    use testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_process_exit'
    call a_solver_message_gets_the_input()
    call a_message_naming_the_input_is_kept()
    call a_message_naming_another_file_is_kept()
    call no_file_no_change()
    call t%report()

contains

    subroutine a_solver_message_gets_the_input()
        call t%check('a solver''s and a generated mesh''s message get the input in front', &
                     naming_file('left eigenvector: inverse iteration did not converge', &
                                 'in.nml') == &
                     'in.nml: left eigenvector: inverse iteration did not converge' .and. &
                     naming_file('mesh: cell 1 is inverted', 'a/b.nml') == &
                     'a/b.nml: mesh: cell 1 is inverted')
    end subroutine a_solver_message_gets_the_input

    subroutine a_message_naming_the_input_is_kept()
        call t%check('a message that starts with the input file is kept', &
                     naming_file('in.nml: &adapt: tolerance not met', 'in.nml') == &
                     'in.nml: &adapt: tolerance not met')
    end subroutine a_message_naming_the_input_is_kept

    subroutine a_message_naming_another_file_is_kept()
        call t%check('a message that starts with a mesh file or an output file is kept', &
                     naming_file('meshes/a.msh:27: cell inverted', 'in.nml') == &
                     'meshes/a.msh:27: cell inverted' .and. &
                     naming_file('/tmp/.out.nceig-staging-1/mode_002.vtu: cannot write', &
                                 'in.nml') == &
                     '/tmp/.out.nceig-staging-1/mode_002.vtu: cannot write')
    end subroutine a_message_naming_another_file_is_kept

    subroutine no_file_no_change()
        call t%check('without a file name the message is as it was', &
                     naming_file('mesh: cell 1 is inverted', '') == 'mesh: cell 1 is inverted')
    end subroutine no_file_no_change
end program test_process_exit
