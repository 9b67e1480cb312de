#!/usr/bin/python3
"""The numerical checks of docs/derivation.md section 12 (what "converged" guarantees), in numpy, independent of the
C code.

  tests/stopping_check.py [--nodes 24] [--seed 5]

Checks (exit status 1 if one fails):
  1. (12.1), (12.3): at random points (w, r) of every kind (separated, pulled, stuck, sliding, penetrating) the
     approximation step at gamma_w gives a pair (d, -b/gamma_w) that satisfies the Coulomb law exactly (to round-off),
     |w - d| = |z| and |r + b/gamma_w| = |z|/gamma_w; points that satisfy the law have rho = 0
  2. (12.2): a stiff body nearly floating on a soft spring (P = E (I - Pi) A (I - Pi) + k Pi, Pi the rigid translations,
     E/k = 1e8), pressed and sheared: iterates near its exact discrete solution that ||z|| <= 1e-10 max(||u||, ||gamma f||)
     accepts have forces off by more than 1e-6 of max|r|; from them at most two Newton steps bring rho below 1e-8 and
     the forces and displacements within 1e-6 of the exact solution
  3. (12.5): one node dragged back by its plane (a spring k, friction phi N, the answer: it sticks): from the sliding
     state the plain semismooth iteration reaches the stuck answer for gamma >= 1/(2k) and flips between the two sliding
     directions for gamma < 1/(2k); the elastic trial (the node stuck) is the answer in one step
"""
import argparse
import sys

import numpy as np


def approximation_step(w, c, phi):
    """(1.1)-(1.4) on the scaled c = gamma r at every node (Coulomb): z, d, b"""
    d = np.zeros_like(w)
    for i in range(len(w) // 3):
        wi, ci = w[3 * i:3 * i + 3], c[3 * i:3 * i + 3]
        s = phi * max(0.0, ci[2] - wi[2])
        v = wi[:2] - ci[:2]
        t = (1 - s / np.linalg.norm(v)) * v if np.linalg.norm(v) > s else np.zeros(2)
        d[3 * i:3 * i + 3] = [t[0], t[1], max(wi[2] - ci[2], 0.0)]
    z = d - w
    return z, d, -z - c


def law_violation(w, r, phi):
    """how far the pair (w, r) is from satisfying the Coulomb law exactly, relative to its size (0: it does)"""
    scale = max(np.abs(w).max(), np.abs(r).max(), 1e-300)
    worst = 0.0
    for i in range(len(w) // 3):
        wi, ri = w[3 * i:3 * i + 3], r[3 * i:3 * i + 3]
        worst = max(worst, -wi[2], -ri[2], abs(wi[2] * ri[2]) / scale, np.linalg.norm(ri[:2]) - phi * ri[2])
        if np.linalg.norm(wi[:2]) > 0:
            worst = max(worst, np.abs(ri[:2] + phi * ri[2] * wi[:2] / np.linalg.norm(wi[:2])).max())
    return worst / scale


def law_residual(w, r, phi, U, F):
    """rho of (12.3) on the contact dofs (the whole problem is reduced: no free dofs)"""
    z, _, _ = approximation_step(w, (U / F) * r, phi)
    return np.abs(z).max() / U


def check_exactness(rng, phi):
    """1: (12.1) at random points, rho = 0 at points of the law"""
    n = 400
    w = rng.standard_normal(3 * n)
    r = rng.standard_normal(3 * n)
    worst_graph = worst_identity = 0.0
    for gamma in (1e-6, 1.0, 1e6):
        z, d, b = approximation_step(w, gamma * r, phi)
        worst_graph = max(worst_graph, law_violation(d, -b / gamma, phi))
        worst_identity = max(worst_identity, np.abs((w - d) + z).max() / np.abs(w).max(), np.abs((r + b / gamma) + z / gamma).max() / max(np.abs(r).max(), np.abs(z / gamma).max()))
    # points of the law: separated (w_n > 0, r = 0), stuck (w = 0, r inside the cone), sliding (r on the cone against w_t)
    lawful_w, lawful_r = np.zeros(3 * n), np.zeros(3 * n)
    for i in range(n):
        kind, rn = i % 3, rng.uniform(0.5, 2)
        t = rng.standard_normal(2)
        t /= np.linalg.norm(t)
        if kind == 0:
            lawful_w[3 * i:3 * i + 3] = [*rng.standard_normal(2), rng.uniform(0.1, 1)]
        elif kind == 1:
            lawful_r[3 * i:3 * i + 3] = [*(rng.uniform(0, 0.99) * phi * rn * t), rn]
        else:
            lawful_w[3 * i:3 * i + 2] = rng.uniform(0.1, 1) * t
            lawful_r[3 * i:3 * i + 3] = [*(-phi * rn * t), rn]
    rho = law_residual(lawful_w, lawful_r, phi, np.abs(lawful_w).max(), np.abs(lawful_r).max())
    ok = worst_graph <= 1e-14 and worst_identity <= 1e-15 and rho <= 1e-15
    print("%-46s %s (the law at (d, -b/gamma) %.1e, (12.1) %.1e, rho at points of the law %.1e)" % (
        "(12.1), (12.3): the approximation step's pair", "ok" if ok else "FAILED", worst_graph, worst_identity, rho))
    return ok


def floating_body(p, rng, E=2e8, k=2.0):
    """P of a stiff body (E) on a soft spring (k): the rigid translations Pi held by k alone"""
    A = rng.standard_normal((3 * p, 3 * p))
    A = A @ A.T / (3 * p) + np.eye(3 * p)
    modes = np.zeros((3 * p, 3))
    for j in range(3):
        modes[j::3, j] = 1 / np.sqrt(p)
    Pi = modes @ modes.T
    return E * (np.eye(3 * p) - Pi) @ A @ (np.eye(3 * p) - Pi) + k * Pi


def newton_iterates(P, f, phi, u0=None, its=40):
    """section 7 with gamma = 1/mean diag P from u0 (default 0; plain, as derivation_check.py): every iterate u with its
    ||z|| and the scale max(||u||, ||gamma f||)"""
    n, gamma = len(f), 1 / np.mean(np.diag(P))
    u, out = (np.zeros(n) if u0 is None else u0.copy()), []
    for _ in range(its):
        z, d, b = approximation_step(u, gamma * (P @ u - f), phi)
        out.append((u.copy(), np.linalg.norm(z), max(np.linalg.norm(u), gamma * np.linalg.norm(f))))
        S, T = np.zeros((n, n)), np.zeros((n, n))
        for i in range(n // 3):
            k3 = slice(3 * i, 3 * i + 3)
            di, bi = d[k3], b[k3]
            if di[2] > 0:  # L: zero force
                S[k3, k3] = np.eye(3)
            elif np.linalg.norm(di[:2]) > 0 and bi[2] < 0:  # M1 (5.2)
                om = di[:2] / np.linalg.norm(di[:2])
                S[k3, k3] = [[1, 0, phi * om[0]], [0, 1, phi * om[1]], [0, 0, 0]]
                T[k3, k3][:2, :2] = -phi * bi[2] / np.linalg.norm(di[:2]) * (np.eye(2) - np.outer(om, om))
                T[3 * i + 2, 3 * i + 2] = 1
            else:  # stuck (or weak contact, not met here)
                T[k3, k3] = np.eye(3)
        if np.linalg.norm(z) == 0:
            break
        u = u + np.linalg.solve(S @ (gamma * P) + T, (S + T) @ z)
    return out


def check_floating(rng, phi, p):
    """2: (12.2)-(12.4) on a stiff, nearly floating body: iterates near the exact solution that the ||z|| test accepts
    (a random direction, scaled so that ||z|| = 1e-10 of its scale) have forces off by far more than 1e-8 of max|r|;
    from there Newton steps reach rho <= 1e-8 within two, and the exact solution within 1e-6"""
    P = floating_body(p, rng)
    f = np.zeros(3 * p)
    for i in range(p):
        f[3 * i:3 * i + 3] = [0.32 + 0.02 * rng.uniform(), 0.02 * rng.uniform(), -1.0]  # pressed and sheared past phi: it slides on its spring
    gamma = 1 / np.mean(np.diag(P))
    exact = newton_iterates(P, f, phi)[-1][0]
    r_exact = P @ exact - f
    U, F = np.abs(exact).max(), np.abs(r_exact).max()
    worst_force, worst_steps, worst_error = 0.0, 0, 0.0
    for _ in range(5):
        e = rng.standard_normal(3 * p)
        e *= 1e-6 * U / np.linalg.norm(e)
        t = 1e-10 * max(np.linalg.norm(exact), gamma * np.linalg.norm(f)) / np.linalg.norm(approximation_step(exact + e, gamma * (P @ (exact + e) - f), phi)[0])
        u = exact + t * e  # ||z(u)|| = 1e-10 of the scale (z is linear in t near the solution, the states kept)
        worst_force = max(worst_force, np.abs(P @ u - f - r_exact).max() / F)
        iterates = newton_iterates(P, f, phi, u0=u)
        steps = next((j for j, (v, _, _) in enumerate(iterates) if law_residual(v, P @ v - f, phi, U, F) <= 1e-8), 99)
        worst_steps = max(worst_steps, steps)
        if steps < len(iterates):
            v = iterates[steps][0]
            worst_error = max(worst_error, np.abs(v - exact).max() / U, np.abs(P @ v - f - r_exact).max() / F)
    ok = worst_force > 1e-6 and worst_steps <= 2 and worst_error <= 1e-6
    print("%-46s %s (at ||z|| = 1e-10 of its scale the forces are off by up to %.1e of max|r|; rho <= 1e-8 after at "
          "most %d Newton steps, then within %.1e of the exact solution)" % (
              "(12.2)-(12.4): a stiff body on a soft spring", "ok" if ok else "FAILED", worst_force, worst_steps, worst_error))
    return ok


def drag_back(gamma, k=1000.0, phiN=0.5, delta=5e-4, its=30):
    """3: the node's slip increment s in a step where its plane moved back by delta: the tangential force on it is
    k (s - delta) + phiN (the spring, which held phi N at the step before); the answer: stuck, s = 0 (|k delta| < 2 phi
    N). The plain semismooth iteration (1.2) + Newton from s = delta; returns its iterates"""
    s, out = delta, []
    for _ in range(its):
        r = k * (s - delta) + phiN
        v = s - gamma * r
        sliding = abs(v) > gamma * phiN
        out.append(s)
        z = (v - gamma * phiN * np.sign(v)) - s if sliding else -s
        if abs(z) <= 1e-15 * delta:
            break
        s = delta - (phiN + np.sign(v) * phiN) / k if sliding else 0.0  # the Newton step: r = -sign(v) phi N, or s = 0
    return out


def check_elastic_trial():
    k, delta, phiN = 1000.0, 5e-4, 0.5
    converged = {g: abs(drag_back(g / k, k)[-1]) <= 1e-15 for g in (0.25, 0.45, 0.55, 1, 100)}
    flips = len(drag_back(1e-6 / k, k))  # gamma of (6.1) for a stiff block: 1e-6 of 1/k
    # the trial: the node stuck (s = 0) where the plane took it; its force is inside phi N, so z = 0 there exactly
    force = k * (0 - delta) + phiN
    ok = converged == {0.25: False, 0.45: False, 0.55: True, 1: True, 100: True} and abs(force) <= phiN and flips == 30
    print("%-46s %s (gamma k = 0.25, 0.45: %s; 0.55, 1, 100: %s; gamma k = 1e-6: %d iterations without the answer; "
          "the trial's force %.2f, inside phi N = 0.5: the answer)" % (
              "(12.5): a node dragged back by its plane", "ok" if ok else "FAILED",
              "flips" if not (converged[0.25] or converged[0.45]) else "CONVERGES", "converges" if all(converged[g] for g in (0.55, 1, 100)) else "DOES NOT",
              flips, force))
    return ok


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--nodes", type=int, default=24)
    parser.add_argument("--seed", type=int, default=5)
    parser.add_argument("--phi", type=float, default=0.3)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    ok = check_exactness(rng, args.phi)
    ok &= check_floating(rng, args.phi, args.nodes)
    ok &= check_elastic_trial()
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
