"""What converged means (issue 23, docs/derivation.md section 12): a solve the program calls converged writes a file
whose every step satisfies the friction law and the equilibrium to the tolerance docs/guide/converged.md states, on both paths and
1-2 ranks, at the default settings; steps driven by a motion converge and feel the motion at every -snes_rtol; where
the law cannot be met the solve says so. Comparisons of paths, ranks and steps use bounds that follow from that
guarantee (docs/guide/converged.md: within 1e-6 of the exact discrete solution on the robustness scenes, so two
runs within 2e-6 of each other)."""
import os
import re
import sys

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

sys.path.insert(0, os.path.join(ROOT, "bench"))
import robust  # noqa: E402  (the robustness families: members, runs, the checks of a file)

robust.OUT = os.path.join(OUT, "robust")  # the members' files among the tests' own
os.makedirs(robust.OUT, exist_ok=True)

CONTACT = os.path.join(ROOT, "examples", "contact")
AGREE = 2e-6  # two runs at the defaults, each within 1e-6 of the exact discrete solution
PATHS = [(red, ranks) for red in ("direct", "none") for ranks in (1, 2)]
LAW = re.compile(r"^distance to the law\s+(\S+)", re.M)


def h5(name):
    return os.path.join(OUT, name)


def law_distance(path, *extra):
    """check_solution.py's largest distance to the law over the file's steps (it passes at its default 1e-7; a file
    without contact, a cantilever's, has no law: 0, its fields checked all the same)"""
    out = run(CHECK + ["coulomb", path, "--steps", *extra])
    return max([float(x) for x in LAW.findall(out)], default=0.0)


@test("docs/derivation.md section 12 holds (tests/stopping_check.py, numpy): the approximation step at gamma_w = U/F gives a pair that satisfies the law exactly within |z| of the iterate (12.1), 0 at points of the law; on a stiff body sliding on a soft spring (E/k = 1e8) iterates that ||z|| <= 1e-10 accepts have forces off by more than 1e-6 of max|r|, and at most two Newton steps bring the law residual below 1e-8 and the solution within 1e-6 (12.2)-(12.4); a node dragged back by its plane reaches its stuck answer from the sliding state only for gamma >= 1/(2k), the elastic trial at once (12.5)")
def converged_derivation():
    page = open(os.path.join(ROOT, "docs", "derivation.md")).read()
    for equation in ("(12.1)", "(12.2)", "(12.3)", "(12.4)", "(12.5)"):
        expect(equation in page, "docs/derivation.md has no equation %s" % equation)
    out = run([PYTHON, os.path.join(ROOT, "tests", "stopping_check.py")])
    expect(out.count(" ok (") == 3 and "FAILED" not in out, "tests/stopping_check.py", out)


@test("a plane dragging a block (E = 2e8, pressed by P = 1, held sideways by a spring k = 1000, phi = 0.5) forward by 0.002, more than it can follow, then back by 5e-4: forward the block stops where the spring holds phi P (u_x = phi P/k = 5e-4, tangential force phi N), back it sticks and returns with the plane (u_x = 0, no tangential force): forward the closed forms to 1e-6 (measured 1e-10), back to the block's compliance, 1e-4 of phi N/k (measured 7.5e-6), the law on every step of the file, direct and none, 1 and 2 ranks (it never converged back: 250 iterations)")
def converged_drag_closed_form():
    for red, ranks in PATHS:
        out = run(mpiexec(ranks, CONTACT, *robust.dragged(0.002, 0.0015), "-snes_ssstar_reduction", red, "-o", h5("drag_%s_%d.h5" % (red, ranks))))
        with h5py.File(h5("drag_%s_%d.h5" % (red, ranks)), "r") as f:
            st = f["steps"]
            ux, tx, N = st["groups/top/displacement"][:, 0], st["tangential_force"][:, 0], st["normal_force"][:]
            expect((st["reason"][:] > 0).all() and len(ux) == 4, "%s %d: steps %s" % (red, ranks, st["reason"][:]), out)
        slid = 0.5 * N[2] / 1000  # phi N/k: the spring holds the friction force (N is P less what the spring takes)
        expect(abs(ux[2] - slid) <= 1e-6 * slid and abs(tx[2] - 0.5 * N[2]) <= 1e-6 * 0.5 * N[2], "%s %d: forward u_x %.9g (phi N/k %.9g), force %.9g (phi N %.9g)" % (red, ranks, ux[2], slid, tx[2], 0.5 * N[2]))
        expect(abs(ux[3]) <= 1e-4 * slid and abs(tx[3]) <= 1e-4 * 0.5 * N[3], "%s %d: back u_x %.3g, force %.3g (0 to the block's compliance: stuck, back with the plane)" % (red, ranks, ux[3], tx[3]))
        expect(law_distance(h5("drag_%s_%d.h5" % (red, ranks))) <= 1e-7, "%s %d: the law" % (red, ranks))


@test("no false converged on a load path at any -snes_rtol from 1e-3 to 1e-12 (the plane dragging the block forward and back, both paths): every run either ends converged with the law on every step to max(rtol, 1e-8) (check_solution, ten times that) and the answer within 10 max(rtol, 1e-8) of the exact discrete solution (the dense route at 1e-13) at every step, the motion felt (the forward step's friction force phi N to that tolerance; at 1e-4 it was accepted in 0 iterations with no force), or exits with status 2 saying why", full=True)
def converged_rtol_sweep():
    args = robust.dragged(0.002, 0.0015)
    run(mpiexec(1, CONTACT, *args, "-snes_ssstar_reduction", "direct", "-snes_rtol", "1e-13", "-o", h5("sweep_reference.h5")))
    for rtol in ("1e-3", "1e-4", "1e-6", "1e-8", "1e-10", "1e-12"):
        tol = 10 * max(float(rtol), 1e-8)
        for red in ("direct", "none"):
            name = h5("sweep_%s_%s.h5" % (red, rtol))
            out = run(mpiexec(1, CONTACT, *args, "-snes_ssstar_reduction", red, "-snes_rtol", rtol, "-o", name), expect_rc=None)
            if "exit status 2" in out:
                continue
            expect(law_distance(name, "--tol", str(tol)) <= tol, "%s at rtol %s: the law" % (red, rtol), out)
            run(CHECK + ["compare", h5("sweep_reference.h5"), name, "--steps", "--tol", str(tol)])
            with h5py.File(name, "r") as f:
                tx, N = f["steps/tangential_force"][2, 0], f["steps/normal_force"][2]
            expect(abs(tx - 0.5 * N) <= tol * 0.5, "%s at rtol %s: the plane's motion not felt (friction force %.6g, phi N %.6g)" % (red, rtol, tx, 0.5 * N), out)


@test("a stiff block (E = 2e8, loads of order 1, E/k = 2e5) pressed, sheared both ways past sliding and released to zero load in 20 steps: every step converges at the defaults, its file satisfies the law at every step (check_solution --steps; it missed it by 1.3e-2 of max|r|: a pull, |r_t| > phi r_n) and lies within 1e-6 of the exact discrete solution at every step (measured 6e-9), direct and none, 1 and 2 ranks", full=True)
def converged_stiff_block():
    name = "stiff block, loads of order 1: press, shear both ways past sliding, release to zero, 20 steps"
    for ranks in (1, 2):
        result = robust.run_member(name, robust.PATHS[name], ranks)
        expect(result is not None, "the reference did not converge")
        for red, r in result.items():
            expect(robust.passed(r), "%s, %d ranks: %s" % (red, ranks, robust.cell(r)))


@test("the block load path of the README and docs/guide/load-paths.md (the block on a spring, E = 2e8, pressed, sheared to 1.5 phi P both ways, released) at the defaults: the file passes check_solution on every step (it failed at 2.3e-5 and 7.4e-5), both paths within 1e-6 of the exact discrete solution at every step, 1 and 2 ranks; the same for the ball pressed into a block held by a spring with E/k = 2e8 and sheared obliquely (6e-7 dense, 6e-6 whole body before) on 2 and 3 ranks", full=True)
def converged_readme_block_and_ball():
    name = "block on a spring: press, shear 1.5 phi P, release, reverse, release (the README's)"
    for ranks in (1, 2):
        result = robust.run_member(name, robust.PATHS[name], ranks)
        for red, r in result.items():
            expect(robust.passed(r), "block, %s, %d ranks: %s" % (red, ranks, robust.cell(r)))
    name = "ball, k = 1e-3, sheared obliquely"
    for ranks in (2, 3):
        result = robust.run_member(name, robust.FAMILY[name], ranks)
        for red, r in result.items():
            expect(robust.passed(r), "ball, %s, %d ranks: %s" % (red, ranks, robust.cell(r)))


@test("a law tolerance below the round-off floor (-snes_ssstar_law_rtol 1e-18) is not met, and the solve says so: LAW_STALLED (DIVERGED_LOCAL_MIN), exit status 2, the file's / attributes sub_reason LAW_STALLED with law_residual above law_tolerance; at the defaults the file records law_residual <= law_tolerance = 1e-8")
def converged_law_stalled():
    args = robust.BLOCK + ["-friction_bottom", "0.5", "-traction_top", "0,0,-1", "-snes_converged_reason"]
    out = run(mpiexec(1, CONTACT, *args, "-snes_ssstar_law_rtol", "1e-18", "-o", h5("stalled.h5")), expect_rc=NOT_CONVERGED)
    expect("LAW_STALLED" in out and "DIVERGED_LOCAL_MIN" in out, "no LAW_STALLED", out)
    with h5py.File(h5("stalled.h5"), "r") as f:
        a = f.attrs
        expect(a["sub_reason"] == "LAW_STALLED" and a["law_residual"] > a["law_tolerance"] == 1e-18, "attributes %s" % dict(a))
    out = run(mpiexec(1, CONTACT, *args, "-o", h5("lawful.h5")))
    with h5py.File(h5("lawful.h5"), "r") as f:
        a = f.attrs
        expect(a["sub_reason"] == "CONVERGED_RELATIVE" and 0 <= a["law_residual"] <= a["law_tolerance"] == 1e-8, "attributes %s" % dict(a), out)


# commands of the README and the guide that this test does not run, each with its reason
DOC_SKIP = {"-level 32": "level 32 on the whole body (1.6 M dofs, 3.6 GB per rank): make bench-large measures it",
            "-level 48": "level 48 (5.4 M dofs, 6.7 GB per rank): make bench-large measures it",
            "examples/fclib": "tests/check_solution.py does not read an FCLib solution file yet (issue 31); suite_fclib checks them"}
# options that change what a run prints, not its file
QUIET = {"-snes_monitor", "-snes_converged_reason", "-log_view", "-snes_view"}


def scene_runs():
    import glob
    scenes = sorted(glob.glob(os.path.join(ROOT, "scenes", "*.opts")))
    expect(len(scenes) >= 13, "%d scenes" % len(scenes))
    return [("scenes/", [CONTACT, "-options_file", os.path.relpath(s, ROOT), "-o", "x.h5"]) for s in scenes]


def run_key(argv):
    """What makes two commands the same run: the arguments less the output file and the options that only print"""
    import doc_commands
    out_at = doc_commands.output_of(argv)
    return tuple(a for i, a in enumerate(argv) if i != out_at and a not in QUIET)


def law_of_runs(runs, skip=()):
    """Runs each (page, argv) once (argv as a page gives it, its output file renamed into the test's folder) and
    requires check_solution.py law --steps of its file"""
    import doc_commands
    done = set(skip)
    for k, (page, argv) in enumerate(runs):
        key = run_key(argv)
        if key in done:
            continue
        done.add(key)
        out_at = doc_commands.output_of(argv)
        path = h5("every_%d.h5" % k)
        argv = argv[:out_at] + [path] + argv[out_at + 1:]
        if argv[0].endswith(".py") or (argv[0] == "mpiexec" and argv[3].endswith(".py")):
            at = 0 if argv[0] != "mpiexec" else 3
            argv = argv[:at] + [PYTHON] + argv[at:]
        if argv[0] != "mpiexec":
            argv = mpiexec(1, *argv)
        if any(a.endswith((CONTACT, PRISM)) for a in argv):
            argv = argv + ["-ssstar_progress", "0"]
        out = run(argv, timeout=300)
        # the law to 1e-7, or to the looser tolerance a command asks for (-snes_rtol: converged.md's loose tolerances)
        tol = max([1e-7] + [float(argv[i + 1]) for i, a in enumerate(argv[:-1]) if a in ("-snes_rtol", "-snes_ssstar_law_rtol")])
        expect(law_distance(path, "--tol", repr(tol)) <= tol, "%s: %s: the law to %g" % (page, " ".join(argv), tol), out)


@test("every scene of scenes/ at its level and the default settings (the scenes of docs/guide/scenes.md) writes a file that passes tests/check_solution.py law FILE --steps (the law as written on every step, tolerance 1e-7)", full=True)
def converged_every_scene():
    law_of_runs(scene_runs())


@test("every other command of README.md and docs/guide/*.md that writes a file (tests/doc_commands.py: examples/contact, prism, generic, and examples/scene.py, generic.py in Python; the five-minute tour, the known answers, the block load path and its displacement-controlled sliding), run as the page gives it at the default settings, writes a file that passes tests/check_solution.py law FILE --steps (to the tolerance a command asks for with -snes_rtol, else 1e-7); only levels 32 and 48 (make bench-large) and the FCLib file (tests/suite_fclib.py) are left out")
def converged_doc_commands():
    import doc_commands
    documented = doc_commands.commands()
    block = "examples/contact -geo meshes/block.geo -level 2 -E 2e8 -nu 0.3 -spring_top 1000 -contact bottom -friction_bottom 0.5"
    expect(any(block in " ".join(argv) and "-traction_top" in argv for _, argv in documented), "the block load path is not among the documented commands: update this test", str(documented))
    expect(any("-obstacle_bottom_motion" in argv for _, argv in documented), "the displacement-controlled sliding is not among the documented commands", str(documented))
    expect(len(documented) >= 20, "only %d documented commands write a file" % len(documented), str(documented))
    runs = [(page, [os.path.join(ROOT, a) if a.startswith("examples/") else a for a in argv]) for page, argv in documented
            if not any(key in " ".join(argv) for key in DOC_SKIP)]
    law_of_runs(runs, skip={run_key(argv) for _, argv in scene_runs()})
