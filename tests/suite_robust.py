"""The whole-body path is as robust as the dense route (issue 18), and both are right at the default settings (issue
23): nearly floating bodies (soft springs against a stiff body: Newton matrices of condition 1e5 and more) under tilted
rollers, rigid balls and two-body pairs, sheared, with friction from 0.1 to 2, on 1 to 4 ranks: both paths converge,
their files satisfy the law (tests/check_solution.py) and lie within 1e-6 of the exact discrete solution (the dense route
on one rank at -snes_rtol 1e-13; docs/guide/converged.md). bench/robust.py sweeps the whole families (FAMILY,
PATHS) on 1-4 ranks and prints the table; here members of them (tests/suite_converged.py has the load-path ones)."""
import os
import re
import sys

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

sys.path.insert(0, os.path.join(ROOT, "bench"))
import robust  # noqa: E402

robust.OUT = os.path.join(OUT, "robust")  # the members' files among the tests' own
os.makedirs(robust.OUT, exist_ok=True)
from robust import FAMILY, ROLLER  # noqa: E402

REFINED = re.compile(r"(\d+) inexact steps solved on to the floor after a failed full step")


def members_pass(names, ranks):
    for name in names:
        for r in ranks:
            result = robust.run_member(name, FAMILY[name], r)
            expect(result is not None, "%s: the reference did not converge" % name)
            for path, res in result.items():
                expect(robust.passed(res), "%s, %s, %d ranks: %s" % (name, path, r, robust.cell(res)))


@test("issue 18's scene, a rigid cylinder with its axis turned 30 degrees on a block held by a soft spring, sheared along x at 0.22 of the load either way: at the defaults both paths converge, satisfy the law and lie within 1e-6 of the exact discrete solution on 1, 2 and 3 ranks (3 ranks: a rank owns no dof; it stopped with MPI_ERR_TRUNCATE, and the reversed shear stagnated on 1 and 2 ranks)", full=True)
def robust_issue_scene():
    members_pass(["roller 30°, shear 0.22", "roller 30°, shear -0.22"], (1, 2, 3))


@test("the dense route on 4 ranks, where the unknown dofs of the dense Newton matrix move between ranks from one step to the next, completes (it hung in MatCreateDense), and both paths lie within 1e-6 of the exact discrete solution there", full=True)
def robust_dense_four_ranks():
    members_pass(["roller 60°, shear 0.4"], (4,))


@test("the robustness family at the defaults on 1-4 ranks (soft springs k = 1e-3 and 1e-1 against E = 2.1e5, friction 0.1 (the block slides) and 2, rigid balls, two-body pairs with shear): both paths converge, satisfy the law and lie within 1e-6 of the exact discrete solution", full=True)
def robust_family():
    for name, ranks in (("roller 30°, k = 1e-3", 2), ("roller 30°, k = 1e-1", 1), ("roller 30°, phi = 0.1 (slides)", 3), ("roller 30°, phi = 2", 4),
                        ("ball, phi = 2, shear 0.3 diagonal", 4), ("ball, k = 1e-3, phi = 0.5", 2), ("slider (pair), phi = 0.9 (sticks)", 3),
                        ("mindlin (pair), Q = 0.9 phi P, phi = 0.1", 2)):
        members_pass([name], (ranks,))


@test("an inexact Newton step (whole body) whose full step fails the line search is solved on to the floor tolerance before any damping (-snes_view counts them: at least one on the reversed shear of issue 18's scene), and none is on the prism, whose iteration needs no remedy")
def robust_refined_steps():
    out = run(mpiexec(1, os.path.join(ROOT, "examples", "contact"), *ROLLER, "-traction_bottom", "-66,0,300", "-snes_ssstar_reduction", "none", "-snes_view"))
    m = REFINED.search(out)
    expect(m is not None and int(m.group(1)) >= 1, "no refined step on the reversed shear", out)
    out = run(mpiexec(1, PRISM, "-level", "5", "-snes_ssstar_reduction", "none", "-snes_view"))
    m = REFINED.search(out)
    expect(m is not None and int(m.group(1)) == 0 and "remedies: damped steps 0, full steps after a failed line search 0" in out, "the prism refined a step or needed a remedy", out)
