#!/usr/bin/python3
"""Re-does the checks of docs/derivation.md section 14 (bodies held by contact alone) in numpy, independently of the
C code.

  tests/floating_check.py [--seed 5]

Checks (exit status 1 if one fails):
  1. the Schur complement of a semidefinite K (14.2)-(14.3): K_II regular, P symmetric positive semidefinite with
     ker P = R_C, R_C^T f = R^T b, R_C^T (P u - f) = -R^T b for every u, and FETI's form P = (Pi F Pi)^+,
     f = P (d + F lambda_0) - lambda_0 (F = E_C K^+ E_C^T, d = E_C K^+ b) to 1e-10
  2. the balance (14.4): a rigid block on a slope of 20 degrees, its bottom a grid of contact points: balanced
     (residual 0) for phi = 0.5 > tan 20 deg; for phi = 0.3 and 0 the least unbalanced part is sin(alpha - arctan phi)
     of the load's, and the residual r is the certificate: Rc r in the dual cones, g . r = |r|^2
  3. the proximal Newton step (14.5) and the least-norm solution (14.6) on a semidefinite P whose kernel holds a
     motion no contact point resists (zero normal components) and one the normals hold: frictionless (the plain
     Newton matrix singular at every iterate, the proximal one not; also from gaps of 3, every point separated at
     first, the body reaching its first contact in one step) and Coulomb phi = 0.4 (no free motion), it converges
     (||z|| <= 1e-13) superlinearly, the free motion's part of u stays zero from u = 0, and the answer is the limit of
     the regular problems P + eps I as eps -> 0 (the differences shrink in proportion to eps)"""
import argparse
import math
import sys

import numpy as np

from derivation_check import approximation_step, blocks, classify

FREE_TOL = 1e-8  # as floating.c
BETA = 1.0       # the proximal stiffness in units of 1/gamma (newtonimpl.h, SSSTAR_FREE_STIFFNESS)


def orthonormal(A):
    q, _ = np.linalg.qr(A)
    return q


def semidefinite_stiffness(rng, n, R):
    """An SPSD K (n x n) with kernel exactly span(R) (orthonormal columns)"""
    Q = orthonormal(np.c_[R, rng.standard_normal((n, n - R.shape[1]))])[:, R.shape[1]:]
    lam = rng.uniform(0.5, 3.0, n - R.shape[1])
    return Q @ np.diag(lam) @ Q.T


def schur(K, b, C):
    I = np.setdiff1d(np.arange(len(b)), C)
    KII = K[np.ix_(I, I)]
    X = np.linalg.solve(KII, K[np.ix_(I, C)])
    P = K[np.ix_(C, C)] - K[np.ix_(C, I)] @ X
    f = b[C] - K[np.ix_(C, I)] @ np.linalg.solve(KII, b[I])
    return P, f, np.linalg.cond(KII)


def check_schur(rng):
    n, p, m = 72, 12, 6
    R = orthonormal(rng.standard_normal((n, m)))
    K = semidefinite_stiffness(rng, n, R)
    b = rng.standard_normal(n)
    C = np.arange(3 * p)
    P, f, cond = schur(K, b, C)
    RC = R[C]
    ev = np.linalg.eigvalsh(P)
    ok = cond < 1e8 and ev[0] >= -1e-12 * ev[-1] and (ev[:m] <= 1e-12 * ev[-1]).all() and ev[m] > 1e-6 * ev[-1]
    ok &= np.abs(P @ RC).max() <= 1e-12 * np.abs(P).max()
    ok &= np.abs(RC.T @ f - R.T @ b).max() <= 1e-12 * np.abs(b).max()
    u = rng.standard_normal(3 * p)
    ok &= np.abs(RC.T @ (P @ u - f) + R.T @ b).max() <= 1e-11 * np.abs(b).max()
    Kp = np.linalg.pinv(K)
    F, d = Kp[np.ix_(C, C)], Kp[C] @ b
    Pi = np.eye(3 * p) - RC @ np.linalg.solve(RC.T @ RC, RC.T)
    feti = np.linalg.pinv(Pi @ F @ Pi)
    lam0 = -RC @ np.linalg.solve(RC.T @ RC, R.T @ b)
    e1 = np.abs(feti - P).max() / np.abs(P).max()
    e2 = np.abs(P @ (d + F @ lam0) - lam0 - f).max() / np.abs(f).max()
    ok &= e1 <= 1e-10 and e2 <= 1e-10
    print("%s 1. Schur complement of a semidefinite K (%d dofs, kernel %d, %d contact dofs): cond K_II %.1e, ker P = R_C "
          "(eigenvalues %.1e .. %.1e, then %.2e), P = (Pi F Pi)^+ to %.1e, f = P (d + F l0) - l0 to %.1e"
          % ("PASS" if ok else "FAIL", n, m, 3 * p, cond, ev[0], ev[m - 1], ev[m], e1, e2))
    return ok


def project_cone(s, x):
    t, nrm = np.linalg.norm(x[:2]), x[2]
    if s == 0:
        return np.array([0.0, 0.0, max(nrm, 0.0)])
    if t <= s * nrm:
        return x.copy()
    if s * t <= -nrm:
        return np.zeros(3)
    a = (s * t + nrm) / (1 + s * s)
    return np.array([x[0] * s * a / t, x[1] * s * a / t, a])


def balance(Rc, g, s, its=200000):
    """min over mu in the cones of 1/2 |g + Rc^T mu|^2 by projected gradients with momentum (FISTA, restarts);
    returns the residual r"""
    npts = Rc.shape[0] // 3
    L = np.linalg.eigvalsh(Rc.T @ Rc)[-1]
    mu = np.zeros(3 * npts)
    y, t = mu.copy(), 1.0
    for _ in range(its):
        grad = Rc @ (g + Rc.T @ y)
        xn = np.concatenate([project_cone(s, (y - grad / L)[3 * i:3 * i + 3]) for i in range(npts)])
        restart = (y - xn) @ (xn - mu) > 0
        tn = 1.0 if restart else 0.5 * (1 + math.sqrt(1 + 4 * t * t))
        y = xn + (0.0 if restart else (t - 1) / tn) * (xn - mu)
        mu, t = xn, tn
    return g + Rc.T @ mu


def check_balance():
    alpha = math.radians(20)
    n = np.array([math.sin(alpha), 0, math.cos(alpha)])
    t1 = np.array([math.cos(alpha), 0, -math.sin(alpha)])  # downhill
    t2 = np.cross(n, t1)
    frame = np.array([t1, t2, n])
    # the block 2 x 1 x 0.5 in the slope's axes: its nodes on a grid, the bottom's nodes the contact points
    grid = [(x, y, z) for x in np.linspace(0, 2, 5) for y in np.linspace(0, 1, 3) for z in (0.0, 0.5)]
    X = np.array([a * t1 + b * t2 + c * n for a, b, c in grid])
    contact = [k for k, (_, _, c) in enumerate(grid) if c == 0]
    xc = X.mean(0)
    modes = []
    for k in range(3):
        e = np.zeros(3)
        e[k] = 1
        modes.append(np.tile(e, len(X)))
        modes.append(np.cross(e, X - xc).ravel())
    R = orthonormal(np.array(modes).T)
    b = np.tile([0, 0, -1.0], len(X))  # gravity, equal masses
    g = R.T @ b
    Rc = np.concatenate([frame @ R[3 * k:3 * k + 3] for k in contact])
    ok, lines = True, []
    for phi in (0.5, 0.3, 0.0):
        r = balance(Rc, g, phi, its=20000)
        if phi > math.tan(alpha):
            good = np.linalg.norm(r) <= 1e-10 * np.linalg.norm(g)
            lines.append("phi %.1f: residual %.1e" % (phi, np.linalg.norm(r) / np.linalg.norm(g)))
        else:
            w = (Rc @ r).reshape(-1, 3)
            viol = np.maximum(0, phi * np.linalg.norm(w[:, :2], axis=1) - w[:, 2]).max() / np.abs(w).max()
            part, expected = np.linalg.norm(r) / np.linalg.norm(g), math.sin(alpha - math.atan(phi))
            good = abs(part / expected - 1) <= 1e-6 and viol <= 1e-8 and abs(g @ r / (r @ r) - 1) <= 1e-8
            lines.append("phi %.1f: unbalanced %.6f (sin(alpha - arctan phi) %.6f), dual violation %.1e" % (phi, part, expected, viol))
        ok &= good
    print("%s 2. the balance of a rigid block on a slope of 20 deg: %s" % ("PASS" if ok else "FAIL", "; ".join(lines)))
    return ok


def free_motions(Rc, G, S, T):
    """(14.5): the eigenvectors of G_T y = lambda G y with lambda <= FREE_TOL, G_T = sum Rc_i^T sym(T_i) Rc_i; U = Rc Y
    with the known rows zeroed"""
    Ts = 0.5 * (T + T.T)
    GT = Rc.T @ Ts @ Rc
    Lc = np.linalg.cholesky(G)
    w, V = np.linalg.eigh(np.linalg.solve(Lc, np.linalg.solve(Lc, GT).T))
    Y = np.linalg.solve(Lc.T, V[:, w <= FREE_TOL])
    U = Rc @ Y
    known = np.array([(S[k] == 0).all() and T[k, k] == 1 and np.count_nonzero(T[k]) == 1 for k in range(len(T))])
    U[known] = 0
    return U


def extend_free(U, du, v, states):
    """(14.5): the free part of the step (U U^T du) carried on as far as the model holds for the separated points: to
    the first whose gap it closes (c does not change along a rigid motion); the extra displacement"""
    free = U @ (U.T @ du)
    vp, first = v + du, np.inf
    for i, state in enumerate(states):
        if state == "L" and free[3 * i + 2] < 0 and vp[3 * i + 2] > 0:
            first = min(first, vp[3 * i + 2] / -free[3 * i + 2])
    return free * (first if np.isfinite(first) else 0.0)


def newton(P, f, gap, phi, Rc=None, its=40):
    """Section 7 with gamma = 1/mean diag P from u = 0, and the proximal term on the free motions when Rc is given;
    returns u, the ||z|| history and the smallest 1/cond of the plain Newton matrices"""
    n, gamma = len(f), 1 / np.mean(np.diag(P))
    u, hist, rcond = np.zeros(n), [], 1.0
    newton.proximal = 0  # steps that had free motions
    G = Rc.T @ Rc if Rc is not None else None
    for _ in range(its):
        c = gamma * (P @ u - f)
        v = u + np.tile([0, 0, 1.0], n // 3) * np.repeat(gap, 3)
        z, d, b = approximation_step(v, c, phi)
        hist.append(np.linalg.norm(z))
        if hist[-1] <= 1e-13 * max(np.linalg.norm(u), np.linalg.norm(gamma * f)):
            break
        tol_d, tol_b = 1e-13 * max(np.abs(v).max(), np.abs(d).max()), 1e-13 * max(np.abs(gamma * f).max(), np.abs(b).max())
        S, T, states = np.zeros((n, n)), np.zeros((n, n)), []
        for i in range(n // 3):
            k3 = slice(3 * i, 3 * i + 3)
            state = classify(d[k3], b[k3], phi, tol_d, tol_b)
            states.append(state)
            if phi == 0 and state in ("M3+", "M3-"):
                state = "M1"  # frictionless in strong contact: the sliding blocks with phi = 0 (section 3)
            if state == "M1" and np.linalg.norm(d[k3][:2]) == 0:
                S[k3, k3], T[k3, k3] = np.diag([1.0, 1, 0]), np.diag([0, 0, 1.0])
            else:
                _, _, S[k3, k3], T[k3, k3] = blocks(state, d[k3], b[k3], phi)
        A = S @ (gamma * P) + T
        rcond = min(rcond, 1 / np.linalg.cond(A))
        if Rc is not None:
            U = free_motions(Rc, G, S, T)
            A = A + BETA * S @ U @ U.T
            newton.proximal += U.shape[1] > 0
        du = np.linalg.solve(A, (S + T) @ z)
        if Rc is not None and U.shape[1]:
            du += extend_free(U, du, v, states)
        u = u + du
    return u, hist, rcond


def check_proximal(rng):
    p, m = 10, 2
    nC = 3 * p
    n = nC + 30
    # the kernel: motion 1 moves every contact point along t1 only (no contact point resists it frictionless), motion 2
    # moves them normally (the normals hold it); the interior dofs at random
    R = np.zeros((n, m))
    R[0:nC:3, 0] = 1
    R[2:nC:3, 1] = rng.uniform(0.5, 1.5, p) * np.where(np.arange(p) % 2, 1, -1)
    R[nC:] = rng.standard_normal((n - nC, m))
    R = orthonormal(R)
    K = semidefinite_stiffness(rng, n, R)
    b = rng.standard_normal(n)
    b[:nC:3] += 0.3 * rng.standard_normal(p)
    b[2:nC:3] = -1.0 - rng.uniform(0, 1, p)  # pressing every point onto its plane
    b -= R[:, 0] * (R[:, 0] @ b)          # no load along the free motion: an equilibrium exists
    C = np.arange(nC)
    P, f, _ = schur(K, b, C)
    gap = np.where(np.arange(p) % 3 == 0, 0.05, 0.0)
    Rc = R[C]
    ok, lines = True, []
    for phi, gaps in ((0.0, gap), (0.4, gap), (0.0, gap + 3.0)):
        u, hist, rcond = newton(P, f, gaps, phi, Rc)
        proximal = newton.proximal
        conv = hist[-1] <= 1e-13 * np.linalg.norm(u) and len(hist) <= 15 and hist[-1] <= 1e-3 * hist[-2]
        free = abs(Rc[:, 0] @ u) / np.linalg.norm(u) if phi == 0 else 0.0
        diffs = []
        for eps in (1e-4, 1e-6):
            ue, _, _ = newton(P + eps * np.eye(nC), f, gaps, phi)
            diffs.append(np.abs(ue - u).max() / np.abs(u).max())
        good = conv and (rcond <= 1e-14) == (proximal > 0) and (proximal > 0 or phi > 0) and free <= 1e-12 and diffs[1] <= 1e-5 and 50 <= diffs[0] / max(diffs[1], 1e-300) <= 200
        ok &= good
        lines.append("phi %.1f, gaps up to %g: %d iterations, %d with free motions (||z|| %s), plain 1/cond %.1e, free part %.1e, "
                     "P + eps I differs by %.1e, %.1e" % (phi, gaps.max(), len(hist) - 1, proximal, " ".join("%.1e" % h for h in hist[-3:]), rcond, free, diffs[0], diffs[1]))
    print("%s 3. the proximal Newton step on a semidefinite P (a free and a held motion): %s" % ("PASS" if ok else "FAIL", "; ".join(lines)))
    return ok


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seed", type=int, default=5)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    results = [check_schur(rng), check_balance(), check_proximal(rng)]
    sys.exit(0 if all(results) else 1)


if __name__ == "__main__":
    main()
