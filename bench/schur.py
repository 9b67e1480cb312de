#!/usr/bin/python3
"""The Schur reduction of the prism, its three paths side by side: examples/prism with -snes_ssstar_reduction direct, mumps and
explicit at levels L on 1 and 2 ranks, medians of several runs, beside the yardstick of issue 7: one plain MUMPS
Cholesky factorization of the whole K at the same level and ranks (bench/yardstick -yardstick cholesky).

  bench/schur.py [--levels 6,8,10,12] [--ranks 1,2] [--repeat 3] [--paths direct,mumps,explicit]
                 [--max-level mumps=16,explicit=10] [--threads 1]

Per run: the time of the reduction (event SSStarSchur: P, f and the singular-K check), its phases (SSStarOrdering,
SSStarAnalysis, SSStarFactor, SSStarSchurScat of the direct path), the flops of its MUMPS factorization (MUMPS's
count, all ranks), the peak memory of
the largest rank (-memory_view) and the whole run. limit = reduction time / Cholesky time. Writes
bench/output/schur.csv and bench/output/schur.png."""
import argparse
import csv
import math
import os
import re
import statistics
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output")
PHASES = ["SSStarSchur", "SSStarOrdering", "SSStarAnalysis", "SSStarFactor", "SSStarSchurScat"]
SUMMARY = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\d+)\s+[\d.]+\s+[\d.]+\s+(\d+)\s+[\d.]+\s+(\d+)\s", re.M)
PEAK = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+(\S+)\s+max\s+(\S+)")
WALL = re.compile(r"^Time \(sec\):\s+(\S+)", re.M)
FACTOR_FLOPS = re.compile(r"MUMPS factorization[^:]*: (\S+) flops")
CHOLESKY = re.compile(r"cholesky level \d+ ranks \d+ dofs (\d+) time (\S+) flops (\S+)")


def event(out, name):
    """the time of a -log_view event (max over the ranks), 0 when absent"""
    m = re.search(r"^%s\s+\d+\s+\S+\s+(\S+)" % name, out, re.M)
    return float(m.group(1)) if m else 0.0


def mpiexec(ranks, threads):
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks)]
    if threads > 1:
        cmd += ["--bind-to", "none", "-x", "OPENBLAS_NUM_THREADS=%d" % threads]
    return cmd


def run_prism(level, ranks, path, threads):
    cmd = mpiexec(ranks, threads) + [os.path.join(ROOT, "examples", "prism"), "-level", str(level), "-snes_ssstar_reduction", path,
                                     "-summary_header", "0", "-log_view", "-memory_view", "-info", ":mat"]
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    m = SUMMARY.search(p.stdout)
    if p.returncode or not m:
        error = re.search(r"PETSC ERROR: (?!-+|See |Petsc Release|#|Configure|.*named )(.+)", p.stdout)
        return {"error": error.group(1) if error else "exit status %d" % p.returncode}
    row = {"nodes": int(m.group(3)), "contact": int(m.group(4)), "iters": int(m.group(5)),
           "peak_gb": float(PEAK.search(p.stdout).group(2)) / 1e9, "total_s": float(WALL.search(p.stdout).group(1))}
    for name in PHASES:
        row[name] = event(p.stdout, name)
    row["flops"] = float(FACTOR_FLOPS.search(p.stdout).group(1))
    return row


def run_cholesky(level, ranks, threads):
    cmd = mpiexec(ranks, threads) + [os.path.join(ROOT, "bench", "yardstick"), "-yardstick", "cholesky", "-options_file", os.path.join(ROOT, "scenes", "prism.opts"), "-level", str(level), "-memory_view"]
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    m = CHOLESKY.search(p.stdout)
    if p.returncode or not m:
        return {"error": "exit status %d" % p.returncode}
    return {"time": float(m.group(2)), "flops": float(m.group(3)), "peak_gb": float(PEAK.search(p.stdout).group(2)) / 1e9}


def median(runs, key):
    values = [r[key] for r in runs if key in r]
    return statistics.median(values) if values else math.nan


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--levels", default="6,8,10,12")
    parser.add_argument("--ranks", default="1,2")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--paths", default="direct,mumps,explicit")
    parser.add_argument("--max-level", default="mumps=16,explicit=10", help="skip a path above this level (memory, time)")
    parser.add_argument("--threads", type=int, default=1, help="OpenBLAS threads per rank (mpiexec --bind-to none)")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")):
        os.environ.setdefault(k, v)
    os.environ["OPENBLAS_NUM_THREADS"] = str(args.threads)
    max_level = {k: int(v) for k, v in (kv.split("=") for kv in args.max_level.split(",") if kv)}
    rows = []
    print("medians of %d runs (time: s, max over the ranks; flops: of the MUMPS factorization; memory: GB, largest rank)" % args.repeat)
    print("level ranks  dofs(C) path       reduction  ordering analysis  factor scatter     flops   mem[GB]  whole[s] | cholesky   flops  mem[GB] | limit")
    for level in (int(x) for x in args.levels.split(",")):
        for ranks in (int(r) for r in args.ranks.split(",")):
            chol = [run_cholesky(level, ranks, args.threads) for _ in range(args.repeat)]
            chol_t = median(chol, "time")
            for path in args.paths.split(","):
                if level > max_level.get(path, level):
                    continue
                runs = [run_prism(level, ranks, path, args.threads) for _ in range(args.repeat)]
                ok = [r for r in runs if "error" not in r]
                row = {"level": level, "ranks": ranks, "threads": args.threads, "path": path,
                       "contact": ok[0]["contact"] if ok else "", "error": "" if ok else runs[0]["error"]}
                for key in PHASES + ["flops", "peak_gb", "total_s"]:
                    row[key] = median(ok, key)
                row.update({"cholesky_s": chol_t, "cholesky_flops": median(chol, "flops"), "cholesky_gb": median(chol, "peak_gb")})
                row["limit"] = row["SSStarSchur"] / chol_t if chol_t else math.nan
                rows.append(row)
                if not ok:
                    print("%5d %5d %8s %-9s failed: %s" % (level, ranks, "", path, row["error"]), flush=True)
                    continue
                print("%5d %5d %8d %-9s %9.3f %9.3f %8.3f %7.3f %7.3f %9.2e %8.2f %9.2f | %8.3f %8.2e %7.2f | %5.2f" % (
                    level, ranks, 3 * row["contact"], path, row["SSStarSchur"], row["SSStarOrdering"], row["SSStarAnalysis"],
                    row["SSStarFactor"], row["SSStarSchurScat"], row["flops"], row["peak_gb"], row["total_s"], chol_t,
                    row["cholesky_flops"], row["cholesky_gb"], row["limit"]), flush=True)
    with open(os.path.join(OUT, "schur.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["level", "ranks", "threads", "path", "contact", "SSStarSchur", "SSStarOrdering",
                                          "SSStarAnalysis", "SSStarFactor", "SSStarSchurScat", "flops", "peak_gb", "total_s",
                                          "cholesky_s", "cholesky_flops", "cholesky_gb", "limit", "error"])
        w.writeheader()
        w.writerows(rows)
    plot(rows)
    print("wrote %s/schur.csv and schur.png" % OUT)


def plot(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_t, ax_m) = plt.subplots(1, 2, figsize=(12, 4.5))
    for (path, ranks) in sorted({(r["path"], r["ranks"]) for r in rows}):
        sel = [r for r in rows if r["path"] == path and r["ranks"] == ranks and not r["error"]]
        if not sel:
            continue
        lv = [r["level"] for r in sel]
        ax_t.semilogy(lv, [r["SSStarSchur"] for r in sel], "o-", label="%s, %d rank%s" % (path, ranks, "s" if ranks > 1 else ""))
        ax_m.semilogy(lv, [r["peak_gb"] for r in sel], "o-", label="%s, %d rank%s" % (path, ranks, "s" if ranks > 1 else ""))
    for ranks in sorted({r["ranks"] for r in rows}):
        chol = sorted({(r["level"], r["cholesky_s"], r["cholesky_gb"]) for r in rows if r["ranks"] == ranks})
        ax_t.semilogy([c[0] for c in chol], [c[1] for c in chol], "k--", label="Cholesky of K, %d rank%s" % (ranks, "s" if ranks > 1 else ""))
        ax_m.semilogy([c[0] for c in chol], [c[2] for c in chol], "k--", label="Cholesky of K, %d rank%s" % (ranks, "s" if ranks > 1 else ""))
    ax_t.set_xlabel("level")
    ax_t.set_ylabel("reduction time [s] (max over ranks)")
    ax_m.set_xlabel("level")
    ax_m.set_ylabel("peak memory of the largest rank [GB]")
    for ax in (ax_t, ax_m):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Schur reduction of the prism: direct (MUMPS + METIS), mumps (PETSc, rank 0), explicit")
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "schur.png"), dpi=120)


if __name__ == "__main__":
    main()
