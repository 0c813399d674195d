! SPDX-License-Identifier: MIT
!> Layer-check fixture, bottom folder: a module that uses only an intrinsic module.
module base
    use, intrinsic :: iso_fortran_env, only: int32
    implicit none
    private
    public :: base_value
contains
    pure integer(int32) function base_value()
        base_value = 1
    end function base_value
end module base
