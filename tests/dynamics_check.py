#!/usr/bin/python3
"""docs/derivation.md section 16 (moving obstacles that turn; elastodynamics with contact and friction) checked in
numpy, independent of the C code:

  1. the placement (16.1): Q is a rotation, the inverse undoes it, the normal turns with the obstacle; a cylinder
     rolled without slip (d = R theta along the slab) moves the point it touches by O(dtheta^2) in a step (16.3): the
     node under it sees no slip to first order, where a cylinder dragged without turning moves it by R dtheta
  2. the energy identity (16.8) of the scheme (16.5)-(16.7) on a random body with three contact points against
     planes, Coulomb friction, Rayleigh damping and a load, 60 steps: E^(n+1) - E^n = W - D_friction - D_damping -
     D_impact to round-off at every step, with D_friction, D_impact >= 0 (no energy gained at contact) and the
     projection's loss >= 0
  3. a rod on a rigid wall (a chain of 40 P1 elements, consistent mass, nu = 0): the stabilized scheme keeps contact
     for 2 L / c, its force is the plateau E A v0 / c, the rod leaves at -v0 within the stated impact dissipation and
     its energy never rises above the initial; the trapezoidal step without the projection (newmark) chatters (the
     force oscillates by more than 30 % about the plateau); classical Newmark, whose stored acceleration carries the
     contact force of the step before, gains energy at the release
  4. a rigid block on a slope (one contact point, the mass m): phi < tan(alpha) slides with the acceleration
     g (sin(alpha) - phi cos(alpha)) at every step, to round-off; phi > tan(alpha) stays, u = 0
Prints PASS/FAIL per check; exit status 0 when all pass.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from loadpath_check import incremental_dual, report  # noqa: E402  (the incremental law solved on the dual)


# ---------------------------------------------------------------------------------------------------------------------
# 1. the placement of a moving obstacle (16.1)-(16.3)
# ---------------------------------------------------------------------------------------------------------------------

def rotation(axis, angle):
    """Rodrigues: the rotation by angle about the axis (its direction)"""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    A = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.cos(angle) * np.eye(3) + np.sin(angle) * A + (1 - np.cos(angle)) * np.outer(a, a)


def place(Q, c, d, X):
    return Q @ (X - c) + c + d


def unplace(Q, c, d, x):
    return Q.T @ (x - c - d) + c


def check_placement():
    rng = np.random.default_rng(3)
    Q, c, d = rotation(rng.standard_normal(3), 0.7), rng.standard_normal(3), rng.standard_normal(3)
    X = rng.standard_normal(3)
    orthonormal = np.abs(Q.T @ Q - np.eye(3)).max()
    inverse = np.abs(unplace(Q, c, d, place(Q, c, d, X)) - X).max()
    # a cylinder of radius R along y through (0, 0, R) touching z = 0: the node under it at the origin; after the
    # placement (theta, d) the point it faces is the obstacle's point at x - gap n, its motion in the next step
    R, ratios, drag = 1.0, [], []
    for dtheta in (1e-2, 1e-3, 1e-4):
        c0 = np.array([0.0, 0.0, R])
        for roll in (True, False):
            Q0, d0 = rotation([0, 1, 0], 0.3 if roll else 0.0), np.array([0.3 * R, 0, 0])
            Q1, d1 = rotation([0, 1, 0], (0.3 + dtheta) if roll else 0.0), d0 + np.array([R * dtheta, 0, 0])
            x = np.array([0.3 * R, 0.0, 0.0])                     # the node under the cylinder's axis
            axis_at = place(Q0, c0, d0, c0)
            n = (x - axis_at) / np.linalg.norm(x - axis_at)       # the cylinder's normal at x
            gap = np.linalg.norm(x - axis_at) - R
            Y = unplace(Q0, c0, d0, x - gap * n)                  # the obstacle's point the node faces
            move = place(Q1, c0, d1, Y) - place(Q0, c0, d0, Y)    # its displacement in the step (16.3)
            (ratios if roll else drag).append(np.linalg.norm(move) / (R * dtheta))
    ok = orthonormal < 1e-15 and inverse < 1e-14 and ratios[-1] < 1e-3 and abs(ratios[0] / ratios[1] - 10) < 0.5 and abs(drag[-1] - 1) < 1e-12
    return ok, "Q^T Q - I %.1e, inverse %.1e; rolled: |dd|/(R dtheta) = %s (first order in dtheta), dragged: %.6f" % (
        orthonormal, inverse, ", ".join("%.2e" % r for r in ratios), drag[-1])


# ---------------------------------------------------------------------------------------------------------------------
# the scheme (16.5)-(16.7), one step, on the incremental law of loadpath_check (the dual, Tresca fixed points)
# ---------------------------------------------------------------------------------------------------------------------

def frames_of(normals):
    R = []
    for n in normals:
        a = np.array([1.0, 0, 0]) if abs(n[0]) < 0.9 else np.array([0, 1.0, 0])
        t1 = np.cross(a, n)
        t1 /= np.linalg.norm(t1)
        R.append(np.array([t1, np.cross(n, t1), n]))
    return R


class Body:
    """M u'' + C u' + K u = f + B^T lambda: contact points (node dofs, frames) against planes at rest, gaps g"""

    def __init__(self, K, M, nodes, normals, gaps, laws, alpha=0.0, beta=0.0):
        n = K.shape[0]
        self.K, self.M, self.alpha, self.beta, self.laws = K, M, alpha, beta, laws
        self.B = np.zeros((3 * len(nodes), n))
        for i, (node, R) in enumerate(zip(nodes, frames_of(normals))):
            self.B[3 * i:3 * i + 3, 3 * node:3 * node + 3] = R
        self.g = np.zeros(3 * len(nodes))
        self.g[2::3] = gaps

    def step(self, u, v, wt, f0, f1, tau, project=True):
        """One step (16.5)-(16.7) from (u, v) with the slip wt after the step before; returns the new state and what
        the balance (16.8) is made of"""
        K, M, B = self.K, self.M, self.B
        C = self.alpha * M + self.beta * K
        p = u + tau * v
        if project and (B @ p + self.g)[2::3].min() < 0:  # (16.5): frictionless, in the norm of M
            p = incremental_dual(M, M @ p, B, self.g, np.zeros((len(self.laws), 2)), [("none", 0.0)] * len(self.laws), np.zeros(len(self.g)))[0]
        vt = (p - u) / tau
        A = 0.5 * K + C / tau + 2 * M / tau ** 2
        b = M @ (2 * p / tau ** 2) + C @ u / tau - 0.5 * K @ u + 0.5 * (f0 + f1)
        u1, w, lam = incremental_dual(A, b, B, self.g, wt.reshape(-1, 2), self.laws, np.zeros(len(self.g)))
        v1 = 2 * (u1 - u) / tau - vt
        du, r = u1 - u, B.T @ lam
        wt1 = w.reshape(-1, 3)[:, :2].ravel()
        parts = {"work": 0.5 * (f0 + f1) @ du, "contact": r @ du, "damping": du @ C @ du / tau,
                 "projection": 0.5 * v @ M @ v - 0.5 * vt @ M @ vt,
                 "friction": -sum(lam[3 * i:3 * i + 2] @ (wt1[2 * i:2 * i + 2] - wt[2 * i:2 * i + 2]) for i in range(len(self.laws)))}
        parts["impact"] = parts["projection"] - parts["contact"] - parts["friction"]  # (16.8): fixed obstacles
        return u1, v1, wt1, lam, parts

    def energy(self, u, v):
        return 0.5 * v @ self.M @ v + 0.5 * u @ self.K @ u


def check_energy_identity():
    rng = np.random.default_rng(11)
    n = 8  # nodes: 24 dofs
    G = rng.standard_normal((3 * n, 3 * n))
    K = G @ G.T / n + 0.5 * np.eye(3 * n)
    H = rng.standard_normal((3 * n, 3 * n))
    M = 0.05 * (H @ H.T / n + np.eye(3 * n))
    normals = [np.array([0.1, 0.0, 1.0]) / np.hypot(0.1, 1.0), np.array([0.0, 0.0, 1.0]), np.array([-0.2, 0.1, 1.0]) / np.linalg.norm([-0.2, 0.1, 1.0])]
    body = Body(K, M, [0, 3, 5], normals, [0.0, 0.01, 0.02], [("coulomb", 0.3), ("coulomb", 0.5), ("coulomb", 0.2)], alpha=0.05, beta=0.01)
    u, v, wt = np.zeros(3 * n), np.zeros(3 * n), np.zeros(6)
    v[2::3] = -0.5  # towards the planes
    f = np.zeros(3 * n)
    f[0::3], f[2::3] = 0.3, -0.4
    worst, gained, negative = 0.0, 0.0, 0.0
    for k in range(60):
        E0 = body.energy(u, v)
        u, v, wt, lam, parts = body.step(u, v, wt, f, f, 0.02)
        E1 = body.energy(u, v)
        residual = E1 - E0 - (parts["work"] - parts["friction"] - parts["damping"] - parts["impact"])
        worst = max(worst, abs(residual) / max(E0, E1))
        gained = min(gained, parts["impact"] / max(E0, E1))
        negative = min(negative, parts["friction"] / max(E0, E1), parts["projection"] / max(E0, E1))
    ok = worst < 1e-10 and gained > -1e-10 and negative > -1e-10
    return ok, "balance residual %.1e of the energy, least impact dissipation %.1e, least friction/projection loss %.1e (60 steps)" % (worst, gained, negative)


# ---------------------------------------------------------------------------------------------------------------------
# 3. a rod on a rigid wall: 1D waves (the longitudinal motion of the scenes' rod, nu = 0)
# ---------------------------------------------------------------------------------------------------------------------

def rod(nel=40, L=1.0, EA=1.0, rhoA=1.0):
    h = L / nel
    n = nel + 1
    K, M = np.zeros((n, n)), np.zeros((n, n))
    for e in range(nel):
        K[e:e + 2, e:e + 2] += EA / h * np.array([[1, -1], [-1, 1]])
        M[e:e + 2, e:e + 2] += rhoA * h / 6 * np.array([[2, 1], [1, 2]])
    return K, M


def rod_impact(scheme, nel=40, steps=120, T=3.0, v0=0.01):
    """The rod (E = A = rho = L = 1, c = 1) at rest on the wall z = 0 with the velocity -v0: returns times, the wall's
    force, the energy and the final mean velocity. scheme: stabilized, newmark (16.6) without (16.5), classical
    (Newmark's trapezoidal rule with the contact force in the stored acceleration)"""
    K, M = rod(nel)
    n = K.shape[0]
    tau = T / steps
    u, v = np.zeros(n), -v0 * np.ones(n)
    a = np.zeros(n)  # classical: the acceleration of the state, with its contact force
    times, forces, energies = [], [], []
    for k in range(steps):
        if scheme == "classical":
            A = K + 4 * M / tau ** 2
            b = M @ (4 * u / tau ** 2 + 4 * v / tau + a)
            x = np.linalg.solve(A, b)
            lam = 0.0
            if x[0] < 0:  # the tip on the wall: its force lam from A x = b + lam e0 with x0 = 0
                Ai = np.linalg.inv(A)
                lam = -(Ai @ b)[0] / Ai[0, 0]
                x = Ai @ (b + lam * np.eye(n)[0])
            a1 = 4 * (x - u) / tau ** 2 - 4 * v / tau - a
            v = v + tau / 2 * (a + a1)
            u, a, force = x, a1, lam
        else:
            p = u + tau * v
            if scheme == "stabilized" and p[0] < 0:  # (16.5): M-projection onto p0 >= 0
                Mi = np.linalg.inv(M)
                p = p + Mi[:, 0] * (-p[0] / Mi[0, 0])
            vt = (p - u) / tau
            A = 0.5 * K + 2 * M / tau ** 2
            b = 2 * M @ p / tau ** 2 - 0.5 * K @ u
            x = np.linalg.solve(A, b)
            force = 0.0
            if x[0] < 0:
                Ai = np.linalg.inv(A)
                force = -(Ai @ b)[0] / Ai[0, 0]
                x = Ai @ (b + force * np.eye(n)[0])
            v = 2 * (x - u) / tau - vt
            u = x
        times.append((k + 1) * tau)
        forces.append(force)
        energies.append(0.5 * v @ M @ v + 0.5 * u @ K @ u)
    mean_v = np.ones(n) @ M @ v / (np.ones(n) @ M @ np.ones(n))
    return np.array(times), np.array(forces), np.array(energies), mean_v


def check_rod():
    v0, E0 = 0.01, 0.5 * 0.01 ** 2  # m v0^2 / 2 with m = 1
    t, F, E, vm = rod_impact("stabilized")
    touching = t[F > 0]
    plateau = F[(t > 0.5) & (t < 1.5)] / v0  # E A v0 / c = v0
    _, Fn, En, _ = rod_impact("newmark")
    chatter = np.abs(Fn[(t > 0.5) & (t < 1.5)] / v0 - 1).max()
    _, Fc, Ec, _ = rod_impact("classical")
    ok = (abs(touching[-1] - 2.0) <= 0.05 and abs(plateau.mean() - 1) < 1e-3 and np.abs(plateau - 1).max() < 0.02 and
          E.max() <= E0 * (1 + 1e-12) and 0.95 < vm / v0 < 1.0 and chatter > 0.3 and Ec.max() > E0 * 1.001)
    return ok, ("stabilized: contact until t = %.3f (2L/c = 2), plateau %.6f E A v0/c (within %.1e), leaving at %.4f v0, "
                "max energy %.6f E0; newmark: force off the plateau by %.0f %%; classical Newmark: max energy %.4f E0" % (
                    touching[-1], plateau.mean(), np.abs(plateau - 1).max(), vm / v0, E.max() / E0, 100 * chatter, Ec.max() / E0))


# ---------------------------------------------------------------------------------------------------------------------
# 4. a rigid block on a slope: one contact point of mass m
# ---------------------------------------------------------------------------------------------------------------------

def check_slope():
    alpha, g, m, tau = np.radians(20), 9.81, 2.0, 0.01
    normal = np.array([np.sin(alpha), 0.0, np.cos(alpha)])
    down = np.array([np.cos(alpha), 0.0, -np.sin(alpha)])
    out = []
    for phi in (0.3, 0.5):
        body = Body(np.zeros((3, 3)), m * np.eye(3), [0], [normal], [0.0], [("coulomb", phi)])
        u, v, wt = np.zeros(3), np.zeros(3), np.zeros(2)
        f = m * np.array([0, 0, -g])
        travel = []
        for k in range(50):
            u, v, wt, lam, parts = body.step(u, v, wt, f, f, tau)
            travel.append(u @ down)
        tk = tau * np.arange(1, 51)
        exact = max(g * (np.sin(alpha) - phi * np.cos(alpha)), 0) * tk ** 2 / 2
        out.append(np.abs(np.array(travel) - exact).max())
    ok = out[0] < 1e-12 and out[1] < 1e-12
    return ok, "phi 0.3: travel - g (sin a - phi cos a) t^2/2 = %.1e; phi 0.5: |u| = %.1e" % tuple(out)


def main():
    ok = True
    for name, check in (("placement", check_placement), ("energy identity (16.8)", check_energy_identity),
                        ("rod on a wall", check_rod), ("block on a slope", check_slope)):
        good, figures = check()
        report(name, good, figures)
        ok &= good
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
