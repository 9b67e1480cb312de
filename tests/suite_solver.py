"""The SNES type on its own: kernels, the Newton step, the -dll_append path, singular systems, input wrong on one rank (every rank ends with the error), options prefixes."""
import os
import re
import subprocess

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


@test("a singular Newton matrix ends the solve with DIVERGED_LINEAR_SOLVE (sub-reason SINGULAR_NEWTON_MATRIX), not a crash: sparse and dense, 1 and 2 ranks", full=True)
def singular_newton_matrix():
    for ranks in (1, 2):
        for dense in ("0", "1"):
            out = plain_contact(ranks, 0.3, "-singular", "-dense", dense, "-snes_view", expect_rc=1)
            expect("DIVERGED_LINEAR_SOLVE" in out and "SINGULAR_NEWTON_MATRIX" in out and "PETSC ERROR" not in out,
                   "%d ranks, dense %s: no honest divergence reason" % (ranks, dense), out)


def within_a_minute(cmd, env=None):
    """Runs cmd under timeout 60 (a hang fails the test instead of blocking the suite): its exit status and output"""
    p = subprocess.run(["timeout", "-k", "5", "60"] + cmd, cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    expect(p.returncode not in (124, 137), "still running after 60 s (a rank waits for another): %s" % " ".join(cmd), p.stdout)
    return p.returncode, p.stdout


COLLECTIVE = {"straddle": "dof 24 of contact node 3 of rank 0 is not owned by that rank (it owns 0..23)",
              "normals": "SNESSSStarSetContactNodes: the normals: 11 local entries, expected 12 (3 per contact node) [found on rank 1]",
              "friction": "Contact node 2 (law coulomb), its friction -0.5: the friction coefficient must be a number >= 0 [found on rank 1]",
              "law": "law 99 of contact node 1 is not in the table of laws (0..3, SSStarLawGetNames()) [found on rank 1]",
              "operator": "contact point 2 (dofs 36, 37, 38): B's block at the point's own dofs is not a positive multiple of a rotation"}


@test("input wrong on one rank of two (a contact node whose dofs straddle the ranks, normals of the wrong size, a negative per-node friction, a law not in the table, a contact operator block that is not a rotation) ends both ranks within seconds with the same error code and the message of the rank that found it, naming the node (and the dof); without catching, the program exits non-zero on every rank with that message; the same program without the fault converges")
def collective_errors():
    program = os.path.join(ROOT, "tests", "test_collective")
    for case, message in COLLECTIVE.items():
        rc, out = within_a_minute(mpiexec(2, program, "-case", case, "-catch"))
        errors = re.findall(r"rank (\d): error (\d+): (.*)", out)
        expect(rc != 0 and len(errors) == 2 and {e[0] for e in errors} == {"0", "1"} and errors[0][1:] == errors[1][1:] and errors[0][1] != "0" and message in errors[0][2],
               "-case %s: not the same error with the message on both ranks" % case, out)
    rc, out = within_a_minute(mpiexec(2, program, "-case", "straddle"))
    expect(rc != 0 and COLLECTIVE["straddle"] in out and "Global size overflow" not in out, "uncaught: no clean exit with the message", out)
    rc, out = within_a_minute(mpiexec(2, program, "-case", "none", "-catch"))
    expect(rc == 0 and "rank 0: error 0: none" in out and "rank 1: error 0: none" in out and "CONVERGED_FNORM" in out, "the faultless problem does not converge", out)


@test("a Python program (petsc4py and the module) on 2 ranks whose contact node straddles the ranks, or whose normals have the wrong size on one rank, exits non-zero within seconds on both ranks, each raising the message (ssstar.Error, a petsc4py.PETSc.Error, from the module; petsc4py's from snes.solve; no 'Global size overflow', no hang); without the fault it solves")
def collective_errors_python():
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    script = os.path.join(ROOT, "tests", "python_collective_check.py")
    messages = {"straddle": "SNESSSStarSetContactNodes: dof 12 of contact node 3 of rank 0 is not owned by that rank (it owns 0..11)",
                "normals": "SNESSSStarSetContactNodes: the normals: 11 local entries, expected 12 (3 per contact node) [found on rank 1]"}
    for case, message in messages.items():
        rc, out = within_a_minute(mpiexec(2, PYTHON, script, "-case", case), env)
        expect(rc != 0 and out.count(message) == 2 and "Global size overflow" not in out, "-case %s: not the message on both ranks" % case, out)
    rc, out = within_a_minute(mpiexec(2, PYTHON, script, "-case", "none"), env)
    expect(rc == 0 and "rank 0: solved" in out and "rank 1: solved" in out, "the faultless program does not solve", out)


@test("a SNES with the options prefix foo_ gives it to its reduction: -foo_snes_ssstar_reduction chooses it, and the direct, mumps and explicit reductions read -foo_schur_direct_mumps_icntl_14, -foo_schur_mat_mumps_icntl_14, -foo_interior_ksp_view (no unused option of its own, -options_left); -foo_schur_direct_mumps_icntl_7 is refused by that name, the unprefixed -schur_direct_mumps_icntl_7 is left unread (2 ranks)")
def reduction_options_prefix():
    program = os.path.join(ROOT, "tests", "test_collective")
    own = {"direct": "-foo_schur_direct_mumps_icntl_14", "mumps": "-foo_schur_mat_mumps_icntl_14", "explicit": "-foo_interior_ksp_view"}
    for red, option in own.items():
        out = run(mpiexec(2, program, "-prefix", "foo_", "-foo_snes_ssstar_reduction", red, *((option, "30") if red != "explicit" else (option,)), "-options_left"))
        expect("CONVERGED_FNORM" in out and "with the reduction %s" % red in out and "There are no unused options" in out, "%s: %s not read" % (red, option), out)
        if red == "explicit":
            expect("KSP Object: (foo_interior_)" in out, "explicit: the interior solver has not the prefix foo_interior_", out)
    out = run(mpiexec(2, program, "-prefix", "foo_", "-foo_snes_ssstar_reduction", "direct", "-foo_schur_direct_mumps_icntl_7", "2"), expect_rc=1)
    expect("-foo_schur_direct_mumps_icntl_7: ICNTL(7) is set by the direct reduction itself" in out, "the prefixed ICNTL(7) is not refused by its name", out)
    out = run(mpiexec(2, program, "-prefix", "foo_", "-foo_snes_ssstar_reduction", "direct", "-schur_direct_mumps_icntl_7", "2", "-options_left"))
    expect("with the reduction direct" in out and "Option left: name:-schur_direct_mumps_icntl_7" in out, "the unprefixed option was read", out)
