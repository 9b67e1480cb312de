#!/usr/bin/env python3
"""The ssstar test suite (make test). Each test states the requirement it checks; the last line is
"N passed, N failed". Usage: tests/run.py [-k SUBSTRING] [-v]"""
import argparse
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "tests", "output")
LIB = os.path.join(ROOT, "lib", "libssstar.so")
PYTHON = "/usr/bin/python3"  # Debian's, with h5py
PRISM = os.path.join(ROOT, "examples", "prism")
CHECK = [PYTHON, os.path.join(ROOT, "tests", "check_solution.py")]
# iterations from u = 0 and separated/sliding/sticking counts of an independent implementation (DERIVATION.md section 8)
REFERENCE_ITERATIONS = {3: 7, 4: 7, 5: 8, 6: 9, 7: 9, 8: 10, 9: 9, 10: 10}
REFERENCE_STATES = {3: "14/55/15", 4: "26/89/29", 6: "51/182/79"}


def mpiexec(n, *args):
    return ["mpiexec", "--oversubscribe", "-n", str(n)] + list(args)


class Failure(Exception):
    pass


def run(cmd, expect_rc=0, timeout=600):
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=timeout)
    if expect_rc is not None and (p.returncode != 0) != (expect_rc != 0):
        raise Failure("exit status %d from %s\n%s" % (p.returncode, " ".join(cmd), p.stdout[-3000:]))
    return p.stdout


def expect(cond, message, output=""):
    if not cond:
        raise Failure(message + ("\n" + output[-3000:] if output else ""))


SUMMARY = re.compile(r"^\s*(-?\d+)\s+(\d+)\s+(\d+)\s+[\d.]+\s+[\d.]+\s+(\d+)\s+[\d.]+\s+(\d+)\s+([\d/]+)\s+([\d/]+)\s+(\S+)", re.M)


def prism(level, ranks=1, extra=(), h5=None):
    """Runs examples/prism and returns (output, summary fields)."""
    cmd = mpiexec(ranks, PRISM, "-level", str(level), "-snes_monitor", "-snes_converged_reason") + list(extra)
    if h5:
        cmd += ["-o", os.path.join(OUT, h5)]
    out = run(cmd)
    m = SUMMARY.search(out)
    expect(m is not None, "no summary row", out)
    return out, {"level": int(m.group(1)), "ranks": int(m.group(2)), "nodes": int(m.group(3)), "contact": int(m.group(4)),
                 "iters": int(m.group(5)), "states": m.group(6), "sep_sl_st": m.group(7), "reason": m.group(8)}


def last_znorm(out):
    norms = re.findall(r"SNES Function norm ([0-9.eE+-]+)", out)
    expect(norms, "no -snes_monitor output", out)
    return float(norms[-1])


TESTS = []


def test(requirement):
    def register(fn):
        TESTS.append((fn.__name__, requirement, fn))
        return fn
    return register


@test("per-node kernels (approximation step, Table 1 classification, G/H and S/T blocks) give hand-computed values for L, M1, M2, M3+, M3-, M4 and phi = 0")
def kernels():
    run([os.path.join(ROOT, "tests", "test_kernels")])


@test("one 3p Newton step of SNESSolve equals the 6p step D [du; eta] = [z; z] on random states, to 1e-10 relative")
def newton_3p_equals_6p():
    run([os.path.join(ROOT, "tests", "test_newton")])


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


def prism_level(level):
    out, s = prism(level)
    expect(s["reason"] == "CONVERGED_FNORM_RELATIVE", "level %d: %s" % (level, s["reason"]), out)
    expect(last_znorm(out) <= 1e-12, "level %d: final |z| %g > 1e-12" % (level, last_znorm(out)), out)
    ref = REFERENCE_ITERATIONS[level]
    expect(abs(s["iters"] - ref) <= 1, "level %d: %d iterations, reference %d" % (level, s["iters"], ref), out)
    expect(s["contact"] == 4 * level * (2 * level + 1), "level %d: %d contact nodes" % (level, s["contact"]), out)
    expect(s["nodes"] == (4 * level + 1) * (2 * level + 1) ** 2, "level %d: %d nodes" % (level, s["nodes"]), out)
    if level in REFERENCE_STATES:
        expect(s["sep_sl_st"] == REFERENCE_STATES[level], "level %d: states %s, reference %s" % (level, s["sep_sl_st"], REFERENCE_STATES[level]), out)


for _L in sorted(REFERENCE_ITERATIONS):
    test("prism level %d converges from u = 0 (relative rule, rtol 1e-10) to |z| <= 1e-12 in %d +- 1 iterations, with the reference node counts%s"
         % (_L, REFERENCE_ITERATIONS[_L], " and states " + REFERENCE_STATES[_L] if _L in REFERENCE_STATES else ""))(
        (lambda L: (lambda: prism_level(L)))(_L))
    TESTS[-1] = ("prism_level_%d" % _L,) + TESTS[-1][1:]


@test("the prism solution (level 4) satisfies the Coulomb law at every contact node to 1e-8 relative, checked from the HDF5 file; the XDMF file matches it; plot_contact.py draws it")
def prism_coulomb_law():
    prism(4, h5="coulomb_L4.h5")
    out = run(CHECK + ["coulomb", os.path.join(OUT, "coulomb_L4.h5"), "--phi", "0.3", "--tol", "1e-8"])
    expect("VIOLATED" not in out, "law violated", out)
    png = os.path.join(OUT, "coulomb_L4.png")
    if os.path.exists(png):
        os.remove(png)
    run([PYTHON, os.path.join(ROOT, "examples", "plot_contact.py"), os.path.join(OUT, "coulomb_L4.h5")])
    expect(os.path.getsize(png) > 10000, "examples/plot_contact.py wrote no picture")


@test("a non-default friction (-friction 0.5) reaches the solver and the law holds with it")
def prism_friction_option():
    prism(3, extra=["-friction", "0.5"], h5="friction05_L3.h5")
    run(CHECK + ["coulomb", os.path.join(OUT, "friction05_L3.h5"), "--phi", "0.5"])


@test("1 rank and 2 ranks give the same iterates (|z| to 1e-8 relative while above 1e-10) and the same solution (level 5, contact face and whole mesh) to 1e-10 relative")
def prism_ranks_agree():
    out1, s1 = prism(5, 1, h5="ranks1_L5.h5")
    out2, s2 = prism(5, 2, h5="ranks2_L5.h5")
    z1 = [float(z) for z in re.findall(r"SNES Function norm ([0-9.eE+-]+)", out1)]
    z2 = [float(z) for z in re.findall(r"SNES Function norm ([0-9.eE+-]+)", out2)]
    expect(len(z1) == len(z2), "%d iterations on 1 rank, %d on 2" % (len(z1) - 1, len(z2) - 1), out1 + out2)
    for k, (a, b) in enumerate(zip(z1, z2)):
        expect(a < 1e-10 or abs(a - b) <= 1e-8 * a, "iterate %d: |z| %.12e on 1 rank, %.12e on 2" % (k, a, b), out1 + out2)
    run(CHECK + ["compare", os.path.join(OUT, "ranks1_L5.h5"), os.path.join(OUT, "ranks2_L5.h5"), "--tol", "1e-10"])


@test("the two Schur paths (MUMPS's own, MatSchurComplement explicit) give the same solution, on the contact face and on the whole mesh (recovery), to 1e-10, on 1 and 2 ranks")
def prism_schur_paths_agree():
    prism(4, 1, h5="mumps_L4.h5")
    prism(4, 1, extra=["-reduction", "explicit"], h5="explicit_L4.h5")
    prism(4, 2, extra=["-reduction", "explicit"], h5="explicit2_L4.h5")
    run(CHECK + ["compare", os.path.join(OUT, "mumps_L4.h5"), os.path.join(OUT, "explicit_L4.h5"), "--tol", "1e-10"])
    run(CHECK + ["compare", os.path.join(OUT, "mumps_L4.h5"), os.path.join(OUT, "explicit2_L4.h5"), "--tol", "1e-10"])


@test("-snes_view prints the ssstar settings and -log_view shows the assembly, Schur, AS and NS events")
def prism_view_and_log():
    out, _ = prism(3, extra=["-snes_view", "-log_view", "-snes_ssstar_monitor_states"])
    for pattern in [r"type: ssstar", r"friction coefficient phi = 0.3", r"stopping rule \|\|z\|\| <= max\(atol, rtol max\(\|\|u\|\|, \|\|gamma f\|\|\)\), atol = 1e-50, rtol = 1e-10",
                    r"SSStarAssembly", r"SSStarSchur", r"SSStarAS", r"SSStarNS", r"SSStar states L 14 M1 55 M2 0 M3\+ 15 M3- 0 M4 0"]:
        expect(re.search(pattern, out) is not None, "missing in output: " + pattern, out)


@test("meshes/prism.geo gives the node counts of Table 2 for L = 3..16 and 4L(2L+1) contact nodes")
def mesh_node_counts():
    table2 = [637, 1377, 2541, 4225, 6525, 9537, 13357, 18081, 23805, 30625, 38637, 47937, 58621, 70785]
    for level, nodes in zip(range(3, 17), table2):
        msh = os.path.join(OUT, "count_L%d.msh" % level)
        run(["gmsh", "-3", "-setnumber", "L", str(level), "-format", "msh22", os.path.join(ROOT, "meshes", "prism.geo"), "-o", msh])
        with open(msh) as f:
            lines = f.read().split("\n")
        got = int(lines[lines.index("$Nodes") + 1])
        expect(got == nodes, "level %d: %d nodes, Table 2 has %d" % (level, got, nodes))
        os.remove(msh)


@test("-mesh runs a gmsh file given by the user (here msh 4.1 written by the gmsh command) and finds the same solution as -level")
def prism_user_mesh():
    msh = os.path.join(OUT, "user_L3.msh")
    run(["gmsh", "-3", "-setnumber", "L", "3", "-format", "msh41", os.path.join(ROOT, "meshes", "prism.geo"), "-o", msh])
    out = run(mpiexec(2, PRISM, "-mesh", msh, "-snes_converged_reason"))
    m = SUMMARY.search(out)
    expect(m is not None and m.group(7) == REFERENCE_STATES[3] and m.group(8) == "CONVERGED_FNORM_RELATIVE", "different result from -mesh", out)


@test("bad input is refused with an error naming it: a missing mesh file, a mesh without a physical group, a negative friction, an output file that cannot be written")
def errors_name_the_problem():
    out = run([PRISM, "-mesh", "no/such.msh"], expect_rc=1)
    expect("no/such.msh" in out, "the missing file is not named", out)
    geo = os.path.join(OUT, "no_right.geo")
    with open(os.path.join(ROOT, "meshes", "prism.geo")) as f:
        text = f.read().replace('Physical Surface("right") = {4};', "")
    with open(geo, "w") as f:
        f.write(text)
    out = run([PRISM, "-geo", geo, "-level", "2"], expect_rc=1)
    expect('no physical group named "right"' in out, "the missing group is not named", out)
    out = run([PRISM, "-level", "2", "-snes_ssstar_friction", "-1"], expect_rc=1)
    expect("-snes_ssstar_friction -1" in out, "the bad option is not named", out)
    out = run([PRISM, "-level", "2", "-o", "no/such/folder/x.h5"], expect_rc=1)
    expect("Cannot write no/such/folder/x.h5" in out, "the output file is not named", out)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("-k", default="", help="run only tests whose name contains this")
    parser.add_argument("-v", action="store_true", help="print each requirement")
    args = parser.parse_args()
    os.makedirs(OUT, exist_ok=True)
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    passed = failed = 0
    for name, requirement, fn in TESTS:
        if args.k not in name:
            continue
        t0 = time.time()
        try:
            fn()
            passed += 1
            print("ok   %-28s %6.1fs" % (name, time.time() - t0), flush=True)
        except (Failure, subprocess.TimeoutExpired) as e:
            failed += 1
            print("FAIL %-28s %6.1fs\n  requirement: %s\n  %s" % (name, time.time() - t0, requirement, str(e).replace("\n", "\n  ")), flush=True)
        if args.v:
            print("     " + requirement)
    print("%d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
