"""Large sliding (issue 24, docs/derivation.md section 13): load paths whose contact is measured where the bodies are at
every step -- a ball and a cylinder dragged along a slab, a flat punch dragged off its edge, a block slid across
another by twice its length -- against their known answers, on both paths and 1 to 4 ranks."""
import os
import re

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)
import scene_answers

CONTACT = os.path.join(ROOT, "examples", "contact")
SCENES = os.path.join(ROOT, "scenes")
# both paths and both rank counts, in two runs: the dense route on one rank, the whole body on two
RUNS = (("direct", 1), ("none", 2))
# the law at every step of the file, at check_solution.py's default (what converged guarantees, docs/derivation.md 12)
LAW = CHECK + ["coulomb", "--steps"]


def sliding_run(scene, name, red, ranks, extra=(), expect_rc=0):
    path = os.path.join(OUT, name)
    out = run(mpiexec(ranks, CONTACT, "-options_file", os.path.join(SCENES, scene), "-ssstar_progress", "0",
                      "-snes_ssstar_reduction", red, *extra, "-o", path, "-malloc_dump"), expect_rc=expect_rc)
    return out, path


def law(path):
    out = run(LAW + [path])
    expect("slip_increment" in out, "%s: check_solution.py did not check the slip increment" % path, out)


@test("docs/derivation.md section 13 holds (tests/sliding_check.py, numpy): small sliding's first-order gap errs by |d|^2/(2R) for a ball moved along its tangent (0.24 for R = 2 pressed 0.02 and moved 1); the offsets (13.4) give the step's kinematics (13.1)-(13.3), unchanged by a common translation of body and obstacle; the linearization updated at the solution (13.5) converges to the exact gap's KKT point at the rate of the neglected geometric stiffness")
def sliding_derivation():
    page = open(os.path.join(ROOT, "docs", "derivation.md")).read()
    for equation in ("(13.1)", "(13.2)", "(13.3)", "(13.4)", "(13.5)"):
        expect(equation in page, "docs/derivation.md has no equation %s" % equation)
    out = run([PYTHON, os.path.join(ROOT, "tests", "sliding_check.py")])
    expect(out.count("PASS") == 3 and "FAIL" not in out, "tests/sliding_check.py", out)


@test("a rigid ball (R = 1) pressed 0.02 into a slab and dragged by two radii (scenes/drag.opts, large sliding): every touching node slides in every drag step, the normal force stays that of the indentation within 5 % (the mesh's resolution at level 1: measured 3.6 % spread) and repeats with the mesh (positions 0.5 apart to 0.5 %), the tangential force is phi N within 1 % (measured 0.9975: the tilted normals under the ball), the contact patch follows the ball (its centroid less the ball's translation stays within 0.01), the law holds at every step of the file (check_solution.py --steps); the dense route on 1 rank and the whole body on 2 give the same forces to 2e-6 (harness.AGREE; measured 4e-9); -sliding small refuses the drag at its first step", full=True)
def sliding_ball_drag():
    forces = []
    for red, ranks in RUNS:
        _, path = sliding_run("drag.opts", "sliding_drag_%s_%d.h5" % (red, ranks), red, ranks)
        f = h5py.File(path, "r")
        t, N = f["steps/time"][:], f["steps/normal_force"][:]
        pressed = N[np.argmin(abs(t - 1))]
        a = scene_answers.sliding(path, 1.25)
        expect(a["sliding_steps"] == a["steps"] == 15, "%s %d: not every drag step slides: %s" % (red, ranks, a))
        expect(abs(a["normal_force_mean"] / pressed - 1) <= 0.05 and a["normal_force_spread"] / pressed <= 0.05, "%s %d: the normal force during the drag %g (spread %g) against %g pressed" % (red, ranks, a["normal_force_mean"], a["normal_force_spread"], pressed))
        repeat = [abs(N[np.argmin(abs(t - s))] / N[np.argmin(abs(t - s - 0.5))] - 1) for s in (1.25, 1.375, 1.5, 1.625)]
        expect(max(repeat) <= 5e-3, "%s %d: the normal force does not repeat with the mesh: %s" % (red, ranks, repeat))
        expect(0.99 <= a["friction_ratio_min"] and a["friction_ratio_max"] <= 1.0, "%s %d: T / (phi N) in [%g, %g]" % (red, ranks, a["friction_ratio_min"], a["friction_ratio_max"]))
        expect(a["centroid_lag_x_spread"] <= 0.01 and a["centroid_lag_y_spread"] <= 0.01, "%s %d: the contact patch does not follow the ball: %s" % (red, ranks, a))
        law(path)
        forces.append(np.c_[N, np.linalg.norm(f["steps/tangential_force"][:], axis=1)])
    diff = np.abs(forces[0] - forces[1]).max() / np.abs(forces[0]).max()
    expect(diff <= AGREE, "the dense route and the whole body on 2 ranks differ by %.1e in the forces" % diff)
    out = run([CONTACT, "-options_file", os.path.join(SCENES, "drag.opts"), "-sliding", "small"], expect_rc=1)
    expect(re.search(r"Step 6 \(t = 1\.125\): the obstacle of -obstacle_top .* first-order gap", out), "-sliding small: the drag is not refused at its first step", out)


@test("a rigid cylinder (R = 1, along y) pressed 0.01 into the slab and slid across its axis by 2 (large sliding): every touching node slides, the tangential force is phi N within 1 % (measured 0.9988-0.9993: the normals tilted across the contact line), the normal force repeats with the mesh (positions 0.5 apart to 0.5 %) and stays within 10 % of its mean (a line contact three nodes wide at level 1); the dense route (1 rank) and the whole body (2 ranks) agree to 2e-6 (harness.AGREE), the law holds at every step of the file", full=True)
def sliding_cylinder():
    args = ["-obstacle_top", "cylinder:0.5,0,1,0,1,0,1", "-obstacle_top_motion", "0:0,0,0;1:0,0,-0.01;3:2,0,-0.01", "-steps", "24"]
    forces = []
    for red, ranks in RUNS:
        _, path = sliding_run("drag.opts", "sliding_cylinder_%s_%d.h5" % (red, ranks), red, ranks, args)
        f = h5py.File(path, "r")
        t, N = f["steps/time"][:], f["steps/normal_force"][:]
        a = scene_answers.sliding(path, 1.25)
        expect(a["sliding_steps"] == a["steps"] and 0.99 <= a["friction_ratio_min"] and a["friction_ratio_max"] <= 1, "%s %d: %s" % (red, ranks, a))
        repeat = [abs(N[np.argmin(abs(t - s))] / N[np.argmin(abs(t - s - 0.5))] - 1) for s in (1.25, 1.375, 1.5, 1.625)]
        expect(max(repeat) <= 5e-3 and a["normal_force_spread"] <= 0.2 * a["normal_force_mean"], "%s %d: the normal force %s, repeats %s" % (red, ranks, a, repeat))
        law(path)
        forces.append(np.c_[N, np.linalg.norm(f["steps/tangential_force"][:], axis=1)])
    diff = np.abs(forces[0] - forces[1]).max() / np.abs(forces[0]).max()
    expect(diff <= AGREE, "the dense route and the whole body on 2 ranks differ by %.1e in the forces" % diff)


@test("a flat rigid punch (meshes/punch.msh, a closed box of 0.4 x 0.4 searched at the current positions) pressed 0.002 into the slab and dragged off its end (scenes/punch.opts): the contact area follows the overlap of the punch and the slab within the mesh's resolution (the nodes along the overlap's rim count with their whole tributary area: h times half its perimeter plus h^2, h = 0.1) and shrinks, as the punch's rear edge reaches the slab's end, to the nodes of the end row under it; while it slides with contact the tangential force is phi N to 1e-3; both paths, 1 and 2 ranks, the law at every step of the file", full=True)
def sliding_punch():
    for red, ranks in RUNS:
        _, path = sliding_run("punch.opts", "sliding_punch_%s_%d.h5" % (red, ranks), red, ranks)
        f = h5py.File(path, "r")
        st = f["steps"]
        xp, A = st["motion/top"][:, 0], st["area"][:]
        width = np.clip(4 - (xp - 0.2), 0, 0.4)
        on = xp - 0.2 <= 4 + 1e-9  # the punch's rear edge not past the slab's end: nodes under it may touch
        overlap, h = width * 0.4, 0.1
        tolerance = np.where(on, h * (width + 0.4) + h * h, 0) + 1e-12  # edge nodes count with their whole tributary area
        pressed = st["time"][:] >= 1
        expect(np.all(np.abs(A - overlap)[pressed] <= tolerance[pressed]), "%s %d: the contact area %s against the overlap %s" % (red, ranks, A[pressed], overlap[pressed]))
        x = f["contact/coordinates"][:]
        end = np.isclose(x[:, 0], 4) & (np.abs(x[:, 1]) <= 0.2 + 1e-9)
        expect(abs(A[-1] - f["contact/area"][:][end].sum()) <= 1e-12 and np.all(np.diff(A[pressed][1:]) <= 1e-12), "%s %d: the area does not shrink to the half of the end row under the punch's rear edge: %s" % (red, ranks, A[pressed]))
        a = scene_answers.sliding(path, 1.2)
        expect(abs(a["friction_ratio_min"] - 1) <= 1e-3 and abs(a["friction_ratio_max"] - 1) <= 1e-3, "%s %d: T / (phi N) %s" % (red, ranks, a))
        law(path)


@test("a flat block slid across a long one by twice its own length (scenes/track.opts, large sliding between two bodies: the master faces of every slave node found at the current configuration at every step): while it slides the tangential force is phi N to 1e-4, the contact area constant to 0.5 % (one rim node), the slide (q - phi p)/k = 1 to 1e-3, and every touching slave node ends on master faces outside the block's initial footprint; node-to-surface and dual mortar, the dense route on 1 rank and the whole body on 2 ranks (masters on other ranks reported by -info), and node-to-surface's dense route on 3 ranks (MUMPS's workspace estimated short where the block reaches new master faces: factored again with a larger ICNTL(14)), agreeing to 2e-6 (harness.AGREE; measured 1e-10; 1-4 ranks in bench/robust.py's sliding family); the law holds at every step of the file", full=True)
def sliding_block_track():
    results = []
    for method, red, ranks in (("node_to_surface", "direct", 1), ("node_to_surface", "none", 2), ("node_to_surface", "direct", 3), ("dual_mortar", "direct", 1), ("dual_mortar", "none", 2)):
        out, path = sliding_run("track.opts", "sliding_track_%s_%s_%d.h5" % (method, red, ranks), red, ranks, ["-pair_discretization", method, "-info", ":sys"])
        a = scene_answers.sliding(path, 1.125)
        f = h5py.File(path, "r")
        expect(a["sliding_steps"] == a["steps"] and abs(a["friction_ratio_min"] - 1) <= 1e-4 and abs(a["friction_ratio_max"] - 1) <= 1e-4, "%s %s %d: %s" % (method, red, ranks, a))
        expect(a["area_spread"] <= 5e-3 * a["area_mean"], "%s %s %d: the contact area varies: %s" % (method, red, ranks, a))
        slide = f["steps/groups/slider_top/displacement"][-1, 0]
        expect(abs(slide - 1) <= 1e-3, "%s %s %d: slid by %g, not 1" % (method, red, ranks, slide))
        c = f["contact"]
        touching = np.isin(c["state"][:], scene_answers.TOUCHING)
        x = (c["coordinates"][:] + c["displacement"][:])[touching]
        expect(touching.sum() > 100 and x[:, 0].min() > 0.75, "%s %s %d: touching slave nodes still over the initial footprint (x >= %g)" % (method, red, ranks, x[:, 0].min()))
        remote = [int(m) for m in re.findall(r"contact operator: (\d+) of \d+ contact nodes compared with master vertices of other ranks", out)]
        expect(ranks == 1 or max(remote) > 0, "%s %s %d: no slave node compared with masters of another rank" % (method, red, ranks), out[-2000:])
        law(path)
        results.append((method, np.array([a["friction_ratio_min"], a["area_mean"], slide])))
    for method in ("node_to_surface", "dual_mortar"):
        r = [v for m, v in results if m == method]
        diff = max(np.abs(v / r[0] - 1).max() for v in r)
        expect(diff <= AGREE, "%s: the runs differ by %.1e in T / (phi N), area and slide" % (method, diff))


@test("a block pushed back past the end of the block it slides on (scenes/track.opts): a slave node beyond the master's rim meets its edge, the contact measured at the step's solution does not settle and the step is cut, then the path stops (exit status 2, the message says why); the sub-steps in between, set again after a failure, start from a fresh measure at the accepted state (their normal force is the pressing load, not that of the failed attempt's linearization)")
def sliding_off_the_rim():
    out, path = sliding_run("track.opts", "sliding_off_rim.h5", "direct", 1, ["-traction_slider_top", "0:0,0,0;1:0,0,-0.01;2:-1.005,0,-0.01", "-steps", "0,1,1.5,2"], expect_rc=NOT_CONVERGED)
    expect("not converged (the contact measured at its solution did not settle in -sliding_max_it linearizations), retried at t 1.25" in out and "the path stops here" in out, "no cut, or no stop, for the rim", out)
    f = h5py.File(path, "r")
    t, N = f["steps/time"][:], f["steps/normal_force"][:]
    k = int(np.argmin(abs(t - 1.25)))
    expect(abs(t[k] - 1.25) < 1e-12 and abs(N[k] / N[1] - 1) <= 1e-3, "the sub-step at t = 1.25 after the failure: normal force %g against %g pressed" % (N[k], N[1]))


@test("the contact faces' gap of a vertex held on a contact face (the prism's x = 0 edge of its bottom, against a ball under it moved by 0.5 along the face and 0.001 up): /contact_faces/gap at the last step is the held vertex's distance to the moved ball, |y - c - d| - R, to 1e-12 (the obstacle asked at y - d), not the first-order g - n.d (off by up to 0.04 there), on 1 and 2 ranks")
def sliding_held_face_gap():
    centre, d = np.array([1.0, 0.5, -1.0]), np.array([0.5, 0.0, 0.001])
    for ranks in (1, 2):
        path = os.path.join(OUT, "sliding_held_gap_%d.h5" % ranks)
        run(mpiexec(ranks, CONTACT, "-geo", os.path.join(ROOT, "meshes", "prism.geo"), "-level", "1", "-E", "1e5", "-nu", "0.3",
                    "-dirichlet", "dirichlet", "-contact", "contact", "-obstacle_contact", "sphere:1,0.5,-1,1",
                    "-obstacle_contact_motion", "0:0,0,0;1:0,0,0.001;2:0.5,0,0.001", "-steps", "0,1,1.5,2",
                    "-friction_contact", "0.3", "-ssstar_progress", "0", "-o", path))
        with h5py.File(path, "r") as f:
            y, gap, held = f["contact_faces/vertices"][:], f["contact_faces/gap"][:], f["contact_faces/state"][:] == -1
        y = y[held]
        exact = np.linalg.norm(y - centre - d, axis=1) - 1
        n = (y - centre) / np.linalg.norm(y - centre, axis=1)[:, None]
        first_order = np.linalg.norm(y - centre, axis=1) - 1 - n @ d
        expect(held.sum() == 3 and np.abs(first_order - exact).max() > 0.01, "%d ranks: %d held face vertices, first-order off by %g" % (ranks, held.sum(), np.abs(first_order - exact).max()))
        expect(np.abs(gap[held] - exact).max() <= 1e-12, "%d ranks: the held vertices' gap %s against the distance to the moved ball %s" % (ranks, gap[held], exact))
