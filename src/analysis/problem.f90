! SPDX-License-Identifier: MIT
!> The discrete problem every analysis starts from: mesh, boundary parts, free dofs, the
!> contact boundary and the stiffness matrix K on the free dofs.
module problem
    use kinds, only: wp
    use status, only: status_t, STATUS_BAD_INPUT
    use run_config, only: config_t, NAME_LEN
    use input_config, only: split_names
    use mesh, only: mesh_t, element_from_name
    use mesh_structured, only: structured_rectangle
    use mesh_gmsh, only: read_gmsh
    use mesh_check, only: check_mesh
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use contact_boundary, only: contact_t, build_contact
    use csr_matrix, only: csr_matrix_t
    implicit none
    private
    public :: problem_t, build_problem, assemble_all_dofs

    type, public :: problem_t
        type(mesh_t) :: mesh
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: k                  !! stiffness on the free dofs
        !> Only for analyses with non-zero Dirichlet data (with_all_dofs): K and Gamma_C on all
        !> dofs, prescribed ones included; k is then their restriction to the free dofs.
        type(dof_map_t) :: all_dofs
        type(csr_matrix_t) :: k_all
        type(contact_t) :: all_contact
        integer, allocatable :: dirichlet_parts(:), neumann_parts(:)
        integer :: contact_part = 0
        real(wp) :: young = 0.0_wp
        real(wp) :: poisson = 0.0_wp
    end type problem_t

contains

    !> Mesh the domain, resolve the boundary part names, number the free dofs, collect the
    !> contact boundary and assemble K; `with_all_dofs` also keeps K and Gamma_C on all dofs.
    subroutine build_problem(config, prob, stat, with_all_dofs)
        type(config_t), intent(in) :: config
        type(problem_t), intent(out) :: prob
        type(status_t), intent(out) :: stat
        logical, intent(in), optional :: with_all_dofs   !! default false
        integer, allocatable :: contact_parts(:)

        select case (config%mesh%source)
        case ('rectangle')
            call structured_rectangle(config%mesh%width, config%mesh%height, config%mesh%nx, &
                config%mesh%ny, element_from_name(config%mesh%element), config%mesh%diagonal, &
                prob%mesh, stat)
            if (.not. stat%ok()) stat%message = config%input_file//': &mesh: '//stat%message
        case ('gmsh')
            ! The element type comes from the file; &mesh element is not used.
            call read_gmsh(trim(config%mesh%file), prob%mesh, stat)
        case default
            call stat%fail(STATUS_BAD_INPUT, config%input_file//': &mesh: source = '''// &
                trim(config%mesh%source)//''': expected ''rectangle'' or ''gmsh''')
        end select
        if (.not. stat%ok()) return

        call resolve_parts('dirichlet', config%mesh%dirichlet, prob%dirichlet_parts, stat)
        if (.not. stat%ok()) return
        call resolve_parts('neumann', config%mesh%neumann, prob%neumann_parts, stat)
        if (.not. stat%ok()) return
        call resolve_parts('contact', config%mesh%contact, contact_parts, stat)
        if (.not. stat%ok()) return
        prob%contact_part = contact_parts(1)
        call check_mesh(prob%mesh, prob%dirichlet_parts, prob%neumann_parts, contact_parts, stat)
        if (.not. stat%ok()) then
            if (.not. allocated(prob%mesh%file)) &
                stat%message = config%input_file//': &mesh: '//stat%message
            return
        end if

        prob%young = config%material%young
        prob%poisson = config%material%poisson
        call build_dof_map(prob%mesh, prob%dirichlet_parts, prob%dofs, stat)
        if (.not. stat%ok()) return
        call build_contact(prob%mesh, prob%contact_part, prob%dofs, prob%contact, stat)
        if (.not. stat%ok()) then
            ! A mesh-file message already names the file and line.
            if (.not. allocated(prob%mesh%file)) &
                stat%message = config%input_file//': &mesh: contact: '//stat%message
            return
        end if
        if (.not. present(with_all_dofs)) then
            call assemble_stiffness(prob%mesh, prob%dofs, prob%young, prob%poisson, prob%k, stat)
            return
        end if
        if (.not. with_all_dofs) then
            call assemble_stiffness(prob%mesh, prob%dofs, prob%young, prob%poisson, prob%k, stat)
            return
        end if
        call assemble_all_dofs(prob%mesh, prob%young, prob%poisson, prob%contact_part, &
                               prob%all_dofs, prob%k_all, prob%all_contact, stat)
        if (stat%ok()) prob%k = prob%k_all%restrict(free_numbers(prob%dofs))

    contains

        !> The free number of every dof in the numbering of all dofs (0 where prescribed).
        pure function free_numbers(dofs) result(numbers)
            type(dof_map_t), intent(in) :: dofs
            integer :: numbers(size(dofs%free_dof))
            numbers = reshape(dofs%free_dof, [size(dofs%free_dof)])
        end function free_numbers

        !> Indices of the mesh's boundary parts named in `list`.
        subroutine resolve_parts(variable, list, parts, stat)
            character(len=*), intent(in) :: variable, list
            integer, allocatable, intent(out) :: parts(:)
            type(status_t), intent(out) :: stat
            character(len=NAME_LEN), allocatable :: names(:)
            character(len=:), allocatable :: known
            integer :: i
            allocate (names(0))   ! see split_names: avoids a false -Wuninitialized at -O3
            names = split_names(list)
            allocate (parts(size(names)))
            do i = 1, size(names)
                parts(i) = prob%mesh%part_index(trim(names(i)))
                if (parts(i) == 0) then
                    known = join(prob%mesh%part_names)
                    if (allocated(prob%mesh%file)) then
                        ! A Gmsh file: the parts are its 1D physical groups.
                        call stat%fail(STATUS_BAD_INPUT, config%input_file//': &mesh: '// &
                            variable//' = '''//trim(list)//''': the mesh file '// &
                            prob%mesh%file//' has no 1D physical group '''//trim(names(i))// &
                            ''' (it has: '//known//')')
                        return
                    end if
                    call stat%fail(STATUS_BAD_INPUT, config%input_file//': &mesh: '//variable// &
                        ' = '''//trim(list)//''': the mesh has no boundary part '''// &
                        trim(names(i))//''' (it has: '//known//')')
                    return
                end if
            end do
        end subroutine resolve_parts

        pure function join(words) result(text)
            character(len=*), intent(in) :: words(:)
            character(len=:), allocatable :: text
            integer :: i
            text = ''
            do i = 1, size(words)
                text = text//trim(words(i))
                if (i < size(words)) text = text//', '
            end do
        end function join
    end subroutine build_problem

    !> K and the contact boundary on all dofs (none prescribed), in the node-major numbering
    !> of dof_map::all_dof: what the compliance problem with Dirichlet data needs.
    subroutine assemble_all_dofs(m, young, poisson, contact_part, all_dofs, k_all, &
                                 all_contact, stat)
        type(mesh_t), intent(in) :: m
        real(wp), intent(in) :: young, poisson
        integer, intent(in) :: contact_part
        type(dof_map_t), intent(out) :: all_dofs
        type(csr_matrix_t), intent(out) :: k_all
        type(contact_t), intent(out) :: all_contact
        type(status_t), intent(out) :: stat
        call build_dof_map(m, [integer ::], all_dofs, stat)
        if (stat%ok()) call assemble_stiffness(m, all_dofs, young, poisson, k_all, stat)
        if (stat%ok()) call build_contact(m, contact_part, all_dofs, all_contact, stat)
    end subroutine assemble_all_dofs
end module problem
