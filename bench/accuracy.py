#!/usr/bin/python3
"""What accuracy costs in time: the work-precision study of ssstar on the seed's prism (make accuracy).

  bench/accuracy.py [--levels 4,6,8,10,12] [--finest 16] [--tols 1e-2,...,1e-12] [--methods ssstar,fixedpoint]
                    [--repeat 3] [--baseline-levels 4,6,8] [--baseline-repeat 1] [--out docs/accuracy]

The first-order baseline (-snes_ssstar_method fixedpoint) needs thousands of iterations per solve: it runs on the
--baseline-levels only, --baseline-repeat times per tolerance.

For every level: examples/prism writes the reduced problem (P, f, coordinates); bench/accuracy_worker.py solves it
for every method and stopping tolerance (-snes_rtol) and once at the tightest tolerance (the reference). Errors are
measured against the reference of the same level (solver error) and the reference of the finest level
(discretization error). Writes OUT/sweep.csv, OUT/discretization.csv, OUT/*.png and docs/accuracy.md."""
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
PRISM = os.path.join(ROOT, "examples", "prism")
ROW = re.compile(r"^\s*(\d+)\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)\s+(\d+)\s+([\d.]+)\s+(\d+)", re.M)
STATE_TOL = 1e-8  # a node carries force if r_n > STATE_TOL max r_n; it slips if |u_t| > STATE_TOL max|u| (reference scales)
COLUMNS = ["level", "method", "eps", "iterations", "time_s", "err_u", "err_r", "normal_force_err", "contact_nodes_diff", "state_diff",
           "converged", "znorm_final", "coulomb_residual"]


def parse():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--levels", default="4,6,8,10,12")
    p.add_argument("--finest", type=int, default=16)
    p.add_argument("--tols", default="1e-2,1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12")
    p.add_argument("--methods", default="ssstar,fixedpoint")
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--baseline-levels", default="4,6,8", help="levels on which the methods other than ssstar run")
    p.add_argument("--baseline-repeat", type=int, default=1, help="runs per tolerance of the methods other than ssstar")
    p.add_argument("--out", default=os.path.join(ROOT, "docs", "accuracy"))
    p.add_argument("--doc", default=os.path.join(ROOT, "docs", "accuracy.md"))
    return p.parse_args()


def run(cmd):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
    if p.returncode:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), p.stdout[-3000:]))
    return p.stdout


def save_level(level, work):
    """examples/prism at the level, saving the reduced problem; returns the file and the fixed costs"""
    binary = os.path.join(work, "prism_L%d.bin" % level)
    m = ROW.search(run([PRISM, "-level", str(level), "-save_reduced", binary, "-snes_rtol", "1e-14"]))
    return binary, {"nodes": int(m.group(3)), "contact": int(m.group(6)), "assembly": float(m.group(4)), "schur": float(m.group(5))}


def solve_level(binary, methods, tols, repeat, baseline_repeat=1):
    cmd = [sys.executable, os.path.join(ROOT, "bench", "accuracy_worker.py"), binary, "--methods", methods, "--tols", tols, "--repeat", str(repeat),
           "--baseline-repeat", str(baseline_repeat)]
    run(cmd)
    with open(binary + ".json") as f:
        return json.load(f)


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


def plots(out, rows, disc, level_data):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    levels = sorted(level_data)
    colors = dict(zip(levels, plt.cm.viridis(np.linspace(0, 0.9, len(levels)))))
    fig, ax = plt.subplots(figsize=(8, 6))
    for (level, method), group in _groups(rows).items():
        ax.loglog([g["time_s"] for g in group], [max(g["err_u"], 1e-17) for g in group], "o-" if method == "ssstar" else "s--",
                  color=colors[level], label="L%d %s" % (level, method))
    for d in disc:
        ax.axhline(d["err_u"], color=colors[d["level"]], lw=0.8, ls=":")
    ax.set_xlabel("solve time [s] (SNESSolve on the reduced problem, median)")
    ax.set_ylabel("max |u - u_ref| / max |u_ref| (contact displacement)")
    ax.set_title("Error against time; dotted: discretization error of the level")
    ax.legend(fontsize=7, ncol=2)
    fig.savefig(os.path.join(out, "error_vs_time.png"), dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(8, 6))
    tols = sorted({g["eps"] for g in rows}, reverse=True)
    for eps in tols[::2]:
        pts = [(g["level"], g["err_u"]) for g in rows if g["method"] == "ssstar" and g["eps"] == eps]
        ax.semilogy([p[0] for p in pts], [max(p[1], 1e-17) for p in pts], "o-", label="ssstar, rtol %.0e" % eps)
    ax.semilogy([d["level"] for d in disc], [d["err_u"] for d in disc], "k^-", lw=2, label="discretization (vs finest level)")
    ax.set_xlabel("level")
    ax.set_ylabel("max |u - u_ref| / max |u_ref|")
    ax.set_title("Solver error and discretization error against the level")
    ax.legend(fontsize=8)
    fig.savefig(os.path.join(out, "error_vs_level.png"), dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(8, 6))
    for level in levels:
        h = level_data[level]["reference"]["history"]
        ax.semilogy(range(len(h)), h, "o-", color=colors[level], label="L%d (order %.2f)" % (level, observed_order(h)))
    ax.set_xlabel("iteration k")
    ax.set_ylabel("||z_k||")
    ax.set_title("ssstar: ||z_k|| per iteration (reference solves); observed order of the tail")
    ax.legend()
    fig.savefig(os.path.join(out, "znorm_history.png"), dpi=120)
    plt.close(fig)


def _groups(rows):
    groups = {}
    for g in rows:
        groups.setdefault((g["level"], g["method"]), []).append(g)
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


def main():
    args = parse()
    levels = [int(l) for l in args.levels.split(",")]
    work = os.path.join(ROOT, "bench", "output", "accuracy")
    os.makedirs(work, exist_ok=True)
    os.makedirs(args.out, exist_ok=True)
    costs, level_data = {}, {}
    for level in levels:
        binary, costs[level] = save_level(level, work)
        baseline = level in [int(l) for l in args.baseline_levels.split(",") if l]
        methods = ",".join(m for m in args.methods.split(",") if m == "ssstar" or baseline)
        level_data[level] = solve_level(binary, methods, args.tols, args.repeat, args.baseline_repeat)
        print("level %d done" % level, flush=True)
    binary, costs[args.finest] = save_level(args.finest, work)
    finest = solve_level(binary, "ssstar", "", 1)

    rows = []
    for level, data in sorted(level_data.items()):
        ref = data["reference"]
        for r in data["runs"]:
            m = metrics(r, ref)
            rows.append(dict(level=level, method=r["method"], eps=r["eps"], iterations=r["iterations"], time_s=r["time"],
                             converged=int(r["reason"] > 0), znorm_final=r["history"][-1], **m))
    with open(os.path.join(args.out, "sweep.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({c: r[c] for c in COLUMNS})
    disc = discretization(level_data, finest)
    with open(os.path.join(args.out, "discretization.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(disc[0]))
        w.writeheader()
        w.writerows(disc)
    plots(args.out, rows, disc, level_data)
    write_doc(args, levels, costs, level_data, finest, rows, disc)


def write_doc(args, levels, costs, level_data, finest, rows, disc):
    refs = [{"level": l, "iterations": level_data[l]["reference"]["iterations"], "znorm": level_data[l]["reference"]["history"][-1],
             "law": coulomb_residual(*arrays(level_data[l]["reference"])), "order": observed_order(level_data[l]["reference"]["history"]),
             "second": second_method(level_data[l]), "assembly": costs[l]["assembly"], "schur": costs[l]["schur"], "contact": costs[l]["contact"]}
            for l in levels]
    sweep = [r for r in rows if r["method"] == "ssstar"]
    base = [r for r in rows if r["method"] != "ssstar"]
    text = TEMPLATE.format(
        date=datetime.date.today().isoformat(), machine=machine(), levels=args.levels, finest=args.finest, tols=args.tols,
        methods=args.methods, repeat=args.repeat, baseline_levels=args.baseline_levels, baseline_repeat=args.baseline_repeat, state_tol=STATE_TOL,
        refs=table(refs, ["level", "contact", "assembly", "schur", "iterations", "znorm", "law", "second", "order"],
                   ["%d", "%d", "%.2f", "%.2f", "%d", "%.1e", "%.1e", lambda v: "%.1e" % v if v == v else "—", "%.2f"]),
        sweep=table(sweep, ["level", "eps", "iterations", "time_s", "err_u", "err_r", "normal_force_err", "contact_nodes_diff", "state_diff"],
                    ["%d", "%.0e", "%d", "%.4f", "%.1e", "%.1e", "%.1e", "%d", "%d"]),
        base=table(base, ["level", "eps", "iterations", "time_s", "converged", "err_u", "err_r", "state_diff"],
                   ["%d", "%.0e", "%d", "%.4f", "%d", "%.1e", "%.1e", "%d"]) if base else "(not run)",
        disc=table(disc, ["level", "err_u", "normal_force_err", "contact_area_err", "stick_area_err"], ["%d", "%.1e", "%.1e", "%.1e", "%.1e"]),
        advice=advice(sweep, disc) + baseline_advice(sweep, base))
    with open(args.doc, "w") as f:
        f.write(text)


def second_method(data):
    """the agreement of the first-order method's tightest converged run with the reference (nan if none converged)"""
    runs = [r for r in data["runs"] if r["method"] != "ssstar" and r["reason"] > 0]
    if not runs:
        return float("nan")
    best = min(runs, key=lambda r: r["eps"])
    return metrics(best, data["reference"])["err_u"]


def advice(sweep, disc):
    lines = []
    for d in disc:
        level_rows = sorted((r for r in sweep if r["level"] == d["level"]), key=lambda r: -r["eps"])
        enough = next((r for r in level_rows if r["err_u"] <= 0.1 * d["err_u"] and r["state_diff"] == 0), None)
        if enough:
            lines.append("- level %d: the discretization error is %.1e; rtol %.0e (%d iterations, %.3f s) already puts the solver error "
                         "at %.1e with the reference's contact states — tighter buys nothing for the physics of this mesh."
                         % (d["level"], d["err_u"], enough["eps"], enough["iterations"], enough["time_s"], enough["err_u"]))
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
        lines.append("- level %d, at equal error: %s." % (level, "; ".join(parts)))
    return ("\n" + "\n".join(lines)) if lines else ""


TEMPLATE = """# What accuracy costs in time

Generated by `make accuracy` (`bench/accuracy.py --levels {levels} --finest {finest} --methods {methods} --repeat {repeat} --baseline-levels {baseline_levels} --baseline-repeat {baseline_repeat}`)
on {date}, {machine}. Every number below comes from that run: `docs/accuracy/sweep.csv` (one row per run),
`docs/accuracy/discretization.csv`, and the pictures beside them.

## The set-up
The seed's prism at each level (`examples/prism -level L -save_reduced`), reduced to its contact dofs once; then the
reduced problem is solved with the stopping tolerance `-snes_rtol` in {tols} by ssstar (semismooth* Newton) and by the
first-order baseline of the same plugin (`-snes_ssstar_method fixedpoint`: u <- u + z, the approximation step alone,
with gamma = 1/||P||_inf; on levels {baseline_levels}, {baseline_repeat} run(s) per tolerance: it needs thousands of iterations).
Times are SNESSolve on the reduced problem (median of {repeat}); the fixed costs of a level (mesh and assembly, Schur
complement) do not depend on the tolerance and are listed apart. Errors are maxima over the contact nodes relative to
the reference's max |u| (max |r| for reactions); states: a node is in contact when r_n > {state_tol:g} max r_n, it sticks
when in contact with |u_t| <= {state_tol:g} max |u|.

## The references
Each level's reference is ssstar at rtol 1e-14, the tightest the solver reaches (its ||z|| ends at round-off). It is
trustworthy because it satisfies the Coulomb law at every node to the residual shown ("law", the check of
`tests/check_solution.py`), and because the first-order method, a different algorithm, converges to the same point
("second": max difference of the displacement between the reference and the baseline's tightest converged run).
"order" is the observed order of convergence q = log(z_k+1/z_k)/log(z_k/z_k-1) over the last steps.

{refs}

![||z_k|| per iteration](accuracy/znorm_history.png)

## Solver error against tolerance (ssstar)

{sweep}

![error against time](accuracy/error_vs_time.png)

## The first-order baseline

{base}

## Discretization error beside solver error
Each level's reference against the finest level's (level {finest}): the displacement at the level's nodes (the finest
solution interpolated bilinearly on its contact face), the total normal force, and the areas in contact and sticking.

{disc}

![error against level](accuracy/error_vs_level.png)

## Which tolerance for which purpose
{advice}

- **What the stopping rule means.** ssstar stops when ||z|| <= rtol max(||u||, ||gamma f||) (SNESConvergedSSStar). z is
  the approximation step: the distance, in the units of u (mm for the prism), from the iterate to its projection onto
  the friction law; gamma = 1/mean(diag P) turns the forces of the reduced problem into displacements, so ||z|| is a
  displacement whatever the units of the problem. rtol is therefore a relative displacement accuracy: with max|u| ~ 1e-3 mm,
  rtol 1e-6 asks for the contact displacements to about a nanometre (times the conditioning of the problem, which the
  tables show: err_u tracks rtol within a factor of ~10 once the states are right).
- **The Coulomb-law residual** is what a user checks afterwards (tests/check_solution.py): the worst violation of
  u_n >= 0, r_n >= 0, u_n r_n = 0, |r_t| <= phi r_n and the slip direction. At the solution z = 0 exactly when the law
  holds, and near it the residual is of the order of ||z|| relative to max|u| — except the slip direction of nodes that
  barely slide, which is only as accurate as |u_t| allows.
- **Engineering quantities** (total normal force, contact area, stick/slip map) settle long before the displacement
  does: once the states are those of the reference (state_diff = 0), the Newton step is exact for the remaining
  iterations and the error falls superlinearly, so the last two or three orders of accuracy cost one or two iterations.
- **The baseline** (the approximation step alone) converges linearly, at a rate set by the conditioning of P: its
  iterations grow with the level and by a constant number per decade of rtol. The lines "at equal error" above compare
  the two methods at the same accuracy; at the same rtol the baseline can be faster only where its error is far
  larger than ssstar's (its table), because z with gamma = 1/||P||_inf is a short step, not a small error.
"""


if __name__ == "__main__":
    main()
