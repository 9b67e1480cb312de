#!/usr/bin/python3
"""Independent checks of an ssstar solution file (HDF5 written by examples/prism -o).

  check_solution.py coulomb FILE.h5 [--phi 0.3] [--tol 1e-8]
      the Coulomb law at every contact node, relative to max|u| and max|r|:
      u_n >= 0, r_n >= 0, u_n r_n = 0, |r_t| <= phi r_n, r_t = -phi r_n u_t/|u_t| where u_t != 0;
      and the XDMF file beside it names datasets of the right shapes
  check_solution.py compare A.h5 B.h5 [--tol 1e-10]
      the contact displacement and reaction, and the displacement on the whole mesh, of two runs agree
      (relative to their max norms), and so do the contact states
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
    u = f["contact/displacement"][:]
    r = f["contact/reaction"][:]
    state = f["contact/state"][:]
    p = len(u)
    shapes = {"coordinates": (p, 3), "displacement": (p, 3), "reaction": (p, 3), "state": (p,)}
    for name, shape in shapes.items():
        if f["contact/" + name].shape != shape:
            print("/contact/%s has shape %s, not %s" % (name, f["contact/" + name].shape, shape))
            return False
    if state.dtype.kind != "i" or state.min() < 0 or state.max() > 5:
        print("/contact/state is not an integer state 0..5")
        return False
    umax, rmax = np.abs(u).max(), np.abs(r).max()
    ut, rt = np.linalg.norm(u[:, :2], axis=1), np.linalg.norm(r[:, :2], axis=1)
    sliding = ut > args.tol * umax
    unit = np.zeros_like(u[:, :2])
    unit[sliding] = u[sliding, :2] / ut[sliding, None]
    violations = {
        "u_n >= 0": np.max(-u[:, 2]) / umax,
        "r_n >= 0": np.max(-r[:, 2]) / rmax,
        "u_n r_n = 0": np.max(np.abs(u[:, 2] * r[:, 2])) / (umax * rmax),
        "|r_t| <= phi r_n": np.max(rt - args.phi * r[:, 2]) / rmax,
        "r_t = -phi r_n u_t/|u_t|": np.max(np.abs(r[sliding, :2] + args.phi * r[sliding, 2, None] * unit[sliding])) / rmax if sliding.any() else 0.0,
    }
    ok = True
    for name, v in violations.items():
        good = v <= args.tol
        ok &= good
        print("%-28s %9.1e %s" % (name, v, "ok" if good else "VIOLATED"))
    separated = u[:, 2] > args.tol * umax
    print("nodes %d: separated %d, sliding %d, sticking %d; states %s" % (
        len(u), separated.sum(), (~separated & sliding).sum(), (~separated & ~sliding).sum(),
        "/".join(str((state == s).sum()) for s in range(6))))
    ok &= check_xdmf(args.file, f)
    return ok


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
    ua, ub = vertex_field(a), vertex_field(b)
    if ua.shape != ub.shape:
        print("the meshes differ")
        return False
    d = np.abs(ua - ub).max() / np.abs(ua).max()
    ok &= d <= args.tol
    print("%-12s max difference %9.1e relative %s" % ("full field", d, "ok" if d <= args.tol else "DIFFERENT"))
    same = np.array_equal(a["contact/state"][:], b["contact/state"][:])
    print("state        %s" % ("identical" if same else "DIFFERENT"))
    return ok and same


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("coulomb")
    c.add_argument("file")
    c.add_argument("--phi", type=float, default=0.3)
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
