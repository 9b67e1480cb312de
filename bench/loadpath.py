#!/usr/bin/python3
"""The Mindlin-Deresiewicz loop of scenes/mindlin.opts as a load path against its closed forms, per level and path:
the mesh error of the energy dissipated per cycle and of the loop's opening (docs/derivation.md (11.9), (11.11)).

  bench/loadpath.py [--levels 1,2] [--amplitudes 0.5] [--paths direct] [--ranks 1] [--steps 10]

Each run: P (one step), then Q: 0 -> -Q* -> Q* -> -Q* with Q* = s phi P, --steps steps per branch (examples/contact
-steps, tests/loadpath_check.py mindlin_scene_args); the cycle's area by trapezoids of (Q, delta), delta the mean x
displacement of block_top where Q acts, and the node-wise dissipation (10.9) over the cycle, against the half-space's
closed forms with the contact's normal force. Prints a table and writes bench/output/loadpath.csv (and each run's
file bench/output/mindlin_L<level>_s<s>_<path>_<ranks>.h5, drawn by examples/plot_contact.py). Level 1 takes seconds,
level 2 minutes (1191 contact nodes)."""
import argparse
import csv
import os
import subprocess
import sys
import time

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
import loadpath_check as closed  # noqa: E402

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
OUT = os.path.join(ROOT, "bench", "output")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--levels", default="1,2")
    parser.add_argument("--amplitudes", default="0.5", help="Q*/(phi P), comma-separated")
    parser.add_argument("--paths", default="direct", help="reductions: direct, none")
    parser.add_argument("--ranks", default="1")
    parser.add_argument("--steps", type=int, default=10, help="steps per branch of the loop")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    rows = []
    print("%5s %5s %7s %5s %6s %9s %9s %7s %10s %10s %7s %9s %7s %8s" % ("level", "s", "path", "ranks", "steps", "W", "W (11.9)", "error", "opening", "(11.11)", "error", "D nodes", "D/W-1", "wall[s]"))
    for level in [int(x) for x in args.levels.split(",")]:
        for s in [float(x) for x in args.amplitudes.split(",")]:
            for path in args.paths.split(","):
                for ranks in [int(x) for x in args.ranks.split(",")]:
                    h5 = os.path.join(OUT, "mindlin_L%d_s%g_%s_%d.h5" % (level, s, path, ranks))
                    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), os.path.join(ROOT, "examples", "contact")] + \
                        closed.mindlin_scene_args(level, s, ROOT, args.steps) + ["-snes_ssstar_reduction", path, "-o", h5]
                    t0 = time.time()
                    subprocess.run(cmd, cwd=ROOT, env=ENV, check=True, stdout=subprocess.DEVNULL)
                    wall = time.time() - t0
                    m = closed.mindlin_scene_loop(h5py.File(h5, "r"))
                    row = {"level": level, "s": s, "path": path, "ranks": ranks, "steps_per_branch": args.steps, "W": m["W"], "W_closed": m["W_closed"],
                           "W_error": m["W"] / m["W_closed"] - 1, "opening": m["opening"], "opening_closed": m["opening_closed"],
                           "opening_error": m["opening"] / m["opening_closed"] - 1, "D": m["D"], "D_over_W": m["D"] / m["W"] - 1, "wall": wall}
                    rows.append(row)
                    print("%5d %5g %7s %5d %6d %9.4g %9.4g %+6.1f%% %10.4g %10.4g %+6.1f%% %9.4g %+6.1f%% %8.1f" % (
                        level, s, path, ranks, args.steps, m["W"], m["W_closed"], 100 * row["W_error"], m["opening"], m["opening_closed"],
                        100 * row["opening_error"], m["D"], 100 * row["D_over_W"], wall), flush=True)
    with open(os.path.join(OUT, "loadpath.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print("wrote " + os.path.join(OUT, "loadpath.csv"))


if __name__ == "__main__":
    main()
