#!/usr/bin/python3
"""Re-does the numerical checks of docs/derivation.md section 17 (a nonlinear residual with contact) in numpy, with the
per-node formulas of tests/derivation_check.py (sections 1-5).

  tests/nonlinear_check.py [--nodes 16] [--seed 3] [--stiffening 0.5]

Checks (exit status 1 if one fails):
  1. F(u) = P u + kappa u^3 - f (a random SPD P, Coulomb phi = 0.3, kappa u^3 = s max|f| at the affine solution):
     the iteration of (17.2)-(17.4) (the Jacobian at every iterate, the merit ||z|| of F itself, Armijo damping) ends at
     z = 0 with F + Q satisfied by its approximation step's pair to round-off, and converges superlinearly: the observed
     order log(z_k+1/z_k)/log(z_k/z_k-1) of its last steps at least 1.8
  2. the affine model (the Jacobian and b = -F(0) taken once, c = J u - b: what the solver did before section 17) ends
     at its own z = 0 where F is off equilibrium by about s max|f| (17.1): a false "converged", which the check of a
     declared-affine residual at the solution (17.6) sees
  3. the chord iteration (the first Jacobian kept, c from F: -snes_lag_jacobian -2) converges to the same point, only
     linearly (orders about 1): the superlinear rate is the Jacobian's
  4. the contact measured at the iterates (17.5): nodes pressed frictionlessly onto a ball, its normal and gap taken at
     each iterate: the limit has the exact gap 0 at the touching nodes and the force along the exact normal; without
     the normal's turning in the Newton matrix it converges linearly at about r_n/(R k), with it (17.7) quadratically"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from derivation_check import approximation_step, blocks, classify, problem  # noqa: E402

SIGMA = 1e-4  # Armijo's constant of the globalization (globalization.c)


def frame(n):
    """Rows t1, t2, n of a frame of the unit normal n"""
    a = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    t1 = np.cross(a, n)
    t1 /= np.linalg.norm(t1)
    return np.array([t1, np.cross(n, t1), n])


def step_blocks(v, c, phi, gamma):
    """The approximation step at (v, gamma c) in the nodes' frames and the blocks S, T of its states (sections 1-5)"""
    n = len(v)
    z, d, b = approximation_step(v, gamma * c, phi)
    tol_d, tol_b = 1e-13 * max(np.abs(v).max(), np.abs(d).max()), 1e-13 * max(np.abs(b).max(), 1e-300)
    S, T = np.zeros((n, n)), np.zeros((n, n))
    for i in range(n // 3):
        k = slice(3 * i, 3 * i + 3)
        _, _, S[k, k], T[k, k] = blocks(classify(d[k], b[k], phi, tol_d, tol_b), d[k], b[k], phi)
    return z, S, T


def solve(F, J, f, phi, u0, its=60, lag=1, damp=True, Q=None, offset=None):
    """Section 17's iteration from u0: c = F(u) (in the frames Q: v = Q u + o), the Newton matrix S gamma Q J Q^T + T
    with J at the iterate every lag iterations, damped on ||z||; returns the ||z|| of the iterates and the last u"""
    n = len(u0)
    Q = np.eye(n) if Q is None else Q
    o = np.zeros(n) if offset is None else offset
    gamma = 1 / np.mean(np.diag(J(u0)))
    u, history, Jk = u0.copy(), [], None
    for k in range(its):
        z, S, T = step_blocks(Q @ u + o, Q @ F(u), phi, gamma)
        history.append(np.linalg.norm(z))
        if history[-1] <= 1e-15 * max(np.linalg.norm(u), np.linalg.norm(gamma * f)):
            break
        if Jk is None or (lag > 0 and k % lag == 0):
            Jk = J(u)
        du = Q.T @ np.linalg.solve(S @ (gamma * Q @ Jk @ Q.T) + T, (S + T) @ z)
        alpha = 1.0
        while damp and alpha > 1 / 64:
            zt, _, _ = step_blocks(Q @ (u + alpha * du) + o, Q @ F(u + alpha * du), phi, gamma)
            if np.linalg.norm(zt) <= (1 - SIGMA * alpha + 0.5 ** (k + 1)) * history[-1]:
                break
            alpha /= 2
        u = u + alpha * du
    return history, u


def orders(history, floor):
    """log(z_k+1/z_k)/log(z_k/z_k-1) over the iterates above the round-off floor"""
    h = [x for x in history if x > floor]
    return [np.log(h[k + 1] / h[k]) / np.log(h[k] / h[k - 1]) for k in range(1, len(h) - 1)]


def check_cubic(p, seed, s, phi=0.3):
    P, f = problem(p, seed)
    _, ua = solve(lambda u: P @ u - f, lambda u: P, f, phi, np.zeros(3 * p), damp=False)
    kappa = s * np.abs(f).max() / np.abs(ua).max() ** 3
    F = lambda u: P @ u + kappa * u ** 3 - f  # noqa: E731
    J = lambda u: P + np.diag(3 * kappa * u ** 2)  # noqa: E731
    history, u = solve(F, J, f, phi, np.zeros(3 * p))
    gamma = 1 / np.mean(np.diag(P))
    z, d, b = approximation_step(u, gamma * F(u), phi)
    law = max(np.abs(z).max() / np.abs(u).max(), np.abs(F(u) + b / gamma + z / gamma).max() / np.abs(f).max())
    q = orders(history, 1e-13 * history[0])
    results = []
    ok1 = law < 1e-12 and q[-1] >= 1.8
    results.append((ok1, "(17.2)-(17.4) on F = P u + kappa u^3 - f: %d iterations, ||z|| %s; the law at the end %.1e; orders %s" % (
        len(history), ", ".join("%.1e" % x for x in history), law, ", ".join("%.2f" % x for x in q[-3:]))))
    off = np.abs(F(ua) - (P @ ua - f)).max() / np.abs(f).max()  # F against the model's c = P u - f at its solution
    ok2 = abs(off - s) < 1e-12 and np.abs(ua - u).max() > 1e-2 * np.abs(u).max()
    results.append((ok2, "the affine model's solution (its z = 0): F is off the model by kappa u^3 = %.3f of max|f| there, %.2g of max|u| from the answer" % (
        off, np.abs(ua - u).max() / np.abs(u).max())))
    chord, uc = solve(F, J, f, phi, np.zeros(3 * p), its=200, lag=0)
    tail = [x for x in chord if x > 1e-13 * chord[0]][-11:]
    rate = (tail[-1] / tail[0]) ** 0.1  # the mean contraction of its last ten steps
    ok3 = np.abs(uc - u).max() <= 1e-9 * np.abs(u).max() and len(chord) > 3 * len(history) and 0.02 < rate < 0.95
    results.append((ok3, "the chord iteration (the first Jacobian kept): %d iterations to the same point (%.1e), linear: mean rate %.2f over its last ten steps" % (
        len(chord), np.abs(uc - u).max() / np.abs(u).max(), rate)))
    return results


def check_ball(geometric, p=6, seed=5, R=2.0, press=0.3):
    """p nodes on the line y = 0 over a ball of radius R (centre (0, 0, -R)), springs P between them and a cubic one to
    their rest positions, pressed down by -f: the contact measured at each iterate (17.5); frictionless"""
    rng = np.random.default_rng(seed)
    X = np.array([[x, 0.0, 0.0] for x in np.linspace(-0.6, 0.6, p)])
    centre = np.array([0.0, 0.0, -R])
    A = rng.standard_normal((3 * p, 3 * p))
    P = A @ A.T / (3 * p) + 2 * np.eye(3 * p)
    f = np.tile([0.0, 0.0, -press], p)
    F = lambda u: P @ u + 0.5 * u ** 3 - f  # noqa: E731
    u, history = np.zeros(3 * p), []
    gamma = 1 / np.mean(np.diag(P))
    for k in range(40):
        x = X + u.reshape(p, 3) - centre
        dist = np.linalg.norm(x, axis=1)
        normals = x / dist[:, None]
        Q = np.zeros((3 * p, 3 * p))
        o = np.zeros(3 * p)
        for i in range(p):
            Q[3 * i:3 * i + 3, 3 * i:3 * i + 3] = frame(normals[i])
            o[3 * i:3 * i + 3] = -Q[3 * i:3 * i + 3, 3 * i:3 * i + 3] @ u[3 * i:3 * i + 3]  # v_t = 0 at the iterate
            o[3 * i + 2] = dist[i] - R - normals[i] @ u[3 * i:3 * i + 3]                       # v_n = the exact gap there
        v, c = Q @ u + o, Q @ F(u)
        z, S, T = step_blocks(v, c, 0.0, gamma)
        history.append(np.linalg.norm(z))
        if history[-1] <= 1e-15:
            break
        Jk = P + np.diag(1.5 * u ** 2)
        if geometric:  # (17.7): the force r_n n(u) turns with the normal
            for i in range(p):
                rn = normals[i] @ F(u)[3 * i:3 * i + 3]
                if rn > 0:
                    Jk[3 * i:3 * i + 3, 3 * i:3 * i + 3] -= rn * (np.eye(3) - np.outer(normals[i], normals[i])) / dist[i]
        u = u + Q.T @ np.linalg.solve(S @ (gamma * Q @ Jk @ Q.T) + T, (S + T) @ z)
    x = X + u.reshape(p, 3) - centre
    gap = np.linalg.norm(x, axis=1) - R
    r = F(u).reshape(p, 3)
    normals = x / np.linalg.norm(x, axis=1)[:, None]
    rn = np.einsum("ij,ij->i", r, normals)
    touching = gap <= 1e-9
    exact = max(np.abs(gap[touching]).max(), np.abs(r[touching] - rn[touching, None] * normals[touching]).max() / rn.max(),
                np.abs(r[~touching]).max() / rn.max() if (~touching).any() else 0.0, max(0.0, -gap.min()))
    q = orders(history, 1e-12 * history[0])
    tail = [x for x in history if x > 1e-13 * history[0]]
    rate = max(tail[k + 1] / tail[k] for k in range(len(tail) - 4, len(tail) - 1))
    bound = rn.max() / R / np.linalg.eigvalsh(P)[0]
    if geometric:
        ok = exact < 1e-12 and touching.sum() >= 2 and q[-1] >= 1.8
        text = "orders %s" % ", ".join("%.2f" % x for x in q[-3:])
    else:
        ok = exact < 1e-12 and touching.sum() >= 2 and rate <= bound and len(history) > 8
        text = "rate %.3f <= r_n/(R k_min) = %.3f" % (rate, bound)
    return ok, "a ball measured at the iterates%s: %d iterations, %d of %d nodes touching, exact gap and normal at the end %.1e; %s" % (
        ", the normal's turning in the Newton matrix (17.7)" if geometric else "", len(history), touching.sum(), p, exact, text)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--nodes", type=int, default=16)
    parser.add_argument("--seed", type=int, default=3)
    parser.add_argument("--stiffening", type=float, default=0.5)
    args = parser.parse_args()
    results = check_cubic(args.nodes, args.seed, args.stiffening)
    results.append(check_ball(False))
    results.append(check_ball(True))
    failed = 0
    for ok, text in results:
        failed += not ok
        print("%s %s" % ("PASS" if ok else "FAIL", text))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
