#!/usr/bin/python3
"""What accuracy costs in time: the work-precision study of ssstar (make accuracy, make accuracy-quick).

  bench/accuracy.py [--quick] [--levels 4,6,8,10] [--finest 24] [--tols 1e-2,...,1e-12] [--repeat 3]
                    [--baseline-levels 4,6] [--whole-levels 4,6,8,10] [--krylov-rtols 1e-3] [--krylov-levels 8]
                    [--hertz-levels 1,2,3] [--hertz-tols 1e-1,...,1e-8] [--ranks 1]
                    [--big-levels 12,16] [--big-tols 1e-2,1e-4,1e-8] [--big-ranks 2] [--mindlin-levels 1,2] [--mindlin-tols ...]
                    [--slider-levels 1,2,3] [--slider-tols ...] [--loadpath-steps 5,...] [--out docs/accuracy]
                    [--report-only [--extend]]

Both paths of the solver on the seed's prism, per level L and stopping tolerance t (-snes_rtol):
- the dense route (-snes_ssstar_reduction direct): examples/prism writes the reduced problem (P, f, coordinates) once
  per level; bench/accuracy_worker.py solves it for every tolerance (median of --repeat) and once at 1e-14 (the
  reference), with ssstar and with the first-order baseline (-snes_ssstar_method fixedpoint, on --baseline-levels);
- the whole body (-snes_ssstar_reduction none -nested_levels 0, P never formed, Krylov + multigrid): one run of
  examples/prism per tolerance, its contact solution against the same reference; --krylov-rtols adds runs with
  other loosest Krylov tolerances of the Newton steps (-snes_ssstar_ksp_rtol_max) on --krylov-levels.
On --big-ranks ranks, beside an AMG yardstick on as many: both paths at --big-levels and --big-tols (the dense route's
worker under mpiexec, one run each), the finest level --finest on the whole body at rtol 1e-10 (the reference of the
discretization error: each level's reference against it), Cattaneo-Mindlin's stick radius (scenes/mindlin.opts at
--mindlin-levels, --mindlin-tols), the slider's T = phi N and the load path.
The mesh axis: the hertz scene at --hertz-levels and --hertz-tols, whole runs, the contact radius, peak pressure and
the subsurface von Mises maximum against Hertz's formulas (bench/accuracy_mesh.py); the rules "for X % take level L,
rtol t: s seconds on N ranks" from the data, into the doc and claims.json. The AMG yardstick (bench/yardstick -yardstick amg, the prism at
--yardstick-level) is measured at the start, the middle and the end of the run; the median is beside every time.
The load path: the block on a spring at --loadpath-steps (bench/accuracy_mesh.py).
Writes OUT/sweep.csv, discretization.csv, hertz.csv, mindlin.csv, slider.csv, loadpath.csv, claims.json, *.png and the doc, each with the machine, the date
and the command. --quick: levels 4 and 6 (the whole body at 6; finest 8), rtol 1e-3 and 1e-6, hertz level 1, 6 steps, one
yardstick (at level 6): under a minute on a quiet machine, into
bench/output/accuracy_quick (tests/suite_accuracy.py re-measures the doc's claims with it)."""
import argparse
import csv
import datetime
import json
import os
import platform
import re
import statistics
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import accuracy_mesh  # noqa: E402
from table2 import ROW as PRISM_ROW, SETUP, yardstick  # noqa: E402 (the summary row, the set-up line, the AMG yardstick)

PRISM = os.path.join(ROOT, "examples", "prism")
ROW = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+(\d+)\s+([\d.]+)\s+(\d+)", re.M)
STATE_TOL = 1e-8  # a node carries force if r_n > STATE_TOL max r_n; it slips if |u_t| > STATE_TOL max|u| (reference scales)
COLUMNS = ["level", "path", "method", "ksp_rtol_max", "eps", "iterations", "time_s", "setup_s", "err_u", "err_r", "normal_force_err",
           "contact_nodes_diff", "state_diff", "converged", "znorm_final", "coulomb_residual"]
FULL = {"levels": "4,6,8,10", "finest": 24, "tols": "1e-2,1e-3,1e-4,1e-6,1e-8,1e-10,1e-12", "repeat": 3, "baseline_levels": "4,6",
        "whole_levels": "4,6,8,10", "krylov_rtols": "1e-3", "krylov_levels": "8", "hertz_levels": "1,2,3", "hertz_tols": "1e-1,1e-2,1e-3,1e-5,1e-8",
        "loadpath_steps": "5,6,11,25,26,51,101,201", "slider_levels": "1,2,3", "slider_tols": "1e-2,1e-4,1e-8", "big_levels": "12,16", "big_tols": "1e-2,1e-4,1e-8",
        "mindlin_levels": "1,2", "mindlin_tols": "1e-2,1e-4,1e-8", "big_ranks": 2, "yardstick_level": 8, "out": os.path.join(ROOT, "docs", "accuracy"),
        "doc": os.path.join(ROOT, "docs", "accuracy.md")}
QUICK = {"levels": "4,6", "finest": 8, "tols": "1e-3,1e-6", "repeat": 1, "baseline_levels": "4", "whole_levels": "6",
         "krylov_rtols": "", "krylov_levels": "", "hertz_levels": "1", "hertz_tols": "1e-8", "loadpath_steps": "6", "slider_levels": "", "slider_tols": "", "big_levels": "",
         "big_tols": "", "mindlin_levels": "", "mindlin_tols": "", "big_ranks": 1, "yardstick_level": 6,
         "out": os.path.join(ROOT, "bench", "output", "accuracy_quick"), "doc": os.path.join(ROOT, "bench", "output", "accuracy_quick", "accuracy.md")}
FINEST_RTOL = 1e-10  # the finest level's whole-body run: the reference of the discretization error
CLAIM_LEVEL, CLAIM_EPS, CLAIM_HERTZ = 6, 1e-6, 1  # the claims a test re-measures: err_u at level 6, rtol 1e-6; Hertz at level 1


def parse():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--quick", action="store_true", help="the quick study (about a minute; bench/output/accuracy_quick)")
    for key, value in FULL.items():
        p.add_argument("--" + key.replace("_", "-"), type=type(value), default=None, help="full: %s; quick: %s" % (value, QUICK[key]))
    p.add_argument("--baseline-repeat", type=int, default=1, help="runs per tolerance of the baseline")
    p.add_argument("--ranks", type=int, default=1, help="MPI ranks of the prism at --levels (both paths) and of the hertz runs")
    p.add_argument("--report-only", action="store_true", help="the doc, the files and the pictures again from the last run's results.json")
    p.add_argument("--extend", action="store_true", help="with --report-only: measure the parts the last run's results.json lacks (the runs on "
                   "--big-ranks: big levels, the finest, Cattaneo-Mindlin, the slider, the load path; hertz levels; the von Mises maximum of its files)")
    args = p.parse_args()
    for key, value in (QUICK if args.quick else FULL).items():
        if getattr(args, key) is None:
            setattr(args, key, value)
    args.command = " ".join(["bench/accuracy.py"] + sys.argv[1:])
    return args


def numbers(spec, kind=int):
    return [kind(v) for v in spec.split(",") if v]


def run(cmd):
    return accuracy_mesh.timed(cmd)[0]


def save_level(level, work, ranks=1):
    """examples/prism at the level, saving the reduced problem; returns the file and the fixed costs"""
    binary = os.path.join(work, "prism_L%d.bin" % level)
    m = ROW.search(run(accuracy_mesh.mpiexec(ranks) + [PRISM, "-level", str(level), "-save_reduced", binary, "-snes_rtol", "1e-14"]))
    return binary, {"nodes": int(m.group(3)), "contact": int(m.group(6)), "assembly": float(m.group(4)), "schur": float(m.group(5))}


def solve_level(binary, methods, tols, repeat, baseline_repeat=1, ranks=1):
    cmd = accuracy_mesh.mpiexec(ranks) + [sys.executable, os.path.join(ROOT, "bench", "accuracy_worker.py"), binary, "--methods", methods, "--tols", tols, "--repeat", str(repeat),
           "--baseline-repeat", str(baseline_repeat)]
    run(cmd)
    with open(binary + ".json") as f:
        return json.load(f)


def whole_body(level, eps, ranks, work, coordinates=None, extra=()):
    """examples/prism on the whole body from u = 0: the contact solution (in the order of coordinates) and the costs"""
    h5 = os.path.join(work, "whole_L%d_%g.h5" % (level, eps))
    out = run(accuracy_mesh.mpiexec(ranks) + [PRISM, "-level", str(level), "-snes_ssstar_reduction", "none", "-nested_levels", "0",
                                              "-snes_rtol", "%g" % eps, "-summary_header", "0", "-o", h5] + list(extra))
    m, setup = PRISM_ROW.search(out), SETUP.search(out)
    x, u, r = accuracy_mesh.prism_contact(h5, coordinates)
    setup_s = float(setup.group(1)) if setup else 0.0
    return {"u": u.ravel().tolist(), "r": r.ravel().tolist(), "coordinates": x.ravel().tolist(), "iterations": int(m.group(8)),
            "converged": int(m.group(11).startswith("CONVERGED")), "time": float(m.group(7)) - setup_s, "setup": setup_s,
            "assembly": float(m.group(4)), "contact": int(m.group(6))}


FULL_KRYLOV = "0.1"  # the default -snes_ssstar_ksp_rtol_max


def arrays(run_):
    return np.array(run_["u"]).reshape(-1, 3), np.array(run_["r"]).reshape(-1, 3)


def states(u, r, uscale, rscale):
    """0 separated, 1 sliding, 2 sticking, from the solution alone"""
    contact = r[:, 2] > STATE_TOL * rscale
    slips = np.hypot(u[:, 0], u[:, 1]) > STATE_TOL * uscale
    return np.where(~contact, 0, np.where(slips, 1, 2))


def coulomb_residual(u, r, phi=0.3):
    """the worst violation of the law (as tests/check_solution.py), relative to max|u| and max|r|"""
    umax, rmax = np.abs(u).max(), np.abs(r).max()
    ut, rt = np.hypot(u[:, 0], u[:, 1]), np.hypot(r[:, 0], r[:, 1])
    v = [np.max(-u[:, 2]) / umax, np.max(-r[:, 2]) / rmax, np.max(np.abs(u[:, 2] * r[:, 2])) / (umax * rmax), np.max(rt - phi * r[:, 2]) / rmax]
    sliding = ut > 1e-8 * umax
    if sliding.any():
        unit = u[sliding, :2] / ut[sliding, None]
        v.append(np.max(np.abs(r[sliding, :2] + phi * r[sliding, 2, None] * unit)) / rmax)
    return max(v)


def metrics(run_, ref):
    u, r = arrays(run_)
    uref, rref = arrays(ref)
    uscale, rscale = np.abs(uref).max(), np.abs(rref[:, 2]).max()
    s, sref = states(u, r, uscale, rscale), states(uref, rref, uscale, rscale)
    return {"err_u": np.abs(u - uref).max() / uscale, "err_r": np.abs(r - rref).max() / np.abs(rref).max(),
            "normal_force_err": abs(r[:, 2].sum() - rref[:, 2].sum()) / abs(rref[:, 2].sum()),
            "contact_nodes_diff": int(abs((s > 0).sum() - (sref > 0).sum())), "state_diff": int((s != sref).sum()),
            "coulomb_residual": coulomb_residual(u, r)}


def grid_interpolate(xyz_fine, values, points):
    """bilinear interpolation of nodal values on the regular (x, y) grid of the finest contact face"""
    xs, ys = np.unique(xyz_fine[:, 0].round(9)), np.unique(xyz_fine[:, 1].round(9))
    grid = np.zeros((len(xs), len(ys), values.shape[1]))  # grid points that are not contact nodes are held: u = 0
    grid[np.searchsorted(xs, xyz_fine[:, 0].round(9)), np.searchsorted(ys, xyz_fine[:, 1].round(9))] = values
    out = np.empty((len(points), values.shape[1]))
    for k, (x, y) in enumerate(points[:, :2]):
        i = min(max(np.searchsorted(xs, x) - 1, 0), len(xs) - 2)
        j = min(max(np.searchsorted(ys, y) - 1, 0), len(ys) - 2)
        a, b = (x - xs[i]) / (xs[i + 1] - xs[i]), (y - ys[j]) / (ys[j + 1] - ys[j])
        corners = [grid[i, j], grid[i + 1, j], grid[i, j + 1], grid[i + 1, j + 1]]
        weights = [(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b]
        out[k] = sum(w * c for w, c in zip(weights, corners) if w > 0)
    return out


def tributary_area(xyz):
    """the area each contact node stands for on its regular grid (halved on the face's edges)"""
    xs, ys = np.unique(xyz[:, 0].round(9)), np.unique(xyz[:, 1].round(9))
    hx, hy = xs[1] - xs[0], ys[1] - ys[0]
    w = np.full(len(xyz), hx * hy)
    for coord, values in ((0, xs), (1, ys)):
        edge = np.isclose(xyz[:, coord], values[0]) | np.isclose(xyz[:, coord], values[-1])
        w[edge] *= 0.5
    return w


def discretization(level_data, finest):
    """each level's reference against the finest level's: displacement at the level's nodes, integrated quantities"""
    xyzf = np.array(finest["coordinates"]).reshape(-1, 3)
    uf, rf = arrays(finest["reference"])
    sf = states(uf, rf, np.abs(uf).max(), np.abs(rf[:, 2]).max())
    af = tributary_area(xyzf)
    rows = []
    for level, data in sorted(level_data.items()):
        xyz = np.array(data["coordinates"]).reshape(-1, 3)
        u, r = arrays(data["reference"])
        s = states(u, r, np.abs(u).max(), np.abs(r[:, 2]).max())
        a = tributary_area(xyz)
        rows.append({"level": level, "err_u": np.abs(u - grid_interpolate(xyzf, uf, xyz)).max() / np.abs(uf).max(),
                     "normal_force_err": abs(r[:, 2].sum() - rf[:, 2].sum()) / abs(rf[:, 2].sum()),
                     "contact_area_err": abs(a[s > 0].sum() - af[sf > 0].sum()) / af[sf > 0].sum(),
                     "stick_area_err": abs(a[s == 2].sum() - af[sf == 2].sum()) / af[sf == 2].sum()})
    return rows


def observed_order(history):
    """q from the last three ||z_k|| clearly above round-off: log(z_k+1/z_k) / log(z_k/z_k-1)"""
    z = [h for h in history if h > 1e-12 * max(history)]  # below: the round-off floor of ||z||
    if len(z) < 3:
        return float("nan")
    a, b, c = z[-3:]
    return np.log(c / b) / np.log(b / a)


def stamp(fig, args):
    fig.text(0.01, 0.005, "%s; %s; %s" % (args.command, args.date, args.machine), fontsize=6, color="0.4")


def plots(out, rows, disc, level_data, args):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    levels = sorted(level_data)
    colors = dict(zip(levels, plt.cm.viridis(np.linspace(0, 0.9, len(levels)))))
    fig, ax = plt.subplots(figsize=(9, 6.5))
    styles = {("direct", "ssstar"): "o-", ("none", "ssstar"): "^--", ("direct", "fixedpoint"): "s:"}
    for (level, path, method, krylov), group in _groups(rows).items():
        if krylov not in ("", FULL_KRYLOV):
            continue
        ax.loglog([g["yardsticks"] for g in group], [max(g["err_u"], 1e-17) for g in group], styles[(path, method)],
                  color=colors[level], label="L%d %s %s" % (level, {"direct": "dense", "none": "whole body"}[path], method))
    for d in disc:
        ax.axhline(d["err_u"], color=colors[d["level"]], lw=0.8, ls=":")
    ax.set_xlabel("solve time in AMG yardsticks of as many ranks (1 = %.3f s on %d, %.3f s on %d; the iterations only, fixed costs apart)"
                  % (args.yardstick, args.ranks, args.big_yardstick, args.big_ranks))
    ax.set_ylabel("max |u - u_ref| / max |u_ref| (contact displacement)")
    ax.set_title("Solver error against time, both paths; dotted: discretization error of the level")
    ax.legend(fontsize=6, ncol=3)
    stamp(fig, args)
    fig.savefig(os.path.join(out, "error_vs_time.png"), dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(8, 6))
    tols = sorted({g["eps"] for g in rows}, reverse=True)
    for eps in tols[::2]:
        for path, mark in (("direct", "o-"), ("none", "^--")):
            pts = [(g["level"], g["err_u"]) for g in rows if g["method"] == "ssstar" and g["path"] == path and g["eps"] == eps and g["ksp_rtol_max"] in ("", FULL_KRYLOV)]
            if pts:
                ax.semilogy([p[0] for p in pts], [max(p[1], 1e-17) for p in pts], mark, label="%s, rtol %.0e" % ({"direct": "dense", "none": "whole"}[path], eps))
    ax.semilogy([d["level"] for d in disc], [d["err_u"] for d in disc], "k^-", lw=2, label="discretization (vs finest level)")
    ax.set_xlabel("level")
    ax.set_ylabel("max |u - u_ref| / max |u_ref|")
    ax.set_title("Solver error and discretization error against the level")
    ax.legend(fontsize=7, ncol=2)
    stamp(fig, args)
    fig.savefig(os.path.join(out, "error_vs_level.png"), dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(8, 6))
    for level in levels:
        h = level_data[level]["reference"]["history"]
        ax.semilogy(range(len(h)), h, "o-", color=colors[level], label="L%d (order %.2f)" % (level, observed_order(h)))
    ax.set_xlabel("iteration k")
    ax.set_ylabel("||z_k||")
    ax.set_title("ssstar: ||z_k|| per iteration (dense reference solves); observed order of the tail")
    ax.legend()
    stamp(fig, args)
    fig.savefig(os.path.join(out, "znorm_history.png"), dpi=120)
    plt.close(fig)


def _groups(rows):
    groups = {}
    for g in rows:
        groups.setdefault((g["level"], g["path"], g["method"], g["ksp_rtol_max"]), []).append(g)
    return groups


def machine():
    model = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), platform.processor())
    mem = next((int(l.split()[1]) // 2**20 for l in open("/proc/meminfo") if l.startswith("MemTotal")), 0)
    return "%s, %d cores, %d GB, %s" % (model, os.cpu_count(), mem, platform.platform())


def table(rows, columns, formats):
    out = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for r in rows:
        out.append("| " + " | ".join(f % r[c] if isinstance(f, str) else f(r[c]) for c, f in zip(columns, formats)) + " |")
    return "\n".join(out)


def stick(args, ranks):
    return sum(yardstick(args.yardstick_level, ranks, "amg"))


def dense_row(level, r, ref, ranks):
    return dict(level=level, ranks=ranks, path="direct", method=r["method"], ksp_rtol_max="", eps=r["eps"], iterations=r["iterations"], time_s=r["time"],
                setup_s=0.0, converged=int(r["reason"] > 0), znorm_final=r["history"][-1], **metrics(r, ref))


def whole_row(level, eps, krylov, ranks, work, costs, data):
    w = whole_body(level, eps, ranks, work, data["coordinates"], ["-snes_ssstar_ksp_rtol_max", krylov])
    costs["whole_assembly"] = w["assembly"]
    costs.setdefault("setup", []).append(w["setup"])
    return dict(level=level, ranks=ranks, path="none", method="ssstar", ksp_rtol_max=krylov, eps=eps, iterations=w["iterations"], time_s=w["time"],
                setup_s=w["setup"], converged=w["converged"], znorm_final=float("nan"), **metrics(w, data["reference"]))


def measure(args, levels, work):
    """every run of the study; the results as one dictionary (saved as WORK/results.json for --report-only)"""
    sticks = [stick(args, args.ranks)]
    costs, level_data = {}, {}
    for level in levels:
        binary, costs[level] = save_level(level, work)
        methods = "ssstar,fixedpoint" if level in numbers(args.baseline_levels) else "ssstar"
        level_data[level] = solve_level(binary, methods, args.tols, args.repeat, args.baseline_repeat)
        print("dense route, level %d done" % level, flush=True)
    sticks += [] if args.quick else [stick(args, args.ranks)]  # the quick study: once
    rows = [dense_row(level, r, data["reference"], args.ranks) for level, data in sorted(level_data.items()) for r in data["runs"]]
    variants = [(level, FULL_KRYLOV) for level in numbers(args.whole_levels)] + \
               [(level, k) for level in numbers(args.krylov_levels) for k in args.krylov_rtols.split(",") if k]
    for level, krylov in variants:
        rows += [whole_row(level, eps, krylov, args.ranks, work, costs[level], level_data[level]) for eps in numbers(args.tols, float)]
        print("whole body, level %d, ksp_rtol_max %s done" % (level, krylov), flush=True)
    hertz = accuracy_mesh.hertz_sweep(numbers(args.hertz_levels), numbers(args.hertz_tols, float), args.ranks, work, lambda s: print(s, flush=True))
    sticks += [] if args.quick else [stick(args, args.ranks)]  # the quick study: once
    res = {"costs": costs, "level_data": level_data, "rows": rows, "hertz": hertz, "sticks": sticks, "date": args.date, "machine": args.machine,
           "command": args.command}
    measure_big(args, work, res)
    return res


def measure_big(args, work, res):
    """the runs on --big-ranks, beside their own yardstick on as many ranks (start, middle, end; the first part's when
    the ranks are the same): the prism at --big-levels on both paths, the finest level (the reference of the
    discretization error), Cattaneo-Mindlin, the slider and the load path"""
    same = args.big_ranks == args.ranks and "sticks" in res
    sticks = [] if same else [stick(args, args.big_ranks)]
    for level in numbers(args.big_levels):
        binary, res["costs"][level] = save_level(level, work, args.big_ranks)
        data = res["level_data"][level] = solve_level(binary, "ssstar", args.big_tols, 1, ranks=args.big_ranks)
        res["rows"] += [dense_row(level, r, data["reference"], args.big_ranks) for r in data["runs"]]
        res["rows"] += [whole_row(level, eps, FULL_KRYLOV, args.big_ranks, work, res["costs"][level], data) for eps in numbers(args.big_tols, float)]
        print("level %d on %d ranks, both paths done" % (level, args.big_ranks), flush=True)
    finest = whole_body(args.finest, FINEST_RTOL, args.big_ranks, work)
    res["finest"], res["finest_level"] = {"coordinates": finest["coordinates"], "reference": finest, "time": finest["time"]}, args.finest
    print("finest level %d done" % args.finest, flush=True)
    sticks += [] if same else [stick(args, args.big_ranks)]
    res["mindlin"] = [accuracy_mesh.mindlin_run(level, eps, args.big_ranks, work) for level in numbers(args.mindlin_levels)
                      for eps in numbers(args.mindlin_tols, float)]
    res["slider"] = [accuracy_mesh.slider_run(level, eps, work, args.big_ranks) for level in numbers(args.slider_levels)
                     for eps in numbers(args.slider_tols, float)]
    res["loadpath"] = [accuracy_mesh.loadpath_run(n, work, args.big_ranks) for n in numbers(args.loadpath_steps)]
    print("Cattaneo-Mindlin, the slider and the load paths done", flush=True)
    res["big_sticks"] = res["sticks"] if same else sticks + [stick(args, args.big_ranks)]
    res["big_ranks"] = args.big_ranks


def main():
    args = parse()
    os.environ.update(accuracy_mesh.environment())
    levels = numbers(args.levels)
    work = os.path.join(ROOT, "bench", "output", "accuracy_quick_work" if args.quick else "accuracy")
    os.makedirs(work, exist_ok=True)
    os.makedirs(args.out, exist_ok=True)
    saved = os.path.join(work, "results.json")
    if args.report_only:
        with open(saved) as f:
            res = json.load(f)
        for key in ("costs", "level_data"):
            res[key] = {int(k): v for k, v in res[key].items()}
        levels = sorted(res["level_data"])
        if args.extend:  # parts added to the study after the run: measured now, dated apart
            now = datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC")
            journal = accuracy_mesh.JOURNAL["file"] = os.path.join(work, "extend_runs.json")
            if os.path.exists(journal):  # an --extend that failed: its finished runs are kept
                with open(journal) as f:
                    accuracy_mesh.JOURNAL["runs"] = json.load(f)
            if "big_sticks" not in res:
                measure_big(args, work, res)
                res["big_date"], res["big_command"], res["slider_date"] = now, args.command, now
            have = {(r["level"], r["eps"]) for r in res["hertz"]}
            for level in numbers(args.hertz_levels):
                missing = [eps for eps in numbers(args.hertz_tols, float) if (level, eps) not in have]
                if missing:
                    res["hertz"] += accuracy_mesh.hertz_sweep([level], missing, args.ranks, work, lambda s: print(s, flush=True))
                    res.setdefault("hertz_dates", {})[str(level)] = now
            for r in res["hertz"]:  # the von Mises maximum from the files of runs made before it was measured
                if "vm_error" not in r:
                    r.update(accuracy_mesh.von_mises(os.path.join(work, "hertz_L%d_%g.h5" % (r["level"], r["eps"]))))
            with open(saved, "w") as f:
                json.dump(res, f)
    else:
        args.date, args.machine = datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC"), machine()
        res = measure(args, levels, work)
        with open(saved, "w") as f:
            json.dump(res, f)
    report(args, res, levels)


def report(args, res, levels):
    """the CSVs, claims.json, the pictures and the doc from the results of a run"""
    args.date, args.machine, args.command = res["date"], res["machine"], res["command"]
    costs, level_data, rows, finest, hertz, loadpath, sticks = (res[k] for k in ("costs", "level_data", "rows", "finest", "hertz", "loadpath", "sticks"))
    args.finest, args.big_ranks = res.get("finest_level", args.finest), res.get("big_ranks", args.ranks)
    args.finest_time = finest.get("time", finest["reference"]["time"])
    args.yardstick, args.sticks = statistics.median(sticks), sticks
    args.big_sticks = res.get("big_sticks", sticks)
    args.big_yardstick = statistics.median(args.big_sticks)
    args.big_when = "" if "big_date" not in res else " by `%s` on %s" % (res["big_command"], res["big_date"])
    per_ranks = {args.ranks: args.yardstick, args.big_ranks: args.big_yardstick}
    for r in rows:
        r.setdefault("ranks", args.ranks)
        r["yardsticks"] = r["time_s"] / per_ranks[r["ranks"]]
    for r in hertz + res.get("mindlin", []) + res.get("slider", []) + loadpath:
        r.setdefault("ranks", args.ranks)
        r["yardsticks"] = r["whole_s"] / per_ranks[r["ranks"]]
    provenance = "# %s; %s; %s; AMG yardstick %.3f s (prism level %d, %d rank(s))" % (args.command, args.date, args.machine, args.yardstick,
                                                                                        args.yardstick_level, args.ranks)
    if args.big_ranks != args.ranks or "big_date" in res:
        provenance += "; the runs on %d ranks%s: AMG yardstick %.3f s (prism level %d, %d ranks)" % (
            args.big_ranks, args.big_when.replace("`", ""), args.big_yardstick, args.yardstick_level, args.big_ranks)
    write_csv(os.path.join(args.out, "sweep.csv"), provenance, COLUMNS + ["ranks", "yardsticks"], rows)
    disc = discretization(level_data, finest)
    write_csv(os.path.join(args.out, "discretization.csv"), provenance, list(disc[0]), disc)
    write_csv(os.path.join(args.out, "hertz.csv"), provenance, accuracy_mesh.HERTZ_COLUMNS + ["yardsticks"], hertz)
    plots(args.out, rows, disc, level_data, args)
    footer = "%s; %s; %s" % (args.command, args.date, args.machine)
    accuracy_mesh.plot_work_precision(os.path.join(args.out, "hertz_work_precision.png"), hertz,
                                      [("p0_error", "peak pressure error p0/p0_Hertz - 1"), ("a_error", "contact radius error a/a_Hertz - 1")],
                                      "Hertz (scenes/hertz.opts): error against the whole run's time, %d rank(s)" % args.ranks, args.yardstick, footer)
    accuracy_mesh.plot_work_precision(os.path.join(args.out, "von_mises_work_precision.png"), hertz,
                                      [("vm_error", "von Mises maximum error vm/(0.620 p0) - 1"), ("vm_depth_error", "its depth error z/(0.481 a) - 1")],
                                      "Hertz's subsurface von Mises maximum: error against the whole run's time, %d rank(s)" % args.ranks, args.yardstick, footer)
    mindlin = res.get("mindlin", [])
    if mindlin:
        write_csv(os.path.join(args.out, "mindlin.csv"), provenance, accuracy_mesh.MINDLIN_COLUMNS + ["yardsticks"], mindlin)
        accuracy_mesh.plot_work_precision(os.path.join(args.out, "mindlin_work_precision.png"), mindlin, [("c_error", "stick radius error c/c_CM - 1")],
                                          "Cattaneo-Mindlin (scenes/mindlin.opts, Q = 0.5 phi P): error against the whole run's time, %d ranks" % args.big_ranks,
                                          args.big_yardstick, footer)
    write_csv(os.path.join(args.out, "loadpath.csv"), provenance, accuracy_mesh.LOADPATH_COLUMNS + ["yardsticks"], loadpath)
    slider = res.get("slider", [])
    if slider:
        write_csv(os.path.join(args.out, "slider.csv"), provenance + (" (the slider measured %s)" % res["slider_date"] if "slider_date" in res else ""),
                  accuracy_mesh.SLIDER_COLUMNS + ["yardsticks"], slider)
    accuracy_mesh.plot_loadpath(os.path.join(args.out, "loadpath_steps.png"), loadpath, footer)
    claims, rules = measure_claims(rows, hertz), all_rules(args, hertz, mindlin, slider, loadpath)
    with open(os.path.join(args.out, "claims.json"), "w") as f:
        json.dump(dict(claims, rules=[x for _, found in rules.values() for x in found], command=args.command, date=args.date, machine=args.machine),
                  f, indent=1)
    args.hertz_dates = res.get("hertz_dates", {})
    write_doc(args, levels, costs, level_data, rows, disc, hertz, loadpath, claims, slider, res.get("slider_date", args.date), mindlin,
              {k: text for k, (text, _) in rules.items()})


def all_rules(args, hertz, mindlin, slider, loadpath):
    """the rules of the doc ("for X % on A take level L, rtol t: s seconds on N ranks (y yardsticks)"), as text and as data"""
    rule = accuracy_mesh.rule_lines
    off = [dict(r, level=r["steps"], eps=1.0) for r in loadpath if not r["at_knots"]]
    return {"hertz_p0": rule(hertz, "p0_error", "the peak pressure", (0.05, 0.02, 0.01, 0.005), args.ranks),
            "hertz_a": rule(hertz, "a_error", "the contact radius", (0.05, 0.02, 0.01, 0.005), args.ranks),
            "von_mises": rule(hertz, "vm_error", "the von Mises maximum", (0.1, 0.05, 0.02, 0.01), args.ranks),
            "mindlin": rule(mindlin, "c_error", "the stick radius", (0.2, 0.1, 0.05), args.big_ranks),
            "slider": rule(slider, "ratio_error", "T = phi N", (1e-2, 1e-3, 1e-4), args.big_ranks),
            "loadpath": rule(off, "error", "the end of the path (steps off its knots)", (0.2, 0.1, 0.05, 0.02, 0.01), args.big_ranks,
                             "%(steps)d equal steps (rtol 1e-10, the default)")}


def write_csv(path, provenance, columns, rows):
    with open(path, "w", newline="") as f:
        f.write(provenance + "\n")
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)


def measure_claims(rows, hertz):
    """the two numbers of the doc a test re-measures with the quick study"""
    pick = lambda path: next(r["err_u"] for r in rows if r["level"] == CLAIM_LEVEL and r["path"] == path and r["method"] == "ssstar"
                             and r["eps"] == CLAIM_EPS and r["ksp_rtol_max"] in ("", FULL_KRYLOV))
    tight = min((r for r in hertz if r["level"] == CLAIM_HERTZ), key=lambda r: r["eps"])
    return {"err_u_dense": pick("direct"), "err_u_whole": pick("none"), "level": CLAIM_LEVEL, "eps": CLAIM_EPS,
            "hertz_level": CLAIM_HERTZ, "hertz_eps": tight["eps"], "hertz_p0_error": tight["p0_error"], "hertz_a_error": tight["a_error"]}


def write_doc(args, levels, costs, level_data, rows, disc, hertz, loadpath, claims, slider, slider_date, mindlin, rules):
    refs = [{"level": l, "iterations": level_data[l]["reference"]["iterations"], "znorm": level_data[l]["reference"]["history"][-1],
             "law": coulomb_residual(*arrays(level_data[l]["reference"])), "order": observed_order(level_data[l]["reference"]["history"]),
             "second": second_method(level_data[l]), "assembly": costs[l]["assembly"], "schur": costs[l]["schur"], "contact": costs[l]["contact"],
             "setup": statistics.median(costs[l]["setup"]) if costs[l].get("setup") else float("nan")} for l in levels]
    dense = [r for r in rows if r["method"] == "ssstar" and r["path"] == "direct"]
    whole = [r for r in rows if r["path"] == "none" and r["ksp_rtol_max"] == FULL_KRYLOV]
    krylov = [r for r in rows if r["path"] == "none" and r["ksp_rtol_max"] != FULL_KRYLOV]
    base = [r for r in rows if r["method"] != "ssstar"]
    nan = lambda f: (lambda v: f % v if v == v else "—")
    sweep_columns = ["level", "ranks", "eps", "iterations", "time_s", "yardsticks", "err_u", "err_r", "normal_force_err", "state_diff"]
    sweep_formats = ["%d", "%d", "%.0e", "%d", "%.4f", "%.3f", "%.1e", "%.1e", "%.1e", "%d"]
    floors = {key: accuracy_mesh.tolerance_floor(hertz, key) for key in ("p0_error", "a_error")}
    text = TEMPLATE.format(
        date=args.date, machine=args.machine, command=args.command, tols=args.tols, repeat=args.repeat, ranks=args.ranks, finest=args.finest,
        baseline_levels=args.baseline_levels, state_tol=STATE_TOL, yardstick=args.yardstick, yardstick_level=args.yardstick_level,
        sticks=", ".join("%.3f" % s for s in args.sticks), default_krylov=FULL_KRYLOV, big_tols=args.big_tols, finest_rtol=FINEST_RTOL,
        finest_time=args.finest_time,
        refs=table(refs, ["level", "contact", "assembly", "schur", "setup", "iterations", "znorm", "law", "second", "order"],
                   ["%d", "%d", "%.2f", "%.2f", nan("%.2f"), "%d", "%.1e", "%.1e", nan("%.1e"), "%.2f"]),
        dense=table(dense, sweep_columns, sweep_formats), whole=table(whole, sweep_columns, sweep_formats),
        krylov=("Whole body with `-snes_ssstar_ksp_rtol_max` other than %s (levels %s):\n\n%s" % (FULL_KRYLOV, args.krylov_levels,
                table(krylov, ["level", "ksp_rtol_max"] + sweep_columns[2:], ["%d", "%s"] + sweep_formats[2:]))) if krylov else "",
        base=table(base, ["level", "eps", "iterations", "time_s", "converged", "err_u", "err_r", "state_diff"],
                   ["%d", "%.0e", "%d", "%.4f", "%d", "%.1e", "%.1e", "%d"]) if base else "(not run)",
        disc=table(disc, ["level", "err_u", "normal_force_err", "contact_area_err", "stick_area_err"], ["%d", "%.1e", "%.1e", "%.1e", "%.1e"]),
        advice=advice(dense, disc, "the dense route") + "\n" + advice(whole, disc, "the whole body") + baseline_advice(dense, base),
        hertz=table(hertz, ["level", "eps", "route", "contact", "iterations", "assembly_s", "schur_s", "solve_s", "whole_s", "yardsticks",
                            "force", "a_error", "p0_error", "bracket_error", "vm_error", "vm_depth_error"],
                    ["%d", "%.0e", "%s", "%d", "%d", "%.2f", "%.2f", "%.2f", "%.1f", "%.0f", "%.0f", "%+.4f", "%+.4f", "%+.4f", "%+.4f", "%+.3f"]),
        hertz_rule=rules["hertz_p0"] + "\n" + rules["hertz_a"], floors=floor_text(floors), vm_rule=rules["von_mises"],
        vm=table(hertz, ["level", "eps", "whole_s", "yardsticks", "vm_max", "vm_error", "vm_depth", "vm_depth_error"],
                 ["%d", "%.0e", "%.1f", "%.0f", "%.4f", "%+.4f", "%.3f", "%+.3f"]),
        mindlin=table(mindlin, ["level", "eps", "route", "contact", "iterations", "solve_s", "whole_s", "yardsticks", "ratio", "c", "stick_outer",
                                "slide_inner", "c_error", "bracket"],
                      ["%d", "%.0e", "%s", "%d", "%d", "%.2f", "%.1f", "%.1f", "%.3f", "%.3f", "%.3f", "%.3f", "%+.3f", "%.3f"]) if mindlin else "(not run)",
        mindlin_rule=rules["mindlin"], slider_rule=rules["slider"], loadpath_rule=rules["loadpath"], big_ranks=args.big_ranks,
        big_yardstick=args.big_yardstick, big_sticks=", ".join("%.3f" % s for s in args.big_sticks), big_when=args.big_when,
        big_levels=", ".join(str(l) for l in sorted({r["level"] for r in rows if r["ranks"] == args.big_ranks and args.big_ranks != args.ranks})) or "none",
        hertz_dates="".join(" Level %s was measured on %s (`--report-only --extend`), after the rest of the run." % item for item in sorted(args.hertz_dates.items())),
        loadpath_order=loadpath_order(loadpath, args.big_yardstick), slider_date=slider_date,
        slider=table(slider, accuracy_mesh.SLIDER_COLUMNS + ["yardsticks"], ["%d", "%.0e", "%d", "%d", "%d", "%.2f", "%.1f", "%+.1e", "%.1e", "%d", "%d", "%.1f"])
        if slider else "(not run)",
        slider_text=slider_text(slider),
        loadpath=table(loadpath, accuracy_mesh.LOADPATH_COLUMNS + ["yardsticks"], ["%d", "%d", "%d", "%.6f", "%.1e", "%d", "%.3f", "%.2f", "%.4f", "%.1f"]),
        claim_dense=claims["err_u_dense"], claim_whole=claims["err_u_whole"], claim_level=CLAIM_LEVEL, claim_eps=CLAIM_EPS,
        claim_hertz=claims["hertz_p0_error"], claim_hertz_level=CLAIM_HERTZ, claim_hertz_eps=claims["hertz_eps"])
    with open(args.doc, "w") as f:
        f.write(text)


def loadpath_order(loadpath, yardstick):
    """the observed order of the end's error in the step (a least-squares slope over the runs off the knots)"""
    off = [r for r in loadpath if not r["at_knots"] and r["error"] > 0]
    if len(off) < 2:
        return "(fewer than two runs off the knots: no order measured)"
    n, e = np.array([r["steps"] for r in off], float), np.array([r["error"] for r in off])
    slope = np.polyfit(np.log(n), np.log(e), 1)[0]
    per_step = statistics.median(r["per_step_s"] for r in loadpath)
    return ("Off the knots the error falls as steps^%.2f (least squares over %d to %d steps; error x steps = %.1f to %.1f): first order. "
            "A step costs %.3f s (median; %.3f yardsticks), so each halving of this error costs twice the steps."
            % (slope, n.min(), n.max(), (n * e).min(), (n * e).max(), per_step, per_step / yardstick))


def slider_text(slider):
    if not slider:
        return ""
    loose = max(r["eps"] for r in slider)
    return SLIDER_TEXT.format(slider_max=max(abs(r["ratio_error"]) for r in slider), slider_loose=loose,
                              cone_loose=max(r["cone_error"] for r in slider if r["eps"] == loose),
                              cone_tight=max((r["cone_error"] for r in slider if r["eps"] < loose), default=float("nan")))


def floor_text(floors):

    lines = []
    for key, name in (("p0_error", "peak pressure"), ("a_error", "contact radius")):
        lines.append("- %s: " % name + "; ".join("level %d from rtol %.0e (error %+.2f %%)" % (level, r["eps"], 100 * r[key])
                                                  for level, r in sorted(floors[key].items())))
    return "\n".join(lines)


def second_method(data):
    """the agreement of the first-order method's tightest converged run with the reference (nan if none converged)"""
    runs = [r for r in data["runs"] if r["method"] != "ssstar" and r["reason"] > 0]
    if not runs:
        return float("nan")
    best = min(runs, key=lambda r: r["eps"])
    return metrics(best, data["reference"])["err_u"]


def advice(sweep, disc, path):
    lines = []
    for d in disc:
        level_rows = sorted((r for r in sweep if r["level"] == d["level"]), key=lambda r: -r["eps"])
        enough = next((r for r in level_rows if r["err_u"] <= 0.1 * d["err_u"] and r["state_diff"] == 0), None)
        if enough:
            lines.append("- %s, level %d: the discretization error is %.1e; rtol %.0e (%d iterations, %.3f s, %.2f yardsticks) puts the solver "
                         "error at %.1e with the reference's contact states — tighter buys nothing for the physics of this mesh."
                         % (path, d["level"], d["err_u"], enough["eps"], enough["iterations"], enough["time_s"], enough["yardsticks"], enough["err_u"]))
    return "\n".join(lines)


def baseline_advice(sweep, base):
    """per level of the baseline: its cheapest run as accurate as ssstar at its loosest and at a middle tolerance"""
    lines = []
    for level in sorted({r["level"] for r in base}):
        newton = sorted((r for r in sweep if r["level"] == level), key=lambda r: -r["eps"])
        fixed = sorted((r for r in base if r["level"] == level and r["converged"]), key=lambda r: r["time_s"])
        parts = []
        for target in (newton[0], next((r for r in newton if r["eps"] <= 1e-6), newton[-1])):
            match = next((r for r in fixed if r["err_u"] <= max(target["err_u"], 1e-15)), None)
            if match:
                parts.append("ssstar's error %.1e at rtol %.0e (%.4f s) costs the baseline rtol %.0e, %d iterations, %.4f s (%.0fx)"
                             % (target["err_u"], target["eps"], target["time_s"], match["eps"], match["iterations"], match["time_s"],
                                match["time_s"] / target["time_s"]))
            else:
                parts.append("ssstar's error %.1e at rtol %.0e (%.4f s) is beyond every baseline run" % (target["err_u"], target["eps"], target["time_s"]))
        lines.append("- level %d, at equal error (dense route): %s." % (level, "; ".join(parts)))
    return ("\n" + "\n".join(lines)) if lines else ""


SLIDER_TEXT = """The largest |ratio_error| is {slider_max:.1e} over these levels and tolerances: from rtol {slider_loose:.0e} on, a sliding
contact's total force is right to that, with no tighter tolerance and no finer mesh. Node by node the tolerance does
show: cone_error, the largest | |r_t| / (phi r_n) - 1 | of a sliding node, is up to {cone_loose:.1e} at rtol {slider_loose:.0e}
and at most {cone_tight:.1e} at the tighter ones. |T| <= phi N with equality only when all slip directions are
parallel: the shortfall (negative ratio_error) is the spread of the nodes' slip directions, not an error of the law."""
TEMPLATE = """# What accuracy costs in time

Generated by `{command}` (`make accuracy`; `make accuracy-quick` is the small version a test runs) on {date},
{machine}. Every number below comes from that run: `docs/accuracy/sweep.csv` (one row per solve, both paths),
`discretization.csv`, `hertz.csv`, `mindlin.csv`, `slider.csv`, `loadpath.csv`, `claims.json` and the pictures beside them, each
stamped with the command, the date and the machine. Times are on a shared 2-core machine (2–3x swings): read them beside the
**AMG yardstick of the same run on as many ranks**, one CG + GAMG solve of the prism's K at level {yardstick_level}
(`bench/yardstick -yardstick amg`), measured at the start, the middle and the end of the runs it stands beside: on
{ranks} rank(s) {sticks} s, median **{yardstick:.3f} s**; on {big_ranks} ranks (the runs on {big_ranks} ranks{big_when}) {big_sticks} s,
median **{big_yardstick:.3f} s**. The column "yardsticks" is time / the yardstick of the row's number of ranks.

## What is re-measured by a test
`tests/suite_accuracy.py` runs `make accuracy-quick` and re-measures these two claims (no timings in pass/fail):
- the prism at level {claim_level}, rtol {claim_eps:.0e}: the solver error max|u - u_ref| / max|u_ref| is
  **{claim_dense:.1e}** on the dense route and **{claim_whole:.1e}** on the whole body;
- the hertz scene at level {claim_hertz_level}, rtol {claim_hertz_eps:.0e}: the peak pressure is **{claim_hertz:+.2%}** off Hertz's p0.
It also checks that every rule below ("for X % take ...") is the one `docs/accuracy/claims.json` holds.

## The set-up
The seed's prism at each level, solved from u = 0 with the stopping tolerance `-snes_rtol` in {tols} on {ranks} rank(s);
levels {big_levels} on {big_ranks} ranks with `-snes_rtol` in {big_tols}, one run each (column "ranks"):
- **the dense route** (`-snes_ssstar_reduction direct`): `examples/prism -level L -save_reduced` reduces K to the
  contact dofs once (the fixed cost "schur"), then `bench/accuracy_worker.py` solves the reduced problem per
  tolerance (time: SNESSolve, median of {repeat});
- **the whole body** (`-snes_ssstar_reduction none -nested_levels 0`, P never formed, Newton steps by Krylov +
  multigrid with the default `-snes_ssstar_ksp_rtol_max {default_krylov}`): one run of `examples/prism` per tolerance on
  {ranks} rank(s); time: the summary row's solve less the set-up of the whole body (the fixed cost "setup", the
  median over the tolerances), one run each;
- **the first-order baseline** (`-snes_ssstar_method fixedpoint`, u <- u + z, on the dense route, levels
  {baseline_levels}): the reference method.
Errors of both paths are measured against the same reference, the dense route at rtol 1e-14 (the exact solution of
the level's discrete problem to round-off): maxima over the contact nodes relative to the reference's max |u| (max
|r| for reactions); states: a node is in contact when r_n > {state_tol:g} max r_n, it sticks when in contact with
|u_t| <= {state_tol:g} max |u|.

## The references and the fixed costs
"law" is the reference's worst Coulomb-law violation (the check of `tests/check_solution.py`), "second" the
distance of the baseline's tightest converged run from it (a different algorithm, the same point), "order" the
observed order q = log(z_k+1/z_k)/log(z_k/z_k-1) of the last steps. Fixed costs in seconds: assembly (mesh to K),
schur (the dense route's reduction), setup (the whole body's, inside SNESSolve).

{refs}

![||z_k|| per iteration](accuracy/znorm_history.png)

## Solver error against tolerance: the dense route

{dense}

## Solver error against tolerance: the whole body

{whole}

{krylov}

![error against time](accuracy/error_vs_time.png)

## The first-order baseline

{base}

## Discretization error beside solver error
Each level's reference against a finer one than any level measured: **level {finest}, the whole body at rtol
{finest_rtol:.0e} on {big_ranks} ranks** (its solve {finest_time:.0f} s): the displacement at the level's nodes (the level-{finest}
solution interpolated bilinearly on its contact face), the total normal force, and the areas in contact and sticking.
The reference's own discretization error is not in these numbers: with err_u falling about as h (see the table), a
level-{finest} reference understates the error of level L by about L/{finest} of it.

{disc}

![error against level](accuracy/error_vs_level.png)

## Which tolerance for which purpose (the prism)
{advice}

## The mesh axis: Hertz
`examples/contact -options_file scenes/hertz.opts -level L -snes_rtol t -o hertz.h5` and `tests/scene_answers.py hertz
hertz.h5`: a half ball (R = 10) pressed on a rigid plane, frictionless; the contact radius a (fitted, and the bracket's
midpoint between the outermost node in contact and the innermost out) and the peak pressure p0 (fitted) against
Hertz's closed forms for the force the plane carries. Times: the whole run (mesh to file) on {ranks} rank(s); the
route is `auto`'s. The error does not go to zero with the mesh: the half ball is not a half space (a/R = 0.1), a
model error of the order of a few 1e-3 that Hertz's formulas carry.{hertz_dates}

{hertz}

![Hertz: error against time](accuracy/hertz_work_precision.png)

**The rule** (the coarsest level, and at it the loosest tolerance, whose error is within the target and stays within it
at every finer level and tighter tolerance measured; the whole run's time, this machine, the route and the nested
start `auto`'s):
{hertz_rule}

**Hertz's subsurface von Mises maximum** (the same runs; `/fields/von_mises` of each file, P1 tetrahedra: one
stress per cell): the largest von Mises stress of the cells under the contact (centroid within a of the axis, above
the depth 2 a) in Hertz's p0 against 0.620 p0, and its depth in a against 0.481 a (ν = 0.3), with a and p0 Hertz's
for the measured force (`tests/scene_answers.py von-mises hertz.h5`). A cell's constant stress averages the peak over the
cell, and the cell nearest the peak decides the depth, so both errors fall with the cells' size.

{vm}

![von Mises: error against time](accuracy/von_mises_work_precision.png)

**The rule** (as above):
{vm_rule}

**Where the tolerance stops mattering** (the loosest rtol from which on the answer moves by less than a tenth of its
error; tighter buys nothing there, the mesh dominates):
{floors}

## A sliding contact: T = phi N
The slider of `scenes/slider.opts` (`examples/contact -options_file scenes/slider.opts -level L -snes_rtol t`; measured
{slider_date}): a block pushed along x beyond phi N on a block, phi = 0.5, node-to-surface; every touching node
slides, so the contact's tangential force is phi times its normal force, whatever the mesh. ratio_error = |T| / (phi N) - 1
(as `tests/suite_pairs.py` measures it), the whole run on {big_ranks} ranks beside the yardstick on as many.

{slider}

{slider_text}

**The rule** (as for Hertz; the whole run on {big_ranks} ranks):
{slider_rule}

## The mesh axis: the Cattaneo–Mindlin stick radius
`examples/contact -options_file scenes/mindlin.opts -level L -snes_rtol t -snes_ssstar_reduction direct -o mindlin.h5` on
{big_ranks} ranks (the dense route: `auto` takes the whole body from level 2, whose inexact Newton steps diverged
there at rtol 1e-2 in a first run): the half ball pressed by
P on a block of the same material, then sheared by Q = 0.5 φP (φ = 0.3; elastically similar bodies, so the normal
load makes no tangential traction and one solve is P then Q). Cattaneo and Mindlin: the contact sticks inside
c = a (1 − Q/(φP))^(1/3) and slips in the annulus c < r < a. Measured c: the midpoint between the outermost sticking
node and the innermost sliding one (`tests/scene_answers.py stick-radius mindlin.h5`); c_error = c / c_CM − 1 with Hertz's a for
the measured P; "bracket" is the radial gap between those two nodes over c (they need not lie on one ray: on an
unstructured mesh the gap can be much smaller than the mesh size, so a small error at one level is partly luck; read
the trend over the levels).

{mindlin}

![Cattaneo-Mindlin: error against time](accuracy/mindlin_work_precision.png)

**The rule** (as for Hertz; the whole run on {big_ranks} ranks):
{mindlin_rule}

## Load paths: the error of a path's end against the steps
The block on a spring of `tests/suite_loadpath.py` (docs/derivation.md (11.1)-(11.2)): a nearly rigid block pressed by
P = 10, held sideways by a spring k = 1000, sheared by Q = 7.5 > phi P = 5, released, sheared back, released (knots of
the load at t = 1, ..., 5); its closed form ends at u_x = -(Q - phi P)/k = -2.5e-3. `examples/contact` with the
options of `BLOCK` in `bench/accuracy_mesh.py` and `-steps N` (equal steps on [0, 5]); the error of u_x at the end,
relative to 2.5e-3, the time of all steps (solve) and per step, the whole run on {big_ranks} ranks (yardsticks: the whole run). The incremental law is
exact on a path that is proportional between two steps: with steps on the knots the end is exact up to the block's
compliance; with steps off them the extreme load is missed by up to a step, an error of first order in the step.

{loadpath}

{loadpath_order}

![load path: error against steps](accuracy/loadpath_steps.png)

**The rule** (the fewest equal steps off the knots whose error is within the target and stays within it with more
steps; a path whose steps land on its knots is exact up to the body's compliance at any number of steps):
{loadpath_rule}

## Reading the stopping rule
- ssstar stops when ||z|| <= rtol max(||u||, ||gamma f||); z is the approximation step, a displacement (gamma =
  1/mean(diag P) turns forces into displacements), so rtol is a relative displacement accuracy, and err_u tracks it
  once the contact states are those of the reference (state_diff = 0); with them the Newton step is exact, the error
  falls superlinearly, and the last orders cost one or two iterations.
- The whole body's Newton steps are inexact (Krylov to a tolerance that tightens with ||z||/||z_0||, loosest
  `-snes_ssstar_ksp_rtol_max`); its iterations cost Krylov solves instead of LU solves, and it has no Schur
  complement to pay first. Its sticking nodes keep a tangential displacement of the order of the solver error
  instead of zero, so its state_diff (a threshold of {state_tol:g} max|u|) stays above zero until the error is below it.
- Engineering quantities (total normal force, contact area, Hertz's a and p0) settle long before the displacement:
  the mesh, not the solver, sets their error from a loose tolerance on.
"""


if __name__ == "__main__":
    main()
