#!/usr/bin/python3
"""The robustness family of issue 18, swept: nearly floating bodies (soft springs against a stiff body) under tilted
rollers, rigid balls and two-body pairs, sheared, with friction from 0.1 to 2, on 1 to 4 ranks, on both paths. Per
case and ranks: the dense route's (-snes_ssstar_reduction direct) and the whole body's (none) iterations and reason,
and the largest difference of the whole body's displacement (whole field) to the dense route's on the same ranks,
relative to the largest displacement. Prints a markdown table and the line "N cases x ranks: dense converged D, whole
body converged W, same answer S (of those where the dense route converged)".

The floating family of issue 25 (FLOATING below): bodies held by contact alone, no spring (README "Bodies held by
contact alone"): slopes at several phi / tan alpha, stacks, squeezed balls, a slider pushed on its base. Where an
equilibrium exists both paths must converge to the same answer; where none exists both must stop before their first
iteration (DIVERGED_DTOL, "no equilibrium") within EARLY seconds. It ends with the line "N floating cases x ranks:
converged C of E expected, the same answer S, early exits X of Y expected".

  bench/robust.py [--family robust,floating] [--ranks 1,2,3,4] [--only SUBSTRING] [--rtol 1e-12]

tests/suite_robust.py runs a few members of the first family (FAMILY below) as tests, tests/suite_floating.py of the
second.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import time

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


SLOPE = scene("slope") + ["-level", "4"]
TAN = math.tan(math.radians(20))
DOWNHILL = (math.cos(math.radians(20)), 0, -math.sin(math.radians(20)))
STACK = scene("stack")
SQUEEZE = scene("squeeze")
SLIDER = ["-geo", "meshes/slider.geo", "-level", "1", "-E", "1", "-nu", "0.3", "-dirichlet", "bottom", "-contact", "slider_bottom",
          "-contact_pair_slider_bottom", "base_top", "-friction_slider_bottom", "0.5"]
EARLY = 30  # seconds: a run without equilibrium must stop within this (mesh and set-up included)


def push(pressure):
    return "%g,0,%g" % (pressure * DOWNHILL[0], pressure * DOWNHILL[2])


# name -> (options, an equilibrium exists)
FLOATING = {
    "slope, phi = 0 (frictionless)": (SLOPE + ["-friction_bottom", "0"], False),
    "slope, phi / tan a = 0.5": (SLOPE + ["-friction_bottom", str(0.5 * TAN)], False),
    "slope, phi / tan a = 0.9": (SLOPE + ["-friction_bottom", str(0.9 * TAN)], False),
    "slope, phi / tan a = 0.999": (SLOPE + ["-friction_bottom", str(0.999 * TAN)], False),
    "slope, phi / tan a = 1.001": (SLOPE + ["-friction_bottom", str(1.001 * TAN)], True),
    "slope, phi / tan a = 1.02": (SLOPE + ["-friction_bottom", str(1.02 * TAN)], True),
    "slope, phi / tan a = 1.2": (SLOPE + ["-friction_bottom", str(1.2 * TAN)], True),
    "slope, phi / tan a = 1.37 (scene)": (SLOPE, True),
    "slope, phi / tan a = 3": (SLOPE + ["-friction_bottom", str(3 * TAN)], True),
    "slope, pushed downhill 400 Pa (holds)": (SLOPE + ["-traction_top", push(400)], True),
    "slope, pushed downhill 800 Pa (slides)": (SLOPE + ["-traction_top", push(800)], False),
    "stack, phi = 0.5": (STACK, True),
    "stack, frictionless (least norm)": (STACK + ["-snes_ssstar_friction", "0"], True),
    "stack, lid pushed by 0.4 of its weight": (STACK + ["-traction_top", "1962,0,0"], True),
    "stack, lid pushed by 0.6 of its weight": (STACK + ["-traction_top", "2943,0,0"], False),
    "squeeze, frictionless": (SQUEEZE, True),
    # two steps: the path matters with friction, and in one step the dense route halves it where the whole body does not
    "squeeze, phi = 0.3, two steps": (SQUEEZE + ["-friction_law_bottom_cap", "coulomb", "-friction_law_top_cap", "coulomb", "-snes_ssstar_friction", "0.3", "-steps", "2"], True),
    "slider (pair), push 0.8 of phi N (holds)": (SLIDER + ["-traction_slider_top", "0.004,0,-0.01"], True),
    "slider (pair), push 1.6 of phi N": (SLIDER + ["-traction_slider_top", "0.008,0,-0.01"], False),
}


def env():
    e = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    return e


def solve(options, path, ranks, h5, rtol):
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), CONTACT] + options + ["-snes_ssstar_reduction", path, "-snes_rtol", str(rtol), "-snes_view", "-o", h5]
    t0 = time.time()
    try:
        p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env(), timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return {"iters": -1, "states": "", "reason": "HUNG (killed after %d s)" % TIMEOUT, "krylov": None, "seconds": TIMEOUT, "noeq": False}
    m = SUMMARY.search(p.stdout)
    if not m:
        tail = p.stdout.strip().splitlines()[-1:] or ["no output"]
        return {"iters": -1, "states": "", "reason": "ERROR: " + tail[0][:60], "krylov": None, "seconds": time.time() - t0, "noeq": False}
    k = KRYLOV.search(p.stdout)
    return {"iters": int(m.group(1)), "states": m.group(2), "reason": m.group(3), "krylov": int(k.group(1)) if k else None, "seconds": time.time() - t0,
            "noeq": "no equilibrium: " in p.stdout}


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


def floating(ranks, only, rtol):
    """the floating family: True when every case converges or stops early as expected"""
    print("| floating case | ranks | dense: its, reason, s | whole body: its (Krylov), reason, s | difference |")
    print("|---|---|---|---|---|")
    total = expected = converged = same = early = expected_early = 0
    for name, (options, exists) in FLOATING.items():
        if only not in name:
            continue
        for r in ranks:
            d, f, diff = run_case(name, options, r, rtol)
            total += 1
            if exists:
                expected += 1
                converged += d["reason"].startswith("CONVERGED") and f["reason"].startswith("CONVERGED")
                same += diff is not None and diff <= 1e-8
            else:
                expected_early += 1
                early += all(x["reason"] == "DIVERGED_DTOL" and x["iters"] == 0 and x["noeq"] and x["seconds"] <= EARLY for x in (d, f))
            print("| %s | %d | %d, %s, %.1f | %d (%s), %s, %.1f | %s |" % (name, r, d["iters"], d["reason"], d["seconds"], f["iters"], f["krylov"], f["reason"], f["seconds"],
                                                                      "—" if diff is None else "%.1e" % diff), flush=True)
    print("%d floating cases x ranks: converged %d of %d expected, the same answer %d, early exits %d of %d expected" % (total, converged, expected, same, early, expected_early))
    return converged == expected == same and early == expected_early


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--family", default="robust,floating")
    parser.add_argument("--ranks", default="1,2,3,4")
    parser.add_argument("--only", default="")
    parser.add_argument("--rtol", type=float, default=1e-13, help="-snes_rtol of both paths (nearly floating bodies: the error is about 1e4 ||z||)")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    ranks = [int(r) for r in args.ranks.split(",")]
    ok = True
    if "floating" in args.family:
        ok = floating(ranks, args.only, args.rtol)
    if "robust" not in args.family:
        sys.exit(0 if ok else 1)
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
    sys.exit(0 if ok and full_ok == dense_ok == same else 1)


if __name__ == "__main__":
    main()
