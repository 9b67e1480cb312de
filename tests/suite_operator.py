"""The contact operator B (SNESSSStarSetContactOperator, docs/contact-operator.md): points compared with another
body's surface through master weights, in tilted frames, with scaled rows; the reduced operator in the points'
variables, the contact law on w = B u + g, the refusal of a rank-deficient B."""
import os
import re

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

OPERATOR = os.path.join(ROOT, "tests", "test_operator")
VIOLATION = re.compile(r"contact law on w: worst violation (\S+)")


@test("two chains pressed together through B (master weights, tilted frames, a row scale of 2): the reduced operator the direct reduction computes equals (C K^-1 C^T)^-1 in the points' variables (C = R^T B / d) to 1e-12 and is symmetric")
def operator_reduced_formula():
    out = run(mpiexec(1, OPERATOR, "-case", "formula"))
    expect("reduced operator:" in out, "no check printed", out)


@test("the solution through B satisfies the contact law on w = B u + g (w_n >= 0, lambda_n >= 0, complementarity, the Coulomb cone, sliding on its boundary) with K u - b = B^T lambda, to 1e-8, on the dense route and the whole body, on 1, 2 and 3 ranks; every run gives the same u to 1e-8")
def operator_contact_law():
    import numpy as np
    sols = {}
    for reduction in ("direct", "none"):
        for ranks in (1, 2, 3):
            name = os.path.join(OUT, "operator_%s_%d.bin" % (reduction, ranks))
            out = run(mpiexec(ranks, OPERATOR, "-snes_ssstar_reduction", reduction, "-o", name))
            m = VIOLATION.search(out)
            expect(m is not None and float(m.group(1)) <= 1e-8, "%s, %d ranks: %s" % (reduction, ranks, m.group(1) if m else "no check"), out)
            sols[(reduction, ranks)] = np.fromfile(name, dtype=">f8")[-72:]  # the 72 entries of u (header first)
    ref = sols[("direct", 1)]
    for key, u in sols.items():
        d = np.abs(u - ref).max() / np.abs(ref).max()
        expect(d <= 1e-8, "%s on %d ranks differs from direct on 1 rank by %.1e" % (key[0], key[1], d))


@test("a rank-deficient B is refused naming the point: a singular block at the point's own dofs, and a master dof that is another point's own dof")
def operator_refused():
    out = run(mpiexec(1, OPERATOR, "-case", "singular"), expect_rc=1)
    expect("contact point 1 (dofs 15, 16, 17): B's block at the point's own dofs has determinant 0., not positive: B is rank-deficient there" in out, "singular block not refused by name", out)
    out = run(mpiexec(1, OPERATOR, "-case", "shared"), expect_rc=1)
    expect("contact point 0 is compared with dof 15, which is another contact point's own dof" in out, "shared dof not refused by name", out)
