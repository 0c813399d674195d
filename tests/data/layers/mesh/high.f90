! SPDX-License-Identifier: MIT
!> Layer-check fixture, upper folder: using a module of core/ (below) is legal.
module high
    use base, only: base_value
    implicit none
    private
    public :: high_value
contains
    pure integer function high_value()
        high_value = 2*base_value()
    end function high_value
end module high
