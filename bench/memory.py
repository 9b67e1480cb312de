#!/usr/bin/python3
"""Where the memory goes, phase by phase: examples/prism on the whole body, the resident memory of the largest rank at
the end of each phase (the progress lines, VmRSS) and the run's peak (VmHWM), as bytes per dof of the ranks together
beyond what each process held before the mesh (its libraries), beside the estimate of the peak made before the work.

  bench/memory.py [--levels 16,24] [--ranks 1,2] [--config name='-opt ...'] ...

Writes bench/output/memory.csv: per level, ranks and configuration, each phase's increase (kB per dof), the peak's,
the estimate and its error."""
import argparse
import csv
import os
import re
import shlex
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output")
LINE = re.compile(r"^\s*(mesh: file|mesh: read|contact|assembly|nested|set-up|\s*\d+ SSStar|output).*, ([\d.]+) GB per rank", re.M)
ROW = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\d+)\s.*\s(\S+)\s([\d.]+)$", re.M)
DOFS = re.compile(r"^assembly: K of (\d+) dofs", re.M)
ESTIMATE = re.compile(r"estimated peak ([\d.]+) GB per rank")
PHASES = ["mesh", "contact", "assembly", "nested", "set-up", "newton", "output"]


def measure(level, ranks, options):
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), os.path.join(ROOT, "examples", "prism"), "-level", str(level), "-snes_ssstar_reduction", "none",
           "-summary_header", "0", "-o", os.path.join(OUT, "memory.h5")] + options
    out = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    row, dofs, est = ROW.search(out), DOFS.search(out), ESTIMATE.search(out)
    if not (row and dofs):
        print("level %d, %d ranks %s: failed\n%s" % (level, ranks, options, out[-1500:]))
        return None
    dofs = int(dofs.group(1))
    lines = LINE.findall(out)
    base = float(lines[0][1])
    last, inc = base, {p: 0.0 for p in PHASES}
    for name, gb in lines[1:]:
        gb = float(gb)
        phase = {"mesh: read": "mesh", "contact": "contact", "assembly": "assembly", "nested": "nested", "set-up": "set-up", "output": "output"}.get(name.strip(), "newton")
        inc[phase] += max(gb - last, 0.0)
        last = max(last, gb)
    peak = float(row.group(5))
    scale = 1e9 * ranks / dofs / 1e3  # GB per rank -> kB per dof of the ranks together
    r = {"level": level, "ranks": ranks, "dofs": dofs, "reason": row.group(4), "base_gb": base, "peak_gb": peak,
         "peak_kb_per_dof": (peak - base) * scale, "estimate_gb": float(est.group(1)) if est else float("nan")}
    for p in PHASES:
        r[p] = inc[p] * scale
    r["estimate_error"] = r["estimate_gb"] / peak - 1
    return r


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--levels", default="16,24")
    parser.add_argument("--ranks", default="1,2")
    parser.add_argument("--config", action="append", default=[], help="name='options' (default: the default configuration alone)")
    args = parser.parse_args()
    for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"), ("OPENBLAS_NUM_THREADS", "1")):
        os.environ.setdefault(k, v)
    os.makedirs(OUT, exist_ok=True)
    configs = [("default", [])] + [(c.partition("=")[0], shlex.split(c.partition("=")[2])) for c in args.config]
    rows = []
    print("kB per dof of the ranks together, beyond each process's memory before the mesh (base); the phases' increases of the largest rank's VmRSS")
    print("level ranks config            dofs   base[GB]  " + " ".join("%8s" % p for p in PHASES) + "   peak  peak[GB] estimate[GB] error")
    for level in (int(x) for x in args.levels.split(",")):
        for ranks in (int(x) for x in args.ranks.split(",")):
            for name, options in configs:
                r = measure(level, ranks, options)
                if not r:
                    continue
                r["config"] = name
                rows.append(r)
                print("%5d %5d %-16s %8d %8.3f  " % (level, ranks, name[:16], r["dofs"], r["base_gb"]) + " ".join("%8.2f" % r[p] for p in PHASES) +
                      "  %5.2f %8.3f %10.3f %+5.0f%%" % (r["peak_kb_per_dof"], r["peak_gb"], r["estimate_gb"], 100 * r["estimate_error"]), flush=True)
    with open(os.path.join(OUT, "memory.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
