"""The mesh axis of the work-precision study (bench/accuracy.py): Hertz's sphere on a plane (scenes/hertz.opts) at
mesh levels L and stopping tolerances t, each a whole run of examples/contact; the contact radius and the peak pressure
measured by tests/scene_answers.py against Hertz's closed forms for the force the plane carries, against the whole
run's seconds. Also the prism's contact solution read from an examples/prism -o file, in the order of the reduced
problem (bench/accuracy_worker.py), for the whole-body path."""
import json
import os
import re
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))
import scene_answers  # noqa: E402 (the project's measurement of Hertz's answers)

SUMMARY = re.compile(r"^summary: nodes (\d+) contact (\d+) assembly ([\d.]+) s schur ([\d.]+) s solve ([\d.]+) s iterations (\d+) .* (\S+) peak", re.M)
ROUTE = re.compile(r"set-up: (the whole body|K reduced)")
HERTZ_COLUMNS = ["level", "eps", "ranks", "route", "nodes", "contact", "iterations", "assembly_s", "schur_s", "solve_s", "whole_s", "force",
                 "a_error", "p0_error", "bracket_error", "vm_error", "vm_depth_error", "reason"]
VON_MISES = ("vm_max", "vm_depth", "vm_error", "vm_depth_error")


def environment():
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")


def mpiexec(ranks):
    return ["mpiexec", "--oversubscribe", "-n", str(ranks)] if ranks > 1 else []


JOURNAL = {}  # {"file": path}: the runs of an --extend measurement, kept as they end so that a failed one resumes


def timed(cmd):
    """runs cmd, returns (stdout, wall seconds); exits with the output on failure; with a journal, a run it holds is
    not run again (its output and seconds come from the journal)"""
    key, runs = " ".join(cmd), JOURNAL.get("runs", {})
    if key in runs:
        return tuple(runs[key])
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=environment())
    if p.returncode:
        sys.exit("failed: %s\n%s" % (key, p.stdout[-3000:]))
    if "file" in JOURNAL:
        runs[key] = (p.stdout, time.perf_counter() - t0)
        JOURNAL["runs"] = runs
        with open(JOURNAL["file"], "w") as f:
            json.dump(runs, f)
    return p.stdout, time.perf_counter() - t0


def hertz_run(level, eps, ranks, work):
    """one whole run of the hertz scene; its costs and its errors against Hertz's formulas"""
    h5 = os.path.join(work, "hertz_L%d_%g.h5" % (level, eps))
    out, whole = timed(mpiexec(ranks) + [os.path.join(ROOT, "examples", "contact"), "-options_file", os.path.join(ROOT, "scenes", "hertz.opts"),
                                         "-level", str(level), "-snes_rtol", "%g" % eps, "-o", h5])
    m, route = SUMMARY.search(out), ROUTE.search(out)
    h = scene_answers.hertz(h5)
    return {"level": level, "eps": eps, "ranks": ranks, "route": "none" if route and route.group(1) == "the whole body" else "direct",
            "nodes": int(m.group(1)), "contact": int(m.group(2)), "iterations": int(m.group(6)), "assembly_s": float(m.group(3)),
            "schur_s": float(m.group(4)), "solve_s": float(m.group(5)), "whole_s": whole, "force": h["force"], "a_error": h["a_error"],
            "p0_error": h["p0_error"], "bracket_error": 0.5 * (h["a_inside"] + h["a_outside"]) / h["a_hertz"] - 1, "reason": m.group(7),
            **von_mises(h5)}


def von_mises(h5):
    """Hertz's subsurface von Mises maximum of a hertz run's file (tests/scene_answers.py): its value and depth errors"""
    v = scene_answers.von_mises(h5)
    return {k: v[k] for k in VON_MISES}


def hertz_sweep(levels, tols, ranks, work, progress=print):
    rows = []
    for level in levels:
        for eps in tols:
            rows.append(hertz_run(level, eps, ranks, work))
            progress("hertz level %d rtol %g: p0 %+.4f a %+.4f, %.1f s" % (level, eps, rows[-1]["p0_error"], rows[-1]["a_error"], rows[-1]["whole_s"]))
    return rows


def prism_contact(h5, coordinates=None):
    """(x, u, r) of the contact nodes of an examples/prism -o file (the plane z = 0: u = (u_t, u_n) = (u_x, u_y, u_z)),
    in the order of the reduced problem's coordinates when they are given"""
    import h5py
    with h5py.File(h5, "r") as f:
        c = f["contact"]
        x, u, r = c["coordinates"][:], c["displacement"][:], c["reaction"][:]
    if coordinates is None:
        return x, u, r
    index = {tuple(np.round(p, 9)): i for i, p in enumerate(x)}
    order = [index[tuple(np.round(p, 9))] for p in np.asarray(coordinates).reshape(-1, 3)]
    return x[order], u[order], r[order]


def tolerance_floor(rows, key):
    """per level: the loosest tolerance from which on the answer moves by less than a tenth of its error (against
    the tightest tolerance of the level): beyond it the mesh dominates and tightening buys nothing"""
    out = {}
    for level in sorted({r["level"] for r in rows}):
        runs = sorted((r for r in rows if r["level"] == level), key=lambda r: -r["eps"])
        tight = runs[-1][key]
        out[level] = next(r for r in runs if all(abs(s[key] - tight) <= 0.1 * abs(tight) for s in runs if s["eps"] <= r["eps"]))
    return out


MINDLIN_COLUMNS = ["level", "eps", "ranks", "route", "contact", "iterations", "solve_s", "whole_s", "ratio", "c", "stick_outer", "slide_inner",
                   "c_error", "bracket"]


def mindlin_run(level, eps, ranks, work):
    """Cattaneo-Mindlin (scenes/mindlin.opts: the half ball pressed by P on a block of the same material, then sheared by
    Q = 0.5 phi P): the stick radius, the midpoint between the outermost sticking node and the innermost sliding one,
    against c = a (1 - Q/(phi P))^(1/3) with Hertz's a for the measured P (c_error = c_measured / c - 1; bracket: the
    radial gap between the two nodes over c)"""
    h5 = os.path.join(work, "mindlin_L%d_%g.h5" % (level, eps))
    out, whole = timed(mpiexec(ranks) + [os.path.join(ROOT, "examples", "contact"), "-options_file", os.path.join(ROOT, "scenes", "mindlin.opts"),
                                         "-level", str(level), "-snes_rtol", "%g" % eps, "-snes_ssstar_reduction", "direct", "-o", h5])
    m, route = SUMMARY.search(out), ROUTE.search(out)
    c = scene_answers.stick_radius(h5, 0.3, 2.1e5)
    return {"level": level, "eps": eps, "ranks": ranks, "route": "none" if route and route.group(1) == "the whole body" else "direct",
            "contact": int(m.group(2)), "iterations": int(m.group(6)), "solve_s": float(m.group(5)), "whole_s": whole, "ratio": c["ratio"], "c": c["c"],
            "stick_outer": c["stick_outer"], "slide_inner": c["slide_inner"], "c_error": 0.5 * (c["stick_outer"] + c["slide_inner"]) / c["c"] - 1,
            "bracket": (c["slide_inner"] - c["stick_outer"]) / c["c"]}


def rule(rows, key, targets):
    """per target error: the coarsest level and at it the loosest tolerance whose |error| is within it, and stays
    within it at every finer level and tighter tolerance measured (no lucky coarse run), or None; the cheapest in
    principle: the measured seconds are too noisy to rank runs of the same level"""
    ordered = sorted(rows, key=lambda r: (r["level"], -r["eps"]))
    holds = lambda r, t: all(abs(q[key]) <= t for q in rows if q["level"] >= r["level"] and q["eps"] <= r["eps"])
    return [(t, next((r for r in ordered if holds(r, t)), None)) for t in targets]


def rule_lines(rows, key, name, targets, ranks, what="level %(level)d, rtol %(eps).0e"):
    """the rule as sentences: "for X % on NAME take level L, rtol t: s seconds on N rank(s) (y yardsticks)", and the
    same as dictionaries for claims.json"""
    lines, found = [], []
    for target, r in rule(rows, key, targets):
        if r:
            lines.append("- for %g %% on %s take %s: %.1f s on %d rank(s) (%.1f yardsticks; measured %+.2g %%)"
                         % (100 * target, name, what % r, r["whole_s"], ranks, r["yardsticks"], 100 * r[key]))
            found.append({"answer": name, "target": target, "reached": True, "level": None if "steps" in r else r["level"], "steps": r.get("steps"), "eps": r["eps"],
                          "seconds": r["whole_s"], "ranks": ranks, "yardsticks": r["yardsticks"], "error": r[key]})
        else:
            lines.append("- %g %% on %s: not reached in the runs measured" % (100 * target, name))
            found.append({"answer": name, "target": target, "reached": False})
    return "\n".join(lines), found


def plot_work_precision(path, rows, keys, title, yardstick, footer):
    """error against whole-run seconds, log-log, each point labelled by level and tolerance"""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(keys), figsize=(6.5 * len(keys), 5.5), squeeze=False)
    levels = sorted({r["level"] for r in rows})
    colors = dict(zip(levels, plt.cm.viridis(np.linspace(0, 0.85, len(levels)))))
    for ax, (key, label) in zip(axes[0], keys):
        for level in levels:
            pts = sorted((r for r in rows if r["level"] == level), key=lambda r: r["whole_s"])
            ax.loglog([r["whole_s"] for r in pts], [max(abs(r[key]), 1e-6) for r in pts], "o", color=colors[level], label="level %d" % level)
            for r in pts:
                ax.annotate("L%d %.0e" % (level, r["eps"]), (r["whole_s"], max(abs(r[key]), 1e-6)), fontsize=7, xytext=(3, 3), textcoords="offset points")
        ax.set_xlabel("whole run [s] (mesh to file; AMG yardstick of the run %.2f s)" % yardstick)
        ax.set_ylabel("|%s|" % label)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.text(0.01, 0.005, footer, fontsize=6, color="0.4")
    fig.savefig(path, dpi=110)
    plt.close(fig)


# the block on a spring (docs/derivation.md (11.1)-(11.2), tests/suite_loadpath.py): pressed by P = 10, sheared by
# Q = 7.5 > phi P = 5, released, sheared back, released (knots at t = 1..5); it ends at -(Q - phi P)/k = -2.5e-3
BLOCK = ["-geo", "meshes/block.geo", "-level", "2", "-E", "2e8", "-nu", "0.3", "-spring_top", "1000", "-contact", "bottom",
         "-friction_bottom", "0.5", "-traction_top", "0:0,0,0;1:0,0,-10;2:7.5,0,-10;3:0,0,-10;4:-7.5,0,-10;5:0,0,-10"]
BLOCK_END = -2.5e-3
LOADPATH_COLUMNS = ["steps", "ranks", "at_knots", "end_ux", "error", "iterations", "solve_s", "whole_s", "per_step_s"]


def loadpath_run(steps, work, ranks=1):
    """the block on a spring in equal steps on t in [0, 5]: the error of its end against the path's closed form"""
    import h5py
    h5 = os.path.join(work, "block_%d.h5" % steps)
    out, whole = timed(mpiexec(ranks) + [os.path.join(ROOT, "examples", "contact")] + BLOCK + ["-steps", str(steps), "-o", h5])
    m = SUMMARY.search(out)
    with h5py.File(h5, "r") as f:
        end = float(f["steps/groups/top/displacement"][-1, 0])
    return {"steps": steps, "ranks": ranks, "at_knots": int(steps % 5 == 0), "end_ux": end, "error": abs(end - BLOCK_END) / abs(BLOCK_END),
            "iterations": int(m.group(6)), "solve_s": float(m.group(5)), "whole_s": whole, "per_step_s": float(m.group(5)) / steps}


def plot_loadpath(path, rows, footer):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5.5))
    off = sorted((r for r in rows if not r["at_knots"]), key=lambda r: r["steps"])
    on = [r for r in rows if r["at_knots"]]
    ax.loglog([r["steps"] for r in off], [r["error"] for r in off], "o-", label="steps off the knots")
    ax.loglog([r["steps"] for r in on], [max(r["error"], 1e-6) for r in on], "s", label="steps on the knots (t = 1, ..., 5)")
    if off:
        n = np.array([r["steps"] for r in off], float)
        ax.loglog(n, off[0]["error"] * off[0]["steps"] / n, "k:", lw=0.8, label="first order (1/steps)")
    for r in rows:
        ax.annotate("%d steps, %.2f s" % (r["steps"], r["solve_s"]), (r["steps"], max(r["error"], 1e-6)), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("steps of the load path")
    ax.set_ylabel("|u_x(end) - (-(Q - phi P)/k)| / ((Q - phi P)/k)")
    ax.set_title("The block on a spring: the error of the path's end against the steps")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.text(0.01, 0.005, footer, fontsize=6, color="0.4")
    fig.savefig(path, dpi=110)
    plt.close(fig)


SLIDER_COLUMNS = ["level", "eps", "ranks", "contact", "iterations", "solve_s", "whole_s", "ratio_error", "cone_error", "sliding", "sticking"]


def slider_run(level, eps, work, ranks=1):
    """the slider of scenes/slider.opts (a block pushed along x beyond phi N on a block, phi = 0.5): the contact's
    tangential force against phi times its normal force, |T| / (phi N) - 1, as tests/suite_pairs.py measures it, and
    the sliding nodes' largest distance from their cones, max | |r_t| / (phi r_n) - 1 |"""
    import h5py
    h5 = os.path.join(work, "slider_L%d_%g.h5" % (level, eps))
    out, whole = timed(mpiexec(ranks) + [os.path.join(ROOT, "examples", "contact"), "-options_file", os.path.join(ROOT, "scenes", "slider.opts"), "-level", str(level),
                        "-snes_rtol", "%g" % eps, "-o", h5])
    m = SUMMARY.search(out)
    with h5py.File(h5, "r") as f:
        c = f["contact"]
        r, n, s, phi = c["reaction"][:], c["normal"][:], c["state"][:], c["friction"][:].max()
    rn = (r * n).sum(axis=1)
    rt = r - rn[:, None] * n
    sliding = np.isin(s, (1, 2))
    return {"cone_error": np.abs(np.linalg.norm(rt[sliding], axis=1) / (phi * rn[sliding]) - 1).max(), "level": level, "eps": eps, "ranks": ranks, "contact": int(m.group(2)), "iterations": int(m.group(6)), "solve_s": float(m.group(5)), "whole_s": whole,
            "ratio_error": np.linalg.norm(rt.sum(axis=0)) / (phi * rn.sum()) - 1, "sliding": int(np.isin(s, (1, 2)).sum()),
            "sticking": int(np.isin(s, (3, 4, 5)).sum())}
