"""The law's degenerate points (issue 34, docs/derivation.md section 19, docs/guide/kinks.md): steps that land exactly on
the onset of sliding or of sliding back, on touching and on release, statically and on load paths, stiff and soft, on
both paths (-snes_ssstar_reduction direct and none); the preconditioner fallback where CG finds the multigrid
indefinite; the unbalanced part of a body without equilibrium on another floating body (issue 31). bench/robust.py
--family degenerate sweeps the family (DEGENERATE) on 1-4 ranks and prints the table; here members of it."""
import math
import os
import re
import sys

import h5py

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

sys.path.insert(0, os.path.join(ROOT, "bench"))
import robust  # noqa: E402
import scene_answers  # noqa: E402

robust.OUT = os.path.join(OUT, "robust")  # the members' files among the tests' own
os.makedirs(robust.OUT, exist_ok=True)
from robust import DEGENERATE  # noqa: E402

CONTACT = os.path.join(ROOT, "examples", "contact")
STIFFER = "onset of sliding back, stiffer (E/k = 2e7), level 1, 20 steps"
ISSUE = "onset of sliding back, stiff (E/k = 5e6), 20 steps (issue 34's)"
TOUCHING = "touching on a path: the plane raised by exactly its gap, the block sheared, then pressed, stiff (E/k = 1e7)"
NOEQ = re.compile(r"no equilibrium: the body of volume group \"(\w+)\" .* slides away along \(([-\d.e+]+), ([-\d.e+]+), ([-\d.e+]+)\): .* \(([-\d.e+]+) of the load")


def lawful(r):
    """converged at the defaults, the law in the file at every step (check_solution); the error to the exact discrete
    solution is the point's conditioning where it exceeds 1e-6 (docs/derivation.md section 19)"""
    return r["reason"].startswith("CONVERGED") and bool(r.get("law_ok"))


def members(names, ranks, exact=True):
    """each member on both paths at the defaults: converged and lawful, and (exact) within 1e-6 of the exact discrete
    solution at every step"""
    for name in names:
        for r in ranks:
            result = robust.run_member(name, DEGENERATE[name], r)
            expect(result is not None, "%s: the reference did not converge" % name)
            for path, res in result.items():
                good = robust.passed(res) if exact else lawful(res)
                expect(good, "%s, %s, %d ranks: %s" % (name, path, r, robust.cell(res)))


def step_reasons(path, ranks):
    """the reasons of the steps of the stiffer block's file of that path and rank count"""
    with h5py.File(os.path.join(robust.OUT, "%s_%s_%d.h5" % (robust.tag(STIFFER), path, ranks)), "r") as f:
        return f["steps/time"][:], f["steps/reason"][:]


@test("docs/derivation.md section 19 holds (tests/kinks_check.py, numpy, independent of the C code): at the exact onset of sliding back of a P1 model of the stiff block on its spring the slide is (A/k)^(1/3) (19.1) to 5 % for k = 10, 40, 160; the iteration creeps there, at least 5 parallel Newton steps each 3/2 times the one before (19.2), then converges quadratically; larger gamma does not remove it, and ||z||, rho and the natural level function all grow along a longer step; the floor rule (19.4) counts at most one stall on the creep where 'rho not halved' counts more than 3, and more than 3 at the round-off floor; (19c.1): the same block (E/k = 1e7) pressed onto the plane it touches converges with exact steps, but from the elastic trial with its slide off by 1e-12 .. 1e-6 (more than the nodes' elastic slips) the plain iteration cycles between slides of +-phi N/k, and with the stuck element at twice-reversed slips it converges")
def kinks_derivation():
    page = open(os.path.join(ROOT, "docs", "derivation.md")).read()
    for equation in ("(19.1)", "(19.2)", "(19.3)", "(19.4)", "(19c.1)"):
        expect(equation in page, "docs/derivation.md has no equation %s" % equation)
    out = run([PYTHON, os.path.join(ROOT, "tests", "kinks_check.py")])
    expect(out.count(" ok (") == 4 and "FAILED" not in out, "tests/kinks_check.py", out)


@test("the stiff block of issue 34 with a stiffer spring (level 1, E = 2e8, k = 10 per unit area, E/k = 2e7) pressed by 1, sheared to 0.8 against phi = 0.5, released and sheared back in 20 steps: the step t = 3.25 lands exactly on the onset of sliding back (it ended DIVERGED_LOCAL_MIN, LAW_STALLED, on both paths and every halving); every step converges at the defaults, the file satisfies the law at every step and lies within 1e-6 of the exact discrete solution, direct and none, 1 rank")
def kinks_stiff_block():
    members([STIFFER], (1,))
    for path in ("direct", "none"):
        times, reasons = step_reasons(path, 1)
        expect(len(times) == 21 and abs(times[13] - 3.25) < 1e-12 and (reasons > 0).all(), "%s: steps %s, reasons %s" % (path, times, reasons))


@test("the two-cycle of a slow mode at touching (docs/derivation.md section 19c): the stiff block (level 1, E = 2e8, k = 20 per unit area, E/k = 1e7) whose plane is raised by exactly its gap, the block sheared by 0.1, then pressed by the plane's further 1e-4 (it ended DIVERGED_MAX_IT on the whole body, DIVERGED_LOCAL_MIN at level 2: the slide flipped by +-phi N/k while every node slid): on the whole body the sliding nodes whose slip reverses twice are stuck at the kink (-snes_view counts them), every step converges at the defaults on both paths, 1 rank, the law holds at every step of both files and the whole body lies within 1e-6 of the dense route")
def kinks_touching_pressed():
    files = {}
    for red in ("direct", "none"):
        files[red] = os.path.join(OUT, "kinks_touching_pressed_%s.h5" % red)
        out = run([CONTACT, "-geo", os.path.join(ROOT, "meshes", "block.geo"), "-level", "1"] + DEGENERATE[TOUCHING][4:] + ["-snes_ssstar_reduction", red, "-snes_view", "-o", files[red]])
        expect("CONVERGED" in out.split("summary:")[-1], "%s: not converged" % red, out)
        stuck = [int(n) for n in re.findall(r"nodes stuck at a reversed slip (\d+)", out)]
        expect(red == "direct" or sum(stuck) > 0, "%s: no node stuck at a reversed slip (the case of section 19c is not met)" % red, out)
        law = run(CHECK + ["law", files[red], "--steps"])
        expect("VIOLATED" not in law and law.count(" ok") >= 4, "%s: the law" % red, law)
    cmp = run(CHECK + ["compare", files["direct"], files["none"], "--steps", "--tol", "1e-6"])  # exit status 1 if they differ
    expect("DIFFERENT" not in cmp, "the whole body against the dense route", cmp)


@test("polishing at a loose tolerance (docs/derivation.md section 19b): scenes/mindlin.opts at level 2, -snes_rtol 1e-2, 2 ranks, auto choosing the whole body, and at level 1, -snes_rtol 1e-1, 1 rank, the whole body, meet the ||z|| threshold with the stick-slip annulus still moving (both ended DIVERGED_LOCAL_MIN, after 23 and 26 iterations: whole polishing steps crept along the block's soft spring, ||z|| 2.2e-3 -> 1.3 at level 2, every sticking node sliding); they converge, each file satisfies the law to its rtol and the outermost sticking node lies within 0.05 (level 2) and 0.1 (level 1: half its mesh size at the pole) of c = a (1 - Q/(phi P))^(1/3)")
def kinks_loose_polishing():
    for level, rtol, ranks, route, near in ((2, "1e-2", 2, "auto", 0.05), (1, "1e-1", 1, "none", 0.1)):
        h5 = os.path.join(OUT, "kinks_mindlin_loose_%d.h5" % level)
        out = run(mpiexec(ranks, CONTACT, "-options_file", os.path.join(ROOT, "scenes", "mindlin.opts"), "-level", str(level), "-snes_rtol", rtol,
                          "-snes_ssstar_reduction", route, "-o", h5))
        expect("P never formed (reduction none" in out, "level %d: not on the whole body: the case is not the one of section 19b" % level, out)
        expect("CONVERGED" in out.split("summary:")[-1], "level %d: not converged" % level, out)
        law = run(CHECK + ["law", h5, "--tol", rtol])
        expect("VIOLATED" not in law, "level %d: the law at %s" % (level, rtol), law)
        c = scene_answers.stick_radius(h5, 0.3, 2.1e5)
        expect(abs(c["stick_outer"] - c["c"]) <= near, "level %d: stick radius %s" % (level, c))


@test("the stiffer block's 20 steps (E/k = 2e7, level 1) on 2 ranks, and issue 34's own stiff block (level 2, k = 40 per unit area, E/k = 5e6) and the same at E/k = 1e7 (k = 20) on 1 and 2 ranks: every step converges at the defaults on both paths, the law holds at every step of the file and the answer lies within 1e-6 of the exact discrete solution", full=True)
def kinks_stiff_blocks_full():
    members([STIFFER], (2,))
    members([ISSUE, "onset of sliding back, stiff (E/k = 1e7), 20 steps"], (1, 2))


@test("members of the degenerate family at the defaults, both paths, 1 rank: the block touching its plane with no normal load and sheared (soft), a ball pressed into a held block and lifted back to exactly touching: converged, the law in the file at every step, within 1e-6 of the exact discrete solution (the exactly touching nodes' reactions compared at the law's force scale); the static exact onset of a stiff block (E/k = 1e7): converged and lawful", full=True)
def kinks_family():
    members(["touching, static: zero gap, no normal load, sheared by 0.1, soft",
             "release on a path: a ball pressed 0.02 into a held block and lifted back to exactly touching, 4 steps"], (1,))
    members(["onset of sliding, static: sheared by exactly phi P, stiff (E/k = 1e7)"], (1,), exact=False)


@test("the rest of the degenerate family on 1 and 2 ranks, both paths: converged at the defaults and the law at every step of the file", full=True)
def kinks_family_full():
    done = {STIFFER, ISSUE, "onset of sliding back, stiff (E/k = 1e7), 20 steps"}
    members([name for name in DEGENERATE if name not in done], (1, 2), exact=False)


@test("the unbalanced part of a body without equilibrium is that of its own load (issue 31): the lid of scenes/stack.opts under gravity tilted by 20 degrees, phi = 0.3 < tan 20 on the lid, 0.5 under the base: no equilibrium, the line names \"lid\", the direction +x, and sin(alpha - arctan phi) = 0.0576 of its load to 1e-3 (0.0442 was printed: of both blocks' loads), direct and none, 1 rank; direct, 2 ranks")
def kinks_unbalanced_lid():
    a = math.radians(20)
    tilted = "%.9g,0,%.9g" % (9.81 * math.sin(a), -9.81 * math.cos(a))
    expected = math.sin(a - math.atan(0.3))
    for red, ranks in (("direct", 1), ("none", 1), ("direct", 2)):
        out = run(mpiexec(ranks, CONTACT, "-options_file", os.path.join(ROOT, "scenes", "stack.opts"), "-gravity", tilted, "-friction_bottom", "0.5",
                          "-friction_lid_bottom", "0.3", "-snes_ssstar_reduction", red), expect_rc=NOT_CONVERGED)
        m = NOEQ.search(out)
        expect(m is not None and m.group(1) == "lid", "%s %d: no line naming the lid" % (red, ranks), out)
        expect(abs(float(m.group(2)) - 1) <= 1e-3 and abs(float(m.group(5)) / expected - 1) <= 1e-3,
               "%s %d: direction (%s, %s, %s), unbalanced %s, not sin(alpha - arctan phi) = %.4g" % (red, ranks, m.group(2), m.group(3), m.group(4), m.group(5), expected), out)


@test("the whole body's CG finds GAMG indefinite on the frictionless stack on 4 ranks (DIVERGED_INDEFINITE_PC: the solve ended DIVERGED_LINEAR_SOLVE before its first iteration): the step is solved again by GMRES on the same multigrid and every later one too, -info logs it, -snes_view counts it; the solve converges and its file satisfies the law")
def kinks_indefinite_pc():
    h5 = os.path.join(OUT, "stack_indefinite.h5")
    out = run(mpiexec(4, CONTACT, "-options_file", os.path.join(ROOT, "scenes", "stack.opts"), "-snes_ssstar_friction", "0", "-snes_ssstar_reduction", "none",
                      "-snes_view", "-info", ":snes", "-o", h5))
    expect("CG stopped with DIVERGED_INDEFINITE_PC" in out and "solved again by GMRES" in out, "no fallback logged", out)
    expect(re.search(r"CG stopped on an indefinite multigrid \(DIVERGED_INDEFINITE_PC\) in \d+ steps? since the set-up", out) is not None, "-snes_view says nothing of it", out)
    expect("CONVERGED" in out.split("summary:")[-1], "not converged", out)
    law = run(CHECK + ["law", h5])
    expect(" ok " in law and "VIOLATED" not in law, "the law", law)
