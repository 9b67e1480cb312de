#!/usr/bin/python3
"""Numerical checks of docs/derivation.md section 18 (hyperelastic bodies), in numpy, independent of the C code:

  18.1  the models' stress P = dW/dF and tangent A = dP/dF (central differences), A's major symmetry, Hooke's at F = I
  18.2  the P1 cell's internal force f_a = V P g_a balances (sum f_a = 0) and has no moment about any point of the current
        configuration (sum (X_a + u_a) x f_a = 0: P F^T symmetric), and is the gradient of V W(F(u))
  18.3  the cell's tangent K_ab = V g_a.A.g_b is the derivative of its force and symmetric
  18.4  the uniaxial stress of a block compressed to lambda_3 (sigma_xx = sigma_yy = 0): the closed forms of the lateral
        stretch and the nominal stress P_33 of each model (the lid's force per reference area)
  18.5  a rigid rotation stresses neither hyperelastic model; the linear model's stress at 90 degrees
  18.6  the small-strain limit: P(I + e H) = C : sym(e H) + O(e^2) for both hyperelastic models
  18.7  the Cauchy stress P F^T / J of neo-Hookean is (mu (B - I) + lambda ln J I) / J, B = F F^T
  18.8  the predictor: the linear response to a change dg of prescribed values solves the lifted equations exactly
        for a linear body (K'du = [-K_FD dg; diag(K) dg] gives K du = 0 on the free dofs, du_D = dg)
Prints PASS/FAIL per check; exit status 1 on a failure."""
import sys

import numpy as np

rng = np.random.default_rng(18)
E, NU = 3.0, 0.3
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
I3 = np.eye(3)
failures = []


def check(name, ok, detail=""):
    print("%s %s %s" % ("PASS" if ok else "FAIL", name, detail))
    if not ok:
        failures.append(name)


def energy(model, F):
    if model == "neo_hookean":
        J = np.linalg.det(F)
        return 0.5 * MU * (np.trace(F.T @ F) - 3) - MU * np.log(J) + 0.5 * LAM * np.log(J) ** 2
    e = 0.5 * (F + F.T) - I3 if model == "linear" else 0.5 * (F.T @ F - I3)
    return 0.5 * LAM * np.trace(e) ** 2 + MU * np.sum(e * e)


def stress(model, F):
    if model == "neo_hookean":
        Fit = np.linalg.inv(F).T
        return MU * (F - Fit) + LAM * np.log(np.linalg.det(F)) * Fit
    e = 0.5 * (F + F.T) - I3 if model == "linear" else 0.5 * (F.T @ F - I3)
    S = LAM * np.trace(e) * I3 + 2 * MU * e
    return S if model == "linear" else F @ S


def tangent(model, F):
    """A[i, J, k, L] = dP_iJ / dF_kL, the closed forms of (18.4)"""
    d = I3
    if model == "linear":
        return LAM * np.einsum("iJ,kL->iJkL", d, d) + MU * (np.einsum("ik,JL->iJkL", d, d) + np.einsum("iL,Jk->iJkL", d, d))
    if model == "saint_venant_kirchhoff":
        e = 0.5 * (F.T @ F - I3)
        S = LAM * np.trace(e) * I3 + 2 * MU * e
        return np.einsum("ik,JL->iJkL", d, S) + LAM * np.einsum("iJ,kL->iJkL", F, F) + MU * np.einsum("ik,JL->iJkL", F @ F.T, d) + MU * np.einsum("iL,kJ->iJkL", F, F)
    G = np.linalg.inv(F)
    lnJ = np.log(np.linalg.det(F))
    return MU * np.einsum("ik,JL->iJkL", d, d) + (MU - LAM * lnJ) * np.einsum("Jk,Li->iJkL", G, G) + LAM * np.einsum("Ji,Lk->iJkL", G, G)


MODELS = ("linear", "saint_venant_kirchhoff", "neo_hookean")
F0 = np.array([[1.2, 0.3, -0.1], [-0.2, 0.8, 0.25], [0.15, -0.05, 1.1]])
h = 1e-6


def fd(fun, F):
    """central differences of fun (scalar or matrix) with respect to F"""
    out = []
    for k in range(9):
        dF = np.zeros(9)
        dF[k] = h
        dF = dF.reshape(3, 3)
        out.append((fun(F + dF) - fun(F - dF)) / (2 * h))
    return np.array(out)


# 18.1
for m in MODELS:
    P = stress(m, F0)
    Pfd = fd(lambda F: energy(m, F), F0).reshape(3, 3)
    A = tangent(m, F0)
    Afd = np.moveaxis(fd(lambda F: stress(m, F), F0).reshape(3, 3, 3, 3), (0, 1), (2, 3))
    check("18.1 %s: P = dW/dF, A = dP/dF, A_iJkL = A_kLiJ" % m,
          np.abs(P - Pfd).max() < 1e-7 * MU and np.abs(A - Afd).max() < 1e-7 * MU and np.abs(A - np.transpose(A, (2, 3, 0, 1))).max() < 1e-14 * MU,
          "(|P - dW/dF| %.1e, |A - dP/dF| %.1e)" % (np.abs(P - Pfd).max(), np.abs(A - Afd).max()))
    check("18.1 %s: no stress and Hooke's tangent at F = I" % m, np.abs(stress(m, I3)).max() < 1e-15 and np.abs(tangent(m, I3) - tangent("linear", I3)).max() < 1e-14)

# a P1 tetrahedron: its basis gradients g_a (rows), its volume
X = np.array([[1.0, 1, 1], [3, 1.5, 1], [1.2, 4, 0.5], [0.7, 1.3, 5]])
U = 0.3 * rng.standard_normal((4, 3))
edges = (X[1:] - X[0]).T
Ginv = np.linalg.inv(edges)
g = np.vstack([-Ginv.sum(axis=0), Ginv])
V = abs(np.linalg.det(edges)) / 6


def deformation(u):
    return I3 + u.T @ g


def force(m, u):
    return V * g @ stress(m, deformation(u)).T  # f[a, i] = V sum_J P_iJ g_aJ


# 18.2, 18.3
for m in ("saint_venant_kirchhoff", "neo_hookean"):
    f = force(m, U)
    moment = np.cross(X + U, f).sum(axis=0)
    fgrad = np.array([[(V * energy(m, deformation(U + h * np.eye(12)[3 * a + i].reshape(4, 3))) - V * energy(m, deformation(U - h * np.eye(12)[3 * a + i].reshape(4, 3)))) / (2 * h) for i in range(3)] for a in range(4)])
    K = V * np.einsum("aJ,iJkL,bL->aibk", g, tangent(m, deformation(U)), g).reshape(12, 12)
    Kfd = np.array([((force(m, U + h * np.eye(12)[j].reshape(4, 3)) - force(m, U - h * np.eye(12)[j].reshape(4, 3))) / (2 * h)).ravel() for j in range(12)]).T
    check("18.2 %s: the cell's force balances, has no moment in the current configuration, is grad V W" % m,
          np.abs(f.sum(axis=0)).max() < 1e-13 * MU and np.abs(moment).max() < 1e-12 * MU and np.abs(f - fgrad).max() < 1e-7 * MU,
          "(sum %.1e, moment %.1e)" % (np.abs(f.sum(axis=0)).max(), np.abs(moment).max()))
    check("18.3 %s: the cell's tangent is the derivative of its force, symmetric" % m, np.abs(K - Kfd).max() < 1e-7 * MU and np.abs(K - K.T).max() < 1e-13 * MU)

# 18.4 uniaxial stress, closed forms
def lateral(m, l3):
    """the lateral stretch s with P_11 = 0 at F = diag(s, s, l3), by bisection on the model's own stress"""
    lo, hi = 0.3, 3.0
    for _ in range(200):
        s = 0.5 * (lo + hi)
        if stress(m, np.diag([s, s, l3]))[0, 0] * stress(m, np.diag([lo, lo, l3]))[0, 0] <= 0:
            hi = s
        else:
            lo = s
    return 0.5 * (lo + hi)


for l3 in (0.9, 0.7, 0.5):
    E33 = 0.5 * (l3 * l3 - 1)
    s_svk = np.sqrt(1 - 2 * NU * E33)  # E11 = -nu E33
    P_svk = l3 * E * E33
    s_nh = lateral("neo_hookean", l3)
    P_nh = MU * (l3 - 1 / l3) + LAM * np.log(s_nh * s_nh * l3) / l3
    res_nh = MU * (s_nh * s_nh - 1) + LAM * np.log(s_nh * s_nh * l3)  # mu (s^2 - 1) + lambda ln J = 0
    Psvk, Pnh = stress("saint_venant_kirchhoff", np.diag([s_svk, s_svk, l3])), stress("neo_hookean", np.diag([s_nh, s_nh, l3]))
    check("18.4 lambda_3 = %g: Saint Venant-Kirchhoff s^2 = 1 - 2 nu E33, P_33 = lambda_3 E E33 (%.6g); neo-Hookean mu (s^2 - 1) + lambda ln J = 0, P_33 = mu (l - 1/l) + lambda ln J / l (%.6g)" % (l3, P_svk, P_nh),
          abs(Psvk[0, 0]) < 1e-13 and abs(Psvk[2, 2] - P_svk) < 1e-13 and abs(Pnh[0, 0]) < 1e-12 and abs(Pnh[2, 2] - P_nh) < 1e-12 and abs(res_nh) < 1e-12)

# 18.5 rotation
R = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])
axis = rng.standard_normal(3)
axis /= np.linalg.norm(axis)
W = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
Rg = I3 + np.sin(1.1) * W + (1 - np.cos(1.1)) * W @ W
check("18.5 a rotation (90 degrees about z, 63 degrees about a random axis) stresses no hyperelastic model",
      all(np.abs(stress(m, Q)).max() < 1e-14 * MU for m in MODELS[1:] for Q in (R, Rg)))
check("18.5 the linear model's stress at 90 degrees about z: (-2 lambda - 2 mu, -2 lambda - 2 mu, -2 lambda)",
      np.abs(stress("linear", R) - np.diag([-2 * LAM - 2 * MU, -2 * LAM - 2 * MU, -2 * LAM])).max() < 1e-14)

# 18.6 small strain
H = rng.standard_normal((3, 3))
for m in MODELS[1:]:
    errs = []
    for e in (1e-2, 1e-3, 1e-4):
        lin = stress("linear", I3 + e * H)
        errs.append(np.abs(stress(m, I3 + e * H) - lin).max() / np.abs(lin).max())
    rates = [np.log10(errs[k] / errs[k + 1]) for k in range(2)]
    check("18.6 %s: P(I + eH) - C:sym(eH) relative falls as e (%s)" % (m, ", ".join("%.1e" % x for x in errs)), all(0.9 < r < 1.1 for r in rates) and errs[-1] < 1e-3)

# 18.7 Cauchy
J = np.linalg.det(F0)
B = F0 @ F0.T
sigma = stress("neo_hookean", F0) @ F0.T / J
check("18.7 neo-Hookean sigma = P F^T / J = (mu (B - I) + lambda ln J I) / J, symmetric",
      np.abs(sigma - (MU * (B - I3) + LAM * np.log(J) * I3) / J).max() < 1e-14 and np.abs(sigma - sigma.T).max() < 1e-14)

# 18.8 the predictor on a linear body: a random SPD K split into free F and prescribed D
n, D = 12, [0, 5, 7]
Fr = [k for k in range(n) if k not in D]
A0 = rng.standard_normal((n, n))
K = A0 @ A0.T + n * np.eye(n)
Kp = K.copy()
Kp[np.ix_(D, Fr)] = 0
Kp[np.ix_(Fr, D)] = 0
Kp[np.ix_(D, D)] = np.diag(np.diag(K)[D])
dg = rng.standard_normal(len(D))
rhs = np.zeros(n)
rhs[Fr] = -K[np.ix_(Fr, D)] @ dg
rhs[D] = np.diag(K)[D] * dg
du = np.linalg.solve(Kp, rhs)
check("18.8 the predictor K' du = [-K_FD dg; diag(K) dg]: du_D = dg and (K du)_F = 0 (the free equations stay balanced)",
      np.abs(du[D] - dg).max() < 1e-12 and np.abs((K @ du)[Fr]).max() < 1e-12)

print("%d checks failed" % len(failures) if failures else "all checks passed")
sys.exit(1 if failures else 0)
