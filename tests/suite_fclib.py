"""FCLib problems through examples/fclib: the FEM files solve (checked again in Python from the -o file), the
rigid-body files and files that are no FCLib problem are refused with a clear message."""
import os
import re
import shutil

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)
from check_solution import fclib_error, fclib_problem

FCLIB = os.path.join(ROOT, "examples", "fclib")
DATA = os.path.join(ROOT, "tests", "data", "fclib")
FEM_FILES = ["LMGC_GFC3D_CubeH8.hdf5", "LMGC_GFC3D-i00001-1-00000.hdf5", "LMGC_GFC3D-i00501-4-00000.hdf5",
             "LMGC_GlobalFrictionContactProblem00046.hdf5"]
# numerical rank of W (numpy's rule, sigma > N eps sigma_max) of the rigid-body files, and its size
RIGID_FILES = {"LMGC_100_PR_PerioBox-i00361-60-03000.hdf5": (72, 180), "Capsules-i125-1213.hdf5": (570, 858),
               "BoxesStack_fclib_local_problem_test.hdf5": (72, 144)}
TOL = 1e-8
ROW = re.compile(r"^(\S+)\s+(local|global)\s+(\d+)\s+\S+\s+\S+\s+(\d+)\s+\S+\s+\S+\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)$", re.M)


def fclib(path, *extra, ranks=1, expect_rc=0):
    """Runs examples/fclib; returns (output, summary fields) when it ran through."""
    out = run(mpiexec(ranks, FCLIB, path, *extra), expect_rc=expect_rc)
    m = ROW.search(out)
    if expect_rc != 0:
        return out, None
    expect(m is not None, "no summary row", out)
    return out, {"contacts": int(m.group(3)), "iters": int(m.group(4)), "fclib": float(m.group(5)),
                 "z": float(m.group(6)), "coulomb": float(m.group(7)), "reason": m.group(8)}


# --- an independent reading of FCLib files (numpy, dense): tests/check_solution.py's, which reads -o files too ---------

def problem(path):
    """(W, q, mu, global parts or None) of an FCLib file (check_solution.fclib_problem())"""
    with h5py.File(path, "r") as f:
        return fclib_problem(f)


def check_solution_file(problem_path, solution_path):
    """Recomputes, from the problem and the -o file, FCLib's error and that u = W r + q (normal first) and, for a
    global problem, M v = H r + f; returns the recomputed FCLib error."""
    W, q, mu, glob = problem(problem_path)
    s = h5py.File(solution_path, "r")
    group = "fclib_global" if glob else "fclib_local"
    expect(group in s, "%s: no copy of /%s" % (solution_path, group))
    with h5py.File(problem_path, "r") as p:
        p[group].visititems(lambda name, obj: expect(not isinstance(obj, h5py.Dataset) or np.array_equal(obj[()], s[group][name][()]),
                                                     "%s: /%s/%s differs from the problem's" % (solution_path, group, name)))
    r, u = s["solution/r"][:], s["solution/u"][:]
    expect(r.shape == q.shape and u.shape == q.shape, "%s: /solution/r, u have shapes %s, %s, not %s" % (solution_path, r.shape, u.shape, q.shape))
    error = fclib_error(W, q, mu, r)
    expect(error <= TOL, "%s: FCLib error recomputed from /solution/r is %.2e > %g" % (solution_path, error, TOL))
    mismatch = np.linalg.norm(u - (W @ r + q)) / np.linalg.norm(q)
    expect(mismatch <= TOL, "%s: /solution/u differs from W r + q by %.2e (relative to ||q||)" % (solution_path, mismatch))
    if glob:
        M, H, load, w = glob
        v = s["solution/v"][:]
        expect(v.shape == load.shape, "%s: /solution/v has shape %s, not %s" % (solution_path, v.shape, load.shape))
        residual = np.linalg.norm(M @ v - H @ r - load) / (np.linalg.norm(M @ v) + np.linalg.norm(load))
        expect(residual <= 1e-12, "%s: M v = H r + f holds only to %.2e" % (solution_path, residual))
        expect(np.linalg.norm(H.T @ v + w - u) / np.linalg.norm(q) <= TOL, "%s: u differs from H^T v + w" % solution_path)
    else:
        expect("solution/v" not in s, "%s: a local problem has no /solution/v" % solution_path)
    return error


def solve_and_check(path, name, ranks=1):
    out, row = fclib(path, "-o", os.path.join(OUT, name), ranks=ranks)
    expect(row["reason"].startswith("CONVERGED") and row["fclib"] <= TOL and row["coulomb"] <= TOL,
           "%s: printed FCLib error %.1e, Coulomb violation %.1e, %s" % (name, row["fclib"], row["coulomb"], row["reason"]), out)
    row["recomputed"] = check_solution_file(path, os.path.join(OUT, name))
    return out, row


@test("every FEM problem of the FCLib data (4 global files) solves from u = 0 to FCLib error <= 1e-8, as printed and as "
      "recomputed in Python from the -o file (r, u normal first, u = W r + q, M v = H r + f)")
def fclib_fem_problems():
    for name in FEM_FILES:
        solve_and_check(os.path.join(DATA, name), name.replace(".hdf5", "_solution.h5"))


def write_copy(src, name, **vectors):
    """A copy of an FCLib file in tests/output with some vectors replaced"""
    dst = os.path.join(OUT, name)
    shutil.copyfile(src, dst)
    with h5py.File(dst, "r+") as f:
        group = "fclib_global" if "fclib_global" in f else "fclib_local"
        for key, value in vectors.items():
            f["%s/vectors/%s" % (group, key)][:] = value
    return dst


@test("the nonsymmetric W of problem 00046 with friction 0.05 (so that contacts slide and Newton steps are taken) "
      "solves to FCLib error <= 1e-8 on 1 and 2 ranks, and both give the same solution to 2e-6 (harness.AGREE)")
def fclib_nonsymmetric_sliding():
    path = write_copy(os.path.join(DATA, "LMGC_GlobalFrictionContactProblem00046.hdf5"), "fclib_00046_mu005.hdf5", mu=0.05)
    rows = []
    for ranks in (1, 2):
        out, row = solve_and_check(path, "fclib_00046_mu005_np%d.h5" % ranks, ranks=ranks)
        expect(row["iters"] >= 2, "no Newton steps were taken (%d iterations)" % row["iters"], out)
        rows.append(row)
    a, b = (h5py.File(os.path.join(OUT, "fclib_00046_mu005_np%d.h5" % n), "r") for n in (1, 2))
    for key in ("r", "u", "v"):
        x, y = a["solution/" + key][:], b["solution/" + key][:]
        expect(np.abs(x - y).max() <= AGREE * np.abs(x).max(), "/solution/%s differs between 1 and 2 ranks" % key)
    expect(rows[0]["iters"] == rows[1]["iters"], "1 and 2 ranks took %d and %d iterations" % (rows[0]["iters"], rows[1]["iters"]))


def write_local_problem(name, W, q, mu, storage):
    """A local FCLib problem with W stored by columns (storage -1) or as triplets (storage >= 0)"""
    path = os.path.join(OUT, name)
    n = len(q)
    with h5py.File(path, "w") as f:
        g = f.create_group("fclib_local")
        g["spacedim"] = np.array([3], dtype=np.int32)
        rows, cols = np.nonzero(W)
        if storage == -1:
            order = np.lexsort((rows, cols))  # by column, then row
            rows, cols = rows[order], cols[order]
            p = np.concatenate([[0], np.cumsum(np.bincount(cols, minlength=n))])
        else:
            p = cols
        nnz = len(rows)
        for key, value in (("m", n), ("n", n), ("nz", storage if storage < 0 else nnz), ("nzmax", nnz)):
            g["W/" + key] = np.array([value], dtype=np.int32)
        g["W/p"] = p.astype(np.int32)
        g["W/i"] = rows.astype(np.int32)
        g["W/x"] = W[rows, cols]
        g["vectors/q"] = q
        g["vectors/mu"] = mu
    return path


@test("a local problem (W by columns and as triplets, nonsymmetric, one contact separating, one sliding, one sticking) "
      "solves to FCLib error <= 1e-8, recomputed in Python from the -o file")
def fclib_local_problem():
    rng = np.random.default_rng(7)
    A = rng.standard_normal((9, 9))
    W = A @ A.T / 9 + np.eye(9) + 0.2 * (A - A.T) / 9  # symmetric part SPD, W nonsymmetric
    q = np.array([0.5, 0.1, -0.2,  -1.0, 2.0, 0.5,  -1.0, 0.01, 0.0])  # normal first
    for storage, name in ((-1, "csc"), (0, "triplets")):
        path = write_local_problem("fclib_local_%s.hdf5" % name, W, q, np.array([0.3, 0.3, 0.9]), storage)
        out, row = solve_and_check(path, "fclib_local_%s_solution.h5" % name)
        expect(row["contacts"] == 3, "3 contacts expected", out)
        u = h5py.File(os.path.join(OUT, "fclib_local_%s_solution.h5" % name), "r")["solution/u"][:].reshape(-1, 3)
        small = TOL * np.abs(u).max()
        separated, slipping = u[:, 0] > small, np.hypot(u[:, 1], u[:, 2]) > small
        expect(list(separated) == [True, False, False] and list(slipping[1:]) == [True, False],
               "the contacts are not separated/sliding/sticking: u = %s" % u.tolist(), out)


@test("the three rigid-body problems (singular W) are refused with a message naming the file and the numerical rank of W, exit status != 0")
def fclib_rigid_refused():
    for name, (rank, n) in RIGID_FILES.items():
        out, _ = fclib(os.path.join(DATA, name), expect_rc=1)
        expect(re.search(r"%s: W is singular: numerical rank %d of %d" % (re.escape(name), rank, n), out) is not None,
               "%s: no message naming the singular W (rank %d of %d)" % (name, rank, n), out)


@test("a W whose symmetric part is not positive definite, a missing file, a file that is not HDF5, an HDF5 file that is "
      "not an FCLib problem (a prism -o output), no file argument and -o naming the problem file are refused clearly", full=True)
def fclib_bad_inputs():
    W = np.eye(3)
    W[1, 2], W[2, 1] = 2.0, -2.0  # nonsingular, symmetric part indefinite
    W[1, 1] = W[2, 2] = -0.5
    path = write_local_problem("fclib_indefinite.hdf5", W, np.array([-1.0, 0.0, 0.0]), np.array([0.3]), -1)
    cases = [
        ([path], "fclib_indefinite.hdf5: W is not positive definite"),
        ([os.path.join(OUT, "no_such_problem.hdf5")], "Cannot read the FCLib problem .*no_such_problem.hdf5"),
        ([os.path.join(DATA, "README.md")], "README.md is not an HDF5 file"),
        ([], "name an FCLib problem file first"),
    ]
    prism_out = os.path.join(OUT, "fclib_not_a_problem.h5")
    run(mpiexec(1, PRISM, "-level", "2", "-o", prism_out))
    cases.append(([prism_out], "fclib_not_a_problem.h5 is not an FCLib problem: it has neither /fclib_local nor /fclib_global"))
    copy = write_copy(os.path.join(DATA, "LMGC_GFC3D_CubeH8.hdf5"), "fclib_cube_copy.hdf5")
    cases.append(([copy, "-o", copy], "-o .*fclib_cube_copy.hdf5 is the problem file"))
    for args, message in cases:
        out = run(mpiexec(1, FCLIB, *args), expect_rc=1)
        expect(re.search(message, out) is not None, "no message /%s/" % message, out)
    expect(h5py.is_hdf5(copy) and "fclib_global" in h5py.File(copy, "r"), "-o naming the problem file destroyed it")
