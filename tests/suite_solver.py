"""The SNES type on its own: kernels, the Newton step, the -dll_append path, singular systems."""
import os

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)


@test("per-node kernels (approximation step, Table 1 classification, G/H and S/T blocks) give hand-computed values for L, M1, M2, M3+, M3-, M4 and phi = 0")
def kernels():
    run([os.path.join(ROOT, "tests", "test_kernels")])


@test("a Newton step of SNESSolve equals the 6p step D [dv; eta] = [z; z] to 1e-10 relative on random problems (Coulomb, phi = 0, Tresca, "
      "frictionless nodes; tilted normals, gaps): the eliminated dense system with a fresh LU and on the previous step's LU (GMRES), "
      "and the sparse path; 1/cond estimate within 10x of the exact one; 1 and 2 ranks")
def newton_3p_equals_6p():
    for ranks in (1, 2):
        for extra in ([], ["-sparse"]):
            out = run(mpiexec(ranks, os.path.join(ROOT, "tests", "test_newton"), *extra))
            expect(out.rstrip().endswith("OK"), "%d ranks %s" % (ranks, extra), out)


def plain_contact(ranks, friction, *extra, expect_rc=0):
    return run(mpiexec(ranks, os.path.join(ROOT, "tests", "test_plain_contact"), "-dll_append", LIB, "-snes_type", "ssstar",
                       "-snes_ssstar_friction", str(friction), *extra), expect_rc=expect_rc)


@test("-dll_append loads the type into a program that does not link libssstar; sparse P; Coulomb law to 1e-8 (1 rank)")
def dll_append_1rank():
    plain_contact(1, 0.3)


@test("-dll_append path on 2 ranks (parallel AIJ P, MUMPS LU); Coulomb law to 1e-8")
def dll_append_2ranks():
    plain_contact(2, 0.3)


@test("phi = 0 (frictionless) through the -dll_append path converges and satisfies the law")
def dll_append_frictionless():
    plain_contact(1, 0.0)


@test("a dense P (LAPACK LU on 1 rank, ScaLAPACK on 2) solves the same problem")
def dll_append_dense():
    for ranks in (1, 2):
        plain_contact(ranks, 0.3, "-dense")


@test("a singular Newton matrix ends the solve with DIVERGED_LINEAR_SOLVE (sub-reason SINGULAR_NEWTON_MATRIX), not a crash: sparse and dense, 1 and 2 ranks")
def singular_newton_matrix():
    for ranks in (1, 2):
        for dense in ("0", "1"):
            out = plain_contact(ranks, 0.3, "-singular", "-dense", dense, "-snes_view", expect_rc=1)
            expect("DIVERGED_LINEAR_SOLVE" in out and "SINGULAR_NEWTON_MATRIX" in out and "PETSC ERROR" not in out,
                   "%d ranks, dense %s: no honest divergence reason" % (ranks, dense), out)
