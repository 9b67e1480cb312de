#!/usr/bin/python3
"""The robustness family of issue 18, swept: nearly floating bodies (soft springs against a stiff body) under tilted
rollers, rigid balls and two-body pairs, sheared, with friction from 0.1 to 2, on 1 to 4 ranks, on both paths. Per
case and ranks: the dense route's (-snes_ssstar_reduction direct) and the whole body's (none) iterations and reason,
and the largest difference of the whole body's displacement (whole field) to the dense route's on the same ranks,
relative to the largest displacement. Prints a markdown table and the line "N cases x ranks: dense converged D, whole
body converged W, same answer S (of those where the dense route converged)".

  bench/robust.py [--ranks 1,2,3,4] [--only SUBSTRING] [--rtol 1e-12]

tests/suite_robust.py runs a few members of the same family (FAMILY below) as tests.
"""
import argparse
import math
import os
import re
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output", "robust")
CONTACT = os.path.join(ROOT, "examples", "contact")
SUMMARY = re.compile(r"summary: .* iterations (\d+) states \S+ ([\d/]+) (\S+)")
TIMEOUT = 300  # seconds: a run this long at these sizes hangs
KRYLOV = re.compile(r"last solve: \d+ linear solves, (\d+) Krylov iterations")


def scene(name):
    return ["-options_file", os.path.join(ROOT, "scenes", name + ".opts")]


def axis(degrees):
    a = math.radians(degrees)
    return "cylinder:0,0,10,%.6f,%.6f,0,10" % (math.cos(a), math.sin(a))


ROLLER = scene("tilted_roller")
BALL = ROLLER + ["-obstacle_top", "sphere:0,0,10,10"]

# name -> options: the members of the family
FAMILY = {
    "roller 30°, shear 0.22": ROLLER,
    "roller 30°, shear -0.22": ROLLER + ["-traction_bottom", "-66,0,300"],
    "roller 0°, shear -0.22": ROLLER + ["-obstacle_top", axis(0), "-traction_bottom", "-66,0,300"],
    "roller 45°, shear 0.22 along y": ROLLER + ["-obstacle_top", axis(45), "-traction_bottom", "0,66,300"],
    "roller 60°, shear 0.4": ROLLER + ["-obstacle_top", axis(60), "-traction_bottom", "120,0,300"],
    "roller 30°, shear along the axis": ROLLER + ["-traction_bottom", "57.2,33,300"],
    "roller 30°, k = 1e-3": ROLLER + ["-spring_bottom", "1e-3"],
    "roller 30°, k = 1e-1": ROLLER + ["-spring_bottom", "1e-1"],
    "roller 30°, k = 1e2": ROLLER + ["-spring_bottom", "1e2"],
    "roller 30°, phi = 0.1 (slides)": ROLLER + ["-friction_top", "0.1"],
    "roller 30°, phi = 0.3": ROLLER + ["-friction_top", "0.3"],
    "roller 30°, phi = 1": ROLLER + ["-friction_top", "1"],
    "roller 30°, phi = 2": ROLLER + ["-friction_top", "2"],
    "ball, phi = 0.3, shear 0.22": BALL + ["-friction_top", "0.3"],
    "ball, phi = 0.1, shear 0.22 (slides)": BALL + ["-friction_top", "0.1"],
    "ball, phi = 2, shear 0.3 diagonal": BALL + ["-friction_top", "2", "-traction_bottom", "64,64,300"],
    "ball, k = 1e-3, phi = 0.5": BALL + ["-spring_bottom", "1e-3"],
    "slider (pair), phi = 0.5": scene("slider"),
    "slider (pair), phi = 0.9 (sticks)": scene("slider") + ["-friction_slider_bottom", "0.9"],
    "mindlin (pair), Q = 0.5 phi P": scene("mindlin"),
    "mindlin (pair), Q = 0.9 phi P, phi = 0.1": scene("mindlin") + ["-friction_cap", "0.1", "-traction_block_top", "-3.534,0,0"],
}


def env():
    e = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    return e


def solve(options, path, ranks, h5, rtol):
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), CONTACT] + options + ["-snes_ssstar_reduction", path, "-snes_rtol", str(rtol), "-snes_view", "-o", h5]
    try:
        p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env(), timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return {"iters": -1, "states": "", "reason": "HUNG (killed after %d s)" % TIMEOUT, "krylov": None}
    m = SUMMARY.search(p.stdout)
    if not m:
        tail = p.stdout.strip().splitlines()[-1:] or ["no output"]
        return {"iters": -1, "states": "", "reason": "ERROR: " + tail[0][:60], "krylov": None}
    k = KRYLOV.search(p.stdout)
    return {"iters": int(m.group(1)), "states": m.group(2), "reason": m.group(3), "krylov": int(k.group(1)) if k else None}


def field(h5):
    """the displacement, ordered by vertex coordinates (the vertex order follows the partition)"""
    with h5py.File(h5, "r") as f:
        x, u = f["geometry/vertices"][:], f["fields/displacement"][:]
    return u[np.lexsort((x[:, 2], x[:, 1], x[:, 0]))]


def difference(a, b):
    ua, ub = field(a), field(b)
    return float(np.abs(ua - ub).max() / np.abs(ua).max())


def run_case(name, options, ranks, rtol):
    """both paths on the given ranks: (dense, whole body, difference or None)"""
    tag = re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_")
    files = {p: os.path.join(OUT, "%s_%s_%d.h5" % (tag, p, ranks)) for p in ("direct", "none")}
    dense = solve(options, "direct", ranks, files["direct"], rtol)
    full = solve(options, "none", ranks, files["none"], rtol)
    diff = None
    if dense["reason"].startswith("CONVERGED") and full["reason"].startswith("CONVERGED"):
        diff = difference(files["direct"], files["none"])
    return dense, full, diff


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--ranks", default="1,2,3,4")
    parser.add_argument("--only", default="")
    parser.add_argument("--rtol", type=float, default=1e-13, help="-snes_rtol of both paths (nearly floating bodies: the error is about 1e4 ||z||)")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    ranks = [int(r) for r in args.ranks.split(",")]
    print("| case | ranks | dense: its, reason | whole body: its (Krylov), reason | difference |")
    print("|---|---|---|---|---|")
    total = dense_ok = full_ok = same = 0
    for name, options in FAMILY.items():
        if args.only not in name:
            continue
        for r in ranks:
            d, f, diff = run_case(name, options, r, args.rtol)
            total += 1
            dense_ok += d["reason"].startswith("CONVERGED")
            full_ok += d["reason"].startswith("CONVERGED") and f["reason"].startswith("CONVERGED")
            same += diff is not None and diff <= 1e-8 and d["states"] == f["states"]
            print("| %s | %d | %d, %s | %d (%s), %s | %s%s |" % (name, r, d["iters"], d["reason"], f["iters"], f["krylov"], f["reason"],
                                                             "—" if diff is None else "%.1e" % diff, "" if d["states"] == f["states"] else ", states differ"), flush=True)
    print("%d cases x ranks: dense converged %d, whole body converged %d, same answer %d (of those where the dense route converged)" % (total, dense_ok, full_ok, same))
    sys.exit(0 if full_ok == dense_ok == same else 1)


if __name__ == "__main__":
    main()
