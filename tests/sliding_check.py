#!/usr/bin/python3
"""docs/derivation.md section 13 (large sliding) checked in numpy, independent of the C code:

  1. small sliding's limit: the first-order gap g - n.d of a ball of radius R moved by d along its tangent at a node on
     it errs by |d|^2/(2R) to leading order, and R = 2 pressed 0.02 and moved 1 errs by 0.24 at the node under it
  2. the offsets (13.4) give the step's kinematics (13.1)-(13.3): v_n = g_a + n_a.(u - a), v_t = R_t(u - u0 - dd);
     a common translation of the body and the obstacle changes neither the exact gap nor the slip increment
  3. the linearization updated at the solution (13.5): a node on springs pressed onto a ball that moves sideways in one
     step, linearized at the step's start and then at each solution, converges to the solution of the exact gap (its
     KKT conditions), linearly at the rate of the neglected geometric stiffness, about kappa lambda / k (the ball's
     curvature times the contact force over the springs' stiffness)
Prints PASS/FAIL per check; exit status 0 when all pass.
"""
import sys

import numpy as np


def ball_gap(x, c, R):
    """Signed distance of x to the ball (centre c, radius R) and the unit normal out of it"""
    r = x - c
    return np.linalg.norm(r) - R, r / np.linalg.norm(r)


def frame(n):
    """Rows t1, t2, n (any orthonormal completion)"""
    a = np.array([1.0, 0, 0]) if abs(n[0]) < 0.9 else np.array([0, 1.0, 0])
    t1 = np.cross(a, n)
    t1 /= np.linalg.norm(t1)
    return np.array([t1, np.cross(n, t1), n])


def check_small_sliding():
    R, c = 2.0, np.array([0.0, 0.0, 2.0])
    x = np.array([0.3, 0.1, 0.0])
    x = c + R * (x - c) / np.linalg.norm(x - c)  # a node on the ball
    g, n = ball_gap(x, c, R)
    t = frame(n)[0]
    ratios = []
    for s in (1e-2, 1e-3, 1e-4):
        d = s * t
        exact = ball_gap(x - d, c, R)[0]
        ratios.append((exact - (g - n @ d)) / (s * s / (2 * R)))
    node = np.array([0.0, 0.0, 0.0])  # under the ball pressed 0.02 and moved 1
    g0, n0 = ball_gap(node, c, R)
    d = np.array([1.0, 0.0, -0.02])
    error = ball_gap(node - d, c, R)[0] - (g0 - n0 @ d)
    ok = abs(ratios[-1] - 1) < 1e-3 and abs(error - 0.2382) < 1e-3
    return ok, "error / (|d|^2 / 2R) = %s; R = 2 pressed 0.02 moved 1: %.4f" % (", ".join("%.6f" % r for r in ratios), error)


def check_offsets():
    rng = np.random.default_rng(7)
    R, c = 1.5, np.array([0.2, -0.1, 1.4])
    X = np.array([0.1, 0.05, 0.0])
    u0 = rng.normal(scale=1e-2, size=3)           # the accepted solution of step k-1
    d0, d1 = np.array([0.05, 0, -0.01]), np.array([0.15, 0.02, -0.01])
    a = u0 + rng.normal(scale=1e-3, size=3)        # the configuration linearized at
    ga, na = ball_gap(X + a - d1, c, R)
    Ra = frame(na)
    o_n = ga - na @ a                              # (13.4), a node against an obstacle (B = R_a)
    o_t = -Ra[:2] @ u0 - Ra[:2] @ (d1 - d0)
    u = a + rng.normal(scale=1e-3, size=3)
    v = Ra @ u + np.r_[o_t, o_n]
    err = max(abs(v[2] - (ga + na @ (u - a))), np.abs(v[:2] - Ra[:2] @ (u - u0 - (d1 - d0))).max())
    shift = np.array([0.7, -0.3, 0.0])             # body and obstacle translated together
    g1 = ball_gap(X + u0 + shift - (d0 + shift), c, R)[0] - ball_gap(X + u0 - d0, c, R)[0]
    slip = Ra[:2] @ ((u0 + shift) - u0 - ((d0 + shift) - d0))
    ok = err < 1e-15 and abs(g1) < 1e-15 and np.abs(slip).max() < 1e-15
    return ok, "offsets against (13.1)-(13.3): %.1e; common translation: gap change %.1e, slip %.1e" % (err, abs(g1), np.abs(slip).max())


def solve_linearized(K, f, a, ga, na):
    """min 1/2 u.K u - f.u subject to ga + na.(u - a) >= 0 (one linear constraint, frictionless)"""
    u = np.linalg.solve(K, f)
    if ga + na @ (u - a) >= 0:
        return u
    Kn = np.linalg.solve(K, na)
    lam = -(ga + na @ (u - a)) / (na @ Kn)
    return u + lam * Kn


def check_geometric_newton():
    K = np.array([[40.0, 5, 0], [5, 30, 2], [0, 2, 100]])  # the node's springs
    f = np.array([3.0, 0.0, 0.5])                           # pushed along x, pulled up a little
    R, c = 1.0, np.array([0.0, 0.0, 1.0])                   # the ball above the node's rest position X = 0
    X = np.zeros(3)
    d = np.array([0.3, 0.0, -0.05])                         # pressed 0.05 and moved 0.3 in one step
    a = np.zeros(3)
    errors, iterates = [], []
    for _ in range(10):
        ga, na = ball_gap(X + a - d, c, R)
        u = solve_linearized(K, f, a, ga, na)
        iterates.append(u)
        errors.append(abs(ball_gap(X + u - d, c, R)[0]))  # the exact gap of the (touching) node at the solution
        a = u
    u = iterates[-1]
    g, n = ball_gap(X + u - d, c, R)
    lam = n @ (K @ u - f)                                   # the exact problem's KKT: K u - f = lam n, lam >= 0, g = 0
    kkt = np.linalg.norm(K @ u - f - lam * n) / np.linalg.norm(f)
    rates = [errors[j + 1] / errors[j] for j in range(1, 5)]
    bound = lam / R / np.linalg.eigvalsh(K)[0]  # kappa lambda / k_min
    ok = errors[6] < 1e-13 and kkt < 1e-10 and lam > 0 and all(r <= bound for r in rates)
    return ok, "exact gap after each linearization: %s; KKT of the exact problem %.1e, force %.3f; rates %s <= kappa lambda / k = %.3f" % (
        ", ".join("%.1e" % e for e in errors[:7]), kkt, lam, ", ".join("%.4f" % r for r in rates), bound)


def main():
    failed = 0
    for name, check in (("small sliding's first-order gap", check_small_sliding), ("offsets (13.4)", check_offsets),
                        ("the geometry updated at the solution (13.5)", check_geometric_newton)):
        ok, text = check()
        failed += not ok
        print("%s %s: %s" % ("PASS" if ok else "FAIL", name, text))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
