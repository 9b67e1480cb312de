#!/usr/bin/python3
"""Numerical check of docs/derivation.md section 18a (numpy, independent of the C code): a P1 cell's tangent along an
infinitesimal rotation of its current configuration, (18.9): w^T K w = -f . (Omega^2 x) for w = Omega x, with f the
cell's internal force and x its current vertices; it is negative for a compressed cell (the geometric stiffness of a
compressive stress) and zero for an unstressed one; and Saint Venant-Kirchhoff's uniaxial force has its maximum at
lambda_3 = 1/sqrt(3), past which d P_33 / d lambda_3 < 0 (an indefinite tangent, (18.4)). Section 18b, (18.10): the
tangent at a stressed state annuls the translations and maps the rotation Omega (x - c) to Omega f, for any centre c.

Prints PASS/FAIL per check; exit status 1 on a failure."""
import sys

import numpy as np

rng = np.random.default_rng(33)
E, NU = 1000.0, 0.3
LAM, MU = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
I3 = np.eye(3)
failures = []


def check(name, ok, detail=""):
    print("%s %s %s" % ("PASS" if ok else "FAIL", name, detail))
    if not ok:
        failures.append(name)


def stress(model, F):
    if model == "neo_hookean":
        Fit = np.linalg.inv(F).T
        return MU * (F - Fit) + LAM * np.log(np.linalg.det(F)) * Fit
    e = 0.5 * (F.T @ F - I3)
    return F @ (LAM * np.trace(e) * I3 + 2 * MU * e)


X = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]]) + 0.1 * rng.standard_normal((4, 3))
D = np.array([X[1] - X[0], X[2] - X[0], X[3] - X[0]]).T
V = abs(np.linalg.det(D)) / 6
G = np.vstack([-np.linalg.inv(D).sum(axis=0), np.linalg.inv(D)])  # g_a, rows: barycentric gradients


def force(model, u):
    """f_a = V P(F) g_a, F = I + sum_a u_a g_a^T  (18.2)"""
    F = I3 + u.T @ G
    return V * (stress(model, F) @ G.T).T


def tangent(model, u, h=1e-6):
    K = np.zeros((12, 12))
    for j in range(12):
        d = np.zeros(12)
        d[j] = h
        K[:, j] = ((force(model, u + d.reshape(4, 3)) - force(model, u - d.reshape(4, 3))) / (2 * h)).ravel()
    return K


axis = rng.standard_normal(3)
axis /= np.linalg.norm(axis)
Om = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
for model in ("neo_hookean", "saint_venant_kirchhoff"):
    for name, Fh in (("unstressed", I3), ("compressed 30 % along z", np.diag([1.08, 1.08, 0.7])), ("sheared and stretched", I3 + 0.2 * rng.standard_normal((3, 3)))):
        u = X @ (Fh - I3).T  # a homogeneous deformation
        x = X + u
        w = (x - x.mean(axis=0)) @ Om.T  # the infinitesimal rotation of the current configuration about its centroid
        f = force(model, u)
        K = tangent(model, u)
        lhs = w.ravel() @ K @ w.ravel()
        rhs = -np.sum(f * ((x - x.mean(axis=0)) @ (Om @ Om).T))
        scale = MU * V * np.sum(w * w)
        check("18.9 %s, %s: w^T K w = -f . (Omega^2 x) for the rotation w = Omega x" % (model, name), abs(lhs - rhs) <= 1e-6 * scale, "(%.6g against %.6g)" % (lhs, rhs))
        if name == "unstressed":
            check("18.9 %s unstressed: no stiffness along a rotation" % model, abs(lhs) <= 1e-6 * scale)
    # the rotation about the x axis of the cell compressed along z: the compressive stress gives it negative stiffness
    u = X @ (np.diag([1.08, 1.08, 0.7]) - I3).T
    x = X + u - (X + u).mean(axis=0)
    Ox = np.array([[0, 0, 0], [0, 0, -1.0], [0, 1.0, 0]])
    w = x @ Ox.T
    check("18.9 %s compressed 30 %% along z: negative stiffness along the rotation about x" % model, w.ravel() @ tangent(model, u) @ w.ravel() < 0)

# (18.10), section 18b: the tangent at any state annuls the translations and maps the rotation w = Omega x of the
# current configuration to Omega f (the internal force turned): the motions a floating body's Newton step regularizes
for model in ("neo_hookean", "saint_venant_kirchhoff"):
    u = X @ (I3 + 0.2 * rng.standard_normal((3, 3)) - I3).T
    x = X + u
    f, K = force(model, u), tangent(model, u)
    scale = MU * V * np.abs(x).max()
    for k in range(3):
        t = np.zeros((4, 3))
        t[:, k] = 1
        check("18.10 %s: K t = 0 for the translation along axis %d" % (model, k), np.abs(K @ t.ravel()).max() <= 1e-6 * MU * V)
    for c in (x.mean(axis=0), np.array([3.0, -2.0, 5.0])):
        w = (x - c) @ Om.T
        check("18.10 %s: K (Omega (x - c)) = Omega f about any centre c" % model, np.abs(K @ w.ravel() - (f @ Om.T).ravel()).max() <= 1e-6 * scale,
              "(|Omega f| %.3g)" % np.abs(f @ Om.T).max())

# Saint Venant-Kirchhoff's uniaxial force P_33 = lambda_3 E E_33 (18.6): its maximum at lambda_3 = 1/sqrt(3)
l3 = np.linspace(0.3, 0.99, 6901)
P = l3 * E * 0.5 * (l3 * l3 - 1)
check("18.4 Saint Venant-Kirchhoff: |P_33| has its maximum at lambda_3 = 1/sqrt(3) (a compression of 42 %), dP_33/dlambda_3 < 0 beyond",
      abs(l3[np.argmin(P)] - 1 / np.sqrt(3)) < 2e-4 and np.all(np.diff(P)[l3[1:] < 1 / np.sqrt(3) - 1e-3] < 0))

print("%d checks failed" % len(failures) if failures else "all checks passed")
sys.exit(1 if failures else 0)
