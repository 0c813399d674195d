! SPDX-License-Identifier: MIT
!> The reference elements by name and code: what the mesh, the finite element spaces and the
!> writers all need to agree on, below any of them so that none has to import another.
module element_types
    implicit none
    private
    public :: element_nodes_per_cell, element_nodes_per_edge, element_from_name, element_name
    public :: element_corners
    public :: ELEMENT_P1, ELEMENT_Q1, ELEMENT_P2, ELEMENT_Q2

    ! Node order inside a cell follows Gmsh: corners anticlockwise, then mid-edge nodes
    ! (edge k joins corner k and corner k+1), then the centre node of Q2.
    integer, parameter :: ELEMENT_P1 = 1   !! 3-node triangle
    integer, parameter :: ELEMENT_Q1 = 2   !! 4-node quadrilateral
    integer, parameter :: ELEMENT_P2 = 3   !! 6-node triangle
    integer, parameter :: ELEMENT_Q2 = 4   !! 9-node quadrilateral

contains

    !> Nodes of one cell of ELEMENT_* `element`; 0 for an unknown code.
    pure integer function element_nodes_per_cell(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_P1); element_nodes_per_cell = 3
        case (ELEMENT_Q1); element_nodes_per_cell = 4
        case (ELEMENT_P2); element_nodes_per_cell = 6
        case (ELEMENT_Q2); element_nodes_per_cell = 9
        case default; element_nodes_per_cell = 0
        end select
    end function element_nodes_per_cell

    !> Nodes of one edge (2 or 3); 0 for an unknown code.
    !> Vertices of the cell (the first nodes of a cell, anticlockwise): 3 or 4.
    pure integer function element_corners(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_Q1, ELEMENT_Q2); element_corners = 4
        case default; element_corners = 3
        end select
    end function element_corners

    pure integer function element_nodes_per_edge(element)
        integer, intent(in) :: element
        select case (element)
        case (ELEMENT_P1, ELEMENT_Q1); element_nodes_per_edge = 2
        case (ELEMENT_P2, ELEMENT_Q2); element_nodes_per_edge = 3
        case default; element_nodes_per_edge = 0
        end select
    end function element_nodes_per_edge

    !> ELEMENT_* code of 'p1', 'q1', 'p2' or 'q2'; 0 for any other name.
    pure integer function element_from_name(name)
        character(len=*), intent(in) :: name
        select case (trim(name))
        case ('p1'); element_from_name = ELEMENT_P1
        case ('q1'); element_from_name = ELEMENT_Q1
        case ('p2'); element_from_name = ELEMENT_P2
        case ('q2'); element_from_name = ELEMENT_Q2
        case default; element_from_name = 0
        end select
    end function element_from_name

    !> 'p1', 'q1', 'p2' or 'q2' of an ELEMENT_* code; '??' for any other.
    pure function element_name(element) result(name)
        integer, intent(in) :: element
        character(len=2) :: name
        character(len=2), parameter :: NAMES(4) = ['p1', 'q1', 'p2', 'q2']
        name = '??'
        if (element >= 1 .and. element <= 4) name = NAMES(element)
    end function element_name
end module element_types
