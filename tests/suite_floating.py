"""Bodies held by contact alone (docs/derivation.md section 14): no spring, no Dirichlet condition, on both paths
(-snes_ssstar_reduction direct and none) and 1 and 2 ranks. A block on a slope that friction holds and one it cannot
hold (no equilibrium: an early exit naming the body and its direction, also on a load path), a ball squeezed between
two plates (Hertz at both, equal forces), a stack of two floating blocks, the least-norm solution of a frictionless
stack, a push beyond phi N on a pair's slider, bodies nothing holds refused by name."""
import math
import os
import re
import time

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
SUMMARY = re.compile(r"summary: nodes (\d+) contact (\d+) .* iterations (\d+) states L/M1/M2/M3\+/M3-/M4/LS ([\d/]+) (\S+)")
NOEQ = re.compile(r"no equilibrium: the body of volume group \"(\w+)\" .* slides away along \(([-\d.e+]+), ([-\d.e+]+), ([-\d.e+]+)\): .* \(([-\d.e+]+) of the load")
PATHS = [(red, ranks) for red in ("direct", "none") for ranks in (1, 2)]
ALPHA = math.radians(20)
DOWNHILL = np.array([math.cos(ALPHA), 0, -math.sin(ALPHA)])


def scene(name, *extra):
    return ["-options_file", os.path.join(ROOT, "scenes", name + ".opts")] + list(extra)


def contact(args, h5, ranks=1, expect_rc=0):
    out = run(mpiexec(ranks, CONTACT, *args, "-o", os.path.join(OUT, h5)), expect_rc=expect_rc)
    m = SUMMARY.search(out)
    expect(m is not None, "no summary", out)
    if expect_rc == 0:
        expect(m.group(5).startswith("CONVERGED"), "not converged", out)
    return out, m, h5py.File(os.path.join(OUT, h5), "r")


def group_force(f, group):
    c = f["contact"]
    names = c["group"].attrs["names"]
    names = [n.split("->")[0] for n in (names.decode() if isinstance(names, bytes) else str(names)).split(",")]
    mine = c["group"][:] == names.index(group)
    return c["reaction"][:][mine].sum(0)


@test("docs/derivation.md section 14 holds (tests/floating_check.py, numpy, independent of the C code): the Schur complement of a semidefinite K has ker P = R_C and equals FETI's (Pi F Pi)^+ with f = P (d + F l0) - l0 to 1e-10; the balance (14.4) of a rigid block on a 20 degree slope is exact for phi = 0.5 and leaves sin(alpha - arctan phi) unbalanced for phi = 0.3, 0 with the residual as Farkas' certificate; the proximal Newton step (14.5) on a semidefinite P converges where the plain matrix is singular, keeps the free motion's part zero (14.6) and gives the limit of P + eps I")
def floating_derivation():
    out = run([PYTHON, os.path.join(ROOT, "tests", "floating_check.py")])
    expect(out.count("PASS") == 3 and "FAIL" not in out, "tests/floating_check.py", out)


@test("a block on a slope of 20 degrees held by contact alone (scenes/slope.opts at level 2: no spring, phi = 0.5 > tan 20 deg): it stays; the contact resultant is its weight (0, 0, 9810) to 1e-6 relative; its displacement is the limit of the spring-held block (scenes/incline.opts) as the spring vanishes: springs k = 1 and 0.01 differ from it by about 1.2e-7 and 1.2e-9 of its largest displacement, in proportion to k (ratio 100 within 10 %); the Coulomb law at every node (check_solution.py); direct and none, 1 and 2 ranks agree to 1e-8")
def floating_slope_stays():
    ref = None
    for red, ranks in PATHS:
        out, m, f = contact(scene("slope", "-level", "2", "-snes_ssstar_reduction", red, "-snes_rtol", "1e-13"), "floating_slope_%s_%d.h5" % (red, ranks), ranks)
        force = f["contact/reaction"][:].sum(0)
        expect(np.abs(force - [0, 0, 9810]).max() <= 1e-6 * 9810, "%s %d: contact resultant %s, not the weight" % (red, ranks, force), out)
        u = f["fields/displacement"][:]
        if ref is None:
            ref = u
        expect(np.abs(u - ref).max() <= 1e-8 * np.abs(ref).max(), "%s %d: displacement differs from direct on 1 rank by %.2e" % (red, ranks, np.abs(u - ref).max() / np.abs(ref).max()))
        run(CHECK + ["coulomb", os.path.join(OUT, "floating_slope_%s_%d.h5" % (red, ranks))])
    diff = []
    for k in ("1", "0.01"):
        out, m, f = contact(scene("incline", "-level", "2", "-spring_top", k, "-snes_rtol", "1e-13"), "floating_slope_spring_%s.h5" % k)
        diff.append(np.abs(f["fields/displacement"][:] - ref).max() / np.abs(ref).max())
    expect(1e-8 <= diff[0] <= 1e-6 and 90 <= diff[0] / diff[1] <= 110, "spring k = 1, 0.01: the displacements differ from the floating block's by %.2e, %.2e (expected about 1.2e-7 and 100 times less)" % tuple(diff))


@test("no equilibrium on a slope steeper than the friction angle (scenes/slope.opts at level 2 with phi = 0.3 and 0 < tan 20 deg): exit status 2 before any iteration, within 30 s, the reason DIVERGED_DTOL (NO_EQUILIBRIUM) in the file, the line naming the body \"block\" and its sliding direction downhill (cos 20, 0, -sin 20) to 1e-3, the unbalanced part of its load sin(20 deg - arctan phi) to 1e-3 relative (the friction cone's distance from the weight); direct and none, 1 and 2 ranks (phi = 0: 1 rank)")
def floating_slope_slides():
    for phi in (0.3, 0.0):
        for red, ranks in (PATHS if phi else [("direct", 1), ("none", 1)]):
            t0 = time.time()
            out, m, f = contact(scene("slope", "-level", "2", "-snes_ssstar_reduction", red, "-friction_bottom", str(phi)), "floating_slides_%s_%d.h5" % (red, ranks), ranks, expect_rc=NOT_CONVERGED)
            expect(time.time() - t0 <= 30, "%s %d: took %.1f s" % (red, ranks, time.time() - t0), out)
            expect(m.group(3) == "0" and m.group(5) == "DIVERGED_DTOL", "%s %d: %s iterations, %s" % (red, ranks, m.group(3), m.group(5)), out)
            attr = f.attrs["converged_reason"]
            expect((attr.decode() if isinstance(attr, bytes) else attr) == "DIVERGED_DTOL", "the file says %s" % attr)
            n = NOEQ.search(out)
            expect(n is not None and n.group(1) == "block", "%s %d: no line naming the block" % (red, ranks), out)
            d = np.array([float(n.group(k)) for k in (2, 3, 4)])
            expect(np.abs(d - DOWNHILL).max() <= 1e-3, "%s %d: direction %s, not downhill %s" % (red, ranks, d, DOWNHILL), out)
            expected = math.sin(ALPHA - math.atan(phi))
            expect(abs(float(n.group(5)) / expected - 1) <= 1e-3, "%s %d: unbalanced part %s, not sin(alpha - arctan phi) = %.4g" % (red, ranks, n.group(5), expected), out)


@test("a load path that loses its equilibrium stops at that step and says so (scenes/slope.opts at level 2, phi = 0.5: pushed downhill by 0, 400, 800 Pa on its top, the friction holds up to 627 Pa): steps 1 and 2 converge, step 3 ends with 'no equilibrium' without halving, exit status 2, the file's failed_step 2 and failed_time 2; direct and none, 1 and 2 ranks", full=True)
def floating_path_stops():
    push = ";".join("%d:%g,0,%g" % (t, p * DOWNHILL[0], p * DOWNHILL[2]) for t, p in ((0, 0), (1, 400), (2, 800)))
    for red, ranks in PATHS:
        out, m, f = contact(scene("slope", "-level", "2", "-snes_ssstar_reduction", red, "-traction_top", push), "floating_path_%s_%d.h5" % (red, ranks), ranks, expect_rc=NOT_CONVERGED)
        expect(re.search(r"step 3/3 t 2\.?: no equilibrium .*: the path stops here", out) is not None and "retried" not in out, "%s %d: step 3 does not stop at once" % (red, ranks), out)
        expect(len(re.findall(r"^step [12]/3 .* iterations", out, re.M)) == 2, "%s %d: steps 1 and 2 not converged" % (red, ranks), out)
        expect(f.attrs["failed_step"] == 2 and f.attrs["failed_time"] == 2, "%s %d: failed_step %s, failed_time %s" % (red, ranks, f.attrs["failed_step"], f.attrs["failed_time"]))
        expect(NOEQ.search(out) is not None, "%s %d: no line naming the body" % (red, ranks), out)


@test("a ball squeezed between two rigid plates, held by them alone (scenes/squeeze.opts, level 1: R = 10, the upper plate moved down by 0.2, frictionless): the two contact forces equal to 1e-8 relative (the ball's equilibrium), each contact's radius and peak pressure within 3 % of Hertz's for its force (measured +1.1 %, +2.3 % below, +0.7 %, +2.6 % above); direct and none, 1 and 2 ranks agree to 1e-7", full=True)
def floating_squeeze():
    import scene_answers
    ref = None
    for red, ranks in PATHS:
        h5 = "floating_squeeze_%s_%d.h5" % (red, ranks)
        out, m, f = contact(scene("squeeze", "-snes_ssstar_reduction", red), h5, ranks)
        bottom, top = group_force(f, "bottom_cap"), group_force(f, "top_cap")
        expect(abs(bottom[2] + top[2]) <= 1e-8 * bottom[2] and bottom[2] > 3e4, "%s %d: forces %g below, %g above" % (red, ranks, bottom[2], -top[2]), out)
        for g in ("bottom_cap", "top_cap"):
            h = scene_answers.hertz(os.path.join(OUT, h5), group=g)
            expect(abs(h["a_error"]) <= 0.03 and abs(h["p0_error"]) <= 0.03, "%s %d %s: a %+.3f, p0 %+.3f against Hertz" % (red, ranks, g, h["a_error"], h["p0_error"]))
        rn = f["contact/reaction"][:][:, 2]
        if ref is None:
            ref = rn
        expect(np.abs(rn - ref).max() <= 1e-7 * np.abs(ref).max(), "%s %d: contact forces differ from direct on 1 rank by %.2e" % (red, ranks, np.abs(rn - ref).max() / np.abs(ref).max()))


@test("a stack of two blocks under gravity, both held by contact alone (scenes/stack.opts at level 1: the base on the plane, the lid on the base through a contact pair, phi = 0.5): the plane carries both weights (0, 0, 9810), the pair the lid's (0, 0, 4905), to 1e-6 relative; direct and none, 1 and 2 ranks agree to 1e-8")
def floating_stack():
    ref = None
    for red, ranks in PATHS:
        out, m, f = contact(scene("stack", "-level", "1", "-snes_ssstar_reduction", red, "-snes_rtol", "1e-12"), "floating_stack_%s_%d.h5" % (red, ranks), ranks)
        for g, w in (("bottom", 9810), ("lid_bottom", 4905)):
            force = group_force(f, g)
            expect(np.abs(force - [0, 0, w]).max() <= 1e-6 * w, "%s %d: %s carries %s, not (0, 0, %g)" % (red, ranks, g, force, w), out)
        u = f["fields/displacement"][:]
        if ref is None:
            ref = u
        expect(np.abs(u - ref).max() <= 1e-8 * np.abs(ref).max(), "%s %d: displacement differs from direct on 1 rank by %.2e" % (red, ranks, np.abs(u - ref).max() / np.abs(ref).max()))


@test("frictionless under vertical gravity (scenes/stack.opts at level 1 with -snes_ssstar_friction 0): each block's sliding along the plane and turning about the vertical are resisted by nothing, and the least-norm solution is returned: per block, the sums of u_x and of u_y and the turning sum (x - xc) u_y - (y - yc) u_x vanish to 1e-10 of its displacement's scale; the forces are the weights; direct and none, 1 and 2 ranks agree to 1e-8")
def floating_least_norm():
    ref = None
    for red, ranks in PATHS:
        out, m, f = contact(scene("stack", "-level", "1", "-snes_ssstar_friction", "0", "-snes_ssstar_reduction", red, "-snes_rtol", "1e-12"), "floating_frictionless_%s_%d.h5" % (red, ranks), ranks)
        x, u = f["geometry/vertices"][:], f["fields/displacement"][:]
        scale = np.abs(u).max() * len(u)
        lid = np.zeros(len(x), bool)  # the nodes of cells above the interface z = 0.5
        for tet in f["viz/topology/cells"][:]:
            if x[tet, 2].max() > 0.5 + 1e-9:
                lid[tet] = True
        for body in (~lid, lid):
            xc = x[body].mean(0)
            turning = ((x[body, 0] - xc[0]) * u[body, 1] - (x[body, 1] - xc[1]) * u[body, 0]).sum()
            sums = (u[body, 0].sum(), u[body, 1].sum(), turning / np.abs(x[body] - xc).max())
            expect(max(abs(s) for s in sums) <= 1e-10 * scale, "%s %d: the free motions' parts %s are not zero (scale %g)" % (red, ranks, sums, scale))
        expect(abs(group_force(f, "bottom")[2] - 9810) <= 1e-6 * 9810, "%s %d: the plane does not carry the weight" % (red, ranks), out)
        if ref is None:
            ref = u
        expect(np.abs(u - ref).max() <= 1e-8 * np.abs(ref).max(), "%s %d: displacement differs from direct on 1 rank by %.2e" % (red, ranks, np.abs(u - ref).max() / np.abs(ref).max()))


def without_spring(name):
    """the options of scenes/NAME.opts without its -spring_<G> lines: the body held by contact alone"""
    lines = [line.split() for line in open(os.path.join(ROOT, "scenes", name + ".opts")) if line.strip() and not line.startswith("#")]
    return [w for line in lines if not line[0].startswith("-spring") for w in line]


@test("orthotropic friction on a body held by contact alone (scenes/orthotropic.opts without its spring: phi_1 = 0.3 along x, phi_2 = 0.6 across, pressed by 10): the balance uses the law's elliptic cone, not a circle: pushed along x by 4 (> 3) no equilibrium, direction +x; across by 4 (< 6) it holds and converges; across by 7 (> 6) no equilibrium, direction +y; direct and none", full=True)
def floating_orthotropic():
    base = without_spring("orthotropic")
    for red in ("direct", "none"):
        for push, exists, direction in (("4,0,-10", False, (1, 0, 0)), ("0,4,-10", True, None), ("0,7,-10", False, (0, 1, 0))):
            out, m, f = contact(base + ["-traction_top", push, "-snes_ssstar_reduction", red], "floating_ortho_%s.h5" % red, 1, expect_rc=0 if exists else NOT_CONVERGED)
            if exists:
                continue
            n = NOEQ.search(out)
            expect(m.group(3) == "0" and n is not None, "%s, push %s: not stopped early" % (red, push), out)
            d = np.array([float(n.group(k)) for k in (2, 3, 4)])
            expect(np.abs(d - direction).max() <= 1e-3, "%s, push %s: direction %s" % (red, push, d), out)


SLIDER = ["-geo", "meshes/slider.geo", "-level", "1", "-E", "1", "-nu", "0.3", "-traction_slider_top", "0.008,0,-0.01", "-contact", "slider_bottom",
          "-contact_pair_slider_bottom", "base_top", "-friction_slider_bottom", "0.5"]


@test("a push beyond phi N on a body held by nothing else (the slider of scenes/slider.opts without its spring, on the held base: push 0.008 > 0.5 x 0.01): no equilibrium, exit status 2 before any iteration, the line naming the body \"slider\" and its direction +x (to 1e-2); direct and none, 1 and 2 ranks", full=True)
def floating_push():
    for red, ranks in PATHS:
        out, m, f = contact(SLIDER + ["-dirichlet", "bottom", "-snes_ssstar_reduction", red], "floating_push_%s_%d.h5" % (red, ranks), ranks, expect_rc=NOT_CONVERGED)
        n = NOEQ.search(out)
        expect(m.group(3) == "0" and n is not None and n.group(1) == "slider", "%s %d: not stopped naming the slider" % (red, ranks), out)
        d = np.array([float(n.group(k)) for k in (2, 3, 4)])
        expect(np.abs(d - [1, 0, 0]).max() <= 1e-2, "%s %d: direction %s, not +x" % (red, ranks, d), out)


@test("a body nothing can hold is refused by name, on 1 and 2 ranks: two bodies joined by a contact pair with no obstacle, Dirichlet condition or spring (the first in file order, \"base\", is named); a body without any contact group, spring or Dirichlet condition (\"slider\" of the slider mesh without -contact)")
def floating_refused():
    cases = ((SLIDER, '"base"'), (SLIDER[:10] + ["-dirichlet", "bottom"], '"slider"'))
    for args, name in cases:
        for ranks in (1, 2):
            out = run(mpiexec(ranks, CONTACT, *args), expect_rc=1)
            expect("The body of volume group %s" % name in out and "is held by nothing" in out, "%d ranks: not refused naming %s" % (ranks, name), out)
