! SPDX-License-Identifier: MIT
!> Whether the mesh resolves the mode of the lowest positive mu on the contact segment: a
!> mode whose contact displacement is a spike a few cells wide at the mesh's own scale moves
!> with the mesh (c_n grows like 1/h: a scene with no continuum value, such as contact on
!> the middle of a side with free parts on both sides), and no error estimate from the same
!> cells can see that. The measure is the mode's effective width on Gamma_C,
!> W = (int u_n^2 ds)^2 / int u_n^4 ds (the length a uniform u_n would need for the same two
!> moments; the whole segment for a constant, about one cell for a spike), in units of the
!> cell size at the mode's peak.
module mode_resolution
    use kinds, only: wp
    use problem, only: problem_t
    use element_types, only: element_degree
    implicit none
    private
    public :: contact_mode_cells

contains

    !> W over the cell size at the largest |u_n|, for the free-dof vector `phi` of `prob`;
    !> negative where it cannot be measured (fewer than three contact nodes, u_n = 0).
    function contact_mode_cells(prob, phi) result(cells)
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: phi(:)
        real(wp) :: cells
        real(wp), allocatable :: u(:), weight(:), position(:)
        real(wp) :: m2, m4, cell
        integer :: p, a, peak

        cells = -1.0_wp
        p = prob%contact%p()
        if (p < 3) return
        allocate (u(p), weight(p), position(p))
        call prob%contact%gather(prob%contact%normal, phi, u)
        ! the lumped boundary mass M 1: the length each node stands for
        call prob%contact%mass%matvec([(1.0_wp, a=1, p)], weight)
        do a = 1, p
            position(a) = dot_product(prob%mesh%coords(:, prob%contact%nodes(a)), &
                                      prob%contact%tangent)
        end do
        m2 = sum(weight*u**2)
        m4 = sum(weight*u**4)
        if (.not. m4 > 0.0_wp) return
        peak = maxloc(abs(u), dim=1)
        ! the cell size there: the spacing of the nodes around the peak times the degree
        cell = abs(position(min(peak + 1, p)) - position(max(peak - 1, 1)))/ &
               real(min(peak + 1, p) - max(peak - 1, 1), wp)*real(max(1, &
               element_degree(prob%mesh%element)), wp)
        if (.not. cell > 0.0_wp) return
        cells = (m2**2/m4)/cell
    end function contact_mode_cells
end module mode_resolution
