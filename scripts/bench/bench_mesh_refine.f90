! SPDX-License-Identifier: MIT
!> Speed of newest-vertex bisection: uniform refinement of a structured P1 mesh up to at least
!> TARGET cells (each step refines every cell: the largest closure-free workload), then the
!> P2 conversion and, optionally, the MSH 4.1 file of the finest mesh. Prints the time and
!> the new cells per second of each step. Usage: bench_mesh_refine [TARGET_CELLS [FILE.msh]]
program bench_mesh_refine
    use iso_fortran_env, only: output_unit, error_unit
    use kinds, only: wp
    use status, only: status_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P2
    use mesh_structured, only: structured_rectangle
    use mesh_refine, only: refinable_mesh_t, build_refinable_mesh
    use gmsh_writer, only: write_gmsh
    use timer, only: wall_time
    implicit none

    type(mesh_t) :: m, fine
    type(refinable_mesh_t) :: r
    type(status_t) :: stat
    character(len=4096) :: argument
    integer :: target_cells, c, step, n_before
    real(wp) :: start, seconds, total

    target_cells = 1000000
    if (command_argument_count() >= 1) then
        call get_command_argument(1, argument)
        read (argument, *) target_cells
    end if
    call structured_rectangle(1.0_wp, 1.0_wp, 16, 16, ELEMENT_P1, 'right', m, stat)
    if (stat%ok()) call build_refinable_mesh(m, r, stat)
    call stop_on_failure()
    write (output_unit, '(a)') '# step  cells_before   cells_after   seconds  cells_after_per_s'
    total = 0.0_wp
    step = 0
    do while (r%n_cells() < target_cells)
        step = step + 1
        n_before = r%n_cells()
        start = wall_time()
        call r%refine([(c, c=1, n_before)], stat)
        seconds = wall_time() - start
        call stop_on_failure()
        total = total + seconds
        write (output_unit, '(i6, 2i14, f10.3, es16.3)') step, n_before, r%n_cells(), &
            seconds, real(r%n_cells(), wp)/max(seconds, 1.0e-9_wp)
    end do
    write (output_unit, '(a, i0, a, f0.3, a, es10.3, a)') '# ', r%n_cells(), ' cells in ', &
        total, ' s of refine: ', real(r%n_cells(), wp)/max(total, 1.0e-9_wp), &
        ' cells/s overall'
    start = wall_time()
    call r%to_mesh(ELEMENT_P2, fine, stat)
    call stop_on_failure()
    write (output_unit, '(a, i0, a, f0.3, a)') '# to_mesh P2: ', fine%n_nodes(), ' nodes in ', &
        wall_time() - start, ' s'
    if (command_argument_count() >= 2) then
        call get_command_argument(2, argument)
        start = wall_time()
        call write_gmsh(trim(argument), fine, stat)
        call stop_on_failure()
        write (output_unit, '(a, f0.3, a)') '# write_gmsh: ', wall_time() - start, ' s'
    end if

contains

    subroutine stop_on_failure()
        if (stat%ok()) return
        write (error_unit, '(a)') 'bench_mesh_refine: '//stat%message
        error stop 1
    end subroutine stop_on_failure
end program bench_mesh_refine
