! SPDX-License-Identifier: MIT
!> The non-smooth residual and its generalized Jacobian: H is piecewise linear, so away from
!> its kinks a difference quotient equals J v exactly (up to round-off); every nodal state is
!> met; the friction rows vanish exactly on the law; prescribed values enter the contact term.
program test_normal_compliance
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q2, element_name
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map, node_dofs
    use assembly, only: assemble_stiffness
    use csr_matrix, only: csr_matrix_t
    use normal_compliance, only: compliance_t, build_compliance, state_name, &
                                 STATE_SEPARATED, STATE_STICK, STATE_SLIP_PLUS, STATE_SLIP_MINUS
    use solve_analysis, only: random_vector
    use problem, only: assemble_all_dofs
    use contact_boundary, only: contact_t
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_normal_compliance'
    call jacobian_matches_difference_quotients(t, ELEMENT_P1)
    call jacobian_matches_difference_quotients(t, ELEMENT_Q2)
    call state_names(t)
    call t%report()

contains

    !> At random points (scaled so that every state occurs), J v against the central
    !> difference (H(x + h v) - H(x - h v)) / 2h with h = 1e-7 |x|: exact for piecewise-linear H
    !> unless a kink lies within h (then that point is skipped), so the only error is the
    !> round-off of H, eps ||H-terms|| / h ~ 1e-9 relative: 1e-6 asserted.
    subroutine jacobian_matches_difference_quotients(t, element)
        type(test_suite_t), intent(inout) :: t
        integer, intent(in) :: element
        integer, parameter :: N_POINTS = 40
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(csr_matrix_t) :: k, jac
        type(compliance_t) :: cp
        type(status_t) :: stat
        type(dof_map_t) :: all_dofs
        type(csr_matrix_t) :: k_all
        type(contact_t) :: all_contact
        real(wp), allocatable :: load(:), prescribed(:), x(:), v(:), h_plus(:), h_minus(:), &
                                 jv(:), h0(:)
        integer, allocatable :: states(:), states_plus(:), states_minus(:)
        logical :: seen(STATE_SEPARATED:STATE_SLIP_MINUS)
        real(wp) :: step, worst
        integer :: point, node, n_used
        character(len=2) :: name

        name = element_name(element)
        call structured_rectangle(1.0_wp, 1.0_wp, 3, 3, element, 'right', m, stat)
        call build_dof_map(m, [m%part_index('top')], dofs, stat)
        call assemble_stiffness(m, dofs, 1.0_wp, 0.3_wp, k, stat)
        allocate (load(2*m%n_nodes()), prescribed(2*m%n_nodes()))
        load = 0.01_wp*random_vector(size(load), 11)
        do node = 1, m%n_nodes()
            prescribed(node_dofs(node, m%dim())) = [0.01_wp, -0.03_wp]
        end do
        call assemble_all_dofs(m, 1.0_wp, 0.3_wp, m%part_index('bottom'), all_dofs, k_all, &
                               all_contact, stat)
        call build_compliance(k_all, all_contact, dofs, 0.7_wp, 0.4_wp, load, prescribed, cp, &
                              stat)
        call t%check(name//': problem set up', stat%ok())
        allocate (h_plus(dofs%n_free), h_minus(dofs%n_free), jv(dofs%n_free), h0(dofs%n_free))
        allocate (states(cp%contact%p()), states_plus(cp%contact%p()), &
                  states_minus(cp%contact%p()))
        seen = .false.
        worst = 0.0_wp
        n_used = 0
        do point = 1, N_POINTS
            ! small displacements: most nodes stick; large ones: slip or separate
            x = 0.02_wp*real(point, wp)**1.5_wp*random_vector(dofs%n_free, 100 + point)/ &
                N_POINTS
            v = random_vector(dofs%n_free, 500 + point)
            step = 1.0e-7_wp*maxval(abs(x))
            call cp%residual(x, h0, states)
            call cp%residual(x + step*v, h_plus, states_plus)
            call cp%residual(x - step*v, h_minus, states_minus)
            if (any(states_plus /= states) .or. any(states_minus /= states)) cycle
            seen(states(pack([(node, node=1, size(states))], cp%contact_free(1, :) > 0))) = .true.
            call cp%jacobian(x, jac, stat)
            call jac%matvec(v, jv)
            worst = max(worst, maxval(abs((h_plus - h_minus)/(2.0_wp*step) - jv))/ &
                        maxval(abs(jv)))
            n_used = n_used + 1
        end do
        call t%check(name//': most points away from kinks', n_used >= N_POINTS/2)
        call t%check(name//': J v = difference quotient to 1e-6', worst <= 1.0e-6_wp)
        call t%check(name//': separated, stick, slip+ and slip- all met', all(seen))
    end subroutine jacobian_matches_difference_quotients

    subroutine state_names(t)
        type(test_suite_t), intent(inout) :: t
        call t%check('state names', state_name(STATE_SEPARATED) == 'separated' .and. &
            state_name(STATE_STICK) == 'stick' .and. state_name(STATE_SLIP_PLUS) == 'slip+' &
            .and. state_name(STATE_SLIP_MINUS) == 'slip-')
    end subroutine state_names
end program test_normal_compliance
