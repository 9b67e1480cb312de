#!/usr/bin/python3
"""A neo-Hookean half ball pressed to 30 % of its radius on the rigid plane: ssstar against GetFEM 5.4 on the same mesh
(issue 33). The scene is scenes/hemisphere.opts (meshes/hemisphere.geo: R = 10, E = 1000, nu = 0.3, its top moved down
by delta = 0.3 R in equal steps, the whole spherical surface in contact with the plane z = 0), frictionless and with
Coulomb friction phi = 0.3 (incremental on the path). GetFEM solves it on the tetrahedra of ssstar's mesh cache with
its finite-strain elasticity brick ('Compressible_Neo_Hookean_Bonet': W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,
ssstar's neo-Hookean law exactly), the top held by multipliers, and its nodal contact brick with the rigid plane
(Alart-Curnier's augmented Lagrangian, non-symmetric version, on the same contact nodes; the friction on the step's
slip u - u_previous, its dynamic term with gamma = -1), its Newton method with MUMPS; ssstar with examples/contact on
one rank (the whole body: the hyperelastic default). For a plane the nodal condition is exact at any deformation in
both codes (its normal and tangent plane do not depend on the configuration): the two codes solve the same discrete
problem, so their forces agree to the solvers' tolerances.

  bench/getfem_ball.py [--level 2] [--steps 6] [--repeat 3] [--phi 0,0.3] [--reference FILE]

Prints per step and code the normal force (the sum of the contact forces), the contact radius (the largest distance
from the axis, in the current configuration, of a contact node carrying a normal force above 1e-6 of the largest
node's), the Newton iterations, and per repeat the whole runs' times (ssstar: the process, mesh cache to the file
written; GetFEM: the mesh read from ssstar's cache, the model built, every step solved) and their ratio; medians over
the repeats, beside the AMG yardstick of the same repeat (bench/yardstick -yardstick amg: one AMG solve of the linear
K on the mesh). Writes bench/output/getfem_ball.csv (per phi and step), bench/output/getfem_ball_times.csv (per repeat)
and bench/output/getfem_ball.png (both codes' curves, both phi, and Hertz's small-indentation curve
F = 4/3 E/(1 - nu^2) R^(1/2) delta^(3/2)). --reference FILE writes GetFEM's curves alone into FILE (no ssstar run) (the known answer
tests/suite_hyperelastic.py holds ssstar to), the command in its first line."""
import argparse
import csv
import os
import re
import statistics
import sys
import time

import h5py
import numpy as np

from getfem_common import OUT, ROOT, environment, mesh_file, timed
from getfem_common import mesh as cached_mesh

R, E, NU = 10.0, 1000.0, 0.3
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
SCENE = os.path.join(ROOT, "scenes", "hemisphere.opts")
CARRIES = 1e-6  # a node carries contact when its normal force is above this fraction of the largest node's


def hertz(delta):
    """Hertz's force of a sphere of radius R on a rigid plane at the indentation delta (small strain, half space)"""
    return 4.0 / 3.0 * E / (1 - NU * NU) * np.sqrt(R) * np.asarray(delta) ** 1.5


def radius(position, force):
    """the contact radius: the largest distance from the axis x = y = 0 of a node (current positions) whose normal
    force is above CARRIES of the largest"""
    carrying = force > CARRIES * force.max()
    return float(np.hypot(position[carrying, 0], position[carrying, 1]).max())


def warm_up(level):
    """meshes the level into ssstar's cache by a run that does not move the top (not timed): the mesh file"""
    output, _ = timed([os.path.join(ROOT, "examples", "contact"), "-options_file", SCENE, "-level", str(level), "-displacement_top", "0:0,0,0;1:0,0,0", "-steps", "1",
                       "-o", os.path.join(OUT, "getfem_ball_warm_up.h5")])
    return mesh_file(output)


def ssstar(level, steps, phi):
    """ssstar's run of the scene: (per step (delta, normal force, contact radius, iterations), whole seconds, mesh file)"""
    h5 = os.path.join(OUT, "getfem_ball_ssstar_L%d_phi%g.h5" % (level, phi))
    cmd = [os.path.join(ROOT, "examples", "contact"), "-options_file", SCENE, "-level", str(level), "-steps", str(steps), "-friction_sphere", "%g" % phi,
           "-o", h5]
    output, whole = timed(cmd)
    iterations = [int(s) for s in re.findall(r"^step \d+/\d+ .*?, (\d+) iterations", output, re.M)]  # step 1 is delta = 0
    rows = []
    with h5py.File(h5, "r") as f:
        x, c = f["geometry/vertices"][:], f["contact/coordinates"][:]
        nodes = np.array([np.argmin(((x - p) ** 2).sum(axis=1)) for p in c])
        for k in range(1, steps + 1):
            force = f["steps/%d/contact/reaction" % k][:, 2]
            position = f["steps/%d/fields/position" % k][:][nodes]
            rows.append((float(force.sum()), radius(position, force), iterations[k]))
    deltas = [0.3 * R * k / steps for k in range(1, steps + 1)]
    return [(d,) + r for d, r in zip(deltas, rows)], whole, mesh_file(output)


def yardstick(level):
    """the AMG yardstick of the same run: seconds of one AMG solve (set-up and solve) of the linear K on the scene's mesh"""
    output, _ = timed([os.path.join(ROOT, "bench", "yardstick"), "-options_file", SCENE, "-level", str(level), "-yardstick", "amg"])
    m = re.search(r"^amg .* setup (\S+) solve (\S+) its", output, re.M)
    return float(m.group(1)) + float(m.group(2))


def getfem(mesh, steps, phi):
    """GetFEM's run of the scene on ssstar's mesh: (per step (delta, normal force, contact radius, iterations), whole
    seconds)"""
    import getfem as gf
    gf.util_trace_level(0)
    t0 = time.perf_counter()
    m, _ = cached_mesh(mesh)
    TOP, SPHERE = 1, 2
    top = m.outer_faces_with_direction([0, 0, 1], 0.01)
    m.set_region(TOP, top)
    m.set_region(SPHERE, m.outer_faces())
    m.region_subtract(SPHERE, TOP)
    mfu = gf.MeshFem(m, 3)
    mfu.set_classical_fem(1)
    mim = gf.MeshIm(m, 2)
    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    md.add_initialized_data("params", [LAM, MU])
    md.add_finite_strain_elasticity_brick(mim, "Compressible_Neo_Hookean_Bonet", "u", "params")
    md.add_initialized_data("press", [0.0, 0.0, 0.0])
    md.add_Dirichlet_condition_with_multipliers(mim, "u", mfu, TOP, "press")
    ndof = mfu.nbdof()
    dofs = mfu.basic_dof_on_region(SPHERE)
    first = dofs[dofs % 3 == 0]  # each contact node's x dof (P1: the node's dofs x, y, z in a row)
    X = mfu.basic_dof_nodes()[:, first]
    nc = first.size
    identity = gf.Spmat("identity", ndof)
    BN = gf.Spmat("copy", identity, list(first + 2), list(range(ndof)))
    BN.scale(-1.0)  # B_N u <= gap: -u_z <= z, the node stays above the plane
    BT = gf.Spmat("copy", identity, list(np.column_stack([first, first + 1]).ravel()), list(range(ndof)))
    md.add_initialized_data("r", [E])
    md.add_initialized_data("gap", X[2])
    md.add_initialized_data("alpha", np.ones(nc))
    md.add_variable("lambda_n", nc)
    if phi > 0:
        md.add_initialized_data("phi", [phi])
        md.add_initialized_data("gamma", [-1.0])  # the friction on B_T (u - w): w the last step's displacement
        md.add_initialized_data("w", np.zeros(ndof))
        md.add_variable("lambda_t", 2 * nc)
        md.add_basic_contact_brick("u", "lambda_n", "lambda_t", "r", BN, BT, "phi", "gap", "alpha", 1, "gamma", "w")
    else:
        md.add_basic_contact_brick("u", "lambda_n", "r", BN, "gap", "alpha", 1)
    rows = []
    for k in range(1, steps + 1):
        delta = 0.3 * R * k / steps
        md.set_variable("press", [0.0, 0.0, -delta])
        if phi > 0:
            md.set_variable("w", md.variable("u"))
        its = md.solve("max_res", 1e-8, "max_iter", 100, "lsolver", "mumps", "lsearch", "default")
        iterations = its[0] if isinstance(its, (tuple, list)) else its
        force = -md.variable("lambda_n")  # the multipliers are the nodal contact forces, GetFEM's sign: -lambda_n
        position = X.T + md.variable("u")[np.column_stack([first, first + 1, first + 2])]
        rows.append((delta, float(force.sum()), radius(position, force), int(iterations)))
    return rows, time.perf_counter() - t0


def plot(rows, path):
    """the force and the contact radius against the indentation: both codes, both phi, Hertz's small-indentation curves
    (F above, a = sqrt(R delta))"""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.4))
    d = np.linspace(0, 0.3 * R, 100)
    ax.plot(d / R, hertz(d) / (E * R * R), "k:", label="Hertz (small strain, half space)")
    bx.plot(d / R, np.sqrt(R * d) / R, "k:", label="Hertz: a = sqrt(R delta)")
    for phi, color in ((0.0, "C0"), (0.3, "C3")):
        sel = [r for r in rows if float(r["phi"]) == phi]
        if not sel:
            continue
        dd = np.array([0] + [float(r["delta"]) for r in sel]) / R
        for axis, key, scale in ((ax, "force", E * R * R), (bx, "radius", R)):
            axis.plot(dd, np.array([0] + [float(r["getfem_" + key]) for r in sel]) / scale, "-", color=color, lw=3, alpha=0.4, label="GetFEM 5.4, phi = %g" % phi)
            axis.plot(dd, np.array([0] + [float(r["ssstar_" + key]) for r in sel]) / scale, "o", color=color, ms=4, label="ssstar, phi = %g" % phi)
    ax.set_ylabel("normal force / (E R^2)")
    bx.set_ylabel("contact radius / R (outermost loaded node, current)")
    for axis in (ax, bx):
        axis.set_xlabel("indentation delta / R")
        axis.legend(fontsize=8)
        axis.grid(alpha=0.3)
    fig.suptitle("neo-Hookean half ball pressed on a rigid plane (scenes/hemisphere.opts)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--level", type=int, default=2)
    parser.add_argument("--steps", type=int, default=6)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--phi", default="0,0.3")
    parser.add_argument("--reference", help="write GetFEM's curves alone into this CSV file (no ssstar run)")
    args = parser.parse_args()
    environment()
    phis = [float(p) for p in args.phi.split(",")]
    if args.reference:
        mesh = warm_up(args.level)
        with open(args.reference, "w", newline="") as f:
            f.write("# bench/getfem_ball.py --level %d --steps %d --phi %s --reference %s (GetFEM 5.4, %s)\n" % (args.level, args.steps, args.phi, os.path.relpath(args.reference, ROOT), time.strftime("%Y-%m-%d")))
            w = csv.writer(f)
            w.writerow(["phi", "delta", "force", "radius", "iterations"])
            for phi in phis:
                for d, force, rad, its in getfem(mesh, args.steps, phi)[0]:
                    w.writerow([phi, "%.6g" % d, "%.10g" % force, "%.10g" % rad, its])
        return
    rows, times = [], []
    print("level %d, %d steps to delta = 0.3 R; ssstar: examples/contact, one rank, the whole run; GetFEM 5.4: one process, MUMPS, Alart-Curnier" % (args.level, args.steps))
    mesh = warm_up(args.level)
    for phi in phis:
        for rep in range(args.repeat):
            y = yardstick(args.level)
            g, tg = getfem(mesh, args.steps, phi)
            s, ts, _ = ssstar(args.level, args.steps, phi)
            times.append({"phi": phi, "repeat": rep, "yardstick_amg": y, "getfem_whole": tg, "ssstar_whole": ts, "ratio": tg / ts, "getfem_iterations": sum(r[3] for r in g),
                          "ssstar_iterations": sum(r[3] for r in s)})
            print("phi %g repeat %d: yardstick (AMG) %.3f s; GetFEM %.2f s (%d Newton iterations), ssstar %.2f s (%d iterations), GetFEM / ssstar %.2f" % (
                phi, rep, y, tg, times[-1]["getfem_iterations"], ts, times[-1]["ssstar_iterations"], tg / ts), flush=True)
        print("  delta/R   ssstar force   GetFEM force  rel. diff   Hertz force  radius ssstar  GetFEM  its ssstar GetFEM")
        for a, b in zip(s, g):
            rows.append({"phi": phi, "delta": a[0], "ssstar_force": a[1], "getfem_force": b[1], "rel_diff": (a[1] - b[1]) / b[1], "hertz_force": float(hertz(a[0])),
                         "ssstar_radius": a[2], "getfem_radius": b[2], "ssstar_iterations": a[3], "getfem_iterations": b[3]})
            r = rows[-1]
            print("  %7.3f %14.6g %14.6g %10.2e %13.6g %14.4f %7.4f %7d %6d" % (a[0] / R, r["ssstar_force"], r["getfem_force"], r["rel_diff"], r["hertz_force"], r["ssstar_radius"],
                                                                               r["getfem_radius"], a[3], b[3]))
        sel = [t for t in times if t["phi"] == phi]
        print("  medians of %d: yardstick %.3f s, GetFEM %.2f s, ssstar %.2f s, GetFEM / ssstar %.2f (the ratio of the same repeats)" % (
            len(sel), statistics.median(t["yardstick_amg"] for t in sel), statistics.median(t["getfem_whole"] for t in sel), statistics.median(t["ssstar_whole"] for t in sel), statistics.median(t["ratio"] for t in sel)))
    for name, table in (("getfem_ball.csv", rows), ("getfem_ball_times.csv", times)):
        with open(os.path.join(OUT, name), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(table[0]))
            w.writeheader()
            w.writerows(table)
    plot(rows, os.path.join(OUT, "getfem_ball.png"))
    print("wrote bench/output/getfem_ball.csv, getfem_ball_times.csv, getfem_ball.png")


if __name__ == "__main__":
    sys.exit(main())
