! SPDX-License-Identifier: MIT
!> Everything a run needs from its input file, validated, with the documented defaults.
!> One component type per namelist group; `input_config` fills it from the file.
module run_config
    use kinds, only: wp
    implicit none
    private

    integer, parameter, public :: NAME_LEN = 64     !! element, solver, analysis names
    integer, parameter, public :: LIST_LEN = 512    !! space-separated lists of side names
    integer, parameter, public :: PATH_LEN = 4096

    type, public :: mesh_config_t
        character(len=NAME_LEN) :: source = 'rectangle'   !! 'rectangle' | 'gmsh'
        character(len=PATH_LEN) :: file = ''              !! Gmsh .msh, relative to the input
        real(wp) :: width = 1.0_wp
        real(wp) :: height = 1.0_wp
        integer :: nx = 8
        integer :: ny = 8
        character(len=NAME_LEN) :: element = 'p1'         !! 'p1' | 'q1' | 'p2' | 'q2'
        character(len=NAME_LEN) :: diagonal = 'right'     !! 'right' | 'left' (p1, p2)
        character(len=LIST_LEN) :: dirichlet = 'top'
        character(len=LIST_LEN) :: neumann = 'left right'
        character(len=LIST_LEN) :: contact = 'bottom'
    end type mesh_config_t

    type, public :: material_config_t
        real(wp) :: young = 1.0_wp
        real(wp) :: poisson = 0.3_wp
    end type material_config_t

    type, public :: analysis_config_t
        character(len=NAME_LEN) :: kind = 'eigen'   !! 'eigen' | 'threshold' | 'branch' | 'solve'
        real(wp) :: lambda = 5.0_wp
    end type analysis_config_t

    type, public :: eigen_config_t
        character(len=NAME_LEN) :: solver = 'auto'  !! 'dense' | 'arpack' | 'auto'
        integer :: nev = 6            !! eigenvalues wanted from ARPACK
        real(wp) :: target = 0.0_wp   !! shift sigma for ARPACK (0: factor K alone)
        real(wp) :: tol = 0.0_wp      !! ARPACK tolerance (0: machine precision)
        integer :: maxit = 1000       !! ARPACK restarts
        integer :: ncv = 0            !! Krylov dimension (0: chosen from nev)
        !> 'auto' uses dense up to this many contact nodes: the measured cross-over of total
        !> run time (README, "Choosing the solver"); both take milliseconds there.
        integer :: dense_max_contact = 16
    end type eigen_config_t

    type, public :: output_config_t
        character(len=PATH_LEN) :: directory = ''   !! '' means output/<input file stem>
        logical :: vtk = .true.
        integer :: modes = 1                        !! how many modes go to mode_NNN.vtu
        logical :: matrices = .false.               !! write K.mtx and B.mtx
    end type output_config_t

    type, public :: config_t
        character(len=:), allocatable :: input_file   !! path as given on the command line
        type(mesh_config_t) :: mesh
        type(material_config_t) :: material
        type(analysis_config_t) :: analysis
        type(eigen_config_t) :: eigen
        type(output_config_t) :: output
    end type config_t
end module run_config
