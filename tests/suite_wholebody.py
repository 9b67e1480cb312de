"""The whole-body path (-snes_ssstar_reduction none: P never formed, the Newton step on K by Krylov + multigrid) gives
the dense route's answer: the same solution to 1e-8, the same contact states, the same iterations within one, on
every kind of problem the dense route solves; and auto chooses between them."""
import os
import re

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)
from suite_generic import GENERIC, TILTED, by_coordinates, generic

import numpy as np

CONTACT = os.path.join(ROOT, "examples", "contact")
SCENE_SUMMARY = re.compile(r"summary: .* iterations (\d+) states \S+ ([\d/]+) (\S+)")


def scene_run(args, h5, ranks=1):
    out = run(mpiexec(ranks, CONTACT, *args, "-o", os.path.join(OUT, h5)))
    m = SCENE_SUMMARY.search(out)
    expect(m is not None, "no summary", out)
    return out, {"iters": int(m.group(1)), "states": m.group(2), "reason": m.group(3)}


def prism_run(args, h5, ranks=1, expect_rc=0, check_memory=True):
    out = run(mpiexec(ranks, PRISM, *args, "-o", os.path.join(OUT, h5), "-snes_converged_reason"), expect_rc=expect_rc, check_memory=check_memory)
    m = SUMMARY.search(out)
    expect(m is not None, "no summary row", out)
    return out, {"iters": int(m.group(6)), "states": m.group(7), "reason": m.group(9), "peak_gb": float(m.group(10))}


def same_answer(name, runner, args, tol=AGREE, ranks=1, iterations=1):
    """runs args on the dense route (direct) and on the whole body (none) and compares them"""
    dense, d = runner(list(args) + ["-snes_ssstar_reduction", "direct"], "%s_direct.h5" % name, ranks)
    full, f = runner(list(args) + ["-snes_ssstar_reduction", "none"], "%s_none.h5" % name, ranks)
    expect(d["reason"] == f["reason"] and d["reason"].startswith("CONVERGED"), "%s: %s dense, %s whole body" % (name, d["reason"], f["reason"]), dense + full)
    expect(abs(d["iters"] - f["iters"]) <= iterations, "%s: %d iterations dense, %d whole body" % (name, d["iters"], f["iters"]), dense + full)
    expect(d["states"] == f["states"], "%s: states %s dense, %s whole body" % (name, d["states"], f["states"]), dense + full)
    run(CHECK + ["compare", os.path.join(OUT, "%s_direct.h5" % name), os.path.join(OUT, "%s_none.h5" % name), "--tol", str(tol)])
    return dense, full


@test("prism levels 3, 4, 5 and 7: the whole-body path gives the dense route's solution (contact face, reactions, whole field) to 1e-8, the same states, the iterations within one; -snes_view names the path, the KSP and PC, and the linear iterations per Newton step", full=True)
def wholebody_prism_same_answer():
    for level in (3, 4, 5, 7):
        _, full = same_answer("wholebody_prism_L%d" % level, prism_run, ["-level", str(level), "-snes_view"])
    for pattern in (r"solved on the whole body, P never formed \(reduction none\)", r"Newton step on the whole body", r"KSP Object:", r"type: gamg",
                    r"last solve: \d+ linear solves, \d+ Krylov iterations \([\d.]+ per solve\)"):
        expect(re.search(pattern, full) is not None, "-snes_view lacks /%s/" % pattern, full)


@test("1, 2, 3, 4 and 8 ranks (oversubscribed) give the same solution to 1e-8 and the same states on both paths (prism level 5), the iterations within one; nothing of the whole-body path needs the problem on one rank", full=True)
def wholebody_ranks_agree():
    for path in ("none", "direct"):
        outs = []
        for ranks in (1, 2, 3, 4, 8):
            out, s = prism_run(["-level", "5", "-snes_ssstar_reduction", path], "ranks_%s%d.h5" % (path, ranks), ranks)
            outs.append((ranks, out, s))
            expect(s["reason"] == "CONVERGED_FNORM_RELATIVE", "%s, %d ranks: %s" % (path, ranks, s["reason"]), out)
        one = outs[0][2]
        for ranks, out, s in outs[1:]:
            expect(abs(s["iters"] - one["iters"]) <= 1 and s["states"] == one["states"], "%s, %d ranks: %d iterations, states %s; 1 rank: %d, %s" % (path, ranks, s["iters"], s["states"], one["iters"], one["states"]), out)
            run(CHECK + ["compare", os.path.join(OUT, "ranks_%s1.h5" % path), os.path.join(OUT, "ranks_%s%d.h5" % (path, ranks)), "--tol", str(AGREE)])


@test("a plain PETSc program (examples/generic, DMDA) with a tilted plane and varying gaps: the whole-body path gives the dense route's solution to 1e-8 on 1 and 3 ranks, the Coulomb law in the nodes' frames holds")
def wholebody_generic_tilted_gaps():
    for ranks in (1, 3):
        generic(ranks, "-snes_type", "ssstar", *TILTED, h5="wholebody_generic_direct%d.h5" % ranks)
        out, distance, _ = generic(ranks, "-snes_type", "ssstar", "-snes_ssstar_reduction", "none", "-snes_converged_reason", *TILTED, h5="wholebody_generic_none%d.h5" % ranks)
        expect("CONVERGED_FNORM_RELATIVE" in out and distance >= -1e-11, "%d ranks: not converged or penetrating (%g)" % (ranks, distance), out)
        law = run(CHECK + ["coulomb", os.path.join(OUT, "wholebody_generic_none%d.h5" % ranks)])
        expect("VIOLATED" not in law, "%d ranks: law violated" % ranks, law)
        a, b = by_coordinates("wholebody_generic_direct%d.h5" % ranks), by_coordinates("wholebody_generic_none%d.h5" % ranks)
        for name in ("displacement", "reaction"):
            d = np.abs(a[name] - b[name]).max() / np.abs(a[name]).max()
            expect(d <= 1e-8, "%d ranks: %s differs by %.1e relative" % (ranks, name, d))


@test("the whole body's Newton matrix is formed in K's own storage when K is AIJ (examples/generic's DMDA matrix) and in an AIJ copy when it is not (-dm_mat_type baij); both give the dense route's solution to 1e-8 on 1 and 2 ranks (the reactions K u - b after the solve: K was put back)")
def wholebody_newton_matrix_storage():
    for ranks in (1, 2):
        generic(ranks, "-snes_type", "ssstar", *TILTED, h5="wholebody_storage_direct%d.h5" % ranks)
        a = by_coordinates("wholebody_storage_direct%d.h5" % ranks)
        for mtype, where in (("aij", "formed in K's storage for each linear solve (no copy of K)"), ("baij", "formed in an AIJ copy of K")):
            out, _, _ = generic(ranks, "-snes_type", "ssstar", "-snes_ssstar_reduction", "none", "-dm_mat_type", mtype, "-snes_view", *TILTED, h5="wholebody_storage_%s%d.h5" % (mtype, ranks))
            expect(where in out, "%s, %d ranks: the Newton matrix is not %s" % (mtype, ranks, where), out)
            b = by_coordinates("wholebody_storage_%s%d.h5" % (mtype, ranks))
            for name in ("displacement", "reaction"):
                d = np.abs(a[name] - b[name]).max() / np.abs(a[name]).max()
                expect(d <= 1e-8, "%s, %d ranks: %s differs by %.1e relative" % (mtype, ranks, name, d))


@test("every friction law and the scenes on the whole body: frictionless (hertz level 1), Tresca (prism level 3), Coulomb sticking and sliding on a tilted plane with gravity and a soft spring (incline), a stick-slip front (shear), 10 load steps with gaps (gap): the dense route's solution to 1e-8 with the same states", full=True)
def wholebody_scenes_same_answer():
    # the half ball hangs on a soft spring (k = 1 against E = 2.1e5): as on the incline, the error is about 1e4 ||z|| and
    # the last linear solve decides it within the stopping rule, so both paths stop at a tighter ||z||
    same_answer("wholebody_hertz", scene_run, ["-options_file", os.path.join(ROOT, "scenes", "hertz.opts"), "-level", "1"])
    same_answer("wholebody_tresca", prism_run, ["-level", "3", "-friction_law_contact", "tresca", "-slip_bound_contact", "2"])
    same_answer("wholebody_incline", scene_run, ["-options_file", os.path.join(ROOT, "scenes", "incline.opts")])
    # the whole body slides, held by a soft spring: the error is about 1e4 ‖z‖, so both paths stop at a tighter ‖z‖
    same_answer("wholebody_incline_slides", scene_run, ["-options_file", os.path.join(ROOT, "scenes", "incline.opts"), "-friction_bottom", "0.3"])
    same_answer("wholebody_shear", scene_run, ["-options_file", os.path.join(ROOT, "scenes", "shear.opts")])
    # reactions at each of 10 load steps: both paths stop at a tighter ||z|| to compare them to 1e-8
    same_answer("wholebody_gap", scene_run, ["-options_file", os.path.join(ROOT, "scenes", "gap.opts")], iterations=10)


@test("hard cases on the whole body: friction phi = 5, nu = 0.49 (the globalization's damped step acts there too; the plain iteration stops at a detected cycle or at a solution of the law), a random start 100x the solution: the dense route's solution to 1e-8; the fixed-point baseline (-snes_ssstar_method fixedpoint, interior in equilibrium at every step) converges to the Newton solution", full=True)
def wholebody_hard_cases():
    _, phi5 = same_answer("wholebody_phi5", prism_run, ["-level", "4", "-snes_ssstar_friction", "5", "-snes_ssstar_monitor_states"])
    dense, full = same_answer("wholebody_nu049", prism_run, ["-level", "4", "-nu", "0.49", "-snes_ssstar_monitor_states"], iterations=2)
    # which of the two needs a damped step depends on the inexact steps (the multigrid's smoother): one of them does
    expect("damped step" in phi5 + full, "no damped step on the whole body", phi5 + full)
    out, s = prism_run(["-level", "4", "-nu", "0.49", "-snes_ssstar_reduction", "none", "-snes_ssstar_globalization", "0", "-snes_ssstar_monitor_states"], "full_nu049_plain.h5", expect_rc=None)
    # the plain iteration's cycle is one of the exact steps; inexact steps may leave it and reach a solution
    cycled = s["reason"] == "DIVERGED_LINE_SEARCH" and "cycle detected" in out
    expect(cycled or s["reason"] == "CONVERGED_FNORM_RELATIVE", "the plain iteration on the whole body: %s, no cycle detected" % s["reason"], out)
    expect(cycled == ("The solve did not converge (DIVERGED_LINE_SEARCH): exit status %d" % NOT_CONVERGED in out), "the exit rule does not follow the reason", out)
    if not cycled:
        law = run(CHECK + ["coulomb", os.path.join(OUT, "full_nu049_plain.h5"), "--phi", "0.3"])
        expect("VIOLATED" not in law, "the plain iteration's solution violates the law", law)
    # far from the solution the inexact first steps take another way through the damped steps: the same solution, a few more iterations
    same_answer("full_random", prism_run, ["-level", "4", "-initial_guess", "random", "-initial_guess_scale", "2"], iterations=4)
    out, s = prism_run(["-level", "3", "-snes_ssstar_reduction", "none", "-snes_ssstar_method", "fixedpoint", "-snes_max_it", "100000", "-snes_rtol", "1e-12"], "full_fixedpoint.h5")
    expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and s["iters"] > 100, "fixed point: %s after %d iterations" % (s["reason"], s["iters"]), out)
    prism_run(["-level", "3", "-snes_ssstar_reduction", "none"], "full_newton.h5")
    run(CHECK + ["compare", os.path.join(OUT, "full_newton.h5"), os.path.join(OUT, "full_fixedpoint.h5"), "--tol", str(AGREE)])


@test("auto (the default) takes the dense route on a small problem and the whole body where the dense P does not fit the memory limit; -snes_view says which and that auto chose it")
def wholebody_auto_chooses():
    out = run(mpiexec(1, PRISM, "-level", "3", "-snes_ssstar_reduction", "auto", "-snes_view"))
    expect("K reduced to the contact dofs by the direct Schur complement (chosen by auto)" in out, "auto did not choose direct at level 3", out)
    # a scene refuses a limit below its mesh's needs before any work (suite_scenes): a plain program (DMDA) meets auto's own check
    out = run(mpiexec(1, os.path.join(ROOT, "examples", "generic"), "-snes_type", "ssstar", "-snes_ssstar_reduction", "auto", "-snes_ssstar_memory_limit", "1e-6", "-snes_view"))
    expect("solved on the whole body, P never formed (reduction none (chosen by auto))" in out or "solved on the whole body, P never formed (reduction none, chosen by auto)" in out,
           "auto did not choose none when P does not fit", out)


def fine_krylov(out):
    """the Krylov iterations of the finest mesh's linear solves (after the nested start's line), in order"""
    fine = out[out.index("nested:"):]
    return [int(n) for n in re.findall(r"Linear solve converged due to \S+ iterations (\d+)", fine)]


@test("the whole body's likely last Newton step (its states repeated) can be solved to half the stopping rule (-snes_ssstar_ksp_floor 0.5; the default is the tenth of every step, docs/derivation.md section 19a), no further: prism level 6 on 2 ranks from level 3 takes the same Newton steps as at the default, its last linear solve fewer Krylov iterations (14 against 16 here), the law within its tolerance and holding in the file; -info names that step; a fraction outside (0, 1] is refused naming the option")
def wholebody_last_step_floor():
    args = ["-level", "6", "-snes_ssstar_reduction", "none", "-nested_levels", "1", "-ksp_converged_reason", "-info", ":snes"]
    out, s = prism_run(args + ["-snes_ssstar_ksp_floor", "0.5"], "last_step_floor.h5", ranks=2)
    before, b = prism_run(args, "last_step_floor01.h5", ranks=2)
    expect(s["reason"] == b["reason"] == "CONVERGED_FNORM_RELATIVE" and s["iters"] == b["iters"] and s["states"] == b["states"],
           "floor 0.5: %s in %d, states %s; 0.1: %s in %d, states %s" % (s["reason"], s["iters"], s["states"], b["reason"], b["iters"], b["states"]), out + before)
    its, its_before = fine_krylov(out), fine_krylov(before)
    expect(its[-1] < its_before[-1] and sum(its) < sum(its_before), "last linear solve: %s Krylov iterations at 0.5, %s at 0.1" % (its, its_before), out + before)
    expect(out.count("(the likely last step)") >= 1, "-info does not name the likely last step", out)
    last = re.findall(r"Iteration \d+: \|\|z\|\| (\S+), threshold (\S+), law residual (\S+) \(tolerance (\S+)\)", out)[-1]
    expect(float(last[0]) <= float(last[1]) and float(last[2]) <= float(last[3]), "the last iterate: ||z|| %s (threshold %s), law %s (tolerance %s)" % last, out)
    law = run(CHECK + ["law", os.path.join(OUT, "last_step_floor.h5"), "--steps"])
    expect("VIOLATED" not in law, "the law does not hold in the file", law)
    for bad in ("0", "1.5"):
        text = run(mpiexec(1, PRISM, "-level", "2", "-snes_ssstar_reduction", "none", "-snes_ssstar_ksp_floor", bad), expect_rc=1)
        expect(re.search(r"-snes_ssstar_ksp_floor %s\.? must be in \(0, 1\]" % re.escape(bad), text) is not None, "-snes_ssstar_ksp_floor %s not refused by name" % bad, text)
