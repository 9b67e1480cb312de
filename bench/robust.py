#!/usr/bin/python3
"""The robustness families of issues 18 and 23, at the default settings. Every member runs on both paths (the dense
route, -snes_ssstar_reduction direct, and the whole body, none) on 1 to 4 ranks and must

  converge (every step of a load path),
  write a file whose every step passes tests/check_solution.py (the friction law as written, docs/derivation.md
  section 12), and
  agree with the exact discrete solution, the dense route on one rank at -snes_rtol 1e-13, to 1e-6 at every step (each
  relative to its own scale: the step's values and their change from the step before; tests/check_solution.py compare
  --steps).

  static: nearly floating bodies (soft springs against a stiff body) under tilted rollers and rigid balls, two-body
          pairs, sheared, friction from 0.1 to 2 (issue 18)
  paths:  load paths (issue 23): stiff blocks on soft springs pressed, sheared past sliding, released, reversed and
          released; a plane dragging a block forward and back (it sticks and returns; or slides back); a ball pressed
          and lifted off, a cylinder pressed and rolled forth and back; the tilted roller and the two-body pairs loaded
          forth and back

Prints a markdown table (and bench/output/robust.csv): per member and ranks, each path's iterations (Krylov iterations
of the whole body), reason, law (check_solution's largest distance to the law over the steps) and error (to the exact
solution), then "N members x ranks: converged C of R runs, the law holds in L, within 1e-6 of the exact solution E";
the exit status is 0 when every run passes.

  bench/robust.py [--family static|paths|all] [--ranks 1,2,3,4] [--only SUBSTRING]

tests/suite_robust.py runs members of both families (FAMILY, PATHS below) as tests.
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from loadpath_check import mindlin_scene_args  # noqa: E402

OUT = os.path.join(ROOT, "bench", "output", "robust")
CONTACT = os.path.join(ROOT, "examples", "contact")
CHECK = ["/usr/bin/python3", os.path.join(ROOT, "tests", "check_solution.py")]
SUMMARY = re.compile(r"summary: .* iterations (\d+) states \S+ ([\d/]+) (\S+)")
KRYLOV = re.compile(r"last solve: \d+ linear solves, (\d+) Krylov iterations")
DISTANCE = re.compile(r"^distance to the law\s+(\S+)", re.M)
DIFFERENCE = re.compile(r"^(?:displacement|reaction|full field)\s+max difference\s+(\S+)", re.M)
TIMEOUT = 600  # seconds: a run this long at these sizes hangs
TOLERANCE = 1e-6  # the error to the exact discrete solution at the defaults (README "What converged means")


def scene(name):
    return ["-options_file", os.path.join(ROOT, "scenes", name + ".opts")]


def axis(degrees):
    a = math.radians(degrees)
    return "cylinder:0,0,10,%.6f,%.6f,0,10" % (math.cos(a), math.sin(a))


def history(*knots):
    """"t:x,y,z;..." of the knots (x, y, z) at t = 0, 1, 2, ..."""
    return ";".join("%d:%s" % (t, ",".join("%.10g" % v for v in k)) for t, k in enumerate(knots))


ROLLER = scene("tilted_roller")
BALL = ROLLER + ["-obstacle_top", "sphere:0,0,10,10"]

# static members: name -> options
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
    "ball, k = 1e-3, sheared obliquely": BALL + ["-spring_bottom", "1e-3", "-traction_bottom", "40,25,300"],
    "slider (pair), phi = 0.5": scene("slider"),
    "slider (pair), phi = 0.9 (sticks)": scene("slider") + ["-friction_slider_bottom", "0.9"],
    "mindlin (pair), Q = 0.5 phi P": scene("mindlin"),
    "mindlin (pair), Q = 0.9 phi P, phi = 0.1": scene("mindlin") + ["-friction_cap", "0.1", "-traction_block_top", "-3.534,0,0"],
}

# a block 1 x 1 x 0.5 (meshes/block.geo, level 2) on the plane z = 0, held sideways only by a spring on its top
# (k = 1000 per unit area): nearly rigid against it (E = 2e8, E/k = 2e5)
BLOCK = ["-geo", "meshes/block.geo", "-level", "2", "-E", "2e8", "-nu", "0.3", "-spring_top", "1000", "-contact", "bottom"]
# pressed by P = 1, held there while the plane moves by d1 along x (it drags the block until the spring holds phi P)
# and then back to d2
def dragged(d1, d2):
    return BLOCK + ["-friction_bottom", "0.5", "-traction_top", history((0, 0, 0), (0, 0, -1)),
                    "-obstacle_bottom_motion", history((0, 0, 0), (0, 0, 0), (d1, 0, 0), (d2, 0, 0))]


# load-path members: name -> options
PATHS = {
    "block on a spring: press, shear 1.5 phi P, release, reverse, release (the README's)":
        BLOCK + ["-friction_bottom", "0.5", "-traction_top", history((0, 0, 0), (0, 0, -10), (7.5, 0, -10), (0, 0, -10), (-7.5, 0, -10), (0, 0, -10))],
    "stiff block, loads of order 1: press, shear both ways past sliding, release to zero, 20 steps":
        BLOCK + ["-friction_bottom", "0.4", "-traction_top", history((0, 0, 0), (0, 0, -1), (0.6, 0, -1), (0, 0, -1), (-0.6, 0, -1), (0, 0, -1), (0, 0, 0)),
                 "-steps", "20"],
    "plane drags a block forward, then back: it sticks and returns": dragged(0.002, 0.0015),
    "plane drags a block forward, then further back: it slides back": dragged(0.002, 0.0005),
    "plane drags a block forward and back in 8 steps": dragged(0.002, 0.0015) + ["-steps", "8"],
    "tilted roller: press, shear 0.22 P, reverse, release": ROLLER + ["-traction_bottom", history((0, 0, 0), (0, 0, 300), (66, 0, 300), (-66, 0, 300), (0, 0, 300))],
    "ball, k = 1e-3: press, shear obliquely, reverse": BALL + ["-spring_bottom", "1e-3", "-traction_bottom", history((0, 0, 0), (0, 0, 300), (40, 25, 300), (-40, -25, 300))],
    "ball pressed 0.02 into a held block, then lifted off, 8 steps": ["-geo", "meshes/indent.geo", "-level", "1", "-E", "2.1e5", "-nu", "0.3", "-dirichlet", "bottom",
        "-contact", "top", "-obstacle_top", "sphere:0,0,10,10", "-friction_top", "0.5", "-obstacle_top_motion", history((0, 0, 0), (0, 0, -0.02), (0, 0, 0.01)), "-steps", "8"],
    "cylinder pressed 0.02 into a held block, rolled forward and back by 0.01, 8 steps": ["-geo", "meshes/roller.geo", "-level", "1", "-E", "2.1e5", "-nu", "0.3",
        "-dirichlet", "bottom", "-contact", "top", "-obstacle_top", "cylinder:0,0,10,0,1,0,10", "-friction_top", "0.5",
        "-obstacle_top_motion", history((0, 0, 0), (0, 0, -0.02), (0.01, 0, -0.02), (-0.01, 0, -0.02), (0, 0, -0.02)), "-steps", "8"],
    "slider (pair): push past sliding, release, reverse, release":
        scene("slider") + ["-traction_slider_top", history((0, 0, 0), (0, 0, -0.01), (0.008, 0, -0.01), (0, 0, -0.01), (-0.008, 0, -0.01), (0, 0, -0.01))],
    "mindlin (pair): P, then Q = 0.5 phi P forth and back, 4 steps per branch": mindlin_scene_args(1, 0.5, ROOT, steps_per_branch=4),
}


def env():
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")


def tag(name):
    return re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_")[:60]


def solve(options, path, ranks, h5, extra=()):
    """one run: its iterations (summed over the steps), reason, Krylov iterations"""
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), CONTACT] + options + ["-snes_ssstar_reduction", path, "-snes_view", "-ssstar_progress", "0", "-o", h5] + list(extra)
    try:
        p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env(), timeout=TIMEOUT)
    except subprocess.TimeoutExpired:
        return {"iters": -1, "reason": "HUNG (killed after %d s)" % TIMEOUT, "krylov": None}
    m = SUMMARY.search(p.stdout)
    if not m:
        tail = p.stdout.strip().splitlines()[-1:] or ["no output"]
        return {"iters": -1, "reason": "ERROR: " + tail[0][:60], "krylov": None}
    krylov = [int(k) for k in KRYLOV.findall(p.stdout)]
    return {"iters": int(m.group(1)), "reason": m.group(3) if p.returncode == 0 else "%s (exit %d)" % (m.group(3), p.returncode), "krylov": sum(krylov) if krylov else None}


def checked(result, h5, reference):
    """the file's law (every step) and its error to the reference (every step)"""
    if not result["reason"].startswith("CONVERGED"):
        result.update(law=None, error=None)
        return result
    law = subprocess.run(CHECK + ["coulomb", h5, "--steps"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    result["law"] = max(float(x) for x in DISTANCE.findall(law.stdout)) if law.returncode in (0, 1) and DISTANCE.search(law.stdout) else float("inf")
    result["law_ok"] = law.returncode == 0
    cmp = subprocess.run(CHECK + ["compare", reference, h5, "--steps", "--tol", str(TOLERANCE)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    found = DIFFERENCE.findall(cmp.stdout)
    result["error"] = max(float(x) for x in found) if found else float("inf")
    return result


REFERENCES = {}  # member -> its reference file, or None where it did not converge


def run_member(name, options, ranks):
    """the reference (dense, one rank, rtol 1e-13; once per member), then both paths at the defaults on the ranks"""
    files = {p: os.path.join(OUT, "%s_%s_%d.h5" % (tag(name), p, ranks)) for p in ("direct", "none")}
    if name not in REFERENCES:
        reference = os.path.join(OUT, "%s_reference.h5" % tag(name))
        REFERENCES[name] = reference if solve(options, "direct", 1, reference, ("-snes_rtol", "1e-13"))["reason"].startswith("CONVERGED") else None
    if REFERENCES[name] is None:
        return None
    return {p: checked(solve(options, p, ranks, files[p]), files[p], REFERENCES[name]) for p in ("direct", "none")}


def passed(r):
    return r["reason"].startswith("CONVERGED") and r.get("law_ok") and r["error"] <= TOLERANCE


def cell(r):
    if r["law"] is None:
        return "%d, %s" % (r["iters"], r["reason"])
    krylov = "" if r["krylov"] is None else " (%d)" % r["krylov"]
    return "%d%s, law %.1e%s, error %.1e" % (r["iters"], krylov, r["law"], "" if r["law_ok"] else " VIOLATED", r["error"])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--family", choices=("static", "paths", "all"), default="all")
    parser.add_argument("--ranks", default="1,2,3,4")
    parser.add_argument("--only", default="")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    ranks = [int(r) for r in args.ranks.split(",")]
    families = [(f, m) for f, m in (("static", FAMILY), ("paths", PATHS)) if args.family in (f, "all")]
    print("| family | member | ranks | dense route: its, law, error | whole body: its (Krylov), law, error |")
    print("|---|---|---|---|---|")
    rows, total, converged, lawful, exact = [], 0, 0, 0, 0
    for family, members in families:
        for name, options in members.items():
            if args.only not in name:
                continue
            for r in ranks:
                result = run_member(name, options, r)
                if result is None:
                    print("| %s | %s | %d | the reference did not converge | |" % (family, name, r), flush=True)
                    total += 2
                    continue
                print("| %s | %s | %d | %s | %s |" % (family, name, r, cell(result["direct"]), cell(result["none"])), flush=True)
                for path, res in result.items():
                    total += 1
                    converged += res["reason"].startswith("CONVERGED")
                    lawful += bool(res.get("law_ok"))
                    exact += res["error"] is not None and res["error"] <= TOLERANCE
                    rows.append([family, name, r, path, res["iters"], res["krylov"], res["reason"], res["law"], res["error"], passed(res)])
    with open(os.path.join(ROOT, "bench", "output", "robust.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["family", "member", "ranks", "path", "iterations", "krylov", "reason", "law", "error", "passed"])
        w.writerows(rows)
    print("%d members x ranks: converged %d of %d runs, the law holds in %d, within %g of the exact solution %d" % (total // 2, converged, total, lawful, TOLERANCE, exact))
    sys.exit(0 if converged == lawful == exact == total else 1)


if __name__ == "__main__":
    main()
