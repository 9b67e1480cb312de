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


@test("load histories (include/ssstarhistory.h, tests/test_history): the issue's example, a plain vector, spaces, exponents, negative times, one component, a single knot and a value of 1000 knots parse to the hand-computed knots; evaluation is linear between knots, constant outside them and exact at them; the knots of several histories merge (1 and 1.0 once); -steps N gives the first knot and N equal steps ending exactly at the last, -steps t1,t2,... the times; every malformed value (empty, no time, not a number, NaN, Inf, wrong count, times not increasing, an empty knot, a count 0 or without a time span) is refused with a message naming the option and the knot or time, leaving nothing allocated (-malloc_dump)")
def history_parser():
    out = run([os.path.join(ROOT, "tests", "test_history")])
    expect("OK: 0 failures" in out, "tests/test_history", out)


@test("the solver's offsets (SNESSSStarSetContactOffsets, tests/test_offsets): the whole body of loadpath_check.py's check 1 (tilted frames, gaps, a moving obstacle, pair points with master weights, Coulomb, Tresca and frictionless nodes; press, shear, release, reverse, release in 21 steps, each step's offsets (10.4) from the previous solution) equals numpy's answer to 1e-9 at every step (measured 5e-13) on the dense route (direct) and the whole body (none), 1, 2 and 3 ranks (one rank without contact points); the reduction is set up once for the whole path")
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
