#!/usr/bin/python3
"""Numerical checks of docs/derivation.md section 15 (prescribed displacements, reactions, stresses), in numpy and
independent of the C code; tests/suite_displacement.py runs it. Prints PASS or FAIL per check.

  15.1  the identity rows: K' u = b' gives u_D = g and K_FF u_F = b_F - K_FD g; the reaction (K u - b)_D is the
        multiplier of the constraint u_D = g (the saddle-point system) to 1e-12
  15.2  the Schur complement of K' on contact dofs C (no prescribed one) and its load are those of K_FF and the
        lifted load b_F - K_FD g
  15.3  ker K' of a P1 cube whose top is held in z alone: the rigid motions whose prescribed components vanish
        (the null space of their Gram matrix), three: the translations in x, y and the turn about z
  15.4  a contact node with a component prescribed as on a plane of symmetry (x, value 0, normal z, Coulomb): the
        problem with the identity row has u_x = 0 and no contact force along x at its solution (reached from random
        starts), for random loads, stiffnesses, gaps and slips along the plane
  15.5  the P1 strain of a linear field is exact; von Mises = sqrt(((s1 - s2)^2 + (s2 - s3)^2 + (s3 - s1)^2)/2) of
        the principal stresses; the volume-weighted nodal recovery of a uniform stress is that stress
  15.6  Hertz's stresses on the axis (nu = 0.3): the largest von Mises stress 0.62 p0 at the depth 0.48 a (and the
        largest shear stress 0.31 p0 there)
"""
import sys

import numpy as np

rng = np.random.default_rng(31)
results = []


def check(name, ok, detail):
    results.append(ok)
    print("%s %s: %s" % ("PASS" if ok else "FAIL", name, detail))


def spd(n):
    A = rng.standard_normal((n, n))
    return A @ A.T + n * np.eye(n)


def identity_rows(K, b, D, g):
    """K' and b' of the identity rows: the rows and columns of D zero but the diagonal, b'_D = diag(K)_D g, the other
    dofs lifted by -K_{:,D} g"""
    n = len(b)
    F = np.setdiff1d(np.arange(n), D)
    Kp = K.copy()
    Kp[D, :] = 0
    Kp[:, D] = 0
    Kp[D, D] = np.diag(K)[D]
    bp = b.copy()
    bp[F] -= K[np.ix_(F, D)] @ g
    bp[D] = np.diag(K)[D] * g
    return Kp, bp, F


# 15.1 ----------------------------------------------------------------------------------------------------------------
n = 30
K, b = spd(n), rng.standard_normal(n)
D = np.array([1, 4, 5, 11, 20])
g = rng.standard_normal(len(D))
Kp, bp, F = identity_rows(K, b, D, g)
u = np.linalg.solve(Kp, bp)
uF = np.linalg.solve(K[np.ix_(F, F)], b[F] - K[np.ix_(F, D)] @ g)
E = np.zeros((len(D), n))
E[np.arange(len(D)), D] = 1
saddle = np.linalg.solve(np.block([[K, E.T], [E, np.zeros((len(D), len(D)))]]), np.concatenate([b, g]))
reaction = (K @ u - b)[D]
err = max(np.abs(u[D] - g).max(), np.abs(u[F] - uF).max() / np.abs(uF).max(), np.abs(reaction + saddle[n:]).max() / np.abs(reaction).max())
check("15.1 identity rows", err < 1e-12 and np.allclose(Kp, Kp.T), "u_D = g, u_F and the reaction (K u - b)_D = -multiplier to %.1e" % err)

# 15.2 ----------------------------------------------------------------------------------------------------------------
C = np.array([0, 2, 3, 7, 8, 9])  # contact dofs, none prescribed
I = np.setdiff1d(np.arange(n), C)
P1 = Kp[np.ix_(C, C)] - Kp[np.ix_(C, I)] @ np.linalg.solve(Kp[np.ix_(I, I)], Kp[np.ix_(I, C)])
f1 = bp[C] - Kp[np.ix_(C, I)] @ np.linalg.solve(Kp[np.ix_(I, I)], bp[I])
IF = np.setdiff1d(F, C)  # the free interior dofs
bl = b[F] - K[np.ix_(F, D)] @ g  # the lifted load on F, indexed by F
lift = dict(zip(F, bl))
P2 = K[np.ix_(C, C)] - K[np.ix_(C, IF)] @ np.linalg.solve(K[np.ix_(IF, IF)], K[np.ix_(IF, C)])
f2 = np.array([lift[c] for c in C]) - K[np.ix_(C, IF)] @ np.linalg.solve(K[np.ix_(IF, IF)], np.array([lift[i] for i in IF]))
err = max(np.abs(P1 - P2).max() / np.abs(P2).max(), np.abs(f1 - f2).max() / np.abs(f2).max())
check("15.2 reduction", err < 1e-12, "P and f of K' equal the Schur complement of K_FF and the lifted load to %.1e" % err)

# 15.3 ----------------------------------------------------------------------------------------------------------------
X = np.array([[i, j, k] for k in (0, 1) for j in (0, 1) for i in (0, 1)], dtype=float)  # the unit cube's 8 corners
tets = [[0, 1, 3, 7], [0, 1, 5, 7], [0, 2, 3, 7], [0, 2, 6, 7], [0, 4, 5, 7], [0, 4, 6, 7]]
lam, mu = 1.0, 1.0
K = np.zeros((24, 24))
for t in tets:
    x = X[t]
    J = (x[1:] - x[0]).T
    grad = np.vstack([-np.linalg.inv(J).sum(axis=0), np.linalg.inv(J)])  # rows: gradients of the barycentric functions
    vol = abs(np.linalg.det(J)) / 6
    Ke = np.zeros((12, 12))
    for a in range(4):
        for c in range(4):
            Ke[3 * a:3 * a + 3, 3 * c:3 * c + 3] = vol * (lam * np.outer(grad[a], grad[c]) + mu * np.outer(grad[c], grad[a]) + mu * grad[a] @ grad[c] * np.eye(3))
    dofs = np.concatenate([[3 * v, 3 * v + 1, 3 * v + 2] for v in t])
    K[np.ix_(dofs, dofs)] += Ke
top = np.where(X[:, 2] == 1)[0]
D = 3 * top + 2  # the top held in z
Kp, _, _ = identity_rows(K, np.zeros(24), D, np.zeros(len(D)))
centre = X.mean(axis=0)
rho = np.zeros((24, 6))
for v in range(8):
    r = X[v] - centre
    rho[3 * v:3 * v + 3, :3] = np.eye(3)
    rho[3 * v:3 * v + 3, 3:] = -np.array([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])  # e_a x r
G = rho[D].T @ rho[D]
w, Y = np.linalg.eigh(G)
kept = Y[:, w <= 1e-10 * w.max()]
modes = rho @ kept
modes[D] = 0
kernel = np.linalg.svd(Kp)[1]
err = np.abs(Kp @ modes).max()
check("15.3 kernel", kept.shape[1] == 3 and err < 1e-12 and (kernel < 1e-12).sum() == 3,
      "%d rigid motions kept (K' rho = 0 to %.1e), K' has %d zero singular values" % (kept.shape[1], err, (kernel < 1e-12).sum()))

# 15.4 ----------------------------------------------------------------------------------------------------------------
def coulomb_node(P, f, offset, phi, u):
    """0 in P u - f + Q(u + offset) for one node (frame = global, n = z), Coulomb: the fixed point of the
    approximation step u <- u + z of section 1, iterated from u to convergence (P SPD)"""
    gamma = 1 / np.abs(P).max()
    for _ in range(200000):
        c = gamma * (P @ u - f)
        v = u + offset
        d3 = max(v[2] - c[2], 0.0)
        s = phi * max(0.0, c[2] - v[2])
        q = v[:2] - c[:2]
        dt = max(0.0, 1 - s / np.linalg.norm(q)) * q if np.linalg.norm(q) > 0 else q
        z = np.concatenate([dt, [d3]]) - v
        u = u + z
        if np.linalg.norm(z) < 1e-15:
            break
    return u, P @ u - f


worst = 0.0
for trial in range(200):
    A = spd(2) * rng.uniform(0.5, 2)
    kd = rng.uniform(0.5, 3)  # the identity row of x: decoupled, its diagonal
    P = np.zeros((3, 3))
    P[0, 0] = kd
    P[1:, 1:] = A
    f = np.array([0.0, rng.uniform(-1, 1), rng.uniform(-2, 0.5)])  # b_x = diag g_x = 0
    offset = np.array([0.0, rng.uniform(-0.3, 0.3), rng.uniform(0, 0.2)])  # no slip across the plane; a gap
    u, r = coulomb_node(P, f, offset, rng.uniform(0.1, 1), 0.1 * rng.standard_normal(3))  # from anywhere
    worst = max(worst, abs(u[0]), abs(r[0]))
check("15.4 plane of symmetry", worst < 1e-12, "200 random nodes: |u_x| and the contact force along x at most %.1e" % worst)

# 15.5 ----------------------------------------------------------------------------------------------------------------
x = rng.standard_normal((4, 3))
A = rng.standard_normal((3, 3)) * 1e-3
ue = x @ A.T + rng.standard_normal(3)
J = (x[1:] - x[0]).T
grad = np.vstack([-np.linalg.inv(J).sum(axis=0), np.linalg.inv(J)])
du = ue.T @ grad  # du[i, j] = d u_i / d x_j
strain = 0.5 * (du + du.T)
err1 = np.abs(strain - 0.5 * (A + A.T)).max() / np.abs(A).max()
s = rng.standard_normal(6)
S = np.array([[s[0], s[5], s[4]], [s[5], s[1], s[3]], [s[4], s[3], s[2]]])
p = np.linalg.eigvalsh(S)
vm_principal = np.sqrt(0.5 * ((p[0] - p[1]) ** 2 + (p[1] - p[2]) ** 2 + (p[2] - p[0]) ** 2))
vm_voigt = np.sqrt(0.5 * ((s[0] - s[1]) ** 2 + (s[1] - s[2]) ** 2 + (s[2] - s[0]) ** 2) + 3 * (s[3:] ** 2).sum())
err2 = abs(vm_principal - vm_voigt) / vm_voigt
vols = rng.uniform(0.1, 1, 7)
err3 = np.abs((vols[:, None] * np.tile(s, (7, 1))).sum(0) / vols.sum() - s).max()
check("15.5 P1 stress", max(err1, err2, err3) < 1e-12, "linear field's strain to %.1e, von Mises of the principal stresses to %.1e, recovery of a uniform stress to %.1e" % (err1, err2, err3))

# 15.6 ----------------------------------------------------------------------------------------------------------------
nu = 0.3
z = np.linspace(1e-3, 3, 300001)
sz = -1 / (1 + z ** 2)
sr = -(1 + nu) * (1 - z * np.arctan(1 / z)) + 0.5 / (1 + z ** 2)
vm = np.abs(sr - sz)
k = vm.argmax()
check("15.6 Hertz on the axis", abs(vm[k] - 0.62) < 0.005 and abs(z[k] - 0.48) < 0.005,
      "largest von Mises %.4f p0 at z = %.4f a, largest shear %.4f p0" % (vm[k], z[k], vm[k] / 2))

sys.exit(0 if all(results) else 1)
