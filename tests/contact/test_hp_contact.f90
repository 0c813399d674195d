! SPDX-License-Identifier: MIT
!> Gamma_C of an hp space: the edge trace mass in closed form (with Lhat_i = (P_i -
!> P_(i-2))/(2i - 1): (h/2) int Lhat_i^2 = (h/2) 4/((2i - 3)(2i - 1)(2i + 1)), Lhat_i and
!> Lhat_(i+2) couple by -(h/2) 2/((2i - 1)(2i + 1)(2i + 3)), the vertex functions meet
!> Lhat_2 with -h/6 and Lhat_3 with +-h/30, nothing higher); the contact functions of a
!> uniform degree p are the n + 1 vertices and n (p - 1) edge functions of the side, in
!> order along t; at degree 1 it is build_contact's Gamma_C of the P1 mesh.
program test_hp_contact
    use kinds, only: wp
    use status, only: status_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map
    use contact_boundary, only: contact_t, build_contact
    use hp_space, only: hp_space_t, build_hp_space
    use hp_contact, only: build_hp_contact, hp_edge_mass
    use fixtures, only: csr_to_dense
    use testing, only: test_suite_t
    implicit none

    integer, parameter :: N = 4
    real(wp), parameter :: H = 0.7_wp
    type(test_suite_t) :: t
    type(mesh_t) :: m
    type(status_t) :: stat
    integer :: p

    t%name = 'test_hp_contact'
    call check_edge_mass()
    call structured_rectangle(1.0_wp, 1.0_wp, N, N, ELEMENT_P1, 'right', m, stat)
    call check_degree_one()
    do p = 2, 5
        call check_uniform(p)
    end do
    call t%report()

contains

    !> The closed-form trace mass of an edge of degree p_e and length H.
    function closed_form(p_e) result(me)
        integer, intent(in) :: p_e
        real(wp) :: me(p_e + 1, p_e + 1)
        integer :: i, a, b
        me = 0.0_wp
        me(1:2, 1:2) = H/6.0_wp*reshape([2.0_wp, 1.0_wp, 1.0_wp, 2.0_wp], [2, 2])
        do i = 2, p_e
            a = i + 1   ! Lhat_i's row
            me(a, a) = 0.5_wp*H*4.0_wp/real((2*i - 3)*(2*i - 1)*(2*i + 1), wp)
            if (i + 2 <= p_e) then
                b = a + 2
                me(a, b) = -0.5_wp*H*2.0_wp/real((2*i - 1)*(2*i + 1)*(2*i + 3), wp)
                me(b, a) = me(a, b)
            end if
        end do
        if (p_e >= 2) then
            me(1:2, 3) = -H/6.0_wp
            me(3, 1:2) = -H/6.0_wp
        end if
        if (p_e >= 3) then   ! l_a = (1 - s)/2 against Lhat_3 = (P_3 - P_1)/5
            me(1:2, 4) = [H, -H]/30.0_wp
            me(4, 1:2) = [H, -H]/30.0_wp
        end if
    end function closed_form

    subroutine check_edge_mass()
        integer :: p_e
        real(wp) :: worst
        worst = 0.0_wp
        do p_e = 1, 12
            worst = max(worst, maxval(abs(hp_edge_mass(p_e, H) - closed_form(p_e))))
        end do
        call t%check('hp_edge_mass: the closed form, degrees 1 to 12', worst <= 1.0e-15_wp)
    end subroutine check_edge_mass

    !> Degree 1: the nodes, dofs, normal and mass of build_contact on the P1 dof map.
    subroutine check_degree_one()
        type(hp_space_t) :: space
        type(dof_map_t) :: dofs
        type(contact_t) :: hp, p1
        integer :: c
        call build_hp_space(m, [(1, c=1, m%n_cells())], [m%part_index('top')], space, stat)
        call build_hp_contact(m, space, m%part_index('bottom'), hp, stat)
        call build_dof_map(m, [m%part_index('top')], dofs, stat)
        call build_contact(m, m%part_index('bottom'), dofs, p1, stat)
        call t%check('degree 1: build_contact''s nodes, dofs, normal and mass', stat%ok() &
                     .and. all(hp%nodes == p1%nodes) .and. all(hp%dofs == p1%dofs) .and. &
                     all(abs(hp%normal - p1%normal) <= 0.0_wp) .and. &
                     maxval(abs(csr_to_dense(hp%mass) - csr_to_dense(p1%mass))) <= 1.0e-16_wp)
    end subroutine check_degree_one

    subroutine check_uniform(p)
        integer, intent(in) :: p
        type(hp_space_t) :: space
        type(contact_t) :: contact
        real(wp), allocatable :: mass(:, :), position(:)
        integer :: c, a, k
        logical :: ordered, dofs_ok
        character(len=8) :: label
        write (label, '(a, i0, a)') ' (p = ', p, ')'
        call build_hp_space(m, [(p, c=1, m%n_cells())], [m%part_index('top')], space, stat)
        call build_hp_contact(m, space, m%part_index('bottom'), contact, stat)
        call t%check('n + 1 vertex and n (p - 1) edge functions'//trim(label), stat%ok() &
                     .and. contact%p() == N + 1 + N*(p - 1))
        ! a function's position along t: its vertex, or its edge's midpoint
        allocate (position(contact%p()))
        dofs_ok = .true.
        do a = 1, contact%p()
            k = contact%nodes(a)
            if (k <= space%n_vertices) then
                position(a) = dot_product(m%coords(:, k), contact%tangent)
            else
                position(a) = dot_product(0.5_wp*sum(m%coords(:, space%edge_ends(:, &
                    findloc(space%edge_first <= k .and. k < space%edge_first + &
                    space%edge_degree - 1, .true., dim=1))), dim=2), contact%tangent)
            end if
            dofs_ok = dofs_ok .and. all(contact%dofs(:, a) == [2*space%free_function(k) - 1, &
                                                               2*space%free_function(k)])
        end do
        ordered = all(position(2:) >= position(:contact%p() - 1))
        call t%check('in order along t, dofs (x, y) of each free function'//trim(label), &
                     ordered .and. dofs_ok)
        mass = csr_to_dense(contact%mass)
        ! the vertex functions sum to one on the side: their block sums to its length
        call t%check('the vertex functions'' mass sums to the length 1'//trim(label), &
                     abs(sum(mass(pack([(a, a=1, contact%p())], contact%nodes <= &
                     space%n_vertices), pack([(a, a=1, contact%p())], contact%nodes <= &
                     space%n_vertices))) - 1.0_wp) <= 1.0e-14_wp)
        ! (symmetric to rounding: each product is formed in the order of its column)
        call t%check('the mass symmetric and positive on the diagonal'//trim(label), &
                     maxval(abs(mass - transpose(mass))) <= 1.0e-15_wp*maxval(abs(mass)) .and. &
                     all([(mass(a, a) > 0.0_wp, a=1, contact%p())]))
    end subroutine check_uniform
end program test_hp_contact
