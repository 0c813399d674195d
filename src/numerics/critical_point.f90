! SPDX-License-Identifier: MIT
!> What a positive real eigenvalue mu at lambda means for the interface: the critical
!> compliance coefficients c_n = mu, c_t = mu |lambda|, and the slip direction s = -sgn(lambda)
!> along t of the branch of solutions. Every output takes them from here.
module critical_point
    use kinds, only: wp
    implicit none
    private
    public :: slip_sign, critical_c_t

contains

    !> s = -sgn(lambda); 0 for lambda = 0, where B = -N'MN has no positive eigenvalue.
    pure integer function slip_sign(lambda)
        real(wp), intent(in) :: lambda
        slip_sign = 0
        if (lambda > 0.0_wp) slip_sign = -1
        if (lambda < 0.0_wp) slip_sign = 1
    end function slip_sign

    !> c_t = mu |lambda|: the tangential coefficient paired with c_n = mu.
    pure real(wp) function critical_c_t(mu, lambda)
        real(wp), intent(in) :: mu, lambda
        critical_c_t = mu*abs(lambda)
    end function critical_c_t
end module critical_point
