"""What a scripted user can rely on (docs/guide/scripting.md): every example refuses an option that
nothing reads, before any work, naming the nearest known one; a solve that did not converge exits with
NOT_CONVERGED (2) and its file says so; one option owns each parameter; the documented defaults are the code's; the
pictures carry a scale for the slip and keep their legends off the labels; ssstar's error message comes first."""
import os
import re
import shutil
import subprocess

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, prism, paths, NOT_CONVERGED)

CONTACT = os.path.join(ROOT, "examples", "contact")
GENERIC = os.path.join(ROOT, "examples", "generic")
FCLIB = os.path.join(ROOT, "examples", "fclib")
FCLIB_SLOW = os.path.join(ROOT, "tests", "data", "fclib", "LMGC_GFC3D-i00501-4-00000.hdf5")  # 3 iterations
INCLINE = ["-options_file", os.path.join(ROOT, "scenes", "incline.opts")]
PETSC_USER_INPUT = 95  # PETSC_ERR_USER_INPUT: the exit status of an unknown option


def out(name):
    return os.path.join(OUT, name)


def fresh(name):
    for path in (out(name), out(name.rsplit(".", 1)[0] + ".xmf")):
        if os.path.exists(path):
            os.remove(path)
    return out(name)


def outcome(path):
    """The attributes of "/" that say how the solve ended"""
    with h5py.File(path, "r") as f:
        a = f.attrs
        reason = a["converged_reason"]
        return (reason.decode() if isinstance(reason, bytes) else str(reason)), float(a["residual_norm"]), int(a["iterations"])


def refused(cmd, option, nearest):
    """cmd is refused naming option and nearest, with PETSC_ERR_USER_INPUT, ssstar's line first and only once"""
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    text = "%s (nearest known option: %s)" % (option, nearest)
    expect(p.returncode == PETSC_USER_INPUT, "exit status %d, not %d, from %s" % (p.returncode, PETSC_USER_INPUT, " ".join(cmd)), p.stdout)
    lines = p.stdout.splitlines()
    expect(len(lines) > 0 and re.match(r"\S+: Unknown options? .*" + re.escape(text), lines[0]) is not None,
           "the first line does not name %s and %s: %s" % (option, nearest, lines[:1]), p.stdout)
    expect(sum(1 for l in lines if "nothing was done" in l and "PETSC ERROR" not in l) == 1, "ssstar's line is not printed once", p.stdout)
    expect("summary" not in p.stdout and "SNES Function norm" not in p.stdout, "work was done before the refusal", p.stdout)
    return p.stdout


@test("a misspelled or unknown option is refused before any work, with PETSc's error code for bad input (95), naming it "
      "and the nearest known option (edit distance; a group option by its group): examples/prism -levle 8 (-level; no mesh "
      "made), -friction and -reduction (removed: -snes_ssstar_friction, -snes_ssstar_reduction), -snes_monitr (a PETSc "
      "option), 2 ranks; examples/contact -frction_bottom 0.9 (-friction_bottom; no file written); examples/generic "
      "-da_grd_x (-da_grid_x); examples/fclib -snes_ssstar_frction (-snes_ssstar_friction)")
def options_unknown_refused():
    geo = out("outcomes_fresh.geo")
    shutil.copy(os.path.join(ROOT, "meshes", "prism.geo"), geo)
    msh = mesh_of(geo, 2)
    if os.path.exists(msh):
        os.remove(msh)
    refused(mpiexec(1, PRISM, "-geo", geo, "-level", "2", "-levle", "8"), "-levle", "-level")
    expect(not os.path.exists(msh), "examples/prism meshed the geometry before refusing -levle")
    text = refused(mpiexec(1, PRISM, "-level", "2", "-friction", "0.4", "-reduction", "mumps", "-snes_monitr"), "-friction", "-snes_ssstar_friction")
    expect("-reduction (nearest known option: -snes_ssstar_reduction)" in text and "-snes_monitr (nearest known option: -snes_monitor)" in text,
           "not every unknown option is named with its nearest", text)
    refused(mpiexec(2, PRISM, "-level", "2", "-levle", "8"), "-levle", "-level")
    h5 = fresh("outcomes_refused.h5")
    refused(mpiexec(1, CONTACT, *INCLINE, "-frction_bottom", "0.9", "-o", h5), "-frction_bottom", "-friction_bottom")
    expect(not os.path.exists(h5), "examples/contact wrote a file while refusing an option")
    refused(mpiexec(1, GENERIC, "-snes_type", "ssstar", "-da_grd_x", "5"), "-da_grd_x", "-da_grid_x")
    refused(mpiexec(1, FCLIB, FCLIB_SLOW, "-snes_ssstar_frction", "0.4"), "-snes_ssstar_frction", "-snes_ssstar_friction")


@test("options that PETSc reads only during the work, after the solve or at PetscFinalize() are not refused: -snes_view, "
      "-snes_converged_reason, -log_view, -options_left, -ksp_view, MUMPS's (-schur_direct_mumps_icntl_14, "
      "-mat_mumps_icntl_14), the Newton step's GMRES (-snes_ssstar_newton_ksp_*), the elastic start's solver "
      "(-initial_*), the whole body's KSP and GAMG, -help; on all four examples")
def options_late_accepted():
    late = ["-snes_view", "-snes_converged_reason", "-log_view", "-options_left", "-ksp_view"]
    out_ = run(mpiexec(1, PRISM, "-level", "2", *late, "-snes_ssstar_newton_ksp_max_it", "50", "-schur_direct_mumps_icntl_14", "40",
                       "-initial_guess", "elastic", "-initial_ksp_type", "preonly", "-initial_pc_factor_mat_solver_type", "mumps",
                       "-initial_mat_mumps_icntl_14", "30", "-mat_mumps_icntl_14", "30"))
    expect("CONVERGED_FNORM_RELATIVE" in out_, "the prism did not converge", out_)
    out_ = run(mpiexec(2, PRISM, "-level", "2", "-snes_ssstar_reduction", "none", "-ksp_rtol", "1e-8", "-pc_gamg_threshold", "0.01",
                       "-ksp_converged_reason", "-snes_view"))
    expect("CONVERGED_FNORM_RELATIVE" in out_, "the prism (whole body) did not converge", out_)
    out_ = run(mpiexec(1, CONTACT, *INCLINE, *late, "-snes_ssstar_monitor_states"))
    expect("CONVERGED_FNORM_RELATIVE" in out_, "the incline did not converge", out_)
    run(mpiexec(1, GENERIC, "-snes_type", "ssstar", "-da_grid_x", "7", *late))
    run(mpiexec(1, FCLIB, FCLIB_SLOW, *late))
    for cmd in ([PRISM, "-level", "2", "-help"], [CONTACT, *INCLINE, "-help"], [GENERIC, "-help"], [FCLIB, "-help"]):
        run(mpiexec(1, *cmd))


@test("one exit rule for every example: a solve that did not converge exits with 2 and the file it writes says so (the "
      "attributes converged_reason, residual_norm and iterations of \"/\"), a converged one exits 0 with the same "
      "attributes; prism -snes_max_it 3 (and no -save_reduced file), contact (incline, -load_steps 2: stops at the first "
      "step), fclib, generic; bad input exits with PETSc's error code, never 2")
def exit_status_and_file():
    h5, binary = fresh("outcomes_prism_maxit.h5"), fresh("outcomes_prism_maxit.bin")
    text, s = prism(3, extra=["-snes_max_it", "3", "-save_reduced", binary], h5="outcomes_prism_maxit.h5", expect_rc=NOT_CONVERGED)
    expect(s["reason"] == "DIVERGED_MAX_IT" and "The solve did not converge (DIVERGED_MAX_IT): exit status 2" in text, "prism: %s" % s["reason"], text)
    reason, norm, its = outcome(h5)
    expect(reason == "DIVERGED_MAX_IT" and its == 3 and 0 < norm < np.inf, "prism file: %s, ||z|| %g, %d iterations" % (reason, norm, its))
    expect(not os.path.exists(binary), "prism wrote -save_reduced after a solve that did not converge")
    text, s = prism(3, extra=["-save_reduced", binary], h5="outcomes_prism.h5")
    reason, norm, its = outcome(out("outcomes_prism.h5"))
    expect(reason == "CONVERGED_FNORM_RELATIVE" and its == s["iters"] and norm < 1e-12, "prism file: %s, ||z|| %g, %d iterations" % (reason, norm, its))
    expect(os.path.exists(binary), "prism did not write -save_reduced after a converged solve")

    h5 = fresh("outcomes_incline_maxit.h5")
    text = run(mpiexec(1, CONTACT, *INCLINE, "-snes_max_it", "2", "-load_steps", "2", "-o", h5), expect_rc=NOT_CONVERGED)
    reason, norm, its = outcome(h5)
    expect(reason == "DIVERGED_MAX_IT" and its == 2 and norm > 0, "contact file: %s, ||z|| %g, %d iterations" % (reason, norm, its), text)
    with h5py.File(h5, "r") as f:
        expect(len(f["load_steps/factor"][:]) == 1, "contact: the load steps after the failed one were solved", text)
    h5 = fresh("outcomes_incline.h5")
    run(mpiexec(1, CONTACT, *INCLINE, "-o", h5))
    expect(outcome(h5)[0] == "CONVERGED_FNORM_RELATIVE", "contact file: %s" % outcome(h5)[0])

    h5 = fresh("outcomes_fclib_maxit.h5")
    text = run(mpiexec(1, FCLIB, FCLIB_SLOW, "-snes_max_it", "1", "-o", h5), expect_rc=NOT_CONVERGED)
    reason, norm, its = outcome(h5)
    expect(reason == "DIVERGED_MAX_IT" and its == 1 and norm > 0, "fclib file: %s, ||z|| %g, %d iterations" % (reason, norm, its), text)
    h5 = fresh("outcomes_fclib.h5")
    run(mpiexec(2, FCLIB, FCLIB_SLOW, "-o", h5))
    expect(outcome(h5)[0] == "CONVERGED_FNORM_RELATIVE", "fclib file: %s" % outcome(h5)[0])

    h5 = fresh("outcomes_generic_maxit.h5")
    text = run(mpiexec(2, GENERIC, "-snes_type", "ssstar", "-snes_max_it", "1", "-o", h5), expect_rc=NOT_CONVERGED)
    reason, norm, its = outcome(h5)
    expect(reason == "DIVERGED_MAX_IT" and its == 1 and norm > 0, "generic file: %s, ||z|| %g, %d iterations" % (reason, norm, its), text)
    h5 = fresh("outcomes_generic.h5")
    run(mpiexec(1, GENERIC, "-snes_type", "ssstar", "-o", h5))
    expect(outcome(h5)[0] == "CONVERGED_FNORM_RELATIVE", "generic file: %s" % outcome(h5)[0])

    for cmd in ([PRISM, "-level", "0"], [CONTACT, *INCLINE, "-E", "0"], [GENERIC, "-nu", "0.5"], [FCLIB, os.path.join(OUT, "no_such.hdf5")]):
        p = subprocess.run(mpiexec(1, *cmd), cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
        expect(p.returncode not in (0, NOT_CONVERGED), "bad input %s: exit status %d" % (" ".join(cmd[1:]), p.returncode), p.stdout)


TWO_GROUPS = ["-level", "2", "-E", "2.1e5", "-nu", "0.3", "-traction_top", "4,0,-10", "-spring_top", "1000", "-contact", "left,right",
              "-friction_left", "0.5"]


@test("a contact group without -friction_<G> takes the solver's -snes_ssstar_friction (0.7), whenever it is read: two "
      "groups (tests/data/two_bottoms.geo), the same solution and states as with -friction_right 0.7, and not those of "
      "the old default 0.3")
def friction_default_reaches_groups():
    geo = out("two_bottoms.geo")
    shutil.copy(os.path.join(ROOT, "tests", "data", "two_bottoms.geo"), geo)
    runs = {}
    for name, options in (("solver", ["-snes_ssstar_friction", "0.7"]), ("group", ["-friction_right", "0.7"]), ("old", ["-friction_right", "0.3"])):
        h5 = fresh("two_groups_%s.h5" % name)
        runs[name] = run(mpiexec(1, CONTACT, "-geo", geo, *TWO_GROUPS, *options, "-o", h5))
    right = {k: re.search(r"^contact group right: (.*);", v, re.M).group(1) for k, v in runs.items()}
    expect(right["solver"] == right["group"], "-snes_ssstar_friction 0.7: %s; -friction_right 0.7: %s" % (right["solver"], right["group"]), runs["solver"])
    expect(right["solver"] != right["old"], "the test does not tell 0.7 from 0.3: %s" % right["old"])
    run(CHECK + ["compare", out("two_groups_solver.h5"), out("two_groups_group.h5"), "--tol", "1e-12"])
    with h5py.File(out("two_groups_solver.h5"), "r") as f:  # the coefficients the solver used, per node
        phi, group = f["contact/friction"][:], f["contact/group"][:]
    expect(np.all(phi[group == 1] == 0.7) and np.all(phi[group == 0] == 0.5), "the file's coefficients: left %s, right %s" % (set(phi[group == 0]), set(phi[group == 1])))
    expect("phi of the solver (-snes_ssstar_friction)" in runs["solver"], "the scene does not say that right takes the solver's coefficient", runs["solver"])


HELP_DEFAULT = re.compile(r"^\s*-snes_ssstar_(\w+)(?::)? <(?:now )?([^:>]+?) : (?:formerly )?([^>]+?)>", re.M)


def normalize(value):
    value = value.strip().rstrip(".").lower()
    if "/" in value:
        a, b = value.split("/", 1)
        try:
            return float(a) / float(b)
        except ValueError:
            return value
    try:
        return float(value)
    except ValueError:
        return {"petsc_true": "true", "petsc_false": "false"}.get(value, value)


@test("the documented defaults of every -snes_ssstar_* option (docs/manual.md: '<default>' of the option lines and "
      "'default V' of a setter's page; the solver's rows of the option table docs/options.md) are those -help prints")
def docs_defaults_match_help():
    text = run(mpiexec(1, GENERIC, "-snes_type", "ssstar", "-help"))
    defaults = {name: normalize(default) for name, _, default in HELP_DEFAULT.findall(text)}
    expect(len(defaults) >= 15 and "lu_reuse" in defaults and "friction" in defaults, "-help lists %d -snes_ssstar_* options" % len(defaults), text)
    manual = open(os.path.join(ROOT, "docs", "manual.md")).read()
    checked = []
    for name, value in re.findall(r"-snes_ssstar_(\w+) <([^>]+)>", manual):
        v = normalize(value)
        if name not in defaults or (isinstance(v, str) and (v not in ("true", "false") and not re.fullmatch(r"[a-z]+", v) or v in ("fraction", "phi", "gamma", "tau", "n", "rtol", "gb"))):
            continue  # a placeholder (<fraction>, <direct,mumps,...>), not a default
        expect(v == defaults[name], "docs/manual.md: -snes_ssstar_%s <%s>, -help: %s" % (name, value, defaults[name]))
        checked.append(name)
    for page in re.split(r"^### ", manual, flags=re.M)[1:]:
        options = set(re.findall(r"^[.+-]\s+-snes_ssstar_(\w+)", page, re.M))
        if len(options) != 1:
            continue
        name = options.pop()
        for value in re.findall(r"[Dd]efault:? ([-\w.+/]+)", page) + re.findall(r"([-\w.+/]+) \(the default\)", page):
            v = normalize(value.rstrip(":;,)"))
            if name in defaults and not (isinstance(v, str) and v not in defaults.values()):
                expect(v == defaults[name], "docs/manual.md, page %s: default %s of -snes_ssstar_%s, -help: %s" % (page.split()[0], value, name, defaults[name]))
                checked.append(name + " (page)")
    table = open(os.path.join(ROOT, "docs", "options.md")).read()  # the solver's rows (generated from -help: make docs)
    for name, value, where in re.findall(r"^\| `-snes_ssstar_(\w+)` \| `([^`]*)`[^|]* \| (\w+) \|", table, re.M):
        if name in defaults and where == "solver":
            v = normalize(value)
            expect(v == defaults[name], "docs/options.md: -snes_ssstar_%s default %s, -help: %s (make docs)" % (name, value, defaults[name]))
            checked.append(name + " (options)")
    for name in ("friction", "reduction", "lu_reuse", "pc_reuse", "ksp_rtol_max", "ksp_floor", "damping_min"):
        expect(name in checked and name + " (options)" in checked, "the default of -snes_ssstar_%s is not checked (%s)" % (name, checked))
    expect("lu_reuse (page)" in checked, "the page of SNESSSStarSetLUReuse states no default", manual)


@test("-snes_view shows no solver that did not run: with a dense P (the prism's direct reduction) no KSP or PC block; on "
      "the whole body the KSP and PC that solved the Newton steps, set up")
def snes_view_without_unused_solver():
    text = run(mpiexec(1, PRISM, "-level", "2", "-snes_view"))
    expect("type: ssstar" in text and "KSP Object" not in text and "PC Object" not in text, "a KSP or PC block in the dense route's -snes_view", text)
    text = run(mpiexec(1, PRISM, "-level", "2", "-snes_ssstar_reduction", "none", "-snes_view"))
    expect("KSP Object" in text and "PC Object" in text and "not been set up" not in text and "not yet setup" not in text,
           "the whole body's -snes_view does not show its solver, set up", text)


@test("an error prints ssstar's message first, on one line with the program's name, before PETSc's report, once on 2 ranks "
      "(bad input: -E 0 on examples/prism and examples/contact)")
def error_message_first():
    for cmd in (mpiexec(2, PRISM, "-level", "2", "-E", "0"), mpiexec(1, CONTACT, *INCLINE, "-E", "0")):
        p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
        lines = p.stdout.splitlines()
        first = next((i for i, l in enumerate(lines) if "PETSC ERROR" in l), len(lines))
        ours = [i for i, l in enumerate(lines) if re.match(r"\S+: -E 0\.?: Young's modulus must be a positive number", l)]
        expect(p.returncode not in (0, NOT_CONVERGED) and len(ours) == 1 and ours[0] < first,
               "ssstar's message is not the first line of the error, once (%s)" % ours, p.stdout)


@test("examples/plot_contact.py: the slip arrows share one scale with a key (a round length at most the largest slip, "
      "named in the legend: the incline's micro-slip of 7e-6 reads as such), no legend or key over a label, title, tick "
      "label or another panel, everything inside the picture; two groups and load steps too")
def plot_slip_key_and_layout():
    import importlib.util
    import matplotlib
    matplotlib.use("Agg")
    from matplotlib.quiver import QuiverKey
    spec = importlib.util.spec_from_file_location("plot_contact", os.path.join(ROOT, "examples", "plot_contact.py"))
    plot = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(plot)
    geo = out("two_bottoms.geo")
    shutil.copy(os.path.join(ROOT, "tests", "data", "two_bottoms.geo"), geo)
    scenes = {"outcomes_plot_incline.h5": INCLINE, "outcomes_plot_two_groups.h5": ["-geo", geo] + TWO_GROUPS,
              "outcomes_plot_gap.h5": ["-options_file", os.path.join(ROOT, "scenes", "gap.opts")]}
    for name, args in scenes.items():
        run(mpiexec(1, CONTACT, *args, "-o", fresh(name)))
        d = plot.read(out(name))
        fig = plot.draw(d)
        renderer = fig.canvas.get_renderer()
        fig.canvas.draw()
        state_axes = [ax for ax in fig.axes if "contact states" in ax.get_title()]
        expect(len(state_axes) == len(set(d["group"].tolist())), "%s: %d state panels" % (name, len(state_axes)))
        for ax, key in zip(state_axes, fig.keys):
            largest = float(re.search(r"largest ([0-9.e+-]+)", ax.get_title()).group(1))
            keys = [a for a in ax.get_children() if isinstance(a, QuiverKey)]
            legend = ax.get_legend()
            expect(len(keys) == 1 and abs(keys[0].U - key) <= 1e-12 * key and 0.1 * largest <= key <= largest * 1.01,
                   "%s: key %s for the largest slip %g" % (name, [k.U for k in keys], largest))
            expect(legend is not None and any(("key: a slip of %.0e" % key) in t.get_text() for t in legend.get_texts()),
                   "%s: the legend does not name the key's length" % name)
            q = keys[0].Q
            per_data = ax.transData.transform((1, 0))[0] - ax.transData.transform((0, 0))[0]
            arrow = keys[0].U / q.scale * per_data
            room = legend.get_window_extent(renderer)
            expect(0 < arrow < room.width, "%s: the key arrow (%.0f px) is not inside its legend" % (name, arrow))
        texts = []  # everything that must not be covered
        for ax in fig.axes:
            for t in [ax.title, ax.xaxis.label, ax.yaxis.label] + ax.get_xticklabels() + ax.get_yticklabels():
                if t.get_text() and t.get_visible():
                    texts.append((t.get_text(), t.get_window_extent(renderer)))
        legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
        figure = fig.bbox
        for lg in legends:
            box = lg.get_window_extent(renderer)
            expect(box.x0 >= figure.x0 - 1 and box.y0 >= figure.y0 - 1 and box.x1 <= figure.x1 + 1 and box.y1 <= figure.y1 + 1,
                   "%s: a legend outside the picture" % name)
            for label, tb in texts:
                expect(not box.overlaps(tb), "%s: a legend covers '%s'" % (name, label))
            for ax in fig.axes:
                expect(not box.overlaps(ax.get_window_extent(renderer)), "%s: a legend covers a panel" % name)
        run([PYTHON, os.path.join(ROOT, "examples", "plot_contact.py"), out(name), "-o", out(name.replace(".h5", ".png"))])
        expect(os.path.getsize(out(name.replace(".h5", ".png"))) > 10000, "%s: no picture" % name)


@test("the memory refusal before the mesh says what it counted (the whole run's peak per rank: mesh, assembly and the "
      "solve on the whole body; what the ranks would add against MemAvailable), not 'dense contact matrices 0 GB' (examples/prism -level 400)")
def memory_refusal_wording():
    text = run(mpiexec(1, PRISM, "-level", "400"), expect_rc=1)
    expect("GB per rank at the peak of the run (mesh, assembly and the solve on the whole body" in text and "the 1 rank would add" in text and " 0 GB" not in text
           and "refused before the work" in text, "the refusal of -level 400 does not say what it counted", text)


BAD_INPUT = [([PRISM, "-level", "0"], "-level 0: the mesh level must be >= 1"),
             ([CONTACT, *INCLINE, "-E", "0"], "Young's modulus must be a positive number"),
             ([GENERIC, "-nu", "0.5"], "-nu 0.5: need E > 0 and -1 < nu < 0.5"),
             ([FCLIB, os.path.join(OUT, "no_such.hdf5")], "no_such.hdf5")]


@test("an error a driver reports is one line, the program's name and ssstar's message naming the option or file, and "
      "the exit status (PETSc's error code): bad input on examples/prism, contact, generic and fclib run as plain "
      "commands, no PETSc report (no 'PETSC ERROR', no 'Configure options' line)")
def error_one_line():
    for cmd, message in BAD_INPUT:
        p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
        lines = p.stdout.splitlines()
        name = cmd[0]  # the program's name as it was run
        expect(p.returncode not in (0, NOT_CONVERGED), "%s: exit status %d" % (name, p.returncode), p.stdout)
        expect(len(lines) == 1 and lines[0].startswith(name + ": ") and message in lines[0],
               "%s: not the one line '%s: ... %s'" % (name, name, message), p.stdout)
        expect("Configure options" not in p.stdout and "PETSC ERROR" not in p.stdout, "%s: PETSc's report without asking" % name, p.stdout)


@test("a debugging option brings PETSc's report back after ssstar's line: -ssstar_traceback (the calls, the "
      "configure line) on examples/prism and examples/contact; -ssstar_traceback is listed by -help")
def error_traceback_on_request():
    for cmd, message in BAD_INPUT[:2]:
        p = subprocess.run(cmd + ["-ssstar_traceback"], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
        lines = p.stdout.splitlines()
        expect(p.returncode not in (0, NOT_CONVERGED) and len(lines) > 10 and message in lines[0], "no report after the line", p.stdout)
        expect("Configure options" in p.stdout and re.search(r"PETSC ERROR: #\d+ main\(\)", p.stdout) is not None, "no calls or configure line", p.stdout)


@test("-help lists the program's, the scene's and the solver's options and exits 0 without any work: on examples/prism, "
      "contact (without a scene), generic and fclib (without a file) each lists -snes_ssstar_friction and an option of "
      "its own, meshes nothing (a fresh .geo stays unmeshed) and writes no -o file")
def help_without_work():
    geo = out("outcomes_help.geo")
    shutil.copy(os.path.join(ROOT, "meshes", "prism.geo"), geo)
    msh = mesh_of(geo, 2)
    own = {"prism": "-initial_guess", "contact": "-obstacle_<G>", "generic": "-obstacle_normal", "fclib": "-summary_header"}
    work = {"prism": "level ranks  nodes", "contact": "summary: nodes", "generic": " iterations\n", "fclib": "FCLib-error"}  # what a solve prints
    args = {"prism": ["-geo", geo, "-level", "2"], "contact": [], "generic": [], "fclib": []}
    for program, option in own.items():
        if os.path.exists(msh):
            os.remove(msh)
        h5 = fresh("outcomes_help_%s.h5" % program)
        p = subprocess.run(mpiexec(1, os.path.join(ROOT, "examples", program), "-help", *args[program], "-o", h5), cwd=ROOT,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
        expect(p.returncode == 0, "examples/%s -help: exit status %d" % (program, p.returncode), p.stdout)
        expect(re.search(r"^\s*-snes_ssstar_friction <", p.stdout, re.M) is not None and option in p.stdout and "-ssstar_traceback" in p.stdout,
               "examples/%s -help does not list -snes_ssstar_friction, %s and -ssstar_traceback" % (program, option), p.stdout)
        expect(program != "contact" or "-obstacle_<G>" in p.stdout and "-contact_pair_<G>" in p.stdout, "examples/contact -help: no scene options", p.stdout)
        expect(not os.path.exists(h5) and not os.path.exists(msh), "examples/%s -help wrote a file or meshed" % program)
        expect(work[program] not in p.stdout and "SNES Function norm" not in p.stdout, "examples/%s -help solved" % program, p.stdout)


@test("an error raised on one rank only ends every rank within seconds, with the message and a non-zero exit status: "
      "examples/fclib on 2 ranks writes -o on rank 0 alone, and -o names a folder (rank 1 has finished and waits); "
      "run under a timeout, so a hang fails")
def error_on_one_rank_ends_all():
    import time
    folder = out("outcomes_a_folder.h5")
    os.makedirs(folder, exist_ok=True)
    t0 = time.time()
    p = subprocess.run(["timeout", "60"] + mpiexec(2, FCLIB, FCLIB_SLOW, "-o", folder), cwd=ROOT, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=120)
    elapsed = time.time() - t0
    expect(p.returncode not in (0, NOT_CONVERGED, 124), "exit status %d (124: the timeout ended a hang)" % p.returncode, p.stdout)
    expect(elapsed < 30, "the ranks ended after %.0f s" % elapsed, p.stdout)
    expect(re.search(r"^\S*fclib, rank 0: Cannot create the HDF5 file .*outcomes_a_folder\.h5", p.stdout, re.M) is not None,
           "no one-line message of rank 0 naming the file", p.stdout)
