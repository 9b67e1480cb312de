#!/usr/bin/python3
"""What an effect costs: the prism scene with its effects switched on and off, side by side (make bench-scenes).

  bench/scenes.py [--level 8] [--repeat 3]

Rows: examples/prism; the same scene through examples/contact (scenes/prism.opts); frictionless
(-friction_law_contact none); no contact group (one linear solve); with gravity. Columns are medians over the repeats
of the phases (mesh + assembly, Schur reduction, solve), the iterations, and the time and flops of the log events
SSStarAssembly (the FEM), SSStarAS (approximation steps) and SSStarNS (Newton steps) from -log_view. An effect that is
switched off must cost nothing: the driver's prism row matches examples/prism, the rows without an effect do no work
for it. Writes bench/output/scenes.csv."""
import argparse
import csv
import os
import re
import statistics
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
PRISM_SCENE = os.path.join(ROOT, "scenes", "prism.opts")


def scene_without(*prefixes):
    """The prism scene's options without those starting with the prefixes"""
    words = []
    for line in open(PRISM_SCENE):
        line = line.strip()
        if line and not line.startswith("#") and not line.startswith(prefixes):
            words += line.split()
    return words


VARIANTS = [
    ("examples/prism", [os.path.join(ROOT, "examples", "prism")]),
    ("contact: prism scene (Coulomb)", [os.path.join(ROOT, "examples", "contact"), "-options_file", PRISM_SCENE]),
    ("contact: frictionless", [os.path.join(ROOT, "examples", "contact")] + scene_without("-friction") + ["-friction_law_contact", "none"]),
    ("contact: no contact group", [os.path.join(ROOT, "examples", "contact")] + scene_without("-friction", "-contact")),
    ("contact: Coulomb + gravity", [os.path.join(ROOT, "examples", "contact"), "-options_file", PRISM_SCENE, "-gravity", "0,0,-9.81", "-density", "7.85e-9"]),
]


def event(out, name):
    """(time, flops) of a -log_view event line"""
    m = re.search(r"^%s\s+(\d+)\s+\S+\s+(\S+)\s+\S+\s+(\S+)" % name, out, re.M)
    return (float(m.group(2)), float(m.group(3))) if m else (0.0, 0.0)


def measure(cmd, level):
    out = subprocess.run(cmd + ["-level", str(level), "-log_view"], cwd=ROOT, env=ENV, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True, check=True).stdout
    m = re.search(r"summary: nodes \d+ contact \d+ assembly ([\d.]+) s schur ([\d.]+) s solve ([\d.]+) s iterations (\d+)", out)
    if m:
        phases = [float(m.group(k)) for k in (1, 2, 3)] + [int(m.group(4))]
    else:  # examples/prism's Table 2 row
        m = re.search(r"^\s*-?\d+\s+\d+\s+\d+\s+([\d.]+)\s+([\d.]+)\s+\d+\s+([\d.]+)\s+(\d+)", out, re.M)
        phases = [float(m.group(k)) for k in (1, 2, 3)] + [int(m.group(4))]
    fem, _ = event(out, "SSStarAssembly")
    as_t, as_f = event(out, "SSStarAS")
    ns_t, ns_f = event(out, "SSStarNS")
    return phases + [fem, as_t, as_f, ns_t, ns_f]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--level", type=int, default=8)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    header = ["variant", "assembly[s]", "schur[s]", "solve[s]", "iterations", "FEM event[s]", "AS[s]", "AS flops", "NS[s]", "NS flops"]
    rows = []
    runs = {name: [] for name, _ in VARIANTS}
    for _ in range(args.repeat):  # interleaved, so that the load of a shared machine hits every variant alike
        for name, cmd in VARIANTS:
            runs[name].append(measure(cmd, args.level))
    print("level %d, medians of %d runs" % (args.level, args.repeat))
    print("%-32s %11s %8s %8s %5s %8s %8s %9s %8s %9s" % tuple(header))
    for name, _ in VARIANTS:
        med = [statistics.median(col) for col in zip(*runs[name])]
        rows.append([name] + med)
        print("%-32s %11.3f %8.3f %8.3f %5d %8.3f %8.4f %9.3g %8.3f %9.3g" % tuple([name] + med))
    os.makedirs(os.path.join(ROOT, "bench", "output"), exist_ok=True)
    with open(os.path.join(ROOT, "bench", "output", "scenes.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["level"] + header)
        for row in rows:
            w.writerow([args.level] + row)


if __name__ == "__main__":
    main()
