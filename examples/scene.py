#!/usr/bin/python3
"""Scenes from Python (ssstar.Scene, the C scene library of examples/contact): four uses.

  examples/scene.py run FILE.opts [-option value ...]   examples/contact -options_file FILE.opts [-option value ...]
                                                          in Python: the same scene, steps, answers and -o file
  examples/scene.py block [--out block.h5]               the README's block load path (press, shear past phi P,
                                                          release, shear back, release), one line per step
  examples/scene.py sweep [--ratios 0.5,...] [--out sweep.png] [--split] [--csv f]
                                                          the residual slip of the block after press, shear Q and
                                                          release, against Q/(phi P), beside (11.2): max(0, Q - phi P)/k
  examples/scene.py onset [--out onset.h5]               a load path decided by its own loop: the shear raised step by
                                                          step, a step that makes more than 8 nodes begin to slide
                                                          refused and halved, until no node sticks

PETSc's options after them apply to every scene (-snes_rtol 1e-12, -snes_ssstar_reduction none, ...); under mpiexec
every rank makes the same scenes (sweep --split: each rank solves its own points alone, on PETSC_COMM_SELF, and rank 0
gathers them through mpi4py).
"""
import argparse
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
import petsc4py  # noqa: E402

petsc4py.init(sys.argv)
from petsc4py import PETSc  # noqa: E402

import numpy as np  # noqa: E402

import ssstar  # noqa: E402  (the source tree's python/ssstar, or the installed one)

# The block of the README's load path: 1 x 1 x 0.5 on the plane z = 0, nearly rigid (E = 2e8) on a soft spring
# k = 1000 per unit area on its top (area 1), pressed by P = 10 on its top, Coulomb friction phi = 0.5
BLOCK = dict(geo=os.path.join(ROOT, "meshes", "block.geo"), level=2, E=2e8, nu=0.3, spring={"top": 1000},
             contact=["bottom"], friction={"bottom": 0.5})
P, PHI, K = 10.0, 0.5, 1000.0


def say(*args):
    PETSc.Sys.Print(" ".join(str(a) for a in args))


def step_line(step):
    """examples/contact's line of a step"""
    r = step.row
    return "t %g: load (%.6g, %.6g, %.6g) normal force %.6g tangential force (%.6g, %.6g, %.6g) area %.6g sliding %d of %d touching, %d iterations%s" % (
        step.time, *r["load"], r["normal_force"], *r["tangential_force"], r["area"], r["sliding"], r["sliding"] + r["sticking"],
        step.iterations, "" if step.converged else ", not converged (%s)" % step.reason)


def options_of(args):
    """-name value pairs (and -flag) after the file, as keywords of Scene()"""
    options, k = {}, 0
    while k < len(args):
        name = args[k]
        if not (name.startswith("-") and len(name) > 1 and name[1].isalpha()):
            sys.exit("scene.py run: %s is no option (-name value)" % name)
        value = args[k + 1] if k + 1 < len(args) and not (args[k + 1].startswith("-") and args[k + 1][1:2].isalpha()) else True
        options[name[1:]] = value
        k += 1 if value is True else 2
    return options


def run(args):
    """A scene of examples/contact in Python: solve() does what examples/contact does, o=... writes its file"""
    with ssstar.Scene(args.file, **options_of(args.options)) as scene:
        scene.view()
        last = scene.solve()
        if scene.has_path:
            say("steps:", scene.knots if last is None else "last at t %g" % last.time)
        say(step_line(last))
        say("iterations %d in all (examples/contact's summary)" % scene.iterations)
        return 0 if last.converged else 2


def block(args):
    """The README's load path: press (t = 1), shear to Q = 7.5 > phi P (2), release (3), shear back (4), release (5)"""
    history = [(0, (0, 0, 0)), (1, (0, 0, -P)), (2, (7.5, 0, -P)), (3, (0, 0, -P)), (4, (-7.5, 0, -P)), (5, (0, 0, -P))]
    with ssstar.Scene(traction={"top": history}, **BLOCK) as scene:
        if args.out:
            scene.write(args.out)
        for step in scene.steps():
            say(step_line(step), "top u_x %.6g" % step.row["groups/top/displacement"][0])
    return 0


def residual_slip(ratio, comm=None):
    """Press P, shear Q = ratio phi P, release: the mean slip of the contact face along x (the block stays where it
    slid), and the path's last step"""
    Q = ratio * PHI * P
    history = [(0, (0, 0, 0)), (1, (0, 0, -P)), (2, (Q, 0, -P)), (3, (0, 0, -P))]
    with ssstar.Scene(traction={"top": history}, comm=comm, **BLOCK) as scene:
        for step in scene.steps():
            if not step.converged:
                raise RuntimeError("Q/(phi P) = %g: the step at t %g did not converge (%s)" % (ratio, step.time, step.reason))
        return float(np.mean(step.contact["slip"][:, 0])), step


def sweep(args):
    ratios = [float(x) for x in args.ratios.split(",")]
    if args.split:  # each rank its own points, alone; rank 0 gathers them
        from mpi4py import MPI
        world = MPI.COMM_WORLD
        mine = {i: residual_slip(r, comm=PETSc.COMM_SELF)[0] for i, r in enumerate(ratios) if i % world.size == world.rank}
        slips = {}
        for part in world.allgather(mine):
            slips.update(part)
        slips = [slips[i] for i in range(len(ratios))]
    else:
        slips = [residual_slip(r)[0] for r in ratios]
    say("Q/(phi P)  Q        residual slip   (11.2) max(0, Q - phi P)/k")
    for r, s in zip(ratios, slips):
        say("%-10.4g %-8.4g %-15.9g %.9g" % (r, r * PHI * P, s, max(0.0, (r - 1) * PHI * P) / K))
    if args.csv and PETSc.COMM_WORLD.getRank() == 0:
        with open(args.csv, "w") as f:
            f.write("ratio,Q,residual_slip,closed_form\n")
            for r, s in zip(ratios, slips):
                f.write("%r,%r,%r,%r\n" % (r, r * PHI * P, s, max(0.0, (r - 1) * PHI * P) / K))
    if args.out and PETSc.COMM_WORLD.getRank() == 0:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fine = np.linspace(0, max(ratios) * 1.05, 200)
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot(fine, np.maximum(0, (fine - 1) * PHI * P) / K * 1e3, "k-", lw=1, label="(11.2): max(0, Q - φP)/k")
        ax.plot(ratios, np.array(slips) * 1e3, "o", color="C3", label="ssstar.Scene, level 2")
        ax.set_xlabel("Q / (φ P)")
        ax.set_ylabel("residual slip after release [10⁻³]")
        ax.set_title("block on a spring: press P = 10, shear Q, release\n(φ = 0.5, k = 1000 per unit area; ssstar.Scene)", fontsize=10)
        ax.legend()
        fig.tight_layout()
        fig.savefig(args.out, dpi=120)
        say("wrote", args.out)
    return 0


def onset(out=None):
    """A load path decided by its own loop (the example of docs/guide/python.md): press the block, then raise the shear Q; a step
    that makes more than 8 nodes begin to slide is refused (accept=False) and halved, until no node sticks"""
    scene = ssstar.Scene(geo=os.path.join(ROOT, "meshes", "block.geo"), level=2, E=2e8, nu=0.3, spring={"top": 1000}, contact=["bottom"],
                         friction={"bottom": 0.5}, traction={"top": (0, 0, -10)})
    if out:
        scene.write(out)                          # every accepted step goes into the file
    last = scene.step(0)                          # pressed by P = 10, no shear: most nodes stick
    Q, dQ = 0.0, 1.0
    while last.sticking().any() and dQ > 1e-3:
        scene.set(traction={"top": (Q + dQ, 0, -10)})
        step = scene.step(Q + dQ, accept=False)   # tentative; its time is the shear
        if step.converged and (step.sliding() & ~last.sliding()).sum() <= 8:
            Q, last = Q + dQ, scene.accept()      # at most 8 nodes began to slide: go on from there
        else:
            dQ /= 2                               # too many at once: a smaller step
    say("no node sticks from Q = %.6g on (phi P = 5): %d nodes slide, %d separated" % (Q, last.sliding().sum(), last.separated().sum()))
    scene.close()
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="use", required=True)
    p = sub.add_parser("run", help="a scene's options file, as examples/contact")
    p.add_argument("file")
    p.add_argument("options", nargs=argparse.REMAINDER)
    p = sub.add_parser("block", help="the README's block load path")
    p.add_argument("--out", help="write the path's file (HDF5 + XDMF), as examples/contact -o")
    p = sub.add_parser("sweep", help="the residual slip against Q/(phi P)")
    p.add_argument("--ratios", default="0.25,0.5,0.75,0.9,1.1,1.25,1.5,1.75,2")
    p.add_argument("--out", default="sweep.png", help="the picture (matplotlib)")
    p.add_argument("--split", action="store_true", help="each rank its own points on PETSC_COMM_SELF (mpi4py)")
    p.add_argument("--csv", help="write the table (ratio, Q, residual slip, (11.2)) with every digit")
    p = sub.add_parser("onset", help="a load path decided by its own loop")
    p.add_argument("--out", help="write the path's file (HDF5 + XDMF)")
    args, petsc = parser.parse_known_args([a for a in sys.argv[1:]])
    if args.use == "run":
        return run(args)
    return {"block": block, "sweep": sweep, "onset": lambda a: onset(a.out)}[args.use](args)


if __name__ == "__main__":
    sys.exit(main())
