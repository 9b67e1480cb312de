#!/usr/bin/python3
"""The contact search on large inputs: what it costs against the whole run (issue 18, item 4).

  bench/search.py [--cases ball,pair,mortar] [--ranks 2] [--repeat 3] [--ball-level 7] [--sphere-level 2]
                  [--pair-level 3] [--yardstick]

Cases, each through examples/contact on the whole-body path (-snes_ssstar_reduction none):
  ball    scenes/ball.opts with the block of meshes/indent.geo at --ball-level (7: about 250 000 nodes, the size of the
          prism's level 24) and the ball as a triangle mesh (-obstacle_top mesh:), meshes/ball_surface.geo meshed here
          at --sphere-level (2: 59 356 triangles), spread over the ranks
  pair    scenes/hertz2.opts at --pair-level (3: two bodies, 103 200 nodes = 310 000 dofs), node-to-surface
  mortar  the same pair with -pair_discretization dual_mortar
Per case the medians of --repeat runs: the whole run (the process's wall time, mesh to the -o file written), the
search (the SSStarSearch event of -log_view, largest rank: building the trees, spreading a mesh obstacle's triangles,
the closest-triangle and region queries) and its share of the whole run, the mesh and solve phases, Newton
iterations, the peak memory of the largest rank (-memory_view), and per rank the triangles of its search and the
memory they take (-info's SSStarSearch lines; a pair's search lives only while the contact operator is built, a mesh
obstacle's as long as the scene). --yardstick adds the AMG yardstick of the same K (bench/yardstick). Writes
bench/output/search.csv."""
import argparse
import csv
import os
import re
import statistics
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output")
EVENT = r"^%s\s+(\d+)\s+[\d.]+\s+([\d.eE+-]+)"
SUMMARY = re.compile(r"summary: nodes (\d+) contact (\d+) .* iterations (\d+) states \S+ \S+ (\S+)")
PEAK = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+(\S+)\s+max\s+(\S+)")
SEARCH = re.compile(r"SSStarSearch: (\d+) of (\d+) triangles on rank (\d+), (\d+) bytes")
AMG = re.compile(r"amg level \d+ ranks \d+ dofs (\d+) setup (\S+) solve (\S+) its (\d+)")


def mpiexec(ranks):
    return ["mpiexec", "--oversubscribe", "-n", str(ranks)]


def ball_surface(level):
    """meshes/ball_surface.geo meshed at level (the obstacle's triangles), once"""
    msh = os.path.join(OUT, "ball_surface_L%d.msh" % level)
    if not os.path.exists(msh):
        subprocess.run(["gmsh", "-2", "-setnumber", "L", str(level), "-format", "msh41", os.path.join(ROOT, "meshes", "ball_surface.geo"),
                        "-o", msh], cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
    return msh


def case_args(name, args):
    if name == "ball":
        return ["-options_file", "scenes/ball.opts", "-level", str(args.ball_level), "-obstacle_top", "mesh:" + ball_surface(args.sphere_level)]
    pair = ["-options_file", "scenes/hertz2.opts", "-level", str(args.pair_level)]
    return pair + (["-pair_discretization", "dual_mortar"] if name == "mortar" else [])


def event(out, name):
    m = re.search(EVENT % name, out, re.M)
    return float(m.group(2)) if m else 0.0


def measure(name, args):
    h5 = os.path.join(OUT, "search_%s.h5" % name)
    cmd = mpiexec(args.ranks) + [os.path.join(ROOT, "examples", "contact")] + case_args(name, args) + [
        "-snes_ssstar_reduction", "none", "-log_view", "-memory_view", "-info", ":sys", "-o", h5]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    whole = time.perf_counter() - t0
    m = SUMMARY.search(p.stdout)
    if p.returncode or not m:
        print("  %s: failed (exit status %d)\n%s" % (name, p.returncode, p.stdout[-2000:]), flush=True)
        return None
    for f in (h5, h5[:-3] + ".xmf"):
        if os.path.exists(f):
            os.remove(f)
    searches = [(int(r), int(n), int(total), int(b)) for n, total, r, b in SEARCH.findall(p.stdout)]
    return {"whole": whole, "search": event(p.stdout, "SSStarSearch"), "mesh": event(p.stdout, "SSStarMesh"),
            "solve": event(p.stdout, "SNESSolve"), "nodes": int(m.group(1)), "contact": int(m.group(2)), "iters": int(m.group(3)),
            "reason": m.group(4), "peak_gb": float(PEAK.search(p.stdout).group(2)) / 1e9,
            "triangles": max(s[2] for s in searches) if searches else 0,
            "triangles_per_rank": max(s[1] for s in searches) if searches else 0,
            "search_mb_per_rank": max(s[3] for s in searches) / 1e6 if searches else 0.0}


def yardstick(name, args):
    cmd = mpiexec(args.ranks) + [os.path.join(ROOT, "bench", "yardstick"), "-yardstick", "amg"] + case_args(name, args)
    out = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    m = AMG.search(out)
    return float(m.group(2)) + float(m.group(3)) if m else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cases", default="ball,pair,mortar")
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--ball-level", type=int, default=7, help="level of meshes/indent.geo (7: about 250 000 nodes)")
    parser.add_argument("--sphere-level", type=int, default=2, help="level of meshes/ball_surface.geo (2: 59 356 triangles)")
    parser.add_argument("--pair-level", type=int, default=3, help="level of meshes/hertz2.geo (3: 310 000 dofs)")
    parser.add_argument("--yardstick", action="store_true", help="the AMG yardstick of each case's K in the same run")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"), ("OPENBLAS_NUM_THREADS", "1")):
        os.environ.setdefault(k, v)
    rows = []
    print("medians of %d runs on %d ranks, the whole body (-snes_ssstar_reduction none); seconds" % (args.repeat, args.ranks))
    print("case    nodes    dofs contact triangles tri/rank search[MB/rank]  mesh   solve   whole  search  search/whole iters peak[GB]  amg  reason")
    for name in args.cases.split(","):
        runs = [r for r in (measure(name, args) for _ in range(args.repeat)) if r]
        if not runs:
            continue
        row = {"case": name, "ranks": args.ranks}
        for key in ("nodes", "contact", "iters", "reason", "triangles", "triangles_per_rank", "search_mb_per_rank"):
            row[key] = runs[0][key]
        for key in ("whole", "search", "mesh", "solve", "peak_gb"):
            row[key] = statistics.median(r[key] for r in runs)
        row["share"] = statistics.median(r["search"] / r["whole"] for r in runs)
        row["amg"] = statistics.median(yardstick(name, args) for _ in range(args.repeat)) if args.yardstick else float("nan")
        print("%-6s %7d %7d %7d %9d %8d %15.1f %6.1f %7.1f %7.1f %7.3f %11.2f%% %5d %8.2f %5.1f  %s" % (
            name, row["nodes"], 3 * row["nodes"], row["contact"], row["triangles"], row["triangles_per_rank"], row["search_mb_per_rank"],
            row["mesh"], row["solve"], row["whole"], row["search"], 100 * row["share"], row["iters"], row["peak_gb"], row["amg"],
            row["reason"]), flush=True)
        rows.append(row)
    with open(os.path.join(OUT, "search.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["case", "ranks", "nodes", "contact", "triangles", "triangles_per_rank", "search_mb_per_rank",
                                          "mesh", "solve", "whole", "search", "share", "iters", "peak_gb", "amg", "reason"])
        w.writeheader()
        w.writerows(rows)
    print("wrote %s/search.csv" % OUT)


if __name__ == "__main__":
    main()
