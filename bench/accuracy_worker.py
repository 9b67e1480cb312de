#!/usr/bin/python3
"""One level of the work-precision study (bench/accuracy.py runs it): loads the reduced prism problem that
`examples/prism -save_reduced FILE` wrote (P, f, u_C, coordinates), solves it with ssstar (loaded by -dll_append)
for every method and tolerance, and writes FILE.json: per run the time of SNESSolve (median of --repeat), the
iterations, the ||z_k|| history and the contact solution u and reaction r = P u - f. Under mpiexec P is
distributed over the ranks (the dense route on N ranks); the first rank gathers the solutions and writes the file.

  [mpiexec -n N] bench/accuracy_worker.py FILE --methods ssstar,fixedpoint --tols 1e-2,...,1e-12 --reference-rtol 1e-14 [--repeat 3]
"""
import argparse
import json
import os
import sys
import time

import numpy as np
import petsc4py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# the options of each method (method names as in the CSV of the study)
METHODS = {"ssstar": {}, "fixedpoint": {"snes_ssstar_method": "fixedpoint"}}


def parse():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("file")
    p.add_argument("--methods", default="ssstar")
    p.add_argument("--tols", default="1e-2,1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12")
    p.add_argument("--reference-rtol", type=float, default=1e-14)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--baseline-repeat", type=int, default=1, help="runs per tolerance of the methods other than ssstar")
    p.add_argument("--max-it", type=int, default=100000, help="iteration limit (the first-order method needs many)")
    return p.parse_args()


def main():
    args = parse()
    petsc4py.init([sys.argv[0], "-dll_append", os.path.join(ROOT, "lib", "libssstar.so")])
    from petsc4py import PETSc

    comm = PETSc.COMM_WORLD
    dofs = int(np.fromfile(args.file, dtype=">i4", count=2)[1])  # the header of P: class id, rows, ...
    nodes, size, rank = dofs // 3, comm.getSize(), comm.getRank()
    local = 3 * (nodes // size + (rank < nodes % size))  # whole nodes per rank (a node's 3 dofs on one rank)
    viewer = PETSc.Viewer().createBinary(args.file, "r")
    P = PETSc.Mat().create()
    P.setSizes(((local, dofs), (local, dofs)))
    P.setType(PETSc.Mat.Type.DENSE)
    P.load(viewer)
    vecs = []
    for _ in range(3):
        v = PETSc.Vec().create()
        v.setSizes((local, dofs))
        v.setType(PETSc.Vec.Type.STANDARD)
        v.load(viewer)
        vecs.append(v)
    f, _, xyz = vecs
    opts = PETSc.Options()

    def gathered(v):
        """the whole vector on the first rank (as a list; empty elsewhere)"""
        scatter, whole = PETSc.Scatter.toZero(v)
        scatter.scatter(v, whole, PETSc.InsertMode.INSERT_VALUES, PETSc.ScatterMode.FORWARD)
        out = whole.getArray().tolist()
        scatter.destroy()
        whole.destroy()
        return out

    def residual(snes, u, r):
        P.mult(u, r)
        r.axpy(-1.0, f)

    def solve(method, rtol):
        for key, value in METHODS[method].items():
            opts.setValue(key, value)
        snes = PETSc.SNES().create()
        snes.setFunction(residual, f.duplicate())
        snes.setJacobian(lambda snes, u, J, Jp: None, P)
        snes.setType("ssstar")
        snes.setTolerances(rtol=rtol, atol=0.0, max_it=args.max_it)
        snes.setConvergenceHistory(length=args.max_it + 1)
        snes.setFromOptions()
        for key in METHODS[method]:
            opts.delValue(key)
        u = f.duplicate()
        u.zeroEntries()
        PETSc.COMM_WORLD.barrier()
        t0 = time.perf_counter()
        snes.solve(None, u)
        elapsed = time.perf_counter() - t0
        r = f.duplicate()
        residual(snes, u, r)
        history = [float(z) for z in snes.getConvergenceHistory()[0]]
        out = {"iterations": snes.getIterationNumber(), "reason": int(snes.getConvergedReason()), "time": elapsed,
               "history": history, "u": gathered(u), "r": gathered(r)}
        snes.destroy()
        return out

    result = {"coordinates": gathered(xyz), "runs": []}
    reference = solve("ssstar", args.reference_rtol)
    reference["method"], reference["eps"] = "ssstar", args.reference_rtol
    result["reference"] = reference
    for method in filter(None, args.methods.split(",")):
        for eps in (float(t) for t in filter(None, args.tols.split(","))):
            runs = [solve(method, eps) for _ in range(args.repeat if method == "ssstar" else args.baseline_repeat)]
            run = runs[0]
            run["time"] = sorted(r["time"] for r in runs)[len(runs) // 2]
            run["method"], run["eps"] = method, eps
            result["runs"].append(run)
    if PETSc.COMM_WORLD.getRank() == 0:
        with open(args.file + ".json", "w") as out:
            json.dump(result, out)


if __name__ == "__main__":
    main()
