#!/usr/bin/python3
"""The whole body on 1, 2, 4 and 8 ranks at about the same dofs per rank (weak scaling; more ranks than cores run
oversubscribed, so their times mean nothing, their counts and bytes do): examples/prism at the levels whose dofs per
rank are closest, with -ssstar_progress_ranks, -log_view and -memory_view.

  bench/ranks.py [--runs 1:8,2:10,4:13,8:16] [--extra '-nested_levels 0']

Per run: dofs per rank, Newton iterations, Krylov iterations per Newton step, the peak memory per rank (largest,
least: max/min), the largest ratio over the phases of rank 0's memory to the least rank's, and from -log_view the
messages, bytes and global reductions of the Krylov solves per Krylov iteration (summed over the ranks), the same of
the multigrid set-ups per set-up. Writes bench/output/ranks.csv; docs/guide/large-problems.md's model of 64-1024 ranks reads it."""
import argparse
import csv
import os
import re
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output")
ROW = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+(\d+)\s+([\d.]+)\s+(\d+)\s+([\d/]+)\s+([\d/]+)\s+(\S+)\s+([\d.]+)$", re.M)
KRYLOV = re.compile(r"last solve: (\d+) linear solves, (\d+) Krylov iterations \(\S+ per solve\), (\d+) preconditioner set-ups")
PHASE = re.compile(r"^\s*(mesh: read|contact|assembly|nested|set-up|\s*\d+ SSStar).*?([\d.]+) GB per rank \(rank 0: ([\d.]+), least: ([\d.]+)\)", re.M)
PEAK = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+(\S+)\s+max\s+(\S+)\s+min\s+(\S+)")


def event(log, name):
    """count, messages, average message length, reductions of a -log_view event"""
    m = re.search(r"^%s\s+(\d+)\s.*$" % re.escape(name), log, re.M)
    if not m:
        return 0, 0.0, 0.0, 0.0
    f = m.group(0).split()
    return int(f[1]), float(f[7]), float(f[8]), float(f[9])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", default="1:8,2:10,4:13,8:16", help="ranks:level pairs")
    parser.add_argument("--extra", default="-nested_levels 0", help="options added to every run")
    args = parser.parse_args()
    for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"), ("OPENBLAS_NUM_THREADS", "1")):
        os.environ.setdefault(k, v)
    os.makedirs(OUT, exist_ok=True)
    rows = []
    print("ranks level  dofs/rank  its  krylov/step  peak max/min [GB]  max/min  rank0/least (worst phase)  Krylov: msgs  kB  reductions per iteration  set-up: msgs  MB per set-up")
    for pair in args.runs.split(","):
        ranks, level = (int(x) for x in pair.split(":"))
        cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), os.path.join(ROOT, "examples", "prism"), "-level", str(level), "-snes_ssstar_reduction", "none",
               "-summary_header", "0", "-ssstar_progress_ranks", "-snes_view", "-log_view", "-memory_view"] + args.extra.split()
        out = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
        m, k, peak = ROW.search(out), KRYLOV.search(out), PEAK.search(out)
        if not (m and k and peak):
            print("%d ranks, level %d failed:\n%s" % (ranks, level, out[-2000:]))
            continue
        nodes, iters = int(m.group(3)), int(m.group(8))
        solves, krylov, setups = int(k.group(1)), int(k.group(2)), int(k.group(3))
        phases = PHASE.findall(out)
        worst = max(((float(r0) / float(least), name.strip()) for name, _, r0, least in phases), default=(1.0, "-"))
        kc, kmsg, klen, kred = event(out, "KSPSolve")
        sc, smsg, slen, sred = event(out, "SSStarNSFactor")
        row = {"ranks": ranks, "level": level, "dofs_per_rank": 3 * nodes / ranks, "iters": iters, "krylov_per_step": krylov / solves,
               "peak_max_gb": float(peak.group(2)) / 1e9, "peak_min_gb": float(peak.group(3)) / 1e9, "peak_ratio": float(peak.group(2)) / float(peak.group(3)),
               "rank0_over_least": worst[0], "worst_phase": worst[1], "msgs_per_krylov": kmsg / krylov, "kb_per_krylov": kmsg * klen / krylov / 1e3,
               "reductions_per_krylov": kred / krylov, "msgs_per_setup": smsg / max(setups, 1), "mb_per_setup": smsg * slen / max(setups, 1) / 1e6}
        rows.append(row)
        print("%5d %5d %10.0f %4d %11.1f %8.3f / %.3f %8.2f %6.2f (%s) %22.0f %5.0f %9.1f %20.0f %8.1f" % (
            ranks, level, row["dofs_per_rank"], iters, row["krylov_per_step"], row["peak_max_gb"], row["peak_min_gb"], row["peak_ratio"],
            row["rank0_over_least"], worst[1], row["msgs_per_krylov"], row["kb_per_krylov"], row["reductions_per_krylov"], row["msgs_per_setup"], row["mb_per_setup"]), flush=True)
    with open(os.path.join(OUT, "ranks.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
