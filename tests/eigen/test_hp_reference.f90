! SPDX-License-Identifier: MIT
!> hp on the reference scene (unit square, E = 1, nu = 0.3, lambda = 5, top clamped, contact
!> at the bottom): geometric meshes toward the singular points found from the geometry and
!> the parts, degrees rising away from them. The lowest positive mu must converge
!> exponentially in dofs^(1/3) to the continuum value of tests/data/truths.csv
!> (0.75284361680855649 +- 4.6e-12, computed by graded P4 meshes and extrapolation, an
!> independent method), from the structured rectangle and from a Gmsh file alike.
program test_hp_reference
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use msh_writer, only: write_msh41
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use mesh_structured, only: structured_rectangle
    use mesh_gmsh, only: read_gmsh
    use mesh_singular, only: singular_vertices
    use mesh_geometric, only: geometric_mesh, cell_layers, layer_degrees
    use hp_space, only: hp_space_t
    use contact_boundary, only: contact_t
    use spectrum, only: spectrum_t
    use timer, only: timings_t
    use hp_eigen, only: hp_dense_spectrum
    implicit none

    real(wp), parameter :: TRUTH = 0.75284361680855649_wp
    real(wp), parameter :: TRUTH_UNCERTAINTY = 4.57e-12_wp
    real(wp), parameter :: SIGMA = 0.15_wp, SLOPE = 1.0_wp
    integer, parameter :: P_MIN = 1
    type(test_suite_t) :: t
    t%name = 'test_hp_reference'
    call singular_points_of_the_square(t)
    call exponential_convergence_from_the_rectangle(t)
    call gmsh_mesh_agrees(t)
    call half_contact_scene(t)
    call t%report()

contains

    !> The four corners are the only singular points of the square: each is a turn of the
    !> boundary and a change of part; no other boundary vertex is either.
    subroutine singular_points_of_the_square(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m
        type(status_t) :: stat
        integer, allocatable :: singular(:)
        call structured_rectangle(1.0_wp, 1.0_wp, 4, 4, ELEMENT_P1, 'left', m, stat)
        allocate (singular(0))   ! (gfortran 12 warns of an unallocated one at -O3)
        singular = singular_vertices(m)
        call t%check('four singular points', size(singular) == 4)
        if (size(singular) /= 4) return
        call t%check('... at the corners', all(abs(m%coords(:, singular) - &
                     nint(m%coords(:, singular))) < 1.0e-15_wp))
    end subroutine singular_points_of_the_square

    !> Layers 4, 6, 8, 10 with the top degree 5 to 8. Measured relative errors 1.3e-6,
    !> 3.1e-8, 2.6e-11, 1.5e-12 at 1524 to 7308 dofs: ln(error) falls by about 2 per unit
    !> of dofs^(1/3). Asserted: every step gains a factor 10 while above the truth's
    !> uncertainty, the last is within 1e-10 (the target of the method; the truth is known
    !> to 4.6e-12), and the rate b in error ~ exp(-b dofs^(1/3)) from the first to the third
    !> mesh exceeds 1, which no algebraic rate can sustain over this range.
    subroutine exponential_convergence_from_the_rectangle(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: LAYERS(4) = [4, 6, 8, 10], P_MAX(4) = [5, 6, 7, 8]
        type(mesh_t) :: m
        type(status_t) :: stat
        real(wp) :: error(4), dofs(4), rate
        character(len=80) :: what
        integer :: i
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        do i = 1, size(LAYERS)
            call hp_lowest(m, LAYERS(i), P_MAX(i), error(i), dofs(i))
        end do
        write (*, '(a, 4es10.2, a, 4f8.0)') '      errors', error, ' at dofs', dofs
        do i = 2, size(LAYERS)
            if (error(i - 1) < 100.0_wp*TRUTH_UNCERTAINTY) cycle
            write (what, '(a, i0, a)') 'rectangle: mesh ', i, ' gains a factor 10'
            call t%check(trim(what), error(i) < error(i - 1)/10.0_wp)
        end do
        call t%check_close('rectangle: c_n to 1e-10 at 10 layers, degree 8', error(4), &
                           0.0_wp, 0.0_wp, 1.0e-10_wp)
        rate = log(error(1)/error(3))/(dofs(3)**(1.0_wp/3) - dofs(1)**(1.0_wp/3))
        call t%check('rectangle: exponential rate in dofs^(1/3) above 1', rate > 1.0_wp)
    end subroutine exponential_convergence_from_the_rectangle

    !> A 3 x 3 mesh with its inner vertices moved (no longer structured) written as MSH 4.1
    !> and read back: the singular points come from its physical groups, and the hp value
    !> must meet the truth as the rectangle's does (1e-10 at 10 layers, degree 8).
    subroutine gmsh_mesh_agrees(t)
        type(test_suite_t), intent(inout) :: t
        character(len=*), parameter :: PATH = 'test_hp_reference.msh'
        type(mesh_t) :: m, from_file
        type(status_t) :: stat
        real(wp) :: error, dofs
        integer :: node, unit
        call structured_rectangle(1.0_wp, 1.0_wp, 3, 3, ELEMENT_P1, 'left', m, stat)
        do node = 1, m%n_nodes()
            associate (xy => m%coords(:, node))
                if (all(xy > 1.0e-12_wp .and. xy < 1.0_wp - 1.0e-12_wp)) &
                    xy = xy + 0.07_wp*[sin(7.0_wp*node), cos(5.0_wp*node)]
            end associate
        end do
        call write_msh41(PATH, m, clockwise=.true.)
        call read_gmsh(PATH, from_file, stat)
        call t%check('Gmsh: the mesh reads back', stat%ok())
        open (newunit=unit, file=PATH)
        close (unit, status='delete')
        if (.not. stat%ok()) return
        call t%check('Gmsh: four singular points from the physical groups', &
                     size(singular_vertices(from_file)) == 4)
        call hp_lowest(from_file, 10, 8, error, dofs)
        write (*, '(a, es10.2, a, f8.0)') '      Gmsh error', error, ' at dofs', dofs
        call t%check_close('Gmsh: c_n to 1e-10 at 10 layers, degree 8', error, 0.0_wp, &
                           0.0_wp, 1.0e-10_wp)
    end subroutine gmsh_mesh_agrees

    !> The 'half-contact' scene of truths.csv (0.79347392036932429 +- 1.5e-12): contact on
    !> the left half of the bottom only, the right half free, lambda = -3. Its fifth
    !> singular point, (1/2, 0), is a change of part on a straight side. Measured 1.5e-12 at
    !> 9 layers, degree 10 (1.4e-12 from a Gmsh mesh of the scene); asserted 1e-10.
    subroutine half_contact_scene(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: HALF_CONTACT = 0.79347392036932429_wp
        type(mesh_t) :: m
        type(status_t) :: stat
        real(wp) :: error, dofs
        integer :: e
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        m%part_names = [character(len=len(m%part_names)) :: m%part_names, 'contact']
        do e = 1, size(m%edge_part)
            if (m%edge_part(e) == m%part_index('bottom') .and. &
                maxval(m%coords(1, m%edges(1:2, e))) <= 0.5_wp) &
                m%edge_part(e) = m%part_index('contact')
        end do
        call t%check('half contact: five singular points', size(singular_vertices(m)) == 5)
        call hp_lowest(m, 9, 10, error, dofs, 'contact', -3.0_wp, HALF_CONTACT)
        write (*, '(a, es10.2, a, f8.0)') '      half contact error', error, ' at dofs', dofs
        call t%check_close('half contact: c_n to 1e-10 at 9 layers, degree 10', error, 0.0_wp, &
                           0.0_wp, 1.0e-10_wp)
    end subroutine half_contact_scene

    !> Relative error of the lowest positive mu on the geometric mesh of m with `layers`
    !> and degrees up to p_max; 'top' clamped, Gamma_C the part `contact` (default 'bottom'),
    !> lambda and the expected value those of the reference scene unless given.
    subroutine hp_lowest(m, layers, p_max, error, dofs, contact, lambda, expected)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: layers, p_max
        real(wp), intent(out) :: error, dofs
        character(len=*), intent(in), optional :: contact
        real(wp), intent(in), optional :: lambda, expected
        type(mesh_t) :: graded
        type(hp_space_t) :: space
        type(contact_t) :: contact_data
        type(spectrum_t) :: spec
        type(timings_t) :: timings
        type(status_t) :: stat
        real(wp), allocatable :: points(:, :)
        real(wp) :: h_min, scene_lambda, scene_truth
        integer, allocatable :: degree(:)
        integer :: contact_part
        contact_part = m%part_index('bottom')
        if (present(contact)) contact_part = m%part_index(contact)
        scene_lambda = 5.0_wp
        if (present(lambda)) scene_lambda = lambda
        scene_truth = TRUTH
        if (present(expected)) scene_truth = expected
        error = huge(1.0_wp)
        dofs = 0.0_wp
        allocate (points(2, 0))   ! (gfortran 12 warns of an unallocated one at -O3)
        points = m%coords(:, singular_vertices(m))
        call geometric_mesh(m, points, SIGMA, layers, graded, h_min, stat)
        if (stat%ok()) then
            degree = layer_degrees(cell_layers(graded, points, SIGMA, h_min), P_MIN, SLOPE, &
                                   p_max)
            call hp_dense_spectrum(graded, degree, [m%part_index('top')], contact_part, &
                                   1.0_wp, 0.3_wp, scene_lambda, 0, space, contact_data, spec, &
                                   timings, stat)
        end if
        call t%check('hp solve runs', stat%ok())
        if (.not. stat%ok()) return
        dofs = real(space%n_free(), wp)
        if (spec%lowest_positive() > 0) error = abs(real(spec%mu(1), wp) - scene_truth)/scene_truth
    end subroutine hp_lowest
end program test_hp_reference
