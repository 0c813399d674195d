! SPDX-License-Identifier: MIT
!> hp on the reference scene (unit square, nu = 0.3, lambda = 5, Gamma_D the top, Gamma_C the
!> bottom): geometric meshes toward the singular points found from the geometry, degrees
!> rising linearly away from them, the lowest positive mu against the continuum value of
!> tests/data/truths.csv, and where the time goes. Run by scripts/bench_hp.sh.
!> Arguments: sigma slope p_min n_start, then pairs (layers p_max) for each row.
program bench_hp
    use kinds, only: wp
    use status, only: status_t
    use timer, only: wall_time, timings_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use mesh_structured, only: structured_rectangle
    use mesh_singular, only: singular_vertices
    use mesh_geometric, only: geometric_mesh, cell_layers, layer_degrees
    use hp_space, only: hp_space_t
    use contact_boundary, only: contact_t
    use spectrum, only: spectrum_t
    use hp_eigen, only: hp_dense_spectrum
    implicit none

    real(wp), parameter :: TRUTH = 0.75284361680855649_wp   !! tests/data/truths.csv, ref
    type(mesh_t) :: m, graded
    type(hp_space_t) :: space
    type(contact_t) :: contact
    type(spectrum_t) :: spec
    type(timings_t) :: timings
    type(status_t) :: stat
    real(wp), allocatable :: points(:, :)
    integer, allocatable :: degree(:), layer(:), singular(:)
    character(len=64) :: arg
    real(wp) :: sigma, slope, h_min, start, mesh_seconds, total, mu
    integer :: p_min, n_start, i, layers, p_max, n_rows

    call get_command_argument(1, arg); read (arg, *) sigma
    call get_command_argument(2, arg); read (arg, *) slope
    call get_command_argument(3, arg); read (arg, *) p_min
    call get_command_argument(4, arg); read (arg, *) n_start
    n_rows = (command_argument_count() - 4)/2
    write (*, '(a)') '  layers  p_max  cells   dofs  contact     error      mesh  assembly'// &
        '  ordering    factor reduction     eigen     total'
    do i = 1, n_rows
        call get_command_argument(3 + 2*i, arg); read (arg, *) layers
        call get_command_argument(4 + 2*i, arg); read (arg, *) p_max
        start = wall_time()
        call structured_rectangle(1.0_wp, 1.0_wp, n_start, n_start, ELEMENT_P1, 'right', m, &
                                  stat)
        call check()
        singular = singular_vertices(m)
        points = m%coords(:, singular)
        call geometric_mesh(m, points, sigma, layers, graded, h_min, stat)
        call check()
        layer = cell_layers(graded, points, sigma, h_min)
        degree = layer_degrees(layer, p_min, slope, p_max)
        mesh_seconds = wall_time() - start
        timings = timings_t()
        call hp_dense_spectrum(graded, degree, [3], 1, 1.0_wp, 0.3_wp, 5.0_wp, 0, space, &
                               contact, spec, timings, stat)
        call check()
        total = wall_time() - start
        mu = -1.0_wp
        if (spec%lowest_positive() > 0) mu = real(spec%mu(1), wp)
        write (*, '(i8, i7, i7, i7, i9, es10.2, 7f10.4)') layers, p_max, graded%n_cells(), &
            space%n_free(), contact%p(), abs(mu - TRUTH)/TRUTH, mesh_seconds, &
            timings%assembly, timings%ordering, timings%factor, timings%reduction, &
            timings%eigen, total
    end do

contains

    subroutine check()
        if (.not. stat%ok()) then
            write (*, '(a)') 'bench_hp: '//stat%message
            error stop 1
        end if
    end subroutine check
end program bench_hp
