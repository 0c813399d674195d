! SPDX-License-Identifier: MIT
!> The text of `nceig --help`: usage, then every group and variable with its default and
!> accepted values, taken from a default `config_t` and from input_validation, so that the
!> documentation cannot drift from the code. test_input_records checks that it names the
!> variables the namelists read.
module input_help
    use run_config, only: config_t, MAX_SWEEP_LAMBDAS
    use strings, only: to_string, quoted, one_of
    use real_format, only: real_to_text
    use input_validation, only: MESH_SOURCES, ELEMENT_NAMES, DIAGONALS, RECTANGLE_SIDES, &
                                ACCEPTED_ANALYSES, ACCEPTED_SOLVERS, MAX_CELLS_PER_SIDE, &
                                SWEEP_SPACINGS, MAX_SWEEP_POINTS, VTK_FORMATS, SOLVE_DATA, &
                                SOLVE_STARTS, ESTIMATE_MODES, EIGEN_OPERATORS
    implicit none
    private
    public :: help_text

    integer, parameter :: HELP_COLUMN = 28   !! where descriptions start in the help text

contains

    !> The --help text: usage, then every group and variable with its default, taken from
    !> a default `config_t` so that the documentation cannot drift from the code. Lines
    !> are separated by new_line('a'); the text ends with one. Lines stay under 100.
    function help_text() result(text)
        character(len=:), allocatable :: text
        type(config_t) :: d
        character(len=*), parameter :: NL = new_line('a')

        text = 'Usage: nceig INPUT.nml | --help | --version'//NL &
               //'       nceig INPUT.nml --set group%variable=value [--set ...]'//NL//NL &
               //'Finds the critical interface parameters of the normal compliance friction' &
               //NL//'model: the eigenvalues mu of K phi = mu B phi for the plane-strain body' &
               //NL//'described by the namelist file INPUT.nml. Every variable is optional;' &
               //NL//'defaults are shown. Names are case-insensitive. Results go to the' &
               //NL//'output directory: summary.json, eigenvalues.csv, mode_NNN.vtu.'//NL//NL &
               //'--set group%variable=value overrides one variable of INPUT.nml, with the' &
               //NL//'same checks (--set analysis%lambda=2.5 --set mesh%element=q2; names need' &
               //NL//'no quotes). A path given so is relative to the working directory.'//NL//NL
        text = text//'&mesh'//NL &
               //entry('source', quoted(d%mesh%source), 'one of '//one_of(MESH_SOURCES)) &
               //entry('file', quoted(d%mesh%file), "Gmsh .msh (source = 'gmsh'), relative" &
                       //' to the input file''s folder') &
               //entry('width', real_to_text(d%mesh%width), 'rectangle size along x') &
               //entry('height', real_to_text(d%mesh%height), 'rectangle size along y') &
               //entry('nx', to_string(d%mesh%nx), 'cells along x (1 to ' &
                       //to_string(MAX_CELLS_PER_SIDE)//')') &
               //entry('ny', to_string(d%mesh%ny), 'cells along y') &
               //entry('element', quoted(d%mesh%element), one_of(ELEMENT_NAMES)) &
               //repeat(' ', HELP_COLUMN + 2) &
               //'(p3, p4: cubic, quartic triangles; rectangle; Gmsh sets its own)'//NL &
               //entry('diagonal', quoted(d%mesh%diagonal), one_of(DIAGONALS) &
                       //': triangle diagonals rise to the right or left') &
               //entry('dirichlet', quoted(d%mesh%dirichlet), 'fixed sides (' &
                       //one_of(RECTANGLE_SIDES)//') or Gmsh groups') &
               //entry('neumann', quoted(d%mesh%neumann), 'loaded by &solve t1, t2 (free in' &
                       //' eigen runs); unnamed sides are free') &
               //entry('contact', quoted(d%mesh%contact), 'the one side or group in contact')
        text = text//'&material'//NL &
               //entry('young', real_to_text(d%material%young), 'Young''s modulus E > 0') &
               //entry('poisson', real_to_text(d%material%poisson), &
                       'Poisson''s ratio, -1 < poisson < 0.5')
        text = text//'&analysis'//NL &
               //entry('kind', quoted(d%analysis%kind), 'one of '//one_of(ACCEPTED_ANALYSES)) &
               //entry('lambda', real_to_text(d%analysis%lambda), &
                       'ratio in b_lambda(phi, v) = lambda int phi_n v_t - int phi_n v_n')
        text = text//'&eigen'//NL &
               //entry('solver', quoted(d%eigen%solver), 'one of '//one_of(ACCEPTED_SOLVERS)) &
               //entry('nev', to_string(d%eigen%nev), 'ARPACK: eigenvalues nearest target' &
                       //' per run (doubled while undecided)') &
               //entry('target', real_to_text(d%eigen%target), 'shift sigma: eigenvalues' &
                       //' nearest to it are found first') &
               //entry('tol', real_to_text(d%eigen%tol), 'sparse solver tolerance' &
                       //' (0: machine precision)') &
               //entry('maxit', to_string(d%eigen%maxit), 'sparse solver restarts') &
               //entry('ncv', to_string(d%eigen%ncv), 'Krylov dimension, 0 or >= nev + 2' &
                       //' (0: chosen from nev)') &
               //entry('dense_max_contact', to_string(d%eigen%dense_max_contact), &
                       "'auto' picks 'dense' up to this many contact nodes, else 'arpack'") &
               //entry('estimate', quoted(d%eigen%estimate), one_of(ESTIMATE_MODES)// &
                       ": error estimate of mu (auto: <= 40000 dofs)") &
               //entry('operator', quoted(d%eigen%operator), one_of(EIGEN_OPERATORS)// &
                       ": ARPACK on p x p or (K - target B)^-1 B") &
               //entry('cn_max', real_to_text(d%eigen%cn_max), 'report every positive mu' &
                       //' in (0, cn_max] (0: only the lowest)')
        text = text//'&output'//NL &
               //entry('directory', quoted(d%output%directory), "'' means output/<input" &
                       //' file stem> (from the working directory)') &
               //entry('vtk', logical_text(d%output%vtk), 'write mode_NNN.vtu for ParaView') &
               //entry('modes', to_string(d%output%modes), 'how many modes to write as .vtu') &
               //entry('matrices', logical_text(d%output%matrices), &
                       'write K.mtx and B.mtx (Matrix Market)') &
               //entry('vtk_format', quoted(d%output%vtk_format), one_of(VTK_FORMATS) &
                       //" ('binary': raw appended data; 'ascii': text)") &
               //entry('plot', logical_text(d%output%plot), 'draw mode_001.png with gnuplot' &
                       //' (the first mode on the deformed mesh)') &
               //entry('progress', logical_text(d%output%progress), 'a line on stdout as' &
                       //' each phase ends (.false.: the final summary only)')
        text = text//"&sweep  (kind = 'lambda_sweep': lowest positive mu against lambda)"//NL &
               //entry('lambda_min', real_to_text(d%sweep%lambda_min), 'first lambda of the' &
                       //' range (either sign)') &
               //entry('lambda_max', real_to_text(d%sweep%lambda_max), 'last lambda, >' &
                       //' lambda_min') &
               //entry('n_lambda', to_string(d%sweep%n_lambda), 'points in the range (2 to ' &
                       //to_string(MAX_SWEEP_POINTS)//')') &
               //entry('spacing', quoted(d%sweep%spacing), one_of(SWEEP_SPACINGS) &
                       //" ('log': one sign, geometric in |lambda|)") &
               //entry('lambdas', 'unset', 'explicit list (up to '// &
                       to_string(MAX_SWEEP_LAMBDAS)//'), replaces the range') &
               //entry('plot', logical_text(d%sweep%plot), 'draw lambda_sweep.png with' &
                       //' gnuplot when it is installed')
        text = text//'&branch      (kind = ''branch'': U + delta phi, docs/model.md 9)'//NL &
               //entry('alpha', real_to_text(d%branch%alpha), 'u_n of U on Gamma_C, > 0') &
               //entry('beta', real_to_text(d%branch%beta), '|u_t| of U on Gamma_C, > 0') &
               //entry('n_delta', to_string(d%branch%n_delta), 'deltas evenly spaced in' &
                       //' [-delta_max, delta_max]') &
               //entry('write_members', to_string(d%branch%write_members), &
                       'members written as branch_NNN.vtu')
        text = text//'&solve       (kind = ''solve'': frictional normal compliance, Newton)'//NL &
               //entry('data', quoted(d%solve%data), one_of(SOLVE_DATA)//': the loads below,' &
                       //' or those of &branch') &
               //entry('c_n', real_to_text(d%solve%c_n), 'normal compliance (data = ''given'')') &
               //entry('c_t', real_to_text(d%solve%c_t), 'tangential compliance') &
               //entry('critical_factor', real_to_text(d%solve%critical_factor), &
                       'data = ''branch'': c_n, c_t = factor * critical') &
               //entry('f1, f2', real_to_text(d%solve%f1)//', '//real_to_text(d%solve%f2), &
                       'body force') &
               //entry('t1, t2', real_to_text(d%solve%t1)//', '//real_to_text(d%solve%t2), &
                       'traction on every Neumann part') &
               //entry('u_d1, u_d2', real_to_text(d%solve%u_d1)//', ' &
                       //real_to_text(d%solve%u_d2), 'displacement on Gamma_D') &
               //entry('start', quoted(d%solve%start), one_of(SOLVE_STARTS)) &
               //entry('start_delta', real_to_text(d%solve%start_delta), &
                       'start = ''branch'': U + start_delta phi') &
               //entry('start_scale', real_to_text(d%solve%start_scale), &
                       'start = ''random'' or ''mode'': size of the guess') &
               //entry('start_noise', real_to_text(d%solve%start_noise), &
                       'uniform noise of this size added to any start') &
               //entry('seed', to_string(d%solve%seed), 'of the random start and the noise') &
               //entry('tol', real_to_text(d%solve%tol), '||residual|| / ||load||' &
                       //' (infinity norms) to stop at') &
               //entry('max_iterations', to_string(d%solve%max_iterations), 'Newton iterations')
        text = text//'&adapt       (eigen, threshold, lambda_sweep: refine until the error bar' &
               //' is met)'//NL &
               //entry('tolerance', real_to_text(d%adapt%tolerance), 'relative error of' &
                       //' mu or of both critical lambdas (0: off; < 1)') &
               //entry('max_dofs', to_string(d%adapt%max_dofs), 'no level solves on more' &
                       //' free dofs (0: as memory allows)') &
               //entry('max_levels', to_string(d%adapt%max_levels), 'refinement steps after' &
                       //' the starting mesh (0: no limit)') &
               //entry('theta', real_to_text(d%adapt%theta), 'Doerfler fraction: refine' &
                       //' cells holding this part of the estimate')

    contains

        function entry(name, value, description) result(line)
            character(len=*), intent(in) :: name, value, description
            character(len=:), allocatable :: line
            line = '    '//name//' = '//value
            if (len(line) < HELP_COLUMN) line = line//repeat(' ', HELP_COLUMN - len(line))
            line = line//'  '//description//NL
        end function entry
    end function help_text

    pure function logical_text(flag) result(text)
        logical, intent(in) :: flag
        character(len=:), allocatable :: text
        text = '.false.'
        if (flag) text = '.true.'
    end function logical_text
end module input_help
