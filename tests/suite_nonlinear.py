"""-snes_type ssstar on a nonlinear residual (docs/derivation.md section 17, docs/guide/nonlinear-residuals.md): a program
of our own that links PETSc alone (tests/test_nonlinear.c: a neo-Hookean block of its own assembly, the prism's K with
a cubic stiffening), the affine declaration and its check at the solution, the contact measured at the iterates,
-snes_lag_jacobian, and the affine route's iterations unchanged."""
import math
import os
import re

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

NONLINEAR = os.path.join(ROOT, "tests", "test_nonlinear")
CONTACT = os.path.join(ROOT, "examples", "contact")
# the prism's Newton iterations before section 17 (main at 69d836b, measured with examples/prism -snes_ssstar_reduction
# R -level L): the affine route keeps them exactly
AFFINE_ITERATIONS = {(2, "direct"): 6, (2, "none"): 7, (4, "direct"): 7, (4, "none"): 8}
HOLDS = re.compile(r"^(\S+) after (\d+) iterations, (-?\d+) Jacobian evaluations, (\d+) function evaluations, (-?\d+) contact updates; "
                   r"separated/sliding/sticking (\d+)/(\d+)/(\d+); F at the free dofs (\S+), contact law violation (\S+) of the force and displacement scales: (.*)$", re.M)


def nonlinear(ranks, *args, expect_rc=0):
    """tests/test_nonlinear through -dll_append; its outcome line as a dict"""
    out = run(mpiexec(ranks, NONLINEAR, "-dll_append", LIB, "-snes_type", "ssstar", "-snes_monitor", "-snes_converged_reason", *args), expect_rc=expect_rc)
    m = HOLDS.search(out)
    expect(m is not None, "no outcome line", out)
    keys = ("reason", "its", "jacobians", "functions", "updates", "separated", "sliding", "sticking", "equilibrium", "law", "verdict")
    r = dict(zip(keys, m.groups()))
    for k in keys[1:8]:
        r[k] = int(r[k])
    r["equilibrium"], r["law"] = float(r["equilibrium"]), float(r["law"])
    r["znorms"] = [float(z) for z in re.findall(r"SNES Function norm ([0-9.eE+-]+)", out)]
    return out, r


def observed_order(znorms, floor=1e-9):
    """log(z_k+1/z_k)/log(z_k/z_k-1) of the last step above the round-off floor (relative to ||z_0||)"""
    z = [x for x in znorms if x > floor * znorms[0]]
    expect(len(z) >= 3, "too few iterates above the round-off floor to measure an order: %s" % znorms)
    return math.log(z[-1] / z[-2]) / math.log(z[-2] / z[-3])


def holds(out, r, what):
    expect(r["reason"].startswith("CONVERGED") and r["verdict"] == "the answer holds" and r["equilibrium"] <= 1e-7 and r["law"] <= 1e-7,
           "%s: %s, F at the free dofs %g, law %g (tolerance 1e-7)" % (what, r["reason"], r["equilibrium"], r["law"]), out)


@test("docs/derivation.md section 17 holds (tests/nonlinear_check.py, numpy): on F = P u + kappa u^3 - f with Coulomb friction the iteration with "
      "the Jacobian at every iterate ends at z = 0 with observed orders >= 1.8; the affine model's own solution is off F by kappa u^3 = 0.5 max|f|; "
      "the chord iteration (one Jacobian) converges to the same point linearly; a ball measured at the iterates ends at its exact gap and normal, "
      "linearly at a rate below r_n/(R k), quadratically with the normal's turning in the Newton matrix")
def nonlinear_derivation():
    out = run([PYTHON, os.path.join(ROOT, "tests", "nonlinear_check.py")])
    expect(out.count("PASS") == 5 and "FAIL" not in out, "tests/nonlinear_check.py", out)


@test("a neo-Hookean block of a program of our own (PETSc alone, the type through -dll_append; 8 x 8 x 4 cells) pressed 30 % and sheared 10 % "
      "onto a plane with Coulomb friction: converged, F = 0 at the free dofs and the law at every contact node to 1e-7 as written, sliding and "
      "sticking nodes, the Jacobian evaluated at every iterate (iterations + 1), the observed order of the last step > 1.5 (superlinear), "
      "within 8 iterations; 1 and 2 ranks agree on the iterations")
def nonlinear_block_plane():
    its = []
    for ranks in (1, 2):
        out, r = nonlinear(ranks, "-n", "8", "-press", "0.3", "-shift", "0.1")
        holds(out, r, "%d ranks" % ranks)
        expect(r["sliding"] > 0 and r["sticking"] > 0, "%d ranks: sliding %d, sticking %d" % (ranks, r["sliding"], r["sticking"]), out)
        expect(r["jacobians"] == r["its"] + 1 and r["its"] <= 8, "%d ranks: %d iterations, %d Jacobians" % (ranks, r["its"], r["jacobians"]), out)
        q = observed_order(r["znorms"])
        expect(q > 1.5, "%d ranks: observed order %.2f" % (ranks, q), out)
        expect("residual nonlinear" in out, "%d ranks: the reason view does not say the residual is nonlinear" % ranks, out)
        its.append(r["its"])
    expect(abs(its[0] - its[1]) <= 1, "iterations on 1 and 2 ranks: %s" % its)


@test("the issue's reproduction: the prism's K and b (examples/prism -level 2 -save_whole) with F = K u + kappa u^3 - b, kappa such that the affine "
      "model's solution is off equilibrium by 0.5 max|b| at the free dofs: undeclared, it converges to F = 0 at the free dofs and the Coulomb law "
      "to 1e-7 (observed order > 1.5); declared affine (-affine), the check at the solution ends it NOT_AFFINE (DIVERGED_LOCAL_MIN, exit status 2) "
      "instead of a false CONVERGED; 1 and 2 ranks", full=True)
def nonlinear_cubic_prism():
    data = os.path.join(OUT, "prism2_whole.bin")
    run([PRISM, "-level", "2", "-save_whole", data, "-ssstar_progress", "0"])
    for ranks in (1, 2):
        out, r = nonlinear(ranks, "-problem", "cubic", "-load", data)
        expect("off equilibrium by 0.5 of max|b| at the free dofs" in out, "%d ranks: the affine model's point" % ranks, out)
        holds(out, r, "%d ranks" % ranks)
        q = observed_order(r["znorms"])
        expect(q > 1.5, "%d ranks: observed order %.2f" % (ranks, q), out)
        out, r = nonlinear(ranks, "-problem", "cubic", "-load", data, "-affine", expect_rc=NOT_CONVERGED)
        expect(r["reason"] == "DIVERGED_LOCAL_MIN" and "ssstar: NOT_AFFINE" in out and r["jacobians"] == 1 and r["equilibrium"] > 0.4,
               "%d ranks: a wrong affine declaration not refused at the solution" % ranks, out)


@test("the contact measured at every iterate (SNESSSStarSetContactUpdate) for a curved obstacle: the neo-Hookean block pressed frictionlessly onto a "
      "ball of radius 2 ends at the exact contact point (the ball's exact gap and normal at the solution: the law to 1e-7), the update called once per "
      "iterate (and at the start); linear convergence (the curvature's term is not in the Newton matrix), superlinear (order > 1.5) when the "
      "program's Jacobian adds it, and with Coulomb friction it converges too; 1 and 2 ranks", full=True)
def nonlinear_ball_update():
    for ranks in (1, 2):
        out, r = nonlinear(ranks, "-obstacle", "ball", "-snes_ssstar_friction", "0")
        holds(out, r, "%d ranks, frictionless" % ranks)
        expect(r["updates"] == r["its"] + 2 and r["separated"] > 0 and r["sliding"] > 0, "%d ranks: %d updates for %d iterations; states %d/%d/%d" % (ranks, r["updates"], r["its"], r["separated"], r["sliding"], r["sticking"]), out)
        q = observed_order(r["znorms"], 1e-8)
        expect(q < 1.3, "%d ranks: observed order %.2f without the curvature's term: not linear" % (ranks, q), out)
        out, g = nonlinear(ranks, "-obstacle", "ball", "-snes_ssstar_friction", "0", "-geometric_stiffness")
        holds(out, g, "%d ranks, with the curvature's term" % ranks)
        q = observed_order(g["znorms"])
        expect(q > 1.5 and g["its"] < r["its"], "%d ranks: with the curvature's term %d iterations (%d without), order %.2f" % (ranks, g["its"], r["its"], q), out)
        out, r = nonlinear(ranks, "-obstacle", "ball")
        holds(out, r, "%d ranks, Coulomb" % ranks)


@test("-snes_lag_jacobian is honoured on a nonlinear residual: 2 evaluates the Jacobian every second iteration, -2 once (then a chord iteration, "
      "more iterations), each converging to the answer; -snes_view says the residual is nonlinear, how often its Jacobian is evaluated and how many "
      "evaluations the last solve made")
def nonlinear_lag_jacobian():
    out, r1 = nonlinear(1, "-press", "0.3", "-shift", "0.1", "-snes_view")
    holds(out, r1, "lag 1")
    expect(re.search(r"residual: nonlinear \(not declared affine\): F evaluated at every iterate and trial point, the Jacobian at every iterate", out)
           and "last solve: residual nonlinear: %d Jacobian evaluations" % r1["jacobians"] in out, "-snes_view", out)
    out, r2 = nonlinear(1, "-press", "0.3", "-shift", "0.1", "-snes_lag_jacobian", "2")
    holds(out, r2, "lag 2")
    expect(r2["jacobians"] == 1 + (r2["its"] + 1) // 2, "lag 2: %d Jacobians in %d iterations" % (r2["jacobians"], r2["its"]), out)
    out, r3 = nonlinear(1, "-press", "0.3", "-shift", "0.1", "-snes_lag_jacobian", "-2")
    holds(out, r3, "lag -2")
    expect(r3["jacobians"] == 1 and r3["its"] > r1["its"], "lag -2: %d Jacobians, %d iterations (%d with lag 1)" % (r3["jacobians"], r3["its"], r1["its"]), out)


@test("the affine route keeps its speed and results: examples/prism (SNESSSStarSetLinearProblem, declared affine) takes exactly the iterations it took "
      "before section 17 (levels 2 and 4, direct and none), says so in -snes_view and the reason line; the same prism declared nonlinear "
      "(-snes_ssstar_affine false: the whole body, F at every iterate) gives the same solution to 2e-6 (harness.AGREE)", full=True)
def affine_prism_unchanged():
    for (level, reduction), its in sorted(AFFINE_ITERATIONS.items()):
        h5 = "affine_L%d_%s.h5" % (level, reduction)
        out, s = prism(level, extra=["-snes_ssstar_reduction", reduction, "-snes_view"], h5=h5)
        expect(s["iters"] == its, "level %d, %s: %d iterations, %d before section 17" % (level, reduction, s["iters"], its), out)
        expect("residual: affine, F(u) = K u - b (SNESSSStarSetLinearProblem())" in out and "ssstar: residual affine: 1 Jacobian evaluation, F checked at the solution" in out,
               "level %d, %s: the views do not say affine" % (level, reduction), out)
    out, s = prism(4, extra=["-snes_ssstar_affine", "false"], h5="nonlinear_L4.h5")
    expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and "ssstar: residual nonlinear" in out, "the prism declared nonlinear", out)
    run(CHECK + ["compare", os.path.join(OUT, "affine_L4_direct.h5"), os.path.join(OUT, "nonlinear_L4.h5"), "--tol", str(AGREE)])


@test("a nonlinear residual with a Schur reduction named (-snes_ssstar_reduction direct) is refused before any work with one line naming the option "
      "and the way out (none or auto, or SNESSSStarSetAffine); a pair of bodies (scenes/patch.opts: slave nodes against master faces, the change of "
      "variables T) declared nonlinear solves on the whole body to the affine route's answer (2e-6)")
def nonlinear_refusals_and_pairs():
    out = run([PRISM, "-level", "2", "-snes_ssstar_affine", "false", "-snes_ssstar_reduction", "direct"], expect_rc=1)
    expect("-snes_ssstar_reduction direct with a residual treated as nonlinear (not declared affine)" in out and "-snes_ssstar_reduction none or auto" in out,
           "the refusal of a Schur reduction", out)
    a = os.path.join(OUT, "patch_affine.h5")
    b = os.path.join(OUT, "patch_nonlinear.h5")
    run([CONTACT, "-options_file", os.path.join(ROOT, "scenes", "patch.opts"), "-nested_levels", "0", "-ssstar_progress", "0", "-o", a])
    out = run([CONTACT, "-options_file", os.path.join(ROOT, "scenes", "patch.opts"), "-nested_levels", "0", "-ssstar_progress", "0", "-snes_ssstar_affine", "false",
               "-snes_converged_reason", "-o", b])
    expect("ssstar: residual nonlinear" in out, "the patch declared nonlinear", out)
    run(CHECK + ["compare", a, b, "--tol", str(AGREE)])


@test("the reduced use (no contact nodes declared: every dof a contact dof, the Jacobian itself the Newton matrix) with a nonlinear residual "
      "P u + kappa u^3 - f (tests/test_plain_contact -kappa 2, through -dll_append): sparse (the SNES's KSP) and dense J, 1 and 2 ranks, "
      "converged with the Coulomb law to 1e-8 and its Jacobian evaluated at every iterate")
def nonlinear_reduced_use():
    for ranks in (1, 2):
        for dense in ("0", "1"):
            out = run(mpiexec(ranks, os.path.join(ROOT, "tests", "test_plain_contact"), "-dll_append", LIB, "-snes_type", "ssstar", "-kappa", "2",
                              "-dense", dense, "-snes_converged_reason"))
            m = re.search(r"residual nonlinear: (\d+) Jacobian evaluations", out)
            its = re.search(r"CONVERGED_FNORM_RELATIVE after (\d+) iterations", out)
            expect(m is not None and its is not None and int(m.group(1)) == int(its.group(1)), "%d ranks, dense %s" % (ranks, dense), out)


@test("a contact update that declares a contact operator with master dofs again at every iterate (tests/test_operator -update: two chains "
      "pressed together through B, the change of variables T taken again, the iterate expressed in its points' variables): the contact law on "
      "w = B u + g to 1e-8, the same u as the whole body without updates to 1e-8, one update per iterate and the start's; 1 and 2 ranks")
def nonlinear_update_with_masters():
    import numpy as np
    plain = os.path.join(OUT, "operator_plain.bin")
    run(mpiexec(1, os.path.join(ROOT, "tests", "test_operator"), "-snes_ssstar_reduction", "none", "-o", plain))
    ref = np.fromfile(plain, dtype=">f8")[-72:]
    for ranks in (1, 2):
        name = os.path.join(OUT, "operator_update_%d.bin" % ranks)
        out = run(mpiexec(ranks, os.path.join(ROOT, "tests", "test_operator"), "-update", "-o", name))
        law = re.search(r"contact law on w: worst violation (\S+)", out)
        m = re.search(r"contact updates: (\d+) in (\d+) iterations", out)
        expect(law is not None and float(law.group(1)) <= 1e-8 and m is not None and int(m.group(1)) == int(m.group(2)) + 2, "%d ranks" % ranks, out)
        u = np.fromfile(name, dtype=">f8")[-72:]
        expect(np.abs(u - ref).max() <= 1e-8 * np.abs(ref).max(), "%d ranks: u differs from the run without updates by %.1e" % (ranks, np.abs(u - ref).max() / np.abs(ref).max()))
