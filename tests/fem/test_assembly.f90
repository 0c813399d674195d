! SPDX-License-Identifier: MIT
!> Global stiffness assembly on structured meshes of every element type: agreement with an
!> independent dense assembly, symmetry, rigid-body modes, positive definiteness with the top
!> side clamped, and patch tests (linear fields exactly; quadratic fields for P2/Q2; fields
!> of the element's degree for P3/P4); L2 convergence of order p + 1.
program test_assembly
    use kinds, only: wp
    use status, only: status_t, STATUS_MESH, STATUS_BAD_INPUT
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, ELEMENT_P4, &
                             MAX_ELEMENT, element_name, element_nodes_per_cell, &
                             element_degree, element_corners
    use mesh_structured, only: structured_rectangle
    use dof_map, only: dof_map_t, build_dof_map, cell_dofs
    use assembly, only: assemble_stiffness
    use csr_matrix, only: csr_matrix_t
    use elasticity, only: element_stiffness, plane_strain_matrix, lame_coefficients, &
                          stiffness_rule
    use cell_geometry, only: jacobian_at
    use quadrature, only: quadrature_rule_t, line_rule, triangle_rule, quad_rule
    use sparse_cholesky, only: cholesky_t
    use shape_functions, only: evaluate_shape, evaluate_line_shape, MAX_NODES
    use testing, only: test_suite_t
    use fixtures, only: csr_to_dense, rigid_mode
    implicit none

    interface
        subroutine dpotrf(uplo, n, a, lda, info)
            import :: wp
            character, intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotrf
    end interface

    real(wp), parameter :: YOUNG = 2.5_wp, POISSON = 0.3_wp
    ! A non-square rectangle with non-square cells, so that no symmetry hides an error.
    real(wp), parameter :: WIDTH = 2.0_wp, HEIGHT = 1.5_wp
    integer, parameter :: NX = 3, NY = 2
    ! Round-off bound for residuals of K u: each entry sums ~ (row length) products of size
    ! |K| |u| and cancels them; a few hundred ulps of |K|_inf |u|_inf is generous but still
    ! many orders below any modelling error (a wrong entry gives O(1) relative residuals).
    real(wp), parameter :: RESIDUAL_TOL = 1.0e-12_wp
    ! Linear field u = (a + b x + c y, d + e x + f y): eps = (b, f, c + e) in Voigt order.
    real(wp), parameter :: LIN(6) = [0.3_wp, 0.7_wp, -0.4_wp, -0.2_wp, 0.25_wp, 0.5_wp]

    ! Quadratic field u_x = al x^2 + be x y + ga y^2, u_y = de x^2 + ep x y + ze y^2.
    real(wp), parameter :: QUAD(6) = [0.4_wp, -0.3_wp, 0.2_wp, 0.15_wp, 0.35_wp, -0.25_wp]
    type(test_suite_t) :: t
    integer :: element

    t%name = 'test_assembly'
    do element = ELEMENT_P1, MAX_ELEMENT
        call check_free(element, 'right')
        if (element_corners(element) == 3) call check_free(element, 'left')
        call check_clamped(element)
    end do
    call check_errors()
    do element = ELEMENT_P1, MAX_ELEMENT
        call check_convergence(element)
    end do
    call t%report()

contains

    !> All dofs free: K against a dense assembly, symmetry, rigid modes, patch tests.
    subroutine check_free(element, diagonal)
        integer, intent(in) :: element
        character(len=*), intent(in) :: diagonal
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(csr_matrix_t) :: k
        type(status_t) :: stat
        real(wp), allocatable :: dense(:, :), reference(:, :), u(:), ku(:), load(:)
        real(wp) :: norm_k
        logical, allocatable :: on_boundary(:), interior_dof(:)
        character(len=:), allocatable :: label
        integer :: i, node

        label = ' ('//element_name(element)//', '//diagonal//')'
        call structured_rectangle(WIDTH, HEIGHT, NX, NY, element, diagonal, m, stat)
        call build_dof_map(m, [integer ::], dofs, stat)
        call t%check('no Dirichlet part: every dof free'//label, stat%ok() .and. &
                     dofs%n_free == 2*m%n_nodes())
        call assemble_stiffness(m, dofs, YOUNG, POISSON, k, stat)
        call t%check('assembly succeeds'//label, stat%ok())
        if (.not. stat%ok()) return

        dense = csr_to_dense(k)
        reference = dense_assembly(m, dofs)
        ! Same element matrices added in the same cell order: equal to round-off (the bound
        ! allows a different summation order).
        call t%check('CSR K equals the dense assembly'//label, &
                     maxval(abs(dense - reference)) <= 1.0e-14_wp*maxval(abs(reference)))
        call t%check('pattern symmetric'//label, pattern_symmetric(k))
        call t%check('K symmetric'//label, &
                     maxval(abs(dense - transpose(dense))) <= 1.0e-14_wp*maxval(abs(dense)))
        norm_k = k%norm_inf()

        allocate (u(dofs%n_free), ku(dofs%n_free))
        do i = 1, 3
            u = rigid_mode(m, i)
            call k%matvec(u, ku)
            call t%check('K kills rigid mode '//achar(48 + i)//label, &
                         maxval(abs(ku)) <= RESIDUAL_TOL*norm_k*maxval(abs(u)))
        end do

        ! Linear field: div sigma = 0, so K u is the consistent load of the constant
        ! traction sigma n: zero at interior nodes, closed-form weights on the boundary.
        allocate (on_boundary(m%n_nodes()), source=.false.)
        do i = 1, size(m%edges, 2)
            on_boundary(m%edges(:, i)) = .true.
        end do
        allocate (interior_dof(dofs%n_free))
        do node = 1, m%n_nodes()
            interior_dof(dofs%free_dof(:, node)) = .not. on_boundary(node)
        end do
        u = linear_field(m)
        call k%matvec(u, ku)
        load = linear_traction_load(m)
        call t%check('linear patch: K u = 0 at interior nodes'//label, &
                     maxval(abs(ku), mask=interior_dof) <= RESIDUAL_TOL*norm_k*maxval(abs(u)))
        call t%check('linear patch: K u = traction load sigma n at boundary nodes'//label, &
                     maxval(abs(ku - load)) <= RESIDUAL_TOL*norm_k*maxval(abs(u)))

        if (element == ELEMENT_P2 .or. element == ELEMENT_Q2) then
            ! Quadratic field, in the P2/Q2 space: K u = int f.v + int (sigma n).v with
            ! f = -div sigma constant; the body load in closed form, the traction load
            ! exactly integrated.
            u = quadratic_field(m)
            call k%matvec(u, ku)
            load = quadratic_body_load(m)
            ! The closed form against int f = f |Omega| and, since the nodes' x interpolate
            ! x exactly, sum_a x_a int f N_a = f int x = f |Omega| (WIDTH/2, HEIGHT/2). The
            ! terms summed share a sign, so round-off stays below (number of terms) ulps,
            ! ~1e-14; a wrong weight is off by O(1).
            call t%check_close('quadratic patch: body load sums to f_x area'//label, &
                               sum(load(1::2)), body_force(1)*WIDTH*HEIGHT, 1.0e-13_wp)
            call t%check_close('quadratic patch: body load sums to f_y area'//label, &
                               sum(load(2::2)), body_force(2)*WIDTH*HEIGHT, 1.0e-13_wp)
            call t%check_close('quadratic patch: x moment of the body load'//label, &
                               sum(m%coords(1, :)*load(2::2)), &
                               body_force(2)*WIDTH*HEIGHT*0.5_wp*WIDTH, 1.0e-13_wp)
            call t%check_close('quadratic patch: y moment of the body load'//label, &
                               sum(m%coords(2, :)*load(1::2)), &
                               body_force(1)*WIDTH*HEIGHT*0.5_wp*HEIGHT, 1.0e-13_wp)
            call t%check('quadratic patch: K u = body load at interior nodes'//label, &
                         maxval(abs(ku - load), mask=interior_dof) <= &
                         RESIDUAL_TOL*norm_k*maxval(abs(u)))
            load = load + quadratic_traction_load(m)
            call t%check('quadratic patch: K u = body + traction load everywhere'//label, &
                         maxval(abs(ku - load)) <= RESIDUAL_TOL*norm_k*maxval(abs(u)))
        end if
        if (element == ELEMENT_P3 .or. element == ELEMENT_P4) then
            ! A field of the element's degree p, in the space: K u equals its consistent
            ! loads int f.N_a + int (sigma n).N_a, integrated exactly (degree 2p - 2 over
            ! the cells, 2p - 1 along the edges).
            u = polynomial_field(m, element_degree(element))
            call k%matvec(u, ku)
            load = polynomial_load(m, element_degree(element))
            call t%check('degree-p patch: K u = body + traction load everywhere'//label, &
                         maxval(abs(ku - load)) <= RESIDUAL_TOL*norm_k*maxval(abs(u)))
        end if
    end subroutine check_free

    !> Coefficients of the field u_i = sum_k POLY(i, k) x^ex(k) y^ey(k) over the monomials of
    !> degree exactly p (3 or 4) plus the quadratic field QUAD, so that every degree <= p
    !> that a wrong stiffness could miss is present.
    subroutine polynomial_terms(p, coefficients, ex, ey)
        integer, intent(in) :: p
        real(wp), allocatable, intent(out) :: coefficients(:, :)
        integer, allocatable, intent(out) :: ex(:), ey(:)
        integer :: k
        ex = [2, 1, 0, [(p - k, k=0, p)]]
        ey = [0, 1, 2, [(k, k=0, p)]]
        allocate (coefficients(2, size(ex)))
        coefficients(1, 1:3) = QUAD(1:3)
        coefficients(2, 1:3) = QUAD(4:6)
        do k = 4, size(ex)
            coefficients(:, k) = [0.3_wp + 0.11_wp*k, 0.2_wp - 0.13_wp*k]*(-1)**k
        end do
    end subroutine polynomial_terms

    function polynomial_field(m, p) result(u)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: p
        real(wp), allocatable :: u(:), coefficients(:, :)
        integer, allocatable :: ex(:), ey(:)
        integer :: k
        call polynomial_terms(p, coefficients, ex, ey)
        allocate (u(2*m%n_nodes()), source=0.0_wp)
        do k = 1, size(ex)
            u(1::2) = u(1::2) + coefficients(1, k)*m%coords(1, :)**ex(k)*m%coords(2, :)**ey(k)
            u(2::2) = u(2::2) + coefficients(2, k)*m%coords(1, :)**ex(k)*m%coords(2, :)**ey(k)
        end do
    end function polynomial_field

    !> Gradient g(i, j) = d u_i / d x_j and second derivatives h(i, j, l) = d2 u_i / dx_j dx_l
    !> of the polynomial field at x.
    subroutine polynomial_derivatives(p, x, g, h)
        integer, intent(in) :: p
        real(wp), intent(in) :: x(2)
        real(wp), intent(out) :: g(2, 2), h(2, 2, 2)
        real(wp), allocatable :: coefficients(:, :)
        integer, allocatable :: ex(:), ey(:)
        integer :: k
        call polynomial_terms(p, coefficients, ex, ey)
        g = 0.0_wp
        h = 0.0_wp
        do k = 1, size(ex)
            associate (i => ex(k), j => ey(k), c => coefficients(:, k))
                g(:, 1) = g(:, 1) + c*i*power(x(1), i - 1)*power(x(2), j)
                g(:, 2) = g(:, 2) + c*j*power(x(1), i)*power(x(2), j - 1)
                h(:, 1, 1) = h(:, 1, 1) + c*i*(i - 1)*power(x(1), i - 2)*power(x(2), j)
                h(:, 1, 2) = h(:, 1, 2) + c*i*j*power(x(1), i - 1)*power(x(2), j - 1)
                h(:, 2, 2) = h(:, 2, 2) + c*j*(j - 1)*power(x(1), i)*power(x(2), j - 2)
            end associate
        end do
        h(:, 2, 1) = h(:, 1, 2)
    end subroutine polynomial_derivatives

    !> x^n, 0 for n < 0 (where the factor in front vanishes anyway).
    pure real(wp) function power(x, n)
        real(wp), intent(in) :: x
        integer, intent(in) :: n
        power = 0.0_wp
        if (n >= 0) power = x**n
    end function power

    !> int f.N_a over the cells (f = -div sigma, degree p - 2; rule of degree 8) plus
    !> int (sigma n).N_a over the boundary edges (5-point Gauss, exact to degree 9).
    function polynomial_load(m, p) result(load)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: p
        real(wp), allocatable :: load(:)
        type(quadrature_rule_t) :: rule
        real(wp) :: values(MAX_NODES), gradients(2, MAX_NODES), jacobian(2, 2), det, x(2), &
                    g(2, 2), h(2, 2, 2), f(2), stress(3), traction(2), n(2), length, &
                    line_values(5), derivatives(5), lame_l, shear_g
        integer :: cell, q, a, node, e, per_cell, per_edge
        call lame_coefficients(YOUNG, POISSON, lame_l, shear_g)
        allocate (load(2*m%n_nodes()), source=0.0_wp)
        per_cell = size(m%cells, 1)
        rule = triangle_rule(8)
        do cell = 1, m%n_cells()
            do q = 1, rule%n_points
                call evaluate_shape(m%element, rule%points(:, q), values, gradients)
                call jacobian_at(m%element, m%coords(:, m%cells(:, cell)), rule%points(:, q), &
                                 jacobian, det)
                x = matmul(m%coords(:, m%cells(:, cell)), values(:per_cell))
                call polynomial_derivatives(p, x, g, h)
                ! div sigma = (L + G) grad div u + G lap u
                f = -((lame_l + shear_g)*[h(1, 1, 1) + h(2, 2, 1), h(1, 1, 2) + h(2, 2, 2)] &
                      + shear_g*(h(:, 1, 1) + h(:, 2, 2)))
                do a = 1, per_cell
                    node = m%cells(a, cell)
                    load(2*node - 1:2*node) = load(2*node - 1:2*node) + &
                                              rule%weights(q)*det*values(a)*f
                end do
            end do
        end do
        per_edge = size(m%edges, 1)
        rule = line_rule(5)
        do e = 1, size(m%edges, 2)
            n = side_normal(m%part_names(m%edge_part(e)))
            length = norm2(m%coords(:, m%edges(2, e)) - m%coords(:, m%edges(1, e)))
            do q = 1, rule%n_points
                call evaluate_line_shape(per_edge, rule%points(1, q), line_values, derivatives)
                x = matmul(m%coords(:, m%edges(:, e)), line_values(:per_edge))
                call polynomial_derivatives(p, x, g, h)
                stress = matmul(plane_strain_matrix(YOUNG, POISSON), &
                                [g(1, 1), g(2, 2), g(1, 2) + g(2, 1)])
                traction = [stress(1)*n(1) + stress(3)*n(2), stress(3)*n(1) + stress(2)*n(2)]
                do a = 1, per_edge
                    node = m%edges(a, e)
                    load(2*node - 1:2*node) = load(2*node - 1:2*node) + &
                        rule%weights(q)*0.5_wp*length*line_values(a)*traction
                end do
            end do
        end do
    end function polynomial_load

    !> Top side clamped: the rigid modes are gone and K is positive definite.
    subroutine check_clamped(element)
        integer, intent(in) :: element
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(csr_matrix_t) :: k
        type(status_t) :: stat
        real(wp), allocatable :: dense(:, :)
        integer :: info, step
        character(len=:), allocatable :: label

        label = ' ('//element_name(element)//')'
        step = element_degree(element)
        call structured_rectangle(WIDTH, HEIGHT, NX, NY, element, 'right', m, stat)
        call build_dof_map(m, [m%part_index('top')], dofs, stat)
        call t%check('top clamped: 2 (nodes - top row) free dofs'//label, &
                     dofs%n_free == 2*(m%n_nodes() - (step*NX + 1)))
        call assemble_stiffness(m, dofs, YOUNG, POISSON, k, stat)
        allocate (dense, source=csr_to_dense(k))
        call t%check('top clamped: K equals the dense assembly'//label, &
                     maxval(abs(dense - dense_assembly(m, dofs))) <= &
                     1.0e-14_wp*maxval(abs(dense)))
        call dpotrf('L', size(dense, 1), dense, size(dense, 1), info)
        call t%check('top clamped: K is SPD (Cholesky succeeds)'//label, info == 0)
    end subroutine check_clamped

    subroutine check_errors()
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(csr_matrix_t) :: k
        type(status_t) :: stat
        integer :: swap
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        call build_dof_map(m, [integer ::], dofs, stat)
        ! Swapping two nodes of cell 5 turns it clockwise: det J = -2 area = -1/4.
        swap = m%cells(2, 5)
        m%cells(2, 5) = m%cells(3, 5)
        m%cells(3, 5) = swap
        call assemble_stiffness(m, dofs, YOUNG, POISSON, k, stat)
        call t%check('inverted cell: STATUS_MESH', stat%code == STATUS_MESH)
        call t%check('inverted cell: a message', allocated(stat%message))
        if (allocated(stat%message)) then
            call t%check('inverted cell: message names cell 5 and det J = -2.5E-01', &
                         index(stat%message, 'mesh: cell 5 is inverted or degenerate '// &
                               '(Jacobian determinant -2.50000E-01)') == 1)
        end if
        call assemble_stiffness(m, dofs, YOUNG, 0.5_wp, k, stat)
        call t%check('Poisson ratio 1/2: STATUS_BAD_INPUT', stat%code == STATUS_BAD_INPUT)
        call assemble_stiffness(m, dofs, -1.0_wp, POISSON, k, stat)
        call t%check('negative Young modulus: STATUS_BAD_INPUT', stat%code == STATUS_BAD_INPUT)
        call check_general_numbering()
        call build_dof_map(m, [7], dofs, stat)
        call t%check('unknown Dirichlet part index: STATUS_BAD_INPUT', &
                     stat%code == STATUS_BAD_INPUT)
    end subroutine check_errors

    !> A numbering that is not node-major (here: reversed) takes the general pattern path.
    subroutine check_general_numbering()
        type(mesh_t) :: m
        type(dof_map_t) :: dofs
        type(csr_matrix_t) :: k
        type(status_t) :: stat
        real(wp), allocatable :: dense(:, :)
        call structured_rectangle(WIDTH, HEIGHT, NX, NY, ELEMENT_P2, 'left', m, stat)
        call build_dof_map(m, [m%part_index('left')], dofs, stat)
        where (dofs%free_dof > 0) dofs%free_dof = dofs%n_free + 1 - dofs%free_dof
        call assemble_stiffness(m, dofs, YOUNG, POISSON, k, stat)
        allocate (dense, source=csr_to_dense(k))
        call t%check('reversed dof numbering: K equals the dense assembly', stat%ok() .and. &
                     maxval(abs(dense - dense_assembly(m, dofs))) <= &
                     1.0e-14_wp*maxval(abs(dense)))
    end subroutine check_general_numbering

    !> Dense K summed directly from element_stiffness, independent of the CSR code.
    function dense_assembly(m, dofs) result(a)
        type(mesh_t), intent(in) :: m
        type(dof_map_t), intent(in) :: dofs
        real(wp), allocatable :: a(:, :)
        real(wp), allocatable :: ke(:, :)
        integer, allocatable :: d(:)
        integer :: cell, i, j, info
        allocate (a(dofs%n_free, dofs%n_free), source=0.0_wp)
        allocate (ke(2*size(m%cells, 1), 2*size(m%cells, 1)))
        do cell = 1, m%n_cells()
            call element_stiffness(m%element, m%coords(:, m%cells(:, cell)), YOUNG, POISSON, &
                                   ke, info)
            d = cell_dofs(dofs, m, cell)
            do j = 1, size(d)
                do i = 1, size(d)
                    if (d(i) > 0 .and. d(j) > 0) a(d(i), d(j)) = a(d(i), d(j)) + ke(i, j)
                end do
            end do
        end do
    end function dense_assembly
    logical function pattern_symmetric(k)
        type(csr_matrix_t), intent(in) :: k
        integer :: i, s
        pattern_symmetric = .true.
        do i = 1, k%n()
            do s = k%row_start(i), k%row_start(i + 1) - 1
                if (k%slot(k%col(s), i) == 0) pattern_symmetric = .false.
            end do
        end do
    end function pattern_symmetric

    function linear_field(m) result(u)
        type(mesh_t), intent(in) :: m
        real(wp), allocatable :: u(:)
        allocate (u(2*m%n_nodes()))
        u(1::2) = LIN(1) + LIN(2)*m%coords(1, :) + LIN(3)*m%coords(2, :)
        u(2::2) = LIN(4) + LIN(5)*m%coords(1, :) + LIN(6)*m%coords(2, :)
    end function linear_field

    !> Outward unit normal of a side of the rectangle, from its part name.
    function side_normal(name) result(n)
        character(len=*), intent(in) :: name
        real(wp) :: n(2)
        select case (trim(name))
        case ('bottom'); n = [0.0_wp, -1.0_wp]
        case ('right'); n = [1.0_wp, 0.0_wp]
        case ('top'); n = [0.0_wp, 1.0_wp]
        case default; n = [-1.0_wp, 0.0_wp]
        end select
    end function side_normal

    !> Consistent nodal forces of the constant traction sigma(u) n of the linear field:
    !> int N_a ds over a straight edge of length h is h/2 for each end of a 2-node edge,
    !> and h/6, h/6, 2h/3 (Simpson) for the ends and mid node of a 3-node edge; Simpson's 3/8
    !> rule (h/8 at the ends, 3h/8 inside) for 4 nodes and Boole's rule (7h/90 at the ends,
    !> 32h/90, 12h/90, 32h/90 inside) for 5.
    function linear_traction_load(m) result(load)
        type(mesh_t), intent(in) :: m
        real(wp), allocatable :: load(:)
        real(wp) :: stress(3), traction(2), n(2), h, weights(5)
        integer :: e, a, node
        allocate (load(2*m%n_nodes()), source=0.0_wp)
        stress = matmul(plane_strain_matrix(YOUNG, POISSON), [LIN(2), LIN(6), LIN(3) + LIN(5)])
        do e = 1, size(m%edges, 2)
            n = side_normal(m%part_names(m%edge_part(e)))
            traction = [stress(1)*n(1) + stress(3)*n(2), stress(3)*n(1) + stress(2)*n(2)]
            h = norm2(m%coords(:, m%edges(2, e)) - m%coords(:, m%edges(1, e)))
            select case (size(m%edges, 1))
            case (2); weights(1:2) = [0.5_wp, 0.5_wp]
            case (3); weights(1:3) = [1.0_wp, 1.0_wp, 4.0_wp]/6.0_wp
            case (4); weights(1:4) = [1.0_wp, 1.0_wp, 3.0_wp, 3.0_wp]/8.0_wp
            case (5); weights(1:5) = [7.0_wp, 7.0_wp, 32.0_wp, 12.0_wp, 32.0_wp]/90.0_wp
            end select
            do a = 1, size(m%edges, 1)
                node = m%edges(a, e)
                load(2*node - 1:2*node) = load(2*node - 1:2*node) + weights(a)*h*traction
            end do
        end do
    end function linear_traction_load

    function quadratic_field(m) result(u)
        type(mesh_t), intent(in) :: m
        real(wp), allocatable :: u(:)
        allocate (u(2*m%n_nodes()))
        associate (x => m%coords(1, :), y => m%coords(2, :))
            u(1::2) = QUAD(1)*x**2 + QUAD(2)*x*y + QUAD(3)*y**2
            u(2::2) = QUAD(4)*x**2 + QUAD(5)*x*y + QUAD(6)*y**2
        end associate
    end function quadratic_field

    !> Voigt stress of the quadratic field at x: eps_xx = 2 al x + be y, eps_yy = ep x +
    !> 2 ze y, gamma_xy = (be + 2 de) x + (2 ga + ep) y.
    function quadratic_stress(x) result(stress)
        real(wp), intent(in) :: x(2)
        real(wp) :: stress(3), d(3, 3), strain(3)
        d = plane_strain_matrix(YOUNG, POISSON)
        strain = [2*QUAD(1)*x(1) + QUAD(2)*x(2), QUAD(5)*x(1) + 2*QUAD(6)*x(2), &
                  (QUAD(2) + 2*QUAD(4))*x(1) + (2*QUAD(3) + QUAD(5))*x(2)]
        stress = matmul(d, strain)
    end function quadratic_stress

    !> f = -div sigma of the quadratic field, constant:
    !> (div sigma)_x = 2 al (L + 2G) + ep L + G (2 ga + ep),
    !> (div sigma)_y = G (be + 2 de) + be L + 2 ze (L + 2G).
    function body_force(component) result(f)
        integer, intent(in) :: component
        real(wp) :: f, lame_l, shear_g
        call lame_coefficients(YOUNG, POISSON, lame_l, shear_g)
        if (component == 1) then
            f = -(2*QUAD(1)*(lame_l + 2*shear_g) + QUAD(5)*lame_l + &
                  shear_g*(2*QUAD(3) + QUAD(5)))
        else
            f = -(shear_g*(QUAD(2) + 2*QUAD(4)) + QUAD(2)*lame_l + &
                  2*QUAD(6)*(lame_l + 2*shear_g))
        end if
    end function body_force

    !> int f N_a over the mesh for the constant f, in closed form (no quadrature, no shape
    !> function code): on a straight-sided P2 triangle of area A, int N_a = 0 at the corners
    !> and A/3 at the mid-edge nodes; on a Q2 rectangle of area A, the product of the 1D
    !> Simpson weights 1/6, 2/3, 1/6: A/36 at the corners, A/9 at the mid-edge nodes, 4A/9 at
    !> the centre. Nodes in Gmsh order: corners, then mid-edge nodes, then the Q2 centre.
    function quadratic_body_load(m) result(load)
        type(mesh_t), intent(in) :: m
        real(wp), allocatable :: load(:)
        real(wp) :: f(2), weights(9), side_a(2), side_b(2), area
        integer :: cell, a, node, last_corner
        allocate (load(2*m%n_nodes()), source=0.0_wp)
        f = [body_force(1), body_force(2)]
        if (m%element == ELEMENT_P2) then
            weights(1:6) = [0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 1.0_wp]/3.0_wp
            last_corner = 3
        else
            weights = [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 4.0_wp, 4.0_wp, 4.0_wp, 4.0_wp, &
                       16.0_wp]/36.0_wp
            last_corner = 4
        end if
        do cell = 1, m%n_cells()
            ! The sides from corner 1 to corner 2 and to the last corner: the modulus of their
            ! cross product is the rectangle's area, twice the triangle's.
            side_a = m%coords(:, m%cells(2, cell)) - m%coords(:, m%cells(1, cell))
            side_b = m%coords(:, m%cells(last_corner, cell)) - m%coords(:, m%cells(1, cell))
            area = abs(side_a(1)*side_b(2) - side_a(2)*side_b(1))
            if (m%element == ELEMENT_P2) area = 0.5_wp*area
            do a = 1, size(m%cells, 1)
                node = m%cells(a, cell)
                load(2*node - 1:2*node) = load(2*node - 1:2*node) + weights(a)*area*f
            end do
        end do
    end function quadratic_body_load

    !> int (sigma n) N_a ds over the boundary edges, 3-point Gauss (exact: sigma is linear
    !> and N_a quadratic along a straight edge).
    function quadratic_traction_load(m) result(load)
        type(mesh_t), intent(in) :: m
        real(wp), allocatable :: load(:)
        type(quadrature_rule_t) :: rule
        real(wp) :: values(3), derivatives(3), x(2), n(2), stress(3), traction(2), h
        integer :: e, q, a, node
        allocate (load(2*m%n_nodes()), source=0.0_wp)
        rule = line_rule(3)
        do e = 1, size(m%edges, 2)
            n = side_normal(m%part_names(m%edge_part(e)))
            h = norm2(m%coords(:, m%edges(2, e)) - m%coords(:, m%edges(1, e)))
            do q = 1, rule%n_points
                call evaluate_line_shape(3, rule%points(1, q), values, derivatives)
                x = matmul(m%coords(:, m%edges(:, e)), values)
                stress = quadratic_stress(x)
                traction = [stress(1)*n(1) + stress(3)*n(2), stress(3)*n(1) + stress(2)*n(2)]
                do a = 1, 3
                    node = m%edges(a, e)
                    ! ds = (h/2) ds_ref on [-1, 1].
                    load(2*node - 1:2*node) = load(2*node - 1:2*node) + &
                                              rule%weights(q)*0.5_wp*h*values(a)*traction
                end do
            end do
        end do
    end function quadratic_traction_load
    !> Observed order of the L2 error on the unit square for the smooth displacement
    !> u = (sin(pi x) sin(pi y), sin(pi x) cos(pi y)), Dirichlet data (its interpolant) on the
    !> whole boundary and the body force f = -div sigma(u). On a convex domain with smooth u,
    !> Aubin-Nitsche gives ||u - u_h||_L2 = C h^(k+1) + O(h^(k+2)): order 2 for P1/Q1, 3 for
    !> P2/Q2, 4 for P3, 5 for P4. From h = 1/8 to 1/16 the higher-order term changes the
    !> observed order by about h ~ 0.1 (it was within 0.07 when this test was written; P3
    !> 4.06, P4 5.00 on their introduction); +-0.3 allows for that and still rejects an order
    !> lost to a wrong element (a whole order or more).
    subroutine check_convergence(element)
        integer, intent(in) :: element
        integer, parameter :: SIZES(3) = [4, 8, 16]
        real(wp) :: errors(3), observed, expected
        character(len=:), allocatable :: label
        integer :: i

        label = ' ('//element_name(element)//')'
        do i = 1, size(SIZES)
            errors(i) = manufactured_l2_error(element, SIZES(i))
        end do
        expected = real(element_degree(element) + 1, wp)
        observed = log(errors(2)/errors(3))/log(2.0_wp)
        write (*, '(a, 3es11.3, a, f6.3)') '      L2 errors'//label//':', errors, &
            '  observed order', observed
        call t%check('errors decrease with h'//label, errors(2) < errors(1) .and. &
                     errors(3) < errors(2))
        call t%check_close('observed L2 order on h = 1/8, 1/16 is k + 1'//label, observed, &
                           expected, 0.0_wp, 0.3_wp)
    end subroutine check_convergence

    !> ||u - u_h||_L2 on an n x n mesh of the unit square for the manufactured solution.
    function manufactured_l2_error(element, n) result(error)
        integer, intent(in) :: element, n
        real(wp) :: error
        ! Degree 5 on triangles, 4 x 4 Gauss on quadrilaterals: the load and the error
        ! integrals are then accurate to O(h^6), far below the errors measured; degree 8 for
        ! P3 and P4 (O(h^9) against errors of O(h^4), O(h^5)).
        type(quadrature_rule_t) :: rule
        type(mesh_t) :: m
        type(dof_map_t) :: all_free, inner
        type(csr_matrix_t) :: k_all, k_inner
        type(cholesky_t) :: chol
        type(status_t) :: stat
        real(wp), allocatable :: load(:, :), lifted(:), k_lifted(:), rhs(:, :), x(:, :), &
                                 u_h(:, :)
        real(wp) :: values(MAX_NODES), gradients(2, MAX_NODES), jacobian(2, 2), det, xq(2)
        integer :: cell, q, a, node, n_nodes_cell

        error = huge(1.0_wp)
        call structured_rectangle(1.0_wp, 1.0_wp, n, n, element, 'right', m, stat)
        call build_dof_map(m, [integer ::], all_free, stat)
        call build_dof_map(m, [1, 2, 3, 4], inner, stat)
        call assemble_stiffness(m, all_free, YOUNG, POISSON, k_all, stat)
        if (stat%ok()) call assemble_stiffness(m, inner, YOUNG, POISSON, k_inner, stat)
        if (.not. stat%ok()) return
        if (element == ELEMENT_P3 .or. element == ELEMENT_P4) then
            rule = triangle_rule(8)
        else if (element == ELEMENT_P1 .or. element == ELEMENT_P2) then
            rule = triangle_rule(5)
        else
            rule = quad_rule(4)
        end if
        n_nodes_cell = size(m%cells, 1)

        ! Consistent load int f . N_a, and the lifting K u_D of the boundary values.
        allocate (load(2, m%n_nodes()), source=0.0_wp)
        do cell = 1, m%n_cells()
            do q = 1, rule%n_points
                call evaluate_shape(element, rule%points(:, q), values, gradients)
                call jacobian_at(element, m%coords(:, m%cells(:, cell)), rule%points(:, q), &
                                 jacobian, det)
                xq = matmul(m%coords(:, m%cells(:, cell)), values(:n_nodes_cell))
                do a = 1, n_nodes_cell
                    load(:, m%cells(a, cell)) = load(:, m%cells(a, cell)) + &
                        rule%weights(q)*det*values(a)*manufactured_force(xq)
                end do
            end do
        end do
        allocate (lifted(all_free%n_free), source=0.0_wp)
        allocate (k_lifted(all_free%n_free))
        do node = 1, m%n_nodes()
            if (inner%free_dof(1, node) == 0) &
                lifted(all_free%free_dof(:, node)) = manufactured_u(m%coords(:, node))
        end do
        call k_all%matvec(lifted, k_lifted)
        allocate (rhs(inner%n_free, 1), x(inner%n_free, 1))
        do node = 1, m%n_nodes()
            if (inner%free_dof(1, node) == 0) cycle
            rhs(inner%free_dof(:, node), 1) = load(:, node) - k_lifted(all_free%free_dof(:, node))
        end do
        call chol%factor(k_inner, stat)
        if (stat%ok()) call chol%solve(rhs, x, stat)
        call chol%free()
        if (.not. stat%ok()) return

        allocate (u_h(2, m%n_nodes()))
        do node = 1, m%n_nodes()
            if (inner%free_dof(1, node) == 0) then
                u_h(:, node) = manufactured_u(m%coords(:, node))
            else
                u_h(:, node) = x(inner%free_dof(:, node), 1)
            end if
        end do
        error = 0.0_wp
        do cell = 1, m%n_cells()
            do q = 1, rule%n_points
                call evaluate_shape(element, rule%points(:, q), values, gradients)
                call jacobian_at(element, m%coords(:, m%cells(:, cell)), rule%points(:, q), &
                                 jacobian, det)
                xq = matmul(m%coords(:, m%cells(:, cell)), values(:n_nodes_cell))
                error = error + rule%weights(q)*det*sum((manufactured_u(xq) - &
                    matmul(u_h(:, m%cells(:, cell)), values(:n_nodes_cell)))**2)
            end do
        end do
        error = sqrt(error)
    end function manufactured_l2_error

    pure function manufactured_u(x) result(u)
        real(wp), intent(in) :: x(2)
        real(wp) :: u(2)
        real(wp), parameter :: PI = acos(-1.0_wp)
        u = [sin(PI*x(1))*sin(PI*x(2)), sin(PI*x(1))*cos(PI*x(2))]
    end function manufactured_u

    !> f = -div sigma = -((L + G) grad div u + G lap u) for manufactured_u, where
    !> div u = pi sin(pi y) (cos(pi x) - sin(pi x)) and lap u = -2 pi^2 u.
    pure function manufactured_force(x) result(f)
        real(wp), intent(in) :: x(2)
        real(wp) :: f(2), lame_l, shear_g, grad_div(2)
        real(wp), parameter :: PI = acos(-1.0_wp)
        call lame_coefficients(YOUNG, POISSON, lame_l, shear_g)
        grad_div = PI**2*[-sin(PI*x(2))*(sin(PI*x(1)) + cos(PI*x(1))), &
                          cos(PI*x(2))*(cos(PI*x(1)) - sin(PI*x(1)))]
        f = -((lame_l + shear_g)*grad_div - 2.0_wp*PI**2*shear_g*manufactured_u(x))
    end function manufactured_force
end program test_assembly
