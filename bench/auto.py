#!/usr/bin/python3
"""What auto chooses, against both routes measured side by side: a family of meshes and contact groups, each run on the
dense route (-snes_ssstar_reduction direct), on the whole body (none) and by auto, the three interleaved in each
repeat so that a noisy spell hits all; medians of the repeats; the AMG yardstick of the same run (bench/yardstick: one
CG + GAMG solve of K, set-up and solve) beside the absolute times.

  bench/auto.py [--members prism6,press,...] [--ranks 1,2] [--repeat 3]

The family (docs/guide/choosing-a-route.md): the prism (levels 4-12: one face of a box, held by Dirichlet conditions),
the unstructured slab of issue 31 (scenes/press.opts: the whole bottom face a contact group, a third of the nodes,
most separated; a three-step press), the same slab squeezed between two planes (contact on its top and bottom, most of
its surface), and small patches on bodies held by soft springs (Hertz's half ball, the ball and the roller on a block;
the block sheared on a spring) or by contact alone (the block on a slope). Per member and route: the whole run (the
process's wall time, mesh to solution), the Newton iterations, the peak memory per rank (VmHWM, the summary), the
estimates printed before the work (the contact line: the whole body's and the dense route's peak), and auto's choice
with auto's time over the faster route's (the target: at most 1.25). Writes bench/output/auto.csv."""
import argparse
import csv
import math
import os
import re
import resource
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output")
SCENES = os.path.join(ROOT, "scenes")
SQUEEZE = ["-options_file", os.path.join(SCENES, "press.opts"), "-contact", "bottom,top,patch", "-traction_patch", "0,0,0", "-steps", "1",
           "-obstacle_top", "plane:0,0,0.281,0,0,-1", "-obstacle_patch", "plane:0,0,0.281,0,0,-1",
           "-obstacle_top_motion", "0:0,0,0;1:0,0,-0.003", "-obstacle_patch_motion", "0:0,0,0;1:0,0,-0.003",
           "-friction_top", "0.3", "-friction_patch", "0.3"]
# name: (program, its arguments, the yardstick's scene arguments, what it is)
MEMBERS = {
    "prism4": ("prism", ["-level", "4"], ["-options_file", os.path.join(SCENES, "prism.opts"), "-level", "4"], "prism, one face of a box"),
    "prism6": ("prism", ["-level", "6"], ["-options_file", os.path.join(SCENES, "prism.opts"), "-level", "6"], "prism"),
    "prism8": ("prism", ["-level", "8"], ["-options_file", os.path.join(SCENES, "prism.opts"), "-level", "8"], "prism"),
    "prism10": ("prism", ["-level", "10"], ["-options_file", os.path.join(SCENES, "prism.opts"), "-level", "10"], "prism"),
    "prism12": ("prism", ["-level", "12"], ["-options_file", os.path.join(SCENES, "prism.opts"), "-level", "12"], "prism"),
    "press": ("contact", ["-options_file", os.path.join(SCENES, "press.opts")], ["-options_file", os.path.join(SCENES, "press.opts")],
              "unstructured slab, its bottom face, mostly separated (issue 31)"),
    "squeeze": ("contact", SQUEEZE, ["-options_file", os.path.join(SCENES, "press.opts")], "the slab between two planes: most of its surface"),
    "hertz1": ("contact", ["-options_file", os.path.join(SCENES, "hertz.opts"), "-level", "1"], ["-options_file", os.path.join(SCENES, "hertz.opts"), "-level", "1"],
               "half ball's cap, a small patch, soft spring"),
    "hertz2": ("contact", ["-options_file", os.path.join(SCENES, "hertz.opts"), "-level", "2"], ["-options_file", os.path.join(SCENES, "hertz.opts"), "-level", "2"],
               "half ball's cap, a small patch, soft spring"),
    "ball": ("contact", ["-options_file", os.path.join(SCENES, "ball.opts")], ["-options_file", os.path.join(SCENES, "ball.opts")], "a ball on a block's face, soft spring"),
    "roller": ("contact", ["-options_file", os.path.join(SCENES, "roller.opts")], ["-options_file", os.path.join(SCENES, "roller.opts")], "a cylinder on a block's face, soft spring"),
    "shear": ("contact", ["-options_file", os.path.join(SCENES, "shear.opts")], ["-options_file", os.path.join(SCENES, "shear.opts")], "a block's face sheared, spring"),
    "slope": ("contact", ["-options_file", os.path.join(SCENES, "slope.opts")], ["-options_file", os.path.join(SCENES, "slope.opts")], "a block on a slope, held by contact alone"),
}
ROUTES = ("direct", "none", "auto")
PRISM_ROW = re.compile(r"^\s*-?\d+(?:r\d+)?\s+\d+\s+\d+\s+[\d.]+\s+[\d.]+\s+\d+\s+[\d.]+\s+(\d+)\s+\S+\s+\S+\s+(\S+)\s+([\d.]+)$", re.M)
CONTACT_ROW = re.compile(r"summary: .* iterations (\d+) states \S+ \S+ (\S+)\s+peak ([\d.]+) GB per rank")
ESTIMATE = re.compile(r"estimated peak ([\d.]+) GB per rank(?: \(plain aggregation\))?(?: on the whole body, ([\d.]+) GB on the dense route)?")
DOFS = re.compile(r"^assembly: K of (\d+) dofs", re.M)
CONTACT_NODES = re.compile(r"^contact: (\d+) contact nodes", re.M)
CHOSEN = re.compile(r"set-up: (K reduced to|the whole body)")
AUTO_INFO = re.compile(r"holding ([\d.e+-]+), MUMPS's flops ([\d.e+-]+): dense route ([\d.e+-]+), whole body ([\d.e+-]+)")
AMG = re.compile(r"amg level \S+ ranks \d+ dofs (\d+) setup (\S+) solve (\S+) its (\d+)")


def mpiexec(ranks):
    return ["nice", "-n", "10", "mpiexec", "--oversubscribe", "-n", str(ranks)]


def measure(member, ranks, route):
    program, args, _, _ = MEMBERS[member]
    cmd = mpiexec(ranks) + [os.path.join(ROOT, "examples", program)] + args + ["-snes_ssstar_reduction", route, "-info", ":mat"]
    t0, c0 = time.perf_counter(), resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    whole, c1 = time.perf_counter() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (c1.ru_utime + c1.ru_stime) - (c0.ru_utime + c0.ru_stime)  # the processor time of its ranks (and mpiexec)
    m = (PRISM_ROW if program == "prism" else CONTACT_ROW).search(p.stdout)
    if p.returncode or not m:
        print("  %s, %d ranks, %s: failed (exit status %d)\n%s" % (member, ranks, route, p.returncode, p.stdout[-1500:]), flush=True)
        return None
    its = int(m.group(1))
    est, info = ESTIMATE.search(p.stdout), (AUTO_INFO.findall(p.stdout) or [None])[-1]  # the finest mesh's (nested: the last)
    chosen = CHOSEN.search(p.stdout)
    return {"whole": whole, "cpu": cpu, "iters": its, "reason": m.group(2), "peak_gb": float(m.group(3)), "dofs": int(DOFS.search(p.stdout).group(1)),
            "contact": int(CONTACT_NODES.search(p.stdout).group(1)), "est_whole_gb": float(est.group(1)) if est else math.nan,
            "est_dense_gb": float(est.group(2)) if est and est.group(2) else math.nan,
            "chosen": ("direct" if chosen.group(1).startswith("K") else "none") if chosen else "?",
            "holding": float(info[0]) if info else math.nan, "mumps_flops": float(info[1]) if info else math.nan,
            "cost_dense": float(info[2]) if info else math.nan, "cost_whole": float(info[3]) if info else math.nan}


def yardstick(member, ranks):
    """one CG + GAMG solve of K (set-up + solve, seconds), nan if it fails"""
    cmd = mpiexec(ranks) + [os.path.join(ROOT, "bench", "yardstick"), "-yardstick", "amg"] + MEMBERS[member][2]
    m = AMG.search(subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout)
    return float(m.group(2)) + float(m.group(3)) if m else math.nan


def median(runs, key):
    return statistics.median(r[key] for r in runs)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--members", default=",".join(MEMBERS), help="default: all (%s)" % ",".join(MEMBERS))
    parser.add_argument("--ranks", default="1,2")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"), ("OPENBLAS_NUM_THREADS", "1")):
        os.environ.setdefault(k, v)
    rows = []
    print("medians of %d runs, seconds (whole runs, mesh to solution); the routes interleaved; amg = the yardstick of the same run" % args.repeat)
    print("wall: the runs' wall times [s]; cpu: their processor time [s] (the ranks' user + system: what a run costs when "
          "other jobs share the cores); ratio: auto over the faster route; peak/est: VmHWM per rank against the estimate [GB]")
    print("%-8s %5s %7s %7s %9s %7s %8s %8s %8s %6s %8s %8s %8s %6s %6s %6s %6s %13s %13s %5s %s" % (
        "member", "ranks", "dofs", "contact", "holding", "chosen", "dense", "whole", "auto", "ratio", "dense", "whole", "auto", "ratio",
        "amg", "d/amg", "w/amg", "dense pk/est", "whole pk/est", "load", "its d/w"))
    print("%-8s %5s %7s %7s %9s %7s %8s %8s %8s %6s %8s %8s %8s %6s" % ("", "", "", "", "", "", "wall", "wall", "wall", "wall", "cpu", "cpu", "cpu", "cpu"))
    for member in args.members.split(","):
        for ranks in (int(r) for r in args.ranks.split(",")):
            measured = {route: [] for route in ROUTES}
            sticks = []
            for _ in range(args.repeat):
                sticks.append(yardstick(member, ranks))
                for route in ROUTES:
                    r = measure(member, ranks, route)
                    if r:
                        measured[route].append(r)
            if not all(measured[route] for route in ROUTES):
                continue
            med = {route: median(measured[route], "whole") for route in ROUTES}
            cpu = {route: median(measured[route], "cpu") for route in ROUTES}
            first = {route: measured[route][0] for route in ROUTES}
            stick = statistics.median(sticks)
            row = {"member": member, "what": MEMBERS[member][3], "ranks": ranks, "dofs": first["auto"]["dofs"], "contact": first["auto"]["contact"],
                   "holding": first["auto"]["holding"], "mumps_flops": first["auto"]["mumps_flops"], "cost_dense": first["auto"]["cost_dense"],
                   "cost_whole": first["auto"]["cost_whole"], "chosen": first["auto"]["chosen"],
                   "dense_s": med["direct"], "whole_s": med["none"], "auto_s": med["auto"], "auto_over_faster": med["auto"] / min(med["direct"], med["none"]),
                   "dense_cpu": cpu["direct"], "whole_cpu": cpu["none"], "auto_cpu": cpu["auto"], "auto_over_faster_cpu": cpu["auto"] / min(cpu["direct"], cpu["none"]),
                   "faster": "direct" if med["direct"] <= med["none"] else "none", "faster_cpu": "direct" if cpu["direct"] <= cpu["none"] else "none",
                   "amg_s": stick, "dense_amg": med["direct"] / stick, "whole_amg": med["none"] / stick,
                   "peak_dense_gb": median(measured["direct"], "peak_gb"), "peak_whole_gb": median(measured["none"], "peak_gb"),
                   "est_dense_gb": first["direct"]["est_dense_gb"], "est_whole_gb": first["none"]["est_whole_gb"],
                   "its_dense": first["direct"]["iters"], "its_whole": first["none"]["iters"], "load": os.getloadavg()[0]}
            rows.append(row)
            print("%-8s %5d %7d %7d %9.2g %7s %8.2f %8.2f %8.2f %6.2f %8.2f %8.2f %8.2f %6.2f %6.2f %6.1f %6.1f %6.3f/%.3f %6.3f/%.3f %5.1f %d/%d" % (
                member, ranks, row["dofs"], row["contact"], row["holding"], row["chosen"], row["dense_s"], row["whole_s"], row["auto_s"],
                row["auto_over_faster"], row["dense_cpu"], row["whole_cpu"], row["auto_cpu"], row["auto_over_faster_cpu"], row["amg_s"],
                row["dense_amg"], row["whole_amg"], row["peak_dense_gb"], row["est_dense_gb"], row["peak_whole_gb"], row["est_whole_gb"],
                row["load"], row["its_dense"], row["its_whole"]), flush=True)
    with open(os.path.join(OUT, "auto.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]) if rows else ["member"])
        w.writeheader()
        w.writerows(rows)
    for key, what in (("auto_over_faster", "wall time"), ("auto_over_faster_cpu", "processor time")):
        worst = max(rows, key=lambda r: r[key]) if rows else None
        if worst:
            print("auto over the faster route, %s: at most %.2f (%s, %d rank%s); target 1.25" % (what, worst[key], worst["member"], worst["ranks"], "s" if worst["ranks"] > 1 else ""))
    print("wrote %s" % os.path.join(OUT, "auto.csv"))
    sys.exit(0 if rows else 1)


if __name__ == "__main__":
    main()
