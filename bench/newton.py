#!/usr/bin/python3
"""The Newton phase of ssstar (event SSStarNS) on the prism, without the Schur step: bench/newton_step loads P, f of a
level (written once into bench/output/data/ by examples/prism -save_reduced) and solves the reduced problem from u = 0.

  bench/newton.py [--levels 4,6,8,10,12,14,16] [--ranks 1,2] [--repeat 3] [--lu-sizes 1000,2000,3300,5000]

Configurations per level: 1 rank; 2 ranks with mpiexec's core binding (rank 0 factors with one BLAS thread) and with
--bind-to none -snes_ssstar_lu_threads 0 (its BLAS uses the core of the sleeping rank too); each with the default reuse of the LU
(-snes_ssstar_lu_reuse 0) and with a fresh LU at every step (-1). Writes bench/output/newton.csv and newton.png
(medians), and with --lu-sizes the dense-LU comparison (bench/dense_lu: LAPACK on rank 0 with 1 and 2 threads against
ScaLAPACK on 2 ranks) into bench/output/dense_lu.csv. OpenBLAS's kernel is the one it detects (or OPENBLAS_CORETYPE, if
set): report it with the figures."""
import argparse
import csv
import io
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output")
STEP = os.path.join(ROOT, "bench", "newton_step")
# (name, ranks, mpiexec binding, options)
CONFIGS = [("1 rank", 1, "core", []), ("2 ranks", 2, "core", []), ("2 ranks, LU on 2 threads", 2, "none", ["-snes_ssstar_lu_threads", "0"])]
REUSE = [("reuse", "0"), ("fresh LU", "-1")]


def mpiexec(ranks, binding, *args):
    return ["mpiexec", "--oversubscribe", "--bind-to", binding, "-n", str(ranks)] + [a for a in args]


def run(cmd):
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), p.stdout[-3000:]))
    return p.stdout


def data(level):
    """P, f of the prism at this level (the Schur step runs once)"""
    path = os.path.join(OUT, "data", "P_L%d.bin" % level)
    if not os.path.exists(path):
        print("computing P, f of level %d into %s" % (level, path), flush=True)
        run(["mpiexec", "-n", "1", os.path.join(ROOT, "examples", "prism"), "-level", str(level), "-save_reduced", path])
    return path


def newton(level, ranks, binding, options, reuse, repeat):
    out = run(mpiexec(ranks, binding, STEP, "-file", data(level), "-level", str(level), "-repeat", str(repeat), "-snes_ssstar_lu_reuse", reuse, *options))
    lines = [l for l in out.splitlines() if l and not l.startswith("#")]
    runs = list(csv.DictReader(io.StringIO("\n".join(lines))))
    if not runs:
        sys.exit("no result from bench/newton_step at level %d\n%s" % (level, out[-2000:]))
    first = runs[0]
    return {"level": level, "dofs": int(first["dofs"]), "iterations": int(first["iterations"]), "lu": int(first["lu"]),
            "reused": int(first["reused"]), "krylov_its": int(first["krylov_its"]), "reason": first["reason"],
            "newton_seconds": statistics.median(float(r["newton_seconds"]) for r in runs)}


def dense_lu(sizes, repeat):
    out = run(mpiexec(2, "none", os.path.join(ROOT, "bench", "dense_lu"), "-n", sizes, "-nb", "64,128", "-repeat", str(repeat)))
    with open(os.path.join(OUT, "dense_lu.csv"), "w") as f:
        f.write(out)
    print(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--levels", default="4,6,8,10,12,14,16")
    parser.add_argument("--ranks", default="1,2")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--lu-sizes", default="")
    args = parser.parse_args()
    os.makedirs(os.path.join(OUT, "data"), exist_ok=True)
    for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"), ("OPENBLAS_NUM_THREADS", "1")):
        os.environ.setdefault(k, v)
    ranks = [int(r) for r in args.ranks.split(",")]
    rows = []
    print("Newton phase (SSStarNS), median of %d solves; OPENBLAS_CORETYPE=%s" % (args.repeat, os.environ.get("OPENBLAS_CORETYPE", "(detected)")))
    print("level   3p  configuration                  LU policy  iters  LU  reused  Krylov its  seconds")
    for level in (int(l) for l in args.levels.split(",")):
        for name, nranks, binding, options in CONFIGS:
            if nranks not in ranks:
                continue
            for policy, reuse in REUSE:
                row = newton(level, nranks, binding, options, reuse, args.repeat)
                row.update({"configuration": name, "ranks": nranks, "binding": binding, "policy": policy})
                print("%5d %5d  %-30s %-9s %5d %3d %7d %11d %8.3f  %s" % (level, row["dofs"], name, policy, row["iterations"], row["lu"],
                                                                        row["reused"], row["krylov_its"], row["newton_seconds"],
                                                                        "" if row["reason"].startswith("CONVERGED") else row["reason"]), flush=True)
                rows.append(row)
    with open(os.path.join(OUT, "newton.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["level", "dofs", "configuration", "ranks", "binding", "policy", "iterations", "lu", "reused",
                                          "krylov_its", "newton_seconds", "reason"])
        w.writeheader()
        w.writerows(rows)
    plot(rows)
    print("wrote %s/newton.csv and newton.png" % OUT)
    if args.lu_sizes:
        dense_lu(args.lu_sizes, args.repeat)


def plot(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 5))
    colors = {c[0]: color for c, color in zip(CONFIGS, ("tab:blue", "tab:red", "tab:green"))}
    for name in colors:
        for policy, style in (("reuse", "-o"), ("fresh LU", ":s")):
            pts = [(r["dofs"], r["newton_seconds"]) for r in rows if r["configuration"] == name and r["policy"] == policy]
            if pts:
                ax.loglog(*zip(*pts), style, color=colors[name], label="%s, %s" % (name, policy))
    ax.set_xlabel("contact dofs 3p")
    ax.set_ylabel("Newton phase, seconds (median)")
    ax.set_title("ssstar Newton steps on the prism (eliminated dense system)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "newton.png"), dpi=120)


if __name__ == "__main__":
    main()
