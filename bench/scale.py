#!/usr/bin/python3
"""The scale table (docs/guide/scale.md; issue 34): examples/prism at the defaults on the whole body at levels 16-48 on
2 ranks, each beside one AMG solve of the same K measured in the same run (bench/yardstick -yardstick amg), and level
10 against GetFEM 5.4 in the same run. Run by bench/table2.py --large (make bench-large):

  bench/table2.py --large [--levels 16,24,32,40,48] [--ranks 2] [--repeat 3] [--refine-also 48] [--getfem-level 10]
                          [--timeout 7200]

Per level (and mesh route: gmsh's -level L, and for the levels of --refine-also also level L/2 refined once in
parallel, -dm_refine 1, the same nodes), --repeat times: the yardstick, then the run (interleaved, so that a noisy
spell of a shared machine hits both); the medians. Columns: the whole run (the process's wall time, mesh to the -o
file written); the solve (nested start + set-up + Newton steps: the summary row's solve and schur) and the yardstick
(GAMG's set-up + one CG solve to 1e-8, its iterations); solve / yardstick; the set-up (the progress line `set-up:`: the
multigrid of the free dofs and their equilibrium solves) / the yardstick's GAMG set-up; the Newton steps and Krylov
iterations on the finest mesh; the peak of the largest rank (VmHWM) against the estimate printed before the work; bytes
per dof (the peak times the ranks over the dofs). The yardstick is skipped where GAMG's smoothed hierarchy of K would
not fit the memory available (YARDSTICK_KB_PER_DOF). A run that fails, is refused or exceeds --timeout leaves its row
marked and the next one runs.

Level 10 against GetFEM (bench/getfem_prism.py: the same mesh and scene, GetFEM in one process with MUMPS): the whole
runs interleaved, medians, the ratio, the normal forces' agreement, and ssstar's phases at level 10 from its progress
lines (mesh, contact, assembly, nested, set-up, Newton steps, output, and the rest of the process: start-up, MPI,
finalize) -- the floor of a small run.

Writes bench/output/scale.csv (a row per level and route, rewritten as each finishes), bench/output/scale.md (the table,
with the command, the date and the load average before and after) and table2_large_targets.png."""
import csv
import math
import os
import re
import signal
import statistics
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "bench", "output")
# the targets of issue 34
WHOLE_TARGET = {16: 4.0, 32: 40.0, 40: 100.0}
SOLVE_TARGET, SETUP_TARGET, KB_TARGET, GETFEM_TARGET = 2.0, 1.2, 2.5, 25.0
# GAMG's smoothed hierarchy of K with the mesh and K (bench/yardstick: measured at levels 16 and 24 on 2 ranks, 4.0
# and 3.8 kB per dof at the peak): the yardstick runs only where this fits MemAvailable
YARDSTICK_KB_PER_DOF = 4.5

ROW = re.compile(r"^\s*(\d+)(?:r\d+)?\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+(\d+)\s+([\d.]+)\s+(\d+)\s+([\d/]+)\s+([\d/]+)\s+(\S+)\s+([\d.]+)$", re.M)
AMG = re.compile(r"amg level \d+ ranks \d+ dofs (\d+) setup (\S+) solve (\S+) its (\d+)")
YPEAK = re.compile(r"^peak ([\d.]+) GB per rank", re.M)
KRYLOV = re.compile(r"last solve: (\d+) linear solves, (\d+) Krylov iterations")
ESTIMATE = re.compile(r"estimated peak ([\d.]+) GB per rank")
MESH = re.compile(r"^mesh: file (\S+?), \d+ nodes", re.M)
DOFS = re.compile(r"^assembly: K of (\d+) dofs", re.M)
# the progress lines' seconds: "<phase>: ..., <s> s, <GB> GB per rank"; a Newton step's "step <s> s"
PHASE = re.compile(r"^\s*(mesh|contact|assembly|nested|set-up|output): .*?([\d.]+) s, [\d.]+ GB per rank", re.M)
STEP = re.compile(r"^\s*\d+ SSStar \|\|z\|\| .*; step ([\d.]+) s", re.M)
PHASES = ["mesh", "contact", "assembly", "nested", "set-up", "newton", "output"]


def load():
    return "%.1f %.1f %.1f" % os.getloadavg()


def dofs_of(level, refine):
    """the prism's dofs at level L (L/2 refined once has the same nodes): (2L+1)^2 (4L+1) nodes, 3 dofs each, less the
    held face's (2L+1)^2"""
    return 3 * (2 * level + 1) ** 2 * 4 * level


def run(cmd, timeout):
    """(return code, output, seconds); a run over the timeout is killed with its process group (rc None)"""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        out, _ = p.communicate(timeout=timeout)
        rc = p.returncode
    except subprocess.TimeoutExpired:
        for sig in (signal.SIGTERM, signal.SIGKILL):
            try:
                os.killpg(p.pid, sig)
            except ProcessLookupError:
                break
            time.sleep(5)
        out, _ = p.communicate()
        rc = None
    return rc, out, time.perf_counter() - t0


def mesh_args(level, refined):
    return ["-level", str(level // 2), "-dm_refine", "1"] if refined else ["-level", str(level)]


def mem_available():
    with open("/proc/meminfo") as f:
        for line in f:
            if line.startswith("MemAvailable:"):
                return float(line.split()[1]) * 1e3
    return math.inf


def yardstick(level, ranks, refined, timeout):
    """one CG + GAMG solve of K: {setup, solve, its, peak_gb}, or a note why not"""
    need = YARDSTICK_KB_PER_DOF * 1e3 * dofs_of(level, refined)
    if need > mem_available():
        return {"note": "not run: GAMG's smoothed hierarchy of K needs about %.0f GB, more than the %.0f GB available" % (need / 1e9, mem_available() / 1e9)}
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), os.path.join(ROOT, "bench", "yardstick"), "-yardstick", "amg", "-options_file",
           os.path.join(ROOT, "scenes", "prism.opts")] + mesh_args(level, refined)
    rc, out, _ = run(cmd, timeout)
    m, p = AMG.search(out), YPEAK.search(out)
    if rc != 0 or not m:
        return {"note": "failed (%s): %s" % ("timeout" if rc is None else "exit status %d" % rc, out.strip().splitlines()[-1] if out.strip() else "")}
    return {"setup": float(m.group(2)), "solve": float(m.group(3)), "its": int(m.group(4)), "peak_gb": float(p.group(1)) if p else math.nan}


def prism(level, ranks, refined, timeout, keep=False):
    """examples/prism at the defaults: the whole run, its phases and counts, or a note why not"""
    h5 = os.path.join(OUT, "scale_L%d%s.h5" % (level, "_refined" if refined else ""))
    cmd = ["mpiexec", "--oversubscribe", "-n", str(ranks), os.path.join(ROOT, "examples", "prism")] + mesh_args(level, refined) + [
        "-summary_header", "0", "-snes_view", "-o", h5]
    rc, out, whole = run(cmd, timeout)
    with open(h5[:-3] + ".log", "w") as f:  # the last repeat's progress lines and -snes_view
        f.write(out)
    m = ROW.search(out)
    if rc != 0 or not m:
        why = "timeout" if rc is None else "killed (out of memory?)" if rc < 0 or rc == 137 else "exit status %d" % rc
        last = [line for line in out.strip().splitlines() if "ERROR" in line or "refused" in line or "Unknown" in line]
        return {"note": "failed (%s)%s" % (why, ": " + last[0][:200] if last else "")}
    k, e, d, mesh = KRYLOV.search(out), ESTIMATE.search(out), DOFS.search(out), MESH.search(out)
    r = {"whole": whole, "solve": float(m.group(7)) + float(m.group(5)), "iters": int(m.group(8)), "states": m.group(10), "reason": m.group(11),
         "peak_gb": float(m.group(12)), "krylov": int(k.group(2)) if k else 0, "estimate_gb": float(e.group(1)) if e else math.nan,
         "dofs": int(d.group(1)) if d else dofs_of(level, refined), "nodes": int(m.group(3)), "mesh_file": mesh.group(1) if mesh else None}
    for p in PHASES:
        r[p] = 0.0
    for name, s in PHASE.findall(out):
        r[name] += float(s)
    r["newton"] = sum(float(s) for s in STEP.findall(out))
    r["setup"] = r["set-up"]
    if keep:
        import h5py
        with h5py.File(h5, "r") as f:
            r["force_n"] = float(f["contact/reaction"][:].sum(axis=0)[2])
    for name in (h5, h5[:-3] + ".xmf"):
        if os.path.exists(name):
            os.remove(name)
    return r


def median(runs, key):
    vals = [r[key] for r in runs if key in r and not (isinstance(r[key], float) and math.isnan(r[key]))]
    return statistics.median(vals) if vals else math.nan


def fmt(x, f="%.2f"):
    return "–" if x is None or (isinstance(x, float) and math.isnan(x)) else f % x


def table(rows, getfem_row):
    lines = ["| level | dofs | whole run [s] (target) | the solve [s] = nested + set-up + Newton | AMG yardstick [s] = set-up + solve (its) | solve ÷ yardstick (≤ 2) "
             "| set-up ÷ GAMG set-up (≤ 1.2) | Newton steps / Krylov its, finest mesh | peak per rank [GB] (estimate) | kB per dof (≤ 2.5 at 24–48) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        name = "%d%s" % (r["level"], " (level %d refined once)" % (r["level"] // 2) if r["refined"] else "")
        if "note" in r:
            lines.append("| %s | %s | %s | | | | | | | |" % (name, fmt(r.get("dofs_est"), "%d"), r["note"]))
            continue
        target = WHOLE_TARGET.get(r["level"])
        y = "%s = %s + %s (%d)" % (fmt(r["amg"]), fmt(r["amg_setup"]), fmt(r["amg_solve"]), r["amg_its"]) if r.get("amg_its") else r.get("amg_note", "–")
        lines.append("| %s | %.3g M | %s%s | %s = %s + %s + %s | %s | **%s** | %s | %d / %d | %s (%s) | **%s** |" % (
            name, r["dofs"] / 1e6, fmt(r["whole"]), " (≤ %g)" % target if target else "", fmt(r["solve"]), fmt(r["nested"]), fmt(r["setup"]), fmt(r["newton"]),
            y, fmt(r["solve_per_amg"]), fmt(r["setup_per_amg"]), r["iters"], r["krylov"], fmt(r["peak_gb"], "%.3f"), fmt(r["estimate_gb"], "%.3f"),
            fmt(r["kb_per_dof"])))
    if getfem_row:
        g = getfem_row
        if "note" in g:
            lines.append("\nLevel %d against GetFEM 5.4: %s" % (g["level"], g["note"]))
        else:
            lines.append("\nLevel %d against GetFEM 5.4 (same mesh and scene; GetFEM one process, MUMPS, Alart–Curnier; ssstar %d ranks, whole runs, medians of %d): "
                         "ssstar %.2f s, GetFEM %.2f s: **%.1f×** (target ≥ %g); normal force %.7g against %.7g (%.1e apart), ssstar %d Newton steps."
                         % (g["level"], g["ranks"], g["runs"], g["ssstar"], g["getfem"], g["ratio"], GETFEM_TARGET, g["force_n"], g["getfem_force_n"],
                            abs(g["force_n"] - g["getfem_force_n"]) / abs(g["force_n"]), g["iters"]))
            lines.append("ssstar's floor at level %d (the progress lines, medians): %s, the rest of the process (start-up, MPI, finalize) %.2f s." % (
                g["level"], ", ".join("%s %.2f s" % (p, g[p]) for p in PHASES), g["rest"]))
    return "\n".join(lines)


def write(rows, getfem_row, header):
    fields = ["level", "refined", "ranks", "runs", "dofs", "nodes", "whole", "solve", "nested", "setup", "newton", "mesh", "contact", "assembly", "output",
              "amg", "amg_setup", "amg_solve", "amg_its", "amg_peak_gb", "solve_per_amg", "setup_per_amg", "iters", "krylov", "peak_gb", "estimate_gb",
              "kb_per_dof", "reason", "note", "amg_note"]
    with open(os.path.join(OUT, "scale.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    text = header + "\n\n" + table(rows, getfem_row) + "\n"
    with open(os.path.join(OUT, "scale.md"), "w") as f:
        f.write(text)
    return text


def compare_getfem(level, ranks, repeat, timeout):
    try:
        from getfem_prism import getfem
        import getfem as _  # noqa: F401 (Debian's python3-getfem)
    except ImportError:
        return {"level": level, "note": "not measured: GetFEM is not installed (Debian's python3-getfem; configure.py installs it as root)"}
    first = prism(level, ranks, False, timeout)  # meshes the level and writes its cache (not timed)
    if "note" in first:
        return {"level": level, "note": "ssstar " + first["note"]}
    runs, gs = [], []
    for _ in range(repeat):
        gs.append(getfem(first["mesh_file"]))
        r = prism(level, ranks, False, timeout, keep=True)
        if "note" in r:
            return {"level": level, "note": "ssstar " + r["note"]}
        runs.append(r)
    g = {"level": level, "ranks": ranks, "runs": repeat, "ssstar": median(runs, "whole"), "getfem": statistics.median(x["whole"] for x in gs),
         "ratio": statistics.median(x["whole"] / r["whole"] for x, r in zip(gs, runs)), "force_n": runs[0]["force_n"], "getfem_force_n": gs[0]["force_n"],
         "iters": runs[0]["iters"]}
    for p in PHASES:
        g[p] = median(runs, p)
    g["rest"] = g["ssstar"] - sum(g[p] for p in PHASES)
    return g


def main(args):
    os.makedirs(OUT, exist_ok=True)
    levels = [int(x) for x in (args.levels or "16,24,32,40,48").split(",")]
    ranks = int((args.ranks or "2").split(",")[0])
    refine_also = [int(x) for x in args.refine_also.split(",") if x]
    header = ("bench/table2.py --large --levels %s --ranks %d --repeat %d --refine-also %s --getfem-level %s; %s; load average before: %s" % (
        ",".join(map(str, levels)), ranks, args.repeat, args.refine_also or "''", args.getfem_level, time.strftime("%Y-%m-%d %H:%M"), load()))
    print(header, flush=True)
    rows, getfem_row = [], None
    for level, refined in [(lv, False) for lv in levels] + [(lv, True) for lv in refine_also]:
        if refined and level % 2:
            continue
        runs, sticks = [], []
        for rep in range(args.repeat):
            y = yardstick(level, ranks, refined, args.timeout)
            sticks.append(y)
            r = prism(level, ranks, refined, args.timeout)
            runs.append(r)
            print("  level %d%s, repeat %d (load %s): yardstick %s; run %s" % (level, " refined" if refined else "", rep, load(),
                  y.get("note") or "%.2f + %.2f s, %d its, %.3f GB per rank" % (y["setup"], y["solve"], y["its"], y["peak_gb"]),
                  r.get("note") or "%.2f s whole, solve %.2f s (nested %.2f, set-up %.2f, Newton %.2f), %d steps, %d Krylov its, %.3f GB per rank" % (
                      r["whole"], r["solve"], r["nested"], r["setup"], r["newton"], r["iters"], r["krylov"], r["peak_gb"])), flush=True)
            if "note" in r:  # a failed run is not repeated
                break
        ok = [r for r in runs if "note" not in r]
        row = {"level": level, "refined": refined, "ranks": ranks, "runs": len(ok), "dofs_est": dofs_of(level, refined)}
        if not ok:
            row["note"] = runs[0]["note"]
            rows.append(row)
            write(rows, getfem_row, header)
            continue
        for key in ("whole", "solve", "nested", "setup", "newton", "mesh", "contact", "assembly", "output", "peak_gb", "estimate_gb"):
            row[key] = median(ok, key)
        for key in ("dofs", "nodes", "iters", "krylov", "reason"):
            row[key] = ok[0][key]
        good = [y for y in sticks if "note" not in y]
        if good:
            row.update({"amg_setup": median(good, "setup"), "amg_solve": median(good, "solve"), "amg_its": good[0]["its"], "amg_peak_gb": median(good, "peak_gb")})
            row["amg"] = row["amg_setup"] + row["amg_solve"]
            row["solve_per_amg"] = statistics.median(r["solve"] / (y["setup"] + y["solve"]) for r, y in zip(runs, sticks) if "note" not in r and "note" not in y)
            row["setup_per_amg"] = statistics.median(r["setup"] / y["setup"] for r, y in zip(runs, sticks) if "note" not in r and "note" not in y)
        else:
            row["amg_note"] = sticks[0]["note"]
            row["solve_per_amg"] = row["setup_per_amg"] = math.nan
        row["kb_per_dof"] = row["peak_gb"] * 1e9 * ranks / row["dofs"] / 1e3
        rows.append(row)
        write(rows, getfem_row, header)
    if args.getfem_level:
        getfem_row = compare_getfem(args.getfem_level, ranks, args.repeat, args.timeout)
    header += "; load average after: %s" % load()
    print(write(rows, getfem_row, header), flush=True)
    plot(rows)
    print("wrote %s/scale.csv, scale.md and table2_large_targets.png" % OUT)


def plot(rows):
    """table2_large_targets.png: the solve in AMG yardsticks, the bytes per dof (measured and estimated), the Newton steps
    and Krylov iterations, against the level"""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rs = sorted((r for r in rows if "note" not in r and not r["refined"]), key=lambda r: r["level"])
    if not rs:
        return
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    lv = [r["level"] for r in rs]
    axes[0].plot(lv, [r["solve_per_amg"] for r in rs], "-o", label="the solve / one AMG solve of K")
    axes[0].plot(lv, [r["setup_per_amg"] for r in rs], "--s", label="set-up / GAMG's set-up")
    axes[1].plot(lv, [r["kb_per_dof"] for r in rs], "-o", label="peak")
    axes[1].plot(lv, [r["estimate_gb"] * 1e9 * r["ranks"] / r["dofs"] / 1e3 for r in rs], "--", alpha=0.6, label="estimate")
    axes[2].plot(lv, [r["iters"] for r in rs], "-o", label="Newton steps")
    axes[2].plot(lv, [r["krylov"] for r in rs], "-s", label="Krylov iterations (finest mesh)")
    axes[2].plot(lv, [r.get("amg_its", math.nan) for r in rs], ":", label="the yardstick's CG iterations")
    for ax, title, targets in ((axes[0], "ratios to the AMG yardstick (same run)", (SOLVE_TARGET, SETUP_TARGET)), (axes[1], "kB per dof (peak x ranks / dofs)", (KB_TARGET,)),
                               (axes[2], "iterations", ())):
        for t in targets:
            ax.axhline(t, color="black", lw=0.8, ls=":")
        ax.set_xlabel("level (2 ranks)")
        ax.set_title(title, fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "table2_large_targets.png"), dpi=110)
