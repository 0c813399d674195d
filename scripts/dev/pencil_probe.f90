! SPDX-License-Identifier: MIT
!> pencil_probe: what the threshold pencil Kt_nn x = lambda Kt_nt x looks like on one mesh, for
!> the study of thresholds that move with the mesh (docs/thresholds.md). Not part of nceig;
!> built on demand: cmake --build build --target pencil_probe.
!>
!>   pencil_probe INPUT.nml [--set group%variable=value]... [--level L] [--degrees D]
!>                [--window LMIN LMAX] [--scan LMIN LMAX N] [--profile] [--edges]
!>                [--vector LAMBDA] [--theta LMIN LMAX N] [--lower | --half | --coarse | --drop S]
!>
!> Without --level the input's own mesh and element (a Lagrange problem, as nceig builds it);
!> with --level L the hp level L of the input mesh (&adapt sigma, p_max), its degrees by D:
!> 'default' (1 + layer, nceig's ladder), 'uniform:Q' (every cell Q), 'pmin:K' (the ladder,
!> at least K), 'plus:K' (the ladder plus K), 'contact:K' (the ladder, at least K on the
!> cells with a side on Gamma_C).
!> Prints one 'real' line per finite real pencil eigenvalue in the window (default -50..50):
!> lambda, its relative condition, where its vector x (the contact forces) sits on Gamma_C
!> (s from 0 to 1 along t: the |x|-weighted mean, the shares of |x| at s < 0.02 and s > 0.98,
!> the effective number of contact functions it spans), and with --profile its profile
!> (pencil_tracking); one 'pair' line per complex pair with |Im| < 0.05 |Re| in the window;
!> with --scan one 'scan' line per lambda: the smallest singular value of
!> Kt_nn^-1/2 (Kt_nn - lambda Kt_nt) Kt_nn^-1/2, the inf-sup constant of the threshold
!> problem in the norms Kt_nn defines (bounded away from 0 under refinement where the
!> continuum problem is invertible); --vector prints the vector of one eigenvalue; --edges
!> the contact edges of an hp level with their degrees; --theta one 'theta' line per lambda: the
!> number of positive mu and the six eigenvalues theta = 1/mu of (lambda Kt_nt - Kt_nn) M with
!> the largest real parts (a pair landing on the real axis, a theta crossing zero).
!> The multiplier variants (the forces x = M I y of a smaller space, the constraint u_n = 0
!> tested against it: (I' M Kt M I) y = lambda (I' M Kt_nt M I) y): --lower, degree p_e - 1
!> on each contact edge of degree p_e >= 2 (hp); --half, degree ceil(p_e / 2) (hp);
!> --coarse, hats on every other vertex (P1); --drop S, the contact functions within S of an
!> end left out (rows and columns).
program pencil_probe
    use iso_fortran_env, only: output_unit, error_unit
    use kinds, only: wp
    use status, only: status_t
    use strings, only: text_t
    use timer, only: timings_t
    use run_config, only: config_t
    use input_config, only: read_input
    use run_inputs, only: run_inputs_t, translate_input
    use problem, only: problem_t, build_problem
    use mesh, only: mesh_t
    use mesh_singular, only: singular_vertices
    use mesh_geometric, only: geometric_mesh, cell_layers, layer_degrees
    use hp_space, only: hp_space_t, build_hp_space
    use hp_eigen, only: hp_assembled_problem, factor_hp_stiffness
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_contact_blocks, contact_flexibility
    use lapack_interfaces, only: dggev, dgeev
    use pencil_tracking, only: pencil_profile_bins
    implicit none

    interface
        subroutine dpotrf(uplo, n, a, lda, info)
            character, intent(in) :: uplo
            integer, intent(in) :: n, lda
            double precision, intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotrf
        subroutine dgesvd(jobu, jobvt, m, n, a, lda, s, u, ldu, vt, ldvt, work, lwork, info)
            character, intent(in) :: jobu, jobvt
            integer, intent(in) :: m, n, lda, ldu, ldvt, lwork
            double precision, intent(inout) :: a(lda, *)
            double precision, intent(out) :: s(*), u(ldu, *), vt(ldvt, *), work(*)
            integer, intent(out) :: info
        end subroutine dgesvd
    end interface

    type(config_t) :: config
    type(run_inputs_t) :: inputs
    type(problem_t) :: start, prob
    type(cholesky_t) :: chol
    type(timings_t) :: timings
    type(status_t) :: stat
    type(text_t), allocatable :: settings(:)
    type(mesh_t) :: graded
    type(hp_space_t) :: space
    real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :), position(:), points(:, :)
    logical, allocatable :: vertex(:)
    character(len=:), allocatable :: input, degrees
    character(len=256) :: argument
    real(wp) :: window(2), scan(2), s_min, s_max
    integer :: level, n_scan, i, narg
    real(wp) :: theta_range(2) = 0.0_wp   !! --theta A B N: the spectrum of A(lambda) near 0
    integer :: n_theta = 0
    logical :: profile, edges
    real(wp) :: dump = 0.0_wp   !! --vector L: print the vector of the real eigenvalue L
    logical :: half = .false.   !! --half: multipliers of degree ceil(p/2)
    logical :: drop_top = .false.   !! --lower: multipliers one degree below each contact edge
    logical :: coarse = .false.   !! --coarse: multipliers on every other vertex (P1 only)
    real(wp) :: drop   !! --drop D: leave out the contact functions within D (s units) of an end

    level = 0
    degrees = 'default'
    window = [-50.0_wp, 50.0_wp]
    n_scan = 0
    scan = 0.0_wp
    profile = .false.
    edges = .false.
    drop = -1.0_wp
    input = ''
    allocate (settings(0))
    narg = command_argument_count()
    i = 0
    do while (i < narg)
        i = i + 1
        call get_command_argument(i, argument)
        select case (trim(argument))
        case ('--set')
            i = i + 1
            call get_command_argument(i, argument)
            call add_setting(trim(argument))
        case ('--level')
            level = int_argument(i + 1)
            i = i + 1
        case ('--degrees')
            i = i + 1
            call get_command_argument(i, argument)
            degrees = trim(argument)
        case ('--window')
            window = [real_argument(i + 1), real_argument(i + 2)]
            i = i + 2
        case ('--scan')
            scan = [real_argument(i + 1), real_argument(i + 2)]
            n_scan = int_argument(i + 3)
            i = i + 3
        case ('--theta')
            theta_range = [real_argument(i + 1), real_argument(i + 2)]
            n_theta = int_argument(i + 3)
            i = i + 3
        case ('--profile')
            profile = .true.
        case ('--edges')
            edges = .true.
        case ('--vector')
            dump = real_argument(i + 1)
            i = i + 1
        case ('--coarse')
            coarse = .true.
        case ('--lower')
            drop_top = .true.
        case ('--half')
            drop_top = .true.
            half = .true.
        case ('--drop')
            drop = real_argument(i + 1)
            i = i + 1
        case default
            input = trim(argument)
        end select
    end do
    if (len(input) == 0) call fail('usage: pencil_probe INPUT.nml [--set g%v=x]... '// &
                                   '[--level L] [--degrees D] [--window A B] [--scan A B N] '// &
                                   '[--profile]')

    call read_input(input, config, stat, settings)
    call check(stat)
    call translate_input(config, inputs)
    call build_problem(inputs%scene, start, stat)
    call check(stat)
    if (level == 0) then
        prob = start
        call factor_contact_blocks(prob%k, prob%mesh, prob%dofs, prob%contact, chol, kt_nn, &
                                   kt_nt, timings, stat)
        call check(stat)
        allocate (vertex(prob%contact%p()), source=.true.)
    else
        points = start%mesh%coords(:, singular_vertices(start%mesh))
        do i = 1, size(points, 2)
            write (output_unit, '(a, 2es24.15)') '# singular point ', points(:, i)
        end do
        call hp_level(stat)
        call check(stat)
        call factor_hp_stiffness(prob%k, prob%mesh, space, prob%contact, chol, timings, stat)
        call check(stat)
        call contact_flexibility(chol, prob%contact, kt_nn, kt_nt, stat)
        call check(stat)
        vertex = prob%contact%nodes <= space%n_vertices
    end if
    call chol%free()
    ! positions along t of the vertex-type contact functions, and of the segment's ends
    allocate (position(prob%contact%p()), source=0.0_wp)
    do i = 1, prob%contact%p()
        if (vertex(i)) position(i) = dot_product(prob%mesh%coords(:, prob%contact%nodes(i)), &
                                                 prob%contact%tangent)
    end do
    call segment_ends(s_min, s_max)
    if (drop >= 0.0_wp) call drop_end_functions()
    if (coarse) call coarse_multipliers()
    if (drop_top) call lower_degree_multipliers()
    write (output_unit, '(a, es24.15)') '# segment length ', s_max - s_min
    write (output_unit, '(a, i0, a, i0, a, es10.3)') '# free dofs ', prob%dofs%n_free, &
        ', contact functions ', prob%contact%p(), ', smallest contact cell ', smallest_cell()
    call pencil_lines()
    if (n_scan > 0) call scan_lines()
    if (n_theta > 0) call theta_lines()

contains

    !> For each lambda of the range: the eigenvalues theta = 1/mu of A = (lambda Kt_nt - Kt_nn) M
    !> with the largest real parts (the positive mu and the pairs about to land), as
    !> 'theta lambda count Re1 Im1 Re2 Im2 ...' with count the number of positive real mu.
    subroutine theta_lines()
        real(wp), allocatable :: mass(:, :), a(:, :), wr(:), wi(:), work(:)
        integer, allocatable :: order(:)
        real(wp) :: lambda, query(1), left(1, 1), right(1, 1)
        integer :: p, info, j, k, n_pos
        p = size(kt_nn, 1)
        mass = prob%contact%mass_dense()
        allocate (wr(p), wi(p))
        do j = 0, n_theta - 1
            lambda = theta_range(1) + (theta_range(2) - theta_range(1))*j/max(1, n_theta - 1)
            a = matmul(lambda*kt_nt - kt_nn, mass)
            if (.not. allocated(work)) then
                call dgeev('N', 'N', p, a, p, wr, wi, left, 1, right, 1, query, -1, info)
                allocate (work(int(query(1))))
            end if
            call dgeev('N', 'N', p, a, p, wr, wi, left, 1, right, 1, work, size(work), info)
            if (info /= 0) call fail('dgeev failed')
            n_pos = count(wr > 0.0_wp .and. .not. abs(wi) > 0.0_wp)
            order = [(k, k=1, p)]
            do k = 1, min(6, p)   ! the six largest real parts first
                order(k:) = cshift(order(k:), maxloc(wr(order(k:)), 1) - 1)
            end do
            write (output_unit, '(a, es24.15, i4, *(es13.5))') 'theta ', lambda, n_pos, &
                (wr(order(k)), wi(order(k)), k=1, min(6, p))
        end do
    end subroutine theta_lines

    !> settings gains `text` (an array constructor of text_t garbles gfortran 12's copy).
    subroutine add_setting(text)
        character(len=*), intent(in) :: text
        type(text_t), allocatable :: longer(:)
        integer :: k
        allocate (longer(size(settings) + 1))
        do k = 1, size(settings)
            longer(k)%text = settings(k)%text
        end do
        longer(size(longer))%text = text
        call move_alloc(longer, settings)
    end subroutine add_setting

    !> The hp level `level` of the input mesh with the degrees --degrees asks for.
    subroutine hp_level(stat)
        type(status_t), intent(out) :: stat
        real(wp) :: h_min
        integer, allocatable :: degree(:), layer(:)
        integer :: c, q
        call geometric_mesh(start%mesh, points, config%adapt%sigma, level, graded, h_min, stat)
        if (.not. stat%ok()) return
        layer = cell_layers(graded, points, config%adapt%sigma, h_min)
        degree = layer_degrees(layer, 1, 1.0_wp, min(level + 1, config%adapt%p_max))
        if (degrees(1:min(8, len(degrees))) == 'uniform:') then
            read (degrees(9:), *) q
            degree = q
        else if (degrees(1:min(5, len(degrees))) == 'pmin:') then
            read (degrees(6:), *) q
            degree = max(degree, q)
        else if (degrees(1:min(5, len(degrees))) == 'plus:') then
            read (degrees(6:), *) q
            degree = min(degree + q, 20)
        else if (degrees(1:min(8, len(degrees))) == 'contact:') then
            read (degrees(9:), *) q
            do c = 1, graded%n_cells()
                if (touches_contact(c)) degree(c) = max(degree(c), q)
            end do
        else if (degrees /= 'default') then
            call fail('--degrees: expected default, uniform:Q, pmin:K or contact:K')
        end if
        call build_hp_space(graded, degree, start%dirichlet_parts, space, stat)
        if (.not. stat%ok()) return
        prob%mesh = graded
        prob%dirichlet_parts = start%dirichlet_parts
        prob%neumann_parts = start%neumann_parts
        prob%contact_part = start%contact_part
        prob%young = start%young
        prob%poisson = start%poisson
        call hp_assembled_problem(graded, space, start%contact_part, start%young, &
                                  start%poisson, prob%contact, prob%k, timings, stat)
        prob%dofs%n_free = space%n_free()
        write (output_unit, '(a, i0, a, i0, a, i0, a, i0)') '# hp level ', level, ': cells ', &
            graded%n_cells(), ', degrees ', minval(degree), ' to ', maxval(degree)
        if (edges) then
            do c = 1, space%n_edges()
                if (space%edge_part(c) /= start%contact_part) cycle
                write (output_unit, '(a, 2es14.6, i4)') '# contact edge ', &
                    graded%coords(1, space%edge_ends(:, c)), space%edge_degree(c)
            end do
        end if
    end subroutine hp_level

    !> Whether cell `c` of the graded mesh has a side on Gamma_C (two corners on it).
    logical function touches_contact(c)
        integer, intent(in) :: c
        logical, allocatable :: on_contact(:)
        integer :: e
        allocate (on_contact(graded%n_nodes()), source=.false.)
        do e = 1, size(graded%edge_part)
            if (graded%edge_part(e) == start%contact_part) on_contact(graded%edges(1:2, e)) = .true.
        end do
        touches_contact = count(on_contact(graded%cells(1:3, c))) >= 2
    end function touches_contact

    subroutine segment_ends(s_min, s_max)
        real(wp), intent(out) :: s_min, s_max
        real(wp) :: s
        integer :: e, k
        s_min = huge(1.0_wp)
        s_max = -huge(1.0_wp)
        do e = 1, size(prob%mesh%edge_part)
            if (prob%mesh%edge_part(e) /= prob%contact_part) cycle
            do k = 1, 2
                s = dot_product(prob%mesh%coords(:, prob%mesh%edges(k, e)), prob%contact%tangent)
                s_min = min(s_min, s)
                s_max = max(s_max, s)
            end do
        end do
    end subroutine segment_ends

    real(wp) function smallest_cell()
        real(wp) :: h
        integer :: e
        smallest_cell = huge(1.0_wp)
        do e = 1, size(prob%mesh%edge_part)
            if (prob%mesh%edge_part(e) /= prob%contact_part) cycle
            h = norm2(prob%mesh%coords(:, prob%mesh%edges(2, e)) - &
                      prob%mesh%coords(:, prob%mesh%edges(1, e)))
            smallest_cell = min(smallest_cell, h)
        end do
    end function smallest_cell

    !> The pencil with the contact forces x = M I y of a coarser multiplier space: continuous
    !> piecewise linear on every other vertex of Gamma_C (ends kept, a clamped end's hat
    !> left out), I its values at the contact nodes; u_n is then zero against that space:
    !> (I' M Kt_nn M I) y = lambda (I' M Kt_nt M I) y. P1 contact functions only.
    subroutine coarse_multipliers()
        real(wp), allocatable :: z(:), interp(:, :), c(:, :), mass(:, :)
        logical, allocatable :: free_node(:)
        integer, allocatable :: all_coarse(:), node_of(:)
        integer :: a, i, k, n, q, left, right, here
        real(wp) :: t
        if (.not. all(vertex)) call fail('--coarse: P1 contact functions only')
        ! the fine vertices along Gamma_C, a clamped end included
        allocate (z, source=position)
        allocate (free_node(size(z)), source=.true.)
        if (minval(z) > s_min + 1.0e-12_wp*(s_max - s_min)) then
            z = [s_min, z]
            free_node = [.false., free_node]
        end if
        if (maxval(z) < s_max - 1.0e-12_wp*(s_max - s_min)) then
            z = [z, s_max]
            free_node = [free_node, .false.]
        end if
        n = size(z)
        all_coarse = [(k, k=1, n, 2)]
        if (all_coarse(size(all_coarse)) /= n) all_coarse = [all_coarse, n]
        node_of = pack([(k, k=1, n)], free_node)
        q = count(free_node(all_coarse))
        allocate (interp(size(position), q), source=0.0_wp)
        k = 0
        do i = 1, size(all_coarse)
            here = all_coarse(i)
            if (.not. free_node(here)) cycle
            k = k + 1
            left = all_coarse(max(1, i - 1))
            right = all_coarse(min(size(all_coarse), i + 1))
            do a = 1, size(position)
                t = z(node_of(a))
                if (node_of(a) == here) then
                    interp(a, k) = 1.0_wp
                else if (left /= here .and. t > z(left) .and. t < z(here)) then
                    interp(a, k) = (t - z(left))/(z(here) - z(left))
                else if (right /= here .and. t > z(here) .and. t < z(right)) then
                    interp(a, k) = (z(right) - t)/(z(right) - z(here))
                end if
            end do
        end do
        mass = prob%contact%mass_dense()
        c = matmul(mass, interp)
        do a = 1, size(c, 2)
            c(:, a) = c(:, a)/norm2(c(:, a))
        end do
        kt_nn = matmul(transpose(c), matmul(kt_nn, c))
        kt_nt = matmul(transpose(c), matmul(kt_nt, c))
        position = z(pack(all_coarse, free_node(all_coarse)))
        vertex = [(.true., k=1, q)]
        write (output_unit, '(a, i0, a)') '# coarse multipliers: ', q, ' functions'
    end subroutine coarse_multipliers

    !> The pencil with multipliers of degree p_e - 1 on each contact edge of degree p_e >= 2
    !> (the trace space without each edge's top hierarchical function; degree-1 edges keep
    !> their hats): x = M I y with I the selection, (I' M Kt M I) y = lambda (...) y. hp only.
    subroutine lower_degree_multipliers()
        real(wp), allocatable :: c(:, :), mass(:, :)
        logical, allocatable :: keep(:)
        integer :: a, f, e
        if (level == 0) call fail('--lower: hp levels only')
        allocate (keep(prob%contact%p()), source=.true.)
        do a = 1, prob%contact%p()
            f = prob%contact%nodes(a)
            if (f <= space%n_vertices) cycle
            do e = 1, space%n_edges()
                if (space%edge_degree(e) < 2) cycle
                if (f < space%edge_first(e) .or. &
                    f > space%edge_first(e) + space%edge_degree(e) - 2) cycle
                ! function f has degree f - edge_first + 2; keep degrees up to the multiplier's
                if (f - space%edge_first(e) + 2 > multiplier_degree(space%edge_degree(e))) &
                    keep(a) = .false.
            end do
        end do
        mass = prob%contact%mass_dense()
        c = mass(:, pack([(a, a=1, size(keep))], keep))
        do a = 1, size(c, 2)   ! unit columns: a diagonal scaling, the same eigenvalues
            c(:, a) = c(:, a)/norm2(c(:, a))
        end do
        kt_nn = matmul(transpose(c), matmul(kt_nn, c))
        kt_nt = matmul(transpose(c), matmul(kt_nt, c))
        position = pack(position, keep)
        vertex = pack(vertex, keep)
        write (output_unit, '(a, i0, a)') '# lower-degree multipliers: ', count(keep), ' functions'
    end subroutine lower_degree_multipliers

    !> The multiplier degree on a contact edge of degree p: p - 1, or with --half ceil(p/2).
    integer function multiplier_degree(p)
        integer, intent(in) :: p
        multiplier_degree = p - 1
        if (half) multiplier_degree = max(1, (p + 1)/2)
    end function multiplier_degree

    !> Keep only the contact functions whose vertex (or edge, by its neighbours) lies more
    !> than `drop` (relative position) from both ends: a multiplier space without them.
    subroutine drop_end_functions()
        logical, allocatable :: keep(:)
        real(wp) :: s, last
        integer :: a
        allocate (keep(size(position)))
        last = 0.5_wp
        do a = 1, size(position)
            if (vertex(a)) last = (position(a) - s_min)/(s_max - s_min)
            s = last
            keep(a) = s > drop .and. s < 1.0_wp - drop
        end do
        kt_nn = kt_nn(pack([(a, a=1, size(keep))], keep), pack([(a, a=1, size(keep))], keep))
        kt_nt = kt_nt(pack([(a, a=1, size(keep))], keep), pack([(a, a=1, size(keep))], keep))
        position = pack(position, keep)
        vertex = pack(vertex, keep)
        write (output_unit, '(a, i0, a)') '# dropped ', count(.not. keep), ' contact functions'
    end subroutine drop_end_functions

    !> The real eigenvalues of the pencil in the window and the complex pairs near the axis.
    subroutine pencil_lines()
        real(wp), allocatable :: a(:, :), b(:, :), alphar(:), alphai(:), beta(:), work(:), &
                                 vl(:, :), vr(:, :), x(:), w(:), s(:), bins(:), weight(:)
        real(wp) :: query(1), lambda, norm_nn, norm_nt, condition, mean, low, high, spread
        integer :: p, info, j, k
        p = size(kt_nn, 1)
        allocate (a, source=kt_nn)
        allocate (b, source=kt_nt)
        allocate (alphar(p), alphai(p), beta(p), vl(p, p), vr(p, p))
        call dggev('V', 'V', p, a, p, b, p, alphar, alphai, beta, vl, p, vr, p, query, -1, info)
        allocate (work(int(query(1))))
        call dggev('V', 'V', p, a, p, b, p, alphar, alphai, beta, vl, p, vr, p, work, &
                   size(work), info)
        if (info /= 0) call fail('dggev failed')
        norm_nn = maxval(sum(abs(kt_nn), dim=2))
        norm_nt = maxval(sum(abs(kt_nt), dim=2))
        s = (position - s_min)/(s_max - s_min)
        do j = 1, p
            if (abs(beta(j))*norm_nn <= p*epsilon(1.0_wp)*abs(alphar(j))*norm_nt) cycle
            lambda = alphar(j)/beta(j)
            if (lambda < window(1) .or. lambda > window(2)) cycle
            if (abs(alphai(j)) > 0.0_wp) then
                if (alphai(j) > 0.0_wp .and. abs(alphai(j)/beta(j)) < 0.05_wp*abs(lambda)) &
                    write (output_unit, '(a, 2es24.15)') 'pair ', lambda, alphai(j)/beta(j)
                cycle
            end if
            x = vr(:, j)/norm2(vr(:, j))
            w = vl(:, j)/norm2(vl(:, j))
            condition = (norm_nn + abs(lambda)*norm_nt)/ &
                        (abs(lambda)*abs(dot_product(w, matmul(kt_nt, x))))
            weight = merge(abs(x), 0.0_wp, vertex)
            mean = sum(weight*s)/sum(weight)
            low = sum(weight, mask=s < 0.02_wp)/sum(weight)
            high = sum(weight, mask=s > 0.98_wp)/sum(weight)
            spread = sum(weight)**2/sum(weight**2)
            write (output_unit, '(a, es24.15, es11.3, 3f8.4, f9.2)', advance='no') 'real ', &
                lambda, condition, mean, low, high, spread
            if (abs(dump) > 0.0_wp .and. abs(lambda - dump) < 1.0e-6_wp*abs(dump)) then
                write (output_unit, '(a)') 
                do k = 1, p
                    write (output_unit, '(a, i4, l2, es14.6, 2es14.6)') 'vec ', k, vertex(k), &
                        s(k)*(s_max - s_min), x(k), w(k)
                end do
            end if
            if (profile) then
                bins = pencil_profile_bins(pack(s, vertex), pack(x, vertex))
                write (output_unit, '(a, *(f7.3))', advance='no') '  |', bins
            end if
            write (output_unit, '(a)') ''
        end do
    end subroutine pencil_lines

    !> The smallest singular value of R^-T (Kt_nn - lambda Kt_nt) R^-1, Kt_nn = R' R.
    subroutine scan_lines()
        real(wp), allocatable :: r(:, :), c(:, :), t(:, :), sv(:), work(:)
        real(wp) :: lambda, query(1), u_dummy(1, 1), vt_dummy(1, 1)
        integer :: p, info, j, k
        p = size(kt_nn, 1)
        allocate (r, source=kt_nn)
        call dpotrf('U', p, r, p, info)
        if (info /= 0) call fail('Kt_nn is not positive definite')
        do k = 1, p
            r(k + 1:, k) = 0.0_wp
        end do
        ! t = R^-T Kt_nt R^-1 by two triangular solves
        allocate (t, source=kt_nt)
        call solve_upper(r, t, .true.)            ! R^-T Kt_nt
        t = transpose(t)
        call solve_upper(r, t, .true.)            ! R^-T (R^-T Kt_nt)' = (Kt_nt R^-1)' ...
        t = transpose(t)
        allocate (sv(p))
        do j = 0, n_scan - 1
            lambda = scan(1) + (scan(2) - scan(1))*j/max(1, n_scan - 1)
            c = -lambda*t
            do k = 1, p
                c(k, k) = c(k, k) + 1.0_wp
            end do
            if (.not. allocated(work)) then
                call dgesvd('N', 'N', p, p, c, p, sv, u_dummy, 1, vt_dummy, 1, query, -1, info)
                allocate (work(int(query(1))))
            end if
            call dgesvd('N', 'N', p, p, c, p, sv, u_dummy, 1, vt_dummy, 1, work, size(work), &
                        info)
            write (output_unit, '(a, f12.6, es12.4)') 'scan ', lambda, sv(p)
        end do
    end subroutine scan_lines

    !> b = R^-T b (transpose = .true.) for the upper triangular R, column by column.
    subroutine solve_upper(r, b, transposed)
        real(wp), intent(in) :: r(:, :)
        real(wp), intent(inout) :: b(:, :)
        logical, intent(in) :: transposed
        integer :: i, j
        if (.not. transposed) call fail('solve_upper: only R^-T')
        do j = 1, size(b, 2)
            do i = 1, size(b, 1)
                b(i, j) = (b(i, j) - dot_product(r(1:i - 1, i), b(1:i - 1, j)))/r(i, i)
            end do
        end do
    end subroutine solve_upper

    integer function int_argument(k)
        integer, intent(in) :: k
        character(len=64) :: text
        call get_command_argument(k, text)
        read (text, *) int_argument
    end function int_argument

    real(wp) function real_argument(k)
        integer, intent(in) :: k
        character(len=64) :: text
        call get_command_argument(k, text)
        read (text, *) real_argument
    end function real_argument

    subroutine check(stat)
        type(status_t), intent(in) :: stat
        if (.not. stat%ok()) call fail(stat%message)
    end subroutine check

    subroutine fail(message)
        character(len=*), intent(in) :: message
        write (error_unit, '(a)') 'pencil_probe: '//message
        error stop 1
    end subroutine fail
end program pencil_probe
