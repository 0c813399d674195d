! SPDX-License-Identifier: MIT
!> hp_rayleigh against an independent evaluation in quadruple precision: the same energy
!> form of the same vectors with the basis, the rule, the map and every sum in real128
!> (the basis and rule sources of src/element instantiated at that kind below), so its
!> rounding is some 1e-30 and what it measures is the double form's own error.
module quad_basis
    use iso_fortran_env, only: rk => real128
    include 'hp_basis_body.inc'
end module quad_basis

module quad_rules
    use iso_fortran_env, only: rk => real128
    include 'gauss_rules_body.inc'
end module quad_rules

program test_hp_rayleigh
    use iso_fortran_env, only: qp => real128
    use kinds, only: wp
    use status, only: status_t
    use testing, only: test_suite_t
    use mesh, only: mesh_t
    use fixtures, only: square_hp_level
    use contact_boundary, only: contact_t, assemble_b
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t
    use spectrum, only: spectrum_t
    use timer, only: timings_t
    use elasticity, only: lame_coefficients
    use hp_basis, only: hp_local_count
    use hp_space, only: hp_space_t
    use hp_stiffness, only: hp_tables_t, hp_cell_fields
    use hp_eigen, only: hp_dense_spectrum, hp_factored_problem
    use hp_rayleigh, only: hp_stiffness_form, refine_lowest_mu
    use roundoff, only: ROUNDOFF_UNITS
    use quad_basis, only: quad_shape => hp_triangle_shape
    use quad_rules, only: quad_rule_t => gauss_rule_t, quad_triangle_rule => triangle_rule_exact
    implicit none

    real(wp), parameter :: YOUNG = 1.0_wp, POISSON = 0.3_wp, LAMBDA = 5.0_wp
    type(test_suite_t) :: t
    type(mesh_t) :: graded
    type(hp_space_t) :: space
    type(contact_t) :: contact
    type(spectrum_t) :: spec
    type(status_t) :: stat

    t%name = 'test_hp_rayleigh'
    call graded_level(graded, space, contact, spec, stat)
    call t%check('graded hp level: dense spectrum with its left vector', stat%ok() .and. &
                 spec%lowest_positive() == 1 .and. allocated(spec%left))
    if (stat%ok() .and. spec%lowest_positive() == 1 .and. allocated(spec%left)) then
        call form_matches_quadruple_precision(t)
        call form_of_nearly_rigid_fields(t)
        call form_matches_assembled_k(t)
        call refined_mu_within_the_double_bound(t)
    end if
    call t%report()

contains

    !> The unit square clamped on top, contact on the bottom (lambda = 5), graded in 10
    !> layers of ratio 0.15 toward its singular vertices, degrees 1 to 10 by layer: cells
    !> down to 1e-8 wide, where the assembled K loses digits to cancellation.
    subroutine graded_level(graded, space, contact, spec, stat)
        type(mesh_t), intent(out) :: graded
        type(hp_space_t), intent(out) :: space
        type(contact_t), intent(out) :: contact
        type(spectrum_t), intent(out) :: spec
        type(status_t), intent(out) :: stat
        type(mesh_t) :: m
        type(timings_t) :: timings
        integer, allocatable :: degree(:)
        call square_hp_level(10, 10, m, graded, degree, stat)
        if (.not. stat%ok()) return
        call hp_dense_spectrum(graded, degree, [3], 1, YOUNG, POISSON, LAMBDA, 1, space, &
                               contact, spec, timings, stat)
    end subroutine graded_level

    !> The eigenvectors' form y' K x: the double form within its stated bound
    !> (ROUNDOFF_UNITS eps times its componentwise size) of the quadruple one.
    subroutine form_matches_quadruple_precision(t)
        type(test_suite_t), intent(inout) :: t
        call compare_with_quadruple(t, 'eigenvectors', real(spec%vectors(:, 1), wp), spec%left)
    end subroutine form_matches_quadruple_precision

    !> Fields that are a translation plus a 1e-6 perturbation (random, fixed seed): nearly
    !> all of |y|'|K||x| cancels, yet the form keeps its bound against quadruple precision.
    subroutine form_of_nearly_rigid_fields(t)
        type(test_suite_t), intent(inout) :: t
        real(wp), allocatable :: x(:), y(:)
        integer, allocatable :: seed(:)
        integer :: n
        call random_seed(size=n)
        allocate (seed(n), source=20261127)
        call random_seed(put=seed)
        allocate (x(space%n_free()), y(space%n_free()))
        call random_number(x)
        call random_number(y)
        x = 1.0e-6_wp*x
        y = 1.0e-6_wp*y
        x(1:space%n_free():2) = x(1:space%n_free():2) + 1.0_wp
        y(2:space%n_free():2) = y(2:space%n_free():2) - 3.0_wp
        call compare_with_quadruple(t, 'nearly rigid fields', x, y)
    end subroutine form_of_nearly_rigid_fields

    subroutine compare_with_quadruple(t, what, x, y)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: what
        real(wp), intent(in) :: x(:), y(:)
        real(wp) :: form, form_abs
        real(qp) :: exact
        type(status_t) :: stat
        call hp_stiffness_form(graded, space, YOUNG, POISSON, x, y, form, form_abs, stat)
        call t%check(what//': double form computed', stat%ok())
        call quadruple_form(x, y, exact, stat)
        call t%check(what//': quadruple form computed', stat%ok())
        call t%check(what//': within ROUNDOFF_UNITS eps of its size', &
                     abs(real(form, qp) - exact) <= ROUNDOFF_UNITS*epsilon(1.0_wp)*form_abs)
        call t%check(what//': its size bounds the value', abs(form) <= form_abs)
    end subroutine compare_with_quadruple

    !> The form of the eigenvectors equals y' K x with the assembled, condensed K within the
    !> assembled product's own rounding (4 eps |y|'|K||x|, as module roundoff counts it):
    !> the form is the same bilinear form, its interior functions recovered.
    subroutine form_matches_assembled_k(t)
        type(test_suite_t), intent(inout) :: t
        type(hp_space_t) :: same_space
        type(contact_t) :: same_contact
        type(csr_matrix_t) :: k
        type(cholesky_t) :: chol
        type(timings_t) :: timings
        type(status_t) :: stat
        real(wp), allocatable :: x(:), y(:), kx(:), kx_abs(:)
        real(wp) :: form, form_abs
        allocate (x(size(spec%left)), y(size(spec%left)))   ! (gfortran 12 -O3 warnings)
        x = real(spec%vectors(:, 1), wp)
        y = spec%left
        call hp_factored_problem(graded, space%cell_degree, [3], 1, YOUNG, POISSON, &
                                 same_space, same_contact, k, chol, timings, stat)
        call t%check('assembled K: built', stat%ok())
        if (.not. stat%ok()) return
        call chol%free()
        allocate (kx(size(x)), kx_abs(size(x)))
        call k%matvec(x, kx)
        k%val = abs(k%val)
        call k%matvec(abs(x), kx_abs)
        call hp_stiffness_form(graded, space, YOUNG, POISSON, x, y, form, form_abs, stat)
        call t%check('assembled K: the form equals y''K x within its rounding', stat%ok() .and. &
                     abs(form - dot_product(y, kx)) <= ROUNDOFF_UNITS*epsilon(1.0_wp)* &
                     (dot_product(abs(y), kx_abs) + form_abs))
    end subroutine form_matches_assembled_k

    !> The refined mu and the double one both lie within their bounds of the exact discrete
    !> eigenvalue, so they differ by at most the sum of the bounds; and the refined bound is
    !> far below the double one on this mesh (the point of the refinement).
    subroutine refined_mu_within_the_double_bound(t)
        type(test_suite_t), intent(inout) :: t
        real(wp) :: mu, refined, refined_bound
        type(csr_matrix_t) :: b
        type(status_t) :: stat
        mu = real(spec%mu(1), wp)
        call assemble_b(contact, space%n_free(), LAMBDA, b, stat)
        call t%check('refined mu: B assembled', stat%ok())
        if (.not. stat%ok()) return
        call refine_lowest_mu(graded, space, YOUNG, POISSON, contact, b, LAMBDA, mu, &
                              real(spec%vectors(:, 1), wp), spec%left, spec%roundoff(1), &
                              minval(abs(spec%mu(2:) - mu))/mu, refined, refined_bound, stat)
        call t%check('refined mu: computed', stat%ok())
        call t%check('refined mu: within the two bounds of the double one', &
                     abs(refined - mu) <= (spec%roundoff(1) + refined_bound)*mu)
        call t%check('refined mu: its bound a tenth of the double one or less', &
                     refined_bound <= 0.1_wp*spec%roundoff(1))
    end subroutine refined_mu_within_the_double_bound

    !> y' K x with every step in quadruple precision (the interior coefficients recovered in
    !> double, as hp_stiffness_form does: they are part of the vectors, not of the form).
    subroutine quadruple_form(x, y, form, stat)
        real(wp), intent(in) :: x(:), y(:)
        real(qp), intent(out) :: form
        type(status_t), intent(out) :: stat
        type(hp_tables_t), allocatable :: tables(:)
        real(wp), allocatable :: coefficients(:, :), fields(:, :)
        real(wp) :: lame_l, shear_g
        integer :: c, p, n_tables, t
        allocate (fields(size(x), 2))
        fields(:, 1) = x
        fields(:, 2) = y
        form = 0.0_qp
        call lame_coefficients(YOUNG, POISSON, lame_l, shear_g)
        n_tables = 0
        do c = 1, graded%n_cells()
            p = space%cell_degree(c)
            call hp_cell_fields(graded, space, c, YOUNG, POISSON, fields, tables, n_tables, &
                                coefficients, t, stat)
            if (.not. stat%ok()) return
            form = form + quadruple_cell(c, p, real(lame_l, qp), real(shear_g, qp), &
                                        coefficients(:, 1), coefficients(:, 2))
        end do
    end subroutine quadruple_form

    real(qp) function quadruple_cell(c, p, lame_l, shear_g, cx, cy) result(form)
        integer, intent(in) :: c, p
        real(qp), intent(in) :: lame_l, shear_g
        real(wp), intent(in) :: cx(:), cy(:)
        type(quad_rule_t) :: rule
        real(qp) :: xy(2, 3), jacobian(2, 2), inverse_t(2, 2), det, gx(2, 2), gy(2, 2)
        real(qp), allocatable :: values(:), gradients(:, :), physical(:, :), ux(:, :), uy(:, :)
        integer :: n, q
        n = hp_local_count(space%edge_degrees_of(c), p)
        allocate (values(n), gradients(2, n), physical(2, n))
        ux = reshape(real(cx, qp), [2, n])
        uy = reshape(real(cy, qp), [2, n])
        xy = real(graded%coords(:, graded%cells(1:3, c)), qp)
        jacobian(:, 1) = xy(:, 2) - xy(:, 1)
        jacobian(:, 2) = xy(:, 3) - xy(:, 1)
        det = jacobian(1, 1)*jacobian(2, 2) - jacobian(1, 2)*jacobian(2, 1)
        inverse_t = reshape([jacobian(2, 2), -jacobian(1, 2), -jacobian(2, 1), &
                             jacobian(1, 1)], [2, 2])/det
        rule = quad_triangle_rule(2*(p - 1))
        form = 0.0_qp
        do q = 1, rule%n_points()
            call quad_shape(space%edge_degrees_of(c), p, space%cell_flip(:, c), &
                            rule%points(:, q), values, gradients)
            physical = matmul(inverse_t, gradients)
            gx = matmul(ux, transpose(physical))
            gy = matmul(uy, transpose(physical))
            form = form + rule%weights(q)*(lame_l*(gx(1, 1) + gx(2, 2))*(gy(1, 1) + gy(2, 2)) + &
                   0.5_qp*shear_g*sum((gx + transpose(gx))*(gy + transpose(gy))))
        end do
        form = det*form
    end function quadruple_cell
end program test_hp_rayleigh
