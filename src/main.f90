! SPDX-License-Identifier: MIT
program nceig
    use version, only: NCEIG_VERSION
    implicit none
    print '(a)', 'nceig '//NCEIG_VERSION
end program nceig
