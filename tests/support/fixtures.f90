! SPDX-License-Identifier: MIT
!> Fixtures and views that several test programs need: the one-triangle mesh with closed
!> forms, the reference scene's configuration, a CSR matrix as a dense array, a file as
!> text, a search in a run's warnings, the fuzz tests' reproducible random stream and
!> whole-file read and write, and the contact blocks of a mesh for the threshold tests.
!> One copy here, so a fix reaches every test that uses them.
module fixtures
    use kinds, only: wp, i8
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1
    use csr_matrix, only: csr_matrix_t
    use eigen_analysis, only: eigen_result_t
    use status, only: status_t
    use run_config, only: config_t
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use contact_boundary, only: contact_t, build_contact
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness, contact_flexibility, reduced_blocks_t
    use timer, only: timings_t
    implicit none
    private
    public :: single_triangle, csr_to_dense, file_text, has_warning, five_point_matrix
    public :: uniform, read_text, write_text, rigid_mode, contact_scene, square_scene

    !> Park-Miller minimal standard generator: the same mutants on every compiler and run.
    type, public :: random_t
        integer(i8) :: state = 1
    end type random_t

contains

    !> The reference scene (unit square, E = 1, nu = 0.3, top fixed, bottom in contact) on
    !> n x n cells of `element`, with two modes kept; everything else at its default.
    subroutine square_scene(n, element, diagonal, config)
        integer, intent(in) :: n
        character(len=*), intent(in) :: element, diagonal
        type(config_t), intent(out) :: config
        config%input_file = 'test'
        config%mesh%nx = n
        config%mesh%ny = n
        config%mesh%element = element
        config%mesh%diagonal = diagonal
        config%output%modes = 2
    end subroutine square_scene

    !> The triangle A = (0,0), B = (l,0), C = (0,l): part 1 = [A,B] (contact), part 2 = [B,C]
    !> (fixed), part 3 = [C,A] (Neumann).
    subroutine single_triangle(l, m)
        real(wp), intent(in) :: l
        type(mesh_t), intent(out) :: m
        m%element = ELEMENT_P1
        m%coords = reshape([0.0_wp, 0.0_wp, l, 0.0_wp, 0.0_wp, l], [2, 3])
        m%cells = reshape([1, 2, 3], [3, 1])
        m%edges = reshape([1, 2, 2, 3, 3, 1], [2, 3])
        m%edge_part = [1, 2, 3]
        m%part_names = [character(len=64) :: 'contact', 'fixed', 'side']
    end subroutine single_triangle

    !> The n x n dense array of a square CSR matrix (zeros off the pattern).
    function csr_to_dense(a) result(dense)
        type(csr_matrix_t), intent(in) :: a
        real(wp), allocatable :: dense(:, :)
        integer :: i, k
        allocate (dense(a%n(), a%n()), source=0.0_wp)
        do i = 1, a%n()
            do k = a%row_start(i), a%row_start(i + 1) - 1
                dense(i, a%col(k)) = a%val(k)
            end do
        end do
    end function csr_to_dense

    !> Whole file as text: each line trimmed and followed by `separator`.
    function file_text(path, separator) result(text)
        character(len=*), intent(in) :: path, separator
        character(len=:), allocatable :: text
        character(len=1000) :: line
        integer :: unit, ios
        text = ''
        open (newunit=unit, file=path, status='old', action='read')
        do
            read (unit, '(a)', iostat=ios) line
            if (ios /= 0) exit
            text = text//trim(line)//separator
        end do
        close (unit)
    end function file_text

    !> Whether one of the run's warnings contains `words`.
    logical function has_warning(res, words)
        type(eigen_result_t), intent(in) :: res
        character(len=*), intent(in) :: words
        integer :: i
        has_warning = .false.
        do i = 1, size(res%warnings)
            if (index(res%warnings(i), words) > 0) has_warning = .true.
        end do
    end function has_warning

    !> The 5-point stencil on an m x m grid of unknowns, lexicographic order; `stencil` holds
    !> the south, west, centre, east and north coefficients. Neighbours outside the grid are
    !> dropped (a zero Dirichlet boundary).
    subroutine five_point_matrix(m, stencil, a)
        integer, intent(in) :: m
        real(wp), intent(in) :: stencil(5)
        type(csr_matrix_t), intent(out) :: a
        integer :: i, j, p, pos, neighbour
        integer :: columns(5)
        logical :: inside(5)
        allocate (a%row_start(m*m + 1), a%col(5*m*m), a%val(5*m*m))
        pos = 1
        do j = 1, m
            do i = 1, m
                p = i + (j - 1)*m
                a%row_start(p) = pos
                columns = [p - m, p - 1, p, p + 1, p + m]     ! sorted
                inside = [j > 1, i > 1, .true., i < m, j < m]
                do neighbour = 1, 5
                    if (.not. inside(neighbour)) cycle
                    a%col(pos) = columns(neighbour)
                    a%val(pos) = stencil(neighbour)
                    pos = pos + 1
                end do
            end do
        end do
        a%row_start(m*m + 1) = pos
        a%col = a%col(1:pos - 1)
        a%val = a%val(1:pos - 1)
    end subroutine five_point_matrix

    !> A uniform integer in [low, high] from the next state of `rng`.
    integer function uniform(rng, low, high)
        type(random_t), intent(inout) :: rng
        integer, intent(in) :: low, high
        rng%state = modulo(48271_i8*rng%state, 2147483647_i8)
        uniform = low + int(modulo(rng%state, int(high - low + 1, i8)))
    end function uniform

    !> The whole file, bytes as they are.
    subroutine read_text(path, text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: text
        integer :: unit, file_size
        open (newunit=unit, file=path, access='stream', form='unformatted', status='old', &
              action='read')
        inquire (unit=unit, size=file_size)
        allocate (character(len=file_size) :: text)
        read (unit) text
        close (unit)
    end subroutine read_text

    !> `text` as the whole file, bytes as they are.
    subroutine write_text(path, text)
        character(len=*), intent(in) :: path, text
        integer :: unit
        open (newunit=unit, file=path, access='stream', form='unformatted', &
              status='replace', action='write')
        write (unit) text
        close (unit)
    end subroutine write_text

    !> Translations along x (1) and y (2) and the infinitesimal rotation (-y, x) (3), as
    !> vectors of the all-free system (dof 2 node - 1 is u_x, 2 node is u_y).
    function rigid_mode(m, which) result(u)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: which
        real(wp), allocatable :: u(:)
        allocate (u(2*m%n_nodes()), source=0.0_wp)
        select case (which)
        case (1); u(1::2) = 1.0_wp
        case (2); u(2::2) = 1.0_wp
        case (3)
            u(1::2) = -m%coords(2, :)
            u(2::2) = m%coords(1, :)
        end select
    end function rigid_mode

    !> K (E = 1), Gamma_C and the contact blocks Kt_nn, Kt_nt with M of mesh `m`. The factor
    !> of K stays in `chol` when present (the caller frees it); `k`, `dofs` and `contact`
    !> are returned when asked for.
    subroutine contact_scene(m, dirichlet_parts, contact_part, poisson, blocks, stat, k, dofs, &
                             contact, chol)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: dirichlet_parts(:), contact_part
        real(wp), intent(in) :: poisson
        type(reduced_blocks_t), intent(out) :: blocks
        type(status_t), intent(out) :: stat
        type(csr_matrix_t), intent(out), optional :: k
        type(dof_map_t), intent(out), optional :: dofs
        type(contact_t), intent(out), optional :: contact
        type(cholesky_t), intent(inout), optional :: chol
        type(dof_map_t) :: own_dofs
        type(contact_t) :: own_contact
        type(csr_matrix_t) :: own_k
        type(cholesky_t) :: own_chol
        type(timings_t) :: timings

        call build_dof_map(m, dirichlet_parts, own_dofs, stat)
        if (stat%ok()) call build_contact(m, contact_part, own_dofs, own_contact, stat)
        if (stat%ok()) call assemble_stiffness(m, own_dofs, 1.0_wp, poisson, own_k, stat)
        if (.not. stat%ok()) return
        ! factored in place: cholesky_t owns a C handle and is finalised, so never copied
        if (present(chol)) then
            call blocks_from_factor(chol)
        else
            call blocks_from_factor(own_chol)
            call own_chol%free()
        end if
        if (.not. stat%ok()) return
        blocks%mass = own_contact%mass
        if (present(k)) k = own_k
        if (present(dofs)) dofs = own_dofs
        if (present(contact)) contact = own_contact

    contains

        subroutine blocks_from_factor(factor)
            type(cholesky_t), intent(inout) :: factor
            call factor_stiffness(own_k, m, own_dofs, own_contact, factor, timings, stat)
            if (stat%ok()) call contact_flexibility(factor, own_contact, blocks%kt_nn, &
                                                    blocks%kt_nt, stat)
        end subroutine blocks_from_factor
    end subroutine contact_scene
end module fixtures
