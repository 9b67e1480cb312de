"""Scenes through examples/contact: each reduction against another solver, the known answers of the shipped scenes,
the effects a scene names and no others, and bad input refused before any work (examples/contact and examples/prism)."""
import os
import re

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)
import scene_answers

CONTACT = os.path.join(ROOT, "examples", "contact")
TEST_SCENES = os.path.join(ROOT, "tests", "test_scenes")
PLOT = [PYTHON, os.path.join(ROOT, "examples", "plot_contact.py")]


def scene(name):
    return ["-options_file", os.path.join(ROOT, "scenes", name + ".opts")]


SCENE_SUMMARY = re.compile(r"summary: nodes (\d+) contact (\d+) .* iterations (\d+) states L/M1/M2/M3\+/M3-/M4/LS ([\d/]+) (\S+)")


def contact_run(args, h5=None, ranks=1, expect_rc=0):
    """Runs examples/contact; returns (output, summary fields)"""
    cmd = mpiexec(ranks, CONTACT, *args)
    if h5:
        cmd += ["-o", os.path.join(OUT, h5)]
    out = run(cmd, expect_rc=expect_rc)
    if expect_rc:
        return out, None
    m = SCENE_SUMMARY.search(out)
    expect(m is not None, "no summary line", out)
    return out, {"nodes": int(m.group(1)), "contact": int(m.group(2)), "iters": int(m.group(3)),
                 "states": [int(s) for s in m.group(4).split("/")], "reason": m.group(5)}


def field(h5):
    f = h5py.File(os.path.join(OUT, h5), "r")
    return f["geometry/vertices"][:], f["fields/displacement"][:]


# ---- each reduction against another solver ----------------------------------------------------------------------

@test("the prism scene file through examples/contact gives examples/prism's solution (level 3: states 14/55/15, contact face and whole mesh to 1e-12)")
def scene_prism_equals_prism():
    _, s = contact_run(scene("prism") + ["-level", "3"], h5="scene_prism_L3.h5")
    expect(s["states"][:6] == [14, 55, 0, 15, 0, 0], "states %s" % s["states"])
    prism(3, h5="prism_L3.h5")
    run(CHECK + ["compare", os.path.join(OUT, "scene_prism_L3.h5"), os.path.join(OUT, "prism_L3.h5"), "--tol", "1e-12"])


@test("frictionless contact (hertz level 1, non-uniform gaps) equals PETSc's SNESVINEWTONRSLS on the same reduced problem P, f with bounds u_n >= -gap, to 1e-10")
def scene_frictionless_is_vi():
    out = run([TEST_SCENES, "-check", "vi", "-tol", "1e-10"] + scene("hertz") + ["-level", "1"])
    expect("SNESVINEWTONRSLS" in out, "no comparison printed", out)


@test("Tresca with the slip bound of each node set to phi r_n of the Coulomb solution reproduces the Coulomb solution: prism level 3 to 1e-10, and the tilted incline (local frames, gravity, a soft spring: condition ~1e4) at level 2 to 1e-8")
def scene_tresca_reproduces_coulomb():
    run([TEST_SCENES, "-check", "tresca", "-tol", "1e-10"] + scene("prism") + ["-level", "3"])
    run([TEST_SCENES, "-check", "tresca", "-tol", "1e-8", "-phi", "0.5"] + scene("incline") + ["-level", "2"])


@test("without a contact group the driver does one linear solve (SNES ksponly, Cholesky, no ssstar) and gets the exact P1 answer of a bar in tension with nu = 0: u_x = T x / E, u_y = u_z = 0 (1e-10)")
def scene_no_contact_is_one_linear_solve():
    out, s = contact_run(["-geo", os.path.join(ROOT, "meshes", "prism.geo"), "-level", "2", "-E", "1000", "-nu", "0",
                          "-dirichlet", "dirichlet", "-traction_right", "5,0,0", "-snes_view"], h5="bar_L2.h5")
    expect("type: ksponly" in out and "type: ssstar" not in out and "one linear solve" in out, "not one linear solve", out)
    expect(s["iters"] == 0 and s["contact"] == 0, "contact nodes or iterations without contact", out)
    x, u = field("bar_L2.h5")
    exact = np.c_[5 * x[:, 0] / 1000, 0 * x[:, 0], 0 * x[:, 0]]
    err = np.abs(u - exact).max() / np.abs(exact).max()
    expect(err <= 1e-10, "bar: %g from the exact solution" % err, out)


@test("an initial gap larger than the deformation (plane at z = -1) gives the no-contact solution: all nodes separated, at most 1 iteration, the whole displacement equal to the linear solve's to 1e-10")
def scene_far_gap_is_no_contact():
    base = scene("prism") + ["-level", "3"]
    out, s = contact_run(base + ["-obstacle_contact", "0,0,-1,0,0,1"], h5="far_gap_L3.h5")
    expect(s["states"][0] == s["contact"] and s["iters"] <= 1, "states %s after %d iterations" % (s["states"], s["iters"]), out)
    opts = open(os.path.join(ROOT, "scenes", "prism.opts")).read().split("\n")
    plain = [w for line in opts if line and not line.startswith("#") and not line.startswith("-contact") and not line.startswith("-friction")
             for w in line.split()]
    contact_run(plain + ["-level", "3"], h5="no_contact_L3.h5")
    (x1, u1), (x2, u2) = field("far_gap_L3.h5"), field("no_contact_L3.h5")
    err = np.abs(u1 - u2).max() / np.abs(u2).max()
    expect(np.array_equal(x1, x2) and err <= 1e-10, "far gap vs no contact: %g" % err)


@test("the whole scene rotated and translated (mesh, plane, tractions) reproduces the solution, rotated: prism level 3, contact displacement and reaction to 1e-8, same states and iterations")
def scene_rotated():
    msh = os.path.join(OUT, "rot_L3.msh")
    run(["gmsh", "-3", "-setnumber", "L", "3", "-format", "msh22", os.path.join(ROOT, "meshes", "prism.geo"), "-o", msh])
    axis = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
    angle = 0.7
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    Q = np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K
    t = np.array([0.3, -1.2, 2.0])
    lines = open(msh).read().split("\n")
    i = lines.index("$Nodes")
    for k in range(i + 2, i + 2 + int(lines[i + 1])):
        w = lines[k].split()
        y = Q @ np.array([float(v) for v in w[1:4]]) + t
        lines[k] = "%s %.17g %.17g %.17g" % (w[0], y[0], y[1], y[2])
    rotated = os.path.join(OUT, "rotated_L3.msh")
    open(rotated, "w").write("\n".join(lines))

    def vec(v):
        return ",".join("%.17g" % c for c in v)
    common = ["-E", "2.1e5", "-nu", "0.3", "-dirichlet", "dirichlet", "-contact", "contact", "-friction_contact", "0.3"]
    _, s1 = contact_run(["-mesh", msh, "-traction_top", "0,0,-500", "-traction_right", "-200,30,200"] + common, h5="unrotated.h5")
    _, s2 = contact_run(["-mesh", rotated, "-traction_top", vec(Q @ [0, 0, -500]), "-traction_right", vec(Q @ [-200, 30, 200]),
                         "-obstacle_contact", vec(t) + "," + vec(Q @ [0, 0, 1])] + common, h5="rotated.h5")
    expect(s1["states"] == s2["states"] and abs(s1["iters"] - s2["iters"]) <= 1, "states %s / %s, iterations %d / %d" % (s1["states"], s2["states"], s1["iters"], s2["iters"]))
    a, b = scene_answers.contact(os.path.join(OUT, "unrotated.h5")), scene_answers.contact(os.path.join(OUT, "rotated.h5"))
    for name in ("displacement", "reaction"):
        err = np.abs(a[name] @ Q.T - b[name]).max() / np.abs(a[name]).max()
        expect(err <= AGREE, "rotated %s differs by %g" % (name, err))
    expect(np.abs(b["gap"]).max() < 1e-12, "the rotated contact face does not lie on the rotated plane")


# ---- the shipped scenes and their known answers -------------------------------------------------------------------

def plot(h5):
    png = os.path.join(OUT, h5.replace(".h5", ".png"))
    if os.path.exists(png):
        os.remove(png)
    run(PLOT + [os.path.join(OUT, h5)])
    expect(os.path.getsize(png) > 10000, "no picture from plot_contact.py for " + h5)
    expect(os.path.exists(os.path.join(OUT, h5.replace(".h5", ".xmf"))), "no XDMF file beside " + h5)


@test("incline (slope tan 20 deg = 0.364, level 3): with phi = 0.5 the block sticks (N = m g cos alpha and |F_t|/N = tan alpha to 0.5 %, most nodes stuck, no rigid slide); with phi = 0.3 it slides (every node sliding, |F_t| = phi N to 0.1 %, the spring stretched by m g (sin alpha - phi cos alpha)/(k A) to 1 %); HDF5, XDMF and PNG written")
def scene_incline():
    alpha = np.radians(20)
    downhill = [np.cos(alpha), 0, -np.sin(alpha)]
    weight, k, area = 1000 * 9.81, 5000, 2.0
    contact_run(scene("incline") + ["-level", "3"], h5="incline_stick.h5")
    h5 = os.path.join(OUT, "incline_stick.h5")
    r, d = scene_answers.friction(h5), scene_answers.slide(h5, downhill)["slide"]
    expect(abs(r["ratio"] / np.tan(alpha) - 1) < 0.005 and r["sticking"] > r["nodes"] / 2 and abs(d) < 1e-3, "sticking case: %s, slide %g" % (r, d))
    expect(abs(r["normal_force"] / (weight * np.cos(alpha)) - 1) < 0.005, "the plane carries N = %g, not m g cos alpha = %g" % (r["normal_force"], weight * np.cos(alpha)))
    contact_run(scene("incline") + ["-level", "3", "-friction_bottom", "0.3"], h5="incline_slide.h5")
    h5 = os.path.join(OUT, "incline_slide.h5")
    r, d = scene_answers.friction(h5), scene_answers.slide(h5, downhill)["slide"]
    expected = weight * (np.sin(alpha) - 0.3 * np.cos(alpha)) / (k * area)
    expect(r["sliding"] == r["nodes"] and abs(r["ratio"] / 0.3 - 1) < 1e-3 and abs(d / expected - 1) < 0.01, "sliding case: %s, slide %g (rigid block: %g)" % (r, d, expected))
    plot("incline_stick.h5")


@test("hertz (level 1, frictionless): contact radius within 2 % and peak pressure within 5 % of Hertz's formulas; the solver runs the frictionless path (no Tresca or Coulomb node)")
def scene_hertz():
    out, _ = contact_run(scene("hertz") + ["-level", "1", "-snes_view"], h5="hertz_L1.h5")
    expect("0 Tresca, 0 Coulomb" in out and re.search(r"active effects: non-penetration\n", out), "not the frictionless path", out)
    h = scene_answers.hertz(os.path.join(OUT, "hertz_L1.h5"))
    expect(abs(h["a_error"]) < 0.02 and abs(h["p0_error"]) < 0.05 and h["a_inside"] < 1.05 * h["a_hertz"] < 1.1 * h["a_outside"], "Hertz: %s" % h)
    plot("hertz_L1.h5")


@test("gap (level 2, 10 load steps): the contact area never shrinks as the load grows, and the plate first touches at the load factor gap/(-u_n) predicted by the linear solution without contact")
def scene_gap():
    out, _ = contact_run(scene("gap") + ["-level", "2"], h5="gap_L2.h5")
    f = h5py.File(os.path.join(OUT, "gap_L2.h5"), "r")
    factor, area = f["load_steps/factor"][:], f["load_steps/area"][:]
    expect(len(factor) == 10 and np.all(np.diff(area) >= 0) and area[-1] > 0, "areas %s" % area, out)
    opts = open(os.path.join(ROOT, "scenes", "gap.opts")).read().split("\n")
    plain = [w for line in opts if line and not line.startswith("#") and not re.match(r"-(contact|obstacle|friction|load_steps)", line) for w in line.split()]
    contact_run(plain + ["-level", "2"], h5="gap_linear_L2.h5")
    first = scene_answers.first_contact(os.path.join(OUT, "gap_linear_L2.h5"), os.path.join(OUT, "gap_L2.h5"))["factor"]
    expect(0.1 < first < 1, "first contact at %g: not within the steps" % first)
    for lam, a in zip(factor, area):
        expect((a > 0) == (lam > first), "load factor %g: contact area %g, first contact predicted at %g" % (lam, a, first), out)
    plot("gap_L2.h5")


@test("shear (level 3): the Coulomb law holds at every node, the friction carries the applied shear (|F_t| = tau A within 2 %), and the stuck zone shrinks as tau grows (2.5, 3.5, 4.5 of phi p = 5) while a stuck zone remains")
def scene_shear():
    stuck = []
    for tau in (2.5, 3.5, 4.5):
        h5 = "shear_%g.h5" % tau
        contact_run(scene("shear") + ["-level", "3", "-traction_top", "%g,0,-10" % tau], h5=h5)
        run(CHECK + ["coulomb", os.path.join(OUT, h5), "--tol", "1e-8"])
        r = scene_answers.friction(os.path.join(OUT, h5))
        expect(abs(r["tangential_force"] / tau - 1) < 0.02, "tau %g: friction %s" % (tau, r))
        stuck.append(r["sticking"])
    expect(stuck[0] > stuck[1] > stuck[2] > 0, "stuck nodes %s" % stuck)
    plot("shear_3.5.h5")


@test("the driver gives the same solution on 1 and 2 ranks for a tilted plane with gaps, gravity and load steps (gap level 2 with -gravity), to 1e-10")
def scene_ranks_agree():
    extra = ["-level", "2", "-gravity", "0,0,-9.81", "-density", "1e-3"]
    contact_run(scene("gap") + extra, h5="gap_r1.h5")
    contact_run(scene("gap") + extra, h5="gap_r2.h5", ranks=2)
    run(CHECK + ["compare", os.path.join(OUT, "gap_r1.h5"), os.path.join(OUT, "gap_r2.h5"), "--tol", str(AGREE)])


# ---- only the effects named ---------------------------------------------------------------------------------------

@test("the driver prints the active effects, and only those named: prism (tractions, Coulomb), hertz (springs, tractions, frictionless contact), incline (springs, gravity, Coulomb), no contact (one linear solve); gravity only when given")
def scene_active_effects():
    expected = {"prism": "elasticity, tractions, contact (non-penetration), Coulomb friction",
                "hertz": "elasticity, springs, tractions, contact (non-penetration)",
                "incline": "elasticity, springs, gravity, contact (non-penetration), Coulomb friction"}
    for name, effects in expected.items():
        out, _ = contact_run(scene(name) + ["-level", "1"])
        m = re.search(r"active effects: (.*)", out)
        expect(m is not None and m.group(1) == effects, "%s: %s" % (name, m.group(1) if m else "no line"), out)
    out, _ = contact_run(["-geo", os.path.join(ROOT, "meshes", "prism.geo"), "-level", "1", "-E", "1", "-nu", "0.3", "-dirichlet", "dirichlet", "-traction_top", "0,0,-1"])
    expect("active effects: elasticity, tractions; no contact: one linear solve" in out and "gravity" not in out, "no-contact effects", out)


# ---- bad input: a clear error before any work, non-zero exit, no output file ---------------------------------------

PRISM_BASE = []
CONTACT_BASE = scene("prism")
# a scene of a mesh file, for the mesh errors: the prism's groups
MESH_SCENE = ["-E", "1", "-nu", "0.3", "-dirichlet", "dirichlet", "-traction_top", "0,0,-1", "-contact", "contact"]


def refused(program, args, messages, name):
    """Runs program with args and -o, expects a non-zero exit, the messages, and no output file (nor temporary one)"""
    h5 = os.path.join(OUT, "refused_%s.h5" % name)
    for f in os.listdir(OUT):
        if f.startswith("refused_%s." % name):
            os.remove(os.path.join(OUT, f))
    out = run([program] + args + ["-o", h5], expect_rc=1)
    for message in [messages] if isinstance(messages, str) else messages:
        expect(message in out, "%s: the message %r is missing" % (name, message), out)
    left = [f for f in os.listdir(OUT) if f.startswith("refused_%s." % name)]
    expect(not left, "%s: files left behind: %s" % (name, left), out)


def bad_mesh(name, text):
    path = os.path.join(OUT, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def corrupt_mesh():
    msh = os.path.join(OUT, "whole_L2.msh")
    run(["gmsh", "-3", "-setnumber", "L", "2", "-format", "msh41", os.path.join(ROOT, "meshes", "prism.geo"), "-o", msh])
    text = open(msh).read()
    return bad_mesh("corrupt.msh", text[: text.index("$Elements") + 200])


BAD_INPUT = [
    # name, arguments for both programs (or a pair: prism's, contact's; or a function giving them), message(s)
    ("missing_mesh", (["-mesh", "no/such.msh"], MESH_SCENE + ["-mesh", "no/such.msh"]), "Cannot read the mesh file no/such.msh"),
    ("empty_mesh", lambda: mesh_args(bad_mesh("empty.msh", "")), ["The mesh file", "empty.msh is empty"]),
    ("not_a_mesh", lambda: mesh_args(bad_mesh("text.msh", "hello\n")), "text.msh is not a gmsh mesh"),
    ("corrupt_mesh", lambda: mesh_args(corrupt_mesh()), "Cannot read the mesh file"),
    ("missing_group", ["-traction_nowhere", "1,2,3"], 'no physical group named "nowhere" (option -traction_nowhere)'),
    ("negative_friction", (["-snes_ssstar_friction", "-0.1"], ["-friction_contact", "-0.1"]), ["-0.1", "the friction coefficient must be a number >= 0"]),
    ("nan_friction", (["-snes_ssstar_friction", "nan"], ["-friction_contact", "nan"]), ["nan", "the friction coefficient must be a number >= 0"]),
    ("zero_E", ["-E", "0"], ["-E 0", "Young's modulus must be a positive number"]),
    ("nu_minus_one", ["-nu", "-1"], ["-nu -1", "Poisson's ratio must be in (-1, 0.5)"]),
    ("nu_half", ["-nu", "0.5"], ["-nu 0.5", "Poisson's ratio must be in (-1, 0.5)"]),
    ("nan_traction", ["-traction_top", "0,0,nan"], "Option -traction_top: value 3 \"nan\" is not a finite number"),
    ("inf_traction", ["-traction_right", "inf,0,0"], "Option -traction_right: value 1 \"inf\" is not a finite number"),
    ("level_zero", ["-level", "0"], "-level 0: the mesh level must be >= 1"),
    ("level_400", ["-level", "400"], ["-level 400 of", "refused before the work", "GB available on this machine (MemAvailable)"]),
    ("mesh_too_large", ["-snes_ssstar_memory_limit", "0.001"], ["more than the 0.001 GB of -snes_ssstar_memory_limit", "refused before the work"]),
    ("unknown_law", ["-friction_law_contact", "sticky"], ["-friction_law_contact", "sticky"]),
    ("contact_group_emptied", lambda: ["-geo", emptied_geo(), "-dirichlet", "dirichlet,sides"],
     'Contact group "contact" (option -contact) has no nodes once the nodes held in every component (-dirichlet, -displacement_<G>) are removed'),
]


def mesh_args(path):
    return ["-mesh", path], MESH_SCENE + ["-mesh", path]


def emptied_geo():
    """The prism with a group "sides" that holds the contact face too"""
    geo = os.path.join(OUT, "emptied.geo")
    with open(geo, "w") as f:
        f.write(open(os.path.join(ROOT, "meshes", "prism.geo")).read() + 'Physical Surface("sides") = {1};\n')
    return geo


def bad_input_test(name, args, message):
    def check():
        a = args() if callable(args) else args
        prism_args, contact_args = a if isinstance(a, tuple) else (a, a)
        refused(PRISM, PRISM_BASE + prism_args, message, name + "_prism")
        refused(CONTACT, (CONTACT_BASE if "-mesh" not in contact_args else []) + contact_args, message, name + "_contact")
    return check


for _name, _args, _message in BAD_INPUT:
    test("bad input refused by examples/prism and examples/contact before any work, non-zero exit, no output file: %s (message: %s)" % (_name.replace("_", " "), _message))(
        bad_input_test(_name, _args, _message))
    TESTS[-1] = ("bad_input_" + _name,) + TESTS[-1][1:]


CONTACT_ONLY = [
    # name, scene, arguments, message
    ("group_option_not_contact", "prism", ["-obstacle_top", "0,0,0,0,0,1"], 'Option -obstacle_top: "top" is not a contact group (not in -contact; the nearest contact group is "contact")'),
    ("friction_with_law_none", "prism", ["-friction_law_contact", "none"], "Options -friction_contact and -friction_law_contact none contradict each other"),
    ("tresca_without_bound", "hertz", ["-friction_law_cap", "tresca"], "Option -friction_law_cap tresca needs -slip_bound_cap"),
    ("gravity_without_density", "prism", ["-gravity", "0,0,-9.81"], "Incomplete body force: -gravity needs -density"),
    ("mesh_and_geo", "prism", ["-mesh", "x.msh"], "Options -mesh and -geo contradict each other"),
    ("traction_on_held_group", "prism", ["-traction_dirichlet", "1,0,0"], "Options -traction_dirichlet and -dirichlet contradict each other"),
    ("node_inside_obstacle", "prism", ["-obstacle_contact", "0,0,0.5,0,0,1"], "inside the obstacle of -obstacle_contact"),
    ("normal_out_of_the_body", "prism", ["-obstacle_contact", "0,0,-0.1,0,0,-1"], "does the normal point into the body?"),
    ("material_not_volume", "prism", ["-material_top", "1,0.3"], 'Physical group "top" of mesh'),
    ("material_of_a_group", "hertz", ["-material_ball", "2.1e5,0.7"], ["-material_ball", "Poisson's ratio nu = 0.7 must be in (-1, 0.5)"]),
]


def contact_only_test(name, base, args, message):
    def check():
        refused(CONTACT, scene(base) + ["-level", "1"] + args, message, name)
    return check


for _name, _base, _args, _message in CONTACT_ONLY:
    test("examples/contact refuses contradictory, incomplete or impossible scenes, naming the option: %s" % _name.replace("_", " "))(
        contact_only_test(_name, _base, _args, _message))
    TESTS[-1] = ("bad_scene_" + _name,) + TESTS[-1][1:]
