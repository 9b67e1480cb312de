"""Obstacles that turn (issue 32, docs/derivation.md section 16a): -obstacle_<G>_rotation beside -obstacle_<G>_motion, one
placement per obstacle that every measure of the contact asks and whose material point's motion friction sees -- a
cylinder rolled without slip over a slab, a flat punch turned about its normal -- on both paths and 1 and 2 ranks,
from C and from Python, and the refusals."""
import os
import re
import sys

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
LAW = CHECK + ["coulomb", "--steps"]
# both paths, 1 and 2 ranks: make test runs the dense route on 1 rank and the whole body on 2, make test-full the other two
QUICK, OTHERS = [("direct", 1), ("none", 2)], [("none", 1), ("direct", 2)]
# a rigid cylinder (R = 1, along y) pressed 0.02 into the slab of scenes/drag.opts, then moved by 1 along x while it
# turns by 1 rad about its axis (v = omega R: it rolls without slip) -- or, without the rotation, dragged
SLAB = ["-geo", "meshes/slab.geo", "-level", "1", "-E", "2.1e5", "-nu", "0.3", "-dirichlet", "bottom", "-contact", "top",
        "-friction_top", "0.3", "-ssstar_progress", "0"]
ROLL = SLAB + ["-obstacle_top", "cylinder:0.5,0,1,0,1,0,1", "-obstacle_top_motion", "0:0,0,0;1:0,0,-0.02;3:1,0,-0.02",
               "-steps", "0,1,1.5,2,2.5,3"]
TURN = ["-obstacle_top_rotation", "0:0,1,0,0;1:0,1,0,0;3:0,1,0,1"]
# the flat punch of scenes/punch.opts (a box 0.4 x 0.4 standing on its face z = 0, reference point its vertices' mean
# (0, 0, 0.1)) pressed 0.002 into the slab at x = 2, then turned by 0.2 rad about its vertical axis
PUNCH = SLAB + ["-obstacle_top", "mesh:meshes/punch.msh", "-obstacle_top_motion", "0:2,0,0.001;1:2,0,-0.002",
                "-obstacle_top_rotation", "0:0,0,1,0;1:0,0,1,0;2:0,0,1,0.2", "-steps", "0,1,1.25,1.5,1.75,2"]


def contact_run(args, name, red="direct", ranks=1, expect_rc=0):
    path = os.path.join(OUT, name)
    out = run(mpiexec(ranks, CONTACT, *args, "-snes_ssstar_reduction", red, "-o", path, "-malloc_dump"), expect_rc=expect_rc)
    return out, path


def touching(c):
    s = c["state"][:]
    return (s != 0) & (s != 6)


def rolling(paths):
    _, drag = contact_run(ROLL, "motion_drag.h5")
    fd = h5py.File(drag, "r")
    dragged = fd["steps/dissipation"][-1] - fd["steps/dissipation"][1]
    expect(abs(np.linalg.norm(fd["steps/tangential_force"][-1]) / (0.3 * fd["steps/normal_force"][-1]) - 1) < 0.01, "the dragged cylinder is not at T = phi N")
    fields = []
    for red, ranks in paths:
        _, path = contact_run(ROLL + TURN, "motion_roll_%s_%d.h5" % (red, ranks), red, ranks)
        f = h5py.File(path, "r")
        st = f["steps"]
        t = st["time"][:]
        expect(np.allclose(st["rotation/top"][:, 1], np.clip(t - 1, 0, None) / 2) and np.abs(st["rotation/top"][:, [0, 2]]).max() == 0, "%s %d: rotation/top is not the angle about y: %s" % (red, ranks, st["rotation/top"][:]))
        expect(f["scene/contact/top"].attrs["rotation"] and np.allclose(f["scene/contact/top"].attrs["rotation_center"], [0.5, 0, 1]), "%s %d: /scene/contact/top lacks the rotation" % (red, ranks))
        for k in range(2, len(t)):
            c = f["steps/%d/contact" % k]
            inc = np.linalg.norm(c["slip_increment"][:][touching(c)], axis=1)
            travel = t[k] - t[k - 1]
            expect(inc.mean() < 0.02 * travel and inc.max() < 0.04 * travel, "%s %d, t = %g: the rolled cylinder slides the touching nodes by %.2e on the mean, %.2e at most (travel %g)" % (red, ranks, t[k], inc.mean(), inc.max(), travel))
        rolled = st["dissipation"][-1] - st["dissipation"][1]
        expect(rolled < 1e-2 * dragged, "%s %d: rolling dissipates %.3g, dragging %.3g" % (red, ranks, rolled, dragged))
        run(LAW + [path])
        fields.append(np.concatenate([f["steps/%d/fields/displacement" % k][:].ravel() for k in range(len(t))]))
    for other in fields[1:]:
        diff = np.abs(other - fields[0]).max() / np.abs(fields[0]).max()
        expect(diff <= AGREE, "the paths and rank counts differ by %.1e in the displacements" % diff)


@test("a rigid cylinder rolled without slip over a slab (-obstacle_top_motion along x by 1 and -obstacle_top_rotation by 1 rad about its axis, R = 1: v = omega R; large sliding, phi = 0.3; 4 steps of 0.25): at every rolling step the touching nodes' slip increments against the cylinder's surface are below 2 % of the step's travel on the mean and 4 % at the most (the placement's second order: the touched point's chord moves R(dtheta - sin dtheta) along the slab, 1 % of the travel at dtheta = 0.25), the friction dissipation of the roll below 1 % of the same cylinder dragged without turning (the dragged one slides every node by the travel, T = phi N), the file's rotation/top column is the angle about y and its /scene says rotation and rotation_center; the law holds at every step of the file; the dense route on 1 rank and the whole body on 2 (make test-full: the other two) agree to 2e-6 (harness.AGREE)")
def motion_rolling_cylinder():
    rolling(QUICK)


@test("the rolled cylinder of motion_rolling_cylinder on the other paths and rank counts (the whole body on 1 rank, the dense route on 2): the same slips and dissipation, agreeing to 2e-6", full=True)
def motion_rolling_cylinder_other_paths():
    rolling(OTHERS)


@test("a flat punch turned about its normal (meshes/punch.msh pressed 0.002 into the slab, then -obstacle_top_rotation 0.2 rad about z through its reference point, the mean of its vertices): in every turning step the touching nodes but the one on its axis slide, their slip increments are circumferential against the turn (the cosine with -e_theta at least 0.98; measured 0.991) and the friction torque about the axis is phi sum(r_n rho) within 1 % (measured 0.04-0.3 %); the law holds at every step; the dense route on 1 rank and the whole body on 2 agree to 2e-6")
def motion_turning_punch():
    torques = []
    for red, ranks in (("direct", 1), ("none", 2)):
        _, path = contact_run(PUNCH, "motion_punch_%s_%d.h5" % (red, ranks), red, ranks)
        f = h5py.File(path, "r")
        t = f["steps/time"][:]
        x = f["contact/coordinates"][:]
        for k in range(2, len(t)):
            c = f["steps/%d/contact" % k]
            u, r, n, inc = c["displacement"][:], c["reaction"][:], c["normal"][:], c["slip_increment"][:]
            rho = x[:, :2] + u[:, :2] - [2.0, 0.0]
            dist = np.linalg.norm(rho, axis=1)
            rn = np.einsum("ij,ij->i", r, n)
            rt = r - rn[:, None] * n
            on = touching(c) & (dist > 0.05)
            s = c["state"][:]
            expect(np.all((s[on] == 1) | (s[on] == 2)), "%s %d, t = %g: touching nodes off the axis stick: %s" % (red, ranks, t[k], s[on]))
            e_theta = np.c_[-rho[:, 1], rho[:, 0]] / np.maximum(dist, 1e-30)[:, None]
            cos = -np.einsum("ij,ij->i", inc[:, :2], e_theta) / np.maximum(np.linalg.norm(inc[:, :2], axis=1), 1e-30)
            expect(cos[on].min() >= 0.98, "%s %d, t = %g: a slip not circumferential against the turn (cos %.4f)" % (red, ranks, t[k], cos[on].min()))
            torque = np.sum(rho[:, 0] * rt[:, 1] - rho[:, 1] * rt[:, 0])
            bound = 0.3 * np.sum((rn * dist)[touching(c)])
            expect(abs(torque / bound - 1) <= 0.01, "%s %d, t = %g: the friction torque %.6g against phi sum(r_n rho) = %.6g" % (red, ranks, t[k], torque, bound))
            torques.append(torque)
        run(LAW + [path])
    n = len(torques) // 2
    diff = np.abs(np.array(torques[:n]) - torques[n:]).max() / np.abs(torques).max()
    expect(diff <= AGREE, "the paths differ by %.1e in the torques" % diff)


@test("a rolling cylinder from Python (ssstar.Scene with obstacle_rotation={G: history}, keywords for the options of C): the same file as examples/contact to 2e-6 (check_solution.py compare --steps on the displacements); Scene.set(obstacle_rotation=...) changes the turn of the steps to come (a cylinder set to turn twice as fast drags the slab: T = phi N) and refuses a scene without a rotation")
def motion_python():
    ref = os.path.join(OUT, "motion_roll_direct_1.h5")
    if not os.path.exists(ref):
        contact_run(ROLL + TURN, "motion_roll_direct_1.h5")
    script = os.path.join(OUT, "motion_python.py")
    open(script, "w").write('''import sys
sys.path.insert(0, %r)
import ssstar
args = %r
opts = {}
for k in range(0, len(args), 2):
    name = args[k][1:]
    if name.startswith("obstacle_top_"):
        opts["obstacle_" + name[len("obstacle_top_"):]] = {"top": args[k + 1]}
    elif name in ("dirichlet", "contact"):
        opts[name] = [args[k + 1]]
    else:
        opts[name] = args[k + 1]
with ssstar.Scene(o=sys.argv[1], **opts) as scene:
    for step in scene.steps():
        assert step.converged
with ssstar.Scene(**opts) as scene:
    for t in (0, 1, 1.5):
        step = scene.step(t)
    scene.set(obstacle_rotation={"top": "0:0,1,0,0;1:0,1,0,0;3:0,1,0,4"})
    for t in (2, 2.5):
        step = scene.step(t)
    print("fast turn: T/(phi N) = %%.4f" %% (abs(step.row["tangential_force"][0]) / (0.3 * step.row["normal_force"])))
try:
    with ssstar.Scene(**{k: v for k, v in opts.items() if k != "obstacle_rotation"}) as scene:
        scene.set(obstacle_rotation={"top": "0,1,0,0"})
except ssstar.Error as e:
    print("refused:", e)
''' % (os.path.join(ROOT, "python"), ROLL + TURN + ["-snes_ssstar_reduction", "direct"]))
    path = os.path.join(OUT, "motion_python.h5")
    out = run([PYTHON, script, path])
    m = re.search(r"fast turn: T/\(phi N\) = (\S+)", out)
    expect(m is not None and abs(float(m.group(1)) - 1) < 0.01, "a cylinder turning twice too fast does not slide the slab at T = phi N", out)
    expect("refused:" in out and "has no rotation" in out, "set(obstacle_rotation=...) is not refused on a scene without a rotation", out)
    out = run(CHECK + ["compare", path, ref, "--steps", "--tol", str(AGREE)])
    expect("full field" in out and "DIFFERENT" not in out.split("full field")[1].split("\n")[0], "Python's rolling file differs from examples/contact's", out)


@test("refusals of -obstacle_<G>_rotation, each one line naming the option: an axis of zero length with a nonzero angle (in a knot or a constant), a value of three numbers, a rotation of a contact pair's group; with -sliding small a turned obstacle's first-order gap g - n.d_i is checked as a moved one's: a ball turned by 0.5 rad about its centre (the chord of its surface point R(1 - cos theta) = 0.12 off its tangent) is refused at that step, the message saying it turned")
def motion_refusals():
    cases = [
        (["-obstacle_top_rotation", "0:0,1,0,0;1:0,0,0,0.5"], "has no direction"),
        (["-obstacle_top_rotation", "0,0,0,1"], "has no direction"),
        (["-obstacle_top_rotation", "0,1,0"], "-obstacle_top_rotation"),
    ]
    for extra, words in cases:
        out = run([CONTACT] + ROLL + extra, expect_rc=1)
        expect(words in out and "-obstacle_top_rotation" in out, "%s: not refused with '%s'" % (extra, words), out)
    out = run([CONTACT, "-options_file", os.path.join(ROOT, "scenes", "hertz2.opts"), "-obstacle_cap_rotation", "0,0,1,0.1"], expect_rc=1)
    expect("contradict" in out and "-obstacle_cap_rotation" in out, "a pair's rotation is not refused", out)
    ball = SLAB + ["-obstacle_top", "sphere:0.5,0,1,1", "-sliding", "small", "-steps", "0,1,2", "-obstacle_top_rotation", "0:0,1,0,0;1:0,1,0,0;2:0,1,0,0.5",
                   "-obstacle_top_motion", "0:0,0,0;1:0,0,-0.01"]
    out = run([CONTACT] + ball, expect_rc=1)
    expect(re.search(r"Step 3 \(t = 2\.?\): the obstacle of -obstacle_top .* and turned", out) is not None, "small sliding does not refuse the turned ball", out)
