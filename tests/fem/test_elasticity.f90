! SPDX-License-Identifier: MIT
!> Hooke's law and element stiffness matrices: the single element of model.md section 8, symmetry,
!> rigid-body modes and rank on distorted elements, and the inverted-cell report.
program test_elasticity
    use kinds, only: wp
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, &
                             ELEMENT_P4, MAX_ELEMENT, element_nodes_per_cell, element_name, &
                             element_corners
    use shape_functions, only: reference_nodes, MAX_NODES
    use elasticity, only: plane_strain_matrix, lame_coefficients, element_stiffness, &
                          ELEMENT_OK, ELEMENT_INVERTED, ELEMENT_BAD_ARGUMENT, &
                          stiffness_tables_t, stiffness_tables, element_energy
    use testing, only: test_suite_t
    implicit none

    interface
        subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
            import :: wp
            character, intent(in) :: jobz, uplo
            integer, intent(in) :: n, lda, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: w(*), work(*)
            integer, intent(out) :: info
        end subroutine dsyev
    end interface

    ! E = 1, nu = 0.3 give the reference scene's L = 15/26, G = 5/13 (model.md section 10).
    real(wp), parameter :: YOUNG = 1.0_wp, POISSON = 0.3_wp
    real(wp), parameter :: LAME_L = 15.0_wp/26.0_wp, SHEAR_G = 5.0_wp/13.0_wp
    type(test_suite_t) :: t
    integer :: element

    t%name = 'test_elasticity'
    call check_lame()
    call check_single_element()
    do element = ELEMENT_P1, MAX_ELEMENT
        call check_distorted(element)
    end do
    call check_bad_cells()
    do element = ELEMENT_P1, MAX_ELEMENT
        call check_tiny_straight_cell(element)
    end do
    call t%report()

contains

    subroutine check_lame()
        real(wp) :: lame_l, shear_g, d(3, 3), expected(3, 3)
        call lame_coefficients(YOUNG, POISSON, lame_l, shear_g)
        ! A few ulps: each coefficient is two or three rounded operations.
        call t%check_close('L = E nu / ((1 + nu)(1 - 2 nu)) = 15/26', lame_l, LAME_L, 1.0e-15_wp)
        call t%check_close('G = E / (2 (1 + nu)) = 5/13', shear_g, SHEAR_G, 1.0e-15_wp)
        d = plane_strain_matrix(YOUNG, POISSON)
        expected = reshape([LAME_L + 2*SHEAR_G, LAME_L, 0.0_wp, LAME_L, LAME_L + 2*SHEAR_G, &
                            0.0_wp, 0.0_wp, 0.0_wp, SHEAR_G], [3, 3])
        call t%check('plane-strain D = [L+2G L 0; L L+2G 0; 0 0 G] (engineering shear)', &
                     maxval(abs(d - expected)) <= 1.0e-15_wp*maxval(abs(expected)))
    end subroutine check_lame

    !> P1 triangle A = (0,0), B = (l,0), C = (0,l). grad N_A = (-1/l, -1/l), area l^2/2, so
    !> the (A, A) block of area B_A^T D B_A is 1/2 [[L+3G, L+G], [L+G, L+3G]] in (x, y): the
    !> xx entry is area ((L+2G)/l^2 + G/l^2), the xy entry area (L/l^2 + G/l^2). With
    !> u_n = -u_y, u_t = -u_x the (u_n, u_t) block of model.md section 8 is the same matrix.
    !> Independent of l: stiffness scales as l^0 in 2D.
    subroutine check_single_element()
        real(wp), parameter :: SIZES(3) = [1.0_wp, 0.01_wp, 100.0_wp]
        real(wp) :: ke(6, 6), xy(2, 3), expected(2, 2), l
        integer :: i, info
        character(len=32) :: label
        expected = 0.5_wp*reshape([LAME_L + 3*SHEAR_G, LAME_L + SHEAR_G, &
                                   LAME_L + SHEAR_G, LAME_L + 3*SHEAR_G], [2, 2])
        do i = 1, size(SIZES)
            l = SIZES(i)
            write (label, '(a, es8.1)') ' l =', l
            xy = reshape([0.0_wp, 0.0_wp, l, 0.0_wp, 0.0_wp, l], [2, 3])
            call element_stiffness(ELEMENT_P1, xy, YOUNG, POISSON, ke, info)
            call t%check('single element: info ok'//trim(label), info == ELEMENT_OK)
            ! 1e-12 relative as asked; the computation is a handful of roundings (~1e-16).
            call t%check('single element: K_AA = 1/2 [L+3G L+G; L+G L+3G]'//trim(label), &
                         maxval(abs(ke(1:2, 1:2) - expected)) <= 1.0e-12_wp*maxval(expected))
            call t%check('single element: ke symmetric'//trim(label), &
                         maxval(abs(ke - transpose(ke))) <= 0.0_wp)
        end do
    end subroutine check_single_element

    !> A general (non-affine for quadrilaterals, curved for P2) element: ke symmetric, kills
    !> the three rigid-body modes, and has exactly three zero eigenvalues (no spurious
    !> zero-energy mode from the quadrature).
    subroutine check_distorted(element)
        integer, intent(in) :: element
        real(wp), allocatable :: xy(:, :), ke(:, :), modes(:, :), work(:), eigenvalues(:)
        real(wp) :: residual, scale, largest, ref_nodes(2, MAX_NODES)
        integer :: n, n_corners, info, i, n_zero
        character(len=:), allocatable :: label

        label = ' ('//element_name(element)//')'
        n = element_nodes_per_cell(element)
        allocate (xy(2, n), ke(2*n, 2*n), modes(2*n, 3), eigenvalues(2*n), work(64*n))
        select case (element)
        case (ELEMENT_P1, ELEMENT_P2, ELEMENT_P3, ELEMENT_P4)
            xy(:, 1:3) = reshape([0.1_wp, 0.2_wp, 1.3_wp, 0.4_wp, 0.5_wp, 1.1_wp], [2, 3])
        case (ELEMENT_Q1, ELEMENT_Q2)
            xy(:, 1:4) = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.1_wp, 1.7_wp, 1.5_wp, &
                                  -0.2_wp, 1.0_wp], [2, 4])
        end select
        n_corners = element_corners(element)
        if (element == ELEMENT_P3 .or. element == ELEMENT_P4) then
            ! Nodes of the straight triangle (the affine image of the reference nodes), then
            ! the first edge node pushed off its side: a curved, isoparametric cell.
            call reference_nodes(element, ref_nodes)
            do i = 4, n
                xy(:, i) = xy(:, 1) + ref_nodes(1, i)*(xy(:, 2) - xy(:, 1)) + &
                           ref_nodes(2, i)*(xy(:, 3) - xy(:, 1))
            end do
            xy(:, 4) = xy(:, 4) + [0.03_wp, -0.05_wp]
        else if (n > n_corners) then
            ! Mid-edge nodes at the chord midpoints, then the first pushed off its chord: a
            ! curved side, so the map is truly non-affine.
            do i = 1, n_corners
                xy(:, n_corners + i) = 0.5_wp*(xy(:, i) + xy(:, modulo(i, n_corners) + 1))
            end do
            xy(:, n_corners + 1) = xy(:, n_corners + 1) + [0.03_wp, -0.05_wp]
            if (n == 9) xy(:, 9) = 0.25_wp*sum(xy(:, 1:4), dim=2) + [0.02_wp, 0.01_wp]
        end if

        call element_stiffness(element, xy, YOUNG, POISSON, ke, info)
        call t%check('distorted element: info ok'//label, info == ELEMENT_OK)
        call t%check('distorted element: ke exactly symmetric'//label, &
                     maxval(abs(ke - transpose(ke))) <= 0.0_wp)
        call check_tables_and_energy(element, xy, ke, label)

        modes = 0.0_wp
        modes(1::2, 1) = 1.0_wp
        modes(2::2, 2) = 1.0_wp
        modes(1::2, 3) = -xy(2, :)
        modes(2::2, 3) = xy(1, :)
        scale = maxval(sum(abs(ke), dim=2))
        do i = 1, 3
            residual = maxval(abs(matmul(ke, modes(:, i))))
            ! Each entry of ke r cancels O(1) terms of size |ke| |r|: round-off is a few
            ! ulps of |ke| |r|; 1e-12 leaves room for the row length and quadrature sums.
            call t%check('distorted element: ke kills rigid mode '//achar(48 + i)//label, &
                         residual <= 1.0e-12_wp*scale*maxval(abs(modes(:, i))))
        end do

        call dsyev('N', 'U', 2*n, ke, 2*n, eigenvalues, work, size(work), info)
        call t%check('distorted element: dsyev info = 0'//label, info == 0)
        largest = maxval(abs(eigenvalues))
        ! Rigid modes give eigenvalues at round-off (~1e-16 largest); genuine ones of a
        ! reasonable element are many orders above 1e-10 largest.
        n_zero = count(abs(eigenvalues) <= 1.0e-10_wp*largest)
        call t%check('distorted element: exactly 3 zero eigenvalues'//label, n_zero == 3)
        call t%check('distorted element: no negative eigenvalue'//label, &
                     all(eigenvalues >= -1.0e-10_wp*largest))
    end subroutine check_distorted

    !> The same matrix from precomputed stiffness tables (the same operations: bit for bit),
    !> and element_energy(u, z) = z' ke u for two fields with no symmetry, to round-off: a
    !> few ulps of |z| |ke| |u| per term, 1e-13 of it allowing the sums.
    subroutine check_tables_and_energy(element, xy, ke, label)
        integer, intent(in) :: element
        real(wp), intent(in) :: xy(:, :), ke(:, :)
        character(len=*), intent(in) :: label
        real(wp) :: ke_tables(size(ke, 1), size(ke, 2)), u(size(ke, 1)), z(size(ke, 1))
        type(stiffness_tables_t) :: tables
        integer :: info, i
        tables = stiffness_tables(element)
        call element_stiffness(element, xy, YOUNG, POISSON, ke_tables, info, tables=tables)
        call t%check('stiffness tables: the same ke bit for bit'//label, info == ELEMENT_OK &
                     .and. maxval(abs(ke_tables - ke)) <= 0.0_wp)
        do i = 1, size(u)
            u(i) = sin(1.3_wp*i) + 0.1_wp*i
            z(i) = cos(0.7_wp*i*i)
        end do
        call t%check('element_energy = z'' ke u'//label, &
                     abs(element_energy(tables, xy, YOUNG, POISSON, u, z) - &
                         dot_product(z, matmul(ke, u))) <= &
                     1.0e-13_wp*norm2(z)*maxval(sum(abs(ke), dim=2))*norm2(u)*size(u))
    end subroutine check_tables_and_energy

    !> A straight cell of size 1e-9 at (0.7, 0.3): its node coordinates carry a rounding of
    !> 1e-16, 1e-7 of its size. Its stiffness must be that of the straight cell of its
    !> corners, whatever the rounding of its other nodes: moving each by one ulp changes
    !> nothing (an isoparametric map of all nodes in global coordinates changed it by ~1e-7
    !> relative).
    subroutine check_tiny_straight_cell(element)
        integer, intent(in) :: element
        real(wp), parameter :: H = 1.0e-9_wp, ORIGIN(2) = [0.7_wp, 0.3_wp]
        real(wp), allocatable :: xy(:, :), nudged(:, :), ke(:, :), ke_nudged(:, :)
        real(wp) :: ref(2, MAX_NODES), corner(2, 4)
        integer :: n, corners, i, info, info_nudged
        character(len=:), allocatable :: label

        n = element_nodes_per_cell(element)
        corners = element_corners(element)
        if (n == corners) return
        label = ' ('//element_name(element)//')'
        allocate (xy(2, n), nudged(2, n), ke(2*n, 2*n), ke_nudged(2*n, 2*n))
        call reference_nodes(element, ref)
        corner = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.1_wp, 0.8_wp, 0.9_wp, -0.1_wp, 1.0_wp], &
                         [2, 4])
        do i = 1, n   ! the affine image of the reference nodes (a parallelogram for quads)
            if (corners == 3) then
                xy(:, i) = ORIGIN + H*(ref(1, i)*corner(:, 2) + ref(2, i)*corner(:, 3))
            else
                xy(:, i) = ORIGIN + H*(0.5_wp*(ref(1, i) + 1.0_wp)*[1.0_wp, 0.1_wp] + &
                                       0.5_wp*(ref(2, i) + 1.0_wp)*[-0.1_wp, 1.0_wp])
            end if
        end do
        nudged = xy
        do i = corners + 1, n
            nudged(:, i) = nudged(:, i) + spacing(nudged(:, i))
        end do
        call element_stiffness(element, xy, YOUNG, POISSON, ke, info)
        call element_stiffness(element, nudged, YOUNG, POISSON, ke_nudged, info_nudged)
        call t%check('tiny straight cell: accepted'//label, info == ELEMENT_OK .and. &
                     info_nudged == ELEMENT_OK)
        call t%check('tiny straight cell: one ulp on its edge nodes changes nothing'//label, &
                     maxval(abs(ke - ke_nudged)) <= 1.0e-12_wp*maxval(abs(ke)))
    end subroutine check_tiny_straight_cell

    subroutine check_bad_cells()
        real(wp) :: ke(6, 6), ke_q1(8, 8), min_det
        integer :: info
        ! Clockwise triangle: det J = -2 area = -1.
        call element_stiffness(ELEMENT_P1, reshape([0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
                               1.0_wp, 0.0_wp], [2, 3]), YOUNG, POISSON, ke, info, min_det)
        call t%check('clockwise triangle is reported inverted', info == ELEMENT_INVERTED)
        call t%check_close('clockwise triangle: det J = -1', min_det, -1.0_wp, 1.0e-15_wp)
        call t%check('inverted cell: ke is zero', maxval(abs(ke)) <= 0.0_wp)
        ! Collinear nodes: det J = 0, degenerate.
        call element_stiffness(ELEMENT_P1, reshape([0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, &
                               2.0_wp, 2.0_wp], [2, 3]), YOUNG, POISSON, ke, info)
        call t%check('collinear triangle is reported degenerate', info == ELEMENT_INVERTED)
        ! Re-entrant corner at node 3: det J < 0 there although it may be > 0 at Gauss points.
        call element_stiffness(ELEMENT_Q1, reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, &
                               0.3_wp, 0.3_wp, 0.0_wp, 2.0_wp], [2, 4]), YOUNG, POISSON, &
                               ke_q1, info, min_det)
        call t%check('non-convex quadrilateral is reported inverted', &
                     info == ELEMENT_INVERTED .and. min_det < 0.0_wp)
        call element_stiffness(ELEMENT_Q1, reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
                               0.0_wp, 1.0_wp], [2, 3]), YOUNG, POISSON, ke_q1, info)
        call t%check('3 nodes for a Q1 cell is a bad argument', info == ELEMENT_BAD_ARGUMENT)
    end subroutine check_bad_cells
end program test_elasticity
