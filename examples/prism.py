#!/usr/bin/python3
"""The prism's reduced contact problem solved from Python: petsc4py, with ssstar loaded as a PETSc plugin.

  examples/prism -level 6 -save_reduced prism_L6.bin
  examples/prism.py prism_L6.bin [-snes_monitor -snes_converged_reason -snes_ssstar_friction 0.3 ...]

Reads P, f and the contact solution u_C that examples/prism wrote, solves 0 in P u - f + Q(u) with
-snes_type ssstar (the type comes from lib/libssstar.so through -dll_append: nothing of ssstar is linked),
checks the Coulomb law at every node and compares u with u_C. Runs under mpiexec too."""
import os
import sys

import petsc4py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if len(sys.argv) < 2 or sys.argv[1].startswith("-"):
    sys.exit(__doc__)
petsc4py.init([sys.argv[0], "-dll_append", os.path.join(ROOT, "lib", "libssstar.so")] + sys.argv[2:])
from petsc4py import PETSc  # noqa: E402 (after init)


def load(path):
    viewer = PETSc.Viewer().createBinary(path, "r")
    P = PETSc.Mat().create()
    P.setType(PETSc.Mat.Type.DENSE)
    P.load(viewer)
    f, uC = PETSc.Vec().load(viewer), PETSc.Vec().load(viewer)
    return P, f, uC


def coulomb_violation(u, r, phi):
    """Worst violation of the law over the nodes (relative to max|u|, max|r|), as tests/check_solution.py"""
    x, y = u.getArray(readonly=True).reshape(-1, 3), r.getArray(readonly=True).reshape(-1, 3)
    umax, rmax = u.norm(PETSc.NormType.INFINITY), r.norm(PETSc.NormType.INFINITY)
    worst = 0.0
    for (u1, u2, un), (r1, r2, rn) in zip(x, y):
        ut, rt = (u1 * u1 + u2 * u2) ** 0.5, (r1 * r1 + r2 * r2) ** 0.5
        v = max(-un / umax, -rn / rmax, abs(un * rn) / (umax * rmax), (rt - phi * rn) / rmax)
        if ut > 1e-8 * umax:
            v = max(v, abs(r1 + phi * rn * u1 / ut) / rmax, abs(r2 + phi * rn * u2 / ut) / rmax)
        worst = max(worst, v)
    per_rank = PETSc.Vec().createMPI((1, PETSc.DECIDE))
    per_rank.setValue(per_rank.getOwnershipRange()[0], worst)
    per_rank.assemble()
    return per_rank.max()[1]


def main():
    P, f, uC = load(sys.argv[1])

    def residual(snes, u, r):
        P.mult(u, r)
        r.axpy(-1.0, f)

    snes = PETSc.SNES().create()
    snes.setFunction(residual, f.duplicate())
    snes.setJacobian(lambda snes, u, J, Jp: None, P)  # P is constant
    snes.setType("ssstar")
    snes.setFromOptions()
    u = f.duplicate()
    u.zeroEntries()
    snes.solve(None, u)
    r = f.duplicate()
    residual(snes, u, r)
    phi = PETSc.Options().getReal("snes_ssstar_friction", 0.3)
    diff = u.copy()
    diff.axpy(-1.0, uC)
    reasons = {v: k for k, v in vars(PETSc.SNES.ConvergedReason).items() if isinstance(v, int)}
    PETSc.Sys.Print("petsc4py + ssstar: %s after %d iterations; %d contact nodes; Coulomb law violation %.1e; |u - u_C|/|u_C| = %.1e"
                    % (reasons[snes.getConvergedReason()], snes.getIterationNumber(), u.getSize() // 3, coulomb_violation(u, r, phi),
                       diff.norm() / uC.norm()))
    return 0 if snes.getConvergedReason() > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
