"""The work-precision study's machinery (make accuracy) on small levels: its files, columns and numbers."""
import csv
import os

from harness import *  # noqa: F401,F403 (run, expect, test, paths)

COLUMNS = "level,method,eps,iterations,time_s,err_u,err_r,normal_force_err,contact_nodes_diff,state_diff".split(",")


@test("bench/accuracy.py on levels 3 and 4 (finest 5; rtol 1e-3, 1e-6, 1e-9; the baseline on level 3) writes sweep.csv with the required columns, one row per run, errors that fall as the tolerance tightens, the reference's contact states at 1e-9, the baseline (fixedpoint) behind ssstar in iterations, references that pass the Coulomb law, the discretization table and the pictures")
def accuracy_machinery():
    out_dir, doc = os.path.join(OUT, "accuracy"), os.path.join(OUT, "accuracy.md")
    run([PYTHON, os.path.join(ROOT, "bench", "accuracy.py"), "--levels", "3,4", "--finest", "5", "--tols", "1e-3,1e-6,1e-9", "--repeat", "1",
         "--baseline-levels", "3", "--out", out_dir, "--doc", doc], timeout=600)
    with open(os.path.join(out_dir, "sweep.csv")) as f:
        rows = list(csv.DictReader(f))
    expect(all(c in rows[0] for c in COLUMNS), "sweep.csv lacks columns: %s" % [c for c in COLUMNS if c not in rows[0]])
    runs = sorted((r["level"], r["method"], float(r["eps"])) for r in rows)
    expected = sorted([(l, "ssstar", e) for l in ("3", "4") for e in (1e-3, 1e-6, 1e-9)] + [("3", "fixedpoint", e) for e in (1e-3, 1e-6, 1e-9)])
    expect(runs == expected, "runs %s, expected %s" % (runs, expected))
    for level in ("3", "4"):
        sweep = sorted((r for r in rows if r["level"] == level and r["method"] == "ssstar"), key=lambda r: -float(r["eps"]))
        errors = [float(r["err_u"]) for r in sweep]
        expect(errors[0] > errors[1] >= errors[2] and errors[2] <= 1e-8 and int(sweep[2]["state_diff"]) == 0,
               "level %s: err_u %s, states differ at 1e-9 in %s nodes" % (level, errors, sweep[2]["state_diff"]))
    fixed = {float(r["eps"]): r for r in rows if r["method"] == "fixedpoint"}
    newton = {float(r["eps"]): r for r in rows if r["method"] == "ssstar" and r["level"] == "3"}
    for eps in (1e-3, 1e-6, 1e-9):
        expect(int(fixed[eps]["iterations"]) > 10 * int(newton[eps]["iterations"]), "rtol %g: fixedpoint %s iterations, ssstar %s" % (eps, fixed[eps]["iterations"], newton[eps]["iterations"]))
    with open(os.path.join(out_dir, "discretization.csv")) as f:
        disc = list(csv.DictReader(f))
    expect([d["level"] for d in disc] == ["3", "4"] and all(float(d["err_u"]) > 0 for d in disc), "discretization.csv: %s" % disc)
    for png in ("error_vs_time.png", "error_vs_level.png", "znorm_history.png"):
        expect(os.path.getsize(os.path.join(out_dir, png)) > 10000, "%s missing or empty" % png)
    with open(doc) as f:
        text = f.read()
    import re
    laws = [float(v) for v in re.findall(r"^\| [34] \| \d+ \| [\d.]+ \| [\d.]+ \| \d+ \| \S+ \| (\S+) \|", text, re.M)]
    expect(len(laws) == 2 and max(laws) <= 1e-8, "the references' Coulomb-law residuals %s (accuracy.md)" % laws, text)
