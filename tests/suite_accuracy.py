"""The work-precision study (make accuracy, make accuracy-quick): its files, columns and numbers, and two of the claims
of docs/accuracy.md re-measured by the quick study."""
import csv
import json
import os

from harness import *  # noqa: F401,F403 (run, expect, test, paths)

COLUMNS = "level,path,method,ksp_rtol_max,eps,iterations,time_s,setup_s,err_u,err_r,normal_force_err,contact_nodes_diff,state_diff,yardsticks".split(",")


def read_csv(path):
    """the rows of a CSV of the study, whose first line is its provenance (# command; date; machine; yardstick)"""
    with open(path) as f:
        first = f.readline()
        expect(first.startswith("# bench/accuracy.py") and "UTC" in first and "cores" in first and "yardstick" in first, "%s: provenance line %r" % (path, first))
        return list(csv.DictReader(f))


@test("make accuracy-quick (bench/accuracy.py --quick: the prism at levels 4 and 6 on the dense route and at 6 on the whole body, rtol 1e-3 and 1e-6, the baseline on level 4, finest level 8, hertz level 1 with its von Mises maximum, the block on a spring in 6 steps, one yardstick) writes sweep.csv, discretization.csv, hertz.csv, loadpath.csv with the command, date, machine and yardstick in their first line, claims.json and the pictures; the solver error falls with the tolerance and is below 1e-5 at rtol 1e-6 on both paths; the baseline takes 10x ssstar's iterations; Hertz's von Mises maximum at level 1 is within 15 % of 0.620 p0; it re-measures two claims of docs/accuracy.md: the solver error at level 6, rtol 1e-6 (within 3x on the dense route, 10x on the whole body's inexact steps) and Hertz's peak pressure error at level 1 (within 0.2 %); and docs/accuracy.md states every rule of its claims.json (Hertz, von Mises, Cattaneo-Mindlin, the slider, the load path: level or steps, rtol, seconds, ranks), with levels 12 and 16 on 2 ranks on both paths in its sweep.csv")
def accuracy_machinery():
    out_dir = os.path.join(OUT, "accuracy")
    run([PYTHON, os.path.join(ROOT, "bench", "accuracy.py"), "--quick", "--out", out_dir, "--doc", os.path.join(out_dir, "accuracy.md")], timeout=600)
    rows = read_csv(os.path.join(out_dir, "sweep.csv"))
    expect(all(c in rows[0] for c in COLUMNS), "sweep.csv lacks columns: %s" % [c for c in COLUMNS if c not in rows[0]])
    runs = sorted((r["level"], r["path"], r["method"], float(r["eps"])) for r in rows)
    expected = sorted([(l, p, "ssstar", e) for l, p in (("4", "direct"), ("6", "direct"), ("6", "none")) for e in (1e-3, 1e-6)] +
                      [("4", "direct", "fixedpoint", e) for e in (1e-3, 1e-6)])
    expect(runs == expected, "runs %s, expected %s" % (runs, expected))
    for level, path in (("4", "direct"), ("6", "direct"), ("6", "none")):
        if True:
            err = {float(r["eps"]): float(r["err_u"]) for r in rows if r["level"] == level and r["path"] == path and r["method"] == "ssstar"}
            expect(err[1e-6] <= err[1e-3] and err[1e-6] <= 1e-5, "level %s, %s: err_u %s" % (level, path, err))
    fixed = {float(r["eps"]): int(r["iterations"]) for r in rows if r["method"] == "fixedpoint"}
    newton = {float(r["eps"]): int(r["iterations"]) for r in rows if r["method"] == "ssstar" and r["level"] == "4" and r["path"] == "direct"}
    expect(all(fixed[e] > 10 * newton[e] for e in fixed), "iterations: fixedpoint %s, ssstar %s" % (fixed, newton))
    disc = read_csv(os.path.join(out_dir, "discretization.csv"))
    expect([d["level"] for d in disc] == ["4", "6"] and float(disc[0]["err_u"]) > float(disc[1]["err_u"]) > 0, "discretization.csv: %s" % disc)
    hertz, loadpath = read_csv(os.path.join(out_dir, "hertz.csv")), read_csv(os.path.join(out_dir, "loadpath.csv"))
    expect(len(hertz) == 1 and len(loadpath) == 1 and float(loadpath[0]["error"]) > 0.1, "hertz.csv %s, loadpath.csv %s (6 steps miss the load's extremes)" % (hertz, loadpath))
    expect(abs(float(hertz[0]["vm_error"])) <= 0.15, "Hertz's von Mises maximum at level 1: %s off 0.620 p0" % hertz[0]["vm_error"])
    for png in ("error_vs_time.png", "error_vs_level.png", "znorm_history.png", "hertz_work_precision.png", "loadpath_steps.png"):
        expect(os.path.getsize(os.path.join(out_dir, png)) > 10000, "%s missing or empty" % png)
    with open(os.path.join(out_dir, "claims.json")) as f:
        now = json.load(f)
    with open(os.path.join(ROOT, "docs", "accuracy", "claims.json")) as f:
        doc = json.load(f)
    expect(now["command"].startswith("bench/accuracy.py --quick") and doc["command"] == "bench/accuracy.py", "claims of %s against %s" % (now["command"], doc["command"]))
    for key, factor in (("err_u_dense", 3), ("err_u_whole", 10)):
        expect(doc[key] / factor <= now[key] <= doc[key] * factor or max(now[key], doc[key]) <= 1e-11,
               "%s at level %d, rtol %g: re-measured %.2e, docs/accuracy.md says %.2e" % (key, doc["level"], doc["eps"], now[key], doc[key]))
    expect(now["hertz_eps"] == doc["hertz_eps"] and abs(now["hertz_p0_error"] - doc["hertz_p0_error"]) <= 0.002,
           "Hertz's peak pressure at level 1: re-measured %+.4f, docs/accuracy.md says %+.4f" % (now["hertz_p0_error"], doc["hertz_p0_error"]))
    with open(os.path.join(ROOT, "docs", "accuracy.md")) as f:
        text = f.read()
    for r in doc["rules"]:
        if not r["reached"]:
            expect("- %g %% on %s: not reached" % (100 * r["target"], r["answer"]) in text, "docs/accuracy.md does not state the rule %s" % r)
            continue
        what = ("take level %d, rtol %.0e:" % (r["level"], r["eps"])) if r["steps"] is None else ("take %d equal steps" % r["steps"])
        line = "- for %g %% on %s %s" % (100 * r["target"], r["answer"], what)
        expect(any(l.startswith(line) and ": %.1f s on %d rank(s)" % (r["seconds"], r["ranks"]) in l for l in text.splitlines()),
               "docs/accuracy.md does not state the rule %s" % r)
    answers = {r["answer"] for r in doc["rules"]}
    expect({"the peak pressure", "the von Mises maximum", "the stick radius", "T = phi N"} <= answers and any(a.startswith("the end of the path") for a in answers),
           "claims.json's rules cover %s" % answers)
    big = {(r["level"], r["path"]) for r in read_csv(os.path.join(ROOT, "docs", "accuracy", "sweep.csv")) if r.get("ranks") == "2"}
    expect({(l, p) for l in ("12", "16") for p in ("direct", "none")} <= big, "docs/accuracy/sweep.csv on 2 ranks: %s" % sorted(big))
    expect("**%.1e**" % doc["err_u_dense"] in text and "**%+.2f%%**" % (100 * doc["hertz_p0_error"]) in text.replace(" %", "%"),
           "docs/accuracy.md does not quote claims.json (%s)" % doc)
