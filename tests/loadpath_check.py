#!/usr/bin/python3
"""Checks docs/derivation.md sections 10 and 11 (load paths: the incremental friction problem and the closed forms of
its known answers) in dense numpy, independently of the C code.

  tests/loadpath_check.py [--seed 5]

Each check prints one line "PASS name: figures" or "FAIL name: figures"; the exit status is 1 if one fails.
  1. offset = incremental law (--write FILE: its problem and answers for tests/test_offsets.c): a whole body (random SPD K, 20 nodes) with 8 nodes against obstacles (tilted frames,
     gaps, one obstacle moving) and 3 points of a contact pair (master weights), Coulomb, Tresca and frictionless
     nodes, loaded by press -> shear -> release -> reverse -> release: the semismooth* iteration on the reduced
     problem with the offsets o^k of (10.4), and on the whole body (the contact rows in place of K's rows), both
     equal a different algorithm -- Tresca fixed points solved by an accelerated projected gradient on the dual
     (Delassus operator), with the incremental law written on w = B u + g directly -- to 1e-10 at every step
  2. the block on a spring (11.1)-(11.2): one node, press -> shear to Q -> release -> -Q -> release, solved in fine
     steps: u_x = (Q - phi P)/k after the release, -(Q - phi P)/k after the second one (11.2), the stick/slip phases
     where (11.1) puts them; with Q > 2 phi P the release slides back to phi P/k
  3. displacement-controlled sliding (11.3): a 3x3 grid of nodes on springs, a rigid plane pushed up then moved
     sideways: the tangential force is phi times the normal force to 1e-12 once every node slides; moved back a
     little, every node sticks and the force drops by k_t times the move
  4. a monotone proportional path (10.8): no gaps, the load growing in proportion: every incremental step equals the
     static answer (slip from the reference) to 1e-10; with gaps, a node whose slip turns makes them differ, and
     exactly where (10.7) says
  5. quadratic convergence of the shifted iteration: a step with reversal and sliding, ||z_k+1|| <= C ||z_k||^2
  6. the Cattaneo-Mindlin / Mindlin-Deresiewicz closed forms (11.4)-(11.11): the loop's area by quadrature equals
     (11.9), the small-amplitude limit (11.10), the branches meet at +-Q*, the opening at Q = 0 (11.11), and the
     centre displacement of the Cattaneo
     traction by quadrature of Cerruti's solution equals pi (2 - nu) q0 a/(8 G)

The functions mindlin_* and block_on_spring_* are the closed forms a scene test can import."""
import argparse
import sys

import numpy as np



def random_problem(*args, **kwargs):
    """derivation_check's random SPD P and a load that separates, slides, sticks; imported here only, because
    derivation_check initializes petsc4py (MPI), and a scene test that imports the closed forms below runs mpiexec"""
    from derivation_check import problem
    return problem(*args, **kwargs)

STATES = ["L", "M1", "M2", "M3+", "M3-", "M4", "LS"]  # the codes of SSStarState
RESULTS = []


def report(name, ok, figures):
    RESULTS.append(ok)
    print("%s %s: %s" % ("PASS" if ok else "FAIL", name, figures))


# ---------------------------------------------------------------------------------------------------------------------
# Per-node kernels of docs/derivation.md sections 1-5 for a law ("coulomb", phi), ("tresca", bound) or ("none", 0);
# v = R u + o, the iterate in the node's frame with its offset (10.5)
# ---------------------------------------------------------------------------------------------------------------------

def threshold(law, c, v):
    """s of (1.2): phi max(0, c_n - v_n) for Coulomb, the bound for Tresca, 0 without friction"""
    kind, par = law
    return {"coulomb": par * max(0.0, c[2] - v[2]), "tresca": par, "none": 0.0}[kind]


def approximation_step(law, v, c):
    """(1.1)-(1.4) at one node: z, d, b"""
    d = np.zeros(3)
    d[2] = max(v[2] - c[2], 0.0)
    w, s = v[:2] - c[:2], threshold(law, c, v)
    d[:2] = (1 - s / np.linalg.norm(w)) * w if np.linalg.norm(w) > s else 0.0
    z = d - v
    return z, d, -z - c


def classify(law, d, b, tol_d, tol_b):
    """Table 1 (2.1); Tresca with its normal and tangential states apart (LS: separated, stuck)"""
    kind, par = law
    sliding = np.linalg.norm(d[:2]) > tol_d
    if kind == "tresca":
        if d[2] > tol_d:
            return "L" if sliding else "LS"
        if -b[2] <= tol_b:
            return "M2" if sliding else "M4"
        return "M1" if sliding else ("M3+" if par - np.linalg.norm(b[:2]) > tol_b else "M3-")
    phi = par if kind == "coulomb" else 0.0
    if d[2] > tol_d:
        return "L"
    if -b[2] <= tol_b:
        return "M2" if sliding else "M4"
    if sliding:
        return "M1"
    return "M3+" if -phi * b[2] - np.linalg.norm(b[:2]) > tol_b else "M3-"


def reduced_blocks(law, state, d, b):
    """S, T of (5.2) (kernels.c's GetBlockKind: frictionless strong contact slides, Tresca has no phi om coupling)"""
    kind, par = law
    closed = state in ("M1", "M3+", "M3-")
    frictionless = kind == "none" or (kind == "coulomb" and par == 0)
    tangent = True if kind == "tresca" else closed
    slides = state in ("L", "M1", "M2") if kind == "tresca" else (state == "M1" or (frictionless and closed))
    S, T = np.diag([1.0, 1.0, 0.0 if closed else 1.0]), np.diag([0.0, 0.0, 1.0 if closed else 0.0])
    if tangent and slides:
        s, kappa = {"coulomb": (-par * b[2], par), "tresca": (par, 0.0), "none": (0.0, 0.0)}[kind]
        if s != 0:
            om = d[:2] / np.linalg.norm(d[:2])  # (3.2): the direction of the slip increment
            T[:2, :2] = s / np.linalg.norm(d[:2]) * (np.eye(2) - np.outer(om, om))
            if closed:
                S[:2, 2] = kappa * om
    elif tangent:
        S[0, 0] = S[1, 1] = 0.0
        T[0, 0] = T[1, 1] = 1.0
    return S, T


# ---------------------------------------------------------------------------------------------------------------------
# The semismooth* iteration (section 7, no globalization) with offsets: on a reduced problem (P, f) and on a whole body
# ---------------------------------------------------------------------------------------------------------------------

def scaled_law(law, gamma):
    """a Tresca bound is a force: the kernels see gamma c (section 6)"""
    return (law[0], law[1] * gamma) if law[0] == "tresca" else law


def node_work(laws, frames, offsets, u_nodes, c_nodes, gamma):
    """z, d, b and the states of every node; u_nodes, c_nodes in global axes (p x 3), c already scaled"""
    p = len(laws)
    v = np.einsum("ikl,il->ik", frames, u_nodes) + offsets
    cf = np.einsum("ikl,il->ik", frames, c_nodes)
    z, d, b = np.zeros((p, 3)), np.zeros((p, 3)), np.zeros((p, 3))
    for i in range(p):
        z[i], d[i], b[i] = approximation_step(scaled_law(laws[i], gamma), v[i], cf[i])
    return v, z, d, b


def node_states(laws, v, d, b, gamma, fscale, tau=1e-13):
    tol_d = tau * max(np.abs(v).max(), np.abs(d).max())
    tol_b = tau * max(fscale, np.abs(b).max())
    return [classify(scaled_law(laws[i], gamma), d[i], b[i], tol_d, tol_b) for i in range(len(laws))]


def newton_reduced(P, f, laws, frames, offsets, u0, rtol=1e-15, its=60):
    """0 in P u - f + Q(R u + o): returns u, the ||z|| of every iterate and the final states"""
    p = len(laws)
    gamma = 1 / np.mean(np.diag(P))
    Rbig = np.zeros((3 * p, 3 * p))
    for i in range(p):
        Rbig[3 * i:3 * i + 3, 3 * i:3 * i + 3] = frames[i]
    u, history = u0.copy(), []
    for _ in range(its):
        c = gamma * (P @ u - f)
        v, z, d, b = node_work(laws, frames, offsets, u.reshape(p, 3), c.reshape(p, 3), gamma)
        history.append(np.linalg.norm(z))
        states = node_states(laws, v, d, b, gamma, gamma * np.abs(f).max())
        if history[-1] <= rtol * max(np.linalg.norm(u), gamma * np.linalg.norm(f), 1e-300):
            return u, history, states
        S, T = np.zeros((3 * p, 3 * p)), np.zeros((3 * p, 3 * p))
        for i in range(p):
            k3 = slice(3 * i, 3 * i + 3)
            S[k3, k3], T[k3, k3] = reduced_blocks(scaled_law(laws[i], gamma), states[i], d[i], b[i])
        dv = np.linalg.solve(S @ Rbig @ (gamma * P) @ Rbig.T + T, (S + T) @ z.ravel())  # (5.1) in the frames
        u = u + Rbig.T @ dv
    raise RuntimeError("the reduced iteration did not converge: ||z|| %s" % history[-5:])


def newton_whole(K, bvec, contact, laws, frames, offsets, U0, rtol=1e-15, its=60):
    """The same on the whole body (newton_wholebody.c): the contact nodes' rows of K replaced by S gamma K + T R E, the free
    dofs' rows kept (z = -gamma (K u - b) there). contact: p x 3 dofs of the contact nodes"""
    n, p = len(bvec), len(laws)
    C = contact.ravel()
    free = np.setdiff1d(np.arange(n), C)
    gamma = 1 / np.mean(np.diag(K)[C])
    U, history = U0.copy(), []
    for _ in range(its):
        c = gamma * (K @ U - bvec)
        v, z, d, b = node_work(laws, frames, offsets, U[contact], c[contact], gamma)
        zfull = np.zeros(n)
        zfull[free] = -c[free]
        zfull[C] = z.ravel()  # in the frames, as ss->z
        history.append(np.linalg.norm(zfull))
        states = node_states(laws, v, d, b, gamma, gamma * np.abs(bvec).max())
        if history[-1] <= rtol * max(np.linalg.norm(U[C]), 1e-300):
            return U, history, states
        M, rhs = gamma * K.copy(), zfull.copy()
        for i in range(p):
            S, T = reduced_blocks(scaled_law(laws[i], gamma), states[i], d[i], b[i])
            rows = contact[i]
            E = np.zeros((3, n))
            E[[0, 1, 2], rows] = 1.0
            M[rows] = S @ frames[i] @ (gamma * K[rows]) + T @ frames[i] @ E
            rhs[rows] = (S + T) @ z[i]
        U = U + np.linalg.solve(M, rhs)
    raise RuntimeError("the whole-body iteration did not converge: ||z|| %s" % history[-5:])


# ---------------------------------------------------------------------------------------------------------------------
# The independent method: the incremental law on w = B u + g - R d directly, by Tresca fixed points, each Tresca
# problem solved on the dual (lambda, the contact force in the frames) by an accelerated projected gradient
# ---------------------------------------------------------------------------------------------------------------------

def project(lam, bounds):
    """onto { lambda_n >= 0, |lambda_t| <= s } per point"""
    lam = lam.reshape(-1, 3).copy()
    lam[:, 2] = np.maximum(lam[:, 2], 0.0)
    nt = np.linalg.norm(lam[:, :2], axis=1)
    scale = np.where(nt > bounds, bounds / np.maximum(nt, 1e-300), 1.0)
    lam[:, :2] *= scale[:, None]
    return lam.ravel()


def tresca_dual(W, q, bounds, lam0, tol):
    """min 1/2 l'W l + q'l over the Tresca set: FISTA with restarts; the gradient W l + q is (slip increment, gap)"""
    L = np.linalg.eigvalsh(W).max()
    lam, y, t = lam0.copy(), lam0.copy(), 1.0
    for _ in range(200000):
        new = project(y - (W @ y + q) / L, bounds)
        if np.abs(new - lam).max() <= tol:
            return new
        tn = (1 + np.sqrt(1 + 4 * t * t)) / 2
        y = new + (t - 1) / tn * (new - lam)
        if (W @ new + q) @ (new - lam) > 0:  # restart when the objective would rise
            y, tn = new.copy(), 1.0
        lam, t = new, tn
    raise RuntimeError("the dual projected gradient did not converge")


def incremental_dual(K, bvec, B, g_minus_Rd, wt_prev, laws, lam0):
    """One step of the incremental problem (10.2) on the points' w = B u + g - R d: friction opposes w_t - w_t_prev.
    Returns u, w, lambda."""
    Kinv = np.linalg.inv(K)
    W = B @ Kinv @ B.T
    q = B @ Kinv @ bvec + g_minus_Rd
    q.reshape(-1, 3)[:, :2] -= wt_prev  # the slip increment, not the slip from the reference
    lam, scale = lam0.copy(), max(np.abs(q).max(), 1.0)
    for _ in range(500):  # Tresca fixed point: bounds phi lambda_n (Coulomb), the bound (Tresca), 0 (none)
        bounds = np.array([law[1] * max(lam[3 * i + 2], 0.0) if law[0] == "coulomb" else (law[1] if law[0] == "tresca" else 0.0) for i, law in enumerate(laws)])
        new = tresca_dual(W, q, bounds, lam, 1e-14 * scale)
        if np.abs(new - lam).max() <= 1e-13 * max(np.abs(new).max(), 1.0):
            lam = new
            break
        lam = new
    u = Kinv @ (bvec + B.T @ lam)
    return u, B @ u + g_minus_Rd, lam


# ---------------------------------------------------------------------------------------------------------------------
# 1. the offset (10.4) against the incremental law solved by another method
# ---------------------------------------------------------------------------------------------------------------------

def rotation(rng, angle):
    axis = rng.standard_normal(3)
    axis /= np.linalg.norm(axis)
    X = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * X + (1 - np.cos(angle)) * X @ X


def piecewise(knots, t):
    """piecewise linear through knots [(t, value)], constant outside (as ssstarhistory.h evaluates a history)"""
    ts = np.array([k[0] for k in knots])
    vs = np.array([k[1] for k in knots], dtype=float)
    return np.array([np.interp(t, ts, vs[:, j]) for j in range(vs.shape[1])])


def body_problem(seed):
    """The whole body of check 1: K, the contact points (obstacle nodes and pair points), their operator B in the
    frames, gaps, laws, and the histories of the load and of the obstacle motion"""
    rng = np.random.default_rng(seed)
    N, p_obst, p_pair = 20, 8, 3
    n = 3 * N
    A = rng.standard_normal((n, n))
    K = A @ A.T / n + 1.5 * np.eye(n)
    slaves = np.arange(p_obst + p_pair)  # contact nodes 0..10, masters among 11..19
    p = len(slaves)
    frames = np.array([rotation(rng, 0.4) if i % 3 == 1 else np.eye(3) for i in range(p)])
    M = np.zeros((3 * p, n))  # master weights of the pair points, in global axes
    for i in range(p_obst, p):
        masters = rng.choice(np.arange(p, N), 3, replace=False)
        weights = rng.dirichlet(np.ones(3))
        for m, wgt in zip(masters, weights):
            M[3 * i:3 * i + 3, 3 * m:3 * m + 3] = wgt * np.eye(3)
    E = np.zeros((3 * p, n))
    for i in range(p):
        E[3 * i:3 * i + 3, 3 * i:3 * i + 3] = np.eye(3)
    Rbig = np.zeros((3 * p, 3 * p))
    for i in range(p):
        Rbig[3 * i:3 * i + 3, 3 * i:3 * i + 3] = frames[i]
    C = E - M  # x_i = u_s - M_i u in global axes
    B = Rbig @ C  # rows t1, t2, n per point
    gaps = np.where(np.arange(p) % 4 == 3, 0.05, 0.0)
    laws = [("coulomb", 0.3)] * p
    laws[5] = ("tresca", 0.4)
    laws[6] = ("none", 0.0)
    moving = np.arange(p) < 3  # points 0, 1, 2 face an obstacle that moves
    # the load: b = K y with B y the target relative displacement of each point (normal: pressed 1 deep, tangential:
    # press -> shear -> release -> reverse -> release); y the least-norm solution
    directions = rng.standard_normal((p, 2))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    shear = 0.9 * directions
    depth = np.where(np.arange(p) == 9, 0.03, 1.0)  # point 9 only just touches: it separates when sheared
    load_knots = [(0, 0.0, 0.0), (1, 1.0, 0.0), (2, 1.0, 1.0), (3, 1.0, 0.0), (4, 1.0, -1.0), (5, 1.0, 0.0)]

    def load(t):
        press, sh = piecewise([(k[0], k[1:]) for k in load_knots], t)
        target = np.zeros((p, 3))
        target[:, 2] = -press * depth
        target[:, :2] = sh * shear
        target[9, 2] += 0.4 * abs(sh)
        y = np.linalg.lstsq(B, target.ravel(), rcond=None)[0]
        return K @ y

    motion_knots = [(0, [0, 0, 0]), (1, [0, 0, 0.02]), (2, [0.3, -0.1, 0.02]), (4, [-0.2, 0.1, 0.02]), (5, [0, 0, 0])]
    steps = np.linspace(0, 5, 21)
    return dict(K=K, B=B, C=C, E=E, M=M, frames=frames, gaps=gaps, laws=laws, moving=moving, load=load,
                motion=lambda t: piecewise(motion_knots, t), steps=steps, p=p, n=n)


def offsets_of_step(pb, d, wt_prev):
    """(10.4): o = g e3 - R d - (w_t^(k-1), 0); R d only for the points whose obstacle moves (pair points: no motion)"""
    o = np.zeros((pb["p"], 3))
    o[:, 2] = pb["gaps"]
    for i in range(pb["p"]):
        if pb["moving"][i]:
            o[i] -= pb["frames"][i] @ d
    o[:, :2] -= wt_prev
    return o


def reduced_operator(pb):
    """the points' variables x = C u (global axes): P_x = (C K^-1 C^T)^-1, f_x = P_x C K^-1 b (contact-operator.md s. 4)"""
    Kinv = np.linalg.inv(pb["K"])
    P = np.linalg.inv(pb["C"] @ Kinv @ pb["C"].T)
    return P, lambda b: P @ pb["C"] @ Kinv @ b


def whole_body_operator(pb):
    """T = I + E_S^T M (u = T v), K_w = T^T K T: the points' own dofs are v's contact dofs (contact-operator.md s. 3)"""
    T = np.eye(pb["n"]) + pb["E"].T @ pb["M"]
    return T, T.T @ pb["K"] @ T


def write_petsc_binary(path, header, mats, vecs_before, steps):
    """PETSc's binary format (big-endian): the header (int32s), the matrices (AIJ), the per-point vectors, then per step
    its vectors, for tests/test_offsets.c (MatLoad, VecLoad, PetscViewerBinaryRead)"""
    def vec(f, v):
        f.write(np.array([1211214, len(v)], ">i4").tobytes() + np.asarray(v, ">f8").tobytes())

    def mat(f, A):
        rows, cols = np.nonzero(A)
        lengths = np.bincount(rows, minlength=A.shape[0])
        f.write(np.array([1211216, A.shape[0], A.shape[1], len(rows)], ">i4").tobytes() + lengths.astype(">i4").tobytes()
                + cols.astype(">i4").tobytes() + A[rows, cols].astype(">f8").tobytes())

    with open(path, "wb") as f:
        f.write(np.array(header, ">i4").tobytes())
        for A in mats:
            mat(f, A)
        for v in vecs_before:
            vec(f, v)
        for step in steps:
            for v in step:
                vec(f, v)


def check_offsets(seed, write=None):
    pb = body_problem(seed)
    p, K, B, frames = pb["p"], pb["K"], pb["B"], pb["frames"]
    P, reduce_load = reduced_operator(pb)
    Tmat, Kw = whole_body_operator(pb)
    contact = np.arange(3 * p).reshape(p, 3)
    x, U = np.zeros(3 * p), np.zeros(pb["n"])
    lam, wt_dual = np.zeros(3 * p), np.zeros((p, 2))
    wt_newton = np.zeros((p, 2))
    worst = {"reduced": 0.0, "whole": 0.0}
    seen, its, written = set(), [], []
    for t in pb["steps"]:
        bvec, d = pb["load"](t), pb["motion"](t)
        g_minus_Rd = np.zeros((p, 3))
        g_minus_Rd[:, 2] = pb["gaps"]
        g_minus_Rd[pb["moving"]] -= np.einsum("ikl,l->ik", frames[pb["moving"]], d)
        u_ind, w_ind, lam = incremental_dual(K, bvec, B, g_minus_Rd.ravel(), wt_dual, pb["laws"], lam)
        wt_dual = w_ind.reshape(p, 3)[:, :2].copy()

        o = offsets_of_step(pb, d, wt_newton)
        x, hist, states = newton_reduced(P, reduce_load(bvec), pb["laws"], frames, o, x)
        its.append(len(hist) - 1)
        seen |= set(states)
        V_S = x
        Vw = np.zeros(pb["n"])
        Vw[contact.ravel()] = V_S
        free = np.arange(3 * p, pb["n"])
        bw = Tmat.T @ bvec
        Vw[free] = np.linalg.solve(Kw[np.ix_(free, free)], bw[free] - Kw[np.ix_(free, contact.ravel())] @ V_S)
        u_red = Tmat @ Vw
        U, hist_w, _ = newton_whole(Kw, bw, contact, pb["laws"], frames, o, U)
        u_whole = Tmat @ U
        wt_newton = (np.einsum("ikl,il->ik", frames, x.reshape(p, 3)) + g_minus_Rd)[:, :2]  # w^k = R x^k + g e3 - R d^k
        scale = max(np.abs(u_ind).max(), 1e-300)
        worst["reduced"] = max(worst["reduced"], np.abs(u_red - u_ind).max() / scale)
        worst["whole"] = max(worst["whole"], np.abs(u_whole - u_ind).max() / scale)
        written.append((bvec, -g_minus_Rd.ravel() + np.outer(pb["gaps"], [0, 0, 1]).ravel(), u_red))
    if write:  # the problem and numpy's answer of every step, for the library's own solve (tests/test_offsets.c)
        codes = {"none": 0, "tresca": 1, "coulomb": 2}
        per_point = [pb["gaps"], [codes[law[0]] for law in pb["laws"]], [law[1] if law[0] == "coulomb" else 0 for law in pb["laws"]],
                     [law[1] if law[0] == "tresca" else 0 for law in pb["laws"]]]
        write_petsc_binary(write, [pb["n"], p, len(written)], [K, B], per_point, written)
    ok_r, ok_w = worst["reduced"] <= 1e-10, worst["whole"] <= 1e-10
    kinds = "/".join(s for s in STATES if s in seen)
    report("offset (10.4) = incremental law, reduced P", ok_r and {"L", "M1", "M3+"} <= seen,
           "%d steps, max |u - u_dual|/|u| = %.1e, states met %s, Newton iterations per step %s" % (len(pb["steps"]), worst["reduced"], kinds, ",".join(map(str, its))))
    report("offset (10.4) = incremental law, whole body", ok_w, "max |u - u_dual|/|u| = %.1e (pair points through T^T K T)" % worst["whole"])


# ---------------------------------------------------------------------------------------------------------------------
# 2. the block on a spring (11.1)-(11.2)
# ---------------------------------------------------------------------------------------------------------------------

def block_on_spring_final(Q, phi, P, k):
    """(11.2): u_x after press -> shear to Q -> release, and after -> -Q -> release"""
    if Q <= phi * P:
        return 0.0, 0.0
    if Q <= 2 * phi * P:
        return (Q - phi * P) / k, -(Q - phi * P) / k
    return phi * P / k, -phi * P / k


def block_on_spring_phase(Q_t, u_before, phi, P, k):
    """(11.1): the state and u_x of the block at the tangential load Q_t, from u_before (stick if the spring and the
    load leave a force within the cone, else slide to where the force is on it)"""
    r = k * u_before - Q_t  # the friction force if it sticks
    if abs(r) <= phi * P:
        return "stick", u_before
    return "slide", (Q_t - np.sign(-r) * phi * P) / k


def check_block_on_spring():
    k, kn, phi, Pn = 2.0, 1e4, 0.3, 10.0
    Pmat = np.diag([k, k, kn])
    laws, frames = [("coulomb", phi)], np.array([np.eye(3)])
    lines, ok = [], True
    for Q in (4.5, 7.5):  # phi P < Q <= 2 phi P, and Q > 2 phi P
        path = [(0, 0, 0), (1, 0, Pn), (2, Q, Pn), (3, 0, Pn), (4, -Q, Pn), (5, 0, Pn)]
        u, wt_prev, expected_u, worst, phase_ok = np.zeros(3), np.zeros(2), 0.0, 0.0, True
        phases = []
        for t in np.linspace(0, 5, 101):
            Qt, Pt = piecewise([(a, (b, c)) for a, b, c in path], t)
            f = np.array([Qt, 0.0, -Pt])
            o = np.array([[-wt_prev[0], -wt_prev[1], 0.0]])
            u, _, states = newton_reduced(Pmat, f, laws, frames, o, u)
            wt_prev = u[:2].copy()
            state, expected_u = block_on_spring_phase(Qt, expected_u, phi, Pt, k) if Pt > 0 else ("stick", expected_u)
            worst = max(worst, abs(u[0] - expected_u))
            kind = "slide" if states[0] == "M1" else "stick"
            phase_ok &= Pt == 0 or kind == state or abs(abs(k * u[0] - Qt) - phi * Pt) < 1e-12  # on the cone: either
            if not phases or phases[-1][0] != kind:
                phases.append([kind, t])
            if t == 3.0:
                first = u[0]
        after = block_on_spring_final(Q, phi, Pn, k)
        final_ok = abs(first - after[0]) <= 1e-12 and abs(u[0] - after[1]) <= 1e-12 and worst <= 1e-12 and phase_ok
        ok &= final_ok
        lines.append("Q/(phi P) = %g: u_x %.6g after the first release, %.6g after the second (10.2: %.6g, %.6g), phases %s, "
                     "max |u_x - (11.1)| = %.1e" % (Q / (phi * Pn), first, u[0], after[0], after[1], " ".join("%s@%.2f" % (a, b) for a, b in phases), worst))
    report("block on a spring (11.1)-(11.2)", ok, "; ".join(lines))


# ---------------------------------------------------------------------------------------------------------------------
# 3. displacement-controlled sliding (11.3)
# ---------------------------------------------------------------------------------------------------------------------

def grid_block(m=3, k_link=1.0, k_t=0.2, k_n=1.0, coupling=0.05):
    """P of m x m nodes on a face: neighbours linked by springs (every direction), each node tied to the body's held far
    side by k_t tangentially and k_n normally, and a weak symmetric normal-tangential coupling"""
    p = m * m
    L = np.zeros((p, p))
    for a in range(m):
        for b in range(m):
            i = a * m + b
            for da, db in ((1, 0), (0, 1)):
                if a + da < m and b + db < m:
                    j = (a + da) * m + b + db
                    L[i, i] += k_link
                    L[j, j] += k_link
                    L[i, j] -= k_link
                    L[j, i] -= k_link
    P = np.kron(L, np.eye(3)) + np.kron(np.eye(p), np.diag([k_t, k_t, k_n]))
    for i in range(p):
        P[3 * i, 3 * i + 2] = P[3 * i + 2, 3 * i] = coupling * ((i % 3) - 1)
    return P


def check_displacement_sliding():
    m, phi = 3, 0.3
    P = grid_block(m)
    p = m * m
    laws, frames = [("coulomb", phi)] * p, np.array([np.eye(3)] * p)
    gaps = np.linspace(0.0, 0.02, p)  # a slightly tilted face: a non-uniform pressure
    path = [(0, [0, 0, 0]), (1, [0, 0, 0.1]), (2, [0.5, 0, 0.1]), (3, [1.0, 0, 0.1]), (3.1, [0.99, 0, 0.1])]
    u, wt_prev, d_prev, rows = np.zeros(3 * p), np.zeros((p, 2)), np.zeros(3), []
    for t in (0, 0.5, 1, 1.25, 1.5, 2, 2.5, 3, 3.1):
        d = piecewise(path, t)
        o = np.zeros((p, 3))
        o[:, 2] = gaps - d[2]
        o[:, :2] = -d[:2] - wt_prev  # (10.4) with R = I: -R d - w_t^(k-1)
        u, _, states = newton_reduced(P, np.zeros(3 * p), laws, frames, o, u)
        r = (P @ u).reshape(p, 3)
        wt_prev = u.reshape(p, 3)[:, :2] - d[:2]  # the slip from the reference, R_t (u - d)
        rows.append((t, r[:, 0].sum(), r[:, 2].sum(), states, u.copy(), d.copy()))
        d_prev = d
    t, T, Nf, states, u_end, _ = rows[-2]  # at t = 3, after sliding
    steady = abs(T - phi * Nf) / Nf
    t, Tb, Nb, states_back, u_back, _ = rows[-1]  # moved back by 0.01
    k_t = P.reshape(p, 3, p, 3)[:, 0, :, 0].sum()  # 1_x^T P 1_x: the face translated rigidly along x
    drop = (T - Tb) / 0.01
    ok = steady <= 1e-12 and all(s == "M1" for s in states) and all(s in ("M3+", "M3-") for s in states_back)
    ok &= abs(drop - k_t) <= 1e-9 * k_t
    report("displacement-controlled sliding (11.3)", ok, "T/(phi N) - 1 = %.1e with all %d nodes sliding; moved back 0.01: "
           "states %s, dT/dx = %.6g (k_t = 1'P_xx 1 = %.6g)" % (steady, p, "/".join(sorted(set(states_back))), drop, k_t))


# ---------------------------------------------------------------------------------------------------------------------
# 4. monotone proportional paths give the static answer (10.7)-(10.8)
# ---------------------------------------------------------------------------------------------------------------------

def incremental_path(P, f_of, laws, gaps, lams):
    p = len(laws)
    frames = np.array([np.eye(3)] * p)
    u, wt_prev, out = np.zeros(3 * p), np.zeros((p, 2)), []
    for lam in lams:
        o = np.zeros((p, 3))
        o[:, 2] = gaps
        o[:, :2] = -wt_prev
        u, _, states = newton_reduced(P, f_of(lam), laws, frames, o, u)
        wt_prev = u.reshape(p, 3)[:, :2].copy()
        out.append((u.copy(), states))
    return out


def static_answers(P, f_of, laws, gaps, lams):
    p = len(laws)
    frames = np.array([np.eye(3)] * p)
    o = np.zeros((p, 3))
    o[:, 2] = gaps
    return [newton_reduced(P, f_of(lam), laws, frames, o, np.zeros(3 * p))[0] for lam in lams]


def condition_97(P, statics, gaps, lams, f_of, tol=1e-9):
    """(10.7): the static answers solve the incremental steps if at every node in contact the static slip's increment
    is zero or a positive multiple of the static slip. Returns the (step, node) pairs where it fails."""
    p = len(gaps)
    failing, prev = [], np.zeros(3 * p)
    for k, (u, lam) in enumerate(zip(statics, lams)):
        r = (P @ u - f_of(lam)).reshape(p, 3)
        s, ds = u.reshape(p, 3)[:, :2], (u - prev).reshape(p, 3)[:, :2]
        for i in range(p):
            if r[i, 2] <= tol or np.linalg.norm(ds[i]) <= tol:
                continue
            aligned = np.linalg.norm(s[i]) > tol and abs(np.cross(s[i], ds[i])) <= tol * np.linalg.norm(ds[i]) and s[i] @ ds[i] > 0
            if not aligned:
                failing.append((k, i))
        prev = u
    return failing


def check_proportional(seed):
    p, phi = 16, 0.3
    P, f = random_problem(p, seed)
    laws = [("coulomb", phi)] * p
    lams = [0.2, 0.4, 0.6, 0.8, 1.0]
    f_of = lambda lam: lam * f  # noqa: E731
    zero = np.zeros(p)
    inc, stat = incremental_path(P, f_of, laws, zero, lams), static_answers(P, f_of, laws, zero, lams)
    diff = max(np.abs(a[0] - b).max() / np.abs(b).max() for a, b in zip(inc, stat))
    states = set(s for a in inc for s in a[1])
    report("proportional path, no gaps (10.8)", diff <= 1e-10 and {"L", "M1", "M3+"} <= states,
           "5 steps to the full load, 16 nodes (states %s): max |u_inc - u_static|/|u| = %.1e" % ("/".join(s for s in STATES if s in states), diff))
    # with gaps the problem is not homogeneous: nodes touch late and their slip can turn
    rng = np.random.default_rng(seed + 1)
    gaps = rng.uniform(0, 0.5, p) * (np.arange(p) % 2)
    lams = np.linspace(0.1, 1.0, 10)
    inc, stat = incremental_path(P, f_of, laws, gaps, lams), static_answers(P, f_of, laws, gaps, lams)
    failing = condition_97(P, stat, gaps, lams, f_of)
    diffs = [np.abs(a[0] - b).max() / np.abs(b).max() for a, b in zip(inc, stat)]
    first_diff = next((k for k, dval in enumerate(diffs) if dval > 1e-9), None)
    first_fail = failing[0][0] if failing else None
    ok = first_diff == first_fail and first_fail is not None
    report("proportional path with gaps: where (10.7) fails", ok,
           "(10.7) first fails at step %s (nodes %s); the paths first differ at step %s, by %.1e at the end" % (
               first_fail, sorted(set(i for k, i in failing if k == first_fail)), first_diff, diffs[-1]))


# ---------------------------------------------------------------------------------------------------------------------
# 5. quadratic convergence of the shifted iteration
# ---------------------------------------------------------------------------------------------------------------------

def check_quadratic(seed):
    p, phi = 16, 0.3
    P, f = random_problem(p, seed)
    laws, frames = [("coulomb", phi)] * p, np.array([np.eye(3)] * p)
    o = np.zeros((p, 3))
    u1, _, _ = newton_reduced(P, f, laws, frames, o, np.zeros(3 * p))  # step 1: the static problem
    f2 = f.copy()
    f2.reshape(p, 3)[:, :2] *= -1.0  # step 2: the tangential loads reversed
    o[:, :2] = -u1.reshape(p, 3)[:, :2]
    u2, hist, states = newton_reduced(P, f2, laws, frames, o, u1)
    ratios = [b / a ** 2 for a, b in zip(hist[:-1], hist[1:]) if a > 0]
    n_slide = sum(s == "M1" for s in states)
    ok = hist[-1] <= 1e-14 and len(hist) <= 10 and (len(ratios) < 2 or ratios[-2] <= 10 / hist[0])
    report("quadratic convergence with the offset", ok, "reversal step, %d of %d nodes sliding back: ||z|| %s" % (n_slide, p, ", ".join("%.1e" % h for h in hist)))


# ---------------------------------------------------------------------------------------------------------------------
# 6. the Cattaneo-Mindlin and Mindlin-Deresiewicz closed forms (11.4)-(11.9)
# ---------------------------------------------------------------------------------------------------------------------

def hertz_radius(P, R, E1, nu1, E2=np.inf, nu2=0.0):
    """a = (3 P R/(4 E*))^(1/3), 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (E2 = inf: a rigid body)"""
    inv = (1 - nu1 ** 2) / E1 + (0.0 if np.isinf(E2) else (1 - nu2 ** 2) / E2)
    return (3 * P * R * inv / 4) ** (1 / 3)


def mindlin_compliance(E1, nu1, E2=np.inf, nu2=0.0):
    """K = (2 - nu1)/G1 + (2 - nu2)/G2, G = E/(2 (1 + nu)) (11.5)"""
    G1 = E1 / (2 * (1 + nu1))
    return (2 - nu1) / G1 + (0.0 if np.isinf(E2) else (2 - nu2) / (E2 / (2 * (1 + nu2))))


def mindlin_loading(Q, mu, P, a, K):
    """(11.5): delta on loading from 0 to Q (|Q| <= mu P)"""
    return np.sign(Q) * 3 * mu * P * K / (16 * a) * (1 - (1 - np.abs(Q) / (mu * P)) ** (2 / 3))


def mindlin_unloading(Q, Qstar, mu, P, a, K):
    """(11.6): delta from +Q* down to Q (-Q* <= Q <= Q*)"""
    return 3 * mu * P * K / (16 * a) * (2 * (1 - (Qstar - Q) / (2 * mu * P)) ** (2 / 3) - (1 - Qstar / (mu * P)) ** (2 / 3) - 1)


def mindlin_reloading(Q, Qstar, mu, P, a, K):
    """(11.7): delta from -Q* up to Q"""
    return -mindlin_unloading(-Q, Qstar, mu, P, a, K)


def mindlin_dissipation(Qstar, mu, P, a, K):
    """(11.9): the energy dissipated per cycle +-Q*"""
    s = Qstar / (mu * P)
    return 9 * mu ** 2 * P ** 2 * K / (10 * a) * (1 - (1 - s) ** (5 / 3) - 5 * s / 6 * (1 + (1 - s) ** (2 / 3)))


def mindlin_opening(Qstar, mu, P, a, K):
    """(11.11): the loop's width at Q = 0"""
    s = Qstar / (mu * P)
    return 3 * mu * P * K / (8 * a) * (2 * (1 - s / 2) ** (2 / 3) - (1 - s) ** (2 / 3) - 1)


def stick_radius_loading(Q, mu, P, a):
    """(11.4): c = a (1 - Q/(mu P))^(1/3)"""
    return a * (1 - abs(Q) / (mu * P)) ** (1 / 3)


def stick_radius_unloading(Q, Qstar, mu, P, a):
    """(11.8): nodes at r > b slip back while Q falls from Q* to Q"""
    return a * (1 - (Qstar - Q) / (2 * mu * P)) ** (1 / 3)


# scenes/mindlin.opts as a load path (tests/suite_loadpath.py, bench/loadpath.py)
def mindlin_scene_args(level, s, root, steps_per_branch=10):
    """scenes/mindlin.opts as a path: P (t = 1), then Q: 0 -> -Q* (t = 2) -> Q* (3) -> -Q* (4), Q* = s phi P"""
    q = s * 0.3 * 31416 / 400  # the traction on block_top (20 x 20)
    times = [0, 1] + [1 + k / steps_per_branch for k in range(1, 3 * steps_per_branch + 1)]
    return ["-options_file", root + "/scenes/mindlin.opts", "-level", str(level), "-traction_block_bottom", "0:0,0,0;1:0,0,78.54",
            "-traction_block_top", "0:0,0,0;1:0,0,0;2:-%.10g,0,0;3:%.10g,0,0;4:-%.10g,0,0" % (q, q, q), "-steps", ",".join("%.10g" % t for t in times)]


def mindlin_scene_loop(f):
    """From the file (h5py) of mindlin_scene_args: the closed forms' inputs and the loop's measured figures over the cycle
    t in [2, 4]: W by trapezoids of (Q, delta) (delta: the mean x displacement of block_top, where Q acts), D the
    node-wise dissipation (10.9), the opening at Q = 0; Hertz and (11.9), (11.11) with the contact's normal force"""
    st = f["steps"]
    t, Q, delta, N, D = st["time"][:], -st["load"][:, 0], -st["groups/block_top/displacement"][:, 0], st["normal_force"][:], st["dissipation"][:]
    E, nu, R, mu = 2.1e5, 0.3, 10.0, 0.3
    i2, i25, i35, i4 = (int(np.argmin(abs(t - x))) for x in (2, 2.5, 3.5, 4))
    P, Qs = N[i4], Q[i2]
    a, K = hertz_radius(P, R, E, nu, E, nu), mindlin_compliance(E, nu, E, nu)
    return {"s": Qs / (mu * P), "W": np.trapz(Q[i2:i4 + 1], delta[i2:i4 + 1]), "W_closed": mindlin_dissipation(Qs, mu, P, a, K),
            "D": D[i4] - D[i2], "opening": delta[i25] - delta[i35], "opening_closed": mindlin_opening(Qs, mu, P, a, K),
            "a": a, "P": P, "Qs": Qs}


def check_mindlin():
    mu, P, R, E, nu = 0.3, 31416.0, 10.0, 2.1e5, 0.3
    a = hertz_radius(P, R, E, nu, E, nu)
    K = mindlin_compliance(E, nu, E, nu)
    worst, worst_open, lines = 0.0, 0.0, []
    for s in (0.2, 0.5, 0.8, 1.0):
        Qs = s * mu * P
        Q = np.linspace(-Qs, Qs, 20001)
        width = mindlin_unloading(Q, Qs, mu, P, a, K) - mindlin_reloading(Q, Qs, mu, P, a, K)
        area = np.sum((width[1:] + width[:-1]) / 2 * np.diff(Q))
        closed = mindlin_dissipation(Qs, mu, P, a, K)
        worst = max(worst, abs(area - closed) / closed)
        opening = mindlin_unloading(0.0, Qs, mu, P, a, K) - mindlin_reloading(0.0, Qs, mu, P, a, K)
        worst_open = max(worst_open, abs(opening / mindlin_opening(Qs, mu, P, a, K) - 1))
        lines.append("s = %.1f: %.6g" % (s, closed))
    ends = max(abs(mindlin_unloading(Qs, Qs, mu, P, a, K) - mindlin_loading(Qs, mu, P, a, K)),
               abs(mindlin_unloading(-Qs, Qs, mu, P, a, K) + mindlin_loading(Qs, mu, P, a, K)))
    small = 1e-3 * mu * P  # (11.10): dW ~ K Q*^3/(36 a mu P)
    limit = abs(mindlin_dissipation(small, mu, P, a, K) / (K * small ** 3 / (36 * a * mu * P)) - 1)
    # Cerruti: u_x(0) of q0 sqrt(1 - r^2/a^2) along x on a circle of radius a, one half-space (G, nu)
    G, q0 = E / (2 * (1 + nu)), 1.0
    r = np.linspace(0, a, 200001)
    integrand = q0 * np.sqrt(np.maximum(1 - r ** 2 / a ** 2, 0)) * (2 * np.pi * (1 - nu) + np.pi * nu) / (2 * np.pi * G)
    centre = np.sum((integrand[1:] + integrand[:-1]) / 2 * np.diff(r))
    cerruti = abs(centre / (np.pi * (2 - nu) * q0 * a / (8 * G)) - 1)
    ok = worst <= 1e-6 and ends <= 1e-12 and limit <= 1e-2 and cerruti <= 1e-5 and worst_open <= 1e-12
    report("Mindlin-Deresiewicz closed forms (11.4)-(11.11)", ok,
           "mindlin.opts data (a = %.4g, K = %.4g): loop area by quadrature = (11.9) to %.1e (dW %s); branches meet at +-Q* to %.1e; "
           "opening (11.11) to %.1e; small-amplitude limit (11.10) to %.1e; Cerruti centre displacement to %.1e" % (a, K, worst, ", ".join(lines), ends, worst_open, limit, cerruti))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seed", type=int, default=5)
    parser.add_argument("--write", metavar="FILE", help="write check 1's problem and answers for tests/test_offsets.c (PETSc binary)")
    args = parser.parse_args()
    check_offsets(args.seed, args.write)
    check_block_on_spring()
    check_displacement_sliding()
    check_proportional(args.seed)
    check_quadratic(args.seed)
    check_mindlin()
    sys.exit(0 if all(RESULTS) else 1)


if __name__ == "__main__":
    main()
