! SPDX-License-Identifier: MIT
!> analysis = 'branch' (model.md section 9): at the critical parameters c_n = mu, c_t = mu |lambda|
!> of the lowest positive eigenpair (mu, phi), the linear field U with u_n = alpha and
!> |u_t| = beta on Gamma_C solves the discrete frictional problem, and so does U + delta phi
!> for every |delta| <= delta_max. The residual of the full stick/slip law is evaluated along
!> that segment of solutions.
module branch_analysis
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use timer, only: wall_time, timings_t
    use run_inputs, only: run_inputs_t
    use problem, only: problem_t
    use eigen_solve, only: eigen_result_t, solve_eigen
    use elasticity, only: lame_coefficients
    use loads, only: edge_loads
    use normal_compliance, only: compliance_t, build_compliance
    use real_format, only: real_to_text
    use critical_point, only: slip_sign, critical_c_t
    implicit none
    private
    public :: critical_data_t, branch_result_t, critical_branch_data, branch_compliance, &
              base_solution, base_stress, branch_delta_max, branch_deltas, run_branch

    !> Gamma_C must have the outward normal (0, -1) to this accuracy (Gmsh writes ~16 digits).
    real(wp), parameter :: NORMAL_TOL = 1.0e-10_wp

    !> The critical point of one lambda: its eigenpair and the base solution U.
    type, public :: critical_data_t
        type(eigen_result_t) :: eig
        real(wp) :: lambda = 0.0_wp
        real(wp) :: mu = 0.0_wp              !! lowest positive eigenvalue = critical c_n
        integer :: slip_sign = 0             !! s = -sgn(lambda)
        real(wp) :: alpha = 0.0_wp, beta = 0.0_wp
        real(wp) :: contact_height = 0.0_wp  !! x2 of Gamma_C (U is written in x2 - this)
        real(wp), allocatable :: phi(:)      !! (n_free) eigenvector, largest entry 1
        real(wp), allocatable :: u_base(:)   !! (2 n_nodes) U at every node, node-major
    end type critical_data_t

    type, public :: branch_result_t
        type(critical_data_t) :: critical
        type(compliance_t) :: cp
        real(wp) :: delta_max = 0.0_wp
        real(wp) :: beyond_sign = 0.0_wp     !! sign of delta in which delta_max binds
        real(wp) :: residual_base = 0.0_wp   !! relative residual of U
        real(wp) :: max_residual = 0.0_wp    !! largest relative residual over the members
        real(wp), allocatable :: deltas(:), residuals(:)
        real(wp) :: time_branch = 0.0_wp
    end type branch_result_t

contains

    !> Eigenpair and U for inputs%point%lambda and the &branch alpha, beta. Fails when
    !> Gamma_C is not horizontal with the body above it, or no positive eigenvalue exists.
    subroutine critical_branch_data(inputs, prob, timings, crit, stat)
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(timings_t), intent(inout) :: timings
        type(critical_data_t), intent(out) :: crit
        type(status_t), intent(out) :: stat
        integer :: lowest

        if (norm2(prob%contact%normal - [0.0_wp, -1.0_wp]) > NORMAL_TOL) then
            call stat%fail(STATUS_BAD_INPUT, inputs%scene%name//': &mesh: contact = '''// &
                trim(inputs%scene%contact)//''': analysis '''//inputs%analysis_name// &
                ''' needs Gamma_C along the x1-axis with outward normal (0, -1) (docs/'// &
                'model.md, section 9); this one has normal ('// &
                real_to_text(prob%contact%normal(1))// &
                ', '//real_to_text(prob%contact%normal(2))//')')
            return
        end if
        crit%lambda = inputs%point%lambda
        crit%alpha = inputs%branch%alpha
        crit%beta = inputs%branch%beta
        crit%contact_height = prob%mesh%coords(2, prob%contact%nodes(1))
        call solve_eigen(inputs%scene, prob, crit%lambda, inputs%eigen, crit%eig, timings, stat)
        if (.not. stat%ok()) return
        lowest = crit%eig%spec%lowest_positive()
        if (lowest == 0) then
            call stat%fail(STATUS_BAD_INPUT, inputs%scene%name//': &analysis: lambda = '// &
                real_to_text(crit%lambda)//': no positive real eigenvalue, so no critical '// &
                'c_n and no branch (|lambda| must exceed the critical threshold)')
            return
        end if
        crit%mu = real(crit%eig%spec%mu(lowest), wp)
        crit%slip_sign = slip_sign(crit%lambda)
        crit%phi = real(crit%eig%spec%vectors(:, lowest), wp)
        crit%u_base = base_solution(prob%mesh%coords, crit%lambda, crit%mu, crit%alpha, &
            crit%beta, crit%contact_height, prob%young, prob%poisson)
    end subroutine critical_branch_data

    !> U(x) = (sgn(lambda) beta + alpha lambda mu / G y, -alpha - alpha mu / (L + 2G) y),
    !> y = x2 - contact_height, at every node, node-major.
    pure function base_solution(coords, lambda, mu, alpha, beta, contact_height, young, &
                                poisson) result(u)
        real(wp), intent(in) :: coords(:, :), lambda, mu, alpha, beta, contact_height, &
                                young, poisson
        real(wp) :: u(size(coords))
        real(wp) :: lame_l, shear_g, y
        integer :: node
        call lame_coefficients(young, poisson, lame_l, shear_g)
        do node = 1, size(coords, 2)
            y = coords(2, node) - contact_height
            u(2*node - 1) = sign(beta, lambda) + alpha*lambda*mu/shear_g*y
            u(2*node) = -alpha - alpha*mu/(lame_l + 2.0_wp*shear_g)*y
        end do
    end function base_solution

    !> sigma(U), constant: eps22 = -alpha mu / (L + 2G), 2 eps12 = alpha lambda mu / G.
    pure function base_stress(lambda, mu, alpha, young, poisson) result(stress)
        real(wp), intent(in) :: lambda, mu, alpha, young, poisson
        real(wp) :: stress(2, 2)   !! in the plane
        real(wp) :: lame_l, shear_g, eps22
        call lame_coefficients(young, poisson, lame_l, shear_g)
        eps22 = -alpha*mu/(lame_l + 2.0_wp*shear_g)
        stress(1, 1) = lame_l*eps22
        stress(2, 2) = (lame_l + 2.0_wp*shear_g)*eps22
        stress(1, 2) = alpha*lambda*mu
        stress(2, 1) = stress(1, 2)
    end function base_stress

    !> The problem of model.md section 9 with c_n = factor mu, c_t = factor mu |lambda|: U on
    !> Gamma_D, sigma(U) n on every other edge but Gamma_C (sides named nowhere included: U
    !> solves the problem only if they carry its traction too), no body force.
    subroutine branch_compliance(prob, crit, factor, cp, stat)
        type(problem_t), intent(in) :: prob
        type(critical_data_t), intent(in) :: crit
        real(wp), intent(in) :: factor
        type(compliance_t), intent(out) :: cp
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: load(:)
        logical, allocatable :: loaded(:)

        allocate (loaded(size(prob%mesh%part_names)), source=.true.)
        loaded(prob%dirichlet_parts) = .false.
        loaded(prob%contact_part) = .false.
        allocate (load(size(prob%mesh%coords)), source=0.0_wp)
        call edge_loads(prob%mesh, loaded, [0.0_wp, 0.0_wp], base_stress(crit%lambda, crit%mu, &
                        crit%alpha, prob%young, prob%poisson), load, stat)
        if (.not. stat%ok()) return
        call build_compliance(prob%k_all, prob%all_contact, prob%dofs, factor*crit%mu, &
            critical_c_t(factor*crit%mu, crit%lambda), load, crit%u_base, cp, stat)
    end subroutine branch_compliance

    !> The largest delta_max such that U + delta phi keeps, at every free contact node,
    !> u_n > 0, s u_t > 0 and a positive friction bound (M u_n)_a > 0 for all |delta| <
    !> delta_max: each condition is affine in delta, a + delta b > 0, and holds for
    !> |delta| < a / |b|. `beyond_sign` is the sign of delta in which the binding one fails.
    pure subroutine branch_delta_max(cp, x_base, phi, slip_sign, delta_max, beyond_sign)
        type(compliance_t), intent(in) :: cp
        real(wp), intent(in) :: x_base(:), phi(:)   !! free dofs
        integer, intent(in) :: slip_sign
        real(wp), intent(out) :: delta_max, beyond_sign
        real(wp), allocatable :: u(:), v(:), un_u(:), un_v(:), ut_u(:), ut_v(:), mn_u(:), &
                                 mn_v(:)
        integer :: a, p

        p = cp%contact%p()
        allocate (un_u(p), un_v(p), ut_u(p), ut_v(p), mn_u(p), mn_v(p))
        allocate (u(size(cp%prescribed)), v(size(cp%prescribed)))
        u(:) = cp%expand(x_base)
        v(:) = cp%dofs%expand(phi)   ! zero on the prescribed dofs
        call cp%contact%gather(cp%contact%normal, u, un_u)
        call cp%contact%gather(cp%contact%normal, v, un_v)
        call cp%contact%gather(cp%contact%tangent, u, ut_u)
        call cp%contact%gather(cp%contact%tangent, v, ut_v)
        call cp%contact%mass%matvec(un_u, mn_u)
        call cp%contact%mass%matvec(un_v, mn_v)
        delta_max = huge(1.0_wp)
        beyond_sign = 1.0_wp
        do a = 1, p
            if (cp%contact_free(1, a) == 0) cycle
            call bound(un_u(a), un_v(a), delta_max, beyond_sign)
            call bound(slip_sign*ut_u(a), slip_sign*ut_v(a), delta_max, beyond_sign)
            call bound(mn_u(a), mn_v(a), delta_max, beyond_sign)
        end do

    contains

        pure subroutine bound(a0, b0, delta_max, beyond_sign)
            real(wp), intent(in) :: a0, b0
            real(wp), intent(inout) :: delta_max, beyond_sign
            real(wp) :: limit
            limit = 0.0_wp
            if (abs(b0) > 0.0_wp) then
                limit = max(a0, 0.0_wp)/abs(b0)
            else if (a0 > 0.0_wp) then
                return   ! holds for every delta
            end if
            if (limit < delta_max) then
                delta_max = limit
                beyond_sign = -sign(1.0_wp, b0)
            end if
        end subroutine bound
    end subroutine branch_delta_max

    !> n values evenly spaced in [-delta_max, delta_max] (just 0 when n = 1).
    pure function branch_deltas(delta_max, n) result(deltas)
        real(wp), intent(in) :: delta_max
        integer, intent(in) :: n
        real(wp) :: deltas(n)
        integer :: i
        if (n == 1) then
            deltas = 0.0_wp
            return
        end if
        do i = 1, n
            deltas(i) = delta_max*real(2*i - n - 1, wp)/real(n - 1, wp)
        end do
    end function branch_deltas

    !> The whole analysis: eigenpair, U, delta_max, and the residual of every member.
    subroutine run_branch(inputs, prob, res, timings, stat)
        type(run_inputs_t), intent(in) :: inputs
        type(problem_t), intent(in) :: prob
        type(branch_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: x_base(:)
        real(wp) :: start
        integer :: i

        call critical_branch_data(inputs, prob, timings, res%critical, stat)
        if (.not. stat%ok()) return
        start = wall_time()
        call branch_compliance(prob, res%critical, 1.0_wp, res%cp, stat)
        if (.not. stat%ok()) return
        x_base = res%critical%u_base(res%cp%free_to_all)
        res%residual_base = res%cp%relative_residual(x_base)
        call branch_delta_max(res%cp, x_base, res%critical%phi, res%critical%slip_sign, &
                              res%delta_max, res%beyond_sign)
        res%deltas = branch_deltas(res%delta_max, inputs%branch%n_delta)
        allocate (res%residuals(size(res%deltas)))
        do i = 1, size(res%deltas)
            res%residuals(i) = res%cp%relative_residual(x_base + res%deltas(i)*res%critical%phi)
        end do
        res%max_residual = max(res%residual_base, maxval(res%residuals))
        res%time_branch = wall_time() - start
    end subroutine run_branch
end module branch_analysis
