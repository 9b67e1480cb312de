#!/usr/bin/env python3
"""What the ssstar test suites share: running programs, expectations, the test registry."""
import os
import re
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# tests/run.py runs every test in a process of its own with SSSTAR_TEST_OUT = tests/output/<test>: tests that run at
# the same time never share a file
OUT = os.environ.get("SSSTAR_TEST_OUT", os.path.join(ROOT, "tests", "output"))
LIB = os.path.join(ROOT, "lib", "libssstar.so")
PYTHON = "/usr/bin/python3"  # Debian's, with h5py
PRISM = os.path.join(ROOT, "examples", "prism")
CHECK = [PYTHON, os.path.join(ROOT, "tests", "check_solution.py")]
# iterations from u = 0 and separated/sliding/sticking counts of an independent implementation (docs/derivation.md section 8)
REFERENCE_ITERATIONS = {3: 7, 4: 7, 5: 8, 6: 9, 7: 9, 8: 10, 9: 9, 10: 10}
REFERENCE_STATES = {3: "14/55/15", 4: "26/89/29", 6: "51/182/79"}


def mesh_of(geo, level, cache=None):
    """The mesh file the programs make of geo (a path relative to the source tree, or absolute) at level: in the mesh
    cache, out of the source tree (SSStarMeshCacheFile(): <cache>/<folder of geo>-<djb2 hash of its real path>/
    <name>_L<level>.msh; cache -mesh_cache, else $XDG_CACHE_HOME/ssstar, else ~/.cache/ssstar)"""
    xdg = os.environ.get("XDG_CACHE_HOME", "")
    cache = cache or (os.path.join(xdg, "ssstar") if xdg.startswith("/") else os.path.expanduser("~/.cache/ssstar"))
    path = os.path.realpath(os.path.join(ROOT, geo))
    h = 5381
    for c in path.encode():
        h = (33 * h + c) & 0xFFFFFFFF
    return os.path.join(cache, "%s-%08x" % (os.path.basename(os.path.dirname(path)), h), os.path.basename(path)[:-4] + "_L%d.msh" % level)


def mpiexec(n, *args):
    return ["mpiexec", "--oversubscribe", "-n", str(n)] + list(args)


class Failure(Exception):
    pass


# Every PETSc program of ours runs with PETSc's leak check: -malloc_dump lists the blocks still allocated at
# PetscFinalize() ("[ 0] 32 bytes VecCreate() at ..."), and the test fails. One-process runs also get -malloc_debug,
# which checks the whole heap at every allocation: under mpiexec -n 2 it makes a level-3 solve 30 times slower
# (the MATSCALAPACK conversion of the Newton matrix allocates per entry).
LEAK = re.compile(r"^\s*\[\s*\d+\]\s*\d+ bytes \S+\(\) at \S+", re.M)


def petsc_program(arg):
    return arg == PRISM or arg.startswith(os.path.join(ROOT, "tests", "test_"))


def malloc_check(cmd):
    parallel = cmd[0] == "mpiexec" and cmd[cmd.index("-n") + 1] != "1"
    return ["-malloc_dump"] if parallel else ["-malloc_debug", "-malloc_dump"]


# docs/guide/converged.md: a solve at the default settings ends within 1e-6 of the exact discrete solution
# (displacements relative to the largest, forces to the largest; a load path's steps each to their own scale), so two
# such runs (other ranks, the other path, another reduction, the scene turned) agree to twice that: the bound of every
# comparison of runs that are not the same computation (issue 23: a bound at round-off fails on another machine's BLAS)
AGREE = 2e-6

# The exit status of our programs when the solve did not converge (SSSTAR_EXIT_NOT_CONVERGED); bad input exits with
# PETSc's error code (55..100), never with this one
NOT_CONVERGED = 2


def rc_matches(rc, expect_rc):
    """expect_rc 0: success; NOT_CONVERGED: exactly that; any other: an error, i.e. neither 0 nor NOT_CONVERGED"""
    if expect_rc == 0 or expect_rc == NOT_CONVERGED:
        return rc == expect_rc
    return rc not in (0, NOT_CONVERGED)


def run(cmd, expect_rc=0, timeout=600, check_memory=True):
    """Runs cmd in the source tree; a PETSc program of ours gets the leak check and fails the test if a run that
    ends normally (converged or not) leaks."""
    cmd = list(cmd)
    if check_memory and any(petsc_program(a) for a in cmd):
        cmd += malloc_check(cmd)
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=timeout)
    if expect_rc is not None and not rc_matches(p.returncode, expect_rc):
        raise Failure("exit status %d (expected %s) from %s\n%s" % (p.returncode, {0: "0", NOT_CONVERGED: "%d" % NOT_CONVERGED}.get(expect_rc, "an error"), " ".join(cmd), p.stdout[-3000:]))
    leaks = LEAK.findall(p.stdout) if p.returncode in (0, NOT_CONVERGED) else []  # a run stopped by an error leaves its objects
    if leaks:
        raise Failure("memory leaked (-malloc_dump) by %s:\n%s" % (" ".join(cmd), "\n".join(leaks[:20])))
    return p.stdout


def expect(cond, message, output=""):
    if not cond:
        raise Failure(message + ("\n" + output[-3000:] if output else ""))


SUMMARY = re.compile(r"^\s*(-?\d+)(?:r(\d+))?\s+(\d+)\s+(\d+)\s+[\d.]+\s+[\d.]+\s+(\d+)\s+[\d.]+\s+(\d+)\s+([\d/]+)\s+([\d/]+)\s+(\S+)\s+([\d.]+)$", re.M)


def prism(level, ranks=1, extra=(), h5=None, expect_rc=0):
    """Runs examples/prism and returns (output, summary fields); expect_rc=NOT_CONVERGED for a solve that must not
    converge."""
    cmd = mpiexec(ranks, PRISM, "-level", str(level), "-snes_monitor", "-snes_converged_reason") + list(extra)
    if h5:
        cmd += ["-o", os.path.join(OUT, h5)]
    out = run(cmd, expect_rc=expect_rc)
    m = SUMMARY.search(out)
    expect(m is not None, "no summary row", out)
    return out, {"level": int(m.group(1)), "refined": int(m.group(2) or 0), "ranks": int(m.group(3)), "nodes": int(m.group(4)), "contact": int(m.group(5)),
                 "iters": int(m.group(6)), "states": m.group(7), "sep_sl_st": m.group(8), "reason": m.group(9),
                 "peak_gb": float(m.group(10))}


def last_znorm(out):
    norms = re.findall(r"SNES Function norm ([0-9.eE+-]+)", out)
    expect(norms, "no -snes_monitor output", out)
    return float(norms[-1])


# (name, requirement, function, full): full tests run only in make test-full (tests/run.py --full)
TESTS = []


def test(requirement, full=False):
    """Registers a test. full=True: a slow test whose capability has a quicker test in the default run; it runs in
    make test-full only."""
    def register(fn):
        TESTS.append((fn.__name__, requirement, fn, full))
        return fn
    return register
