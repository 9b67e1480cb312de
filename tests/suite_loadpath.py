"""Load paths (issue 19): the incremental friction problem of docs/derivation.md sections 10-11 checked in numpy, and the
load-history parser (include/ssstarhistory.h) on hand-computed cases and every refusal."""
import os
import re

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)


@test("docs/derivation.md sections 10-11 hold (tests/loadpath_check.py, numpy, independent of the C code): the semismooth* iteration with the offsets (10.4) equals the incremental law solved by Tresca fixed points on the dual to 1e-10 at every step of press/shear/release/reverse/release, on the reduced problem and on the whole body, with obstacles (tilted, moving) and pair points, Coulomb, Tresca and frictionless nodes; the block on a spring ends at +-(Q - phi P)/k (11.2) with the phases of (11.1); displacement-controlled sliding gives T = phi N to 1e-12 and sticks when moved back (11.3); a proportional path without gaps equals the static answers to 1e-10 (10.8) and with gaps differs exactly where (10.7) fails; the shifted iteration converges quadratically; the Mindlin-Deresiewicz loop area equals (11.9)")
def loadpath_derivation():
    page = open(os.path.join(ROOT, "docs", "derivation.md")).read()
    for equation in ("(10.4)", "(10.5)", "(10.7)", "(10.8)", "(10.9)", "(11.1)", "(11.3)", "(11.6)", "(11.9)", "(11.11)"):
        expect(equation in page, "docs/derivation.md has no equation %s" % equation)
    out = run([PYTHON, os.path.join(ROOT, "tests", "loadpath_check.py")])
    expect(out.count("PASS") == 8 and "FAIL" not in out, "tests/loadpath_check.py", out)


@test("load histories (include/ssstarhistory.h, tests/test_history): the issue's example, a plain vector, spaces, exponents, negative times, one component, a single knot and a value of 1000 knots parse to the hand-computed knots; evaluation is linear between knots, constant outside them and exact at them; the knots of several histories merge (1 and 1.0 once); -steps N gives the first knot and N equal steps ending exactly at the last, -steps t1,t2,... the times; every malformed value (empty, no time, not a number, NaN, Inf, wrong count, times not increasing, an empty knot, a count 0, negative (-3), fractional (2.5, 2.0) or without a time span) is refused with a message naming the option and the knot or time, leaving nothing allocated (-malloc_dump)")
def history_parser():
    out = run([os.path.join(ROOT, "tests", "test_history")])
    expect("OK: 0 failures" in out, "tests/test_history", out)


@test("the solver's offsets (SNESSSStarSetContactOffsets, tests/test_offsets): the whole body of loadpath_check.py's check 1 (tilted frames, gaps, a moving obstacle, pair points with master weights, Coulomb, Tresca and frictionless nodes; press, shear, release, reverse, release in 21 steps, each step's offsets (10.4) from the previous solution) equals numpy's answer to 1e-9 at every step (measured 5e-13) on the dense route (direct) and the whole body (none), 1, 2 and 3 ranks (one rank without contact points); the reduction is set up once for the whole path", full=True)
def offsets_solver():
    data = os.path.join(OUT, "loadpath_offsets.bin")
    run([PYTHON, os.path.join(ROOT, "tests", "loadpath_check.py"), "--write", data])
    for red in ("direct", "none"):
        for ranks in (1, 2, 3):
            out = run(mpiexec(ranks, os.path.join(ROOT, "tests", "test_offsets"), "-f", data, "-snes_ssstar_reduction", red, "-snes_rtol", "1e-13"))
            m = re.search(r"max \|u - u_numpy\|/\|u_numpy\| = (\S+), set-ups of the reduction: (\d+)", out)
            expect(m is not None, "%s on %d ranks: no result line" % (red, ranks), out)
            expect(float(m.group(1)) <= 1e-9, "%s on %d ranks: the steps differ from numpy's by %s" % (red, ranks, m.group(1)), out)
            expect(int(m.group(2)) == 1, "%s on %d ranks: the reduction was set up %s times for one path" % (red, ranks, m.group(2)), out)


# ---------------------------------------------------------------------------------------------------------------------
# examples/contact on load paths: the known answers of docs/derivation.md section 11, the file, step cutting, refusals
# ---------------------------------------------------------------------------------------------------------------------
import json  # noqa: E402
import shutil  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402

import h5py  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(ROOT, "tests"))
import loadpath_check as closed  # noqa: E402  (the closed forms of docs/derivation.md section 11)

CONTACT = os.path.join(ROOT, "examples", "contact")
PATHS = [(red, ranks) for red in ("direct", "none") for ranks in (1, 2)]
STEP = re.compile(r"^step (\d+)/(\d+) t (\S+?)( \(halved \d+x\))?: load", re.M)

# (11.1)-(11.2): a nearly rigid block (E = 2e8: on its spring alone it nearly floats, E/k = 2e5, the whole body's hard case) on the plane z = 0, pressed by P = 10 (the traction on its top, area 1),
# held along x by the spring on its top (k = 1000 per unit area, area 1), sheared by Q = 7.5 > phi P = 5, released,
# sheared back and released: u_x = +-(Q - phi P)/k = +-2.5e-3 after the releases
BLOCK = ["-geo", "meshes/block.geo", "-level", "2", "-E", "2e8", "-nu", "0.3", "-spring_top", "1000", "-contact", "bottom",
         "-friction_bottom", "0.5", "-traction_top", "0:0,0,0;1:0,0,-10;2:7.5,0,-10;3:0,0,-10;4:-7.5,0,-10;5:0,0,-10"]
# (11.3): the plane z = 0 pushed 0.001 up into the block (its top held), moved 0.02 along x, then back by 1e-4
SLIDE = ["-geo", "meshes/block.geo", "-level", "2", "-E", "2.1e5", "-nu", "0.3", "-dirichlet", "top", "-contact", "bottom",
         "-friction_bottom", "0.3", "-obstacle_bottom_motion", "0:0,0,0;1:0,0,0.001;3:0.02,0,0.001;3.1:0.0199,0,0.001",
         "-steps", "0,1,1.2,1.4,1.6,1.8,2,2.2,2.4,2.6,2.8,3,3.1"]


def h5(name):
    return os.path.join(OUT, name)


def path_run(args, name, ranks=1, expect_rc=0, extra=()):
    out = run(mpiexec(ranks, CONTACT, *args, *extra, "-o", h5(name), "-malloc_dump"), expect_rc=expect_rc)
    return out, h5py.File(h5(name), "r")


@test("the block on a spring (docs/derivation.md (11.1)-(11.2), examples/contact): a nearly rigid block (E = 2e8, E/k = 2e5) pressed by P = 10, held sideways by a spring k = 1000, sheared by Q = 7.5 > phi P = 5 (-traction_top with knots), released, sheared back, released, in 25 steps (-steps 25): the mean u_x of its top follows (11.1) at every step to 1e-3 (Q - phi P)/k (measured 3e-5: the block's compliance): no motion up to Q = phi P, none on the releases, reverse sliding from Q = 2 phi P - Q; it stays at (Q - phi P)/k = 2.5e-3 after the first release and at -2.5e-3 after the second; the dissipation is phi P times the slip (5 x 2.5e-3, then 5 x 5e-3); direct and none, 1 and 2 ranks")
def loadpath_block_on_spring():
    phi, P, k = 0.5, 10.0, 1000.0
    for red, ranks in PATHS:
        out, f = path_run(BLOCK + ["-steps", "25", "-snes_ssstar_reduction", red], "loadpath_block_%s_%d.h5" % (red, ranks), ranks)
        st = f["steps"]
        t, ux, D = st["time"][:], st["groups/top/displacement"][:, 0], st["dissipation"][:]
        expect(len(t) == 26 and np.allclose(t, np.linspace(0, 5, 26)), "%s %d: steps at %s" % (red, ranks, t))
        expect(len(STEP.findall(out)) == 26, "%s %d: not one line per step" % (red, ranks), out)
        # (11.1) step by step from the same loads
        Qt = st["load"][:, 0]
        model, u = [], 0.0
        for q in Qt:
            u = closed.block_on_spring_phase(q, u, phi, P, k)[1]
            model.append(u)
        err = np.abs(ux - np.array(model)).max()
        expect(err <= 1e-3 * (7.5 - phi * P) / k, "%s %d: u_x differs from (11.1) by %.2e (%s)" % (red, ranks, err, np.c_[t, ux, model][::5]))
        at = {x: int(np.argmin(abs(t - x))) for x in (2, 3, 4, 5)}
        expect(abs(ux[at[3]] - 2.5e-3) <= 2.5e-6 and abs(ux[at[5]] + 2.5e-3) <= 2.5e-6, "%s %d: after the releases u_x = %.6g, %.6g, not +-2.5e-3" % (red, ranks, ux[at[3]], ux[at[5]]))
        expect(abs(D[at[3]] - 5 * 2.5e-3) <= 1e-3 * 0.0125 and abs(D[at[5]] - D[at[3]] - 5 * 5e-3) <= 1e-3 * 0.025, "%s %d: dissipation %s" % (red, ranks, D[[at[3], at[5]]]))


@test("displacement-controlled sliding (docs/derivation.md (11.3)): a rigid plane (-obstacle_bottom_motion) pushed 0.001 into a block held at its top, then moved 0.02 along x in 10 steps: once every node slides the tangential force on the block is phi times the normal force to 1e-6 (measured 8e-16 direct, 2e-11 none), along the motion; moved back by 1e-4 every node sticks but those at the rim (measured: 1 of 80 slides), the force drops below phi N (to 0.896 phi N); the Coulomb law holds at every node for the slip increment of the last step (tests/check_solution.py, 1e-8); direct and none, 1 and 2 ranks agree to 2e-6 (harness.AGREE)", full=True)
def loadpath_displacement_sliding():
    ref = None
    for red, ranks in PATHS:
        out, f = path_run(SLIDE + ["-snes_ssstar_reduction", red], "loadpath_slide_%s_%d.h5" % (red, ranks), ranks)
        st = f["steps"]
        T, N, t = st["tangential_force"][:], st["normal_force"][:], st["time"][:]
        i3, last = int(np.argmin(abs(t - 3))), len(t) - 1
        ratio = T[i3, 0] / N[i3]
        expect(abs(ratio - 0.3) <= 1e-6 and abs(T[i3, 1]) <= 1e-6 * N[i3], "%s %d: T/N = %.9g at t = 3, not 0.3 along x" % (red, ranks, ratio), out)
        expect(st["sticking"][i3] == 0 and st["sliding"][i3] > 0, "%s %d: not every touching node slides at t = 3" % (red, ranks))
        expect(T[last, 0] < 0.95 * 0.3 * N[last], "%s %d: moved back, T/N = %.4g" % (red, ranks, T[last, 0] / N[last]))
        expect(st["sliding"][last] <= 0.05 * (st["sliding"][last] + st["sticking"][last]), "%s %d: moved back, %d of %d touching nodes slide" % (red, ranks, st["sliding"][last], st["sliding"][last] + st["sticking"][last]))
        law = run(CHECK + ["coulomb", h5("loadpath_slide_%s_%d.h5" % (red, ranks))])
        expect("slip_increment" in law, "check_solution.py did not check the slip increment", law)
        u = f["fields/displacement"][:]
        if ref is None:
            ref = u
        expect(np.abs(u - ref).max() <= AGREE * np.abs(ref).max(), "%s %d: differs from direct on 1 rank by %.1e" % (red, ranks, np.abs(u - ref).max()))


# Measured (bench/loadpath.py): the loop's area exceeds the half-space's closed form by 14.5 % at level 1 and 8.0 % at
# level 2, its opening by 13.9 % and 8.8 % (the mesh at the contact: a = 1.27 covered by elements of 0.2/L)
MINDLIN_TOL = 0.25


@test("Cattaneo-Mindlin loading and Mindlin-Deresiewicz unloading (docs/derivation.md (11.4)-(11.11), scenes/mindlin.opts at level 1, two bodies of one material): P, then Q: 0 -> -Q* -> Q* -> -Q* at Q* = 0.5 phi P, 10 steps per branch: the energy dissipated per cycle by trapezoids of the (Q, delta) loop and the loop's opening at Q = 0 agree with the closed forms (11.9), (11.11) within 25 % (measured +15 %, level 2 in bench/loadpath.py), the node-wise dissipation (10.9) over the cycle with the loop's area within 3 % (measured 1 %), the loop closes (delta at the cycle's end equals its start to 1e-3); 1 and 2 ranks agree to 1e-7 (the whole body, and level 2: bench/loadpath.py)", full=True)
def loadpath_mindlin():
    ref = None
    for red, ranks in (("direct", 1), ("direct", 2)):
        out, f = path_run(closed.mindlin_scene_args(1, 0.5, ROOT) + ["-snes_ssstar_reduction", red], "loadpath_mindlin_%s_%d.h5" % (red, ranks), ranks)
        m = closed.mindlin_scene_loop(f)
        expect(abs(m["s"] - 0.5) <= 0.01, "%s %d: Q*/(phi P) = %.4f" % (red, ranks, m["s"]))
        for what in ("W", "opening"):
            err = m[what] / m[what + "_closed"] - 1
            expect(0 <= err <= MINDLIN_TOL, "%s %d: %s = %.5g against the closed form %.5g (%+.1f %%)" % (red, ranks, what, m[what], m[what + "_closed"], 100 * err), out)
        expect(abs(m["D"] / m["W"] - 1) <= 0.03, "%s %d: node-wise dissipation %.5g against the loop's area %.5g" % (red, ranks, m["D"], m["W"]))
        delta = -f["steps/groups/block_top/displacement"][:, 0]
        t = f["steps/time"][:]
        expect(abs(delta[int(np.argmin(abs(t - 4)))] - delta[int(np.argmin(abs(t - 2)))]) <= 1e-3 * abs(delta).max(), "%s %d: the loop does not close" % (red, ranks))
        if ref is None:
            ref = delta
        expect(np.abs(delta - ref).max() <= 1e-7 * np.abs(ref).max(), "%s %d: the loop differs from direct on 1 rank" % (red, ranks))


def vtk_python():
    """A Python whose VTK has the XDMF reader ParaView uses (SSSTAR_VTK_PYTHON, python3, /usr/bin/python3), or None"""
    for py in (os.environ.get("SSSTAR_VTK_PYTHON"), shutil.which("python3"), PYTHON):
        if py and subprocess.call([py, "-c", "import vtk; vtk.vtkXdmfReader"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) == 0:
            return py
    return None


@test("the file of a load path (-o): /steps holds one row per step (time, iterations, reason, residual_norm, cuts, load, normal_force, tangential_force, area, sliding, sticking, separated, dissipation, groups/<G>/displacement) and /steps/<k> every step's fields (displacement; contact displacement, reaction, state, slip, slip_increment, slip_path, dissipation, final_gap, pressure, traction; contact_faces point fields); the top-level datasets are the last step's; 1 and 2 ranks write the same file (every step to 2e-6, harness.AGREE); its XDMF, read by VTK's vtkXdmfReader (what ParaView uses), is a temporal collection of the mesh and of the contact faces with the file's times, and its fields at each time are the file's and change from step to step")
def loadpath_output_file():
    files = {}
    for ranks in (1, 2):
        out, f = path_run(BLOCK, "loadpath_output_%d.h5" % ranks, ranks)
        files[ranks] = f
        st = f["steps"]
        n = len(st["time"])
        expect(n == 6 and st.attrs["count"] == 6 and np.allclose(st["time"][:], range(6)), "%d ranks: steps %s" % (ranks, st["time"][:]))
        for name, shape in (("iterations", (n,)), ("reason", (n,)), ("residual_norm", (n,)), ("cuts", (n,)), ("load", (n, 3)), ("normal_force", (n,)), ("tangential_force", (n, 3)),
                            ("area", (n,)), ("sliding", (n,)), ("sticking", (n,)), ("separated", (n,)), ("dissipation", (n,)), ("groups/top/displacement", (n, 3)), ("groups/bottom/displacement", (n, 3))):
            expect(name in st and st[name].shape == shape, "%d ranks: /steps/%s is missing or not of shape %s" % (ranks, name, shape))
        expect((st["reason"][:] > 0).all() and (st["cuts"][:] == 0).all(), "%d ranks: reasons %s, cuts %s" % (ranks, st["reason"][:], st["cuts"][:]))
        expect(np.allclose(st["load"][:, 0], [0, 0, 7.5, 0, -7.5, 0]) and np.allclose(st["load"][:, 2], [0, -10, -10, -10, -10, -10]), "%d ranks: /steps/load %s" % (ranks, st["load"][:]))
        for k in range(n):
            for name in ("fields/displacement", "contact/displacement", "contact/reaction", "contact/state", "contact/slip", "contact/slip_increment", "contact/slip_path",
                         "contact/dissipation", "contact/final_gap", "contact/pressure", "contact/traction", "contact_faces/slip", "contact_faces/state", "contact_faces/pressure"):
                expect("%d/%s" % (k, name) in st, "%d ranks: /steps/%d/%s is missing" % (ranks, k, name))
        for name in ("fields/displacement", "contact/slip", "contact/slip_increment", "contact/dissipation", "contact/state", "contact_faces/slip"):
            expect(np.array_equal(f[name][:], st["%d/%s" % (n - 1, name)][:]), "%d ranks: /%s is not the last step's" % (ranks, name))
        expect(np.allclose(f["contact/dissipation"][:].sum(), st["dissipation"][-1]), "%d ranks: the nodes' dissipation does not sum to /steps/dissipation" % ranks)
    run(CHECK + ["compare", h5("loadpath_output_1.h5"), h5("loadpath_output_2.h5"), "--steps", "--tol", str(AGREE)])
    py = vtk_python()
    expect(py is not None, "no Python with VTK's vtkXdmfReader: pip install vtk (or set SSSTAR_VTK_PYTHON)")
    steps = json.loads(run([py, os.path.join(ROOT, "tests", "xdmf_check.py"), h5("loadpath_output_2.h5").replace(".h5", ".xmf")]))
    f = files[2]
    expect([s["time"] for s in steps] == list(f["steps/time"][:]), "the XDMF's times %s are not the file's" % [s["time"] for s in steps])
    for k, s in enumerate(steps):
        mesh, faces = s["grids"]["mesh"], s["grids"]["contact"]
        expect(mesh["points"] == len(f["geometry/vertices"]) and mesh["cells"] == len(f["viz/topology/cells"]), "step %d: the mesh grid has %d points, %d cells" % (k, mesh["points"], mesh["cells"]))
        for grid, path, name in ((mesh, "fields/displacement", "displacement"), (faces, "contact_faces/slip", "slip"), (faces, "contact_faces/pressure", "pressure")):
            mean = f["steps/%d/%s" % (k, path)][:].reshape(len(f["steps/%d/%s" % (k, path)]), -1).mean(axis=0)
            expect(np.allclose(grid["means"][name], mean, rtol=1e-12, atol=1e-300), "step %d: %s in the XDMF (mean %s) is not /steps/%d/%s (mean %s)" % (k, name, grid["means"][name], k, path, mean))
    for k in range(1, len(steps)):
        expect(steps[k]["grids"]["mesh"]["means"]["displacement"] != steps[k - 1]["grids"]["mesh"]["means"]["displacement"], "the displacement of step %d is that of step %d" % (k, k - 1))


@test("step cutting (-steps_max_cuts): on the block with -snes_max_it 6 the shear step t = 2 does not converge; it is retried at its midpoint t = 1.5 (converged, written with cuts 1), then on in halved sub-steps, and after 4 halvings the path stops: exit status 2, the line 'the path stops here', the file holds every converged step and the failed step's last iterate (its reason negative), and / says failed_step (its row) and failed_time; converged_reason is the failed solve's")
def loadpath_step_cutting():
    out, f = path_run(BLOCK + ["-snes_max_it", "6"], "loadpath_cut.h5", expect_rc=NOT_CONVERGED)
    expect("step 3/6 t 2.: not converged (DIVERGED_MAX_IT), retried at t 1.5" in out and "the path stops here" in out, "no retry or no stop", out)
    st = f["steps"]
    t, cuts, reason = st["time"][:], st["cuts"][:], st["reason"][:]
    expect(t[2] == 1.5 and cuts[2] == 1 and reason[2] > 0, "the midpoint t = 1.5 is not the third row: %s %s %s" % (t, cuts, reason))
    expect(reason[-1] < 0 and (reason[:-1] > 0).all() and cuts[-1] == 4, "reasons %s, cuts %s" % (reason, cuts))
    expect(f.attrs["failed_step"] == len(t) - 1 and f.attrs["failed_time"] == t[-1], "failed_step %s, failed_time %s, steps %s" % (f.attrs.get("failed_step"), f.attrs.get("failed_time"), t))
    expect(f.attrs["converged_reason"] in ("DIVERGED_MAX_IT", b"DIVERGED_MAX_IT"), "converged_reason %s" % f.attrs["converged_reason"])


@test("a monotone proportional path without gaps gives the static answers (docs/derivation.md (10.8)): scenes/shear.opts (the block on the plane z = 0, gap 0) with -traction_top 0:0,0,0;1:3.5,0,-10 in 4 steps equals, at every step, the static solve of that load to 1e-8 (measured 1e-12; -snes_rtol 1e-12); tests/check_solution.py compare --steps lines two paths up by their times: the path in 2 steps and the one in 4 agree to 1e-8 at their 3 common times, either file first (as a path that halved a step holds the other's times and the halves between), and a path at other times (0.3) is refused")
def loadpath_proportional_static():
    base = ["-options_file", os.path.join(ROOT, "scenes", "shear.opts"), "-level", "2", "-snes_rtol", "1e-12"]
    out, f = path_run(base + ["-traction_top", "0:0,0,0;1:3.5,0,-10", "-steps", "4"], "loadpath_proportional.h5")
    for k, lam in enumerate((0.25, 0.5, 0.75, 1.0)):
        _, g = path_run(base + ["-traction_top", "%.10g,0,%.10g" % (3.5 * lam, -10 * lam)], "loadpath_static_%d.h5" % k)
        u, ref = f["steps/%d/fields/displacement" % (k + 1)][:], g["fields/displacement"][:]
        err = np.abs(u - ref).max() / np.abs(ref).max()
        expect(err <= 1e-8, "load factor %g: the path's step differs from the static solve by %.1e" % (lam, err))
    path_run(base + ["-traction_top", "0:0,0,0;1:3.5,0,-10", "-steps", "2"], "loadpath_proportional_2.h5")
    path_run(base + ["-traction_top", "0:0,0,0;1:3.5,0,-10", "-steps", "0,0.3,1"], "loadpath_proportional_other.h5")
    for a, b in (("loadpath_proportional.h5", "loadpath_proportional_2.h5"), ("loadpath_proportional_2.h5", "loadpath_proportional.h5")):
        cmp = run(CHECK + ["compare", h5(a), h5(b), "--steps", "--tol", "1e-8"])
        expect(re.search(r"file has 2 steps more \(halved steps\): compared at the \w+ file's 3 times", cmp) and "3 steps compared" in cmp, "%s against %s: not compared at the 3 common times" % (a, b), cmp)
    cmp = run(CHECK + ["compare", h5("loadpath_proportional.h5"), h5("loadpath_proportional_other.h5"), "--steps"], expect_rc=1)
    expect("the files have different steps" in cmp, "paths at different times (0.3) are compared", cmp)


@test("press, then shear between two bodies of different materials (scenes/mindlin.opts, the block 4 times stiffer: -material_block): the pressing alone already slips (Dundurs' beta != 0: nodes sliding radially at Q = 0), the path P then Q differs from the static solve of the final P and Q (the answer remembers the path), and the Coulomb law holds at every node for the last step's slip increment (tests/check_solution.py, 1e-8)")
def loadpath_two_materials():
    base = ["-options_file", os.path.join(ROOT, "scenes", "mindlin.opts"), "-material_block", "8.4e5,0.3"]
    out, f = path_run(base + ["-traction_block_bottom", "0:0,0,0;1:0,0,78.54", "-traction_block_top", "0:0,0,0;1:0,0,0;2:-11.78,0,0", "-steps", "0,1,1.25,1.5,1.75,2"], "loadpath_materials.h5")
    c = f["steps/1/contact"]
    x = f["contact/coordinates"][:]
    sliding = np.isin(c["state"][:], (1, 2))
    expect(sliding.sum() > 0, "pressing alone: no node slides (states %s)" % np.bincount(c["state"][:]))
    slip = c["slip"][:][sliding]
    radial = x[sliding, :2] / np.linalg.norm(x[sliding, :2], axis=1)[:, None]
    share = np.abs((slip[:, :2] * radial).sum(1)) / np.linalg.norm(slip, axis=1)
    expect(share.min() >= 0.9, "pressing alone: the slip is not radial (smallest radial share %.3f)" % share.min())
    _, g = path_run(base, "loadpath_materials_static.h5")
    diff = np.abs(f["contact/traction"][:] - g["contact/traction"][:]).max() / np.abs(g["contact/traction"][:]).max()
    expect(diff >= 1e-2, "the path's tangential tractions equal the static solve's (%.1e)" % diff)
    law = run(CHECK + ["coulomb", h5("loadpath_materials.h5")])
    expect("slip_increment" in law, "check_solution.py did not check the slip increment", law)


def refused(args, message, name):
    """examples/contact refuses args before any mesh work (no progress line "mesh:"): non-zero exit, the message, no
    output file"""
    path = h5("refused_loadpath_%s.h5" % name)
    for x in os.listdir(OUT):
        if x.startswith("refused_loadpath_%s." % name):
            os.remove(os.path.join(OUT, x))
    out = run([CONTACT] + args + ["-o", path], expect_rc=1)
    expect(message in out, "%s: the message %r is missing" % (name, message), out)
    expect(not [x for x in os.listdir(OUT) if x.startswith("refused_loadpath_%s." % name)], "%s: a file was left behind" % name)
    expect("mesh:" not in out, "%s: refused only after the mesh was made" % name, out)


@test("bad load paths are refused before any mesh work, naming the option: -load_steps with a history (static continuation only), a motion for a contact pair, a motion of a group not in -contact (named as the group, with the nearest contact group), a knot with two components, times that do not increase in a knot list or in -steps, -steps N without histories, a negative or fractional count (-steps -3, -steps 2.5), -steps_max_cuts -1")
def loadpath_refusals():
    block = ["-geo", "meshes/block.geo", "-level", "1", "-E", "2e7", "-nu", "0.3", "-spring_top", "1000", "-contact", "bottom"]
    mindlin = ["-options_file", os.path.join(ROOT, "scenes", "mindlin.opts")]
    for name, args, message in (
            ("load_steps", block + ["-traction_top", "0:0,0,0;1:0,0,-10", "-load_steps", "2"], "Option -load_steps scales the constant loads of a static problem"),
            ("pair_motion", mindlin + ["-obstacle_cap_motion", "0:0,0,0;1:0,0,0.1"], "Options -obstacle_cap_motion and -contact_pair_cap contradict each other"),
            ("motion_not_contact", block + ["-obstacle_nowhere_motion", "0:0,0,0;1:0,0,0.1"], 'Option -obstacle_nowhere_motion: "nowhere" is not a contact group (not in -contact; the nearest contact group is "bottom")'),
            ("motion_misspelt", block + ["-obstacle_botom_motion", "0:0,0,0;1:0,0,0.1"], 'Option -obstacle_botom_motion: "botom" is not a contact group (not in -contact; the nearest contact group is "bottom")'),
            ("knot_two_values", block + ["-traction_top", "0:0,0,0;1:0,-10"], "Option -traction_top: knot 2"),
            ("knots_decrease", block + ["-obstacle_bottom_motion", "1:0,0,0;0.5:0,0,0.1"], "the times of the knots must increase"),
            ("steps_decrease", block + ["-traction_top", "0,0,-10", "-steps", "1,0.5"], "Option -steps: the times must increase"),
            ("steps_without_history", block + ["-traction_top", "0,0,-10", "-steps", "4"], "equal steps need load histories that span a time"),
            ("steps_negative", block + ["-traction_top", "0:0,0,0;1:0,0,-10", "-steps", "-3"], "Option -steps -3: a count of equal steps is a whole number >= 1"),
            ("steps_fractional", block + ["-traction_top", "0:0,0,0;1:0,0,-10", "-steps", "2.5"], "Option -steps 2.5: a count of equal steps is a whole number >= 1"),
            ("max_cuts", block + ["-traction_top", "0:0,0,0;1:0,0,-10", "-steps_max_cuts", "-1"], "-steps_max_cuts -1: must be >= 0")):
        refused(args, message, name)


SMALL_SLIDING = re.compile(r"Step (\d+) \(t = ([-\d.e+]+)\): the obstacle of -obstacle_top \((.*?)\) moved by \(([^)]*)\) \(-obstacle_top_motion\): its first-order gap g - n\.d = (\S+) at mesh node (\d+) \(0-based, file order\) at \(([^)]*)\) is off the exact gap (\S+) by (\S+), more than -small_sliding_tol (\S+) times \|d\| = (\S+):")


@test("honest limits of small sliding (issue 23.3, -sliding small): a rigid ball (R = 2) pressed 0.02 into a block and moved 1 along it is refused at that step before any solve and file, with the obstacle, the step and the error of g - n.d against the exact gap in the message (its numbers recomputed in numpy: |x - c - d| - R, the first-order gap and the error to 1e-5, larger than -small_sliding_tol 0.01 times |d|; 1 and 2 ranks the same message); a cylinder moved across its axis likewise; pressed only, or dragged by 0.01 (0.5 % of R), it is solved; the cylinder moved 1 along its axis, a plane and a flat mesh moved 1 across the block are never refused (their first-order gap is exact); -small_sliding_tol 0.5 accepts the ball's drag; -small_sliding_tol 0 is refused", full=True)
def loadpath_small_sliding_limits():
    block = ["-geo", "meshes/block.geo", "-level", "2", "-E", "2.1e5", "-nu", "0.3", "-dirichlet", "bottom", "-contact", "top", "-friction_top", "0.3", "-ssstar_progress", "0", "-sliding", "small"]
    c, R = np.array([0.5, 0.5, 2.5]), 2.0
    ball, drag = ["-obstacle_top", "sphere:0.5,0.5,2.5,2"], ["-obstacle_top_motion", "0:0,0,0;1:0,0,-0.02;2:1,0,-0.02"]
    messages = []
    for ranks in (1, 2):
        name = "small_sliding_refused_%d" % ranks
        for x in os.listdir(OUT):
            if x.startswith(name):
                os.remove(os.path.join(OUT, x))
        out = run(mpiexec(ranks, CONTACT, *block, *ball, *drag, "-steps", "0,1,2", "-o", h5(name + ".h5")), expect_rc=1)
        m = SMALL_SLIDING.search(out)
        expect(m and m.group(1) == "3" and float(m.group(2)) == 2 and "rigid ball of radius 2" in m.group(3), "%d ranks: no refusal naming step 3 (t = 2) and the ball" % ranks, out)
        expect("step 1/" not in out and not [x for x in os.listdir(OUT) if x.startswith(name)], "%d ranks: a step was solved or a file written before the refusal" % ranks, out)
        d = np.array([float(v) for v in m.group(4).split(",")])
        x = np.array([float(v) for v in m.group(7).split(",")])
        linear, exact, error, tol, dd = (float(m.group(k)) for k in (5, 8, 9, 10, 11))
        g, n = np.linalg.norm(x - c) - R, (x - c) / np.linalg.norm(x - c)
        expect(np.allclose(d, [1, 0, -0.02]) and abs(dd - np.linalg.norm(d)) <= 1e-5, "%d ranks: the translation %s, |d| %g" % (ranks, d, dd))
        expect(abs(linear - (g - n @ d)) <= 1e-5 and abs(exact - (np.linalg.norm(x - c - d) - R)) <= 1e-5 and abs(error - abs(exact - linear)) <= 1e-5, "%d ranks: the message's gaps %g, %g, %g against numpy's %g, %g" % (ranks, linear, exact, error, g - n @ d, np.linalg.norm(x - c - d) - R))
        expect(error > tol * dd and tol == 0.01, "%d ranks: an error %g within the tolerance %g |d| was refused" % (ranks, error, tol))
        messages.append(m.group(0))
    expect(messages[0] == messages[1], "1 and 2 ranks refuse differently", "\n".join(messages))
    cylinder = ["-obstacle_top", "cylinder:0.5,0.5,2.5,0,1,0,2"]
    out = run([CONTACT] + block + cylinder + drag + ["-steps", "0,1,2"], expect_rc=1)
    expect("the obstacle of -obstacle_top (rigid cylinder" in out and "Step 3 (t = 2.)" in out, "the cylinder moved across its axis is not refused", out)
    for what, args in (("pressed", ball + ["-obstacle_top_motion", "0:0,0,0;1:0,0,-0.02"]),
                       ("dragged by 0.01", ball + drag + ["-steps", "0,1,1.01"]),
                       ("drag accepted by -small_sliding_tol 0.5", ball + drag + ["-steps", "0,1,2", "-small_sliding_tol", "0.5"]),
                       ("cylinder along its axis", cylinder + ["-obstacle_top_motion", "0:0,0,0;1:0,0,-0.02;2:0,1,-0.02"]),
                       ("plane", ["-obstacle_top", "plane:0,0,0.5,0,0,-1", "-obstacle_top_motion", "0:0,0,0;1:0,0,-0.001;2:1,0,-0.001"]),
                       ("flat mesh", ["-obstacle_top", "mesh:" + os.path.join(OUT, "small_sliding_square.msh"), "-obstacle_top_motion", "0:0,0,0;1:0,0,-0.001;2:1,0,-0.001"])):
        if what == "flat mesh":  # the two-triangle square (-10, 10)^2 at z = 0.5, oriented down (towards the block)
            with open(os.path.join(OUT, "small_sliding_square.msh"), "w") as f:
                f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 -10 -10 0.5\n2 10 -10 0.5\n3 10 10 0.5\n4 -10 10 0.5\n$EndNodes\n"
                        "$Elements\n2\n1 2 2 1 1 3 2 1\n2 2 2 1 1 4 3 1\n$EndElements\n")
        out = run([CONTACT] + block + args)
        expect("CONVERGED" in out and "first-order gap" not in out, "%s: refused or not solved" % what, out)
    out = run([CONTACT] + block + ball + drag + ["-small_sliding_tol", "0"], expect_rc=1)
    expect("-small_sliding_tol 0.: must be a positive number" in out, "-small_sliding_tol 0 is not refused", out)


@test("examples/plot_contact.py on a load path draws FILE_history.png beside the contact faces: the tangential force against the loaded group's displacement (the lines are the file's /steps/load and /steps/groups/<G>/displacement; for a moving obstacle its /steps/motion/<G> against /steps/tangential_force), the loop without its linear elastic part, the normal force against the indentation, the contact area and sliding nodes against the time")
def loadpath_plot():
    import importlib.util
    spec = importlib.util.spec_from_file_location("plot_contact", os.path.join(ROOT, "examples", "plot_contact.py"))
    plot = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(plot)
    # each test runs in its own folder: the two paths are solved here
    path_run(BLOCK, "loadpath_output_1.h5", extra=["-steps", "5"])
    path_run(SLIDE, "loadpath_slide_direct_1.h5", extra=["-snes_ssstar_reduction", "direct"])
    for name, xpath, ypath in (("loadpath_output_1.h5", "steps/groups/top/displacement", "steps/load"),
                               ("loadpath_slide_direct_1.h5", "steps/motion/bottom", "steps/tangential_force")):
        d = plot.read(h5(name))
        fig = plot.draw_history(d)
        f = h5py.File(h5(name), "r")
        line = fig.axes[0].lines[0]
        expect(np.array_equal(line.get_xdata(), f[xpath][:, 0]) and np.array_equal(line.get_ydata(), f[ypath][:, 0]), "%s: the loop is not %s against %s" % (name, ypath, xpath))
        area = [ln for ax in fig.axes for ln in ax.lines if ln.get_label() == "contact area"]
        expect(area and np.array_equal(area[0].get_ydata(), f["steps/area"][:]), "%s: no contact area against the time" % name)
    out = run([PYTHON, os.path.join(ROOT, "examples", "plot_contact.py"), h5("loadpath_output_1.h5")])
    expect(os.path.exists(h5("loadpath_output_1_history.png")) and "loadpath_output_1_history.png" in out, "no history figure", out)
