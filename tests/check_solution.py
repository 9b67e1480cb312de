#!/usr/bin/python3
"""Independent checks of an ssstar solution file (HDF5 written by examples/prism -o).

  check_solution.py coulomb FILE.h5 [--phi PHI] [--tol 1e-8]      (or: check_solution.py law FILE.h5)
      the friction law of every contact node, relative to max|w| and max|r|, in the node's frame built from
      /contact/normal (default (0, 0, 1)): w_n >= 0, r_n = r.n >= 0, w_n r_n = 0, "|r_t| <= bound": r_t in the node's
      friction set (no farther out than its boundary in the direction of r_t), and "r_t = -bound w_t/|w_t|": on a
      sliding node (w_t != 0) r_t the force of maximum dissipation, r_t = -F(w_t); no NaN or Inf. The laws
      (docs/derivation.md sections 0 and 9):
        none         r_t = 0
        tresca       |r_t| <= s;  F(w_t) = s w_t/|w_t|                          (/contact/slip_bound)
        coulomb      |r_t| <= phi r_n;  F(w_t) = phi r_n w_t/|w_t|              (/contact/friction)
        orthotropic  |M^-1/2 r_t| <= r_n;  F(w_t) = r_n M w_t/|M^1/2 w_t|, M = phi_1^2 a a^T + phi_2^2 a' a'^T, a the
                     friction direction projected onto the tangent plane, a' = n x a  (/contact/friction_1,
                     friction_2, friction_direction)
      w is the node's relative displacement: the normal gap and the slip at the solution the file records
      (/contact/final_gap, /contact/slip: against the rigid obstacle, or for a contact pair the slave node against
      the master surface), else u.n + gap and u - (u.n) n from /contact/displacement and the initial gap
      /contact/gap (default 0), as examples/generic writes; on a load path (/contact/slip_increment) the tangential
      law holds for the slip increment of the last step (docs/derivation.md (10.2)). r is the force on the node (/contact/reaction: the
      pressure and traction times the node's area). The law of each node is /contact/friction_law, by the names of
      its attribute names (the table of laws; without it none, tresca, coulomb), and its parameters are the datasets
      /contact/<parameter> (written by the scenes and by examples/generic); a law this script does not know fails the
      check. --phi gives a Coulomb coefficient for every node of a file without them.
      For a file with a mesh, the XDMF file beside it names datasets of the right shapes, and the stresses
      (/fields/strain, stress: cells x 6; von_mises: cells; stress_nodal: nodes x 6; each step's too) are finite, of
      those shapes, with von_mises the von Mises stress of stress; /groups/<G>/reaction has 3 finite values. A file of
      a hyperelastic scene (/fields/J: docs/derivation.md section 18) has, per cell, J = det F > 0 of the deformation
      gradient F computed here from the file's vertices, cells and displacement, stress the Cauchy stress P F^T / J of
      stress_pk1 and strain the Green-Lagrange strain (F^T F - I)/2 where material_model is hyperelastic (1, 2), stress
      = P where it is linear (0), and /fields/position = vertices + displacement (each step's too). A file without
      contact (no /contact) has these checks alone.
      An FCLib solution file (examples/fclib -o: the problem's /fclib_local or /fclib_global and /solution) is checked
      in FCLib's terms: FCLib's error of /solution/r (Siconos's measure, relative to ||q||) at most --tol, and /solution/u
      = W r + q, W and q from the problem in the file (a global problem condensed: W = H^T M^-1 H, q = H^T M^-1 f + w).
  check_solution.py compare A.h5 B.h5 [--tol 2e-6]
      the contact displacement and reaction of two runs agree (relative to their max norms, at least the scales A's
      solver measured its law against: /law_displacement_scale, /law_force_scale), and so do the
      displacement on the whole mesh and the contact states where both files have them (a file of examples/generic
      has /contact alone); of two FCLib solution files, r, u (and v) of /solution. The default tolerance is the
      agreement the solver guarantees between two runs at its defaults, 2e-6 (harness.AGREE: each run within 1e-6 of
      the exact discrete solution, README "What converged means"): runs on other ranks or the other route differ by
      round-off and by less than that (1 against 2 ranks: 1e-9 to 1e-8); --tol 1e-10 asks for the same computation.
Exit status 0 when the check passes.
"""
import argparse
import os
import re
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import AGREE  # noqa: E402 (2e-6: the agreement of two runs at the defaults)


def coulomb(args):
    f = h5py.File(args.file, "r")
    if is_fclib(f):
        return fclib_law(f, args.tol)
    steps = sorted((k for k in f["steps"] if k.isdigit()), key=int) if "steps" in f else []
    # a load path's step is measured against its own forces and displacements too (those of the step before), and
    # against 1e-6 of the path's largest so far (a step where nothing touches has forces of round-off alone)
    before = lambda k: f["steps/%s/contact" % steps[k - 1]] if k > 0 else None  # noqa: E731
    path = [(0.0, 0.0)]
    contact = "contact" in f
    for k in steps if contact else ():
        c = f["steps/%s/contact" % k]
        path.append((max(path[-1][0], np.abs(c["displacement"][:]).max()), max(path[-1][1], np.abs(c["reaction"][:]).max())))
    # the scales the solver measured its law residual against (at least the round-off of K u - b: a stiff body far
    # from its reference computes its forces to no better), recorded in the file
    solver = (f.attrs.get("law_displacement_scale", 0.0), f.attrs.get("law_force_scale", 0.0))
    recorded = lambda k: (f["steps/law_displacement_scale"][int(k)], f["steps/law_force_scale"][int(k)]) if "steps/law_force_scale" in f else (0.0, 0.0)  # noqa: E731
    ok = check_law(f, f["contact"], "/contact", args, before(len(steps) - 1) if steps else None, path[-1], solver) if contact else True
    if args.steps:
        for j, k in enumerate(steps):
            print("-- step %s (/steps/%s%s)" % (k, k, "/contact" if contact else ""))
            ok &= check_law(f, f["steps/%s/contact" % k], "/steps/%s/contact" % k, args, before(j), path[j + 1], recorded(j)) if contact else True
            ok &= check_fields(f, "steps/%s/" % k)
        print("%d steps checked" % len(steps))
    if "geometry" in f:
        ok &= check_xdmf(args.file, f) and check_fields(f, "")
    return ok


def check_fields(f, prefix):
    """the stresses of <prefix>fields (where the file has them) and the reactions /groups/<G>/reaction"""
    if prefix + "fields/stress" not in f:
        return True
    cells, nodes = len(f["viz/topology/cells"]), len(f["geometry/vertices"])
    shapes = {"strain": (cells, 6), "stress": (cells, 6), "von_mises": (cells,), "stress_nodal": (nodes, 6)}
    for name, shape in shapes.items():
        d = f.get(prefix + "fields/" + name)
        if d is None or d.shape != shape or not np.isfinite(d[:]).all():
            print("/%sfields/%s: not %s finite values" % (prefix, name, shape))
            return False
    s = f[prefix + "fields/stress"][:]
    vm = np.sqrt(0.5 * ((s[:, 0] - s[:, 1]) ** 2 + (s[:, 1] - s[:, 2]) ** 2 + (s[:, 2] - s[:, 0]) ** 2) + 3 * (s[:, 3:] ** 2).sum(axis=1))
    d = np.abs(vm - f[prefix + "fields/von_mises"][:]).max() / max(vm.max(), 1e-300)
    print("%-28s %9.1e %s" % ("/%sfields/von_mises" % prefix, d, "ok" if d <= 1e-12 else "WRONG"))
    good = d <= 1e-12
    if prefix + "fields/J" in f:
        good &= check_finite_strain(f, prefix)
    for g in f.get("groups", {}) if not prefix else ():
        r = f["groups/%s" % g].get("reaction")
        if r is not None and (r.shape != (3,) or not np.isfinite(r[:]).all()):
            print("/groups/%s/reaction: not 3 finite values" % g)
            good = False
    return good


def check_finite_strain(f, prefix):
    """a hyperelastic scene's <prefix>fields: J, stress_pk1, material_model against F computed from the file's mesh and
    displacement, position = vertices + displacement (docs/derivation.md section 18)"""
    x, cells = f["geometry/vertices"][:], f["viz/topology/cells"][:]
    u = f[prefix + "fields/displacement"][:]
    shapes = {"J": (len(cells),), "stress_pk1": (len(cells), 9), "material_model": (len(cells),), "position": x.shape}
    for name, shape in shapes.items():
        d = f.get(prefix + "fields/" + name)
        if d is None or d.shape != shape or not np.isfinite(d[:]).all():
            print("/%sfields/%s: not %s finite values" % (prefix, name, shape))
            return False
    X, U = x[cells], u[cells]  # cells x 4 x 3
    G = np.transpose(X[:, 1:] - X[:, :1], (0, 2, 1))  # columns: the edges from vertex 0
    F = np.eye(3) + np.transpose(U[:, 1:] - U[:, :1], (0, 2, 1)) @ np.linalg.inv(G)
    J = np.linalg.det(F)
    P = f[prefix + "fields/stress_pk1"][:].reshape(-1, 3, 3)
    model = f[prefix + "fields/material_model"][:]
    hyper = model > 0
    sigma = np.where(hyper[:, None, None], P @ np.transpose(F, (0, 2, 1)) / J[:, None, None], P)
    sigma = 0.5 * (sigma + np.transpose(sigma, (0, 2, 1)))  # its symmetric part (P F^T of a round-off P is not symmetric)
    E = 0.5 * (np.transpose(F, (0, 2, 1)) @ F - np.eye(3))
    pick = lambda t: t[:, [0, 1, 2, 1, 0, 0], [0, 1, 2, 2, 2, 1]]  # noqa: E731 (xx, yy, zz, yz, xz, xy)
    stress, strain = f[prefix + "fields/stress"][:], f[prefix + "fields/strain"][:]
    scale = max(np.abs(stress).max(), 1e-300)
    errors = {
        "J = det F": np.abs(J - f[prefix + "fields/J"][:]).max(),
        "stress = P F^T/J (P where linear)": np.abs(pick(sigma) - stress).max() / scale,
        "strain = (F^T F - I)/2": np.abs(pick(E) - strain)[hyper].max() if hyper.any() else 0.0,
        "position = vertices + displacement": np.abs(f[prefix + "fields/position"][:] - x - u).max() / max(np.abs(x).max(), 1e-300),
    }
    ok = J.min() > 0 and model.min() >= 0 and model.max() <= 2
    if not ok:
        print("/%sfields: J <= 0 (%g) or a material_model code outside 0..2" % (prefix, J.min()))
    for what, d in errors.items():
        print("%-28s %9.1e %s (%s)" % ("/%sfields" % prefix, d, "ok" if d <= 1e-9 else "WRONG", what))
        ok &= d <= 1e-9
    return ok


def check_law(f, c, where, args, previous=None, path=(0.0, 0.0), solver=(0.0, 0.0)):
    """the law at every node of the contact group c (/contact, or a load path's /steps/<k>/contact, which takes the
    normals, gaps and the laws' parameters of /contact unless it has its own); previous: the contact group of the step
    before on a load path, whose displacements and forces the step's scales include; path: the largest displacement
    and force of the path up to this step; solver: the scales U, F the solver measured against (0: none recorded)"""
    top = f["contact"]

    def data(name):
        return c[name] if name in c else top[name] if name in top else None

    u = data("displacement")[:]
    r = data("reaction")[:]
    p = len(u)
    normal = data("normal")[:] if data("normal") is not None else np.tile([0.0, 0.0, 1.0], (p, 1))
    gap = data("gap")[:] if data("gap") is not None else np.zeros(p)
    shapes = {"coordinates": (p, 3), "displacement": (p, 3), "reaction": (p, 3), "state": (p,), "normal": (p, 3), "gap": (p,)}
    for name, shape in shapes.items():
        if data(name) is not None and data(name).shape != shape:
            print("%s/%s has shape %s, not %s" % (where, name, data(name).shape, shape))
            return False
    state = data("state")[:] if data("state") is not None else None
    if state is not None and (state.dtype.kind != "i" or state.min() < 0 or state.max() > 6):
        print("%s/state is not an integer state 0..6" % where)
        return False
    if not np.isfinite(u).all() or not np.isfinite(r).all():
        print("NaN or Inf in the solution")
        return False
    laws = friction(top, p, args.phi)
    if laws is None:
        return False
    # the law in each node's frame, built here from the normal: w_n, w_t the relative displacement (the file's final
    # gap and slip, against the obstacle or the master surface; else from u: u.n + gap, u - (u.n) n), r_n, r_t
    rn = np.einsum("ij,ij->i", r, normal)
    if data("final_gap") is not None and data("slip") is not None:
        un, ut = data("final_gap")[:], data("slip")[:]
        if un.shape != (p,) or ut.shape != (p, 3) or not np.isfinite(un).all() or not np.isfinite(ut).all():
            print("%s/final_gap or slip: not one finite value (3 for the slip) per contact node" % where)
            return False
        print("kinematics: %s/final_gap and %s/slip (relative to the obstacle or the master surface)" % (where, where))
        if data("slip_increment") is not None:  # a load path: the law of its step holds for the slip increment (10.2)
            ut = data("slip_increment")[:]
            print("tangential law on %s/slip_increment (a load path's step, docs/derivation.md (10.2))" % where)
    else:
        un = np.einsum("ij,ij->i", u, normal) + gap
        ut = u - (un - gap)[:, None] * normal
    rt = r - rn[:, None] * normal
    umax, rmax = max(np.abs(u).max(), np.abs(un).max(), np.abs(ut).max()), np.abs(r).max()
    if previous is not None:  # the step's changes: a released body's forces go to zero, to be measured against their change
        umax = max(umax, np.abs(u - previous["displacement"][:]).max())
        rmax = max(rmax, np.abs(r - previous["reaction"][:]).max())
    umax, rmax = max(umax, 1e-6 * path[0], solver[0]), max(rmax, 1e-6 * path[1], solver[1])
    umax, rmax = umax if umax > 0 else 1.0, rmax if rmax > 0 else 1.0
    # the verdict (docs/derivation.md section 12): each node's (w, r) lies within tol max|w| and tol max|r| of a pair
    # that satisfies its law exactly; the approximation step at gamma = max|w|/max|r| gives such a pair, z away
    distance = np.zeros(p)
    for law, nodes in laws:
        distance[nodes] = law.distance(nodes, un[nodes], ut[nodes], rn[nodes], rt[nodes], normal[nodes], umax, rmax)
    worst = int(np.argmax(distance))
    # what that bound implies for each condition of the law, with a node "sliding" where its slip exceeds tol max|w|:
    # printed with the bound each may reach
    utn = np.linalg.norm(ut, axis=1)
    sliding = utn > args.tol * umax
    excess, direction = np.zeros(p), np.zeros(p)
    for law, nodes in laws:
        excess[nodes] = law.excess(nodes, rn[nodes], rt[nodes], normal[nodes]) / law.reach(nodes)
        slide = nodes[sliding[nodes]]
        if len(slide):
            dissipative = -law.force(slide, rn[slide], ut[slide], normal[slide])
            # the force's direction follows the slip's to an angle 2 tol max|w| / |w_t|
            allowed = 2 * args.tol * umax / utn[slide] * np.linalg.norm(dissipative, axis=1)
            direction[slide] = (np.linalg.norm(rt[slide] - dissipative, axis=1) - allowed) / law.reach(slide)
    conditions = [
        ("w_n >= 0", np.max(-un) / umax, 1),
        ("r_n >= 0", np.max(-rn) / rmax, 1),
        ("w_n r_n = 0", np.max(np.abs(un * rn)) / (umax * rmax), 3),
        ("|r_t| <= bound", np.max(excess) / rmax, 2),
        ("r_t = -bound w_t/|w_t|", np.max(direction) / rmax if sliding.any() else 0.0, 2),
    ]
    ok = distance[worst] <= args.tol
    print("%-28s %9.1e %s (node %d; tolerance %g of max|w| %.3g and max|r| %.3g)" % (
        "distance to the law", distance[worst], "ok" if ok else "VIOLATED", worst, args.tol, umax, rmax))
    for name, v, reach in conditions:
        good = v <= reach * args.tol
        ok &= good
        print("%-28s %9.1e %s" % (name, v, "ok" if good else "VIOLATED"))
    separated = un > args.tol * umax
    print("nodes %d: separated %d, sliding %d, sticking %d%s" % (
        p, separated.sum(), (~separated & sliding).sum(), (~separated & ~sliding).sum(),
        "; states " + "/".join(str((state == s).sum()) for s in range(7)) if state is not None else ""))
    return ok


def approximation_step_normal(un, rn, gamma):
    """(1.1): z_n and the scaled normal force max(0, gamma r_n - w_n) of the approximation step"""
    return np.maximum(-gamma * rn, -un), np.maximum(0.0, gamma * rn - un)


def soft_threshold(v, s):
    """(1.2): max(0, 1 - s/|v|) v, row by row"""
    size = np.linalg.norm(v, axis=1)
    return np.where(size > s, 1 - s / np.where(size > 0, size, 1.0), 0.0)[:, None] * v


class Isotropic:
    """none, tresca, coulomb: the friction set is the disc of radius limit (0, s, phi r_n)"""
    def __init__(self, name, c, p):
        self.name, self.parameter = name, {"none": None, "tresca": "slip_bound", "coulomb": "friction"}[name]
        self.values = None if self.parameter is None else c[self.parameter][:].reshape(p)

    def limit(self, nodes, rn):
        return np.zeros(len(nodes)) if self.values is None else self.values[nodes] * (rn if self.name == "coulomb" else 1.0)

    def excess(self, nodes, rn, rt, normal):
        return np.linalg.norm(rt, axis=1) - self.limit(nodes, rn)

    def force(self, nodes, rn, wt, normal):
        return self.limit(nodes, rn)[:, None] * wt / np.linalg.norm(wt, axis=1)[:, None]

    def reach(self, nodes):
        """how far r_t may lie beyond the bound per unit of error of r: 1 + the coefficient"""
        return 1.0 + (self.values[nodes] if self.name == "coulomb" else 0.0)

    def distance(self, nodes, un, wt, rn, rt, normal, umax, rmax):
        """|z|/max|w| of the approximation step at gamma = max|w|/max|r| (docs/derivation.md sections 1, 12)"""
        gamma = umax / rmax
        zn, force = approximation_step_normal(un, rn, gamma)
        bound = np.zeros(len(nodes)) if self.values is None else self.values[nodes] * (force if self.name == "coulomb" else gamma)
        zt = soft_threshold(wt - gamma * rt, bound) - wt
        return np.maximum(np.abs(zn), np.linalg.norm(zt, axis=1)) / umax

    def describe(self, nodes):
        label = {"none": "frictionless", "tresca": "Tresca (s %s)", "coulomb": "Coulomb (phi %s)"}[self.name]
        return "%d %s" % (len(nodes), label if self.values is None else label % describe(self.values[nodes]))


class Orthotropic:
    """|M^-1/2 r_t| <= r_n, M = phi_1^2 a a^T + phi_2^2 a' a'^T in the tangent plane (docs/derivation.md section 9)"""
    name = "orthotropic"

    def __init__(self, name, c, p):
        self.phi1, self.phi2 = c["friction_1"][:].reshape(p), c["friction_2"][:].reshape(p)
        self.direction = c["friction_direction"][:].reshape(p, 3)

    def axes(self, nodes, normal):
        """a, a' (unit, in the tangent plane) and phi_1, phi_2 of the nodes"""
        a = self.direction[nodes] - np.einsum("ij,ij->i", self.direction[nodes], normal)[:, None] * normal
        a /= np.linalg.norm(a, axis=1)[:, None]
        return a, np.cross(normal, a), self.phi1[nodes], self.phi2[nodes]

    def excess(self, nodes, rn, rt, normal):
        """|r_t| minus the radius of the ellipse r_n E in the direction of r_t"""
        a, b, phi1, phi2 = self.axes(nodes, normal)
        size = np.linalg.norm(rt, axis=1)
        e = rt / np.where(size > 0, size, 1.0)[:, None]
        gauge = np.hypot(np.einsum("ij,ij->i", e, a) / phi1, np.einsum("ij,ij->i", e, b) / phi2)
        return np.where(size > 0, size - rn / np.where(size > 0, gauge, 1.0), -rn)

    def force(self, nodes, rn, wt, normal):
        """r_n M w_t / |M^1/2 w_t|"""
        a, b, phi1, phi2 = self.axes(nodes, normal)
        wa, wb = np.einsum("ij,ij->i", wt, a), np.einsum("ij,ij->i", wt, b)
        sigma = np.hypot(phi1 * wa, phi2 * wb)
        return (rn / sigma)[:, None] * ((phi1 ** 2 * wa)[:, None] * a + (phi2 ** 2 * wb)[:, None] * b)

    def reach(self, nodes):
        return 1.0 + np.maximum(self.phi1[nodes], self.phi2[nodes])

    def distance(self, nodes, un, wt, rn, rt, normal, umax, rmax):
        """|z|/max|w| of the approximation step (9.2) at gamma = max|w|/max|r|: d_t = v - the projection of v onto the
        ellipse of semi-axes (phi_1, phi_2) times the scaled normal force, by the secular equation"""
        gamma = umax / rmax
        zn, force = approximation_step_normal(un, rn, gamma)
        a, b, phi1, phi2 = self.axes(nodes, normal)
        v = wt - gamma * rt
        p = np.stack([np.einsum("ij,ij->i", v, a), np.einsum("ij,ij->i", v, b)], axis=1)
        e = np.stack([phi1 * force, phi2 * force], axis=1)
        inside = np.sum((p / np.where(e > 0, e, 1.0)) ** 2, axis=1) <= 1
        inside &= (e > 0).all(axis=1)
        t = np.zeros(len(nodes))
        w = e * p
        hi = np.linalg.norm(w, axis=1) - (e ** 2).min(axis=1)
        t = np.maximum(0.0, (np.abs(w) - e ** 2).max(axis=1))
        for _ in range(100):  # Newton from the left of the root of sum w^2/(e^2 + t)^2 = 1 (monotone)
            q = w / (e ** 2 + t[:, None])
            g = np.sum(q ** 2, axis=1) - 1
            dg = -2 * np.sum(q ** 2 / (e ** 2 + t[:, None]), axis=1)
            step = np.where((g > 0) & (dg < 0), -g / np.where(dg < 0, dg, -1.0), 0.0)
            t = np.minimum(t + step, np.maximum(hi, t))
            if np.all(step <= 4e-16 * np.maximum(t, 1e-300)):
                break
        dp = np.where(inside[:, None], 0.0, t[:, None] * p / np.where(e ** 2 + t[:, None] > 0, e ** 2 + t[:, None], 1.0))
        dp = np.where((e == 0).any(axis=1)[:, None] & ~inside[:, None], p, dp)  # no force: the ellipse is a point
        zt = dp[:, :1] * a + dp[:, 1:] * b - wt
        return np.maximum(np.abs(zn), np.linalg.norm(zt, axis=1)) / umax

    def describe(self, nodes):
        return "%d orthotropic (phi_1 %s, phi_2 %s)" % (len(nodes), describe(self.phi1[nodes]), describe(self.phi2[nodes]))


LAWS = {"none": Isotropic, "tresca": Isotropic, "coulomb": Isotropic, "orthotropic": Orthotropic}


def friction(c, p, phi):
    """[(law, its nodes)] from the file's /contact/friction_law and parameters, else Coulomb with --phi for every node"""
    if "friction_law" in c:
        codes = c["friction_law"][:].ravel()  # (p, 1) when written by ISView
        names = text(c["friction_law"].attrs["names"]).split(",") if "names" in c["friction_law"].attrs else ["none", "tresca", "coulomb"]
        if codes.shape != (p,):
            print("/contact/friction_law does not have one entry per contact node")
            return None
        laws = []
        for code in np.unique(codes):
            name = names[code] if 0 <= code < len(names) else "code %d" % code
            if name not in LAWS:
                print("the law %s of %d nodes is not one this check knows (%s)" % (name, (codes == code).sum(), ", ".join(LAWS)))
                return None
            try:
                law = LAWS[name](name, c, p)
            except (KeyError, ValueError) as e:
                print("the parameters of the law %s are not in the file with one entry per node (%s)" % (name, e))
                return None
            if name == "coulomb" and phi is not None and np.any(law.values[codes == code] != phi):
                print("--phi %g differs from the file's coefficients %s" % (phi, np.unique(law.values[codes == code])))
                return None
            laws.append((law, np.flatnonzero(codes == code)))
        print("laws (file): " + ", ".join(law.describe(nodes) for law, nodes in laws))
        return laws
    if phi is None:
        print("the file has no /contact/friction_law: give --phi")
        return None
    print("laws (--phi): %d Coulomb (phi %g)" % (p, phi))
    law = Isotropic.__new__(Isotropic)
    law.name, law.parameter, law.values = "coulomb", "friction", np.full(p, phi)
    return [(law, np.arange(p))]


# --- FCLib solution files (examples/fclib -o): the problem and /solution ----------------------------------------------

def is_fclib(f):
    return ("fclib_local" in f or "fclib_global" in f) and "solution" in f


def fclib_sparse(g):
    """An FCLib sparse matrix group as a dense array (nz = -2 rows, -1 columns, >= 0 triplets: i row, p column)."""
    m, n, nz = int(g["m"][0]), int(g["n"][0]), int(g["nz"][0])
    p, i, x = g["p"][:], g["i"][:], g["x"][:]
    a = np.zeros((m, n))
    if nz >= 0:
        np.add.at(a, (i[:nz], p[:nz]), x[:nz])
    else:
        outer = np.repeat(np.arange(len(p) - 1), np.diff(p))
        rows, cols = (outer, i[:p[-1]]) if nz == -2 else (i[:p[-1]], outer)
        np.add.at(a, (rows, cols), x[:p[-1]])
    return a


def fclib_problem(f):
    """(W, q, mu, global parts or None) of an open FCLib file; a global problem condensed: W = H^T M^-1 H, q = H^T M^-1 f + w."""
    if "fclib_local" in f:
        g = f["fclib_local"]
        return fclib_sparse(g["W"]), g["vectors/q"][:], g["vectors/mu"][:], None
    g = f["fclib_global"]
    M, H, load, w = fclib_sparse(g["M"]), fclib_sparse(g["H"]), g["vectors/f"][:], g["vectors/w"][:]
    return H.T @ np.linalg.solve(M, H), H.T @ np.linalg.solve(M, load) + w, g["vectors/mu"][:], (M, H, load, w)


def fclib_error(W, q, mu, r):
    """FCLib's measure (Siconos fc3d_compute_error with norm ||q||): ||r - proj_C(r - u^)|| / ||q||, u^ = u + mu|u_t| e_n."""
    u = (W @ r + q).reshape(-1, 3)
    r = r.reshape(-1, 3)
    x = r - u
    x[:, 0] -= mu * np.hypot(u[:, 1], u[:, 2])
    xt = np.hypot(x[:, 1], x[:, 2])
    proj = x.copy()
    polar = mu * xt <= -x[:, 0]
    outside = ~polar & (xt > mu * x[:, 0])
    proj[polar] = 0
    xn = (mu * xt + x[:, 0]) / (mu * mu + 1)
    proj[outside, 0] = xn[outside]
    proj[outside, 1:] = (mu * xn / np.where(xt > 0, xt, 1))[outside, None] * x[outside, 1:]
    return np.linalg.norm(r - proj) / np.linalg.norm(q)


def fclib_law(f, tol):
    """FCLib's error of /solution/r and u = W r + q, relative to ||q||"""
    W, q, mu, _ = fclib_problem(f)
    r, u = f["solution/r"][:], f["solution/u"][:]
    error, mismatch = fclib_error(W, q, mu, r), np.linalg.norm(u - (W @ r + q)) / np.linalg.norm(q)
    print("%d contacts (FCLib %s problem)" % (len(mu), "global" if "fclib_global" in f else "local"))
    print("FCLib error   %9.1e (relative to ||q||) %s" % (error, "ok" if error <= tol else "VIOLATED"))
    print("u = W r + q   %9.1e (relative to ||q||) %s" % (mismatch, "ok" if mismatch <= tol else "VIOLATED"))
    return error <= tol and mismatch <= tol


def fclib_compare(a, b, tol):
    """/solution/r, u (and v) of two FCLib solution files, relative to their max norms"""
    ok = True
    for name in ("r", "u", "v"):
        if ("solution/" + name in a) != ("solution/" + name in b):
            print("one file has /solution/%s, the other not" % name)
            return False
        if "solution/" + name not in a:
            continue
        x, y = a["solution/" + name][:], b["solution/" + name][:]
        if x.shape != y.shape:
            print("/solution/%s: shapes %s and %s" % (name, x.shape, y.shape))
            return False
        d = relative(x, y)
        ok &= d <= tol
        print("%-12s max difference %9.1e relative %s" % ("solution/" + name, d, "ok" if d <= tol else "DIFFERENT"))
    return ok


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


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


def compare_steps(a, b, tol):
    """every step of two load paths: the contact displacement and reaction and the whole field, relative to the first
    file's step and its change from the step before, and at least 1e-6 of the path's largest so far (the step's own
    scale, as the law's, docs/derivation.md section 12)"""
    steps, pair = aligned_steps(a, b)
    if steps is None:
        return False
    order = lambda f: np.lexsort(f["geometry/vertices"][:].T[::-1])  # noqa: E731 (vertices by coordinates)
    oa, ob = (order(a), order(b)) if "geometry" in a and "geometry" in b else (None, None)
    worst, largest = {}, {}  # the largest of each field over the path so far: its scale is at least 1e-6 of that
    position = {k: i for i, k in enumerate(sorted((k for k in a["steps"] if k.isdigit()), key=int))}
    recorded = lambda name, k: a["steps/law_%s_scale" % name][position[k]] if "steps/law_%s_scale" % name in a else 0.0  # noqa: E731
    for j, k in enumerate(steps):
        fields = [("displacement", "contact/displacement", None), ("reaction", "contact/reaction", None)]
        if oa is not None:
            fields.append(("full field", "fields/displacement", (oa, ob)))
        for name, path, vertex in fields:
            x, y = a["steps/%s/%s" % (k, path)][:], b["steps/%s/%s" % (pair[k], path)][:]
            if vertex is not None:
                x, y = x[vertex[0]], y[vertex[1]]
            scale = np.abs(x).max()
            largest[name] = max(largest.get(name, 0.0), scale)
            if j > 0:
                before = a["steps/%s/%s" % (steps[j - 1], path)][:]
                scale = max(scale, np.abs(x - (before[vertex[0]] if vertex is not None else before)).max())
            scale = max(scale, 1e-6 * largest[name], floor(name, recorded("force", k), recorded("displacement", k)))
            d = np.abs(x - y).max() / (scale if scale > 0 else 1.0)
            if d >= worst.get(name, (-1, None))[0]:
                worst[name] = (d, k)
    ok = True
    for name, (d, k) in worst.items():
        ok &= d <= tol
        print("%-12s max difference %9.1e relative (step %s) %s" % (name, d, k, "ok" if d <= tol else "DIFFERENT"))
    differ = sum(int((a["steps/%s/contact/state" % k][:] != b["steps/%s/contact/state" % pair[k]][:]).sum()) for k in steps)
    print("%d steps compared; states differ at %d node-steps" % (len(steps), differ))
    return ok


def aligned_steps(a, b):
    """the steps of the first file and the second's step at the same time of the path: a path that halved a step (the
    stepper's cut, where a step did not converge) holds every time of the other and the halves between; the steps of
    the file with fewer times are compared. None where neither file's times are all in the other"""
    def times(f):
        ks = sorted((k for k in f["steps"] if k.isdigit()), key=int) if "steps" in f else []
        return ks, [float(f["steps/%s" % k].attrs["time"]) if "time" in f["steps/%s" % k].attrs else float(k) for k in ks]

    (ka, ta), (kb, tb) = times(a), times(b)
    at = lambda t, ts: [i for i, s in enumerate(ts) if abs(s - t) <= 1e-12 * max(1.0, abs(t))]  # noqa: E731
    if ka == kb and ta == tb:
        return ka, dict(zip(ka, kb))
    if all(at(t, tb) for t in ta):
        pair = {k: kb[at(t, tb)[0]] for k, t in zip(ka, ta)}
        print("the second file has %d steps more (halved steps): compared at the first file's %d times" % (len(kb) - len(ka), len(ka)))
        return ka, pair
    if all(at(t, ta) for t in tb):
        keep = [ka[at(t, ta)[0]] for t in tb]
        print("the first file has %d steps more (halved steps): compared at the second file's %d times" % (len(ka) - len(kb), len(kb)))
        return keep, dict(zip(keep, kb))
    print("the files have different steps (times %s and %s)" % (describe(ta), describe(tb)))
    return None, None


def floor(name, force, displacement):
    """the least scale of a contact field: the force and displacement scales the solver measured the law against
    (docs/derivation.md (12.2), /law_force_scale, /law_displacement_scale): where nothing presses (a body exactly
    touching its obstacle, section 19) the reactions are round-off of the terms |K| |u|, which the law's force scale
    counts; their relative difference would compare noise with noise"""
    return {"reaction": force, "displacement": displacement}.get(name, 0.0)


def relative(x, y, least=0.0):
    """max|x - y| relative to max|x| (at least least); absolute where both are zero (every contact node stuck where it
    started)"""
    scale = max(np.abs(x).max(), least)
    return np.abs(x - y).max() / (scale if scale > 0 else 1.0)


def compare(args):
    a, b = h5py.File(args.a, "r"), h5py.File(args.b, "r")
    ok = True
    if is_fclib(a) or is_fclib(b):
        if not (is_fclib(a) and is_fclib(b)):
            print("one file is an FCLib solution, the other not")
            return False
        return fclib_compare(a, b, args.tol)
    if not np.array_equal(a["contact/coordinates"][:], b["contact/coordinates"][:]):
        print("contact nodes differ (coordinates)")
        return False
    if args.steps and "steps" in a:
        return compare_steps(a, b, args.tol)
    for name in ("displacement", "reaction"):
        x, y = a["contact/" + name][:], b["contact/" + name][:]
        d = relative(x, y, floor(name, a.attrs.get("law_force_scale", 0.0), a.attrs.get("law_displacement_scale", 0.0)))
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
        d = relative(ua, ub)
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
    c = sub.add_parser("coulomb", aliases=["law"])
    c.add_argument("file")
    c.add_argument("--phi", type=float, default=None, help="Coulomb coefficient of every node, for files without /contact/friction")
    c.add_argument("--tol", type=float, default=1e-7, help="relative to max|w| and max|r| (default 1e-7: the solver guarantees 1e-8 by its own scales at its defaults)")
    c.add_argument("--steps", action="store_true", help="also every step of a load path (/steps/<k>/contact)")
    m = sub.add_parser("compare")
    m.add_argument("a")
    m.add_argument("b")
    m.add_argument("--steps", action="store_true", help="every step of two load paths, each relative to its own scale (not the states)")
    m.add_argument("--tol", type=float, default=AGREE, help="relative to the max norms (default 2e-6, harness.AGREE: the agreement of two runs at the solver's defaults)")
    args = parser.parse_args()
    ok = coulomb(args) if args.cmd in ("coulomb", "law") else compare(args)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
