"""auto's choice of the route (src/reduction/auto.c, docs/guide/choosing-a-route.md): from what each route costs,
not from the size of K alone; the estimates it prints; the memory estimate of both routes before the work."""
import os
import re

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
SCENES = os.path.join(ROOT, "scenes")
ESTIMATES = re.compile(r"auto's estimates \(flops of a dense LU\): the dense route ([\d.e+-]+), the whole body ([\d.e+-]+) \(K holds the body by ([\d.e+-]+)\)")
MUMPS = re.compile(r"MUMPS analysis: ([\d.e+-]+) flops to factor")
DOFS = re.compile(r"assembly: K of (\d+) dofs")
CONTACT_DOFS = re.compile(r"^contact: (\d+) contact nodes", re.M)


def chosen(args, program=CONTACT, ranks=1):
    """The route auto takes for a scene (its set-up line; one Newton step is enough), and the run's output"""
    out = run(mpiexec(ranks, program, *args, "-snes_max_it", "1", "-snes_view", "-info", ":mat"), expect_rc=None)
    m = re.search(r"set-up: (K reduced to \d+ contact dofs by the direct Schur complement \(chosen by auto\)|the whole body, \d+ dofs, P never formed \(reduction none, chosen by auto\))", out)
    expect(m is not None, "no set-up line of auto's: %s" % " ".join(args), out)
    return ("direct" if m.group(1).startswith("K") else "none"), out


@test("auto chooses from what each route costs, not from K's size: the unstructured slab of issue 31 (scenes/press.opts: "
      "K of 17 325 dofs, below the former 20 000, but 1 981 contact nodes, most separated: a dense 5 943 x 5 943 LU per "
      "Newton step) takes the whole body without even analysing K for MUMPS; the prism at level 4 (432 contact dofs) the "
      "dense route; Hertz's half ball at level 2 (27 045 dofs, above the former limit, but a small cap on a body held by a "
      "soft spring, where the whole body's Krylov solves crawl) the dense route; the prism at level 10 the whole body; "
      "-snes_view prints auto's two estimates, the dense one MUMPS's flops plus 10 LUs of (2/3)(3p)^3", full=True)
def auto_chooses_by_cost():
    route, out = chosen(["-options_file", os.path.join(SCENES, "press.opts"), "-steps", "0,1"])
    expect(route == "none" and "the dense LUs alone cost more" in out and MUMPS.search(out) is None, "the slab: not the whole body before any analysis", out)
    for args, program, expected in ((["-level", "4"], PRISM, "direct"), (["-options_file", os.path.join(SCENES, "hertz.opts"), "-level", "2"], CONTACT, "direct"),
                                    (["-level", "10", "-nested_levels", "0"], PRISM, "none")):
        route, out = chosen(args, program)
        expect(route == expected, "%s: auto took %s, not %s" % (" ".join(args), route, expected), out)
        m = ESTIMATES.search(out)
        expect(m is not None, "%s: -snes_view prints no estimates of auto's" % " ".join(args), out)
        dense, whole = float(m.group(1)), float(m.group(2))
        expect((dense <= whole) == (expected == "direct"), "%s: the estimates %g, %g do not give the choice" % (" ".join(args), dense, whole), out)
        f = MUMPS.search(out)
        NC = 3 * int(CONTACT_DOFS.search(out).group(1))
        if f:
            expect(abs(dense - (float(f.group(1)) + 10 * 2.0 / 3.0 * NC ** 3)) <= 5e-3 * dense, "%s: the dense estimate is not MUMPS's flops plus 10 LUs" % " ".join(args), out)


@test("the memory estimate before the work counts the route: on the contact line the whole body's peak and the dense "
      "route's (MUMPS's factors of K with the Schur block, P and the Newton step's dense matrices); the prism at level 8 "
      "on the dense route peaks within 20 % of the dense estimate (measured +2 %), on the whole body within 20 % of the "
      "whole body's", full=True)
def memory_estimate_both_routes():
    for route, group in (("direct", 2), ("none", 1)):
        out, s = prism(8, extra=["-snes_ssstar_reduction", route])
        m = re.search(r"contact: \d+ contact nodes in 1 group, estimated peak ([\d.]+) GB per rank on the whole body, ([\d.]+) GB on the dense route", out)
        expect(m is not None, "no estimates of both routes on the contact line", out)
        estimate = float(m.group(group))
        expect(abs(estimate / s["peak_gb"] - 1) <= 0.2, "%s: estimated %.3f GB per rank, measured %.3f" % (route, estimate, s["peak_gb"]), out)


@test("on the unstructured slab of issue 31 (scenes/press.opts, pressed in one step) the peak memory per rank is "
      "within 20 % of the estimate printed before the work on both routes (the issue: 'estimated peak 0.179 GB' against "
      "1.86 GB on the dense route; measured 1.638 GB against 1.648 on one rank)", full=True)
def memory_estimate_slab():
    for route, group in (("direct", 2), ("none", 1)):
        out = run(mpiexec(1, CONTACT, "-options_file", os.path.join(SCENES, "press.opts"), "-steps", "0,1", "-snes_ssstar_reduction", route))
        m = re.search(r"contact: \d+ contact nodes in 1 group, estimated peak ([\d.]+) GB per rank on the whole body, ([\d.]+) GB on the dense route", out)
        peak = re.search(r"summary: .* peak ([\d.]+) GB per rank", out)
        expect(m is not None and peak is not None, "no estimates or no peak", out)
        estimate, measured = float(m.group(group)), float(peak.group(1))
        expect(abs(estimate / measured - 1) <= 0.2, "%s: estimated %.3f GB per rank, measured %.3f" % (route, estimate, measured), out)
