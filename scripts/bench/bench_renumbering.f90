! SPDX-License-Identifier: MIT
!> Node renumbering of Gmsh meshes, measured: for each mesh file given on the command line
!> and each ordering (the file's, reverse Cuthill-McKee, METIS nested dissection), the time
!> to compute it, the node bandwidth, and what follows in an eigen run of the reference
!> scene (top fixed): assembly of K, CHOLMOD's factor (its default ordering, as nceig uses
!> it, and the natural ordering, which shows the fill of the node order itself) and the
!> forward solves with the p contact right-hand sides. Medians of REPEATS runs (the machine
!> is shared and noisy). Usage: bench_renumbering FILE.msh...
program bench_renumbering
    use iso_fortran_env, only: output_unit, error_unit
    use kinds, only: wp, i8
    use status, only: status_t
    use mesh, only: mesh_t
    use element_types, only: element_name
    use mesh_gmsh, only: read_gmsh
    use mesh_renumber, only: renumber_nodes, node_bandwidth, RENUMBER_NONE, RENUMBER_METIS
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t, ORDERING_DEFAULT, ORDERING_NATURAL
    use timer, only: wall_time
    use strings, only: to_string
    use sorting, only: sort_index
    implicit none

    integer, parameter :: REPEATS = 5
    character(len=*), parameter :: METHOD_NAMES(0:2) = [character(len=5) :: 'file', 'rcm', &
                                                        'metis']
    character(len=4096) :: path
    type(mesh_t) :: original, m
    type(dof_map_t) :: dofs
    type(csr_matrix_t) :: k
    type(cholesky_t) :: chol
    type(status_t) :: stat
    real(wp) :: t_order(REPEATS), t_assembly(REPEATS), t_factor(REPEATS), t_forward(REPEATS)
    real(wp), allocatable :: rhs(:, :), w(:, :)
    integer(i8) :: nnz_default
    character(len=:), allocatable :: natural_text
    integer :: i_file, method, r, node, p, a
    integer, allocatable :: contact_nodes(:)
    real(wp) :: start

    write (output_unit, '(a)') '| mesh | nodes | ordering | order [ms] | bandwidth | '// &
        'assembly [ms] | nnz(L) CHOLMOD | factor [ms] | forward p rhs [ms] | nnz(L) natural |'
    write (output_unit, '(a)') '|---|---|---|---|---|---|---|---|---|---|'
    do i_file = 1, command_argument_count()
        call get_command_argument(i_file, path)
        call read_gmsh(trim(path), original, stat, renumber=RENUMBER_NONE)
        call stop_on(stat)
        do method = RENUMBER_NONE, RENUMBER_METIS
            do r = 1, REPEATS
                m = original
                start = wall_time()
                call renumber_nodes(m, method, stat)
                t_order(r) = wall_time() - start
                call stop_on(stat)
                call build_dof_map(m, [m%part_index('top')], dofs, stat)
                call stop_on(stat)
                start = wall_time()
                call assemble_stiffness(m, dofs, 1.0_wp, 0.3_wp, k, stat)
                t_assembly(r) = wall_time() - start
                call stop_on(stat)
                start = wall_time()
                call chol%factor(k, stat, ORDERING_DEFAULT)
                t_factor(r) = wall_time() - start
                call stop_on(stat)
                nnz_default = chol%factor_nnz()
                ! p right-hand sides: the normal components at the free bottom nodes.
                contact_nodes = pack([(node, node=1, m%n_nodes())], &
                                     abs(m%coords(2, :)) <= 0.0_wp .and. dofs%free_dof(2, :) > 0)
                p = size(contact_nodes)
                allocate (rhs(dofs%n_free, p), source=0.0_wp)
                allocate (w(dofs%n_free, p))
                do a = 1, p
                    rhs(dofs%free_dof(2, contact_nodes(a)), a) = 1.0_wp
                end do
                start = wall_time()
                call chol%forward(rhs, w, stat)
                t_forward(r) = wall_time() - start
                call stop_on(stat)
                deallocate (rhs, w)
                call chol%free()
            end do
            ! Without a fill-reducing ordering L can outgrow the 32-bit indices of CHOLMOD.
            call chol%factor(k, stat, ORDERING_NATURAL)
            natural_text = 'too large'
            if (stat%ok()) natural_text = to_string(int(chol%factor_nnz()))
            call chol%free()
            write (output_unit, '(a)') '| '//basename(trim(path))//' ('// &
                element_name(m%element)//') | '//to_string(m%n_nodes())//' | '// &
                trim(METHOD_NAMES(method))//' | '//ms(t_order)//' | '// &
                to_string(node_bandwidth(m))//' | '//ms(t_assembly)//' | '// &
                to_string(int(nnz_default))//' | '//ms(t_factor)//' | '//ms(t_forward)// &
                ' | '//natural_text//' |'
        end do
    end do

contains

    subroutine stop_on(stat)
        type(status_t), intent(in) :: stat
        if (stat%ok()) return
        write (error_unit, '(a)') 'bench_renumbering: '//stat%message
        error stop 1
    end subroutine stop_on

    real(wp) function median(values)
        real(wp), intent(in) :: values(:)
        real(wp) :: sorted(size(values))
        sorted = values(sort_index(values))
        median = sorted((size(sorted) + 1)/2)
    end function median

    !> Median of the timings in milliseconds, 2 decimals.
    function ms(seconds) result(text)
        real(wp), intent(in) :: seconds(:)
        character(len=:), allocatable :: text
        character(len=32) :: buffer
        write (buffer, '(f0.2)') 1.0e3_wp*median(seconds)
        text = trim(buffer)
    end function ms

    function basename(text) result(name)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: name
        name = trim(text(index(text, '/', back=.true.) + 1:))
    end function basename
end program bench_renumbering
