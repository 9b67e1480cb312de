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
     nodes of every state (to 1e-15), so the code carries the corrected sign"""
import argparse
import ctypes
import os
import sys

import numpy as np

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


def classify(d, b, phi, tol_d, tol_b):
    """Table 1 (2.1)"""
    if d[2] > tol_d:
        return "L"
    sliding = np.linalg.norm(d[:2]) > tol_d
    if -b[2] <= tol_b:
        return "M2" if sliding else "M4"
    if sliding:
        return "M1"
    return "M3+" if -phi * b[2] - np.linalg.norm(b[:2]) > tol_b else "M3-"


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


def newton(P, f, phi, sign, its=60, check=None):
    """Section 7 with gamma = 1/mean diag P from u = 0; returns the ||z|| of every iterate"""
    n, gamma = len(f), 1 / np.mean(np.diag(P))
    u, history = np.zeros(n), []
    for k in range(its):
        c = gamma * (P @ u - f)
        z, d, b = approximation_step(u, c, phi)
        history.append(np.linalg.norm(z))
        if history[-1] <= 1e-14 * max(np.linalg.norm(u), 1):
            break
        tol_d, tol_b = 1e-13 * max(np.abs(u).max(), np.abs(d).max()), 1e-13 * max(np.abs(gamma * f).max(), np.abs(b).max())
        G, H, S, T = (np.zeros((n, n)) for _ in range(4))
        for i in range(n // 3):
            k3 = slice(3 * i, 3 * i + 3)
            state = classify(d[k3], b[k3], phi, tol_d, tol_b)
            G[k3, k3], H[k3, k3], S[k3, k3], T[k3, k3] = blocks(state, d[k3], b[k3], phi, sign)
        du = np.linalg.solve(S @ (gamma * P) + T, (S + T) @ z)  # (5.1)
        if check is not None:
            check(P, gamma, z, d, b, G, H, S, T, du)
        u = u + du
    return history


class Friction(ctypes.Structure):
    _fields_ = [("law", ctypes.c_int), ("phi", ctypes.c_double), ("bound", ctypes.c_double)]


def library_blocks(lib, state, d, b, phi):
    """G, H, S, T of the library's kernels"""
    fr = Friction(2, phi, 0.0)
    vec = ctypes.c_double * 3
    mats = [(ctypes.c_double * 9)() for _ in range(4)]
    lib.SSStarTangentBlocks(STATES.index(state), ctypes.byref(fr), vec(*d), vec(*b), mats[0], mats[1])
    lib.SSStarReducedBlocks(STATES.index(state), ctypes.byref(fr), vec(*d), vec(*b), mats[2], mats[3])
    return [np.array(m[:]).reshape(3, 3) for m in mats]


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

    derived = newton(P, f, phi, +1.0, check=check)
    slides = newton(P, f, phi, -1.0)
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

    lib = ctypes.CDLL(os.path.join(ROOT, "lib", "libssstar.so"))
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
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
