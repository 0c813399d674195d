! SPDX-License-Identifier: MIT
!> The hp space and its eigenproblems against independent answers: the Dirichlet Laplacian's
!> first eigenvalue 2 pi^2 on the unit square converging exponentially under p-refinement
!> alone; the contact spectrum of hp spaces of uniform degree 1 to 4 equal to that of the
!> Lagrange P1 to P4 elements on the same mesh (the same spaces in other bases: equal to
!> round-off); the single element's closed form.
program test_hp_eigen
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use fixtures, only: single_triangle, contact_scene
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P2, ELEMENT_P3, ELEMENT_P4
    use mesh_structured, only: structured_rectangle
    use contact_boundary, only: contact_t, assemble_b
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use spectrum, only: spectrum_t
    use dense_eigen, only: dense_spectrum
    use contact_reduction, only: reduced_blocks_t
    use timer, only: timings_t
    use hp_basis, only: hp_bubble_count
    use hp_space, only: hp_space_t, build_hp_space
    use hp_stiffness, only: hp_element_laplace, hp_reference_tables, HP_OK
    use hp_eigen, only: hp_dense_spectrum, hp_lowest_positive, hp_factored_problem
    use arpack_eigen, only: arpack_options_t, arpack_search, arpack_finish, arpack_search_t
    use mesh_singular, only: singular_vertices
    use mesh_geometric, only: geometric_mesh, cell_layers, layer_degrees
    implicit none

    interface
        subroutine dsygv(itype, jobz, uplo, n, a, lda, b, ldb, w, work, lwork, info)
            import :: wp
            integer, intent(in) :: itype, n, lda, ldb, lwork
            character(len=1), intent(in) :: jobz, uplo
            real(wp), intent(inout) :: a(lda, *), b(ldb, *)
            real(wp), intent(out) :: w(*), work(*)
            integer, intent(out) :: info
        end subroutine dsygv
    end interface

    type(test_suite_t) :: t
    t%name = 'test_hp_eigen'
    call laplace_eigenvalue_converges_exponentially_in_p(t)
    call uniform_degree_equals_lagrange(t)
    call single_element_closed_form(t)
    call solvers_agree_on_a_graded_mesh(t)
    call t%report()

contains

    !> -Laplace u = lambda u on ]0,1[^2, u = 0 on the boundary: lambda_1 = 2 pi^2, its mode
    !> sin(pi x) sin(pi y) analytic, so on a fixed mesh of 8 triangles the error of the
    !> Rayleigh-Ritz value falls exponentially in p (Babuska-Szabo). Measured: 2e-3 at p = 3,
    !> 2e-10 at p = 7, 1e-13 at p = 9, then a round-off floor of 1e-13 to 5e-13 (the mass
    !> matrix's condition grows with p); asserted: below 1e-10 from p = 10 on, and each step
    !> of 2 in p gaining at least a factor 30 (measured: 20 to 700 per single step) while the
    !> error is above 1e-11.
    subroutine laplace_eigenvalue_converges_exponentially_in_p(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: PI = acos(-1.0_wp)
        real(wp) :: error(12), exact
        character(len=80) :: what
        integer :: p
        exact = 2.0_wp*PI**2
        do p = 1, 12
            error(p) = abs(laplace_lowest(p) - exact)/exact
        end do
        write (*, '(a, 12es9.1)') '      relative errors, p = 1..12:', error
        do p = 10, 12
            write (what, '(a, i0)') 'Laplace 2 pi^2 to 1e-10 at p = ', p
            call t%check(trim(what), error(p) < 1.0e-10_wp)
        end do
        do p = 2, 10
            if (error(p) < 1.0e-11_wp) cycle
            write (what, '(a, i0, a, i0)') 'exponential in p: error(p + 2) < error(p)/30, p = ', p
            call t%check(trim(what), error(p + 2) < error(p)/30.0_wp)
        end do
    end subroutine laplace_eigenvalue_converges_exponentially_in_p

    !> The lowest eigenvalue of the Laplacian with Dirichlet conditions on the hp space of
    !> uniform degree p on a 2 x 2 mesh (8 cells), interior functions kept (dense dsygv).
    real(wp) function laplace_lowest(p) result(lowest)
        integer, intent(in) :: p
        type(mesh_t) :: m
        type(hp_space_t) :: space
        type(status_t) :: stat
        real(wp), allocatable :: a(:, :), b(:, :), ke(:, :), me(:, :), w(:), work(:)
        integer, allocatable :: global(:), functions(:)
        integer :: c, n_free, n, nb, i, info, next
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        call build_hp_space(m, [(p, c=1, m%n_cells())], [1, 2, 3, 4], space, stat)
        n_free = maxval([0, space%free_function])
        n = n_free + m%n_cells()*hp_bubble_count(p)
        allocate (a(n, n), b(n, n), source=0.0_wp)
        next = n_free
        do c = 1, m%n_cells()
            functions = space%cell_functions(c, m%cells(:, c))
            nb = hp_bubble_count(p)
            global = [space%free_function(functions), (next + i, i=1, nb)]
            next = next + nb
            call hp_element_laplace(m%coords(:, m%cells(:, c)), hp_reference_tables( &
                space%edge_degrees_of(c), p, space%cell_flip(:, c)), ke, me, info)
            if (info /= HP_OK .or. .not. stat%ok()) then
                lowest = huge(1.0_wp)
                return
            end if
            do i = 1, size(global)
                if (global(i) == 0) cycle
                a(global(i), pack(global, global > 0)) = a(global(i), pack(global, global > 0)) &
                                                         + pack(ke(i, :), global > 0)
                b(global(i), pack(global, global > 0)) = b(global(i), pack(global, global > 0)) &
                                                         + pack(me(i, :), global > 0)
            end do
        end do
        allocate (w(n), work(64*n))
        call dsygv(1, 'N', 'U', n, a, n, b, n, w, work, size(work), info)
        lowest = w(1)
        if (info /= 0) lowest = huge(1.0_wp)
    end function laplace_lowest

    !> Reference scene (unit square, E = 1, nu = 0.3, lambda = 5, top clamped, contact at
    !> the bottom) on a 3 x 3 mesh: hp of uniform degree p and Lagrange Pp span the same
    !> space, so the pencils (K, B) are congruent and every eigenvalue must agree to
    !> round-off: 1e-11 relative (condition numbers of these mu are below 1e3).
    subroutine uniform_degree_equals_lagrange(t)
        type(test_suite_t), intent(inout) :: t
        integer, parameter :: LAGRANGE(4) = [ELEMENT_P1, ELEMENT_P2, ELEMENT_P3, ELEMENT_P4]
        type(mesh_t) :: vertices, m
        type(spectrum_t) :: hp, lagrange_spec
        type(hp_space_t) :: space
        type(contact_t) :: contact
        type(timings_t) :: timings
        type(status_t) :: stat
        character(len=80) :: what
        integer :: p, c, i
        call structured_rectangle(1.0_wp, 1.0_wp, 3, 3, ELEMENT_P1, 'right', vertices, stat)
        do p = 1, 4
            call structured_rectangle(1.0_wp, 1.0_wp, 3, 3, LAGRANGE(p), 'right', m, stat)
            call lagrange_spectrum(m, [3], 1, 5.0_wp, lagrange_spec)
            call hp_dense_spectrum(vertices, [(p, c=1, vertices%n_cells())], [3], 1, 1.0_wp, &
                                   0.3_wp, 5.0_wp, 0, space, contact, hp, timings, stat)
            write (what, '(a, i0, a)') 'degree ', p, ': hp runs'
            call t%check(trim(what), stat%ok())
            write (what, '(a, i0, a)') 'degree ', p, ': as many eigenvalues as Lagrange'
            call t%check(trim(what), hp%n() == lagrange_spec%n())
            if (hp%n() /= lagrange_spec%n() .or. hp%n() == 0) cycle
            write (what, '(a, i0, a)') 'degree ', p, ': lowest positive mu equals Lagrange'
            call t%check_close(trim(what), real(hp%mu(1), wp), real(lagrange_spec%mu(1), wp), &
                               1.0e-11_wp)
            write (what, '(a, i0, a)') 'degree ', p, ': whole spectrum equals Lagrange'
            call t%check(trim(what), all([(abs(hp%mu(i) - lagrange_spec%mu(i)) <= 1.0e-11_wp* &
                                           abs(lagrange_spec%mu(i)), i=1, hp%n())]))
        end do
    end subroutine uniform_degree_equals_lagrange

    !> One P1 triangle A = (0,0), B = (l,0), C = (0,l), B and C clamped (the edge BC), Gamma_C
    !> = AB: mu = -6 G (L + 2G) / ((L (lambda + 1) + G (lambda + 3)) l) at degree 1 (the
    !> model's known answer), to 1e-12: exact algebra on 2 x 2 matrices.
    subroutine single_element_closed_form(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), parameter :: LAMBDAS(4) = [-10.0_wp, -3.0_wp, 0.0_wp, 5.0_wp]
        real(wp), parameter :: YOUNG = 1.0_wp, POISSON = 0.3_wp, L_SIZE = 0.5_wp
        type(mesh_t) :: m
        type(spectrum_t) :: spec
        type(hp_space_t) :: space
        type(contact_t) :: contact
        type(timings_t) :: timings
        type(status_t) :: stat
        real(wp) :: lame_l, shear_g, expected
        character(len=80) :: what
        integer :: i
        lame_l = YOUNG*POISSON/((1.0_wp + POISSON)*(1.0_wp - 2.0_wp*POISSON))
        shear_g = YOUNG/(2.0_wp*(1.0_wp + POISSON))
        call single_triangle(L_SIZE, m)
        do i = 1, size(LAMBDAS)
            call hp_dense_spectrum(m, [1], [2], 1, YOUNG, POISSON, LAMBDAS(i), 0, space, &
                                   contact, spec, timings, stat)
            expected = -6.0_wp*shear_g*(lame_l + 2.0_wp*shear_g)/ &
                       ((lame_l*(LAMBDAS(i) + 1.0_wp) + shear_g*(LAMBDAS(i) + 3.0_wp))*L_SIZE)
            write (what, '(a, f6.1)') 'single element, degree 1, lambda =', LAMBDAS(i)
            call t%check(trim(what)//': one eigenvalue', stat%ok() .and. spec%n() == 1)
            if (spec%n() == 1) call t%check_close(trim(what), real(spec%mu(1), wp), expected, &
                                                  1.0e-12_wp)
        end do
    end subroutine single_element_closed_form

    !> On a geometric hp mesh (6 layers, degrees 1 to 7, 3120 dofs) the eigensolvers that
    !> take a contact_t must agree on the lowest positive mu: the dense reduced solver,
    !> ARPACK on the reduced operator and on the full operator (K - sigma B)^-1 B, and the
    !> eigenvalues-only path. All are backward stable on a mu of condition below 1e2, so
    !> 1e-10 relative (ARPACK's tolerance is machine epsilon).
    subroutine solvers_agree_on_a_graded_mesh(t)
        type(test_suite_t), intent(inout) :: t
        type(mesh_t) :: m, graded
        type(hp_space_t) :: space
        type(contact_t) :: contact
        type(spectrum_t) :: dense, arpack
        type(timings_t) :: timings
        type(status_t) :: stat
        type(csr_matrix_t) :: k, b
        type(cholesky_t) :: chol
        type(arpack_options_t) :: options
        type(arpack_search_t) :: search
        character(len=:), allocatable :: warning
        real(wp), allocatable :: points(:, :)
        integer, allocatable :: degree(:)
        real(wp) :: h_min, mu
        logical :: found
        character(len=80) :: what
        integer :: i
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        allocate (points(2, 0))   ! (gfortran 12 warns of an unallocated one at -O3)
        points = m%coords(:, singular_vertices(m))
        call geometric_mesh(m, points, 0.15_wp, 6, graded, h_min, stat)
        degree = layer_degrees(cell_layers(graded, points, 0.15_wp, h_min), 1, 1.0_wp, 7)
        call hp_dense_spectrum(graded, degree, [3], 1, 1.0_wp, 0.3_wp, 5.0_wp, 1, space, &
                               contact, dense, timings, stat)
        call t%check('graded mesh: dense spectrum', stat%ok() .and. dense%lowest_positive() == 1)
        if (.not. stat%ok() .or. dense%lowest_positive() /= 1) return
        call t%check('graded mesh: residual of the lowest below 1e-14', dense%residual(1) < &
                     1.0e-14_wp)
        call t%check('graded mesh: condition of the lowest below 1e2', &
                     dense%condition(1) < 1.0e2_wp)
        call hp_lowest_positive(graded, degree, [3], 1, 1.0_wp, 0.3_wp, 5.0_wp, space, mu, &
                                found, timings, stat)
        call t%check('graded mesh: eigenvalues-only path finds it', stat%ok() .and. found)
        call t%check_close('graded mesh: eigenvalues-only path equals dense', mu, &
                           real(dense%mu(1), wp), 1.0e-10_wp)
        call hp_factored_problem(graded, degree, [3], 1, 1.0_wp, 0.3_wp, space, contact, k, &
                                 chol, timings, stat)
        if (stat%ok()) call assemble_b(contact, space%n_free(), 5.0_wp, b, stat)
        call t%check('graded mesh: K, B and the factor', stat%ok())
        if (.not. stat%ok()) return
        do i = 1, 2
            options%full = i == 2
            call arpack_search(k, b, chol, contact, 5.0_wp, options, search, stat)
            if (stat%ok()) call arpack_finish(k, b, chol, contact, 5.0_wp, options, 1, search, &
                                              arpack, warning, stat)
            write (what, '(a, l1)') 'graded mesh: ARPACK equals dense, full operator ', &
                options%full
            call t%check(trim(what)//': certified', stat%ok() .and. len(warning) == 0 .and. &
                         arpack%lowest_positive() == 1)
            if (arpack%lowest_positive() == 1) call t%check_close(trim(what), &
                real(arpack%mu(1), wp), real(dense%mu(1), wp), 1.0e-10_wp)
        end do
    end subroutine solvers_agree_on_a_graded_mesh

    !> The dense spectrum of the Lagrange elements of mesh m (E = 1, nu = 0.3), from the
    !> fixtures' contact scene (K, its factor and the contact blocks).
    subroutine lagrange_spectrum(m, dirichlet_parts, contact_part, lambda, spec)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: dirichlet_parts(:), contact_part
        real(wp), intent(in) :: lambda
        type(spectrum_t), intent(out) :: spec
        type(reduced_blocks_t) :: blocks
        type(contact_t) :: contact
        type(csr_matrix_t) :: k, b
        type(cholesky_t) :: chol
        type(status_t) :: stat
        call contact_scene(m, dirichlet_parts, contact_part, 0.3_wp, blocks, stat, k=k, &
                           contact=contact, chol=chol)
        if (stat%ok()) call assemble_b(contact, k%n(), lambda, b, stat)
        if (stat%ok()) call dense_spectrum(k, b, chol, contact, lambda, 0, spec, stat, &
                                           kt_nn_given=blocks%kt_nn, kt_nt_given=blocks%kt_nt)
        call t%check('Lagrange reference solve', stat%ok())
        if (.not. stat%ok()) allocate (spec%mu(0), spec%kind(0))
    end subroutine lagrange_spectrum
end program test_hp_eigen
