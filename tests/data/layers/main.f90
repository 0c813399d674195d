! SPDX-License-Identifier: MIT
!> Layer-check fixture, top: a file directly in the source folder may use any folder.
program main
    use high, only: high_value
    use low, only: low_value
    implicit none
    print *, high_value(), low_value()
end program main
