# SPDX-License-Identifier: MIT
# The input variables of nceig: one line per namelist variable. The build generates from
# this file (cmake/input_codegen.cmake, into the build tree's generated/ folder) the
# *_config_t types of run_config with their defaults, the namelist readers of input_records
# and the table of input_table (types, help lines, choices), so they cannot disagree.
# Validation rules stay hand-written in input_validation; docs/input.md keeps a row per
# variable (cli_input_reference compares it with --help).
#
#   input_group(GROUP [HEADER text])
#       A namelist group, in the order groups are read, validated and documented. HEADER is
#       its --help line (default '&GROUP'). Its variables follow it; the type is GROUP_config_t,
#       the component config_t%GROUP.
#   input_variable(NAME KIND DEFAULT HELP [LEN n] [DIM n] [CHOICES list] [SHOWN text]
#                  [JOINED])
#       NAME     the namelist name (not record, config, ios, msg or listing_unit: the
#                reader's arguments)
#       KIND     real | integer | logical      real(wp), integer, logical
#                name | path | list            character(len=NAME_LEN | PATH_LEN | LIST_LEN);
#                                              read values are lowercased and left-adjusted,
#                                              left-adjusted, or normalized_list'ed
#                reals                         real(wp) array of DIM entries
#       DEFAULT  a Fortran constant expression ('p1', 1.0_wp, .true., huge(1.0_wp))
#       HELP     the --help description, plain text: '@' stands for the accepted values of
#                CHOICES, {CONSTANT} for to_string(CONSTANT), \n continues on a line of its
#                own under the description
#       LEN      characters of a name other than NAME_LEN
#       DIM      entries of a reals array
#       CHOICES  input_validation's list of accepted values (the help shows it for '@')
#       SHOWN    --help shows this instead of the default
#       JOINED   --help documents it on the next variable's line ('f1, f2 = 0.0, 0.0'),
#                whose HELP describes both
# A constant named in HELP or a new CHOICES list must be imported in input_table's `use`.
# Comments here say what the code needs to know about a variable.

input_group(mesh)
#              name      kind    default       help
input_variable(source    name    'rectangle'   "one of @" CHOICES MESH_SOURCES)
input_variable(file      path    ''
               "Gmsh .msh (source = 'gmsh'), relative to the input file's folder")
input_variable(width     real    1.0_wp        "rectangle size along x")
input_variable(height    real    1.0_wp        "rectangle size along y")
input_variable(nx        integer 8             "cells along x (1 to {MAX_CELLS_PER_SIDE})")
input_variable(ny        integer 8             "cells along y")
input_variable(element   name    'p1'
               "@\n(p3, p4: cubic, quartic triangles; rectangle; Gmsh sets its own)"
               CHOICES ELEMENT_NAMES)
input_variable(diagonal  name    'right'
               "@: triangle diagonals rise to the right or left" CHOICES DIAGONALS)
input_variable(dirichlet list    'top'
               "fixed sides (@) or Gmsh groups" CHOICES RECTANGLE_SIDES)
input_variable(neumann   list    "'left right'"
               "loaded by &solve t1, t2 (free in eigen runs); unnamed sides are free")
input_variable(contact   list    'bottom'      "the one side or group in contact")

input_group(material)
input_variable(young     real    1.0_wp        "Young's modulus E > 0")
input_variable(poisson   real    0.3_wp        "Poisson's ratio, -1 < poisson < 0.5")

input_group(analysis)
# kind is one of ACCEPTED_ANALYSES; each new analysis adds its name there
input_variable(kind      name    'eigen'       "one of @" CHOICES ACCEPTED_ANALYSES)
input_variable(lambda    real    5.0_wp
               "ratio in b_lambda(phi, v) = lambda int phi_n v_t - int phi_n v_n")

input_group(eigen)
input_variable(solver    name    'auto'        "one of @" CHOICES ACCEPTED_SOLVERS)
# eigenvalues wanted from ARPACK
input_variable(nev       integer 6
               "ARPACK: eigenvalues nearest target per run (doubled while undecided)")
# shift sigma for ARPACK (0: factor K alone)
input_variable(target    real    0.0_wp
               "shift sigma: eigenvalues nearest to it are found first")
input_variable(tol       real    0.0_wp        "sparse solver tolerance (0: machine precision)")
input_variable(maxit     integer 1000          "sparse solver restarts")
input_variable(ncv       integer 0
               "Krylov dimension, 0 or >= nev + 2 (0: chosen from nev)")
# 'auto' uses dense up to this many contact nodes: both solvers share the factor of K, and
# up to here the dense solver's extra eigen + output time (1-4 ms) is within the run-to-run
# noise (docs/numerics.md, "Choosing the solver")
input_variable(dense_max_contact integer 24
               "'auto' picks 'dense' up to this many contact nodes, else 'arpack'")
# 'auto': up to ESTIMATE_AUTO_MAX_DOFS free dofs (it costs a few times the solve)
input_variable(estimate  name    'auto'
               "@: error estimate of mu (auto: <= 40000 dofs)" CHOICES ESTIMATE_MODES)
# what ARPACK iterates on: 'reduced' (the p x p contact operator) or 'full'
# ((K - target B)^-1 B in the n free dofs, one sparse LU)
input_variable(operator  name    'reduced'
               "@: ARPACK on p x p or (K - target B)^-1 B" CHOICES EIGEN_OPERATORS)
input_variable(cn_max    real    0.0_wp
               "report every positive mu in (0, cn_max] (0: only the lowest)")

input_group(output)
input_variable(directory path    ''
               "'' means output/<input file stem> (from the working directory)")
input_variable(vtk       logical .true.        "write mode_NNN.vtu for ParaView")
input_variable(modes     integer 1             "how many modes to write as .vtu")
input_variable(matrices  logical .false.       "write K.mtx and B.mtx (Matrix Market)")
# 'binary': raw appended data, 26-32 times faster to write than 'ascii' (docs/performance.md)
input_variable(vtk_format name   'binary'
               "@ ('binary': raw appended data; 'ascii': text)" LEN 8 CHOICES VTK_FORMATS)
input_variable(plot      logical .true.
               "draw mode_001.png, adapt.png, lambda_sweep.png with gnuplot")
input_variable(progress  logical .true.
               "a line on stdout as each phase ends (.false.: the final summary only)")

# analysis = 'lambda_sweep': the lambdas at which the lowest positive mu is computed, a
# range or an explicit list (the list wins when it has any entry: run_config's
# sweep_lambdas)
input_group(sweep HEADER "&sweep  (kind = 'lambda_sweep': lowest positive mu against lambda)")
input_variable(lambda_min real   -20.0_wp      "first lambda of the range (either sign)")
input_variable(lambda_max real   20.0_wp       "last lambda, > lambda_min")
input_variable(n_lambda  integer 401           "points in the range (2 to {MAX_SWEEP_POINTS})")
input_variable(spacing   name    'linear'
               "@ ('log': one sign, geometric in |lambda|)" CHOICES SWEEP_SPACINGS)
# entries equal to huge() are unset (the namelist fills a prefix): run_config's lambda_is_set
input_variable(lambdas   reals   "huge(1.0_wp)"
               "explicit list (up to {MAX_SWEEP_LAMBDAS}), replaces the range"
               DIM MAX_SWEEP_LAMBDAS SHOWN unset)
input_variable(plot      logical .true.
               "draw lambda_sweep.png with gnuplot (&output plot on too)")
input_variable(adapt_thresholds logical .false.
               "hp: adapt lambda+- and the onsets in the points' climb")

# analysis = 'branch' (model.md section 9): the base solution U and the members U + delta phi
input_group(branch HEADER "&branch      (kind = 'branch': U + delta phi, docs/model.md 9)")
input_variable(alpha     real    0.1_wp        "u_n of U on Gamma_C, > 0")
input_variable(beta      real    0.1_wp        "|u_t| of U on Gamma_C, > 0")
input_variable(n_delta   integer 11            "deltas evenly spaced in [-delta_max, delta_max]")
# spread evenly over the deltas
input_variable(write_members integer 3         "members written as branch_NNN.vtu")

# analysis = 'solve': the frictional normal-compliance problem (m_n = m_t = 1), in the
# input's units (run_config's UNSCALED_* ranges)
input_group(solve HEADER "&solve       (kind = 'solve': frictional normal compliance, Newton)")
input_variable(data      name    'given'
               "@: the loads below, or those of &branch" CHOICES SOLVE_DATA)
input_variable(c_n       real    1.0_wp        "normal compliance (data = 'given')")
input_variable(c_t       real    1.0_wp        "tangential compliance")
input_variable(critical_factor real 1.0_wp     "data = 'branch': c_n, c_t = factor * critical")
# per unit volume
input_variable(f1        real    0.0_wp        "" JOINED)
input_variable(f2        real    0.0_wp        "body force")
input_variable(t1        real    0.0_wp        "" JOINED)
input_variable(t2        real    0.0_wp        "traction on every Neumann part")
input_variable(u_d1      real    0.0_wp        "" JOINED)
input_variable(u_d2      real    0.0_wp        "displacement on Gamma_D")
input_variable(start     name    'zero'        "@" CHOICES SOLVE_STARTS)
input_variable(start_delta real  0.0_wp        "start = 'branch': U + start_delta phi")
input_variable(start_scale real  1.0_wp        "start = 'random' or 'mode': size of the guess")
# uniform in [-noise, noise]
input_variable(start_noise real  0.0_wp        "uniform noise of this size added to any start")
input_variable(seed      integer 1             "of the random start and the noise")
input_variable(tol       real    1.0e-10_wp
               "||residual|| / ||load|| (infinity norms) to stop at")
input_variable(max_iterations integer 50       "Newton iterations")

# analysis 'eigen', 'threshold', 'lambda_sweep': refine the mesh until the error estimate
# of the lowest positive mu (or of both critical lambdas) is at most `tolerance`
input_group(adapt HEADER
            "&adapt       (eigen, threshold, lambda_sweep: refine until the error bar is met)")
input_variable(tolerance real    0.0_wp
               "relative error of mu or of both critical lambdas (0: off; < 1)")
# 0: as many as the memory available at the start allows (adaptive_dof_limit)
input_variable(max_dofs  integer 0
               "no level solves on more free dofs (0: as memory allows)")
# 0: no limit (the tolerance or the dofs end the loop, never a level count)
input_variable(max_levels integer 0
               "refinement steps after the starting mesh (0: no limit)")
# Doerfler marking: refine the fewest cells whose indicators sum to at least this fraction
# of the total (1 refines every cell with an indicator)
input_variable(theta     real    0.25_wp
               "Doerfler fraction: refine cells holding this part of the estimate")
# 'h': Doerfler marking; 'hp': geometric meshes toward the singular points with degrees
# rising away from them
input_variable(strategy  name    'h'
               "@: refine cells, or graded meshes with rising degrees"
               CHOICES ADAPT_STRATEGIES)
# cells shrink by sigma per layer; the range is what the geometric meshes can be built with
input_variable(sigma     real    0.15_wp
               "hp: grading factor toward the singular points (0.01 to 0.5)")
input_variable(p_max     integer 20            "hp: highest degree of a cell (1 to 20)")
