! SPDX-License-Identifier: MIT
!> hp on the reference scene (unit square, nu = 0.3, lambda = 5, Gamma_D the top, Gamma_C the
!> bottom) or another scene: geometric meshes toward the singular points found from the
!> geometry, degrees rising linearly away from them, the lowest positive mu against the
!> continuum value of tests/data/truths.csv, and where the time goes. Run by
!> scripts/bench/bench_hp.sh. Arguments: sigma slope p_min n_start (cells per side of the
!> starting square), then pairs (layers p_max) for each row. Each row is run three times:
!> the phase times are the last run's, total and cpu the medians. `dofs` are those of the
!> factor, `interior` those condensed out cell by cell. Another scene comes from the
!> environment: HP_MESH (a Gmsh file, instead of the square), HP_CONTACT (its Gamma_C
!> part; the clamped part is 'top'), HP_POISSON, HP_LAMBDA and HP_TRUTH.
program bench_hp
    use kinds, only: wp
    use status, only: status_t
    use timer, only: wall_time, timings_t
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use mesh_structured, only: structured_rectangle
    use mesh_gmsh, only: read_gmsh
    use mesh_singular, only: singular_vertices
    use mesh_geometric, only: geometric_mesh, cell_layers, layer_degrees
    use hp_basis, only: hp_bubble_count
    use hp_space, only: hp_space_t
    use hp_eigen, only: hp_lowest_positive, hp_dense_spectrum
    use contact_boundary, only: contact_t
    use spectrum, only: spectrum_t
    implicit none

    real(wp), parameter :: REF_TRUTH = 0.75284361680855649_wp   !! tests/data/truths.csv, ref
    integer, parameter :: RUNS = 3   !! each row is run this often; the median is shown
    type(mesh_t) :: m, graded
    type(hp_space_t) :: space
    type(timings_t) :: timings
    type(status_t) :: stat
    real(wp), allocatable :: points(:, :)
    integer, allocatable :: degree(:), layer(:), singular(:)
    character(len=64) :: arg
    real(wp) :: sigma, slope, h_min, start, mesh_seconds, mu, cpu_start, cpu_end
    real(wp) :: total(RUNS), cpu(RUNS)
    real(wp), allocatable :: mus(:)
    character(len=160), allocatable :: rows(:)
    integer :: p_min, n_start, i, layers, p_max, n_rows, run
    logical :: found
    type(contact_t) :: contact
    type(spectrum_t) :: spec
    character(len=:), allocatable :: mesh_file, contact_name, text
    real(wp) :: poisson, lambda, truth

    mesh_file = environment('HP_MESH', '')
    contact_name = environment('HP_CONTACT', 'bottom')
    text = environment('HP_POISSON', '0.3')
    read (text, *) poisson
    text = environment('HP_LAMBDA', '5.0')
    read (text, *) lambda
    text = environment('HP_TRUTH', '0')
    read (text, *) truth
    if (len(mesh_file) == 0) truth = REF_TRUTH

    call get_command_argument(1, arg); read (arg, *) sigma
    call get_command_argument(2, arg); read (arg, *) slope
    call get_command_argument(3, arg); read (arg, *) p_min
    call get_command_argument(4, arg); read (arg, *) n_start
    n_rows = (command_argument_count() - 4)/2
    allocate (mus(n_rows), rows(n_rows))
    write (*, '(a)') '  layers  p_max  cells   dofs  interior     error vs_finest     mesh'// &
        ' assembly ordering   factor   reduce    eigen    total      cpu'
    do i = 1, n_rows
        call get_command_argument(3 + 2*i, arg); read (arg, *) layers
        call get_command_argument(4 + 2*i, arg); read (arg, *) p_max
        do run = 1, RUNS
            call cpu_time(cpu_start)
            start = wall_time()
            if (len(mesh_file) > 0) then
                call read_gmsh(mesh_file, m, stat)
            else
                call structured_rectangle(1.0_wp, 1.0_wp, n_start, n_start, ELEMENT_P1, &
                                          'right', m, stat)
            end if
            call check()
            singular = singular_vertices(m)
            points = m%coords(:, singular)
            call geometric_mesh(m, points, sigma, layers, graded, h_min, stat)
            call check()
            layer = cell_layers(graded, points, sigma, h_min)
            degree = layer_degrees(layer, p_min, slope, p_max)
            mesh_seconds = wall_time() - start
            timings = timings_t()
            call hp_lowest_positive(graded, degree, [m%part_index('top')], &
                                    m%part_index(contact_name), 1.0_wp, poisson, lambda, space, &
                                    mu, found, timings, stat)
            call check()
            total(run) = wall_time() - start
            call cpu_time(cpu_end)
            cpu(run) = cpu_end - cpu_start
        end do
        if (.not. found) mu = -1.0_wp
        mus(i) = mu
        write (rows(i), '(i8, i7, i7, i7, i10, es10.2, a10, 8f9.3)') layers, p_max, &
            graded%n_cells(), space%n_free(), 2*sum(hp_bubble_count(degree)), &
            abs(mu - truth)/truth, '', mesh_seconds, &
            timings%assembly, timings%ordering, timings%factor, timings%reduction, &
            timings%eigen, median(total), median(cpu)
    end do
    ! vs_finest: the difference to the last (finest) row, hp's own convergence below the
    ! truth's uncertainty (4.6e-12)
    do i = 1, n_rows
        if (i < n_rows) write (rows(i)(50:59), '(es10.2)') abs(mus(i) - mus(n_rows))/mus(n_rows)
        write (*, '(a)') trim(rows(i))
    end do

    ! The full spectrum (all p eigenpairs lifted, with residuals) on the next-to-last mesh:
    ! what eigenvalues.csv needs beyond the critical c_n.
    i = max(1, n_rows - 1)
    call get_command_argument(3 + 2*i, arg); read (arg, *) layers
    call get_command_argument(4 + 2*i, arg); read (arg, *) p_max
    call geometric_mesh(m, points, sigma, layers, graded, h_min, stat)
    call check()
    degree = layer_degrees(cell_layers(graded, points, sigma, h_min), p_min, slope, p_max)
    timings = timings_t()
    start = wall_time()
    call hp_dense_spectrum(graded, degree, [m%part_index('top')], m%part_index(contact_name), &
                           1.0_wp, poisson, lambda, 1, space, contact, spec, timings, stat)
    call check()
    write (*, '(a, i0, a, i0, a, i0, a, 3(f0.3, a), es9.2, a, es9.2)') &
        'full spectrum, layers ', layers, ', p_max ', p_max, ': ', spec%n(), &
        ' eigenpairs; reduction ', timings%reduction, ' s, eigen (dgeevx, lift, residuals) ', &
        timings%eigen, ' s, total ', wall_time() - start, ' s; residual of the lowest', &
        spec%residual(1), ', largest', maxval(spec%residual)

contains

    !> The environment variable `name`, or `default` when unset or empty.
    function environment(name, default) result(value)
        character(len=*), intent(in) :: name, default
        character(len=:), allocatable :: value
        integer :: length, code
        call get_environment_variable(name, length=length, status=code)
        value = default
        if (code /= 0 .or. length == 0) return
        deallocate (value)
        allocate (character(len=length) :: value)
        call get_environment_variable(name, value)
    end function environment

    pure real(wp) function median(x)
        real(wp), intent(in) :: x(3)
        median = max(min(x(1), x(2)), min(max(x(1), x(2)), x(3)))
    end function median

    subroutine check()
        if (.not. stat%ok()) then
            write (*, '(a)') 'bench_hp: '//stat%message
            error stop 1
        end if
    end subroutine check
end program bench_hp
