"""The Newton step with a dense P: the eliminated system, the reuse of its LU, its counts."""
import re

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)


def znorms(out):
    return [float(z) for z in re.findall(r"SNES Function norm ([0-9.eE+-]+)", out)]


def step_counts(out):
    m = re.search(r"last solve: (\d+) LU factorizations \(last 1/cond (\S+)\), (\d+) steps on an old LU \((\d+) Krylov iterations\), (\d+) fallbacks", out)
    expect(m is not None, "no Newton counts in -snes_view", out)
    return {"lu": int(m.group(1)), "rcond": float(m.group(2)), "reused": int(m.group(3)), "krylov": int(m.group(4)), "fallbacks": int(m.group(5))}


@test("the reuse of the LU does not change the outer iteration: prism levels 4 and 7 (1 rank) and 5 (2 ranks) give the same |z| at every "
      "iterate (1e-6 relative while above 1e-10) and the same states with a fresh LU at every step (-snes_ssstar_lu_reuse -1), "
      "the default (reuse when no node changed rows) and reuse at every step (1); -snes_view counts LU + reused steps = iterations, "
      "the 1/cond estimate is in (0, 1], and the state monitor shows the counts", full=True)
def newton_lu_reuse_keeps_iterations():
    for level, ranks in ((4, 1), (7, 1), (5, 2)):
        results = {}
        for reuse in ("-1", "0", "1"):
            out, s = prism(level, ranks, extra=["-snes_view", "-snes_ssstar_monitor_states", "-snes_ssstar_lu_reuse", reuse])
            c = step_counts(out)
            expect(c["lu"] + c["reused"] == s["iters"], "level %d reuse %s: %d LU + %d reused != %d iterations" % (level, reuse, c["lu"], c["reused"], s["iters"]), out)
            expect(0 < c["rcond"] <= 1, "level %d: 1/cond estimate %g" % (level, c["rcond"]), out)
            expect(re.search(r"Newton steps so far: \d+ LU, \d+ on an old LU \(\d+ Krylov its\)", out) is not None, "no counts in the state monitor", out)
            results[reuse] = (znorms(out), s, c)
        ref, sref, cref = results["-1"]
        expect(cref["reused"] == 0 and cref["lu"] == sref["iters"], "level %d: -snes_ssstar_lu_reuse -1 reused an LU" % level)
        expect(results["1"][2]["reused"] > 0, "level %d: -snes_ssstar_lu_reuse 1 reused no LU" % level)
        for reuse in ("0", "1"):
            z, s, _ = results[reuse]
            expect(len(z) == len(ref) and s["states"] == sref["states"], "level %d reuse %s: %d iterates, states %s; fresh LU: %d, %s"
                   % (level, reuse, len(z), s["states"], len(ref), sref["states"]))
            for k, (a, b) in enumerate(zip(ref, z)):
                expect(a < 1e-10 or abs(a - b) <= 1e-6 * a, "level %d reuse %s, iterate %d: |z| %.10e, fresh LU %.10e" % (level, reuse, k, b, a))
