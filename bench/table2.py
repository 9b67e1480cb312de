#!/usr/bin/python3
"""Table 2 of the seed, measured: examples/prism at levels L on 1 and 2 ranks, the median of several runs.

  bench/table2.py [--levels 3-12] [--ranks 1,2] [--repeat 3] [--reduction direct] [--no-cholesky]

Per level and ranks: the phases of the summary row (assembly = mesh to K, schur = the reduction, solve = the
Newton phase), the whole run (the process's wall time, mesh to the -o file written), the peak memory of the
largest rank (-memory_view), and the yardstick measured in the same run: one plain MUMPS Cholesky factorization of
the whole K (bench/cholesky); "limit" = whole run / that factorization. Beside them the seed's published figures
(MATLAB) and the ratio seed / ours of the whole run. Writes bench/output/table2.csv and bench/output/table2.png
(time against contact nodes, ours and the seed's)."""
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
PEAK = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+(\S+)\s+max\s+(\S+)")
CHOLESKY = re.compile(r"cholesky level \d+ ranks \d+ dofs (\d+) time (\S+) flops (\S+)")
ROW = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+(\d+)\s+([\d.]+)\s+(\d+)\s+([\d/]+)\s+([\d/]+)\s+(\S+)", re.M)


def levels(spec):
    lo, _, hi = spec.partition("-")
    return list(range(int(lo), int(hi or lo) + 1))


def measure(level, ranks, reduction):
    h5 = os.path.join(OUT, "table2_L%d_%d.h5" % (level, ranks))
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), os.path.join(ROOT, "examples", "prism"), "-level", str(level),
           "-reduction", reduction, "-summary_header", "0", "-memory_view", "-o", h5]
    t0 = time.perf_counter()
    out = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    whole = time.perf_counter() - t0
    m = ROW.search(out)
    if not m:
        sys.exit("no summary from %s\n%s" % (" ".join(cmd), out[-2000:]))
    for name in (h5, h5[:-3] + ".xmf"):
        if os.path.exists(name):
            os.remove(name)
    return {"assembly": float(m.group(4)), "schur": float(m.group(5)), "solve": float(m.group(7)), "iters": int(m.group(8)),
            "nodes": int(m.group(3)), "contact": int(m.group(6)), "states": m.group(10), "reason": m.group(11), "whole": whole,
            "peak_gb": float(PEAK.search(out).group(2)) / 1e9}


def cholesky(level, ranks):
    """the yardstick: one MUMPS Cholesky factorization of the whole K (seconds), nan if it fails"""
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), os.path.join(ROOT, "bench", "cholesky"), "-options_file",
           os.path.join(ROOT, "scenes", "prism.opts"), "-level", str(level)]
    m = CHOLESKY.search(subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout)
    return float(m.group(2)) if m else math.nan


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--levels", default="3-12")
    parser.add_argument("--ranks", default="1,2")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--reduction", default="direct", choices=["direct", "mumps", "explicit"])
    parser.add_argument("--no-cholesky", action="store_true", help="leave out the yardstick")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"), ("OPENBLAS_NUM_THREADS", "1")):
        os.environ.setdefault(k, v)
    rows = []
    print("medians of %d runs, seconds; seed = the slides' Table 2 (MATLAB); method: %s reduction, semismooth* Newton"
          % (args.repeat, args.reduction))
    print("level ranks  nodes contact  assembly (seed)    schur  (seed)   solve  (seed) iters (seed)   whole  (seed) seed/ours  peak[GB] cholesky limit  sep/slide/stick reason")
    fmt = lambda v, w=7: ("%*.2f" % (w, v)) if v is not None else " " * (w - 1) + "-"
    for level in levels(args.levels):
        for ranks in (int(r) for r in args.ranks.split(",")):
            runs = [measure(level, ranks, args.reduction) for _ in range(args.repeat)]
            row = {"level": level, "ranks": ranks, "nodes": runs[0]["nodes"], "contact": runs[0]["contact"],
                   "iters": runs[0]["iters"], "states": runs[0]["states"], "reason": runs[0]["reason"], "method": args.reduction}
            for key in ("assembly", "schur", "solve", "whole", "peak_gb"):
                row[key] = statistics.median(r[key] for r in runs)
            row["cholesky"] = math.nan if args.no_cholesky else statistics.median(cholesky(level, ranks) for _ in range(args.repeat))
            row["limit"] = row["whole"] / row["cholesky"]
            seed = SEED.get(level, (None,) * 6)
            row["seed_whole"] = seed[1] + seed[2] + seed[4] if seed[1] is not None else math.nan
            row["speedup"] = row["seed_whole"] / row["whole"]
            print("%5d %5d %6d %7d  %7.3f %s  %7.3f %s  %6.3f %s %5d %5s  %6.2f %s %9s  %8.2f %8.3f %5.1f  %-15s %s" % (
                level, ranks, row["nodes"], row["contact"], row["assembly"], fmt(seed[1]), row["schur"], fmt(seed[2]),
                row["solve"], fmt(seed[4]), row["iters"], seed[5] if seed[5] else "-", row["whole"], fmt(seed[1] and row["seed_whole"], 8),
                "%.3gx" % row["speedup"] if not math.isnan(row["speedup"]) else "-", row["peak_gb"], row["cholesky"], row["limit"],
                row["states"], row["reason"]), flush=True)
            rows.append(row)
    with open(os.path.join(OUT, "table2.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["level", "ranks", "nodes", "contact", "method", "assembly", "schur", "solve", "iters", "whole",
                                          "peak_gb", "cholesky", "limit", "seed_whole", "speedup", "states", "reason"])
        w.writeheader()
        w.writerows(rows)
    plot(rows)
    print("wrote %s/table2.csv and table2.png" % OUT)


def plot(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 5))
    colors = {"whole": "black", "assembly": "tab:blue", "schur": "tab:red", "solve": "tab:green"}
    seed_index = {"assembly": (1,), "schur": (2,), "solve": (4,), "whole": (1, 2, 4)}
    for key, color in colors.items():
        for ranks, style in ((1, "-o"), (2, "--s")):
            pts = [(r["contact"], r[key]) for r in rows if r["ranks"] == ranks]
            if pts:
                ax.loglog(*zip(*pts), style, color=color, label="%s, %d rank%s" % (key, ranks, "s" if ranks > 1 else ""))
        seed = [(v[3], sum(v[i] for i in seed_index[key])) for v in SEED.values()]
        ax.loglog(*zip(*seed), ":", color=color, alpha=0.6, label="%s, seed (MATLAB)" % key)
    ax.set_xlabel("contact nodes p")
    ax.set_ylabel("seconds (median)")
    ax.set_title("ssstar on the seed's prism: whole run and phases")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "table2.png"), dpi=120)


if __name__ == "__main__":
    main()
