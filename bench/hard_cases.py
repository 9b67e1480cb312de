#!/usr/bin/python3
"""The hard cases of issue 5, measured: per case the iterations, the reason, the remedies of the globalization and
the distance of the contact displacement to a tight reference solve (the same scene with -snes_rtol 1e-14), with
the plain iteration (-snes_ssstar_globalization false) beside it. Prints a markdown table.

  bench/hard_cases.py [--levels 4] [--only SUBSTRING]
"""
import argparse
import os
import re
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PRISM = os.path.join(ROOT, "examples", "prism")
OUT = os.path.join(ROOT, "bench", "output")
TANGENTIAL = ["-traction_top", "2000,800,-500"]
REMEDIES = re.compile(r"remedies: damped steps (\d+), full steps after a failed line search (\d+), rescalings of gamma (\d+), "
                      r"regularized Newton steps (\d+), fixed-point rounds (\d+); cycles detected (\d+)")
SUMMARY = re.compile(r"^\s*-?\d+\s+\d+\s+\d+\s+[\d.]+\s+[\d.]+\s+\d+\s+[\d.]+\s+(\d+)\s+[\d/]+\s+[\d/]+\s+(\S+)", re.M)


def cases(level):
    loads = lambda s: ["-traction_top", "0,0,%g" % (-500 * s), "-traction_right", "%g,%g,%g" % (-200 * s, 30 * s, 200 * s)]
    yield "default scene", level, []
    for phi in (0.6, 1, 2, 3, 5):
        yield "phi = %g" % phi, level, ["-snes_ssstar_friction", str(phi)]
    for phi in (0.6, 1, 2, 3, 5):
        yield "tangential load, phi = %g" % phi, level, TANGENTIAL + ["-snes_ssstar_friction", str(phi)]
    for L in range(3, 9):
        yield "frictionless", L, ["-snes_ssstar_friction", "0"]
    yield "weak contact (nu = 0, sliding load)", level, ["-nu", "0", "-traction_top", "0,0,0", "-traction_right", "-200,0,0"]
    yield "near-grazing load", level, ["-traction_top", "0,0,-0.01", "-traction_right", "-200,30,0"]
    for L in (4, 6, 8):
        for nu in ("0.45", "0.49", "0.499"):
            yield "nu = %s" % nu, L, ["-nu", nu]
    yield "Pa/m (E = 2.1e11)", level, ["-mesh_scale", "1e-3", "-E", "2.1e11"] + loads(1e6)
    yield "loads x 1e-6", level, loads(1e-6)
    yield "loads x 1e6", level, loads(1e6)
    yield "start: linear-elastic solution", level, ["-initial_guess", "elastic"]
    yield "start: random, 100x the solution", level, ["-initial_guess", "random", "-initial_guess_scale", "0.1"]
    yield "zero load", 3, ["-traction_top", "0,0,0", "-traction_right", "0,0,0"]
    yield "lift-off", 3, ["-traction_top", "0,0,500"]
    yield "sliding everywhere (phi = 0.1)", 3, ["-snes_ssstar_friction", "0.1", "-traction_top", "0,0,-500", "-traction_right", "-2000,0,0"]


def solve(level, options, h5):
    cmd = [PRISM, "-level", str(level), "-snes_view", "-snes_converged_reason", "-o", h5] + options
    out = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    m, r = SUMMARY.search(out), REMEDIES.search(out)
    if not m or not r:
        sys.exit("no summary from " + " ".join(cmd) + "\n" + out[-2000:])
    sub = re.search(r"ssstar: (\S+),", out).group(1)
    names = ("damped", "full", "gamma x2", "regularized", "fixed-point", "cycles")
    used = ", ".join("%s %s" % (n, c) for n, c in zip(names, r.groups()) if c != "0") or "none"
    return int(m.group(1)), "%s (%s)" % (m.group(2), sub), used


def displacement(h5):
    with h5py.File(h5, "r") as f:
        return f["contact/displacement"][:]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--levels", type=int, default=4, help="level of the cases that have no level of their own")
    parser.add_argument("--only", default="", help="only the cases whose name contains this")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    print("| case | level | iterations | reason | remedies | error vs tight reference | plain iteration |")
    print("|---|---|---|---|---|---|---|")
    for name, level, options in cases(args.levels):
        if args.only not in name:
            continue
        h5, ref, plain = (os.path.join(OUT, "hard_%s.h5" % k) for k in ("case", "reference", "plain"))
        its, reason, used = solve(level, options, h5)
        solve(level, options + ["-snes_rtol", "1e-14"], ref)
        u, uref = displacement(h5), displacement(ref)
        error = np.abs(u - uref).max() / np.abs(uref).max() if np.abs(uref).max() > 0 else np.abs(u).max()
        pits, preason, _ = solve(level, options + ["-snes_ssstar_globalization", "false"], plain)
        print("| %s | %d | %d | %s | %s | %.1e | %d, %s |" % (name, level, its, reason, used, error, pits, preason), flush=True)


if __name__ == "__main__":
    main()
