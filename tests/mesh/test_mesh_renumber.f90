! SPDX-License-Identifier: MIT
!> Node renumbering is a permutation: every method returns one; the renumbered mesh has the
!> same nodes at the same places, its stiffness matrix is P K P' entry for entry (so the
!> same eigenvalues), and K's half bandwidth stays within the bound the node bandwidth
!> gives (2 node_bandwidth + 1 dofs). Reverse Cuthill-McKee brings a scattered numbering
!> back to a small bandwidth.
program test_mesh_renumber
    use kinds, only: wp
    use status, only: status_t, STATUS_INTERNAL
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P2
    use mesh_structured, only: structured_rectangle
    use mesh_renumber, only: renumber_nodes, node_order, node_bandwidth, RENUMBER_NONE, &
                             RENUMBER_RCM, RENUMBER_METIS
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use csr_matrix, only: csr_matrix_t
    use lapack_interfaces, only: dgeev
    use fixtures, only: csr_to_dense, is_permutation
    use testing, only: test_suite_t
    implicit none

    integer, parameter :: METHODS(3) = [RENUMBER_NONE, RENUMBER_RCM, RENUMBER_METIS]
    character(len=*), parameter :: NAMES(3) = [character(len=5) :: 'none', 'RCM', 'METIS']
    type(test_suite_t) :: t
    type(mesh_t) :: grid, scattered, renumbered
    type(status_t) :: stat
    real(wp), allocatable :: k_scattered(:, :), eigen_scattered(:)
    integer, allocatable :: new_of_old(:), shuffle(:)
    integer :: i, n

    t%name = 'test_mesh_renumber'
    ! 4 x 3 P2 squares: 9 x 7 = 63 nodes, 126 dofs, numbered row by row
    call structured_rectangle(1.0_wp, 0.75_wp, 4, 3, ELEMENT_P2, 'right', grid, stat)
    n = grid%n_nodes()
    ! a P2 cell spans three rows of 9 nodes and three columns: 2 x 9 + 2
    call t%check('node_bandwidth: 20 on the generator''s grid', &
                 node_bandwidth(grid) == 20)
    ! a scattered numbering: node i becomes 1 + mod(29 (i - 1), 63) (29 is prime to 63)
    shuffle = [(1 + mod(29*(i - 1), n), i=1, n)]
    call permuted(grid, shuffle, scattered)
    call stiffness(scattered, k_scattered)
    eigen_scattered = eigenvalues(k_scattered)
    call t%check('a scattered numbering has a wide band', node_bandwidth(scattered) > n/2)

    do i = 1, size(METHODS)
        call node_order(scattered, METHODS(i), new_of_old, stat)
        call t%check(trim(NAMES(i))//': node_order is a permutation of 1..n', stat%ok() .and. &
                     is_permutation(new_of_old, n))
        renumbered = scattered
        call renumber_nodes(renumbered, METHODS(i), stat)
        call check_renumbered(trim(NAMES(i)), renumbered, new_of_old)
    end do
    renumbered = scattered
    call renumber_nodes(renumbered, RENUMBER_RCM, stat)
    call t%check('RCM: the band no wider than the generator''s row by row', &
                 node_bandwidth(renumbered) <= node_bandwidth(grid))
    call node_order(scattered, 7, new_of_old, stat)
    call t%check('an unknown method fails', stat%code == STATUS_INTERNAL)
    ! (AddressSanitizer reports a main program's allocatables)
    deallocate (k_scattered, eigen_scattered, shuffle)
    if (allocated(new_of_old)) deallocate (new_of_old)
    call t%report()

contains

    !> The mesh m with node i renumbered new_of_old(i).
    subroutine check_renumbered(label, m, new_of_old)
        character(len=*), intent(in) :: label
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: new_of_old(:)
        real(wp), allocatable :: k(:, :)
        integer, allocatable :: dof_of_old(:)
        integer :: c
        call t%check(label//': the same nodes at the same places, cells and edges follow', &
                     all(abs(m%coords(:, new_of_old) - scattered%coords) <= 0.0_wp) .and. &
                     all(m%cells == reshape(new_of_old(reshape(scattered%cells, &
                         [size(scattered%cells)])), shape(m%cells))) .and. &
                     all(m%edges == reshape(new_of_old(reshape(scattered%edges, &
                         [size(scattered%edges)])), shape(m%edges))))
        call stiffness(m, k)
        ! node-major dofs: dof c of node i moves to dof c of node new_of_old(i)
        allocate (dof_of_old(2*size(new_of_old)))   ! (gfortran 12 -O3 warns otherwise)
        dof_of_old = [(2*(new_of_old((c + 1)/2) - 1) + 2 - mod(c, 2), c=1, 2*size(new_of_old))]
        ! the same cells in the same order: each entry summed in the same order, so equal
        call t%check(label//': K is P K P'' entry for entry', &
                     all(abs(k(dof_of_old, dof_of_old) - k_scattered) <= 0.0_wp))
        call t%check(label//': the same eigenvalues (to 1e-12 of the largest)', &
                     maxval(abs(eigenvalues(k) - eigen_scattered)) <= &
                     1.0e-12_wp*maxval(abs(eigen_scattered)))
        call t%check(label//': K''s half bandwidth within 2 node_bandwidth + 1', &
                     half_bandwidth(k) <= 2*node_bandwidth(m) + 1)
    end subroutine check_renumbered

    subroutine permuted(m, new_of_old, out)
        type(mesh_t), intent(in) :: m
        integer, intent(in) :: new_of_old(:)
        type(mesh_t), intent(out) :: out
        out = m
        out%coords(:, new_of_old) = m%coords
        out%cells = reshape(new_of_old(reshape(m%cells, [size(m%cells)])), shape(m%cells))
        out%edges = reshape(new_of_old(reshape(m%edges, [size(m%edges)])), shape(m%edges))
    end subroutine permuted

    !> K on all dofs (nothing clamped), dense.
    subroutine stiffness(m, dense)
        type(mesh_t), intent(in) :: m
        real(wp), allocatable, intent(out) :: dense(:, :)
        type(dof_map_t) :: dofs
        type(csr_matrix_t) :: k
        call build_dof_map(m, [integer ::], dofs, stat)
        if (stat%ok()) call assemble_stiffness(m, dofs, 1.0_wp, 0.3_wp, k, stat)
        dense = csr_to_dense(k)
    end subroutine stiffness

    !> The eigenvalues of a symmetric matrix, ascending (LAPACK dgeev: real for these).
    function eigenvalues(a) result(lambda)
        real(wp), intent(in) :: a(:, :)
        real(wp), allocatable :: lambda(:)
        real(wp), allocatable :: copy(:, :), wi(:), work(:), left(:, :), right(:, :)
        integer :: info, i, j
        real(wp) :: swap
        allocate (copy, source=a)
        allocate (lambda(size(a, 1)), wi(size(a, 1)), work(8*size(a, 1)), left(1, 1), &
                  right(1, 1))
        call dgeev('N', 'N', size(a, 1), copy, size(a, 1), lambda, wi, left, 1, right, 1, &
                   work, size(work), info)
        do i = 2, size(lambda)   ! insertion sort
            do j = i, 2, -1
                if (lambda(j - 1) <= lambda(j)) exit
                swap = lambda(j)
                lambda(j) = lambda(j - 1)
                lambda(j - 1) = swap
            end do
        end do
    end function eigenvalues

    pure integer function half_bandwidth(a)
        real(wp), intent(in) :: a(:, :)
        integer :: i, j
        half_bandwidth = 0
        do j = 1, size(a, 2)
            do i = 1, size(a, 1)
                if (abs(a(i, j)) > 0.0_wp) half_bandwidth = max(half_bandwidth, abs(i - j))
            end do
        end do
    end function half_bandwidth
end program test_mesh_renumber
