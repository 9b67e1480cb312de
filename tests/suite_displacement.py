"""Prescribed displacements, reaction forces, stresses and strains (docs/guide/displacements-and-stresses.md,
docs/derivation.md section 15): a block compressed on a frictionless plane by its lid moved down with x, y free (the
reaction E A delta/h and the stress exact at every step), a clamped lid on a frictional base (the reaction balances
the contact force), a plane of symmetry through contact nodes (the half model is the mirrored full model's half), the
bad input refused by name, Hertz's subsurface stress, a cantilever against beam theory, the Python module."""
import json
import os
import re

import h5py
import numpy as np

from harness import *  # noqa: F401,F403 (run, expect, mpiexec, test, paths)

CONTACT = os.path.join(ROOT, "examples", "contact")
BLOCK = ["-geo", os.path.join(ROOT, "meshes", "block.geo"), "-level", "1", "-E", "1000", "-nu", "0.3"]
E, NU, AREA, HEIGHT = 1000.0, 0.3, 1.0, 0.5
STUCK = 24.6  # -reaction z of the clamped lid on a base with phi = 100 (every node sticks): 24.56 at level 1
PATHS = [(red, ranks) for red in ("direct", "none") for ranks in (1, 2)]


def contact(args, h5, ranks=1, expect_rc=0):
    out = run(mpiexec(ranks, CONTACT, *args, "-o", os.path.join(OUT, h5)), expect_rc=expect_rc)
    return out, h5py.File(os.path.join(OUT, h5), "r")


def law(h5):
    out = run(CHECK + ["law", os.path.join(OUT, h5), "--steps"])
    expect("VIOLATED" not in out and "WRONG" not in out, "check_solution.py law %s" % h5, out)


def states(f):
    """The top level and every step of a file: (prefix, time) pairs"""
    steps = sorted((k for k in f.get("steps", {}) if k.isdigit()), key=int)
    return [("steps/%s/" % k, f["steps/time"][int(k)]) for k in steps] if steps else [("", 0.0)]


@test("a block 1 x 1 x 0.5 (E = 1000, nu = 0.3) on a frictionless plane, its lid moved down by delta = 0, 0.005, 0.01 with x and y free (-displacement_top \"0:free,free,0;...\"), the rigid motions in the plane left to the kernel: at every step the lid's reaction /steps/groups/top/reaction is (0, 0, -E A delta/h) and the contact force its opposite to 1e-8, every cell's stress (0, 0, -E delta/h, 0, 0, 0), strain (nu, nu, -1, 0, 0, 0) delta/h and von Mises stress E delta/h to 1e-8 (also the nodal recovery), the displacement u_z = -delta z/h exact; the step line prints the reaction; the law holds at every step (check_solution.py law --steps); direct and none, 1 and 2 ranks")
def displacement_compression():
    for red, ranks in PATHS:
        h5 = "displacement_compression_%s_%d.h5" % (red, ranks)
        out, f = contact(BLOCK + ["-contact", "bottom", "-friction_law_bottom", "none", "-displacement_top", "0:free,free,0;1:free,free,-0.005;2:free,free,-0.01", "-snes_ssstar_reduction", red], h5, ranks)
        what = "%s %d ranks" % (red, ranks)
        expect(re.search(r"^step 3/3 t 2\.?: .* reaction of top \(0, 0, -20\)$", out, re.M) is not None, what + ": the step line does not print the lid's reaction", out)
        st = f["steps"]
        expect(len(st["time"]) == 3 and st["groups/top/reaction"].shape == (3, 3), what + ": no /steps/groups/top/reaction")
        for k, (prefix, t) in enumerate(states(f)):
            delta = 0.005 * t
            scale = E * delta / HEIGHT if delta else 1.0
            reaction = st["groups/top/reaction"][k]
            force = f[prefix + "contact/reaction"][:].sum(0)
            expect(np.abs(reaction - [0, 0, -E * AREA * delta / HEIGHT]).max() <= 1e-8 * scale, "%s t %g: the lid's reaction %s, not (0, 0, %g)" % (what, t, reaction, -E * AREA * delta / HEIGHT))
            expect(np.abs(reaction + force + st["load"][k]).max() <= 1e-8 * scale, "%s t %g: reaction %s + contact force %s + load do not balance" % (what, t, reaction, force))
            stress, strain, vm = f[prefix + "fields/stress"][:], f[prefix + "fields/strain"][:], f[prefix + "fields/von_mises"][:]
            exact = np.array([0, 0, -E * delta / HEIGHT, 0, 0, 0])
            expect(np.abs(stress - exact).max() <= 1e-8 * scale and np.abs(f[prefix + "fields/stress_nodal"][:] - exact).max() <= 1e-8 * scale, "%s t %g: stress off by %g" % (what, t, np.abs(stress - exact).max()))
            expect(np.abs(strain - np.array([NU, NU, -1, 0, 0, 0]) * delta / HEIGHT).max() <= 1e-8 * scale / E, "%s t %g: strain off by %g" % (what, t, np.abs(strain - np.array([NU, NU, -1, 0, 0, 0]) * delta / HEIGHT).max()))
            expect(np.abs(vm - E * delta / HEIGHT).max() <= 1e-8 * scale, "%s t %g: von Mises off" % (what, t))
            x, u = f["geometry/vertices"][:], f[prefix + "fields/displacement"][:]
            expect(np.abs(u[:, 2] + delta * x[:, 2] / HEIGHT).max() <= 1e-8 * max(delta, 1e-300), "%s t %g: u_z is not -delta z/h" % (what, t))
        law(h5)


@test("a lid clamped (-displacement_top 0,0,-0.01, every component) on a block on a frictional base (phi = 0.3): the lid's reaction /groups/top/reaction and the contact force balance (their sum zero to 1e-8 of the reaction), the reaction's z is between the frictionless E A delta/h = 20 and the fully stuck base's (24.56 at phi = 100); the lid's nodes are no contact nodes; direct and none, 1 and 2 ranks agree to 2e-6 (harness.AGREE); the law holds")
def displacement_clamped_balance():
    first = None
    for red, ranks in PATHS:
        h5 = "displacement_clamped_%s_%d.h5" % (red, ranks)
        out, f = contact(BLOCK + ["-contact", "bottom", "-friction_bottom", "0.3", "-displacement_top", "0,0,-0.01", "-snes_ssstar_reduction", red], h5, ranks)
        what = "%s %d ranks" % (red, ranks)
        reaction, force = f["groups/top/reaction"][:], f["contact/reaction"][:].sum(0)
        expect(np.abs(reaction + force).max() <= 1e-8 * np.abs(reaction).max(), "%s: the lid's reaction %s and the contact force %s do not balance" % (what, reaction, force), out)
        expect(0.01 * E * AREA / HEIGHT * 1.01 < -reaction[2] < STUCK, "%s: the reaction %s is not between the frictionless block's and the stuck one's" % (what, reaction))
        law(h5)
        if first is None:
            first = h5
        else:
            run(CHECK + ["compare", os.path.join(OUT, first), os.path.join(OUT, h5), "--tol", str(AGREE)])
