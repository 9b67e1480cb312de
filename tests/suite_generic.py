"""ssstar in any PETSc program: examples/generic, a plain elasticity program (DMDA, its own K and b) that only declares
its contact nodes; the whole-body path (reduction, frames, gaps, recovery) on 1, 2 and 3 ranks."""
import os
import re

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

GENERIC = os.path.join(ROOT, "examples", "generic")
TILTED = ["-obstacle_normal", "0.01,0.005,1", "-obstacle_point", "0,0,-0.001"]
DISTANCE = re.compile(r"smallest distance to the plane (\S+) .* along n (\S+)")


def generic(ranks, *args, h5=None):
    cmd = mpiexec(ranks, GENERIC, *args)
    if h5:
        cmd += ["-o", os.path.join(OUT, h5)]
    out = run(cmd)
    m = DISTANCE.search(out)
    expect(m is not None, "no report line", out)
    return out, float(m.group(1)), float(m.group(2))


def by_coordinates(h5):
    """The contact nodes' data ordered by their coordinates (the file order depends on the partition)."""
    f = h5py.File(os.path.join(OUT, h5), "r")["contact"]
    order = np.lexsort(f["coordinates"][:].T[::-1])
    return {name: f[name][:][order] for name in ("displacement", "reaction", "gap")}


@test("examples/generic with -snes_type ksponly (one linear solve, contact declared but ignored) pushes the block 8e-3 through the plane")
def generic_ksponly_penetrates():
    out, distance, _ = generic(1, "-snes_type", "ksponly", "-ksp_type", "preonly", "-pc_type", "lu")
    expect(abs(distance - (-8e-3)) < 1e-9, "the linear solve should penetrate by push - gap = 8e-3, got %g" % distance, out)


@test("examples/generic with -snes_type ssstar does not penetrate (distance >= -1e-12), carries a normal force, and its contact nodes satisfy the Coulomb law to 1e-8 (checked from the HDF5 file)")
def generic_ssstar_contact():
    out, distance, force = generic(1, "-snes_type", "ssstar", "-snes_converged_reason", h5="generic_flat.h5")
    expect("CONVERGED_FNORM_RELATIVE" in out, "not converged", out)
    expect(distance >= -1e-12 and force > 1e3, "penetration %g or no contact force %g" % (distance, force), out)
    law = run(CHECK + ["coulomb", os.path.join(OUT, "generic_flat.h5")])
    expect("VIOLATED" not in law, "law violated", law)


@test("a tilted obstacle (normal (0.01, 0.005, 1)) with non-zero, varying gaps: separated, sliding and sticking nodes, the Coulomb law in the nodes' frames to 1e-8, and the same solution on 1, 2 and 3 ranks to 1e-9")
def generic_tilted_gaps_ranks():
    sols = []
    for ranks in (1, 2, 3):
        out, distance, force = generic(ranks, "-snes_type", "ssstar", "-snes_converged_reason", *TILTED, h5="generic_tilted%d.h5" % ranks)
        expect("CONVERGED_FNORM_RELATIVE" in out and distance >= -1e-11, "%d ranks: %s, distance %g" % (ranks, "not converged" if "CONVERGED" not in out else "converged", distance), out)
        law = run(CHECK + ["coulomb", os.path.join(OUT, "generic_tilted%d.h5" % ranks)])
        expect("VIOLATED" not in law, "%d ranks: law violated" % ranks, law)
        counts = re.search(r"separated (\d+), sliding (\d+), sticking (\d+)", law)
        expect(counts is not None and all(int(c) > 0 for c in counts.groups()), "%d ranks: not every kind of node: %s" % (ranks, law), law)
        sols.append(by_coordinates("generic_tilted%d.h5" % ranks))
    expect(np.ptp(sols[0]["gap"]) > 1e-3, "the gaps do not vary")
    for ranks, s in zip((2, 3), sols[1:]):
        for name in ("displacement", "reaction"):
            d = np.abs(s[name] - sols[0][name]).max() / np.abs(sols[0][name]).max()
            expect(d <= 1e-9, "%s on %d ranks differs from 1 rank by %.1e relative" % (name, ranks, d))


@test("the explicit Schur path (-snes_ssstar_reduction explicit) gives the whole-body solution of the default path on a tilted plane with gaps, to 1e-9")
def generic_reductions_agree():
    generic(2, "-snes_type", "ssstar", *TILTED, h5="generic_default.h5")
    generic(2, "-snes_type", "ssstar", "-snes_ssstar_reduction", "explicit", *TILTED, h5="generic_explicit.h5")
    a, b = by_coordinates("generic_default.h5"), by_coordinates("generic_explicit.h5")
    for name in ("displacement", "reaction"):
        d = np.abs(a[name] - b[name]).max() / np.abs(a[name]).max()
        expect(d <= 1e-9, "%s differs by %.1e relative" % (name, d))


@test("tests/check_solution.py compares files without a mesh (/contact alone, as examples/generic writes them): the "
      "dense route against the whole body agree to 1e-8; a copy with one reaction changed by 1 % differs")
def generic_compare_without_mesh():
    import shutil
    names = {"direct": "generic_cmp_direct.h5", "none": "generic_cmp_none.h5"}
    for path, h5 in names.items():
        generic(1, "-snes_type", "ssstar", "-snes_ssstar_reduction", path, *TILTED, h5=h5)
    a, b = os.path.join(OUT, names["direct"]), os.path.join(OUT, names["none"])
    with h5py.File(a, "r") as f:
        expect("geometry" not in f and "contact" in f, "examples/generic wrote a mesh")
    out = run(CHECK + ["compare", a, b, "--tol", "1e-8"])
    expect("reaction" in out and "DIFFERENT" not in out, "the two routes differ", out)
    bad = os.path.join(OUT, "generic_cmp_changed.h5")
    shutil.copy(b, bad)
    with h5py.File(bad, "r+") as f:
        r = f["contact/reaction"][:]
        k = np.argmax(np.abs(r).max(axis=1))
        r[k] *= 1.01
        f["contact/reaction"][...] = r
    out = run(CHECK + ["compare", a, bad, "--tol", "1e-8"], expect_rc=1)
    expect(re.search(r"reaction\s+max difference\s+\S+ relative DIFFERENT", out) is not None, "a changed reaction passes", out)
