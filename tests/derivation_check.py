#!/usr/bin/python3
"""Re-does the numerical checks of docs/derivation.md (section 8) on a small random contact problem, in numpy, and
compares the library's per-node kernels with the formulas of the page.

  tests/derivation_check.py [--nodes 16] [--seed 3]

Checks (exit status 1 if one fails):
  1. the approximation step (1.1)-(1.4) gives (d, b) in gph Q exactly: d_n b_n = 0, |b_t| <= phi |b_n|, and on a
     sliding node b_t = -phi b_n d_t/|d_t| (to round-off)
  2. the 6p Newton system (4.1) and the 3p system (5.1) give the same step (to 1e-12)
  3. T G = S H for every state (5.3)
  4. with omega = +d_t/|d_t| (3.2) the iteration converges quadratically (the last ratio ||z_k+1||/||z_k||^2 bounded,
     at most 8 iterations); with the slides' sign it needs at least twice as many iterations (linear convergence)
  5. lib/libssstar.so's SSStarTangentBlocks and SSStarReducedBlocks equal G, H, S, T of (3.1)-(3.2) and (5.2) on
     nodes of every state (to 1e-15), so the code carries the corrected sign
  6. the orthotropic law (section 9) on the same problem with a random direction and coefficients per node: (d, b) in
     gph Q (9.1) exactly, the 6p and 3p steps of its blocks (9.3) equal, T G = S H, quadratic convergence; with
     phi_1 = phi_2 it gives coulomb's iterates; the library's kernels equal (9.2)-(9.4) (its secular equation solved
     here by bisection, independently of the library's Newton iteration)"""
import argparse
import ctypes
import os
import sys

import numpy as np
import petsc4py

petsc4py.init([])  # SSStarFrictionSet needs PETSc and the table of laws
from petsc4py import PETSc  # noqa: E402,F401

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STATES = ["L", "M1", "M2", "M3+", "M3-", "M4"]  # the codes of SSStarState


def approximation_step(u, c, phi):
    """(1.1)-(1.4) at every node: d (its zeros exact), z = d - u, b = -z - c"""
    d = np.zeros_like(u)
    for i in range(len(u) // 3):
        ui, ci = u[3 * i:3 * i + 3], c[3 * i:3 * i + 3]
        s = phi * max(0.0, ci[2] - ui[2])
        v = ui[:2] - ci[:2]
        w = (1 - s / np.linalg.norm(v)) * v if np.linalg.norm(v) > s else np.zeros(2)
        d[3 * i:3 * i + 3] = [w[0], w[1], max(ui[2] - ci[2], 0.0)]
    z = d - u
    return z, d, -z - c


def classify(d, b, phi, tol_d, tol_b, margin=None):
    """Table 1 (2.1); margin: how far b_t is inside the friction set (Coulomb: phi |b_3| - |b_t|; (9.4))"""
    if d[2] > tol_d:
        return "L"
    sliding = np.linalg.norm(d[:2]) > tol_d
    if -b[2] <= tol_b:
        return "M2" if sliding else "M4"
    if sliding:
        return "M1"
    return "M3+" if (-phi * b[2] - np.linalg.norm(b[:2]) if margin is None else margin) > tol_b else "M3-"


def blocks(state, d, b, phi, sign=1.0):
    """G, H (3.1)-(3.2) and S, T (5.2); sign = -1 gives the slides' omega"""
    I, O = np.eye(3), np.zeros((3, 3))
    if state in ("L", "M2", "M4"):
        return I, O, I, O
    if state in ("M3+", "M3-"):
        return O, I, O, I
    om = sign * d[:2] / np.linalg.norm(d[:2])
    W = -phi * b[2] / np.linalg.norm(d[:2]) * (np.eye(2) - np.outer(om, om))
    G = np.diag([1.0, 1.0, 0.0])
    H = np.zeros((3, 3))
    H[:2, :2], H[:2, 2], H[2, 2] = W, -phi * om, 1.0
    S = np.array([[1.0, 0.0, phi * om[0]], [0.0, 1.0, phi * om[1]], [0.0, 0.0, 0.0]])
    T = np.zeros((3, 3))
    T[:2, :2], T[2, 2] = W, 1.0
    return G, H, S, T


def problem(p, seed):
    """A random SPD P (3p x 3p) and a load pressing three nodes in four onto the plane, with tangential parts that
    make some slide and some stick, and lifting the others"""
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((3 * p, 3 * p))
    P = A @ A.T / (3 * p) + 2 * np.eye(3 * p)
    f = np.zeros(3 * p)
    for i in range(p):
        angle, size = rng.uniform(0, 2 * np.pi), rng.uniform(0, 0.7)
        f[3 * i:3 * i + 3] = [size * np.cos(angle), size * np.sin(angle), -1.0 if i % 4 else 0.6]
    return P, f


class Coulomb:
    """Sections 1-3 at every node with one phi (sign = -1: the slides' omega)"""

    def __init__(self, phi, sign=1.0):
        self.phi, self.sign = phi, sign

    def step(self, u, c):
        return approximation_step(u, c, self.phi)

    def classify(self, i, d, b, tol_d, tol_b):
        return classify(d, b, self.phi, tol_d, tol_b)

    def blocks(self, i, state, d, b):
        return blocks(state, d, b, self.phi, self.sign)


class Orthotropic:
    """Section 9 at every node: phi_1 along the unit tangential direction a of the node, phi_2 across it"""

    def __init__(self, phi1, phi2, a):
        self.phi1, self.phi2, self.a = np.asarray(phi1), np.asarray(phi2), np.asarray(a)

    def M(self, i):
        a = self.a[i]
        ap = np.array([-a[1], a[0]])
        return self.phi1[i] ** 2 * np.outer(a, a) + self.phi2[i] ** 2 * np.outer(ap, ap)

    def principal(self, i):
        a = self.a[i]
        return np.array([a, [-a[1], a[0]]])  # rows a, a': v -> its principal coordinates

    def prox(self, i, s, v):
        """(9.2): v minus its projection onto the ellipse s E; the secular equation by bisection"""
        if s == 0:
            return v.copy()
        Q = self.principal(i)
        w, e = Q @ v, s * np.array([self.phi1[i], self.phi2[i]])
        if ((w / e) ** 2).sum() <= 1:
            return np.zeros(2)
        g = lambda t: ((e * w / (e ** 2 + t)) ** 2).sum() - 1
        lo, hi = 0.0, np.linalg.norm(e * w)
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if g(mid) > 0 else (lo, mid)
        t = 0.5 * (lo + hi)
        return Q.T @ (t * w / (e ** 2 + t))

    def step(self, u, c):
        d = np.zeros_like(u)
        for i in range(len(u) // 3):
            ui, ci = u[3 * i:3 * i + 3], c[3 * i:3 * i + 3]
            d[3 * i:3 * i + 2] = self.prox(i, max(0.0, ci[2] - ui[2]), ui[:2] - ci[:2])
            d[3 * i + 2] = max(ui[2] - ci[2], 0.0)
        z = d - u
        return z, d, -z - c

    def gauge(self, i, bt):
        return np.sqrt(bt @ np.linalg.solve(self.M(i), bt))

    def margin(self, i, b):
        """(9.4)"""
        return min(self.phi1[i], self.phi2[i]) * (-b[2] - self.gauge(i, b[:2]))

    def grad(self, i, dt):
        M = self.M(i)
        return M @ dt / np.sqrt(dt @ M @ dt)

    def classify(self, i, d, b, tol_d, tol_b):
        return classify(d, b, None, tol_d, tol_b, self.margin(i, b))

    def blocks(self, i, state, d, b):
        """(9.3): W = r_n grad^2 sigma(d_t), coupling k = grad sigma(d_t)"""
        I, O = np.eye(3), np.zeros((3, 3))
        if state in ("L", "M2", "M4"):
            return I, O, I, O
        if state in ("M3+", "M3-"):
            return O, I, O, I
        M, dt = self.M(i), d[:2]
        sigma = np.sqrt(dt @ M @ dt)
        k = M @ dt / sigma
        W = -b[2] * (M - np.outer(k, k)) / sigma
        G = np.diag([1.0, 1.0, 0.0])
        H = np.zeros((3, 3))
        H[:2, :2], H[:2, 2], H[2, 2] = W, -k, 1.0
        S = np.array([[1.0, 0.0, k[0]], [0.0, 1.0, k[1]], [0.0, 0.0, 0.0]])
        T = np.zeros((3, 3))
        T[:2, :2], T[2, 2] = W, 1.0
        return G, H, S, T


def newton(P, f, law, its=60, check=None):
    """Section 7 with gamma = 1/mean diag P from u = 0; returns the ||z|| of every iterate (and the iterates)"""
    n, gamma = len(f), 1 / np.mean(np.diag(P))
    u, history, iterates = np.zeros(n), [], []
    for k in range(its):
        c = gamma * (P @ u - f)
        z, d, b = law.step(u, c)
        history.append(np.linalg.norm(z))
        iterates.append(u)
        if history[-1] <= 1e-14 * max(np.linalg.norm(u), 1):
            break
        tol_d, tol_b = 1e-13 * max(np.abs(u).max(), np.abs(d).max()), 1e-13 * max(np.abs(gamma * f).max(), np.abs(b).max())
        G, H, S, T = (np.zeros((n, n)) for _ in range(4))
        for i in range(n // 3):
            k3 = slice(3 * i, 3 * i + 3)
            state = law.classify(i, d[k3], b[k3], tol_d, tol_b)
            G[k3, k3], H[k3, k3], S[k3, k3], T[k3, k3] = law.blocks(i, state, d[k3], b[k3])
        du = np.linalg.solve(S @ (gamma * P) + T, (S + T) @ z)  # (5.1)
        if check is not None:
            check(P, gamma, z, d, b, G, H, S, T, du)
        u = u + du
    return history, iterates


class Friction(ctypes.Structure):
    """SSStarFriction: the law (a pointer into the library's table) and its values"""
    _fields_ = [("law", ctypes.c_void_p), ("value", ctypes.c_double * 6)]


def library_friction(lib, law, values):
    fr = Friction()
    lib.SSStarFrictionSet.argtypes = [ctypes.POINTER(Friction), ctypes.c_char_p, ctypes.c_int, ctypes.POINTER(ctypes.c_double)]
    if lib.SSStarFrictionSet(ctypes.byref(fr), law, len(values), (ctypes.c_double * len(values))(*values)):
        sys.exit("SSStarFrictionSet failed")
    return fr


def library_blocks(lib, state, d, b, phi, fr=None):
    """G, H, S, T of the library's kernels (Coulomb with phi, or the friction fr)"""
    fr = fr if fr is not None else library_friction(lib, b"coulomb", [phi])
    vec = ctypes.c_double * 3
    mats = [(ctypes.c_double * 9)() for _ in range(4)]
    lib.SSStarTangentBlocks(STATES.index(state), ctypes.byref(fr), vec(*d), vec(*b), mats[0], mats[1])
    lib.SSStarReducedBlocks(STATES.index(state), ctypes.byref(fr), vec(*d), vec(*b), mats[2], mats[3])
    return [np.array(m[:]).reshape(3, 3) for m in mats]


def library_step(lib, fr, u, c):
    """z, d, b and the state (tolerances 0) of the library's kernels at one node"""
    vec = ctypes.c_double * 3
    z, d, b = vec(), vec(), vec()
    lib.SSStarApproximationStep(ctypes.byref(fr), vec(*u), vec(*c), z, d, b)
    lib.SSStarClassify.restype = ctypes.c_int
    lib.SSStarClassify.argtypes = [ctypes.POINTER(Friction), ctypes.c_void_p, ctypes.c_void_p, ctypes.c_double, ctypes.c_double]
    state = lib.SSStarClassify(ctypes.byref(fr), d, b, 0.0, 0.0)
    return np.array(z[:]), np.array(d[:]), np.array(b[:]), STATES[state]


def check_orthotropic(lib, P, f, seed):
    """Check 6: the orthotropic law (section 9); returns whether every part holds"""
    p, rng = len(f) // 3, np.random.default_rng(seed + 1)
    angles = rng.uniform(0, 2 * np.pi, p)
    law = Orthotropic(rng.uniform(0.2, 0.5, p), rng.uniform(0.2, 0.6, p), np.stack([np.cos(angles), np.sin(angles)], axis=1))
    worst, seen = {"gph Q": 0.0, "6p = 3p": 0.0, "T G = S H": 0.0}, set()

    def check(P, gamma, z, d, b, G, H, S, T, du):
        n, scale = len(z), max(np.abs(b).max(), 1e-300)
        for i in range(n // 3):
            di, bi = d[3 * i:3 * i + 3], b[3 * i:3 * i + 3]
            worst["gph Q"] = max(worst["gph Q"], abs(di[2] * bi[2]) / scale, -law.margin(i, bi) / scale)
            if np.linalg.norm(di[:2]) > 0 and bi[2] < 0:  # sliding: b_t = r_n grad sigma(d_t)
                worst["gph Q"] = max(worst["gph Q"], np.abs(bi[:2] + bi[2] * law.grad(i, di[:2])).max() / scale)
            seen.add(law.classify(i, di, bi, 0, 0))
        D = np.block([[gamma * P, -H], [np.eye(n), G]])
        du6 = np.linalg.solve(D, np.concatenate([z, z]))[:n]
        worst["6p = 3p"] = max(worst["6p = 3p"], np.abs(du6 - du).max() / max(np.abs(du).max(), 1e-300))
        worst["T G = S H"] = max(worst["T G = S H"], np.abs(T @ G - S @ H).max())

    history, _ = newton(P, f, law, check=check)
    ok = True
    for name, limit in (("gph Q", 1e-14), ("6p = 3p", 1e-12), ("T G = S H", 1e-15)):
        good = worst[name] <= limit
        ok &= good
        print("%-34s %9.1e %s" % ("orthotropic: " + name, worst[name], "ok" if good else "FAILED"))
    quadratic = len(history) <= 10 and history[-1] <= 1e-13 and history[-2] <= 10 * history[-3] ** 2 / history[0]
    ok &= quadratic and {"L", "M1", "M3+"} <= seen
    print("%-34s %s (%d iterations: %s); states met: %s" % ("orthotropic: Newton", "quadratic" if quadratic else "NOT QUADRATIC", len(history), ", ".join("%.1e" % h for h in history),
                                                          " ".join(s for s in STATES if s in seen)))
    # phi_1 = phi_2 = 0.3: coulomb's iterates
    iso_h, iso_u = newton(P, f, Orthotropic(np.full(p, 0.3), np.full(p, 0.3), law.a))
    cou_h, cou_u = newton(P, f, Coulomb(0.3))
    diff = max(np.abs(a - b).max() / max(np.abs(b).max(), 1e-300) for a, b in zip(iso_u, cou_u)) if len(iso_u) == len(cou_u) else np.inf
    good = diff <= 1e-12
    ok &= good
    print("%-34s %9.1e %s (%d iterations each)" % ("orthotropic phi_1 = phi_2: coulomb", diff, "ok" if good else "FAILED", len(cou_u)))
    # the library's kernels on random nodes of every kind, the direction (a, 0) in the node's frame
    worst_lib = 0.0
    for k in range(400):
        i = k % p
        u, c = rng.uniform(-1, 1, 3), rng.uniform(-1, 1, 3)
        if k % 3 == 0:
            u[2] = 0.0
        fr = library_friction(lib, b"orthotropic", [law.phi1[i], law.phi2[i], law.a[i][0], law.a[i][1], 0.0])
        zl, dl, bl, state = library_step(lib, fr, u, c)
        zn, dn, bn = law.step(np.concatenate([np.zeros(3 * i), u]), np.concatenate([np.zeros(3 * i), c]))
        zn, dn, bn = zn[3 * i:], dn[3 * i:], bn[3 * i:]
        worst_lib = max(worst_lib, np.abs(zl - zn).max(), np.abs(dl - dn).max(), np.abs(bl - bn).max())
        if state != law.classify(i, dn, bn, 0, 0) and abs(law.margin(i, bn)) > 1e-14:
            worst_lib = np.inf
        for mine, theirs in zip(law.blocks(i, state, dl, bl), library_blocks(lib, state, dl, bl, 0, fr)):
            worst_lib = max(worst_lib, np.abs(mine - theirs).max() / max(1, np.abs(mine).max()))
    good = worst_lib <= 1e-13
    ok &= good
    print("%-34s %9.1e %s" % ("orthotropic: library = (9.2)-(9.4)", worst_lib, "ok" if good else "FAILED"))
    return ok


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--nodes", type=int, default=16)
    parser.add_argument("--seed", type=int, default=3)
    parser.add_argument("--phi", type=float, default=0.3)
    args = parser.parse_args()
    P, f, phi = *problem(args.nodes, args.seed), args.phi
    worst = {"gph Q": 0.0, "6p = 3p": 0.0, "T G = S H": 0.0}
    seen = set()

    def check(P, gamma, z, d, b, G, H, S, T, du):
        n, scale = len(z), max(np.abs(b).max(), 1e-300)  # relative to the largest force
        for i in range(n // 3):
            di, bi = d[3 * i:3 * i + 3], b[3 * i:3 * i + 3]
            worst["gph Q"] = max(worst["gph Q"], abs(di[2] * bi[2]) / scale, (np.linalg.norm(bi[:2]) + phi * bi[2]) / scale)
            if np.linalg.norm(di[:2]) > 0 and bi[2] < 0:
                worst["gph Q"] = max(worst["gph Q"], np.abs(bi[:2] + phi * bi[2] * di[:2] / np.linalg.norm(di[:2])).max() / scale)
            seen.add(classify(di, bi, phi, 0, 0))
        D = np.block([[gamma * P, -H], [np.eye(n), G]])  # (4.1)
        du6 = np.linalg.solve(D, np.concatenate([z, z]))[:n]
        worst["6p = 3p"] = max(worst["6p = 3p"], np.abs(du6 - du).max() / max(np.abs(du).max(), 1e-300))
        worst["T G = S H"] = max(worst["T G = S H"], np.abs(T @ G - S @ H).max())

    derived, _ = newton(P, f, Coulomb(phi), check=check)
    slides, _ = newton(P, f, Coulomb(phi, -1.0))
    ok = True
    for name, value, limit in (("gph Q", worst["gph Q"], 1e-14), ("6p = 3p", worst["6p = 3p"], 1e-12), ("T G = S H", worst["T G = S H"], 1e-15)):
        good = value <= limit
        ok &= good
        print("%-34s %9.1e %s" % (name, value, "ok" if good else "FAILED"))
    quadratic = len(derived) <= 8 and derived[-1] <= 1e-13 and derived[-2] <= 10 * derived[-3] ** 2 / derived[0]
    ok &= quadratic and len(slides) >= 2 * len(derived)
    print("%-34s %s (%d iterations: %s)" % ("omega = +d_t/|d_t| (3.2)", "quadratic" if quadratic else "NOT QUADRATIC", len(derived), ", ".join("%.1e" % h for h in derived)))
    print("%-34s %d iterations (last ratios %s) %s" % ("the slides' omega", len(slides), ", ".join("%.2f" % (a / b) for a, b in zip(slides[-3:], slides[-4:-1])), "ok" if len(slides) >= 2 * len(derived) else "NOT SLOWER"))
    print("states met: %s" % " ".join(s for s in STATES if s in seen))
    ok &= {"L", "M1", "M3+"} <= seen

    lib = ctypes.CDLL(os.path.join(ROOT, "lib", "libssstar.so"), mode=ctypes.RTLD_GLOBAL)
    lib.SSStarInitializePackage()
    rng = np.random.default_rng(args.seed)
    worst_lib = 0.0
    for state in STATES:
        d = np.array([rng.uniform(-1, 1), rng.uniform(-1, 1), 0.0])
        b = np.array([rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), -1.0])
        for mine, theirs in zip(blocks(state, d, b, phi), library_blocks(lib, state, d, b, phi)):
            worst_lib = max(worst_lib, np.abs(mine - theirs).max())
    d, b = np.array([0.3, -0.4, 0.0]), np.array([0.06, -0.08, -1.0])
    slides = max(np.abs(mine - theirs).max() for mine, theirs in zip(blocks("M1", d, b, phi, -1.0), library_blocks(lib, "M1", d, b, phi)))
    good = worst_lib <= 1e-15 and slides >= 0.1 * phi
    ok &= good
    print("%-34s %9.1e %s (the slides' sign differs by %.2f)" % ("library kernels = (3.1), (5.2)", worst_lib, "ok" if good else "FAILED", slides))
    ok &= check_orthotropic(lib, P, f, args.seed)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
