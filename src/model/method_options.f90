! SPDX-License-Identifier: MIT
!> How a run computes, apart from the body it computes on (scene) and the point it computes
!> at (study_point_t): the eigensolver and its error estimate (eigen_options_t), and the
!> adaptive refinement (adapt_options_t), as enumerations. The analyses translate the input
!> into them once (run_inputs); the numerics read only these.
module method_options
    use kinds, only: wp
    implicit none
    private
    public :: solver_name, operator_name

    !> The eigensolver: SOLVER_AUTO resolves to one of the others (eigen_solve: choose_solver).
    integer, parameter, public :: SOLVER_AUTO = 0
    integer, parameter, public :: SOLVER_DENSE = 1    !! all p eigenpairs of the reduced problem
    integer, parameter, public :: SOLVER_ARPACK = 2   !! a few, by ARPACK, with the certificate
    !> When the error estimate of the lowest positive mu is computed.
    integer, parameter, public :: ESTIMATE_AUTO = 0   !! up to eigen_solve's size limit
    integer, parameter, public :: ESTIMATE_ON = 1
    integer, parameter, public :: ESTIMATE_OFF = 2
    !> What ARPACK iterates on.
    integer, parameter, public :: OPERATOR_REDUCED = 1   !! the p x p contact operator
    integer, parameter, public :: OPERATOR_FULL = 2      !! (K - target B)^-1 B in the free dofs
    !> The refinement of an adaptive run.
    integer, parameter, public :: REFINE_NONE = 0   !! one mesh, no loop
    integer, parameter, public :: REFINE_H = 1      !! Doerfler marking and bisection
    integer, parameter, public :: REFINE_HP = 2     !! graded meshes with rising degrees

    type, public :: eigen_options_t
        integer :: solver = SOLVER_AUTO
        integer :: nev = 6                  !! ARPACK: eigenvalues per run
        integer :: ncv = 0                  !! ARPACK: Krylov dimension, 0: from nev
        integer :: maxit = 1000             !! ARPACK: restarts
        real(wp) :: tol = 0.0_wp            !! ARPACK: relative residual, 0: machine precision
        !> ARPACK's shift sigma, in the input's unit of mu (E / length; 0: none)
        real(wp) :: target = 0.0_wp
        integer :: dense_max_contact = 24   !! SOLVER_AUTO: dense up to this many contact nodes
        integer :: estimate = ESTIMATE_AUTO
        integer :: operator = OPERATOR_REDUCED
        !> every positive mu up to this is wanted, in the input's unit of mu (0: the lowest)
        real(wp) :: cn_max = 0.0_wp
        integer :: modes = 1                !! eigenvectors wanted (at least one is kept)
    end type eigen_options_t

    type, public :: adapt_options_t
        integer :: refine = REFINE_NONE
        real(wp) :: tolerance = 0.0_wp     !! relative error bar to meet; 0: no loop
        integer :: max_dofs = 0            !! free dofs of a level at most; 0: as memory allows
        integer :: max_levels = 0          !! refinements at most; 0: no limit
        real(wp) :: theta = 0.25_wp        !! h: Doerfler's fraction
        real(wp) :: sigma = 0.15_wp        !! hp: grading factor per layer
        integer :: p_max = 20              !! hp: highest degree of a cell
    end type adapt_options_t

contains

    !> 'dense' or 'arpack', as summary.json and the stdout summary name a solver used.
    pure function solver_name(solver) result(name)
        integer, intent(in) :: solver
        character(len=:), allocatable :: name
        name = 'dense'
        if (solver == SOLVER_ARPACK) name = 'arpack'
    end function solver_name

    !> 'reduced' or 'full': what the run's eigensolver worked on (the dense solver always
    !> works on the reduced p x p matrix), as summary.json names it.
    pure function operator_name(solver, operator) result(name)
        integer, intent(in) :: solver, operator
        character(len=:), allocatable :: name
        name = 'reduced'
        if (solver == SOLVER_ARPACK .and. operator == OPERATOR_FULL) name = 'full'
    end function operator_name
end module method_options
