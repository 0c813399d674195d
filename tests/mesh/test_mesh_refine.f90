! SPDX-License-Identifier: MIT
!> Newest-vertex bisection: building from P1 and P2 meshes (longest edge as refinement edge),
!> uniform refinement (2^k cells, area and part lengths conserved, conforming, straight sides,
!> bounded angles), the child -> parent map (children tile their parent), graded refinement
!> of a corner (linear growth), P1/P2 output (unique exact mid nodes), assembly and the contact
!> segment on refined meshes, and the error paths.
program test_mesh_refine
    use kinds, only: wp, PI
    use status, only: status_t, STATUS_BAD_INPUT, STATUS_MESH
    use mesh, only: mesh_t
    use element_types, only: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_P3, ELEMENT_P4, &
                             element_name
    use mesh_check, only: check_mesh
    use mesh_structured, only: structured_rectangle, PART_BOTTOM, PART_RIGHT, PART_TOP, &
                               PART_LEFT
    use mesh_refine, only: refinable_mesh_t, build_refinable_mesh
    use dof_map, only: dof_map_t, build_dof_map
    use assembly, only: assemble_stiffness
    use csr_matrix, only: csr_matrix_t
    use contact_boundary, only: contact_t, build_contact
    use sorting, only: sort_index
    use strings, only: to_string
    use testing, only: test_suite_t
    use fixtures, only: single_triangle, rigid_mode
    use timer, only: timings_t
    use sparse_cholesky, only: cholesky_t
    use contact_reduction, only: factor_stiffness, contact_flexibility
    implicit none

    real(wp), parameter :: WIDTH = 2.0_wp, HEIGHT = 1.5_wp
    ! Sums of O(n) areas or lengths, each with a rounding error of a few ulps.
    real(wp), parameter :: SUM_TOL = 1.0e-13_wp
    ! Linear field u = (a + b x + c y, d + e x + f y) for the patch test.
    real(wp), parameter :: LIN(6) = [0.3_wp, 0.7_wp, -0.4_wp, -0.2_wp, 0.25_wp, 0.5_wp]
    type(test_suite_t) :: t

    t%name = 'test_mesh_refine'
    call check_build()
    call check_uniform('right')
    call check_uniform('left')
    call check_exact_area()
    call check_angles()
    call check_parent_map()
    call check_graded()
    call check_to_mesh()
    call check_assembly(ELEMENT_P1)
    call check_assembly(ELEMENT_P2)
    call check_assembly(ELEMENT_P3)
    call check_assembly(ELEMENT_P4)
    call check_contact_segment()
    call check_contact_last_factor()
    call check_errors()
    call t%report()

contains

    !> From P1 and P2 meshes: the corners only, and the longest side as refinement edge.
    subroutine check_build()
        type(mesh_t) :: m
        type(refinable_mesh_t) :: r, r2
        type(status_t) :: stat
        integer :: c
        logical :: longest

        call structured_rectangle(WIDTH, HEIGHT, 3, 2, ELEMENT_P1, 'right', m, stat)
        call build_refinable_mesh(m, r, stat)
        call t%check('build from P1: ok, the same vertices and cells', stat%ok() .and. &
                     r%n_vertices() == m%n_nodes() .and. r%n_cells() == m%n_cells())
        longest = .true.
        do c = 1, r%n_cells()
            associate (x => r%coords(:, r%cells(:, c)))
                longest = longest .and. norm2(x(:, 3) - x(:, 2)) >= norm2(x(:, 1) - x(:, 3)) &
                          .and. norm2(x(:, 3) - x(:, 2)) >= norm2(x(:, 2) - x(:, 1))
            end associate
        end do
        call t%check('build: the refinement edge (vertex 2 to 3) is the longest side', longest)
        call t%check('build: cells anticlockwise', minval(signed_areas(r)) > 0.0_wp)
        call t%check('build: parent map is the identity', &
                     all(r%parent == [(c, c=1, r%n_cells())]))
        call t%check('build: conforming, boundary = unshared sides', conforming(r))

        call structured_rectangle(WIDTH, HEIGHT, 3, 2, ELEMENT_P2, 'right', m, stat)
        call build_refinable_mesh(m, r2, stat)
        call t%check('build from P2: ok, (nx+1)(ny+1) vertices, the P1 mesh''s coordinates', &
                     stat%ok() .and. r2%n_vertices() == 4*3 .and. r2%n_cells() == 12)
        if (stat%ok()) then
            call t%check('build from P2: the same vertex mesh as from P1', &
                         maxval(abs(r2%coords - r%coords)) <= 0.0_wp .and. &
                         all(r2%cells == r%cells) .and. &
                         all(r2%edges == r%edges) .and. all(r2%edge_part == r%edge_part))
        end if
    end subroutine check_build

    !> Refining all cells k times gives 2^k times the cells, conserves the area and each
    !> part's length, keeps the mesh conforming and the sides straight.
    subroutine check_uniform(diagonal)
        character(len=*), intent(in) :: diagonal
        type(mesh_t) :: m
        type(refinable_mesh_t) :: r
        type(status_t) :: stat
        integer :: level, c, n0
        logical :: counts_ok, conforming_ok, area_ok, length_ok, straight_ok
        real(wp) :: lengths(4), expected(4)
        character(len=:), allocatable :: label

        label = ' ('//diagonal//' diagonal)'
        call structured_rectangle(WIDTH, HEIGHT, 3, 2, ELEMENT_P1, diagonal, m, stat)
        call build_refinable_mesh(m, r, stat)
        n0 = r%n_cells()
        expected = [WIDTH, HEIGHT, WIDTH, HEIGHT]
        counts_ok = .true.
        conforming_ok = .true.
        area_ok = .true.
        length_ok = .true.
        straight_ok = .true.
        do level = 1, 6
            call r%refine([(c, c=1, r%n_cells())], stat)
            counts_ok = counts_ok .and. stat%ok() .and. r%n_cells() == n0*2**level
            if (level == 2) call t%check('uniform: refining all cells twice gives 4x cells' &
                                         //label, r%n_cells() == 4*n0)
            conforming_ok = conforming_ok .and. conforming(r)
            area_ok = area_ok .and. abs(sum(signed_areas(r))/2.0_wp - WIDTH*HEIGHT) <= &
                      SUM_TOL*WIDTH*HEIGHT
            lengths = part_lengths(r)
            length_ok = length_ok .and. all(abs(lengths - expected) <= SUM_TOL*expected)
            straight_ok = straight_ok .and. on_sides(r)
        end do
        call t%check('uniform: n_cells = n0 2^k for k = 1..6'//label, counts_ok)
        call t%check('uniform: conforming at every level'//label, conforming_ok)
        call t%check('uniform: total area conserved'//label, area_ok)
        call t%check('uniform: length of each boundary part conserved'//label, length_ok)
        call t%check('uniform: boundary vertices exactly on their sides'//label, straight_ok)
        call t%check('uniform: anticlockwise cells'//label, minval(signed_areas(r)) > 0.0_wp)
    end subroutine check_uniform

    !> On a dyadic mesh every midpoint and area is exact in binary64: no rounding at all.
    subroutine check_exact_area()
        type(mesh_t) :: m
        type(refinable_mesh_t) :: r
        type(status_t) :: stat
        integer :: level, c
        logical :: exact, conforming_ok
        call structured_rectangle(1.0_wp, 1.0_wp, 4, 4, ELEMENT_P1, 'right', m, stat)
        call build_refinable_mesh(m, r, stat)
        exact = .true.
        conforming_ok = .true.
        do level = 1, 8
            ! Alternate uniform and local steps, so that 2-, 3- and 4-child splits all occur.
            if (modulo(level, 2) == 1) then
                call r%refine([(c, c=1, r%n_cells())], stat)
            else
                call r%refine([(c, c=1, r%n_cells(), 7)], stat)
            end if
            exact = exact .and. abs(sum(signed_areas(r)) - 2.0_wp) <= 0.0_wp
            conforming_ok = conforming_ok .and. conforming(r)
        end do
        call t%check('dyadic unit square: area exactly 1 after 8 mixed refinements', exact)
        call t%check('mixed uniform and local refinements: conforming at every step', &
                     conforming_ok)
    end subroutine check_exact_area

    !> NVB gives each initial triangle's descendants at most 4 similarity classes, so angles
    !> are bounded: uniform steps 3..6 must not lower the minimum angle reached at level 2,
    !> and the finest level may hold at most 4 shapes. A scalene triangle, with no symmetry
    !> to hide a wrong bisection (a wrong newest vertex quickly creates new shapes).
    subroutine check_angles()
        type(mesh_t) :: m
        type(refinable_mesh_t) :: r
        type(status_t) :: stat
        real(wp) :: level_min(0:6)
        integer :: level, c, n_classes
        call single_triangle(1.0_wp, m)
        m%coords(:, 3) = [0.3_wp, 0.8_wp]
        call build_refinable_mesh(m, r, stat)
        level_min(0) = min_angle(r)
        do level = 1, 6
            call r%refine([(c, c=1, r%n_cells())], stat)
            level_min(level) = min_angle(r)
        end do
        call t%check('angles: the minimum angle of levels 3..6 is that of level 2', &
                     all(level_min(3:) >= level_min(2)*(1.0_wp - 1.0e-12_wp)))
        n_classes = similarity_classes(r)
        call t%check('angles: at most 4 similarity classes after 6 uniform steps (found '// &
                     to_string(n_classes)//')', n_classes <= 4)
    end subroutine check_angles

    !> After a partial refinement each new cell lies inside its parent, and the children of
    !> a parent (1 if left whole, else 2 to 4) tile it: their areas sum to its area.
    subroutine check_parent_map()
        type(mesh_t) :: m
        type(refinable_mesh_t) :: r
        type(status_t) :: stat
        real(wp), allocatable :: before(:, :), area_before(:), area_sum(:), area_after(:)
        integer, allocatable :: before_cells(:, :), n_children(:), marked(:)
        integer :: c, p, a
        logical :: inside, kept

        call structured_rectangle(WIDTH, HEIGHT, 3, 2, ELEMENT_P1, 'left', m, stat)
        call build_refinable_mesh(m, r, stat)
        call r%refine([1, 5], stat)
        call r%refine([2, 3, 11], stat)   ! refinement edges now differ from the longest
        allocate (before, source=r%coords)
        allocate (before_cells, source=r%cells)
        area_before = signed_areas(r)
        marked = [(c, c=1, r%n_cells(), 3)]
        call r%refine(marked, stat)
        call t%check('parent map: one parent per cell, in range', stat%ok() .and. &
                     size(r%parent) == r%n_cells() .and. minval(r%parent) >= 1 .and. &
                     maxval(r%parent) <= size(before_cells, 2))
        if (.not. stat%ok()) return
        allocate (n_children(size(before_cells, 2)), source=0)
        allocate (area_sum(size(before_cells, 2)), source=0.0_wp)
        area_after = signed_areas(r)
        inside = .true.
        do c = 1, r%n_cells()
            p = r%parent(c)
            n_children(p) = n_children(p) + 1
            area_sum(p) = area_sum(p) + area_after(c)
            do a = 1, 3
                inside = inside .and. in_triangle(r%coords(:, r%cells(a, c)), &
                                                  before(:, before_cells(:, p)))
            end do
        end do
        call t%check('parent map: every child lies in its parent', inside)
        call t%check('parent map: children areas sum to the parent area', &
                     all(abs(area_sum - area_before) <= 1.0e-14_wp*area_before))
        call t%check('parent map: 1 to 4 children, marked cells at least 2', &
                     all(n_children >= 1 .and. n_children <= 4) .and. &
                     all(n_children(marked) >= 2))
        kept = .true.
        do c = 1, r%n_cells()
            if (n_children(r%parent(c)) == 1) &
                kept = kept .and. all(r%cells(:, c) == before_cells(:, r%parent(c)))
        end do
        call t%check('parent map: cells left whole keep their vertices', kept)
    end subroutine check_parent_map

    !> Refining the cell at a corner 15 times grades the mesh towards it: the closure touches
    !> a bounded neighbourhood, so the cell count grows by a bounded amount per step (linear),
    !> not by a factor, and the cell at the corner halves at least once per step.
    subroutine check_graded()
        type(mesh_t) :: m
        type(refinable_mesh_t) :: r
        type(status_t) :: stat
        integer :: step, corner_cell, n_cells(0:15)
        integer :: increments(15)
        real(wp) :: corner_area, first_area
        logical :: conforming_ok

        call structured_rectangle(1.0_wp, 1.0_wp, 4, 4, ELEMENT_P1, 'right', m, stat)
        call build_refinable_mesh(m, r, stat)
        n_cells(0) = r%n_cells()
        first_area = 1.0_wp/32.0_wp
        conforming_ok = .true.
        do step = 1, 15
            call r%refine([smallest_at_origin(r)], stat)
            n_cells(step) = r%n_cells()
            conforming_ok = conforming_ok .and. conforming(r)
        end do
        corner_cell = smallest_at_origin(r)
        corner_area = twice_area(r%coords(:, r%cells(:, corner_cell)))/2.0_wp
        increments = n_cells(1:) - n_cells(:14)
        call t%check('graded: conforming after each of 15 corner refinements', conforming_ok)
        call t%check('graded: the corner cell has area <= 2^-15 of the first (got 2^'// &
                     to_string(nint(log(corner_area/first_area)/log(2.0_wp)))//')', &
                     corner_area <= first_area*2.0_wp**(-15))
        call t%check('graded: growth per step bounded: steps 8-15 add no more than steps '// &
                     '1-7 (increments '//to_string(minval(increments))//' to '// &
                     to_string(maxval(increments))//')', &
                     maxval(increments(8:)) <= maxval(increments(:7)))
        call t%check('graded: cell count linear in the steps ('//to_string(n_cells(15))// &
                     ' cells; uniform would give 2^15 x)', &
                     n_cells(15) <= n_cells(0) + 15*maxval(increments(:7)))
    end subroutine check_graded

    !> P1 output is the vertex mesh; P2 output has one mid node per edge at its exact middle.
    subroutine check_to_mesh()
        type(mesh_t) :: m, p1, p2
        type(refinable_mesh_t) :: r
        type(status_t) :: stat
        integer :: c, k, e, n_edges
        logical :: exact_middle, boundary_middle
        integer, parameter :: NEXT(3) = [2, 3, 1]

        call structured_rectangle(WIDTH, HEIGHT, 3, 2, ELEMENT_P2, 'right', m, stat)
        call build_refinable_mesh(m, r, stat)
        call r%refine([1, 4, 9], stat)
        call r%refine([(c, c=1, r%n_cells(), 2)], stat)
        call r%to_mesh(ELEMENT_P1, p1, stat)
        call t%check('to_mesh P1: the vertex mesh and its parts', stat%ok() .and. &
                     p1%element == ELEMENT_P1 .and. &
                     maxval(abs(p1%coords - r%coords)) <= 0.0_wp .and. &
                     all(p1%cells == r%cells) .and. all(p1%edges == r%edges) .and. &
                     all(p1%edge_part == r%edge_part) .and. &
                     all(p1%part_names == m%part_names))
        call r%to_mesh(ELEMENT_P2, p2, stat)
        call t%check('to_mesh P2: ok', stat%ok() .and. p2%element == ELEMENT_P2)
        if (.not. stat%ok()) return
        ! Euler: each interior edge is a side of two cells, each boundary edge of one.
        n_edges = (3*r%n_cells() + size(r%edges, 2))/2
        call t%check('to_mesh P2: one mid node per edge (n_vertices + n_edges nodes)', &
                     p2%n_nodes() == r%n_vertices() + n_edges)
        exact_middle = .true.
        do c = 1, p2%n_cells()
            do k = 1, 3
                exact_middle = exact_middle .and. maxval(abs(p2%coords(:, p2%cells(3 + k, c)) - &
                    0.5_wp*(p2%coords(:, p2%cells(k, c)) + &
                            p2%coords(:, p2%cells(NEXT(k), c))))) <= 0.0_wp
            end do
        end do
        call t%check('to_mesh P2: mid nodes exactly at side midpoints, Gmsh order', &
                     exact_middle)
        boundary_middle = .true.
        do e = 1, size(p2%edges, 2)
            boundary_middle = boundary_middle .and. maxval(abs(p2%coords(:, p2%edges(3, e)) - &
                0.5_wp*(p2%coords(:, p2%edges(1, e)) + p2%coords(:, p2%edges(2, e))))) <= 0.0_wp
        end do
        call t%check('to_mesh P2: boundary edges carry their exact mid node', boundary_middle)
        call t%check('to_mesh P2: every node used by a cell', all(node_used(p2)))
    end subroutine check_to_mesh

    !> The refined mesh goes through the assembly: K kills the rigid modes and reproduces a
    !> linear field (K u = 0 at interior nodes), on a graded non-uniform mesh.
    subroutine check_assembly(element)
        integer, intent(in) :: element
        type(mesh_t) :: m, fine
        type(refinable_mesh_t) :: r
        type(status_t) :: stat
        type(dof_map_t) :: dofs
        type(csr_matrix_t) :: k
        real(wp), allocatable :: u(:), ku(:)
        logical, allocatable :: on_boundary(:), interior_dof(:)
        integer :: step, i, node
        real(wp) :: norm_k, rigid
        character(len=:), allocatable :: label

        label = ' ('//element_name(element)//')'
        call structured_rectangle(WIDTH, HEIGHT, 3, 2, ELEMENT_P1, 'right', m, stat)
        call build_refinable_mesh(m, r, stat)
        do step = 1, 5
            call r%refine([smallest_at_origin(r)], stat)
        end do
        call r%to_mesh(element, fine, stat)
        call t%check('to_mesh succeeds'//label, stat%ok())
        ! conforming cells (shared edges share their nodes), boundary edges with their cell's
        ! edge nodes
        call check_mesh(fine, [1, 2], [3], [4], stat)
        call t%check('refined mesh passes the mesh checks'//label, stat%ok())
        call build_dof_map(fine, [integer ::], dofs, stat)
        call assemble_stiffness(fine, dofs, 2.5_wp, 0.3_wp, k, stat)
        call t%check('assembly on the refined mesh succeeds'//label, stat%ok())
        if (.not. stat%ok()) return
        norm_k = k%norm_inf()
        allocate (ku(dofs%n_free))
        rigid = 0.0_wp
        do i = 1, 3
            u = rigid_mode(fine, i)
            call k%matvec(u, ku)
            rigid = max(rigid, maxval(abs(ku))/maxval(abs(u)))
        end do
        call t%check('refined mesh: K kills the three rigid modes'//label, &
                     rigid <= 1.0e-12_wp*norm_k)
        allocate (on_boundary(fine%n_nodes()), source=.false.)
        do i = 1, size(fine%edges, 2)
            on_boundary(fine%edges(:, i)) = .true.
        end do
        allocate (interior_dof(dofs%n_free))
        do node = 1, fine%n_nodes()
            interior_dof(dofs%free_dof(:, node)) = .not. on_boundary(node)
        end do
        u(1::2) = LIN(1) + LIN(2)*fine%coords(1, :) + LIN(3)*fine%coords(2, :)
        u(2::2) = LIN(4) + LIN(5)*fine%coords(1, :) + LIN(6)*fine%coords(2, :)
        call k%matvec(u, ku)
        call t%check('refined mesh: linear patch test, K u = 0 at interior nodes'//label, &
                     maxval(abs(ku), mask=interior_dof) <= 1.0e-12_wp*norm_k*maxval(abs(u)))
    end subroutine check_assembly

    !> The contact segment (a straight part) stays one straight segment of the same length.
    subroutine check_contact_segment()
        type(mesh_t) :: m, fine
        type(refinable_mesh_t) :: r
        type(status_t) :: stat
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        integer :: step, n_bottom
        call structured_rectangle(WIDTH, HEIGHT, 3, 2, ELEMENT_P1, 'right', m, stat)
        call build_refinable_mesh(m, r, stat)
        do step = 1, 4
            call r%refine([smallest_at_origin(r)], stat)
        end do
        call r%to_mesh(ELEMENT_P2, fine, stat)
        n_bottom = count(fine%edge_part == PART_BOTTOM)
        call build_dof_map(fine, [PART_TOP], dofs, stat)
        call build_contact(fine, PART_BOTTOM, dofs, contact, stat)
        call t%check('contact: the refined bottom is one straight segment', stat%ok())
        call t%check_close('contact: its length is the width', contact%length, WIDTH, 1.0e-15_wp)
        call t%check('contact: graded towards the corner (more edges than the 3 at start)', &
                     n_bottom > 3 .and. contact%p() == 2*n_bottom + 1)
    end subroutine check_contact_segment

    subroutine check_errors()
        type(mesh_t) :: m, out
        type(refinable_mesh_t) :: r, copy
        type(status_t) :: stat
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_Q1, 'right', m, stat)
        call build_refinable_mesh(m, r, stat)
        call t%check('build from quadrilaterals: STATUS_BAD_INPUT', &
                     stat%code == STATUS_BAD_INPUT)
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        m%cells(2:3, 3) = m%cells([3, 2], 3)
        call build_refinable_mesh(m, r, stat)
        call t%check('build with a clockwise cell: STATUS_MESH naming cell 3', &
                     stat%code == STATUS_MESH .and. index(stat%message, 'cell 3 ') > 0)
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        m%edges(2, 1) = m%edges(2, 2)
        call build_refinable_mesh(m, r, stat)
        call t%check('build with a boundary edge off the cell sides: STATUS_MESH', &
                     stat%code == STATUS_MESH)
        call structured_rectangle(1.0_wp, 1.0_wp, 2, 2, ELEMENT_P1, 'right', m, stat)
        call build_refinable_mesh(m, r, stat)
        copy = r
        call r%refine([1, 9], stat)
        call t%check('refine cell 9 of 8: STATUS_BAD_INPUT, mesh unchanged', &
                     stat%code == STATUS_BAD_INPUT .and. r%n_cells() == copy%n_cells() .and. &
                     all(r%cells == copy%cells))
        call r%refine([integer ::], stat)
        call t%check('refine nothing: ok, mesh unchanged', stat%ok() .and. &
                     all(r%cells == copy%cells) .and. all(r%parent == copy%parent))
        copy%edges(2, 1) = copy%edges(2, 2)
        call copy%refine([1], stat)
        call t%check('refine with a boundary edge off the cell sides: STATUS_BAD_INPUT', &
                     stat%code == STATUS_BAD_INPUT)
        call r%to_mesh(ELEMENT_Q1, out, stat)
        call t%check('to_mesh Q1: STATUS_BAD_INPUT', stat%code == STATUS_BAD_INPUT)
    end subroutine check_errors

    ! ------------------------------------------------------------------------ helpers

    !> Twice the signed area of each cell.
    function signed_areas(r) result(areas)
        type(refinable_mesh_t), intent(in) :: r
        real(wp), allocatable :: areas(:)
        integer :: c
        allocate (areas(r%n_cells()))
        do c = 1, r%n_cells()
            areas(c) = twice_area(r%coords(:, r%cells(:, c)))
        end do
    end function signed_areas

    pure real(wp) function twice_area(x)
        real(wp), intent(in) :: x(2, 3)
        twice_area = (x(1, 2) - x(1, 1))*(x(2, 3) - x(2, 1)) - &
                     (x(2, 2) - x(2, 1))*(x(1, 3) - x(1, 1))
    end function twice_area

    !> Conforming: every side is shared by at most two cells, in opposite directions (the
    !> cells agree on orientation), and the sides of one cell are exactly the boundary edges,
    !> with the body on their left. Checked by sorting, independently of the module's table.
    logical function conforming(r)
        type(refinable_mesh_t), intent(in) :: r
        integer, allocatable :: from(:), to(:), order(:), boundary(:, :)
        real(wp), allocatable :: keys(:)
        integer :: c, k, i, n, n_unshared
        real(wp) :: scale
        n = 3*r%n_cells()
        allocate (from(n), to(n), keys(n))
        scale = real(r%n_vertices() + 1, wp)
        do c = 1, r%n_cells()
            do k = 1, 3
                from(3*(c - 1) + k) = r%cells(k, c)
                to(3*(c - 1) + k) = r%cells(modulo(k, 3) + 1, c)
            end do
        end do
        keys = real(min(from, to), wp)*scale + real(max(from, to), wp)
        order = sort_index(keys)
        conforming = .true.
        allocate (boundary(2, n))
        n_unshared = 0
        i = 1
        do while (i <= n)
            if (i < n) then
                if (abs(keys(order(i + 1)) - keys(order(i))) <= 0.0_wp) then
                    conforming = conforming .and. from(order(i)) == to(order(i + 1))
                    if (i + 2 <= n) conforming = conforming .and. &
                        abs(keys(order(i + 2)) - keys(order(i))) > 0.0_wp
                    i = i + 2
                    cycle
                end if
            end if
            n_unshared = n_unshared + 1
            boundary(:, n_unshared) = [from(order(i)), to(order(i))]
            i = i + 1
        end do
        if (.not. conforming .or. n_unshared /= size(r%edges, 2)) then
            conforming = .false.
            return
        end if
        ! Unshared sides and boundary edges, both sorted by their directed key, must agree.
        order = sort_index(real(boundary(1, :n_unshared), wp)*scale + boundary(2, :n_unshared))
        boundary = boundary(:, order)
        order = sort_index(real(r%edges(1, :), wp)*scale + r%edges(2, :))
        conforming = all(boundary(:, :n_unshared) == r%edges(:, order))
    end function conforming

    !> Length of each boundary part.
    function part_lengths(r) result(lengths)
        type(refinable_mesh_t), intent(in) :: r
        real(wp) :: lengths(size(r%part_names))
        integer :: e
        lengths = 0.0_wp
        do e = 1, size(r%edges, 2)
            lengths(r%edge_part(e)) = lengths(r%edge_part(e)) + &
                norm2(r%coords(:, r%edges(2, e)) - r%coords(:, r%edges(1, e)))
        end do
    end function part_lengths

    !> Every vertex of a structured rectangle's part lies exactly on that side.
    logical function on_sides(r)
        type(refinable_mesh_t), intent(in) :: r
        integer :: e, a
        real(wp) :: x(2)
        on_sides = .true.
        do e = 1, size(r%edges, 2)
            do a = 1, 2
                x = r%coords(:, r%edges(a, e))
                select case (r%edge_part(e))
                case (PART_BOTTOM); on_sides = on_sides .and. abs(x(2)) <= 0.0_wp
                case (PART_RIGHT); on_sides = on_sides .and. abs(x(1) - WIDTH) <= 0.0_wp
                case (PART_TOP); on_sides = on_sides .and. abs(x(2) - HEIGHT) <= 0.0_wp
                case (PART_LEFT); on_sides = on_sides .and. abs(x(1)) <= 0.0_wp
                end select
            end do
        end do
    end function on_sides

    !> Smallest angle of the mesh, radians.
    real(wp) function min_angle(r)
        type(refinable_mesh_t), intent(in) :: r
        integer :: c
        min_angle = PI
        do c = 1, r%n_cells()
            min_angle = min(min_angle, minval(angles(r%coords(:, r%cells(:, c)))))
        end do
    end function min_angle

    pure function angles(x) result(theta)
        real(wp), intent(in) :: x(2, 3)
        real(wp) :: theta(3), a(2), b(2)
        integer :: k
        do k = 1, 3
            a = x(:, modulo(k, 3) + 1) - x(:, k)
            b = x(:, modulo(k + 1, 3) + 1) - x(:, k)
            theta(k) = acos(dot_product(a, b)/(norm2(a)*norm2(b)))
        end do
    end function angles

    !> Number of distinct sorted angle triples (to 1e-9 rad) among the cells.
    integer function similarity_classes(r)
        type(refinable_mesh_t), intent(in) :: r
        real(wp), allocatable :: classes(:, :)
        real(wp) :: theta(3)
        integer :: c, j
        logical :: known
        allocate (classes(3, 0))
        do c = 1, r%n_cells()
            theta = angles(r%coords(:, r%cells(:, c)))
            theta = [minval(theta), sum(theta) - minval(theta) - maxval(theta), maxval(theta)]
            known = .false.
            do j = 1, size(classes, 2)
                if (all(abs(classes(:, j) - theta) <= 1.0e-9_wp)) known = .true.
            end do
            if (.not. known) classes = reshape([classes, theta], [3, size(classes, 2) + 1])
        end do
        similarity_classes = size(classes, 2)
    end function similarity_classes

    !> Whether point p lies in the triangle x (barycentric coordinates >= -round-off).
    pure logical function in_triangle(p, x)
        real(wp), intent(in) :: p(2), x(2, 3)
        real(wp) :: whole, tol
        whole = twice_area(x)
        tol = 1.0e-14_wp*whole
        in_triangle = twice_area(reshape([p, x(:, 2), x(:, 3)], [2, 3])) >= -tol .and. &
                      twice_area(reshape([x(:, 1), p, x(:, 3)], [2, 3])) >= -tol .and. &
                      twice_area(reshape([x(:, 1), x(:, 2), p], [2, 3])) >= -tol
    end function in_triangle

    !> The smallest cell with a vertex at the origin.
    integer function smallest_at_origin(r)
        type(refinable_mesh_t), intent(in) :: r
        integer :: c
        real(wp) :: best, area
        smallest_at_origin = 0
        best = huge(1.0_wp)
        do c = 1, r%n_cells()
            if (minval(abs(r%coords(1, r%cells(:, c))) + abs(r%coords(2, r%cells(:, c)))) &
                > 0.0_wp) cycle
            area = twice_area(r%coords(:, r%cells(:, c)))
            if (area < best) then
                best = area
                smallest_at_origin = c
            end if
        end do
    end function smallest_at_origin

    function node_used(m) result(used)
        type(mesh_t), intent(in) :: m
        logical, allocatable :: used(:)
        integer :: c
        allocate (used(m%n_nodes()), source=.false.)
        do c = 1, m%n_cells()
            used(m%cells(:, c)) = .true.
        end do
    end function node_used

    !> Bisected meshes factor with the contact dofs last: the contact blocks of K^-1 are read
    !> off the trailing block of the factor, so its ordering must keep them there (on the
    !> single triangle bisected twice, a contact node's free neighbours are all on Gamma_C).
    subroutine check_contact_last_factor()
        type(mesh_t) :: m, fine
        type(refinable_mesh_t) :: r
        type(dof_map_t) :: dofs
        type(contact_t) :: contact
        type(csr_matrix_t) :: k
        type(cholesky_t) :: chol
        type(timings_t) :: timings
        type(status_t) :: stat
        real(wp), allocatable :: kt_nn(:, :), kt_nt(:, :)
        integer :: level, i
        logical :: ok

        call single_triangle(1.0_wp, m)
        call build_refinable_mesh(m, r, stat)
        ok = stat%ok()
        do level = 1, 6
            call r%refine([(i, i=1, r%n_cells())], stat)
            ok = ok .and. stat%ok()
            call r%to_mesh(ELEMENT_P1, fine, stat)
            if (stat%ok()) call build_dof_map(fine, [fine%part_index('fixed')], dofs, stat)
            if (stat%ok()) call build_contact(fine, fine%part_index('contact'), dofs, contact, &
                                              stat)
            if (stat%ok()) call assemble_stiffness(fine, dofs, 1.0_wp, 0.3_wp, k, stat)
            if (stat%ok()) call factor_stiffness(k, fine, dofs, contact, chol, timings, stat)
            if (stat%ok()) call contact_flexibility(chol, contact, kt_nn, kt_nt, stat)
            call chol%free()
            if (.not. stat%ok()) print '(a)', '      level '//to_string(level)//': '// &
                                              stat%message
            ok = ok .and. stat%ok()
        end do
        call t%check('contact-last factor and contact blocks on a triangle bisected 1-6 times', &
                     ok)
    end subroutine check_contact_last_factor
end program test_mesh_refine
