! SPDX-License-Identifier: MIT
!> The discrete frictional normal-compliance problem (model.md section 3, m_n = m_t = 1) as a
!> non-smooth system H(x) = 0 on the free dofs x, with its generalized (Clarke) Jacobian.
!>
!> Contact terms: with M the consistent mass matrix of Gamma_C on ALL its nodes (prescribed
!> ones included, so non-zero Dirichlet data count) and u_n, u_t the nodal normal and
!> tangential displacements, the normal nodal force is P = c_n M (u_n)+ (the positive part is
!> taken at the nodes and interpolated: int_C I_h((u_n)+) v_n, exact where u_n > 0, where it is
!> the linear term of K phi = mu B phi) and the friction bound is Q = max(c_t M (u_n)+, 0).
!> The law is imposed node by node on the nodal tangential force S_a:
!>     |S_a| <= Q_a where u_t(a) = 0,    S_a = Q_a sgn(u_t(a)) where u_t(a) /= 0,
!> written as the equation S_a = proj_[-Q_a, Q_a](S_a + rho_a u_t(a)) with rho_a the
!> tangential diagonal stiffness of the node (a force per length, so both sides are forces).
!>
!> H(x): the equilibrium rows K u + N^T P - f on the free dofs, except at a free contact node,
!> whose x row holds the normal equilibrium n.(K u - f)_a + P_a and whose y row holds the
!> friction residual S_a - proj(S_a + rho_a u_t(a)) with S_a = -t.(K u - f)_a (the tangential
!> force the foundation must supply). Where every node slips with sign s and u_n > 0, H = 0 is
!> the slipping problem K u + c_n N^T M N u + s c_t T^T M N u = f of model.md section 3.
module normal_compliance
    use kinds, only: wp
    use status, only: status_t, STATUS_INTERNAL
    use dof_map, only: dof_map_t
    use contact_boundary, only: contact_t
    use csr_matrix, only: csr_matrix_t
    implicit none
    private
    public :: compliance_t, build_compliance, state_name
    public :: STATE_SEPARATED, STATE_STICK, STATE_SLIP_PLUS, STATE_SLIP_MINUS

    !> Nodal states of the friction law.
    integer, parameter :: STATE_SEPARATED = 0   !! Q_a = 0: no normal force, no friction
    integer, parameter :: STATE_STICK = 1       !! |S_a + rho_a u_t(a)| < Q_a: u_t(a) = 0
    integer, parameter :: STATE_SLIP_PLUS = 2   !! S_a = Q_a, u_t(a) >= 0
    integer, parameter :: STATE_SLIP_MINUS = 3  !! S_a = -Q_a, u_t(a) <= 0

    type, public :: compliance_t
        type(csr_matrix_t) :: k_all              !! K on all dofs, numbered 2 (node - 1) + c
        type(contact_t) :: contact               !! Gamma_C, all its nodes, all-dof numbering
        type(dof_map_t) :: dofs                  !! the free dofs x lives on
        integer, allocatable :: free_to_all(:)   !! (n_free) all-dof number of each free dof
        integer, allocatable :: contact_free(:, :) !! (dim, p) free dofs of contact node a, or 0
        real(wp), allocatable :: load(:)         !! (2 n_nodes) consistent nodal forces f
        real(wp), allocatable :: prescribed(:)   !! (2 n_nodes) u on prescribed dofs, else 0
        real(wp), allocatable :: rho(:)          !! (p) t^T K_aa t of each contact node
        real(wp) :: c_n = 0.0_wp
        real(wp) :: c_t = 0.0_wp
        real(wp) :: load_norm = 0.0_wp           !! ||f - K u_D||_inf on the free rows
    contains
        procedure :: n_free => compliance_n_free
        procedure :: expand => compliance_expand
        procedure :: free_stiffness => compliance_free_stiffness
        procedure :: residual => compliance_residual
        procedure :: relative_residual => compliance_relative_residual
        procedure :: jacobian => compliance_jacobian
        procedure :: nodal_forces => compliance_nodal_forces
    end type compliance_t

contains

    pure function state_name(state) result(name)
        integer, intent(in) :: state
        character(len=:), allocatable :: name
        select case (state)
        case (STATE_SEPARATED); name = 'separated'
        case (STATE_STICK); name = 'stick'
        case (STATE_SLIP_PLUS); name = 'slip+'
        case default; name = 'slip-'
        end select
    end function state_name

    !> Set up the problem from K and Gamma_C on all dofs (k_all, all_contact), `dofs` numbering
    !> the free ones: `load` holds the consistent nodal forces on all dofs and `prescribed` the
    !> displacement on all dofs (only its prescribed entries are used).
    subroutine build_compliance(k_all, all_contact, dofs, c_n, c_t, load, prescribed, cp, stat)
        type(csr_matrix_t), intent(in) :: k_all
        type(contact_t), intent(in) :: all_contact
        type(dof_map_t), intent(in) :: dofs
        real(wp), intent(in) :: c_n, c_t
        real(wp), intent(in) :: load(:), prescribed(:)   !! (2 n_nodes)
        type(compliance_t), intent(out) :: cp
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: b(:), u_d(:)
        integer :: node, c, a, k, i, p

        cp%k_all = k_all
        cp%contact = all_contact
        cp%c_n = c_n
        cp%c_t = c_t
        cp%load = load
        cp%prescribed = prescribed

        cp%dofs = dofs
        cp%free_to_all = dofs%free_to_all()
        ! Prescribed values only where a dof is prescribed: a free entry would leak into K u.
        cp%prescribed(cp%free_to_all) = 0.0_wp

        p = cp%contact%p()
        allocate (cp%contact_free(dofs%dim(), p), cp%rho(p))
        do a = 1, p
            node = cp%contact%nodes(a)
            cp%contact_free(:, a) = dofs%free_dof(:, node)
            if (any(cp%contact_free(:, a) == 0)) cp%contact_free(:, a) = 0
            cp%rho(a) = 0.0_wp
            do i = 1, dofs%dim()
                do c = 1, dofs%dim()
                    k = cp%k_all%slot(cp%contact%dofs(i, a), cp%contact%dofs(c, a))
                    if (k > 0) cp%rho(a) = cp%rho(a) + &
                        cp%contact%tangent(i)*cp%k_all%val(k)*cp%contact%tangent(c)
                end do
            end do
        end do

        ! The data's right-hand side on the free rows: f - K u_D.
        allocate (b(size(load)))
        u_d = cp%prescribed
        call cp%k_all%matvec(u_d, b)
        b = load - b
        cp%load_norm = 0.0_wp
        if (dofs%n_free > 0) cp%load_norm = maxval(abs(b(cp%free_to_all)))
    end subroutine build_compliance

    pure integer function compliance_n_free(this)
        class(compliance_t), intent(in) :: this
        compliance_n_free = size(this%free_to_all)
    end function compliance_n_free

    !> The displacement on all dofs: x on the free dofs, the prescribed values elsewhere.
    pure function compliance_expand(this, x) result(u)
        class(compliance_t), intent(in) :: this
        real(wp), intent(in) :: x(:)
        real(wp) :: u(size(this%prescribed))
        u = this%dofs%expand(x, this%prescribed)
    end function compliance_expand

    !> K on the free dofs, the Jacobian's pattern: restricted from K on all dofs when needed
    !> rather than kept as a second copy of K.
    function compliance_free_stiffness(this) result(k_free)
        class(compliance_t), intent(in) :: this
        type(csr_matrix_t) :: k_free
        k_free = this%k_all%restrict(reshape(this%dofs%free_dof, [size(this%dofs%free_dof)]))
    end function compliance_free_stiffness

    !> H(x) (see the module), and optionally the state of every contact node (prescribed
    !> nodes are reported as separated: no law applies there).
    subroutine compliance_residual(this, x, h, states)
        class(compliance_t), intent(in) :: this
        real(wp), intent(in) :: x(:)
        real(wp), intent(out) :: h(:)
        integer, intent(out), optional :: states(:)
        real(wp), allocatable :: r(:), u_n(:), u_t(:), p_n(:), bound(:)
        real(wp) :: s, z
        integer :: a

        call contact_terms(this, x, r, u_n, u_t, p_n, bound)
        h = r(this%free_to_all)
        if (present(states)) states = STATE_SEPARATED
        do a = 1, this%contact%p()
            if (this%contact_free(1, a) == 0) cycle
            associate (rows => this%contact%dofs(:, a), n => this%contact%normal, &
                       t => this%contact%tangent)
                s = -dot_product(t, r(rows))
                z = s + this%rho(a)*u_t(a)
                h(this%contact_free(1, a)) = dot_product(n, r(rows))
                h(this%contact_free(2, a)) = s - min(max(z, -bound(a)), bound(a))
            end associate
            if (present(states)) states(a) = node_state(z, bound(a))
        end do
    end subroutine compliance_residual

    !> ||H(x)||_inf / ||f - K u_D||_inf (absolute when the data vanish).
    function compliance_relative_residual(this, x) result(e)
        class(compliance_t), intent(in) :: this
        real(wp), intent(in) :: x(:)
        real(wp) :: e
        real(wp), allocatable :: h(:)
        allocate (h(size(x)))
        call this%residual(x, h)
        e = 0.0_wp
        if (size(h) > 0) e = maxval(abs(h))
        if (this%load_norm > 0.0_wp) e = e/this%load_norm
    end function compliance_relative_residual

    !> Nodal u_n, u_t, normal force P, tangential force S and friction bound Q at x, per
    !> contact node (S from the equilibrium rows: the force the foundation supplies).
    subroutine compliance_nodal_forces(this, x, u_n, u_t, p_n, s_t, bound)
        class(compliance_t), intent(in) :: this
        real(wp), intent(in) :: x(:)
        real(wp), allocatable, intent(out) :: u_n(:), u_t(:), p_n(:), s_t(:), bound(:)
        real(wp), allocatable :: r(:)
        integer :: a
        call contact_terms(this, x, r, u_n, u_t, p_n, bound)
        allocate (s_t(size(u_n)))
        do a = 1, size(u_n)
            s_t(a) = -dot_product(this%contact%tangent, r(this%contact%dofs(:, a)))
        end do
    end subroutine compliance_nodal_forces

    !> r = K u - f + N^T P on all dofs, and the nodal contact quantities.
    subroutine contact_terms(this, x, r, u_n, u_t, p_n, bound)
        type(compliance_t), intent(in) :: this
        real(wp), intent(in) :: x(:)
        real(wp), allocatable, intent(out) :: r(:), u_n(:), u_t(:), p_n(:), bound(:)
        real(wp), allocatable :: u(:)
        integer :: p

        p = this%contact%p()
        ! u allocated, then filled: reallocation on assignment from this function result
        ! made UBSan see overflowing bounds arithmetic
        allocate (r(size(this%prescribed)), u(size(this%prescribed)), u_n(p), u_t(p), p_n(p), &
                  bound(p))
        u(:) = this%expand(x)
        call this%k_all%matvec(u, r)
        r = r - this%load
        call this%contact%gather(this%contact%normal, u, u_n)
        call this%contact%gather(this%contact%tangent, u, u_t)
        call this%contact%mass%matvec(max(u_n, 0.0_wp), bound)
        p_n = this%c_n*bound
        ! P2/Q2 masses have negative entries: a negative bound would make the law void.
        bound = max(this%c_t*bound, 0.0_wp)
        call this%contact%scatter(this%contact%normal, p_n, r)
    end subroutine contact_terms

    !> Branch of the projection proj_[-q, q](z) that is active.
    pure integer function node_state(z, q)
        real(wp), intent(in) :: z, q
        if (.not. q > 0.0_wp) then
            node_state = STATE_SEPARATED
        else if (abs(z) < q) then
            node_state = STATE_STICK
        else if (z > 0.0_wp) then
            node_state = STATE_SLIP_PLUS
        else
            node_state = STATE_SLIP_MINUS
        end if
    end function node_state

    !> An element of the generalized Jacobian of H at x, on the pattern of K_free (contact
    !> nodes of Gamma_C are neighbours through a cell, so the pattern holds every coupling).
    !> Kinks are resolved as: u_n = 0 counts as separated, |z| = Q as slipping.
    subroutine compliance_jacobian(this, x, jac, stat)
        class(compliance_t), intent(in) :: this
        real(wp), intent(in) :: x(:)
        type(csr_matrix_t), intent(out) :: jac
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: r(:), u_n(:), u_t(:), p_n(:), bound(:), row_n(:), row_t(:)
        real(wp) :: s, z, sign_q
        integer :: a, b, k, ix, iy, first_x, first_y, length, state
        type(csr_matrix_t) :: k_free

        k_free = this%free_stiffness()
        jac = k_free
        call contact_terms(this, x, r, u_n, u_t, p_n, bound)
        do a = 1, this%contact%p()
            if (this%contact_free(1, a) == 0) cycle
            ix = this%contact_free(1, a)
            iy = this%contact_free(2, a)
            first_x = jac%row_start(ix)
            first_y = jac%row_start(iy)
            length = jac%row_start(ix + 1) - first_x
            if (length /= jac%row_start(iy + 1) - first_y .or. any(jac%col(first_x: &
                first_x + length - 1) /= jac%col(first_y:first_y + length - 1))) then
                call stat%fail(STATUS_INTERNAL, 'normal compliance: the two rows of a '// &
                               'contact node differ in pattern')
                return
            end if
            associate (n => this%contact%normal, t => this%contact%tangent, &
                       vx => k_free%val(first_x:first_x + length - 1), &
                       vy => k_free%val(first_y:first_y + length - 1))
                row_n = n(1)*vx + n(2)*vy
                row_t = -(t(1)*vx + t(2)*vy)   ! dS
                s = -dot_product(t, r(this%contact%dofs(:, a)))
                z = s + this%rho(a)*u_t(a)
                state = node_state(z, bound(a))
                jac%val(first_x:first_x + length - 1) = row_n
                if (state == STATE_STICK) then
                    ! S - z = -rho u_t
                    jac%val(first_y:first_y + length - 1) = 0.0_wp
                    call jac%add_to(iy, ix, -this%rho(a)*t(1), stat)
                    if (stat%ok()) call jac%add_to(iy, iy, -this%rho(a)*t(2), stat)
                else
                    jac%val(first_y:first_y + length - 1) = row_t
                end if
                if (.not. stat%ok()) return
                ! dP_a and dQ_a: c M_ab on the normal dofs of penetrating neighbours b.
                sign_q = 0.0_wp
                if (state == STATE_SLIP_PLUS) sign_q = -1.0_wp   ! S - Q
                if (state == STATE_SLIP_MINUS) sign_q = 1.0_wp   ! S + Q
                do k = this%contact%mass%row_start(a), this%contact%mass%row_start(a + 1) - 1
                    b = this%contact%mass%col(k)
                    if (.not. u_n(b) > 0.0_wp .or. this%contact_free(1, b) == 0) cycle
                    call add_pair(ix, b, this%c_n*this%contact%mass%val(k), n, stat)
                    if (abs(sign_q) > 0.0_wp .and. stat%ok()) &
                        call add_pair(iy, b, sign_q*this%c_t*this%contact%mass%val(k), n, stat)
                    if (.not. stat%ok()) return
                end do
            end associate
        end do

    contains

        !> jac(row, dofs of node b) += value * n
        subroutine add_pair(row, b, value, n, stat)
            integer, intent(in) :: row, b
            real(wp), intent(in) :: value, n(2)   !! a unit vector of the contact line
            type(status_t), intent(inout) :: stat
            call jac%add_to(row, this%contact_free(1, b), value*n(1), stat)
            if (stat%ok()) call jac%add_to(row, this%contact_free(2, b), value*n(2), stat)
        end subroutine add_pair
    end subroutine compliance_jacobian
end module normal_compliance
