! SPDX-License-Identifier: MIT
!> What both eigensolvers share on the way from K phi = mu B phi to the p contact nodes and
!> back (model.md sections 4-7): the Cholesky factor of K with the contact dofs pivoted last, the
!> contact blocks Kt_nn = N K^-1 N' and Kt_nt = N K^-1 T' read off its trailing block, and
!> the lift of reduced eigenvectors y to full ones phi = K^-1 (lambda T' - N') M y with the
!> backward error of every pair on (K, B).
!>
!> Why the contact dofs last: then the trailing 2p x 2p block L_c of P K P' = L L' is the
!> Cholesky factor of the Schur complement S of K onto the contact dofs, and K^-1 restricted
!> to them is S^-1 = L_c^-T L_c^-1: O(p^3) flops, independent of n, where forming the
!> blocks by forward solves costs O(p nnz(L)) flops and an n x p array.
module contact_reduction
    use kinds, only: wp, i8
    use status, only: status_t, STATUS_SOLVER, STATUS_BAD_INPUT, STATUS_SINGULAR
    use strings, only: to_string
    use timer, only: wall_time, timings_t, PHASE_ORDERING, PHASE_FACTOR, PHASE_REDUCTION
    use mesh, only: mesh_t
    use dof_map, only: dof_map_t
    use csr_matrix, only: csr_matrix_t
    use sparse_cholesky, only: cholesky_t, ORDERING_GIVEN
    use node_ordering, only: nested_dissection_last
    use contact_boundary, only: contact_t
    use spectrum, only: backward_error, normalise_mode
    use lapack_interfaces, only: dpotri, dtrsm
    implicit none
    private
    public :: factor_stiffness, factor_permuted, factor_contact_blocks, contact_tail, &
              flexibility_blocks, contact_flexibility, &
              lift_eigenvectors, lift_block_columns, reduced_matrix, scaled_reduced_matrix, &
              lambda_unit, mu_of_theta, lift_share, lift_left

    !> mu = 1 / theta of an eigenvalue theta / unit of A / unit (unit: lambda_unit, or 1):
    !> the one place the reciprocal is taken. unit is a power of two, so (1 / theta) / unit
    !> is 1 / (theta unit) exactly.
    interface mu_of_theta
        module procedure mu_of_theta_real, mu_of_theta_complex
    end interface mu_of_theta

    !> Columns per multi-right-hand-side solve of the lift: up to 64 keeps CHOLMOD's
    !> supernodal solve in BLAS-3 (each solve streams the whole factor), but one n x block
    !> array stays within BLOCK_BYTES: the solve holds about four of them (our right-hand
    !> sides and result, CHOLMOD's result and workspace), so about 1 GB at most beside the
    !> factor. At n = 2.1e6 (N = 1024) that is 15 columns, at n = 5.3e5 (N = 512) 61.
    integer, parameter :: RHS_BLOCK_MAX = 64
    integer, parameter :: RHS_BLOCK_MIN = 8
    integer(i8), parameter :: BLOCK_BYTES = 256_i8*1024_i8**2

    !> What every lift (lift_eigenvectors) on one factor of K shares, whatever lambda: the
    !> trailing block L_c of the factor with the slots of the contact dofs in it
    !> (contact_tail), and ||K||_inf for the backward errors. An hp level solves its points at
    !> many lambdas on one factor: made once for them, it spares each point a copy of L_c
    !> (2p x 2p) out of CHOLMOD and a pass over K.
    type, public :: lift_share_t
        real(wp), allocatable :: l_tail(:, :)   !! (2p, 2p) lower triangle
        integer, allocatable :: slot(:, :)      !! (2, p), see contact_tail
        real(wp) :: k_norm = 0.0_wp              !! ||K||_inf
    end type lift_share_t

    !> The contact blocks of K^-1 with the contact mass: all the reduced problem needs at any
    !> lambda, so an analysis that visits many lambdas forms them once.
    type, public :: reduced_blocks_t
        real(wp), allocatable :: kt_nn(:, :)   !! (p, p) N K^-1 N'
        real(wp), allocatable :: kt_nt(:, :)   !! (p, p) N K^-1 T'
        type(csr_matrix_t) :: mass             !! (p, p) M, the contact mass matrix
    contains
        procedure :: matrix => reduced_blocks_matrix
        procedure :: free => reduced_blocks_free
    end type reduced_blocks_t

contains

    !> A = (lambda Kt_nt - Kt_nn) M, the reduced p x p matrix whose eigenvalues are theta =
    !> 1/mu (docs/model.md, section 6): the one place it is formed (scaled_reduced_matrix
    !> forms its scaled copy by the same operations). M is sparse (a band along Gamma_C), so
    !> the product costs O(p^2) per lambda, not O(p^3).
    pure function reduced_matrix(kt_nn, kt_nt, mass, lambda) result(a)
        real(wp), intent(in) :: kt_nn(:, :), kt_nt(:, :)   !! (p, p)
        type(csr_matrix_t), intent(in) :: mass
        real(wp), intent(in) :: lambda
        real(wp) :: a(size(kt_nn, 1), size(kt_nn, 2))
        real(wp) :: flex(size(kt_nn, 1), size(kt_nn, 2))
        integer :: j, k
        flex = lambda*kt_nt - kt_nn
        ! column j of flex M is the sum over row j of M (symmetric) of M_jk flex(:, k): whole
        ! columns, where row by row (M flex(i, :)) strode through flex; each entry sums the
        ! same terms in the same order (that of the CSR row), so the result is the same
        do j = 1, size(a, 2)
            a(:, j) = 0.0_wp
            do k = mass%row_start(j), mass%row_start(j + 1) - 1
                a(:, j) = a(:, j) + mass%val(k)*flex(:, mass%col(k))
            end do
        end do
    end function reduced_matrix

    !> A(lambda) / lambda_unit(lambda) (see reduced_matrix and lambda_unit): what every
    !> solver decomposes; its eigenvalues are theta / lambda_unit (mu_of_theta).
    pure function scaled_reduced_matrix(kt_nn, kt_nt, mass, lambda) result(a)
        real(wp), intent(in) :: kt_nn(:, :), kt_nt(:, :)   !! (p, p)
        type(csr_matrix_t), intent(in) :: mass
        real(wp), intent(in) :: lambda
        real(wp) :: a(size(kt_nn, 1), size(kt_nn, 2))
        real(wp), allocatable :: flex(:, :)
        real(wp) :: scaled, inverse
        integer :: j, k
        ! reduced_matrix(Kt_nn / unit, Kt_nt, M, lambda / unit) to the last bit (the same
        ! products and sums in the same order; / unit and * (1 / unit) are the same exact
        ! scaling by a power of two): an hp sweep forms this matrix at every point. The
        ! flexibility column is formed once, not once per entry of M's column (up to about
        ! 25 on the top hp levels): each entry is the same rounded value either way.
        scaled = lambda/lambda_unit(lambda)
        inverse = 1.0_wp/lambda_unit(lambda)
        allocate (flex(size(kt_nn, 1), size(kt_nn, 2)))
        do j = 1, size(a, 2)
            flex(:, j) = scaled*kt_nt(:, j) - kt_nn(:, j)*inverse
        end do
        do j = 1, size(a, 2)
            a(:, j) = 0.0_wp
            do k = mass%row_start(j), mass%row_start(j + 1) - 1
                a(:, j) = a(:, j) + mass%val(k)*flex(:, mass%col(k))
            end do
        end do
    end function scaled_reduced_matrix

    elemental real(wp) function mu_of_theta_real(theta, unit) result(mu)
        real(wp), intent(in) :: theta, unit
        mu = (1.0_wp/theta)/unit
    end function mu_of_theta_real

    elemental complex(wp) function mu_of_theta_complex(theta, unit) result(mu)
        complex(wp), intent(in) :: theta
        real(wp), intent(in) :: unit
        mu = (1.0_wp/theta)/unit
    end function mu_of_theta_complex

    !> A power of two 2^c with |lambda| / 2^c in [1, 2) when |lambda| > 1, else 1. The
    !> solvers work on A / lambda_unit and (lambda t - n) / lambda_unit, exact rescalings that
    !> only divide the eigenvalues theta and the vectors phi by it: lambda Kt_nt overflows from
    !> |lambda| ~ 1e308 and B phi (~ lambda^2) from 1e155, where mu ~ 1/lambda is fine.
    elemental real(wp) function lambda_unit(lambda)
        real(wp), intent(in) :: lambda
        lambda_unit = 1.0_wp
        if (abs(lambda) > 1.0_wp) lambda_unit = set_exponent(1.0_wp, exponent(lambda))
    end function lambda_unit

    !> A(lambda) / lambda_unit(lambda) of these blocks (see reduced_matrix): its eigenvalues
    !> are theta / lambda_unit, i.e. mu = 1 / (lambda_unit theta).
    pure function reduced_blocks_matrix(this, lambda) result(a)
        class(reduced_blocks_t), intent(in) :: this
        real(wp), intent(in) :: lambda
        real(wp) :: a(size(this%kt_nn, 1), size(this%kt_nn, 2))
        a = scaled_reduced_matrix(this%kt_nn, this%kt_nt, this%mass, lambda)
    end function reduced_blocks_matrix

    !> Factor K for the eigenproblem, whatever the solver and analysis: METIS nested
    !> dissection on the node graph with the contact nodes last (node_ordering), then CHOLMOD
    !> with that ordering, so that `contact_tail` can read K^-1 on the contact dofs off the
    !> factor. Adds the ordering and factorization times to `timings`. A singular K is
    !> explained (the usual cause: no Dirichlet boundary). `contact_last` = .false. (for
    !> the full ARPACK operator, which only solves with K) leaves the ordering to CHOLMOD:
    !> no dense 2p x 2p trailing block, which dominates when p is a large part of n.
    subroutine factor_stiffness(k, m, dofs, contact, chol, timings, stat, contact_last)
        type(csr_matrix_t), intent(in) :: k
        type(mesh_t), intent(in) :: m
        type(dof_map_t), intent(in) :: dofs
        type(contact_t), intent(in) :: contact
        type(cholesky_t), intent(inout) :: chol
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        logical, intent(in), optional :: contact_last   !! default .true.
        integer, allocatable :: permutation(:)
        real(wp) :: start

        start = wall_time()
        if (present(contact_last)) then
            if (.not. contact_last) then
                call chol%factor(k, stat)
                call explain_factor(k, 'CHOLMOD, its own ordering', '', start, timings, stat)
                return
            end if
        end if
        call nested_dissection_last(m, dofs, contact%nodes, permutation, stat)
        if (.not. stat%ok()) return
        call factor_permuted(k, permutation, contact, 'contact nodes last', '', start, chol, &
                             timings, stat)
    end subroutine factor_stiffness

    !> Factor K in `permutation` (from an ordering begun at `start`, described by `ordering`)
    !> with the 2p contact dofs of `contact` kept last, for the reduced operator's dense
    !> trailing block. `space` ('' or 'hp ') names K's space in the messages and times.
    subroutine factor_permuted(k, permutation, contact, ordering, space, start, chol, timings, &
                               stat)
        type(csr_matrix_t), intent(in) :: k
        integer, intent(in) :: permutation(:)
        type(contact_t), intent(in) :: contact
        character(len=*), intent(in) :: ordering, space
        real(wp), intent(in) :: start
        type(cholesky_t), intent(inout) :: chol
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp) :: factor_start
        call timings%add(PHASE_ORDERING, wall_time() - start, ': METIS, '//ordering)
        factor_start = wall_time()
        call chol%factor(k, stat, ordering=ORDERING_GIVEN, permutation=permutation, &
                         keep_last=2*contact%p())
        call explain_factor(k, 'CHOLMOD', space, factor_start, timings, stat)
    end subroutine factor_permuted

    !> A failed factor of K explained (the usual cause of a singular one: no Dirichlet
    !> boundary), or the factor's time since `start` by `what`.
    subroutine explain_factor(k, what, space, start, timings, stat)
        type(csr_matrix_t), intent(in) :: k
        character(len=*), intent(in) :: what, space
        real(wp), intent(in) :: start
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(inout) :: stat
        if (stat%code == STATUS_SINGULAR) then
            stat%message = 'the '//space//'stiffness matrix K is singular: is there a '// &
                'Dirichlet boundary that stops every rigid motion? ('//stat%message//')'
        else if (.not. stat%ok()) then
            stat%message = space//'stiffness matrix K: '//stat%message
        else
            call timings%add(PHASE_FACTOR, wall_time() - start, ': '//what//', '// &
                             to_string(k%n())//' '//space//'dofs')
        end if
    end subroutine explain_factor

    !> Factor K with the contact dofs last (factor_stiffness) and form its contact blocks
    !> Kt_nn, Kt_nt (contact_flexibility), their time added to `timings`: the start of every
    !> threshold computation, on any mesh. `chol` stays factored for the caller's solves
    !> (free it), also when stat fails.
    subroutine factor_contact_blocks(k, m, dofs, contact, chol, kt_nn, kt_nt, timings, stat)
        type(csr_matrix_t), intent(in) :: k
        type(mesh_t), intent(in) :: m
        type(dof_map_t), intent(in) :: dofs
        type(contact_t), intent(in) :: contact
        type(cholesky_t), intent(inout) :: chol
        real(wp), allocatable, intent(out) :: kt_nn(:, :), kt_nt(:, :)
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp) :: start
        call factor_stiffness(k, m, dofs, contact, chol, timings, stat)
        if (.not. stat%ok()) return
        start = wall_time()
        call contact_flexibility(chol, contact, kt_nn, kt_nt, stat)
        if (stat%ok()) call timings%add(PHASE_REDUCTION, wall_time() - start, &
            ': contact blocks of K^-1, '//to_string(contact%p())//' x '//to_string(contact%p()))
    end subroutine factor_contact_blocks

    !> The trailing 2p x 2p block L_c of a factor made by factor_stiffness, and `slot`(c, a):
    !> the row of L_c of the dof c (1 = x, 2 = y) of contact node a.
    subroutine contact_tail(chol, contact, l_tail, slot, stat)
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), allocatable, intent(out) :: l_tail(:, :)
        integer, allocatable, intent(out) :: slot(:, :)
        type(status_t), intent(out) :: stat
        integer, allocatable :: rows(:), position(:)
        integer :: a, c, m

        if (any(contact%dofs <= 0)) then
            call stat%fail(STATUS_BAD_INPUT, 'contact blocks: a contact node has a fixed '// &
                           'dof; the reduction needs both dofs of every contact node free')
            return
        end if
        m = 2*contact%p()
        call chol%trailing_block(m, l_tail, rows, stat)
        if (.not. stat%ok()) then
            stat%message = 'contact blocks (p = '//to_string(contact%p())//' contact nodes): '// &
                           stat%message
            return
        end if
        allocate (position(max(maxval(rows), maxval(contact%dofs))), source=0)
        position(rows) = [(c, c=1, m)]
        allocate (slot(2, contact%p()))
        do a = 1, contact%p()
            slot(:, a) = position(contact%dofs(:, a))
        end do
        if (any(slot == 0)) then
            call stat%fail(STATUS_SOLVER, 'contact blocks: the Cholesky factor of K does not '// &
                           'end with the contact dofs (factor it with factor_stiffness)')
        end if
    end subroutine contact_tail

    !> Kt_nn = N S^-1 N' and Kt_nt = N S^-1 T' (p x p) from L_c (S = L_c L_c'): LAPACK dpotri
    !> forms S^-1 in 2 (2p)^3 / 3 flops, then entry (a, b) is n' [S^-1]_ab n, resp.
    !> n' [S^-1]_ab t, with [S^-1]_ab the 2 x 2 block of contact nodes a, b.
    subroutine flexibility_blocks(l_tail, slot, normal, tangent, kt_nn, kt_nt, stat)
        real(wp), intent(in) :: l_tail(:, :)      !! (2p, 2p) lower triangle
        integer, intent(in) :: slot(:, :)         !! (2, p), see contact_tail
        real(wp), intent(in) :: normal(2), tangent(2)
        real(wp), allocatable, intent(out) :: kt_nn(:, :), kt_nt(:, :)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: s_inv(:, :), column_n(:), column_t(:)
        integer :: m, p, a, b, j, info, ierr

        m = size(l_tail, 1)
        p = size(slot, 2)
        allocate (s_inv, source=l_tail, stat=ierr)
        if (ierr /= 0) then
            call out_of_memory('the inverse of the 2p x 2p block')
            return
        end if
        call dpotri('L', m, s_inv, m, info)
        if (info /= 0) then
            call stat%fail(STATUS_SOLVER, 'contact blocks: dpotri on the trailing block of '// &
                           'the factor of K: info = '//to_string(info))
            return
        end if
        do j = 1, m   ! dpotri fills the lower triangle only
            s_inv(j, j + 1:m) = s_inv(j + 1:m, j)
        end do
        allocate (kt_nn(p, p), kt_nt(p, p), column_n(m), column_t(m), stat=ierr)
        if (ierr /= 0) then
            call out_of_memory('Kt_nn and Kt_nt')
            return
        end if
        do b = 1, p
            ! S^-1 n_b and S^-1 t_b: the contact loads of unit normal / tangential force at b
            column_n = normal(1)*s_inv(:, slot(1, b)) + normal(2)*s_inv(:, slot(2, b))
            column_t = tangent(1)*s_inv(:, slot(1, b)) + tangent(2)*s_inv(:, slot(2, b))
            do a = 1, p
                kt_nn(a, b) = normal(1)*column_n(slot(1, a)) + normal(2)*column_n(slot(2, a))
                kt_nt(a, b) = normal(1)*column_t(slot(1, a)) + normal(2)*column_t(slot(2, a))
            end do
        end do
        ! Kt_nn is symmetric; make it exactly so (the two triangles round differently)
        do b = 1, p
            kt_nn(b + 1:p, b) = kt_nn(b, b + 1:p)
        end do

    contains

        subroutine out_of_memory(what)
            character(len=*), intent(in) :: what
            call stat%fail(STATUS_SOLVER, 'contact blocks: cannot allocate '//what// &
                           ' (p = '//to_string(p)//' contact nodes): out of memory')
        end subroutine out_of_memory
    end subroutine flexibility_blocks

    !> Kt_nn and Kt_nt (p x p) from a factor made by factor_stiffness; `share`, the lifts'
    !> data on that factor of K (`k`), made from the same trailing block on request.
    subroutine contact_flexibility(chol, contact, kt_nn, kt_nt, stat, k, share)
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), allocatable, intent(out) :: kt_nn(:, :), kt_nt(:, :)
        type(status_t), intent(out) :: stat
        type(csr_matrix_t), intent(in), optional :: k
        type(lift_share_t), intent(out), optional :: share
        real(wp), allocatable :: l_tail(:, :)
        integer, allocatable :: slot(:, :)
        call contact_tail(chol, contact, l_tail, slot, stat)
        if (.not. stat%ok()) return
        call flexibility_blocks(l_tail, slot, contact%normal, contact%tangent, kt_nn, kt_nt, &
                                stat)
        if (.not. (stat%ok() .and. present(share) .and. present(k))) return
        share%k_norm = k%norm_inf()
        call move_alloc(l_tail, share%l_tail)
        call move_alloc(slot, share%slot)
    end subroutine contact_flexibility

    !> The lifts' shared data (lift_share_t) on the factor `chol` of `k` (factor_stiffness).
    subroutine lift_share(k, chol, contact, share, stat)
        type(csr_matrix_t), intent(in) :: k
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        type(lift_share_t), intent(out) :: share
        type(status_t), intent(out) :: stat
        call contact_tail(chol, contact, share%l_tail, share%slot, stat)
        share%k_norm = k%norm_inf()
    end subroutine lift_share

    !> Columns per block of lift_eigenvectors for n free dofs (see RHS_BLOCK_MAX).
    pure integer function lift_block_columns(n_free)
        integer, intent(in) :: n_free
        lift_block_columns = int(max(int(RHS_BLOCK_MIN, i8), min(int(RHS_BLOCK_MAX, i8), &
                                 BLOCK_BYTES/(8_i8*max(1, n_free)))))
    end function lift_block_columns

    !> Full eigenvectors phi = K^-1 (lambda T' - N') M y of the reduced eigenvectors y (the
    !> columns of `y`, p x n_ev, in output order, for the eigenvalues `mu`), by
    !> multi-right-hand-side solves in column blocks, so that memory is O(n x block), never
    !> n x n_ev. Every pair gets its backward error on (K, B) in `residual`; the first n_keep
    !> are normalised (normalise_mode) and kept in `vectors`. A real y costs one column, a
    !> complex one two (real and imaginary part); the conjugate partner that follows a
    !> complex pair's first member costs none (K and B are real: conjugate vector, same
    !> backward error). `chol` is the factor from factor_stiffness: the right-hand sides live
    !> on the contact dofs, pivoted last, so the forward half of each solve is L_c^-1 on the
    !> trailing rows (dense, O(p^2) per column) and only the backward half passes over L.
    !> `share`: L_c, its slots and ||K||_inf made once for this factor (lift_share).
    subroutine lift_eigenvectors(k, b, chol, contact, lambda, mu, y, n_keep, residual, vectors, &
                                 stat, share)
        type(csr_matrix_t), intent(in) :: k, b
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        real(wp), intent(in) :: lambda
        complex(wp), intent(in) :: mu(:)         !! (n_ev)
        complex(wp), intent(in) :: y(:, :)       !! (p, n_ev)
        integer, intent(in) :: n_keep
        real(wp), allocatable, intent(out) :: residual(:)
        complex(wp), allocatable, intent(out) :: vectors(:, :)
        type(status_t), intent(out) :: stat
        type(lift_share_t), intent(in), optional :: share
        type(lift_share_t) :: own
        if (present(share)) then
            call lift(share)
        else
            call lift_share(k, chol, contact, own, stat)
            if (stat%ok()) call lift(own)
        end if

    contains

        !> The lift on the shared data `s`.
        subroutine lift(s)
            type(lift_share_t), intent(in) :: s
            real(wp), allocatable :: w(:, :), g(:, :), my(:), w_tail(:, :)
            complex(wp), allocatable :: phi(:)
            integer, allocatable :: columns(:), first_column(:)
            real(wp) :: direction(2), k_norm, b_norm
            integer :: n_ev, n_free, block_columns, first, last, i, c, n_cols, m, a

            n_ev = size(mu)
            n_free = k%n()
            ! lambda t - n up to a factor, which only scales phi: divided by lambda_unit, so that
            ! phi and B phi (~ lambda^2) cannot overflow in the backward error (they gave
            ! Infinity from |lambda| ~ 1e155)
            direction = contact%slip_direction(lambda, lambda_unit(lambda))
            k_norm = s%k_norm
            b_norm = b%norm_inf()
            allocate (residual(n_ev), vectors(n_free, min(n_keep, n_ev)))
            m = size(s%l_tail, 1)
            allocate (columns(n_ev), first_column(n_ev), my(contact%p()), phi(n_free))
            do i = 1, n_ev
                columns(i) = merge(2, 1, any(abs(aimag(y(:, i))) > 0.0_wp))
            end do
            do i = 2, n_ev
                if (columns(i) /= 2 .or. columns(i - 1) /= 2) cycle
                ! exact conjugates, as LAPACK and ARPACK return the members of a pair
                if (abs(mu(i) - conjg(mu(i - 1))) <= 0.0_wp .and. &
                    maxval(abs(y(:, i) - conjg(y(:, i - 1)))) <= 0.0_wp) columns(i) = 0
            end do
            block_columns = lift_block_columns(n_free)
            first = 1
            do while (first <= n_ev)
                ! A partner (0 columns) always fits, so it joins its first member's block.
                n_cols = 0
                last = first - 1
                do while (last < n_ev)
                    if (n_cols + columns(last + 1) > block_columns .and. n_cols > 0) exit
                    last = last + 1
                    n_cols = n_cols + columns(last)
                end do
                ! right-hand sides (lambda T' - N') M y in the trailing pivot order, then L_c^-1
                allocate (w_tail(m, n_cols), source=0.0_wp)
                c = 0
                do i = first, last
                    first_column(i) = c + 1
                    if (columns(i) == 0) cycle
                    call contact%mass%matvec(real(y(:, i), wp), my)
                    do a = 1, size(my)
                        w_tail(s%slot(:, a), c + 1) = direction*my(a)
                    end do
                    if (columns(i) == 2) then
                        call contact%mass%matvec(aimag(y(:, i)), my)
                        do a = 1, size(my)
                            w_tail(s%slot(:, a), c + 2) = direction*my(a)
                        end do
                    end if
                    c = c + columns(i)
                end do
                call dtrsm('L', 'L', 'N', 'N', m, n_cols, 1.0_wp, s%l_tail, m, w_tail, m)
                allocate (w(n_free, n_cols), source=0.0_wp)
                w(n_free - m + 1:, :) = w_tail
                deallocate (w_tail)
                allocate (g(n_free, n_cols))
                call chol%backward(w, g, stat)
                if (.not. stat%ok()) return
                deallocate (w)
                do i = first, last
                    c = first_column(i)
                    select case (columns(i))
                    case (0)
                        phi = conjg(phi)   ! the partner of the pair just recorded
                    case (1)
                        phi = cmplx(g(:, c), 0.0_wp, wp)
                    case default
                        phi = cmplx(g(:, c), g(:, c + 1), wp)
                    end select
                    residual(i) = backward_error(k, b, mu(i), phi, k_norm, b_norm)
                    if (i <= size(vectors, 2)) then
                        vectors(:, i) = phi
                        call normalise_mode(vectors(:, i))
                    end if
                end do
                deallocate (g)
                first = last + 1
            end do
        end subroutine lift
    end subroutine lift_eigenvectors

    !> The pencil's left vector y = K^-1 N' w from w, a left eigenvector of the reduced
    !> matrix (roundoff: left_from_reduced), on the lifts' shared data `share` of the factor
    !> `chol` (contact dofs last): N' w lives on the contact dofs, pivoted last, so the
    !> forward half of the solve is L_c^-1 on the trailing rows and only the backward half
    !> passes over L, as lift_eigenvectors does for the right vector.
    subroutine lift_left(share, chol, contact, n_free, w, y, stat)
        type(lift_share_t), intent(in) :: share
        type(cholesky_t), intent(in) :: chol
        type(contact_t), intent(in) :: contact
        integer, intent(in) :: n_free
        real(wp), intent(in) :: w(:)   !! (p)
        real(wp), allocatable, intent(out) :: y(:)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: w_tail(:, :), pivoted(:, :), solution(:, :)
        integer :: m, a
        m = size(share%l_tail, 1)
        allocate (w_tail(m, 1), source=0.0_wp)
        do a = 1, size(w)
            w_tail(share%slot(:, a), 1) = contact%normal*w(a)
        end do
        call dtrsm('L', 'L', 'N', 'N', m, 1, 1.0_wp, share%l_tail, m, w_tail, m)
        allocate (pivoted(n_free, 1), source=0.0_wp)
        pivoted(n_free - m + 1:, :) = w_tail
        allocate (solution(n_free, 1))
        call chol%backward(pivoted, solution, stat)
        if (.not. stat%ok()) return
        y = solution(:, 1)
    end subroutine lift_left

    !> Every array of the blocks deallocated, as soon as their user is done with them (and
    !> explicitly where the blocks are a component of a goal inside another goal, which
    !> gfortran 12 does not free whole: joint_goal under Asan).
    subroutine reduced_blocks_free(this)
        class(reduced_blocks_t), intent(inout) :: this
        if (allocated(this%kt_nn)) deallocate (this%kt_nn)
        if (allocated(this%kt_nt)) deallocate (this%kt_nt)
        if (allocated(this%mass%row_start)) deallocate (this%mass%row_start)
        if (allocated(this%mass%col)) deallocate (this%mass%col)
        if (allocated(this%mass%val)) deallocate (this%mass%val)
    end subroutine reduced_blocks_free
end module contact_reduction
