#!/usr/bin/python3
"""ssstar against GetFEM on the prism, in the same run: GetFEM 5.4 (Debian's python3-getfem, MUMPS) solves the same
scene on the same mesh (meshes/prism_L<L>.msh through ssstar's mesh cache), frictional contact with the rigid plane
by its nodal contact brick with Alart-Curnier's augmented Lagrangian (version 1, non-symmetric) and its generalized
Newton method; ssstar solves it with examples/prism on 2 ranks (the default path). The repeats interleave them.

  bench/getfem_prism.py [--level 10] [--ranks 2] [--repeat 3]

Prints per repeat and as medians: GetFEM's phases (mesh and model, solve: its Newton iterations), its whole run, and
ssstar's whole run (the process's wall time, mesh to the -o file written), the ratio GetFEM / ssstar, and the check
that both solved the same problem: the total contact force (sum of ssstar's reactions against GetFEM's multipliers)
and the contact states' counts. Writes bench/output/getfem.csv."""
import argparse
import csv
import os
import re
import statistics
import time

import h5py
import numpy as np

from getfem_common import OUT, ROOT, environment, mesh_file, timed
from getfem_common import mesh as cached_mesh

E, NU, PHI = 2.1e5, 0.3, 0.3
TOP, RIGHT = (0.0, 0.0, -500.0), (-200.0, 30.0, 200.0)
ROW = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+(\d+)\s+([\d.]+)\s+(\d+)\s+([\d/]+)\s+([\d/]+)\s+(\S+)\s+([\d.]+)$", re.M)


def ssstar(level, ranks):
    h5 = os.path.join(OUT, "getfem_ssstar_L%d.h5" % level)
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), os.path.join(ROOT, "examples", "prism"), "-level", str(level), "-summary_header", "0", "-o", h5]
    output, whole = timed(cmd)
    m = ROW.search(output)
    if not m:
        raise SystemExit("ssstar printed no summary row:\n" + output[-2000:])
    with h5py.File(h5, "r") as f:
        force = f["contact/reaction"][:].sum(axis=0)
    return {"whole": whole, "iters": int(m.group(8)), "states": m.group(10), "force": force, "mesh": mesh_file(output)}


def getfem(mesh):
    """GetFEM's solve of the prism on the mesh of ssstar's cache (the gmsh file ssstar's run names on its mesh line;
    its .h5 beside it): (seconds of mesh and model, of the solve), Newton iterations, the total contact force and the
    counts separated/sliding/sticking"""
    import getfem as gf
    t0 = time.perf_counter()
    m, _ = cached_mesh(mesh)
    regions = {"contact": 1, "top": 2, "dirichlet": 3, "right": 4}
    for name, direction in (("contact", [0, 0, -1]), ("top", [0, 0, 1]), ("dirichlet", [-1, 0, 0]), ("right", [1, 0, 0])):
        m.set_region(regions[name], m.outer_faces_with_direction(direction, 0.01))
    mfu = gf.MeshFem(m, 3)
    mfu.set_classical_fem(1)
    mim = gf.MeshIm(m, 2)
    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    md.add_initialized_data("lambda", [E * NU / ((1 + NU) * (1 - 2 * NU))])
    md.add_initialized_data("mu", [E / (2 * (1 + NU))])
    md.add_isotropic_linearized_elasticity_brick(mim, "u", "lambda", "mu")
    for name, traction in (("top", TOP), ("right", RIGHT)):
        md.add_initialized_data("F" + name, list(traction))
        md.add_source_term_brick(mim, "u", "F" + name, regions[name])
    md.add_Dirichlet_condition_with_multipliers(mim, "u", mfu, regions["dirichlet"])
    ncontact = mfu.basic_dof_on_region(regions["contact"]).size // 3
    md.add_variable("lambda_n", ncontact)
    md.add_variable("lambda_t", 2 * ncontact)
    md.add_initialized_data("r", [E])
    md.add_initialized_data("phi", [PHI])
    md.add_nodal_contact_with_rigid_obstacle_brick(mim, "u", "lambda_n", "lambda_t", "r", "phi", regions["contact"], "z + Heaviside(1e-9 - x)", 1)
    t1 = time.perf_counter()
    its = md.solve("max_res", 1e-9, "max_iter", 200, "lsolver", "mumps")
    t2 = time.perf_counter()
    ln, lt = md.variable("lambda_n"), md.variable("lambda_t").reshape(-1, 2)
    # the multipliers are the contact forces of the nodes (normal: positive = pressure; GetFEM's sign: -lambda_n)
    force_n = -ln.sum()
    tol = 1e-8 * max(np.abs(ln).max(), 1e-300)
    separated = int((np.abs(ln) <= tol).sum())
    sliding = int(((np.abs(ln) > tol) & (np.linalg.norm(lt, axis=1) >= PHI * np.abs(ln) * (1 - 1e-6))).sum())
    return {"model": t1 - t0, "solve": t2 - t1, "whole": t2 - t0, "iters": its[0] if isinstance(its, (tuple, list)) else its,
            "force_n": force_n, "states": "%d/%d/%d" % (separated, sliding, ln.size - separated - sliding)}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--level", type=int, default=10)
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    environment()
    mesh = ssstar(args.level, args.ranks)["mesh"]  # meshes the level and writes its cache (not timed)
    rows = []
    print("level %d; ssstar: examples/prism on %d ranks (whole run); GetFEM 5.4: one process, MUMPS, Alart-Curnier" % (args.level, args.ranks))
    print("repeat  getfem: model   solve   whole  its  normal force  states (sep/slide/stick) | ssstar: whole  its  normal force  states | getfem/ssstar")
    for rep in range(args.repeat):
        g = getfem(mesh)
        s = ssstar(args.level, args.ranks)
        ratio = g["whole"] / s["whole"]
        rows.append({"level": args.level, "ranks": args.ranks, "repeat": rep, "getfem_model": g["model"], "getfem_solve": g["solve"], "getfem_whole": g["whole"],
                     "getfem_iters": g["iters"], "getfem_force_n": g["force_n"], "getfem_states": g["states"], "ssstar_whole": s["whole"], "ssstar_iters": s["iters"],
                     "ssstar_force_n": s["force"][2], "ssstar_states": s["states"], "ratio": ratio})
        print("%6d  %13.2f %7.2f %7.2f %4s %13.6g  %-24s | %13.2f %4d %13.6g  %-12s | %6.1f" % (rep, g["model"], g["solve"], g["whole"], g["iters"], g["force_n"], g["states"],
                                                                                             s["whole"], s["iters"], s["force"][2], s["states"], ratio), flush=True)
    med = {k: statistics.median(r[k] for r in rows) for k in ("getfem_whole", "ssstar_whole", "ratio")}
    print("medians: GetFEM %.2f s, ssstar %.2f s, GetFEM / ssstar %.1f (the ratio of the same repeats); normal force %.6g against %.6g (%.1e apart)" % (
        med["getfem_whole"], med["ssstar_whole"], med["ratio"], rows[0]["getfem_force_n"], rows[0]["ssstar_force_n"],
        abs(rows[0]["getfem_force_n"] - rows[0]["ssstar_force_n"]) / abs(rows[0]["ssstar_force_n"])))
    with open(os.path.join(OUT, "getfem.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
