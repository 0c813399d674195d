! SPDX-License-Identifier: MIT
!> The effective width of a mode on Gamma_C in cells (mode_resolution), on fields whose
!> width is known: W = (int u_n^2)^2 / int u_n^4 is the whole segment for a constant u_n
!> (so n cells on n x n squares, whatever the degree: the nodes of P2 are half a cell
!> apart, and the lumped masses still sum to the length), and the one node's share of the
!> length for u_n nonzero at one interior P1 node (one cell). W does not change with the
!> scale or sign of the mode; it is not measured with fewer than three contact nodes or
!> u_n = 0.
program test_mode_resolution
    use kinds, only: wp
    use fixtures, only: problem_of
    use status, only: status_t
    use testing, only: test_suite_t
    use run_config, only: config_t
    use problem, only: problem_t, build_problem
    use mesh, only: mesh_t
    use mode_resolution, only: contact_mode_cells
    use fixtures, only: square_scene, single_element_scene
    implicit none

    type(test_suite_t) :: t

    t%name = 'test_mode_resolution'
    call constant_mode_spans_the_segment(t, 'p1')
    call constant_mode_spans_the_segment(t, 'p2')
    call spike_is_one_cell(t)
    call scale_and_sign_do_not_matter(t)
    call not_measurable(t)
    call t%report()

contains

    !> n x n squares of `element`, the problem built.
    subroutine scene(n, element, prob)
        integer, intent(in) :: n
        character(len=*), intent(in) :: element
        type(problem_t), intent(out) :: prob
        type(config_t) :: config
        type(status_t) :: stat
        call square_scene(n, element, 'right', config)
        call problem_of(config, prob, stat)
        if (.not. stat%ok()) error stop 'test_mode_resolution: problem not built'
    end subroutine scene

    !> The free-dof vector with normal displacement u_n(a) at contact node a, zero elsewhere.
    function normal_field(prob, u_n) result(phi)
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: u_n(:)
        real(wp), allocatable :: phi(:)
        allocate (phi(prob%dofs%n_free), source=0.0_wp)
        call prob%contact%scatter(prob%contact%normal, u_n, phi)
    end function normal_field

    subroutine constant_mode_spans_the_segment(t, element)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: element
        type(problem_t) :: prob
        real(wp), allocatable :: u_n(:)
        call scene(4, element, prob)
        allocate (u_n(prob%contact%p()), source=1.0_wp)
        call t%check_close('constant u_n on 4 x 4 '//element//': 4 cells', &
                           contact_mode_cells(prob, normal_field(prob, u_n)), 4.0_wp, 1.0e-14_wp)
    end subroutine constant_mode_spans_the_segment

    !> u_n = 1 at the middle contact node of 8 x 8 P1 only: W = h, one cell.
    subroutine spike_is_one_cell(t)
        type(test_suite_t), intent(inout) :: t
        type(problem_t) :: prob
        real(wp), allocatable :: u_n(:)
        call scene(8, 'p1', prob)
        allocate (u_n(prob%contact%p()), source=0.0_wp)
        u_n(5) = 1.0_wp
        call t%check_close('u_n at one interior P1 node: 1 cell', &
                           contact_mode_cells(prob, normal_field(prob, u_n)), 1.0_wp, 1.0e-14_wp)
    end subroutine spike_is_one_cell

    !> A smooth profile, then the same times -3: the same width (to rounding).
    subroutine scale_and_sign_do_not_matter(t)
        type(test_suite_t), intent(inout) :: t
        type(problem_t) :: prob
        real(wp), allocatable :: u_n(:), phi(:)
        integer :: a
        call scene(8, 'p1', prob)
        allocate (u_n(prob%contact%p()))
        do a = 1, size(u_n)
            u_n(a) = 1.0_wp + real(a, wp)**2
        end do
        phi = normal_field(prob, u_n)
        call t%check_close('-3 phi has the width of phi', contact_mode_cells(prob, -3.0_wp*phi), &
                           contact_mode_cells(prob, phi), 1.0e-14_wp)
    end subroutine scale_and_sign_do_not_matter

    !> The single element has one contact node; a zero mode has no width: both -1 (< 0).
    subroutine not_measurable(t)
        type(test_suite_t), intent(inout) :: t
        type(problem_t) :: prob
        type(config_t) :: config
        type(mesh_t) :: m
        type(status_t) :: stat
        real(wp), allocatable :: phi(:)
        call single_element_scene('unused', config, m)
        call problem_of(config, prob, stat, given_mesh=m)
        allocate (phi(prob%dofs%n_free), source=1.0_wp)
        call t%check('one contact node: not measured', stat%ok() .and. &
                     contact_mode_cells(prob, phi) < 0.0_wp)
        call scene(4, 'p1', prob)
        deallocate (phi)
        allocate (phi(prob%dofs%n_free), source=0.0_wp)
        call t%check('u_n = 0: not measured', contact_mode_cells(prob, phi) < 0.0_wp)
    end subroutine not_measurable
end program test_mode_resolution
