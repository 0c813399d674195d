! SPDX-License-Identifier: MIT
!> The reference elements by name and code: what the mesh, the finite element spaces and the
!> writers all need to agree on, below any of them so that none has to import another.
module element_types
    implicit none
    private
    public :: element_nodes_per_cell, element_nodes_per_edge, element_from_name, element_name
    public :: element_corners, element_degree, element_dimension, triangle_lattice
    public :: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, ELEMENT_P4
    public :: MAX_ELEMENT

    ! Node order inside a cell follows Gmsh: corners anticlockwise, then mid-edge nodes
    ! (edge k joins corner k and corner k+1), then the centre node of Q2. Cubic and quartic
    ! triangles have p - 1 nodes per edge, listed from corner k towards corner k+1, then
    ! their interior nodes (P3: the centre; P4: a P1 triangle of nodes, as Gmsh and VTK's
    ! Lagrange triangle order them).
    integer, parameter :: ELEMENT_P1 = 1   !! 3-node triangle
    integer, parameter :: ELEMENT_Q1 = 2   !! 4-node quadrilateral
    integer, parameter :: ELEMENT_P2 = 3   !! 6-node triangle
    integer, parameter :: ELEMENT_Q2 = 4   !! 9-node quadrilateral
    integer, parameter :: ELEMENT_P3 = 5   !! 10-node triangle
    integer, parameter :: ELEMENT_P4 = 6   !! 15-node triangle
    integer, parameter :: MAX_ELEMENT = 6  !! largest ELEMENT_* code

contains

    !> Nodes of one cell of ELEMENT_* `element`; 0 for an unknown code.
    pure integer function element_nodes_per_cell(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_P1); element_nodes_per_cell = 3
        case (ELEMENT_Q1); element_nodes_per_cell = 4
        case (ELEMENT_P2); element_nodes_per_cell = 6
        case (ELEMENT_Q2); element_nodes_per_cell = 9
        case (ELEMENT_P3); element_nodes_per_cell = 10
        case (ELEMENT_P4); element_nodes_per_cell = 15
        case default; element_nodes_per_cell = 0
        end select
    end function element_nodes_per_cell

    !> Spatial dimension of the cells of `element`, and so of the reference coordinates of
    !> its shape functions, of a mesh made of them and of a node's displacement: 2 for every
    !> element here (plane strain); 0 for an unknown code. A mesh takes its dimension from
    !> here (mesh_t%dim), and every count that depends on it (dofs per node, Jacobians,
    !> the coordinates a writer pads to three) from the mesh.
    pure integer function element_dimension(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2, ELEMENT_P3, ELEMENT_P4)
            element_dimension = 2
        case default
            element_dimension = 0
        end select
    end function element_dimension

    !> Vertices of the cell (the first nodes of a cell, anticlockwise): 3 or 4.
    pure integer function element_corners(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_Q1, ELEMENT_Q2); element_corners = 4
        case default; element_corners = 3
        end select
    end function element_corners

    !> Polynomial degree p of the element (1 to 4); 0 for an unknown code.
    pure integer function element_degree(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_P1, ELEMENT_Q1); element_degree = 1
        case (ELEMENT_P2, ELEMENT_Q2); element_degree = 2
        case (ELEMENT_P3); element_degree = 3
        case (ELEMENT_P4); element_degree = 4
        case default; element_degree = 0
        end select
    end function element_degree

    !> Nodes of one edge (p + 1: ends, then the p - 1 inner nodes from the first end); 0 for
    !> an unknown code.
    pure integer function element_nodes_per_edge(element)
        integer, intent(in) :: element
        element_nodes_per_edge = 0
        if (element_degree(element) > 0) element_nodes_per_edge = element_degree(element) + 1
    end function element_nodes_per_edge

    !> Barycentric lattice indices (i1, i2, i3), i1 + i2 + i3 = p, of the nodes of a triangle
    !> of degree p: node a sits at (i1, i2, i3)/p, i.e. at reference point (i2, i3)/p, in
    !> Gmsh node order. Columns beyond the node count (all, for a quadrilateral) are zero.
    pure subroutine triangle_lattice(element, lattice)
        integer, intent(in) :: element
        integer, intent(out) :: lattice(:, :)   !! (3, >= nodes per cell)
        ! Tables, not a loop: shape functions ask for them at every quadrature point of
        ! every cell (the loop was 8% of an adaptive P3 run).
        integer, parameter :: P1(3, 3) = reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3])
        integer, parameter :: P2(3, 6) = reshape([2, 0, 0, 0, 2, 0, 0, 0, 2, &
                                                  1, 1, 0, 0, 1, 1, 1, 0, 1], [3, 6])
        integer, parameter :: P3(3, 10) = reshape([3, 0, 0, 0, 3, 0, 0, 0, 3, &
            2, 1, 0, 1, 2, 0, 0, 2, 1, 0, 1, 2, 1, 0, 2, 2, 0, 1, 1, 1, 1], [3, 10])
        integer, parameter :: P4(3, 15) = reshape([4, 0, 0, 0, 4, 0, 0, 0, 4, &
            3, 1, 0, 2, 2, 0, 1, 3, 0, 0, 3, 1, 0, 2, 2, 0, 1, 3, 1, 0, 3, 2, 0, 2, 3, 0, 1, &
            2, 1, 1, 1, 2, 1, 1, 1, 2], [3, 15])
        lattice = 0
        if (element_corners(element) /= 3) return
        ! corners, then p - 1 nodes per edge k (corner k to corner k + 1) from corner k on,
        ! then the inner nodes (P4: a P1 triangle, its corners next to corners 1, 2, 3)
        select case (element_degree(element))
        case (1); lattice(:, 1:3) = P1
        case (2); lattice(:, 1:6) = P2
        case (3); lattice(:, 1:10) = P3
        case (4); lattice(:, 1:15) = P4
        end select
    end subroutine triangle_lattice

    !> ELEMENT_* code of 'p1', 'q1', 'p2', 'q2', 'p3' or 'p4'; 0 for any other name.
    pure integer function element_from_name(name)
        character(len=*), intent(in) :: name
        select case (trim(name))
        case ('p1'); element_from_name = ELEMENT_P1
        case ('q1'); element_from_name = ELEMENT_Q1
        case ('p2'); element_from_name = ELEMENT_P2
        case ('q2'); element_from_name = ELEMENT_Q2
        case ('p3'); element_from_name = ELEMENT_P3
        case ('p4'); element_from_name = ELEMENT_P4
        case default; element_from_name = 0
        end select
    end function element_from_name

    !> 'p1', 'q1', 'p2', 'q2', 'p3' or 'p4' of an ELEMENT_* code; '??' for any other.
    pure function element_name(element) result(name)
        integer, intent(in) :: element
        character(len=2) :: name
        character(len=2), parameter :: NAMES(MAX_ELEMENT) = ['p1', 'q1', 'p2', 'q2', 'p3', 'p4']
        name = '??'
        if (element >= 1 .and. element <= MAX_ELEMENT) name = NAMES(element)
    end function element_name
end module element_types
