! SPDX-License-Identifier: MIT
!> Consistent nodal forces against mathematics: the patch test K U = F(sigma(U) n) for a
!> linear field on every element, resultants and moments of tractions and body forces.
program test_loads
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, element_name
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use csr_matrix, only: csr_matrix_t
    use elasticity, only: lame_coefficients
    use loads, only: edge_loads, body_force_loads
    use dof_map, only: all_dof, node_dofs
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_loads'
    call numbering(t)
    call patch_test_linear_field(t)
    call traction_resultants(t)
    call body_force_resultant_and_moment(t)
    call t%report()

contains

    subroutine numbering(t)
        type(test_suite_t), intent(inout) :: t
        call t%check('all_dof is node-major', all_dof(2, 5, 2) == 10 .and. &
                     all_dof(1, 1, 2) == 1)
        call t%check('node_dofs(3) = (5, 6) in the plane', all(node_dofs(3, 2) == [5, 6]))
        ! the dimension is an argument: three components per node in space
        call t%check('node_dofs(2) = (4, 5, 6) in space', all(node_dofs(2, 3) == [4, 5, 6]) &
                     .and. all_dof(3, 2, 3) == 6)
    end subroutine numbering

    !> For a linear U, a(U, v) = int_boundary sigma(U) n . v exactly (constant stress), so the
    !> full K times U equals the edge loads of sigma(U) n on the whole boundary. K U is a sum
    !> of terms bounded by ||K|| ||U||: 100 eps of that covers the row length (<= 50 terms).
    subroutine patch_test_linear_field(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: ELEMENTS(6) = [ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, &
                                             ELEMENT_P3, ELEMENT_P4]
        real(wp), parameter :: YOUNG = 2.5_wp, POISSON = 0.27_wp
        real(wp), parameter :: GRAD(2, 2) = reshape([0.3_wp, -0.7_wp, 1.1_wp, 0.4_wp], [2, 2])
        type(mesh_t) :: m
        type(dof_map_t) :: all_dofs
        type(csr_matrix_t) :: k
        type(status_t) :: stat
        real(wp), allocatable :: u(:), ku(:), f(:)
        real(wp) :: lame_l, shear_g, strain(2, 2), stress(2, 2), bound
        integer :: e, node

        call lame_coefficients(YOUNG, POISSON, lame_l, shear_g)
        strain = 0.5_wp*(GRAD + transpose(GRAD))   ! GRAD(i, j) = d u_i / d x_j
        stress = 2.0_wp*shear_g*strain
        stress(1, 1) = stress(1, 1) + lame_l*(strain(1, 1) + strain(2, 2))
        stress(2, 2) = stress(2, 2) + lame_l*(strain(1, 1) + strain(2, 2))
        do e = 1, size(ELEMENTS)
            call structured_rectangle(2.0_wp, 1.5_wp, 3, 2, ELEMENTS(e), merge('left ', 'right', &
                                      mod(e, 2) == 1), m, stat)
            call build_dof_map(m, [integer ::], all_dofs, stat)
            call assemble_stiffness(m, all_dofs, YOUNG, POISSON, k, stat)
            allocate (u(2*m%n_nodes()), ku(2*m%n_nodes()), f(2*m%n_nodes()))
            do node = 1, m%n_nodes()
                u(node_dofs(node, m%dim())) = [0.2_wp, -0.1_wp] + &
                                              matmul(GRAD, m%coords(:, node))
            end do
            call k%matvec(u, ku)
            f = 0.0_wp
            call edge_loads(m, [.true., .true., .true., .true.], [0.0_wp, 0.0_wp], stress, f, &
                            stat)
            call t%check(element_name(ELEMENTS(e))//': edge loads built', stat%ok())
            bound = 100.0_wp*epsilon(1.0_wp)*k%norm_inf()*maxval(abs(u))
            call t%check(element_name(ELEMENTS(e))//': K U = consistent loads of sigma(U) n', &
                         maxval(abs(ku - f)) <= bound)
            deallocate (u, ku, f)
        end do
    end subroutine patch_test_linear_field

    !> A constant traction on one side: the nodal forces add up to traction x length, and a
    !> pressure sigma = -p I pushes inward on every side (outward normals).
    subroutine traction_resultants(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: ELEMENTS(4) = [ELEMENT_P1, ELEMENT_Q2, ELEMENT_P3, ELEMENT_P4]
        real(wp), parameter :: WIDTH = 3.0_wp, HEIGHT = 0.5_wp, P = 2.0_wp
        type(mesh_t) :: m
        type(status_t) :: stat
        real(wp), allocatable :: f(:)
        real(wp) :: pressure(2, 2)
        integer :: e

        pressure = reshape([-P, 0.0_wp, 0.0_wp, -P], [2, 2])
        do e = 1, size(ELEMENTS)
            call structured_rectangle(WIDTH, HEIGHT, 4, 3, ELEMENTS(e), 'right', m, stat)
            allocate (f(2*m%n_nodes()), source=0.0_wp)
            call edge_loads(m, m%part_names == 'left', [0.7_wp, -1.3_wp], &
                            reshape([0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], [2, 2]), f, stat)
            ! sums of a few exact-ish terms: 1e-14 relative
            call t%check_close(element_name(ELEMENTS(e))//': x resultant on the left side', &
                               sum(f(1::2)), 0.7_wp*HEIGHT, 1.0e-14_wp)
            call t%check_close(element_name(ELEMENTS(e))//': y resultant on the left side', &
                               sum(f(2::2)), -1.3_wp*HEIGHT, 1.0e-14_wp)
            f = 0.0_wp
            call edge_loads(m, m%part_names == 'bottom', [0.0_wp, 0.0_wp], pressure, f, stat)
            call t%check_close(element_name(ELEMENTS(e))//': pressure on the bottom pushes up', &
                               sum(f(2::2)), P*WIDTH, 1.0e-14_wp)
            f = 0.0_wp
            call edge_loads(m, m%part_names == 'right', [0.0_wp, 0.0_wp], pressure, f, stat)
            call t%check_close(element_name(ELEMENTS(e))//': pressure on the right pushes left', &
                               sum(f(1::2)), -P*HEIGHT, 1.0e-14_wp)
            deallocate (f)
        end do
    end subroutine traction_resultants

    !> sum_a F_a = f |Omega| and sum_a x_a F_a = f int x (the shape functions reproduce x).
    subroutine body_force_resultant_and_moment(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: ELEMENTS(6) = [ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, &
                                             ELEMENT_P3, ELEMENT_P4]
        real(wp), parameter :: WIDTH = 2.0_wp, HEIGHT = 1.5_wp, FORCE(2) = [0.5_wp, -2.0_wp]
        type(mesh_t) :: m
        type(status_t) :: stat
        real(wp), allocatable :: f(:)
        integer :: e
        do e = 1, size(ELEMENTS)
            call structured_rectangle(WIDTH, HEIGHT, 3, 4, ELEMENTS(e), 'left', m, stat)
            allocate (f(2*m%n_nodes()), source=0.0_wp)
            call body_force_loads(m, FORCE, f)
            call t%check_close(element_name(ELEMENTS(e))//': body force y resultant', &
                               sum(f(2::2)), FORCE(2)*WIDTH*HEIGHT, 1.0e-14_wp)
            call t%check_close(element_name(ELEMENTS(e))//': body force moment about x2 = 0', &
                               sum(f(1::2)*m%coords(2, :)), &
                               FORCE(1)*WIDTH*HEIGHT*0.5_wp*HEIGHT, 1.0e-14_wp)
            deallocate (f)
        end do
    end subroutine body_force_resultant_and_moment
end program test_loads
