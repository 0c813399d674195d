! SPDX-License-Identifier: MIT
!> Everything a run needs from its input file, validated, with the documented defaults.
!> One component type per namelist group; `input_config` fills it from the file. Functions
!> of a record that the analyses need (sweep_lambdas) live here, beside the record.
module run_config
    use kinds, only: wp
    use strings, only: NAME_LEN, LIST_LEN
    use ieee_arithmetic, only: ieee_is_finite
    implicit none
    private
    public :: sweep_lambdas, count_set_lambdas, lambda_is_set
    public :: NAME_LEN, LIST_LEN   !! of strings, for the users of the records

    integer, parameter, public :: PATH_LEN = 4096
    !> 'branch' and 'solve' work in the input's units (their loads, displacements and
    !> compliances have units): E and the mesh size stay within these powers of ten, so that
    !> the products of assembly and residuals (E / h^2 x h^2, squared norms) stay in binary64;
    !> the build of the problem checks E and the size, the validation of &solve its forces
    !> (E's range) and displacements (the size's).
    real(wp), parameter, public :: UNSCALED_YOUNG_RANGE = 1.0e100_wp
    real(wp), parameter, public :: UNSCALED_SIZE_RANGE = 1.0e50_wp

    type, public :: mesh_config_t
        character(len=NAME_LEN) :: source = 'rectangle'   !! 'rectangle' | 'gmsh'
        character(len=PATH_LEN) :: file = ''              !! Gmsh .msh, relative to the input
        real(wp) :: width = 1.0_wp
        real(wp) :: height = 1.0_wp
        integer :: nx = 8
        integer :: ny = 8
        character(len=NAME_LEN) :: element = 'p1'   !! 'p1' | 'q1' | 'p2' | 'q2' | 'p3' | 'p4'
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
        !> one of input_validation's ACCEPTED_ANALYSES: 'eigen', 'threshold', 'lambda_sweep',
        !> 'branch', 'solve'
        character(len=NAME_LEN) :: kind = 'eigen'
        real(wp) :: lambda = 5.0_wp
    end type analysis_config_t

    type, public :: eigen_config_t
        character(len=NAME_LEN) :: solver = 'auto'  !! 'dense' | 'arpack' | 'auto'
        integer :: nev = 6            !! eigenvalues wanted from ARPACK
        real(wp) :: target = 0.0_wp   !! shift sigma for ARPACK (0: factor K alone)
        real(wp) :: tol = 0.0_wp      !! ARPACK tolerance (0: machine precision)
        integer :: maxit = 1000       !! ARPACK restarts
        integer :: ncv = 0            !! Krylov dimension (0: chosen from nev)
        !> 'auto' uses dense up to this many contact nodes: both solvers share the factor of
        !> K, and up to here the dense solver's extra eigen + output time (1-4 ms) is within
        !> the run-to-run noise (docs/numerics.md, "Choosing the solver")
        integer :: dense_max_contact = 24
        !> error estimate of the lowest positive mu: 'auto' (up to ESTIMATE_AUTO_MAX_DOFS free
        !> dofs: it costs a few times the solve), 'on', 'off'
        character(len=NAME_LEN) :: estimate = 'auto'
        !> what ARPACK iterates on: 'reduced' (the p x p contact operator) or 'full'
        !> ((K - target B)^-1 B in the n free dofs, one sparse LU)
        character(len=NAME_LEN) :: operator = 'reduced'
        !> report every positive real mu in (0, cn_max]; 0: only the lowest
        real(wp) :: cn_max = 0.0_wp
    end type eigen_config_t

    type, public :: output_config_t
        character(len=PATH_LEN) :: directory = ''   !! '' means output/<input file stem>
        logical :: vtk = .true.
        integer :: modes = 1                        !! how many modes go to mode_NNN.vtu
        logical :: matrices = .false.               !! write K.mtx and B.mtx
        !> 'binary': raw appended data, 26-32 times faster to write than 'ascii'
        !> (docs/performance.md).
        character(len=8) :: vtk_format = 'binary'
        logical :: plot = .true.                    !! draw mode_001.png (gnuplot)
        logical :: progress = .true.                !! a line on stdout as each phase ends
    end type output_config_t

    integer, parameter, public :: MAX_SWEEP_LAMBDAS = 1000   !! length of &sweep lambdas

    !> &sweep (analysis = 'lambda_sweep'): the lambdas at which the lowest positive mu is
    !> computed, a range or an explicit list (the list wins when it has any entry).
    type, public :: sweep_config_t
        real(wp) :: lambda_min = -20.0_wp
        real(wp) :: lambda_max = 20.0_wp
        integer :: n_lambda = 401
        character(len=NAME_LEN) :: spacing = 'linear'   !! 'linear' | 'log' (one sign)
        !> explicit list; entries equal to huge() are unset (the namelist fills a prefix)
        real(wp) :: lambdas(MAX_SWEEP_LAMBDAS) = huge(1.0_wp)
        logical :: plot = .true.                        !! draw lambda_sweep.png (gnuplot)
    end type sweep_config_t
    !> analysis = 'branch' (model.md section 9): the base solution U and the members U + delta phi.
    type, public :: branch_config_t
        real(wp) :: alpha = 0.1_wp        !! u_n of U on Gamma_C, > 0
        real(wp) :: beta = 0.1_wp         !! |u_t| of U on Gamma_C, > 0
        integer :: n_delta = 11           !! delta values, evenly spaced in [-delta_max, delta_max]
        integer :: write_members = 3      !! members written as branch_NNN.vtu (spread evenly)
    end type branch_config_t

    !> analysis = 'solve': the frictional normal-compliance problem (m_n = m_t = 1).
    type, public :: solve_config_t
        character(len=NAME_LEN) :: data = 'given'   !! 'given' | 'branch' (model.md section 9 data)
        real(wp) :: c_n = 1.0_wp                    !! normal compliance ('given' data)
        real(wp) :: c_t = 1.0_wp                    !! tangential compliance ('given' data)
        real(wp) :: critical_factor = 1.0_wp        !! 'branch' data: c = factor * critical
        real(wp) :: f1 = 0.0_wp, f2 = 0.0_wp        !! body force per unit volume
        real(wp) :: t1 = 0.0_wp, t2 = 0.0_wp        !! traction on every Neumann part
        real(wp) :: u_d1 = 0.0_wp, u_d2 = 0.0_wp    !! displacement on Gamma_D
        character(len=NAME_LEN) :: start = 'zero'   !! 'zero' | 'branch' | 'random' | 'mode'
        real(wp) :: start_delta = 0.0_wp            !! 'branch' start: U + start_delta phi
        real(wp) :: start_scale = 1.0_wp            !! 'random', 'mode': size of the guess
        real(wp) :: start_noise = 0.0_wp            !! uniform noise in [-noise, noise] added
        integer :: seed = 1                         !! of the 'random' start and the noise
        real(wp) :: tol = 1.0e-10_wp                !! on ||residual||_inf / ||load||_inf
        integer :: max_iterations = 50
    end type solve_config_t

    !> &adapt (analysis 'eigen', 'lambda_sweep'): refine the mesh by newest-vertex bisection
    !> until the error estimate of the lowest positive mu is at most `tolerance` (0: none).
    type, public :: adapt_config_t
        real(wp) :: tolerance = 0.0_wp      !! relative, 0 <= tolerance < 1; 0 is off
        !> no level solves on more free dofs than this; 0: as many as the memory available
        !> at the start allows (adaptive_dof_limit)
        integer :: max_dofs = 0
        !> refinement steps after the starting mesh; 0: no limit (the tolerance or the
        !> dofs end the loop, never a level count)
        integer :: max_levels = 0
        !> Doerfler marking: refine the fewest cells whose indicators sum to at least this
        !> fraction of the total (0 < theta <= 1; 1 refines every cell with an indicator)
        real(wp) :: theta = 0.25_wp
        !> 'h': refine the mesh (Doerfler marking); 'hp': geometric meshes toward the
        !> singular points with degrees rising away from them (analysis 'eigen' only)
        character(len=4) :: strategy = 'h'
        !> 'hp': the geometric grading factor, 0 < sigma < 1 (cells shrink by sigma per layer)
        real(wp) :: sigma = 0.15_wp
        !> 'hp': the highest polynomial degree of a cell, 1 to 20
        integer :: p_max = 20
    end type adapt_config_t

    type, public :: config_t
        character(len=:), allocatable :: input_file   !! path as given on the command line
        type(mesh_config_t) :: mesh
        type(material_config_t) :: material
        type(analysis_config_t) :: analysis
        type(eigen_config_t) :: eigen
        type(output_config_t) :: output
        type(sweep_config_t) :: sweep
        type(branch_config_t) :: branch
        type(solve_config_t) :: solve
        type(adapt_config_t) :: adapt
    end type config_t

contains

    !> The lambdas of a validated &sweep: the explicit list if any, else the range, evenly
    !> spaced ('linear') or in geometric progression ('log', one sign), ends included exactly.
    pure function sweep_lambdas(c) result(lambdas)
        type(sweep_config_t), intent(in) :: c
        real(wp), allocatable :: lambdas(:)
        real(wp) :: ratio, half, t
        integer :: n, i

        n = count_set_lambdas(c)
        if (n > 0) then
            lambdas = c%lambdas(1:n)
            return
        end if
        n = c%n_lambda
        allocate (lambdas(n))
        if (c%spacing == 'log') then
            ! The ratio overflows (or underflows) beyond 308 decades (1e-200 to 1e200):
            ! then through logs, which cost about |log ratio| ulps; below, the power.
            if (abs(exponent(c%lambda_max) - exponent(c%lambda_min)) < &
                maxexponent(1.0_wp) - 1) then
                ratio = c%lambda_max/c%lambda_min   ! > 0: one sign
                do i = 1, n
                    lambdas(i) = c%lambda_min*ratio**(real(i - 1, wp)/real(n - 1, wp))
                end do
            else
                do i = 1, n
                    t = real(i - 1, wp)/real(n - 1, wp)
                    lambdas(i) = sign(exp((1.0_wp - t)*log(abs(c%lambda_min)) + &
                                          t*log(abs(c%lambda_max))), c%lambda_min)
                end do
            end if
        else
            ! In units of 2 when an end exceeds 1: the span max - min then stays finite
            ! (-9e307 to 9e307), and halving and doubling are exact, so the points are
            ! those of the plain formula wherever it does not overflow.
            half = 1.0_wp
            if (max(abs(c%lambda_min), abs(c%lambda_max)) > 1.0_wp) half = 0.5_wp
            do i = 2, n - 1   ! the ends exactly, below: near huge(), t = 1 could round over
                t = real(i - 1, wp)/real(n - 1, wp)
                lambdas(i) = (half*c%lambda_min + (half*c%lambda_max - half*c%lambda_min)*t) &
                             /half
            end do
        end if
        lambdas(1) = c%lambda_min
        lambdas(n) = c%lambda_max
    end function sweep_lambdas

    !> Number of leading entries of &sweep lambdas that were set.
    pure integer function count_set_lambdas(c)
        type(sweep_config_t), intent(in) :: c
        count_set_lambdas = 0
        do while (count_set_lambdas < size(c%lambdas))
            if (.not. lambda_is_set(c%lambdas(count_set_lambdas + 1))) exit
            count_set_lambdas = count_set_lambdas + 1
        end do
    end function count_set_lambdas

    !> An entry of &sweep lambdas differs from the unset mark huge(); NaN and infinities
    !> count as set so that validation rejects them (and no ordered comparison sees a NaN).
    elemental logical function lambda_is_set(x)
        real(wp), intent(in) :: x
        lambda_is_set = .not. ieee_is_finite(x)
        if (.not. lambda_is_set) lambda_is_set = x < huge(1.0_wp)
    end function lambda_is_set
end module run_config
