! SPDX-License-Identifier: MIT
!> A stiffness matrix K without a Dirichlet boundary is singular (rigid motions): the eigen
!> analysis must stop with STATUS_SINGULAR and a message that says so, not a library code.
!> Input validation rejects an empty dirichlet list first; this covers what gets past it
!> (e.g. a Gmsh physical group of one point).
program test_singular_stiffness
    use kinds, only: wp
    use fixtures, only: eigen_of
    use status, only: status_t, STATUS_SINGULAR
    use testing, only: test_suite_t
    use timer, only: timings_t
    use run_config, only: config_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q2
    use mesh_structured, only: structured_rectangle
    use problem, only: problem_t
    use eigen_solve, only: eigen_result_t, solve_eigen
    use dof_map, only: build_dof_map
    use contact_boundary, only: build_contact
    use assembly, only: assemble_stiffness
    implicit none

    type(test_suite_t) :: t
    t%name = 'test_singular_stiffness'
    call no_dirichlet_boundary(t, ELEMENT_P1)
    call no_dirichlet_boundary(t, ELEMENT_Q2)
    call t%report()

contains

    subroutine no_dirichlet_boundary(t, element)
        type(test_suite_t), intent(inout) :: t
        integer, intent(in) :: element
        type(config_t) :: c
        type(problem_t) :: prob
        type(eigen_result_t) :: res
        type(timings_t) :: timings
        type(status_t) :: stat
        c%input_file = 'no dirichlet'
        c%eigen%solver = 'dense'
        call structured_rectangle(1.0_wp, 1.0_wp, 3, 3, element, 'right', prob%mesh, stat)
        prob%young = 1.0_wp
        prob%poisson = 0.3_wp
        allocate (prob%dirichlet_parts(0))
        if (stat%ok()) call build_dof_map(prob%mesh, prob%dirichlet_parts, prob%dofs, stat)
        if (stat%ok()) call build_contact(prob%mesh, prob%mesh%part_index('bottom'), prob%dofs, &
                                          prob%contact, stat)
        if (stat%ok()) call assemble_stiffness(prob%mesh, prob%dofs, 1.0_wp, 0.3_wp, prob%k, stat)
        call t%check('setup', stat%ok())
        call eigen_of(c, prob, 5.0_wp, res, timings, stat)
        call t%check('no Dirichlet boundary: STATUS_SINGULAR', stat%code == STATUS_SINGULAR)
        ! No message at all is a failure too, not a skipped check.
        call t%check('the message names K, singular and the Dirichlet boundary', &
                     message_has(stat, 'K is singular') .and. message_has(stat, 'Dirichlet'))
        if (allocated(stat%message)) write (*, '(a)') '      '//stat%message
    end subroutine no_dirichlet_boundary

    !> Whether stat carries a message containing `text` (false without a message).
    pure logical function message_has(stat, text)
        type(status_t), intent(in) :: stat
        character(len=*), intent(in) :: text
        message_has = .false.
        if (allocated(stat%message)) message_has = index(stat%message, text) > 0
    end function message_has
end program test_singular_stiffness
