#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The comparison run of scripts/bench/bench_operator.sh: SLEPc Krylov-Schur, shift-and-invert
with MUMPS, on the K.mtx and B.mtx that nceig wrote (&output matrices = .true.), for the
eigenvalues of K phi = mu B phi nearest a target.

Usage: bench_slepc.py DIRECTORY TARGET NEV TOL
Prints one line: seconds (setup + solve, the matrices already in memory), the number of
solves with K - target B (KSPSolve calls, from PETSc's log), the lowest positive real mu
among the converged ones (or 'none'), and their largest relative residual as SLEPc
reports it. Needs python3-slepc4py (Debian); PETSC_DIR and SLEPC_DIR may have to name
/usr/lib/petscdir/... and /usr/lib/slepcdir/... when the alternatives are not set.
"""
import sys
import time

import numpy as np
import petsc4py

petsc4py.init(sys.argv[:1])
from petsc4py import PETSc  # noqa: E402
import slepc4py  # noqa: E402

slepc4py.init(sys.argv[:1])
from slepc4py import SLEPc  # noqa: E402


def read_matrix_market(path):
    """A 'coordinate real general' Matrix Market file as a PETSc AIJ matrix."""
    with open(path, 'rb') as handle:
        header = handle.readline()
        if b'coordinate real general' not in header:
            raise SystemExit(f'{path}: expected coordinate real general, got {header!r}')
        line = handle.readline()
        while line.startswith(b'%'):
            line = handle.readline()
        rows, cols, nnz = (int(x) for x in line.split())
        values = np.array(handle.read().split(), dtype=float).reshape(nnz, 3)
    i = values[:, 0].astype(np.int32) - 1
    j = values[:, 1].astype(np.int32) - 1
    order = np.lexsort((j, i))
    i, j, v = i[order], j[order], values[order, 2]
    indptr = np.zeros(rows + 1, dtype=np.int32)
    np.add.at(indptr, i + 1, 1)
    indptr = np.cumsum(indptr, dtype=np.int32)
    return PETSc.Mat().createAIJ(size=(rows, cols), csr=(indptr, j, v))


def main():
    directory, target, nev, tol = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), \
        float(sys.argv[4])
    k = read_matrix_market(f'{directory}/K.mtx')
    b = read_matrix_market(f'{directory}/B.mtx')
    PETSc.Log.begin()
    start = time.perf_counter()
    eps = SLEPc.EPS().create()
    eps.setOperators(k, b)
    eps.setProblemType(SLEPc.EPS.ProblemType.GNHEP)
    eps.setType(SLEPc.EPS.Type.KRYLOVSCHUR)
    eps.setDimensions(nev=nev)
    eps.setTolerances(tol=tol, max_it=1000)
    eps.setTarget(target)
    eps.setWhichEigenpairs(SLEPc.EPS.Which.TARGET_MAGNITUDE)
    st = eps.getST()
    st.setType(SLEPc.ST.Type.SINVERT)
    ksp = st.getKSP()
    ksp.setType(PETSc.KSP.Type.PREONLY)
    pc = ksp.getPC()
    pc.setType(PETSc.PC.Type.LU)
    pc.setFactorSolverType('mumps')
    eps.solve()
    seconds = time.perf_counter() - start
    solves = PETSc.Log.Event('KSPSolve').getPerfInfo()['count']
    lowest, worst = None, 0.0
    for i in range(eps.getConverged()):
        mu = eps.getEigenvalue(i)
        worst = max(worst, eps.computeError(i, SLEPc.EPS.ErrorType.BACKWARD))
        if abs(mu.imag) <= 1e-8 * abs(mu) and mu.real > 0 and (lowest is None or mu.real < lowest):
            lowest = mu.real
    print(f'{seconds:.3f} {solves} {lowest if lowest is not None else "none"} {worst:.1e}')


if __name__ == '__main__':
    main()
