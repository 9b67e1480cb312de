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
    out = run(CHECK + ["compare", a, b, "--tol", str(AGREE)])
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


def resultant(h5):
    """The total contact force on the bottom: its normal part F_n, its tangential vector F_t (global axes), and the
    tangential displacement of every node"""
    c = h5py.File(os.path.join(OUT, h5), "r")["contact"]
    r, n, u = (c[name][:].reshape(-1, 3) for name in ("reaction", "normal", "displacement"))
    fn = (r * n).sum()
    return fn, r.sum(axis=0) - fn * n[0], u - (u * n).sum(axis=1)[:, None] * n


ORTHOTROPIC = ["-snes_type", "ssstar", "-nu", "0", "-snes_ssstar_friction_law", "orthotropic", "-snes_ssstar_friction_1", "0.3", "-snes_ssstar_friction_2", "0.6"]


@test("the orthotropic law's known answer (phi_1 = 0.3 along the friction direction, phi_2 = 0.6 across, nu = 0 so that nothing moves across the push): a block pressed onto the plane and pushed along the direction by 0.008 slides, every node along the push, with a tangential force of phi_1 times the normal force (to 1e-8); pushed across by as much it holds (phi_1 F_n < F_t < phi_2 F_n, some nodes stuck); pushed across by 0.02 it slides with phi_2; pushed along by 0.004 (F_t = 0.206 F_n) no node moves tangentially; the direction turned to y swaps the axes, and a direction with a normal part is projected onto the plane; direct and none, 1 and 2 ranks", full=True)
def generic_orthotropic_known_answer():
    cases = [("0.008,0,-0.01", "1,0,0", 0, "slides", 0.3), ("0,0.008,-0.01", "1,0,0", 1, "holds", None), ("0,0.02,-0.01", "1,0,0", 1, "slides", 0.6),
             ("0.004,0,-0.01", "1,0,0", 0, "sticks", None), ("0.008,0,-0.01", "0,1,0", 0, "holds", None), ("0.008,0,-0.01", "1,0,0.7", 0, "slides", 0.3)]
    for k, (push, direction, axis, kind, phi) in enumerate(cases):
        for red in ("direct", "none"):
            for ranks in ((1, 2) if k < 3 else (1,)):
                name = "ortho_%d_%s_%d.h5" % (k, red, ranks)
                out, distance, _ = generic(ranks, *ORTHOTROPIC, "-snes_ssstar_friction_direction", direction, "-push", push, "-snes_ssstar_reduction", red, "-snes_converged_reason", h5=name)
                fn, ft, slip = resultant(name)
                ratio, moved = -ft[axis] / fn, np.linalg.norm(slip, axis=1)
                what = "push %s, direction %s, %s, %d ranks: F_t/F_n = %.10f, slip %.2g..%.2g" % (push, direction, red, ranks, ratio, moved.min(), moved.max())
                expect("CONVERGED_FNORM" in out and distance >= -1e-11 and fn > 1e3, what + ": not converged or no contact", out)
                delta = max(abs(float(x)) for x in push.split(",")[:2])
                expect(abs(ft[1 - axis]) <= 1e-8 * fn and np.abs(slip[:, 1 - axis]).max() <= 1e-8 * delta, what + ": a force or a slip across the push", out)
                if kind == "slides":  # every node along the push, F_t = phi F_n against it
                    expect(abs(ratio - phi) <= 1e-8 * phi and (slip[:, axis] > 1e-6).all(), what + ": not sliding with phi = %g" % phi, out)
                elif kind == "holds":  # more than phi_1 could hold, less than phi_2, not sliding as a whole
                    expect(0.3 * 1.01 < ratio < 0.6 and moved.min() <= 1e-8 * delta, what + ": does not hold between phi_1 and phi_2", out)
                else:  # no node moves: the force of the bonded block, below phi_1
                    expect(moved.max() <= 1e-8 * delta and abs(ratio - 0.2055608871) <= 1e-8, what + ": not stuck", out)


@test("the orthotropic law with phi_1 = phi_2 = 0.3 (any direction) is the Coulomb law: on the tilted plane with gaps its solution equals coulomb's (phi = 0.3) to 1e-12 on both paths, with the same iterations")
def generic_orthotropic_is_coulomb():
    for red in ("direct", "none"):
        iso = ["-snes_ssstar_friction_law", "orthotropic", "-snes_ssstar_friction_1", "0.3", "-snes_ssstar_friction_2", "0.3", "-snes_ssstar_friction_direction", "1,2,0"]
        out_o, _, _ = generic(1, "-snes_type", "ssstar", *TILTED, "-snes_ssstar_reduction", red, *iso, h5="ortho_iso_%s.h5" % red)
        out_c, _, _ = generic(1, "-snes_type", "ssstar", *TILTED, "-snes_ssstar_reduction", red, "-snes_ssstar_friction", "0.3", h5="coulomb_iso_%s.h5" % red)
        a, b = by_coordinates("ortho_iso_%s.h5" % red), by_coordinates("coulomb_iso_%s.h5" % red)
        its = [re.search(r"after (\d+) iterations", out).group(1) for out in (out_o, out_c)]
        expect(its[0] == its[1], "%s: %s iterations, coulomb %s" % (red, its[0], its[1]), out_o)
        for name in ("displacement", "reaction"):
            d = np.abs(a[name] - b[name]).max() / np.abs(b[name]).max()
            expect(d <= 1e-12, "%s: %s differs from coulomb's by %.1e relative" % (red, name, d))
