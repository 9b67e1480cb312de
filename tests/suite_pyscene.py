"""Scenes from Python (ssstar.Scene, python/ssstar/scene.py, over the C scene library; examples/scene.py): the block
load path (README, docs/guide/load-paths.md), a parameter sweep, scenes of docs/guide/scenes.md and a load path decided by a Python loop, each against
examples/contact with the same options (-snes_rtol named on both, so that the solver's defaults do not matter); the
module's contract (tests/python_scene_check.py); pip install ./python and make install."""
import os
import re
import shutil
import subprocess

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
SCENE_PY = os.path.join(ROOT, "examples", "scene.py")
SCENE_CHECK = os.path.join(ROOT, "tests", "python_scene_check.py")
RTOL = ["-snes_rtol", "1e-12"]
# the block of the load path of the README and docs/guide/load-paths.md (examples/scene.py's BLOCK)
BLOCK = ["-geo", "meshes/block.geo", "-level", "2", "-E", "2e8", "-nu", "0.3", "-spring_top", "1000", "-contact", "bottom", "-friction_bottom", "0.5"]
README_PATH = "0:0,0,0;1:0,0,-10;2:7.5,0,-10;3:0,0,-10;4:-7.5,0,-10;5:0,0,-10"
# The path of each rank count: on 2 ranks MUMPS's parallel factorization is not reproducible on a loaded machine (its
# dynamic scheduling: examples/contact itself then differs from run to run by 1e-9 relative on the nearly floating block,
# measured); the whole body (-snes_ssstar_reduction none, CG + GAMG) is, so the 2-rank comparisons name it
PATHS = {1: [], 2: ["-snes_ssstar_reduction", "none"]}
# datasets and attributes that are the stopping test's own quantities (||z|| at convergence: round-off by construction)
STOPPING = ("residual_norm", "tolerance")


def out(name):
    return os.path.join(OUT, name)


def python_run(cmd, timeout=600, expect_rc=0):
    """A Python program of ours (PYTHONPATH: the source tree's module) with PETSc's leak check: no block left"""
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    env.pop("SSSTAR_LIB", None)
    p = subprocess.run(cmd + ["-malloc_dump"], cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=timeout)
    expect(p.returncode == expect_rc, "exit status %d from %s" % (p.returncode, " ".join(cmd)), p.stdout)
    leaks = LEAK.findall(p.stdout)
    expect(not leaks, "memory leaked (-malloc_dump) by %s:\n%s" % (" ".join(cmd), "\n".join(leaks[:20])))
    return p.stdout


def same_law(c_h5, py_h5):
    """tests/check_solution.py coulomb gives the Python file the verdicts it gives examples/contact's (each condition
    ok or VIOLATED, the states)"""
    verdicts = []
    for h5 in (c_h5, py_h5):
        p = subprocess.run(CHECK + ["coulomb", h5], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
        verdicts.append([line.split()[0] + " " + line.split()[-1] for line in p.stdout.split("\n") if line.strip().endswith(("ok", "VIOLATED"))]
                        + [line for line in p.stdout.split("\n") if line.startswith("nodes")])
    expect(verdicts[0] == verdicts[1] and verdicts[0], "check_solution.py: %s, examples/contact's file %s" % (verdicts[1], verdicts[0]))


def same_files(c_h5, py_h5, rtol=1e-12):
    """Every dataset of examples/contact's file in the Python one, of the same shape, within rtol of the dataset's
    largest value (integers equal), and the same outcome; returns the largest relative difference"""
    worst = 0.0
    with h5py.File(c_h5, "r") as c, h5py.File(py_h5, "r") as p:
        names = []
        c.visititems(lambda name, obj: names.append(name) if isinstance(obj, h5py.Dataset) else None)
        for name in names:
            expect(name in p, "%s: no dataset %s" % (py_h5, name))
            a, b = c[name][()], p[name][()]
            expect(a.shape == b.shape, "%s: shape %s, examples/contact's %s" % (name, b.shape, a.shape))
            if a.dtype.kind not in "fiu" or name.split("/")[-1] in STOPPING:
                continue
            if a.dtype.kind in "iu":
                expect(np.array_equal(a, b), "%s differs from examples/contact's" % name)
                continue
            scale = np.abs(a).max() if a.size else 0
            d = np.abs(a - b).max() / scale if scale > 0 else (np.abs(b).max() if b.size else 0)
            expect(d <= rtol, "%s differs from examples/contact's by %.2e relative" % (name, d))
            worst = max(worst, d)
        for attr in ("converged_reason", "iterations", "failed_step"):
            expect(str(c.attrs.get(attr)) == str(p.attrs.get(attr)), "attribute %s: %s, examples/contact's %s" % (attr, p.attrs.get(attr), c.attrs.get(attr)))
    return worst


@test("the block load path of the README and docs/guide/load-paths.md from Python (examples/scene.py block: ssstar.Scene with the history as (t, (x, y, z)) pairs, steps() and write()) writes the file examples/contact writes for the documented command: every dataset of every step within 1e-12 of it on 1 and 2 ranks (on 2 ranks the whole body, -snes_ssstar_reduction none: MUMPS's parallel factorization is not reproducible under load); the top face back at u_x = +-2.49994e-3 after the releases (docs/guide/load-paths.md); check_solution.py coulomb judges it as it judges examples/contact's, and passes it at every step (--steps); no PETSc memory left")
def pyscene_block_path():
    for ranks in (1, 2):
        c_h5, py_h5 = out("pyscene_block_c_np%d.h5" % ranks), out("pyscene_block_py_np%d.h5" % ranks)
        run(mpiexec(ranks, CONTACT, *BLOCK, "-traction_top", README_PATH, *RTOL, *PATHS[ranks], "-o", c_h5))
        text = python_run(mpiexec(ranks, PYTHON, SCENE_PY, "block", "--out", py_h5, *RTOL, *PATHS[ranks]))
        same_files(c_h5, py_h5)
        ux = {float(t): float(u) for t, u in re.findall(r"^t (\S+):.*top u_x (\S+)$", text, re.M)}
        expect(sorted(ux) == [0, 1, 2, 3, 4, 5] and abs(ux[3] - 2.49994e-3) < 5e-9 and abs(ux[5] + 2.49994e-3) < 5e-9,
               "%d ranks: u_x after the releases %s" % (ranks, ux), text)
        same_law(c_h5, py_h5)
        law = run(CHECK + ["coulomb", "--steps", py_h5])
        expect("VIOLATED" not in law, "%d ranks: the law at some step" % ranks, law)


def sweep_csv(path):
    rows = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return rows[:, 0], rows[:, 2]


@test("the parameter sweep from Python (examples/scene.py sweep: a scene per Q/(phi P), press, shear, release): each residual slip (the mean x slip of the contact face after the release) equals examples/contact's for the same path on as many ranks (2: the whole body) to 1e-12 of the largest, on 1 rank, 2 ranks and 2 ranks with --split (each rank its own scenes on PETSC_COMM_SELF, gathered by mpi4py: examples/contact on 1 rank); it follows (11.2) max(0, Q - phi P)/k within 1e-6 (2e-4 of the largest: the block's compliance) and is below 1e-8 under phi P; the picture is written", full=True)
def pyscene_sweep():
    ratios = [0.5, 1.25, 2.0]
    reference = {}
    for ranks in (1, 2):
        slips = []
        for r in ratios:
            c_h5 = out("pyscene_sweep_c_%g_np%d.h5" % (r, ranks))
            run(mpiexec(ranks, CONTACT, *BLOCK, "-traction_top", "0:0,0,0;1:0,0,-10;2:%r,0,-10;3:0,0,-10" % (r * 0.5 * 10), *RTOL, *PATHS[ranks], "-o", c_h5))
            with h5py.File(c_h5, "r") as f:
                slips.append(np.mean(f["contact/slip"][:, 0]))
        reference[ranks] = np.array(slips)
    for ranks, split in ((1, []), (2, []), (2, ["--split"])):
        csv, png = out("pyscene_sweep_np%d%s.csv" % (ranks, "_split" if split else "")), out("pyscene_sweep_np%d.png" % ranks)
        if os.path.exists(png):
            os.remove(png)
        text = python_run(mpiexec(ranks, PYTHON, SCENE_PY, "sweep", "--ratios", ",".join(map(str, ratios)), "--out", png, "--csv", csv, *split, *RTOL, *PATHS[1 if split else ranks]))
        got_ratios, slips = sweep_csv(csv)
        expect(list(got_ratios) == ratios, "the ratios of the csv: %s" % got_ratios, text)
        ref = reference[1 if split else ranks]  # --split: each scene on one rank
        d = np.abs(slips - ref).max() / np.abs(ref).max()
        expect(d <= 1e-12, "%d ranks%s: the residual slips %s differ from examples/contact's %s by %.1e" % (ranks, " --split" if split else "", slips, ref, d), text)
        expect(os.path.exists(png), "%d ranks: no picture %s" % (ranks, png), text)
    closed = np.maximum(0, (np.array(ratios) - 1) * 0.5 * 10) / 1000
    expect(np.abs(slips - closed).max() <= 1e-6 and abs(slips[0]) < 1e-8, "against (11.2): %s, %s" % (slips, closed))


@test("scenes of docs/guide/scenes.md from Python (examples/scene.py run scenes/X.opts -o: ssstar.Scene from the options file, solve(), o=...) write the files of examples/contact -options_file scenes/X.opts -o: shear (a stick-slip front; and with -nested_levels 1, started from the coarser mesh's solution: the same iterations), gap (-load_steps 10: /load_steps too), incline (gravity, a tilted plane) and slider (two bodies, a contact pair), every dataset within 1e-12; the incline's tangential/normal force is tan 20 degrees (docs/guide/scenes.md)", full=True)
def pyscene_table_scenes():
    for name, extra in (("shear", []), ("shear", ["-nested_levels", "1"]), ("gap", []), ("incline", []), ("slider", [])):
        tag = name + "".join(extra).replace("-", "_")
        c_h5, py_h5 = out("pyscene_%s_c.h5" % tag), out("pyscene_%s_py.h5" % tag)
        opts = os.path.join("scenes", name + ".opts")
        run(mpiexec(1, CONTACT, "-options_file", opts, *extra, *RTOL, "-o", c_h5))
        text = python_run(mpiexec(1, PYTHON, SCENE_PY, "run", opts, *extra, *RTOL, "-o", py_h5))
        same_files(c_h5, py_h5)
        if name == "gap":
            with h5py.File(py_h5, "r") as f:
                expect(len(f["load_steps/factor"][()]) == 10, "gap: the 10 load steps of /load_steps", text)
        if name == "incline":
            with h5py.File(py_h5, "r") as f:
                force = f["contact/reaction"][()].sum(axis=0)
                normal = f["contact/normal"][0]
                fn = force @ normal
                ratio = np.linalg.norm(force - fn * normal) / fn
            expect(abs(ratio - np.tan(np.radians(20))) < 1e-3, "incline: tangential/normal force %.6f, tan 20 = %.6f" % (ratio, np.tan(np.radians(20))), text)


@test("step cutting from Python (ssstar.Scene's steps(), examples/scene.py run on an options file): the block load path with -snes_max_it 6, whose step t = 2 does not converge, is halved as examples/contact halves it (retried at t 1.5, then on in sub-steps, 4 halvings, then the path stops): the same rows, cuts and reasons, the same file to 1e-12 with failed_step and failed_time, and exit status 2 as examples/contact's")
def pyscene_step_cutting():
    opts = out("pyscene_cut.opts")
    with open(opts, "w") as f:
        f.write("# the block load path, with too few iterations for the step to t = 2\n")
        for name, value in zip(BLOCK[::2], BLOCK[1::2]):
            f.write("%s %s\n" % (name, value))
        f.write("-traction_top %s\n-snes_max_it 6\n" % README_PATH)
    c_h5, py_h5 = out("pyscene_cut_c.h5"), out("pyscene_cut_py.h5")
    run(mpiexec(1, CONTACT, "-options_file", opts, *RTOL, "-o", c_h5), expect_rc=NOT_CONVERGED)
    text = python_run(mpiexec(1, PYTHON, SCENE_PY, "run", opts, *RTOL, "-o", py_h5), expect_rc=NOT_CONVERGED)
    same_files(c_h5, py_h5)
    with h5py.File(py_h5, "r") as f:
        t, cuts, reason = f["steps/time"][()], f["steps/cuts"][()], f["steps/reason"][()]
        expect(t[2] == 1.5 and cuts[2] == 1 and reason[-1] < 0 and cuts[-1] == 4 and f.attrs["failed_step"] == len(t) - 1,
               "times %s, cuts %s, reasons %s, failed_step %s" % (t, cuts, reason, f.attrs.get("failed_step")), text)


# Large sliding (scenes/drag.opts, scenes/track.opts): the drag's press and its first two steps along the slab (the
# first re-linearized), and the track's block pushed back off the rim of the one it slides on (tests/suite_sliding.py)
DRAG_START = ["-steps", "0,1,1.125,1.25"]
OFF_THE_RIM = ["-traction_slider_top", "0:0,0,0;1:0,0,-0.01;2:-1.005,0,-0.01", "-steps", "0,1,1.5,2"]


@test("large sliding from Python (ssstar.Scene solves each step of a path as examples/contact: solved again from its solution, linearized there, while the contact measured there moves, SSStarSceneCheckStep(); the motions of the steps checked first, SSStarSceneCheckSteps()): scenes/track.opts (a contact pair, most steps re-linearized) on 1 rank and the drag of scenes/drag.opts to t 1.25 (a moving ball) on 1 and 2 ranks (2: the whole body) write examples/contact's file within 1e-12 and count its iterations in all (its summary's, more than the rows of /steps add: the re-linearizations); the track pushed off the rim, whose contact does not settle, is cut and stops as examples/contact's (the same file: rows, reason DIVERGED_MAX_IT, failed_step; exit status 2); the drag with -sliding small is refused with examples/contact's message before any solve and file", full=True)
def pyscene_large_sliding():
    cases = (("track", 1, "track.opts", []), ("drag", 1, "drag.opts", DRAG_START), ("drag", 2, "drag.opts", DRAG_START), ("rim", 1, "track.opts", OFF_THE_RIM))
    for name, ranks, opts, extra in cases:
        opts, rc = os.path.join("scenes", opts), NOT_CONVERGED if name == "rim" else 0
        c_h5, py_h5 = out("pyscene_sliding_%s_c_np%d.h5" % (name, ranks)), out("pyscene_sliding_%s_py_np%d.h5" % (name, ranks))
        c_text = run(mpiexec(ranks, CONTACT, "-options_file", opts, *extra, *RTOL, *PATHS[ranks], "-o", c_h5), expect_rc=rc)
        text = python_run(mpiexec(ranks, PYTHON, SCENE_PY, "run", opts, *extra, *RTOL, *PATHS[ranks], "-o", py_h5), expect_rc=rc)
        same_files(c_h5, py_h5)
        c_its, py_its = re.search(r"^summary: .* iterations (\d+) ", c_text, re.M), re.search(r"^iterations (\d+) in all", text, re.M)
        with h5py.File(py_h5, "r") as f:
            rows, reason, cuts = f["steps/iterations"][()], f["steps/reason"][()], f["steps/cuts"][()]
            failed, converged = f.attrs.get("failed_step"), f.attrs["converged_reason"]
        expect(c_its and py_its and int(py_its.group(1)) == int(c_its.group(1)) > rows.sum(),
               "%s on %d ranks: iterations %s in all, examples/contact's %s, the rows' %d" % (name, ranks, py_its and py_its.group(1), c_its and c_its.group(1), rows.sum()), text)
        if name == "rim":
            expect(reason[-1] == -5 and cuts[-1] == 4 and failed == len(rows) - 1 and converged == "DIVERGED_MAX_IT" and (reason[:-1] > 0).all(),
                   "off the rim: reasons %s, cuts %s, failed_step %s, %s" % (reason, cuts, failed, converged), text)
    c_h5, py_h5 = out("pyscene_sliding_small_c.h5"), out("pyscene_sliding_small_py.h5")
    for h5 in (c_h5, py_h5):
        if os.path.exists(h5):
            os.remove(h5)
    c_text = run(mpiexec(1, CONTACT, "-options_file", "scenes/drag.opts", "-sliding", "small", "-o", c_h5), expect_rc=1)
    text = python_run(mpiexec(1, PYTHON, SCENE_PY, "run", "scenes/drag.opts", "-sliding", "small", "-o", py_h5), expect_rc=1)
    m = re.search(r"^\S*examples/contact: (Step \d+ \(t = \S+\): the obstacle of -obstacle_top .* for small sliding)$", c_text, re.M)
    expect(m and "ssstar.Error: " + m.group(1) in text and not os.path.exists(c_h5) and not os.path.exists(py_h5),
           "-sliding small: examples/contact's refusal %s, a file %s" % (m and m.group(1), [h5 for h5 in (c_h5, py_h5) if os.path.exists(h5)]), text)


def onset_code():
    """The lines of examples/scene.py's onset() that docs/guide/python.md shows: the scene and the loop"""
    text = open(SCENE_PY).read()
    body = text[text.index("def onset("):text.index("\n\n\n", text.index("def onset("))].split("\n")
    first = next(i for i, line in enumerate(body) if "scene = ssstar.Scene(" in line)
    last = next(i for i, line in enumerate(body) if "dQ /= 2" in line)
    # the guide names the mesh from the source tree, the example from its own place (it runs from any directory)
    lines = [re.sub(r'os\.path\.join\(ROOT, "meshes", "([^"]+)"\)', r'"meshes/\1"', line) for line in body[first:last + 1]]
    return [line.split("#")[0].strip() for line in lines if line.strip() and not line.strip().startswith(("if out", "scene.write"))]


@test("a load path decided by a Python loop (examples/scene.py onset, the example of docs/guide/python.md: the shear raised step by step, a tentative step (step(t, accept=False)) that makes more than 8 nodes begin to slide refused and halved, accept() otherwise, set() the next load): no accepted step starts more than 8 nodes sliding, no node sticks at its end, below phi P = 5; on 1 and 2 ranks (2: the whole body), examples/contact replaying the path it chose (-traction_top t:t,0,-10;... -steps t0,t1,...) writes the same file to 1e-12 (check_solution.py judges both alike, and passes every step); docs/guide/python.md holds the loop's code", full=True)
def pyscene_user_loop():
    for ranks in (1, 2):
        py_h5, c_h5 = out("pyscene_onset_py_np%d.h5" % ranks), out("pyscene_onset_c_np%d.h5" % ranks)
        text = python_run(mpiexec(ranks, PYTHON, SCENE_PY, "onset", "--out", py_h5, *RTOL, *PATHS[ranks]))
        m = re.search(r"no node sticks from Q = (\S+) on", text)
        expect(m is not None and 4 < float(m.group(1)) < 5, "%d ranks: the shear at which no node sticks" % ranks, text)
        with h5py.File(py_h5, "r") as f:
            times = f["steps/time"][()]
            states = [f["steps/%d/contact/state" % k][()] for k in range(len(times))]
            expect(f["steps/sticking"][-1] == 0 and times[-1] == float(m.group(1)), "%d ranks: the last step: %d sticking, t %g" % (ranks, f["steps/sticking"][-1], times[-1]), text)
        sliding = [np.isin(s, (1, 2)) for s in states]
        new = [int((sliding[k] & ~sliding[k - 1]).sum()) for k in range(1, len(sliding))]
        expect(max(new) <= 8 and np.all(np.diff(times) > 0), "%d ranks: new sliding nodes per step %s, times %s" % (ranks, new, times), text)
        history = ";".join("%r:%r,0,-10" % (float(t), float(t)) for t in times)
        run(mpiexec(ranks, CONTACT, *BLOCK, "-traction_top", history, "-steps", ",".join(repr(float(t)) for t in times), *RTOL, *PATHS[ranks], "-o", c_h5))
        same_files(c_h5, py_h5)
        same_law(c_h5, py_h5)
        law = run(CHECK + ["coulomb", "--steps", py_h5])
        expect("VIOLATED" not in law, "%d ranks: the law at some step" % ranks, law)
    guide = open(os.path.join(ROOT, "docs", "guide", "python.md")).read()
    missing = [line for line in onset_code() if line not in guide]
    expect(not missing, "docs/guide/python.md does not show these lines of examples/scene.py's onset(): %s" % missing)


@test("ssstar.Scene's contract (tests/python_scene_check.py) on 1 and 2 ranks: each Step's arrays and row equal the file's datasets bit for bit; keywords override the options file; a misspelt keyword raises ssstar.Error (a PETSc.Error, code 95) naming the nearest option, a bad value the library's message, a missing options file on every rank; two scenes used in turn give what each gives alone and leave petsc4py's database as it was; a tentative step leaves no trace; set(), write() and accept() refuse what they cannot do; a scene per rank on PETSC_COMM_SELF; help(ssstar.Scene) documents solve, steps, step, set, write, close")
def pyscene_contract():
    for ranks in (1, 2):
        env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
        env.pop("SSSTAR_LIB", None)
        p = subprocess.run(mpiexec(ranks, PYTHON, SCENE_CHECK, OUT), cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
        expect(p.returncode == 0 and "test_scene: ok" in p.stdout, "%d ranks: exit status %d" % (ranks, p.returncode), p.stdout)


@test("installation as Python users expect: pip install --no-build-isolation ./python into a venv (with Debian's petsc4py through --system-site-packages) installs the module with the library copied beside it; from another folder the venv's python imports it, its version is include/ssstar.h's, its library the copy, and a scene solves; a module whose recorded version differs from its library's refuses to import; make install PREFIX=... installs the scenes too (python_scene_check.py passes with that module alone)")
def pyscene_install():
    venv = out("pyscene_venv")
    shutil.rmtree(venv, ignore_errors=True)
    run([PYTHON, "-m", "venv", "--system-site-packages", venv])
    pip = run([os.path.join(venv, "bin", "pip"), "install", "--no-build-isolation", "-q", os.path.join(ROOT, "python")], timeout=300)
    elsewhere = out("pyscene_elsewhere")
    os.makedirs(elsewhere, exist_ok=True)
    header = open(os.path.join(ROOT, "include", "ssstar.h")).read()
    version = ".".join(re.search(r"#define SSSTAR_VERSION_%s (\d+)" % k, header).group(1) for k in ("MAJOR", "MINOR", "SUBMINOR"))
    probe = ("import ssstar, os\nprint('version', ssstar.__version__, ssstar.library)\n"
             "s = ssstar.Scene(geo=%r, level=1, E=2e8, nu=0.3, spring={'top': 1000}, contact=['bottom'], traction={'top': (1, 0, -10)})\n"
             "print('solved', s.solve().converged)\ns.close()\n" % os.path.join(ROOT, "meshes", "block.geo"))
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    env.pop("SSSTAR_LIB", None)
    p = subprocess.run([os.path.join(venv, "bin", "python"), "-c", probe], cwd=elsewhere, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
    m = re.search(r"version (\S+) (\S+)", p.stdout)
    expect(p.returncode == 0 and m and m.group(1) == version and m.group(2).startswith(venv) and "solved True" in p.stdout,
           "the installed module (version %s expected, its library in %s)" % (version, venv), pip + p.stdout)
    site = os.path.dirname(os.path.dirname(m.group(2)))
    stale = out("pyscene_stale")
    shutil.rmtree(stale, ignore_errors=True)
    # without the compiled modules: the edit below keeps _config.py's size and may keep its mtime's second, and Python
    # would then import the stale __pycache__ of the true version
    shutil.copytree(os.path.join(site, "ssstar"), os.path.join(stale, "ssstar"), ignore=shutil.ignore_patterns("__pycache__"))
    config = os.path.join(stale, "ssstar", "_config.py")
    text = open(config).read()
    open(config, "w").write(text.replace('VERSION = "%s"' % version, 'VERSION = "0.0.1"'))
    p = subprocess.run([PYTHON, "-c", "import ssstar"], cwd=elsewhere, env=dict(env, PYTHONPATH=stale), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=60)
    expect(p.returncode != 0 and "the library" in p.stdout and "is version %s" % version in p.stdout, "a module of another version imported", p.stdout)
    prefix = out("pyscene_prefix")
    shutil.rmtree(prefix, ignore_errors=True)
    run(["make", "-s", "install", "PREFIX=" + prefix])
    installed = os.path.join(prefix, "lib", "python3", "dist-packages")
    p = subprocess.run(mpiexec(2, PYTHON, SCENE_CHECK, OUT), cwd=elsewhere, env=dict(env, PYTHONPATH=installed), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    expect(p.returncode == 0 and "test_scene: ok" in p.stdout and os.path.join(prefix, "lib", "libssstar.so") in p.stdout, "the make-installed module's scenes", p.stdout)
