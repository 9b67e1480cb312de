#!/usr/bin/python3
"""Independent checks of an ssstar solution file (HDF5 written by examples/prism -o).

  check_solution.py coulomb FILE.h5 [--phi PHI] [--tol 1e-8]
      the friction law of every contact node, relative to max|w| and max|r|, in the node's frame built from
      /contact/normal (default (0, 0, 1)): w_n >= 0, r_n = r.n >= 0, w_n r_n = 0, |r_t| <= bound,
      r_t = -bound w_t/|w_t| where w_t != 0, with bound = phi r_n (Coulomb), s (Tresca) or 0 (frictionless); no NaN
      or Inf. w is the node's relative displacement: the normal gap and the slip at the solution the file records
      (/contact/final_gap, /contact/slip: against the rigid obstacle, or for a contact pair the slave node against
      the master surface), else u.n + gap and u - (u.n) n from /contact/displacement and the initial gap
      /contact/gap (default 0), as examples/generic writes; on a load path (/contact/slip_increment) the tangential
      law holds for the slip increment of the last step (docs/derivation.md (10.2)). r is the force on the node (/contact/reaction: the
      pressure and traction times the node's area). The law, phi and s of each node are read from the file
      (/contact/friction_law, /contact/friction, /contact/slip_bound, written by the scenes and by
      examples/generic); --phi gives a Coulomb coefficient for every node of a file without them.
      For a file with a mesh, the XDMF file beside it names datasets of the right shapes.
  check_solution.py compare A.h5 B.h5 [--tol 1e-10]
      the contact displacement and reaction of two runs agree (relative to their max norms), and so do the
      displacement on the whole mesh and the contact states where both files have them (a file of examples/generic
      has /contact alone)
Exit status 0 when the check passes.
"""
import argparse
import os
import re
import sys

import h5py
import numpy as np


def coulomb(args):
    f = h5py.File(args.file, "r")
    c = f["contact"]
    u = c["displacement"][:]
    r = c["reaction"][:]
    p = len(u)
    normal = c["normal"][:] if "normal" in c else np.tile([0.0, 0.0, 1.0], (p, 1))
    gap = c["gap"][:] if "gap" in c else np.zeros(p)
    shapes = {"coordinates": (p, 3), "displacement": (p, 3), "reaction": (p, 3), "state": (p,), "normal": (p, 3), "gap": (p,)}
    for name, shape in shapes.items():
        if name in c and c[name].shape != shape:
            print("/contact/%s has shape %s, not %s" % (name, c[name].shape, shape))
            return False
    if "state" in c:
        state = c["state"][:]
        if state.dtype.kind != "i" or state.min() < 0 or state.max() > 6:
            print("/contact/state is not an integer state 0..6")
            return False
    if not np.isfinite(u).all() or not np.isfinite(r).all():
        print("NaN or Inf in the solution")
        return False
    law, phi, bound = friction(c, p, args.phi)
    if law is None:
        return False
    # the law in each node's frame, built here from the normal: w_n, w_t the relative displacement (the file's final
    # gap and slip, against the obstacle or the master surface; else from u: u.n + gap, u - (u.n) n), r_n, r_t
    rn = np.einsum("ij,ij->i", r, normal)
    if "final_gap" in c and "slip" in c:
        un, ut = c["final_gap"][:], c["slip"][:]
        if un.shape != (p,) or ut.shape != (p, 3) or not np.isfinite(un).all() or not np.isfinite(ut).all():
            print("/contact/final_gap or /contact/slip: not one finite value (3 for the slip) per contact node")
            return False
        print("kinematics: /contact/final_gap and /contact/slip (relative to the obstacle or the master surface)")
        if "slip_increment" in c:  # a load path: the law of its last step holds for the slip increment (10.2)
            ut = c["slip_increment"][:]
            print("tangential law on /contact/slip_increment (the last step of a load path, docs/derivation.md (10.2))")
    else:
        un = np.einsum("ij,ij->i", u, normal) + gap
        ut = u - (un - gap)[:, None] * normal
    rt = r - rn[:, None] * normal
    umax, rmax = max(np.abs(u).max(), np.abs(un).max(), np.abs(ut).max()), np.abs(r).max()
    utn, rtn = np.linalg.norm(ut, axis=1), np.linalg.norm(rt, axis=1)
    sliding = utn > args.tol * umax
    unit = np.zeros_like(ut)
    unit[sliding] = ut[sliding] / utn[sliding, None]
    # the largest tangential force of each node: phi r_n (Coulomb), s (Tresca), 0 (frictionless)
    limit = np.where(law == COULOMB, phi * rn, np.where(law == TRESCA, bound, 0.0))
    violations = {
        "w_n >= 0": np.max(-un) / umax,
        "r_n >= 0": np.max(-rn) / rmax,
        "w_n r_n = 0": np.max(np.abs(un * rn)) / (umax * rmax),
        "|r_t| <= bound": np.max(rtn - limit) / rmax,
        "r_t = -bound w_t/|w_t|": np.max(np.abs(rt[sliding] + limit[sliding, None] * unit[sliding])) / rmax if sliding.any() else 0.0,
    }
    ok = True
    for name, v in violations.items():
        good = v <= args.tol
        ok &= good
        print("%-28s %9.1e %s" % (name, v, "ok" if good else "VIOLATED"))
    separated = un > args.tol * umax
    print("nodes %d: separated %d, sliding %d, sticking %d%s" % (
        p, separated.sum(), (~separated & sliding).sum(), (~separated & ~sliding).sum(),
        "; states " + "/".join(str((c["state"][:] == s).sum()) for s in range(7)) if "state" in c else ""))
    if "geometry" in f:
        ok &= check_xdmf(args.file, f)
    return ok


NONE, TRESCA, COULOMB = 0, 1, 2


def friction(c, p, phi):
    """The law, Coulomb coefficient and Tresca bound of each node: from the file, else Coulomb with --phi."""
    if "friction_law" in c and "friction" in c:
        law, coefficient = c["friction_law"][:].ravel(), c["friction"][:].ravel()  # (p, 1) when written by ISView
        bound = c["slip_bound"][:].ravel() if "slip_bound" in c else np.zeros(p)
        if law.shape != (p,) or coefficient.shape != (p,) or bound.shape != (p,):
            print("/contact/friction_law, friction or slip_bound do not have one entry per contact node")
            return None, None, None
        if phi is not None and np.any((law == COULOMB) & (coefficient != phi)):
            print("--phi %g differs from the file's coefficients %s" % (phi, np.unique(coefficient[law == COULOMB])))
            return None, None, None
        print("laws (file): %d frictionless, %d Tresca (s %s), %d Coulomb (phi %s)" % (
            (law == NONE).sum(), (law == TRESCA).sum(), describe(bound[law == TRESCA]), (law == COULOMB).sum(),
            describe(coefficient[law == COULOMB])))
        return law, coefficient, bound
    if phi is None:
        print("the file has no /contact/friction_law and /contact/friction: give --phi")
        return None, None, None
    print("laws (--phi): %d Coulomb (phi %g)" % (p, phi))
    return np.full(p, COULOMB), np.full(p, phi), np.zeros(p)


def describe(values):
    u = np.unique(values)
    return "-" if not len(u) else ("%g" % u[0] if len(u) == 1 else "%g..%g" % (u.min(), u.max()))


def check_xdmf(h5name, f):
    xmf = re.sub(r"\.h5$", "", h5name) + ".xmf"
    if not os.path.exists(xmf):
        print("missing XDMF file %s" % xmf)
        return False
    text = open(xmf).read()
    ok = True
    for dims, path in re.findall(r'Dimensions="([0-9 ]+)"[^>]*>[^:<]+:([^<]+)<', text):
        shape = tuple(int(d) for d in dims.split())
        if path not in f or f[path].shape != shape:
            print("XDMF names %s %s, the HDF5 file has %s" % (path, shape, f[path].shape if path in f else "nothing"))
            ok = False
    return ok


def vertex_field(f):
    """The displacement on the mesh, ordered by vertex coordinates (the vertex order depends on the partition)."""
    x, u = f["geometry/vertices"][:], f["fields/displacement"][:]
    return u[np.lexsort((x[:, 2], x[:, 1], x[:, 0]))]


def compare(args):
    a, b = h5py.File(args.a, "r"), h5py.File(args.b, "r")
    ok = True
    if not np.array_equal(a["contact/coordinates"][:], b["contact/coordinates"][:]):
        print("contact nodes differ (coordinates)")
        return False
    for name in ("displacement", "reaction"):
        x, y = a["contact/" + name][:], b["contact/" + name][:]
        d = np.abs(x - y).max() / np.abs(x).max()
        good = d <= args.tol
        ok &= good
        print("%-12s max difference %9.1e relative %s" % (name, d, "ok" if good else "DIFFERENT"))
    if ("geometry" in a) != ("geometry" in b):
        print("one file has a mesh, the other not")
        return False
    if "geometry" in a:
        ua, ub = vertex_field(a), vertex_field(b)
        if ua.shape != ub.shape:
            print("the meshes differ")
            return False
        d = np.abs(ua - ub).max() / np.abs(ua).max()
        ok &= d <= args.tol
        print("%-12s max difference %9.1e relative %s" % ("full field", d, "ok" if d <= args.tol else "DIFFERENT"))
    if "state" in a["contact"] and "state" in b["contact"]:
        same = np.array_equal(a["contact/state"][:], b["contact/state"][:])
        ok &= same
        print("state        %s" % ("identical" if same else "DIFFERENT"))
    return ok


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("coulomb")
    c.add_argument("file")
    c.add_argument("--phi", type=float, default=None, help="Coulomb coefficient of every node, for files without /contact/friction")
    c.add_argument("--tol", type=float, default=1e-8)
    m = sub.add_parser("compare")
    m.add_argument("a")
    m.add_argument("b")
    m.add_argument("--tol", type=float, default=1e-10)
    args = parser.parse_args()
    ok = coulomb(args) if args.cmd == "coulomb" else compare(args)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
