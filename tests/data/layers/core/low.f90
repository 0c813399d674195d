! SPDX-License-Identifier: MIT
!> Layer-check fixture: THE violation (core/ uses `high`, a module of mesh/), among uses
!> that are legal (its own folder, spelt in capitals and with ::) or not uses at all.
Module Low
    USE :: Base, only: base_value
    use high, only: high_value
    ! use high, only: a comment is not a use
    implicit none
    private
    public :: low_value
    interface low_value
        module procedure low_value_plain
    end interface low_value
contains
    pure integer function low_value_plain()
        low_value_plain = base_value() + high_value()
    end function low_value_plain
end module low
