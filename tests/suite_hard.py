"""Hard cases (issue 5): far from the default scene the solver converges to a solution that passes the Coulomb-law
check, or stops with an honest reason; the globalization's remedies are observable; no leaks; determinism."""
import os
import re

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, prism, paths)

TIGHT = ["-snes_rtol", "1e-14"]  # the reference solve a hard case is compared with
TANGENTIAL = ["-traction_top", "2000,800,-500"]  # a strong tangential load on the top face
WEAK = ["-nu", "0", "-traction_top", "0,0,0", "-traction_right", "-200,0,0"]  # slides the body, no contact force
REMEDIES = re.compile(r"remedies: damped steps (\d+), full steps after a failed line search (\d+), rescalings of gamma (\d+), "
                      r"regularized Newton steps (\d+), fixed-point rounds (\d+); cycles detected (\d+); nodes stuck at a reversed slip (\d+)")


def h5(name):
    return os.path.join(OUT, name + ".h5")


def contact(name):
    import h5py  # Debian's python3-h5py: tests/run.py runs under /usr/bin/python3
    with h5py.File(h5(name), "r") as f:
        return {k: f[k][:] for k in ("contact/coordinates", "contact/displacement", "contact/reaction", "contact/state", "fields/displacement")}


def relative_difference(a, b):
    import numpy as np
    return float(np.abs(a - b).max() / np.abs(b).max())


def znorms(out):
    return [float(z) for z in re.findall(r"SNES Function norm ([0-9.eE+-]+)", out)]


def remedies(out):
    m = REMEDIES.search(out)
    expect(m is not None, "no remedy counts in -snes_view", out)
    return dict(zip(("damped", "full", "rescale", "regularized", "fixed_point", "cycles", "stuck"), (int(g) for g in m.groups())))


def law(tag):
    """The Coulomb law at every node of the solution file, to 1e-6 of the largest displacement and contact force:
    with rtol 1e-10 on ||z|| (a displacement) the forces of an ill-conditioned (nu -> 1/2) or lightly pressed
    (grazing) scene are good to ~1e-8 of the largest contact force only, and the slip direction of a node that
    barely slides to less"""
    run(CHECK + ["coulomb", h5(tag), "--tol", "1e-6"])


def converged(tag, level, options, max_iters=20, ranks=1):
    """Solves; asserts convergence within max_iters, the Coulomb law (independent check of the HDF5 file, law()) and
    the distance to a tight reference solve (rtol 1e-14, where the law holds to 1e-8) below 1e-8 relative; returns
    (summary, output, error)."""
    out, s = prism(level, ranks, extra=list(options) + ["-snes_view", "-snes_ssstar_monitor_states"], h5=tag + ".h5")
    expect(s["reason"] == "CONVERGED_FNORM_RELATIVE", "%s: %s" % (tag, s["reason"]), out)
    expect(s["iters"] <= max_iters, "%s: %d iterations > %d" % (tag, s["iters"], max_iters), out)
    law(tag)
    prism(level, ranks, extra=list(options) + TIGHT, h5=tag + "_ref.h5")
    run(CHECK + ["coulomb", h5(tag + "_ref"), "--tol", "1e-8"])
    error = relative_difference(contact(tag)["contact/displacement"], contact(tag + "_ref")["contact/displacement"])
    expect(error <= 1e-8, "%s: contact displacement %.1e relative from the tight reference" % (tag, error), out)
    return s, out, error


@test("friction far beyond 'sufficiently small' (phi = 0.6, 2, 5) on the default scene and under a strong tangential load (level 4): converged, Coulomb law, 1e-8 from a tight reference", full=True)
def hard_friction():
    for name, scene in (("default", []), ("tangential", TANGENTIAL)):
        for phi in (0.6, 2, 5):
            converged("friction_%s_%g" % (name, phi), 4, scene + ["-snes_ssstar_friction", str(phi)])


@test("frictionless contact (phi = 0) converges in at most 6 iterations on levels 3, 5 and 7 on the dense route, with r_t = 0; "
      "at level 8 auto's whole body (inexact steps) in at most 7", full=True)
def hard_frictionless():
    for level, route, most in [(level, "direct", 6) for level in (3, 5, 7)] + [(8, "auto", 7)]:
        tag = "frictionless_L%d_%s" % (level, route)
        out, s = prism(level, extra=["-snes_ssstar_friction", "0", "-snes_ssstar_reduction", route], h5=tag + ".h5")
        expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and s["iters"] <= most, "level %d, %s: %s after %d iterations" % (level, route, s["reason"], s["iters"]), out)
        law(tag)


def superlinear_end(tag, out):
    z = znorms(out)
    expect(len(z) >= 3 and z[-1] <= 1e-3 * z[-2], "%s: the last step is not superlinear (|z| %s)" % (tag, z[-3:]), out)
    expect("cycle detected" not in out, "%s: a cycle" % tag, out)


@test("weak contact: nu = 0 and a load that only slides the body give the uniaxial solution u_x = -p x/E, u_y = u_z = 0 and no contact force (levels 3, 5), every node M2 (weak contact) with tau = 1e-8, no cycle, a superlinear last step", full=True)
def hard_weak_contact():
    for level in (3, 5):
        for tau in ("1e-13", "1e-8"):
            tag = "weak_L%d_tau%s" % (level, tau)
            out, s = prism(level, extra=WEAK + ["-snes_ssstar_state_tol", tau, "-snes_ssstar_monitor_states"], h5=tag + ".h5")
            expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and s["iters"] <= 5, "%s: %s after %d iterations" % (tag, s["reason"], s["iters"]), out)
            superlinear_end(tag, out)
            c = contact(tag)
            exact = 0 * c["contact/displacement"]
            exact[:, 0] = -200 * c["contact/coordinates"][:, 0] / 2.1e5
            error = relative_difference(c["contact/displacement"], exact)
            force = abs(c["contact/reaction"]).max() / (200 * 1 * 1)  # against the load on the right face
            expect(error <= 1e-8 and force <= 1e-8, "%s: %.1e from the closed form, contact force %.1e of the load" % (tag, error, force), out)
            if tau == "1e-8":
                expect(s["states"] == "0/0/%d/0/0/0" % s["contact"], "%s: states %s, not all M2" % (tag, s["states"]), out)


@test("a near-grazing load (top 0,0,-0.01, right -200,30,0; level 4) converges without cycling, with a superlinear last step and the Coulomb law", full=True)
def hard_grazing():
    s, out, _ = converged("grazing", 4, ["-traction_top", "0,0,-0.01", "-traction_right", "-200,30,0"])
    superlinear_end("grazing", out)


@test("near incompressibility (nu = 0.45, 0.499; levels 4, 6) converges; the cycle of the plain iteration at level 4, nu = 0.49, is detected (reason CYCLE) and the globalization breaks it with a damped step", full=True)
def hard_incompressible():
    for level in (4, 6):
        for nu in ("0.45", "0.499"):
            out, s = prism(level, extra=["-nu", nu], h5="nu%s_L%d.h5" % (nu, level))
            expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and s["iters"] <= 20, "level %d, nu %s: %s after %d iterations" % (level, nu, s["reason"], s["iters"]), out)
            law("nu%s_L%d" % (nu, level))
    out, s = prism(4, extra=["-nu", "0.49", "-snes_ssstar_globalization", "0", "-snes_ssstar_monitor_states"], expect_rc=NOT_CONVERGED)
    expect(s["reason"] == "DIVERGED_LINE_SEARCH" and "ssstar: CYCLE" in out and "cycle detected" in out, "the plain iteration's cycle is not reported", out)
    out, s = prism(4, extra=["-nu", "0.49", "-snes_ssstar_monitor_states", "-snes_view"])
    expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and remedies(out)["damped"] >= 1 and "damped step alpha = 0.5" in out, "no damped step shown and counted", out)


@test("units and scale: MPa/mm, Pa/m (E = 2.1e11) and loads x 1e-6 and x 1e6 give the same iterations (+-1), states and solution (1e-9 relative after the change of units; level 4)", full=True)
def hard_units():
    loads = lambda s: ["-traction_top", "0,0,%g" % (-500 * s), "-traction_right", "%g,%g,%g" % (-200 * s, 30 * s, 200 * s)]
    variants = {"MPa_mm": ([], 1), "Pa_m": (["-mesh_scale", "1e-3", "-E", "2.1e11"] + loads(1e6), 1e-3),
                "small": (loads(1e-6), 1e-6), "large": (loads(1e6), 1e6)}
    summary = {}
    for name, (options, _) in variants.items():
        out, summary[name] = prism(4, extra=options, h5="units_%s.h5" % name)
        expect(summary[name]["reason"] == "CONVERGED_FNORM_RELATIVE", "%s: %s" % (name, summary[name]["reason"]), out)
    reference = contact("units_MPa_mm")
    for name, (_, scale) in variants.items():
        expect(abs(summary[name]["iters"] - summary["MPa_mm"]["iters"]) <= 1 and summary[name]["states"] == summary["MPa_mm"]["states"],
               "%s: %d iterations, states %s; MPa/mm: %d, %s" % (name, summary[name]["iters"], summary[name]["states"], summary["MPa_mm"]["iters"], summary["MPa_mm"]["states"]))
        error = relative_difference(contact("units_" + name)["contact/displacement"] / scale, reference["contact/displacement"])
        expect(error <= 1e-9, "%s: contact displacement %.1e relative from MPa/mm" % (name, error))


@test("starting points (level 4): zero, the linear-elastic solution and a random point 100x the solution converge 1e-8 near a tight reference by the globalization (damped steps, or nodes stuck at a reversed slip); the plain iteration from the far ones stops with an honest reason (CYCLE or STAGNATION) and a finite output file", full=True)
def hard_starting_points():
    import numpy as np
    converged("start_zero", 4, [])
    far = "%g" % (100 * abs(contact("start_zero")["contact/displacement"]).max())
    starts = {"elastic": ["-initial_guess", "elastic"], "random": ["-initial_guess", "random", "-initial_guess_scale", far]}
    for name, options in starts.items():
        out, s = prism(4, extra=options + ["-snes_view"], h5="start_%s.h5" % name)
        expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and s["iters"] <= 20, "%s: %s after %d iterations" % (name, s["reason"], s["iters"]), out)
        error = relative_difference(contact("start_" + name)["contact/displacement"], contact("start_zero_ref")["contact/displacement"])
        expect(error <= 1e-8, "%s: %.1e from the tight reference" % (name, error), out)
        r = remedies(out)  # the globalization's work: damped steps, or nodes stuck at a reversed slip (derivation 19c)
        expect(r["damped"] + r["stuck"] >= 1, "%s: no damped step and no node stuck at a reversed slip" % name, out)
        out, s = prism(4, extra=options + ["-snes_ssstar_globalization", "0"], h5="plain_%s.h5" % name, expect_rc=NOT_CONVERGED)
        expect(s["reason"] in ("DIVERGED_LINE_SEARCH", "DIVERGED_LOCAL_MIN") and re.search(r"ssstar: (CYCLE|STAGNATION)", out),
               "plain iteration from %s: %s" % (name, s["reason"]), out)
        expect(all(np.isfinite(a).all() for a in contact("plain_" + name).values()), "plain iteration from %s: NaN or Inf in the output file" % name)
    out, s = prism(3, extra=["-initial_guess", "elastic", "-snes_ssstar_globalization", "0"], expect_rc=NOT_CONVERGED)
    expect(s["reason"] == "DIVERGED_LOCAL_MIN" and "ssstar: STAGNATION" in out, "the plain iteration's stagnation (level 3, elastic start) is not reported", out)


@test("degenerate scenes (level 3): zero load gives u = 0 in 0 iterations; a load that lifts the body off separates every node; a load that slides it (phi = 0.1) makes every node slide")
def hard_degenerate():
    import numpy as np
    out, s = prism(3, extra=["-traction_top", "0,0,0", "-traction_right", "0,0,0"], h5="zero_load.h5")
    expect(s["reason"] == "CONVERGED_FNORM_ABS" and s["iters"] == 0, "zero load: %s after %d iterations" % (s["reason"], s["iters"]), out)
    expect(not np.any(contact("zero_load")["fields/displacement"]), "zero load: u is not 0")
    out, s = prism(3, extra=["-traction_top", "0,0,500"])
    expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and s["iters"] <= 2 and s["sep_sl_st"] == "%d/0/0" % s["contact"], "lift-off: %s, %s" % (s["reason"], s["sep_sl_st"]), out)
    s, out, _ = converged("sliding_everywhere", 3, ["-snes_ssstar_friction", "0.1", "-traction_top", "0,0,-500", "-traction_right", "-2000,0,0"], max_iters=8)
    expect(s["sep_sl_st"] == "0/%d/0" % s["contact"], "not every node slides: %s" % s["sep_sl_st"], out)


def states_per_iteration(out):
    return re.findall(r"SSStar states (.*)", out)


@test("determinism: 1, 2 and 3 ranks give the same iterates (|z| to 1e-8 relative above round-off, the same states and remedies at every iteration; default scene level 5, tangential load phi = 0.6 level 4 with damped steps), and a rerun on one rank writes a bitwise-equal HDF5 file", full=True)
def hard_determinism():
    import h5py
    import numpy as np
    for level, options in ((5, []), (4, TANGENTIAL + ["-snes_ssstar_friction", "0.6"])):
        outs = [prism(level, ranks, extra=options + ["-snes_ssstar_monitor_states"])[0] for ranks in (1, 2, 3)]
        for ranks, out in zip((2, 3), outs[1:]):
            z1, z = znorms(outs[0]), znorms(out)
            expect(len(z1) == len(z), "level %d: %d iterations on 1 rank, %d on %d" % (level, len(z1), len(z), ranks), outs[0] + out)
            for k, (a, b) in enumerate(zip(z1, z)):
                # below 1e-8 of the first |z| the last, superlinear step is at round-off: its Krylov solve on an old LU
                # sums in an order that depends on the ranks
                expect(a < 1e-8 * z1[0] or abs(a - b) <= 1e-8 * a, "level %d, iterate %d: |z| %.12e on 1 rank, %.12e on %d" % (level, k, a, b, ranks), outs[0] + out)
            expect(states_per_iteration(outs[0]) == states_per_iteration(out), "level %d: other states or remedies on %d ranks" % (level, ranks), outs[0] + out)
    prism(4, extra=TANGENTIAL + ["-snes_ssstar_friction", "0.6"], h5="rerun_a.h5")
    prism(4, extra=TANGENTIAL + ["-snes_ssstar_friction", "0.6"], h5="rerun_b.h5")
    with h5py.File(h5("rerun_a"), "r") as a, h5py.File(h5("rerun_b"), "r") as b:
        names = []
        a.visititems(lambda name, obj: names.append(name) if isinstance(obj, h5py.Dataset) else None)
        for name in names:
            expect(name in b and np.array_equal(a[name][:], b[name][:]), "rerun: dataset %s differs" % name)


@test("the remedies are observable: with no damping allowed (level 6, nu = 0.49) a full step and then sliding nodes whose slip reverses twice in a cycle stuck at the kink (docs/derivation.md 19c; a doubled gamma broke that cycle before) are shown by -snes_ssstar_monitor_states, counted by -snes_view, and the solve converges; a singular Newton matrix shows a regularized step and fixed-point rounds before SINGULAR_NEWTON_MATRIX (1 and 2 ranks)")
def hard_remedies():
    out, s = prism(6, extra=["-nu", "0.49", "-snes_ssstar_damping_min", "1", "-snes_ssstar_monitor_states", "-snes_view"], h5="nodamping.h5")
    counts = remedies(out)
    expect(s["reason"] == "CONVERGED_FNORM_RELATIVE" and counts["full"] >= 1 and counts["stuck"] >= 1 and counts["damped"] == 0, "counts %s" % counts, out)
    expect("full step after a failed line search" in out and "nodes stuck at a reversed slip;" not in out and re.search(r"; \d+ nodes stuck at a reversed slip", out), "remedies not shown", out)
    law("nodamping")
    for ranks in (1, 2):
        out = run(mpiexec(ranks, os.path.join(ROOT, "tests", "test_plain_contact"), "-dll_append", LIB, "-snes_type", "ssstar", "-singular",
                          "-snes_ssstar_monitor_states", "-snes_view", "-snes_converged_reason"), expect_rc=1)
        counts = remedies(out)
        violation = re.search(r"Coulomb law violation (\S+)", out)
        expect("regularized Newton step; fixed-point round" in out and counts["regularized"] >= 1 and counts["fixed_point"] >= 1
               and "ssstar: SINGULAR_NEWTON_MATRIX" in out, "%d ranks: counts %s" % (ranks, counts), out)
        expect(violation is not None and violation.group(1) not in ("nan", "inf", "-nan"), "%d ranks: the returned iterate is not finite" % ranks, out)


@test("bad input is refused with an error naming it: NaN or Inf in the load, the stiffness or the initial guess (sparse and dense P, 1 and 2 ranks); -snes_rtol nan; unknown or bad values of -snes_ssstar_* options", full=True)
def hard_bad_input():
    messages = {"load": "the reduced load f is NaN or Inf at contact dof 11 (node 3",
                "stiffness": "the reduced stiffness P has NaN or Inf entries in row 11 (node 3",
                "guess": "the initial guess is NaN or Inf at contact dof 11 (node 3"}
    for what, message in messages.items():
        for ranks in (1, 2):
            for dense in ("0", "1"):
                out = run(mpiexec(ranks, os.path.join(ROOT, "tests", "test_plain_contact"), "-dll_append", LIB, "-snes_type", "ssstar", "-poison", what, "-dense", dense), expect_rc=1)
                expect(message in out, "-poison %s, %d ranks, dense %s: not refused by name" % (what, ranks, dense), out)
    options = {("-snes_rtol", "nan"): "-snes_rtol nan", ("-snes_ssstar_friction", "nan"): "-snes_ssstar_friction nan",
               ("-snes_ssstar_friction_law", "dry"): "Unknown option dry for -snes_ssstar_friction_law",
               ("-snes_ssstar_reduction", "lu"): "Unknown option lu for -snes_ssstar_reduction",
               ("-snes_ssstar_globalization", "maybe"): "Option -snes_ssstar_globalization maybe: maybe is not true or false",
               ("-snes_ssstar_damping_min", "0"): "-snes_ssstar_damping_min 0", ("-snes_ssstar_stagnation_its", "0"): "-snes_ssstar_stagnation_its 0",
               ("-snes_ssstar_scaling", "-1"): "-snes_ssstar_scaling -1", ("-initial_guess", "far"): "Unknown option far for -initial_guess"}
    for option, message in options.items():
        out = run([PRISM, "-level", "2"] + list(option), expect_rc=1)
        expect(message in out, "%s %s: not refused by name" % option, out)


@test("valgrind (memcheck, level 3, one rank): no invalid access and nothing definitely lost outside Open MPI's and PETSc's start-up (tests/valgrind.supp) [slow]", full=True)
def hard_valgrind():
    prism(3)  # the mesh exists before valgrind runs
    out = run(["valgrind", "--leak-check=full", "--errors-for-leak-kinds=definite", "--num-callers=40",
               "--suppressions=" + os.path.join(ROOT, "tests", "valgrind.supp"), PRISM, "-level", "3", "-o", h5("valgrind")], check_memory=False)
    expect("definitely lost: 0 bytes in 0 blocks" in out or "All heap blocks were freed" in out, "valgrind finds a leak", out)
    expect(re.search(r"ERROR SUMMARY: 0 errors", out) is not None, "valgrind finds errors", out)
