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
    use eigen_solve, only: eigen_result_t, solve_eigen
    use run_inputs, only: run_inputs_t, translate_input
    use status, only: status_t, STATUS_SUCCESS, STATUS_NOT_MET
    use run_config, only: config_t
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use contact_boundary, only: contact_t, build_contact
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness, contact_flexibility, reduced_blocks_t
    use timer, only: timings_t
    use problem, only: problem_t, build_problem
    use analysis_base, only: analysis_t
    use analysis_registry, only: new_analysis
    use run_report, only: report_run
    use filesystem, only: file_exists
    use testing, only: test_suite_t
    use strings, only: to_string
    use iso_fortran_env, only: output_unit
    use mesh_structured, only: structured_rectangle
    use mesh_singular, only: singular_vertices
    use mesh_geometric, only: geometric_mesh, cell_layers, layer_degrees
    implicit none
    private
    public :: single_triangle, csr_to_dense, file_text, has_warning, five_point_matrix
    public :: uniform, read_text, write_text, rigid_mode, contact_scene, square_scene
    public :: single_element_scene, single_element_mu, single_element_lambda_minus
    public :: run_as_main, json_value, json_real, listed_files, data_rows, index_of_newline
    public :: all_present, adaptive_scene, run_checked, thresholds_within_bars
    public :: problem_of, eigen_of, check_limit_not_met, is_permutation, square_hp_level

    !> The reference scene's continuum values (tests/data/truths.csv, scenes 'ref' and
    !> 'ref-threshold': graded P4 meshes, uncertainties 4.6e-12 and 5.7e-10).
    real(wp), parameter, public :: REF_MU = 0.75284361680855649_wp
    real(wp), parameter, public :: REF_LAMBDA_PLUS = 1.9447114426738574_wp
    real(wp), parameter, public :: REF_LAMBDA_MINUS = -1.9447114426978778_wp

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

    !> The reference scene on 2 x 2 squares of P1 triangles, analysis `kind` adapted by
    !> `strategy` to `tolerance` in at most `max_levels` levels (0: no limit), lambda = 5;
    !> outputs in `directory`, no pictures.
    subroutine adaptive_scene(kind, strategy, tolerance, max_levels, directory, config)
        character(len=*), intent(in) :: kind, strategy, directory
        real(wp), intent(in) :: tolerance
        integer, intent(in) :: max_levels
        type(config_t), intent(out) :: config
        call square_scene(2, 'p1', 'right', config)
        config%analysis%kind = kind
        config%adapt%strategy = strategy
        config%adapt%tolerance = tolerance
        config%adapt%max_levels = max_levels
        config%output%directory = directory
        config%output%plot = .false.
        config%output%progress = .false.
    end subroutine adaptive_scene

    !> The single element of docs/model.md section 8 as an input would give it: the triangle
    !> of single_triangle with l = 2, [B,C] fixed, [C,A] a Neumann side, E = 1, nu = 0.3,
    !> lambda = -5, the dense solver; outputs in `directory`, no pictures.
    subroutine single_element_scene(directory, config, m)
        character(len=*), intent(in) :: directory
        type(config_t), intent(out) :: config
        type(mesh_t), intent(out) :: m
        config%input_file = 'single_element'
        config%mesh%dirichlet = 'fixed'
        config%mesh%neumann = 'side'
        config%mesh%contact = 'contact'
        config%analysis%lambda = -5.0_wp
        config%eigen%solver = 'dense'
        config%output%directory = directory
        config%output%plot = .false.
        config%sweep%plot = .false.
        config%output%progress = .false.
        call single_triangle(2.0_wp, m)
    end subroutine single_element_scene

    !> The single element's one eigenvalue (docs/model.md section 8):
    !> mu = -6 G (L + 2G) / ((L (lambda + 1) + G (lambda + 3)) l), E = 1.
    pure real(wp) function single_element_mu(lambda, poisson, l)
        real(wp), intent(in) :: lambda, poisson, l
        real(wp) :: lame_l, shear_g
        lame_l = poisson/((1.0_wp + poisson)*(1.0_wp - 2.0_wp*poisson))
        shear_g = 0.5_wp/(1.0_wp + poisson)
        single_element_mu = -6.0_wp*shear_g*(lame_l + 2.0_wp*shear_g)/ &
            ((lame_l*(lambda + 1.0_wp) + shear_g*(lambda + 3.0_wp))*l)
    end function single_element_mu

    !> Its one threshold lambda- = -(L + 3G) / (L + G) (there is no lambda+).
    pure real(wp) function single_element_lambda_minus(poisson)
        real(wp), intent(in) :: poisson
        real(wp) :: lame_l, shear_g
        lame_l = poisson/((1.0_wp + poisson)*(1.0_wp - 2.0_wp*poisson))
        shear_g = 0.5_wp/(1.0_wp + poisson)
        single_element_lambda_minus = -(lame_l + 3.0_wp*shear_g)/(lame_l + shear_g)
    end function single_element_lambda_minus

    !> build_problem on the scene of `config`; `with_all_dofs`: in the input's units on all
    !> dofs, as 'branch' and 'solve' need.
    subroutine problem_of(config, prob, stat, with_all_dofs, given_mesh)
        type(config_t), intent(in) :: config
        type(problem_t), intent(out) :: prob
        type(status_t), intent(out) :: stat
        logical, intent(in), optional :: with_all_dofs
        type(mesh_t), intent(in), optional :: given_mesh
        type(run_inputs_t) :: inputs
        logical :: all_dofs
        call translate_input(config, inputs)
        all_dofs = .false.
        if (present(with_all_dofs)) all_dofs = with_all_dofs
        if (all_dofs) then
            call build_problem(inputs%scene, prob, stat, inputs%analysis_name, given_mesh)
        else
            call build_problem(inputs%scene, prob, stat, given_mesh=given_mesh)
        end if
    end subroutine problem_of

    !> solve_eigen at `lambda` on `prob`, the problem of `config`, with its &eigen options.
    subroutine eigen_of(config, prob, lambda, res, timings, stat)
        type(config_t), intent(in) :: config
        type(problem_t), intent(in) :: prob
        real(wp), intent(in) :: lambda
        type(eigen_result_t), intent(out) :: res
        type(timings_t), intent(inout) :: timings
        type(status_t), intent(out) :: stat
        type(run_inputs_t) :: inputs
        call translate_input(config, inputs)
        call solve_eigen(inputs%scene, prob, lambda, inputs%eigen, res, timings, stat)
    end subroutine eigen_of

    !> What the nceig program does after reading its input, in process: the analysis of
    !> &analysis kind and &adapt from the registry, the problem (on `given_mesh` when
    !> present), the run into &output directory. `summary`: the text of the
    !> summary.json written ('' when none); `report`: the summary the program prints.
    subroutine run_as_main(config, analysis, stat, summary, given_mesh, report)
        type(config_t), intent(in) :: config
        class(analysis_t), allocatable, intent(out) :: analysis
        type(status_t), intent(out) :: stat
        character(len=:), allocatable, intent(out) :: summary
        type(mesh_t), intent(in), optional :: given_mesh
        character(len=:), allocatable, intent(out), optional :: report
        type(problem_t) :: prob
        type(timings_t) :: timings
        type(run_inputs_t) :: inputs
        character(len=:), allocatable :: text
        summary = ''
        call translate_input(config, inputs)
        call new_analysis(inputs, analysis)
        call problem_of(config, prob, stat, analysis%in_input_units(), given_mesh)
        if (.not. stat%ok()) return
        call analysis%solve(inputs, prob, timings, stat)
        if (.not. stat%ok()) return
        call report_run(analysis, inputs, prob, 0.0_wp, timings, text, stat)
        if (.not. stat%ok()) return
        summary = file_text(trim(config%output%directory)//'/summary.json', new_line('a'))
        if (present(report)) report = text
    end subroutine run_as_main

    !> run_as_main with the checks every run gets, named `label`: it ran, its verdict has
    !> the code `verdict` (default: success), every file its summary.json lists is in place.
    !> `ran`: whether there is a set to look at.
    subroutine run_checked(t, label, config, analysis, summary, ran, given_mesh, report, verdict)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: label
        type(config_t), intent(in) :: config
        class(analysis_t), allocatable, intent(out) :: analysis
        character(len=:), allocatable, intent(out) :: summary
        logical, intent(out) :: ran
        type(mesh_t), intent(in), optional :: given_mesh
        character(len=:), allocatable, intent(out), optional :: report
        integer, intent(in), optional :: verdict
        type(status_t) :: stat
        ! gfortran 12 loses the length of a deferred-length optional passed on: a local
        character(len=:), allocatable :: text
        integer :: expected
        expected = STATUS_SUCCESS
        if (present(verdict)) expected = verdict
        call run_as_main(config, analysis, stat, summary, given_mesh, text)
        if (present(report) .and. allocated(text)) report = text
        ran = stat%ok()
        if (.not. ran) write (output_unit, '(a)') '      '//stat%message
        call t%check(label//': runs', ran)
        if (.not. ran) return
        call t%check(label//': verdict code '//to_string(expected), &
                     analysis%verdict%code == expected)
        call t%check(label//': every file summary.json lists is in place', &
                     all_present(trim(config%output%directory), listed_files(summary)))
    end subroutine run_checked

    !> The reference scene from 2 x 2 P1 adapted by `kind` ('eigen', 'threshold') on
    !> `strategy` levels to 1e-8 within max_levels = `levels`, into `folder`: the verdict
    !> STATUS_NOT_MET, the set complete (run_checked) with `rows` rows of adapt.csv.
    subroutine check_limit_not_met(t, kind, strategy, levels, folder, rows)
        type(test_suite_t), intent(inout) :: t
        character(len=*), intent(in) :: kind, strategy, folder
        integer, intent(in) :: levels, rows
        type(config_t) :: config
        class(analysis_t), allocatable :: analysis
        character(len=:), allocatable :: summary
        logical :: ran
        call adaptive_scene(kind, strategy, 1.0e-8_wp, levels, folder, config)
        call run_checked(t, strategy//' not met', config, analysis, summary, ran, &
                         verdict=STATUS_NOT_MET)
        if (ran) call t%check(strategy//' not met: adapt.csv has '//to_string(rows)// &
                              ' rows', data_rows(folder//'/adapt.csv') == rows)
    end subroutine check_limit_not_met

    !> Whether the summary's lambda+ and lambda- hold `plus` and `minus` within their
    !> relative error bars.
    pure logical function thresholds_within_bars(summary, plus, minus)
        character(len=*), intent(in) :: summary
        real(wp), intent(in) :: plus, minus
        real(wp) :: found_plus, found_minus
        found_plus = json_real(summary, 'lambda_critical_plus')
        found_minus = json_real(summary, 'lambda_critical_minus')
        thresholds_within_bars = &
            abs(found_plus - plus) <= json_real(summary, 'lambda_critical_plus_error_bar')* &
            abs(found_plus) .and. &
            abs(found_minus - minus) <= json_real(summary, 'lambda_critical_minus_error_bar')* &
            abs(found_minus)
    end function thresholds_within_bars

    !> The text of member `key` of a JSON object as json_writer writes it (one member per
    !> line, two spaces in); '' if absent.
    pure function json_value(text, key) result(value)
        character(len=*), intent(in) :: text, key
        character(len=:), allocatable :: value
        integer :: start, newline
        value = ''
        start = index(text, new_line('a')//'  "'//key//'": ')
        if (start == 0) return
        start = start + len(key) + 7
        newline = index_of_newline(text, start)
        value = text(start:newline - 1)
        if (value(len(value):) == ',') value = value(:len(value) - 1)
    end function json_value

    !> The number of member `key` (-huge when absent or not a number).
    pure real(wp) function json_real(text, key)
        character(len=*), intent(in) :: text, key
        character(len=:), allocatable :: value
        integer :: ios
        json_real = -huge(1.0_wp)
        value = json_value(text, key)
        read (value, *, iostat=ios) json_real
    end function json_real

    !> The names of the 'files' array of a summary.json's text.
    function listed_files(text) result(names)
        character(len=*), intent(in) :: text
        character(len=255), allocatable :: names(:)
        character(len=:), allocatable :: list
        integer :: start, finish
        allocate (names(0))
        list = json_value(text, 'files')
        start = index(list, '"')
        do while (start > 0)
            finish = start + index(list(start + 1:), '"')
            names = [character(len=255) :: names, list(start + 1:finish - 1)]
            list = list(finish + 1:)
            start = index(list, '"')
        end do
    end function listed_files

    !> Whether every one of `names` is a file in `directory` with at least one byte.
    logical function all_present(directory, names)
        character(len=*), intent(in) :: directory
        character(len=*), intent(in) :: names(:)
        integer :: i, bytes
        all_present = size(names) > 0
        do i = 1, size(names)
            bytes = -1
            if (file_exists(directory//'/'//trim(names(i)))) &
                inquire (file=directory//'/'//trim(names(i)), size=bytes)
            if (bytes < 1) all_present = .false.
        end do
    end function all_present

    !> Rows of a CSV file below its header (-1 when it cannot be read).
    integer function data_rows(path)
        character(len=*), intent(in) :: path
        character(len=1) :: first
        integer :: unit, ios
        data_rows = -1
        open (newunit=unit, file=path, status='old', action='read', iostat=ios)
        if (ios /= 0) return
        do
            read (unit, '(a)', iostat=ios) first
            if (ios /= 0) exit
            data_rows = data_rows + 1
        end do
        close (unit)
    end function data_rows

    !> The position of the first line feed at or after `start` (len(text) + 1 if none).
    pure integer function index_of_newline(text, start)
        character(len=*), intent(in) :: text
        integer, intent(in) :: start
        index_of_newline = index(text(start:), new_line('a'))
        if (index_of_newline == 0) then
            index_of_newline = len(text) + 1
        else
            index_of_newline = start + index_of_newline - 1
        end if
    end function index_of_newline

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

    !> The unit square of 2 x 2 squares (P1, 'right') graded geometrically in `layers` layers
    !> of ratio 0.15 toward its singular vertices, with degrees 1 + layer up to `p_max`: the
    !> reference scene's hp level of that many layers (&adapt sigma = 0.15); `m` the square
    !> itself, for its part indices.
    subroutine square_hp_level(layers, p_max, m, graded, degree, stat)
        integer, intent(in) :: layers, p_max
        type(mesh_t), intent(out) :: m, graded
        integer, allocatable, intent(out) :: degree(:)
        type(status_t), intent(out) :: stat
        real(wp), allocatable :: points(:, :)
        real(wp) :: h_min
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        if (.not. stat%ok()) return
        allocate (points(2, 0))   ! (gfortran 12 warns of an unallocated one at -O3)
        points = m%coords(:, singular_vertices(m))
        call geometric_mesh(m, points, 0.15_wp, layers, graded, h_min, stat)
        if (.not. stat%ok()) return
        degree = layer_degrees(cell_layers(graded, points, 0.15_wp, h_min), 1, 1.0_wp, p_max)
    end subroutine square_hp_level
    !> Whether p holds each of 1..n exactly once.
    pure logical function is_permutation(p, n)
        integer, intent(in) :: p(:), n
        logical :: seen(n)
        is_permutation = size(p) == n .and. all(p >= 1 .and. p <= n)
        if (.not. is_permutation) return
        seen = .false.
        seen(p) = .true.
        is_permutation = all(seen)
    end function is_permutation
end module fixtures
