#!/usr/bin/python3
"""Bad input on one rank of two from Python (tests/suite_solver.py runs it under timeout): a contact node of rank 0
whose last dof rank 1 owns (-case straddle), or normals of the wrong size on rank 1 only (-case normals). Every rank
gets petsc4py.PETSc.Error with the same error and message, uncaught: each prints its traceback ("[r] <message>") and
exits non-zero. -case none: nothing wrong, "rank r: solved" on each."""
import sys

import numpy as np
import petsc4py

petsc4py.init(sys.argv)
from petsc4py import PETSc  # noqa: E402

import ssstar  # noqa: E402


def main():
    comm = PETSc.COMM_WORLD
    rank = comm.getRank()
    case = PETSc.Options().getString("case", "straddle")
    nodes = 4  # per rank
    K = PETSc.Mat().createAIJ(((3 * nodes, None), (3 * nodes, None)), nnz=(1, 0), comm=comm)
    K.setUp()
    lo, hi = K.getOwnershipRange()
    for r in range(lo, hi):
        K.setValue(r, r, 1e3)
    K.assemble()
    b = K.createVecLeft()
    b.setArray(np.where(np.arange(lo, hi) % 3 == 2, -10.0, 2.0))
    dofs = np.arange(lo, hi)
    if case == "straddle" and rank == 0:
        dofs[-1] = hi  # rank 1's first dof
    normals = np.tile([0.0, 0.0, 1.0], nodes)
    if case == "normals" and rank == 1:
        normals = normals[:-1]
    snes = PETSc.SNES().create(comm=comm)
    snes.setType(ssstar.SNESSSSTAR)
    ssstar.set_linear_problem(snes, K, b)
    ssstar.set_contact_nodes(snes, dofs, normals)
    u = b.duplicate()
    u.zeroEntries()
    snes.solve(None, u)
    print("rank %d: solved" % rank, flush=True)


if __name__ == "__main__":
    main()
