#!/usr/bin/python3
"""Table 2 of the seed, measured on both paths: examples/prism at levels L on 1 and 2 ranks, the median of several runs.

  bench/table2.py [--levels 4,6,8,10,12,14,16] [--ranks 1,2] [--repeat 3] [--once-from L] [--paths direct,none]
                  [--yardsticks cholesky,amg] [--cholesky-max-level 14]
  bench/table2.py --large [--levels 16,24,32,40,48] [--ranks 2] [--repeat 3] [--refine-also 48] [--getfem-level 10]
                                   # the scale table of docs/guide/scale.md (make bench-large; bench/scale.py): the whole
                                   # body at levels 16-48 on 2 ranks beside the AMG yardstick of the same run, level 48
                                   # also as level 24 refined once in parallel, level 10 against GetFEM

Per level, ranks and path (direct: the dense route, P formed by MUMPS and the Newton steps by LU; none: the whole
body, P never formed, Krylov + multigrid): the phases of the summary row (assembly = mesh to K, schur = the
reduction, solve = SNESSolve without it), the whole run (the process's wall time, mesh to the -o file written), the
Newton iterations and the linear (Krylov) iterations per Newton step, and the peak memory of the largest rank
(the summary row's last column: VmHWM). Beside them the yardsticks measured in the same run (bench/yardstick): one plain MUMPS Cholesky of
the whole K, and one CG + GAMG solve of K (set-up + solve, rtol 1e-8), with the ratios whole / yardstick that divide
out the machine; the seed's published figures (MATLAB) and seed / ours; and, per ranks, the crossover: the first
level where the whole body is faster than the dense route (what -snes_ssstar_reduction auto follows). Writes
bench/output/table2.csv and table2.png (time against contact nodes)."""
import argparse
import csv
import math
import os
import re
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output")
# seed Table 2: level -> (nodes, assembly, Cholesky + Schur, contact nodes, solve, iterations)
SEED = {3: (637, 0.13, 0.02, 84, 0.03, 6), 4: (1377, 0.19, 0.09, 144, 0.07, 6), 5: (2541, 0.28, 0.24, 220, 0.27, 9),
        6: (4225, 0.61, 0.69, 312, 0.51, 9), 7: (6525, 1.11, 1.76, 420, 0.93, 9), 8: (9537, 1.61, 3.73, 544, 1.60, 9),
        9: (13357, 2.48, 7.20, 684, 3.05, 10), 10: (18081, 3.30, 13.44, 840, 4.69, 9), 11: (23805, 4.38, 23.07, 1012, 8.17, 10),
        12: (30625, 5.73, 40.71, 1200, 12.48, 10), 13: (38637, 7.33, 107.63, 1404, 17.55, 9), 14: (47937, 9.16, 293.50, 1624, 30.24, 11),
        15: (58621, 11.92, 684.17, 1860, 43.00, 11), 16: (70785, 13.78, 1217.38, 2112, 57.80, 11)}
CHOLESKY = re.compile(r"cholesky level \d+ ranks \d+ dofs (\d+) time (\S+) flops (\S+)")
AMG = re.compile(r"amg level \d+ ranks \d+ dofs (\d+) setup (\S+) solve (\S+) its (\d+)")
ROW = re.compile(r"^\s*(\d+)(?:r\d+)?\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+(\d+)\s+([\d.]+)\s+(\d+)\s+([\d/]+)\s+([\d/]+)\s+(\S+)\s+([\d.]+)$", re.M)
KRYLOV_FULL = re.compile(r"last solve: (\d+) linear solves, (\d+) Krylov iterations")
SETUP = re.compile(r"^\s*set-up: .*, ([\d.]+) s, [\d.]+ GB per rank", re.M)
MULTIGRID = re.compile(r"new multigrid \(([\d.]+) s\)")  # a Newton step's multigrid set-up, on the finest mesh
NESTED = re.compile(r"^nested: .*, ([\d.]+) s, [\d.]+ GB per rank", re.M)
ESTIMATE = re.compile(r"estimated peak ([\d.]+) GB per rank")
DOFS = re.compile(r"^assembly: K of (\d+) dofs", re.M)
KRYLOV_DENSE = re.compile(r"last solve: (\d+) LU factorizations .*?, (\d+) steps on an old LU \((\d+) Krylov iterations\)")


def level_list(spec):
    out = []
    for part in spec.split(","):
        lo, _, hi = part.partition("-")
        out += list(range(int(lo), int(hi or lo) + 1))
    return out


def mpiexec(ranks):
    return ["mpiexec", "--oversubscribe", "-n", str(ranks)]


def mesh_args(level, refine_from):
    """-level L, or from refine_from on level L/2 refined once in parallel (-dm_refine 1: the same nodes)"""
    if level >= refine_from and level % 2 == 0:
        return ["-level", str(level // 2), "-dm_refine", "1"]
    return ["-level", str(level)]


def measure(level, ranks, path, refine_from=10**6):
    h5 = os.path.join(OUT, "table2_L%d_%d_%s.h5" % (level, ranks, path))
    cmd = mpiexec(ranks) + [os.path.join(ROOT, "examples", "prism")] + mesh_args(level, refine_from) + ["-snes_ssstar_reduction", path,
                            "-summary_header", "0", "-snes_view", "-o", h5]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    whole = time.perf_counter() - t0
    with open(h5[:-3] + ".log", "w") as f:  # the run's progress lines, the last repeat's
        f.write(p.stdout)
    m = ROW.search(p.stdout)
    if p.returncode or not m:
        print("  level %d, %d ranks, %s: failed (exit status %d)\n%s" % (level, ranks, path, p.returncode, p.stdout[-1500:]), flush=True)
        return None
    for name in (h5, h5[:-3] + ".xmf"):
        if os.path.exists(name):
            os.remove(name)
    full, dense = KRYLOV_FULL.findall(p.stdout), KRYLOV_DENSE.search(p.stdout)
    steps, krylov = (int(full[-1][0]), int(full[-1][1])) if full else (int(dense.group(1)) + int(dense.group(2)), int(dense.group(3))) if dense else (0, 0)
    setup, nested, estimate, dofs = SETUP.search(p.stdout), NESTED.search(p.stdout), ESTIMATE.search(p.stdout), DOFS.search(p.stdout)
    return {"assembly": float(m.group(4)), "schur": float(m.group(5)), "solve": float(m.group(7)), "iters": int(m.group(8)),
            "nodes": int(m.group(3)), "contact": int(m.group(6)), "states": m.group(10), "reason": m.group(11), "whole": whole,
            "krylov_per_step": krylov / steps if steps else 0.0, "krylov": krylov, "peak_gb": float(m.group(12)),
            "setup": float(setup.group(1)) + sum(float(t) for t in MULTIGRID.findall(p.stdout[setup.end():])) if setup else math.nan, "nested": float(nested.group(1)) if nested else 0.0,
            "estimate_gb": float(estimate.group(1)) if estimate else math.nan, "dofs": int(dofs.group(1)) if dofs else 3 * int(m.group(3))}


def yardstick(level, ranks, which, refine_from=10**6):
    """one MUMPS Cholesky of the whole K (seconds), or one CG + GAMG solve (set-up + solve, seconds); nan if it fails"""
    cmd = mpiexec(ranks) + [os.path.join(ROOT, "bench", "yardstick"), "-yardstick", which, "-options_file",
                            os.path.join(ROOT, "scenes", "prism.opts")] + mesh_args(level, refine_from)
    out = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    if which == "cholesky":
        m = CHOLESKY.search(out)
        return float(m.group(2)) if m else math.nan
    m = AMG.search(out)
    return (float(m.group(2)), float(m.group(3))) if m else (math.nan, math.nan)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--levels", default=None, help="default 4,6,8,10,12,14,16 (--large: 16,24,32,40,48)")
    parser.add_argument("--ranks", default=None, help="default 1,2")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--paths", default="direct,none")
    parser.add_argument("--yardsticks", default="cholesky,amg", help="the yardsticks to measure (empty: none)")
    parser.add_argument("--cholesky-max-level", type=int, default=14, help="no Cholesky yardstick above this level (its time and memory)")
    parser.add_argument("--once-from", type=int, default=10**6, help="levels from this one run once (their time)")
    parser.add_argument("--large", action="store_true", help="the scale table (bench/scale.py): levels 16-48 on the whole body on 2 ranks (make bench-large)")
    parser.add_argument("--refine-from", type=int, default=10**6, help="even levels from this one: level L/2's mesh refined once in parallel (-dm_refine 1)")
    parser.add_argument("--refine-also", default="48", help="--large: these levels also as level L/2 refined once in parallel (empty: none)")
    parser.add_argument("--getfem-level", type=int, default=10, help="--large: this level against GetFEM in the same run (0: none)")
    parser.add_argument("--timeout", type=float, default=7200, help="--large: seconds a run may take before it is killed")
    args = parser.parse_args()
    for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"), ("OPENBLAS_NUM_THREADS", "1")):
        os.environ.setdefault(k, v)
    if args.large:
        import scale
        scale.main(args)
        return
    args.levels, args.ranks = args.levels or "4,6,8,10,12,14,16", args.ranks or "1,2"
    os.makedirs(OUT, exist_ok=True)
    paths = args.paths.split(",")
    sticks = [s for s in args.yardsticks.split(",") if s]
    rows = []
    print("medians of %d runs%s, seconds; seed = the slides' Table 2 (MATLAB); direct = the dense route, none = the whole body" % (args.repeat, " (one from level %d)" % args.once_from if args.once_from < 10**6 else ""))
    print("level ranks path    nodes contact assembly   schur   solve   whole  (seed) seed/ours iters krylov/step peak[GB] cholesky amg  whole/chol whole/amg  sep/slide/stick reason")
    for level in level_list(args.levels):
        repeat = args.repeat if level < args.once_from else 1
        for ranks in (int(r) for r in args.ranks.split(",")):
            ys = {}
            for s in sticks:
                if s == "cholesky" and level > args.cholesky_max_level:
                    ys[s] = math.nan
                    continue
                runs = [yardstick(level, ranks, s, args.refine_from) for _ in range(repeat)]
                if s == "amg":  # set-up and solve
                    ys["amg_setup"] = statistics.median(r[0] for r in runs)
                    runs = [r[0] + r[1] for r in runs]
                ys[s] = statistics.median(runs)
            measured = {path: [] for path in paths}
            for _ in range(repeat):  # the paths interleaved, so that a noisy spell hits both
                for path in paths:
                    r = measure(level, ranks, path, args.refine_from)
                    if r:
                        measured[path].append(r)
            for path in paths:
                runs = measured[path]
                if not runs:
                    continue
                row = {"level": level, "ranks": ranks, "path": path, "nodes": runs[0]["nodes"], "contact": runs[0]["contact"],
                       "iters": runs[0]["iters"], "states": runs[0]["states"], "reason": runs[0]["reason"]}
                for key in ("assembly", "schur", "solve", "whole", "peak_gb", "krylov_per_step", "krylov", "setup", "nested", "estimate_gb"):
                    row[key] = statistics.median(r[key] for r in runs)
                row["dofs"] = runs[0]["dofs"]
                row["solve_per_amg"] = (row["solve"] + row["schur"]) / ys.get("amg", math.nan) if "amg" in ys else math.nan
                row["setup_share"] = (row["nested"] + row["setup"]) / (row["solve"] + row["schur"]) if row["solve"] + row["schur"] > 0 else math.nan
                row["bytes_per_dof"] = row["peak_gb"] * 1e9 * ranks / row["dofs"]
                row["cholesky"], row["amg"], row["amg_setup"] = ys.get("cholesky", math.nan), ys.get("amg", math.nan), ys.get("amg_setup", math.nan)
                row["whole_per_cholesky"] = row["whole"] / row["cholesky"]
                row["whole_per_amg"] = row["whole"] / row["amg"]
                seed = SEED.get(level)
                row["seed_whole"] = seed[1] + seed[2] + seed[4] if seed else math.nan
                row["speedup"] = row["seed_whole"] / row["whole"]
                print("%5d %5d %-6s %7d %7d %8.3f %7.3f %7.3f %7.2f %7s %9s %5d %11.1f %8.2f %8.3f %6.3f %10.2f %9.2f  %-15s %s" % (
                    level, ranks, path, row["nodes"], row["contact"], row["assembly"], row["schur"], row["solve"], row["whole"],
                    "%.2f" % row["seed_whole"] if seed else "-", "%.3gx" % row["speedup"] if seed else "-", row["iters"],
                    row["krylov_per_step"], row["peak_gb"], row["cholesky"], row["amg"], row["whole_per_cholesky"],
                    row["whole_per_amg"], row["states"], row["reason"]), flush=True)
                rows.append(row)
    if "direct" in paths and "none" in paths:
        for ranks in sorted({r["ranks"] for r in rows}):
            whole = {(r["level"], r["path"]): r["whole"] for r in rows if r["ranks"] == ranks}
            faster = [lv for lv in sorted({lv for lv, _ in whole}) if (lv, "none") in whole and (lv, "direct") in whole and whole[(lv, "none")] < whole[(lv, "direct")]]
            print("crossover, %d rank%s: the whole body is faster from level %s" % (ranks, "s" if ranks > 1 else "", faster[0] if faster else "- (not in these levels)"))
    name = "table2"
    with open(os.path.join(OUT, name + ".csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["level", "ranks", "path", "nodes", "dofs", "contact", "assembly", "schur", "solve", "whole", "iters",
                                          "krylov_per_step", "krylov", "nested", "setup", "setup_share", "peak_gb", "bytes_per_dof", "estimate_gb",
                                          "cholesky", "amg", "amg_setup", "whole_per_cholesky", "whole_per_amg", "solve_per_amg", "seed_whole", "speedup", "states", "reason"])
        w.writeheader()
        w.writerows(rows)
    plot(rows, name)
    print("wrote %s/%s.csv and %s.png" % (OUT, name, name))


def plot(rows, name):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 5))
    styles = {1: "-o", 2: "--s"}
    for path, color in (("direct", "tab:red"), ("none", "tab:blue")):
        for ranks, style in styles.items():
            pts = sorted((r["contact"], r["whole"]) for r in rows if r["ranks"] == ranks and r["path"] == path)
            if pts:
                ax.loglog(*zip(*pts), style, color=color, label="whole run, %s, %d rank%s" % ("dense route" if path == "direct" else "whole body", ranks, "s" if ranks > 1 else ""))
    for stick, color in (("cholesky", "tab:gray"), ("amg", "tab:green")):
        for ranks, style in styles.items():
            pts = sorted({(r["contact"], r[stick]) for r in rows if r["ranks"] == ranks and not math.isnan(r[stick])})
            if pts:
                ax.loglog(*zip(*pts), style, color=color, alpha=0.6, label="%s of K, %d rank%s" % ("one Cholesky" if stick == "cholesky" else "one AMG solve", ranks, "s" if ranks > 1 else ""))
    seed = sorted((v[3], v[1] + v[2] + v[4]) for v in SEED.values())
    ax.loglog(*zip(*seed), ":", color="black", alpha=0.6, label="seed (MATLAB), whole")
    ax.set_xlabel("contact nodes p")
    ax.set_ylabel("seconds (median)")
    ax.set_title("ssstar on the seed's prism: dense route and whole body")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2, loc="upper left")
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, name + ".png"), dpi=120)


if __name__ == "__main__":
    main()
