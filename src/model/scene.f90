! SPDX-License-Identifier: MIT
!> The body a run computes on, apart from what is computed on it: its geometry (the
!> rectangle generator's parameters or a Gmsh file), its material, the names of its
!> boundary parts, and the input's name for messages (scene_t); and a study point, the
!> lambda and nu one computation is made at (study_point_t). build_problem (module problem)
!> turns a scene into the discrete problem; a finer mesh of the same body is an operation on
!> the scene (scene_halved) or on its mesh (mesh_refine), never an edited input.
module scene
    use kinds, only: wp
    use strings, only: NAME_LEN, LIST_LEN, to_string
    use element_types, only: ELEMENT_P1
    implicit none
    private

    integer, parameter, public :: MESH_RECTANGLE = 1   !! the structured rectangle generator
    integer, parameter, public :: MESH_GMSH = 2        !! a Gmsh .msh file

    !> The linear elastic material (plane strain).
    type, public :: material_t
        real(wp) :: young = 1.0_wp     !! Young's modulus E, in the input's unit of stress
        real(wp) :: poisson = 0.3_wp   !! Poisson's ratio nu, dimensionless, in (-1, 0.5)
    end type material_t

    type, public :: scene_t
        !> the input file as given on the command line: messages about the scene start with it
        character(len=:), allocatable :: name
        integer :: source = MESH_RECTANGLE    !! MESH_RECTANGLE or MESH_GMSH
        !> the rectangle (source MESH_RECTANGLE): its size in the input's unit of length,
        !> cells per side, element (ELEMENT_*) and the direction of its triangles' diagonals
        real(wp) :: width = 1.0_wp
        real(wp) :: height = 1.0_wp
        integer :: nx = 8
        integer :: ny = 8
        integer :: element = ELEMENT_P1
        character(len=NAME_LEN) :: diagonal = 'right'
        !> the Gmsh file (source MESH_GMSH), whose cells have their own element
        character(len=:), allocatable :: file
        type(material_t) :: material
        !> the boundary parts, blank-separated names: sides of the rectangle or 1D physical
        !> groups of the Gmsh file
        character(len=LIST_LEN) :: dirichlet = 'top'
        character(len=LIST_LEN) :: neumann = 'left right'
        character(len=LIST_LEN) :: contact = 'bottom'
    contains
        procedure :: halved => scene_halved
        procedure :: mesh_words => scene_mesh_words
        procedure :: source_name => scene_source_name
    end type scene_t

    !> One computation of a study: the ratio lambda of b_lambda and the Poisson ratio nu of
    !> the body, on the scene `scene` of the study (a run has one scene: 1). K depends on nu,
    !> not on lambda: a problem serves every lambda of its (scene, nu).
    type, public :: study_point_t
        real(wp) :: lambda = 5.0_wp    !! dimensionless
        real(wp) :: poisson = 0.3_wp   !! dimensionless
        integer :: scene = 1
    end type study_point_t

contains

    !> The same body with every cell of the rectangle halved (2 nx x 2 ny; nested: its space
    !> holds this one's); a Gmsh scene is itself (its mesh is halved by bisection:
    !> halved_mesh).
    pure function scene_halved(this) result(halved)
        class(scene_t), intent(in) :: this
        type(scene_t) :: halved
        halved = this
        if (this%source /= MESH_RECTANGLE) return
        halved%nx = 2*this%nx
        halved%ny = 2*this%ny
    end function scene_halved

    !> How messages name the mesh: "file = 'F'" or 'nx = N, ny = M'.
    pure function scene_mesh_words(this) result(words)
        class(scene_t), intent(in) :: this
        character(len=:), allocatable :: words
        if (this%source == MESH_GMSH) then
            words = 'file = '''//this%file//''''
        else
            words = 'nx = '//to_string(this%nx)//', ny = '//to_string(this%ny)
        end if
    end function scene_mesh_words

    !> 'rectangle' or 'gmsh', as the input and summary.json name the source.
    pure function scene_source_name(this) result(name)
        class(scene_t), intent(in) :: this
        character(len=:), allocatable :: name
        name = 'rectangle'
        if (this%source == MESH_GMSH) name = 'gmsh'
    end function scene_source_name
end module scene
