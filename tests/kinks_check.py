#!/usr/bin/python3
"""The numerical checks of docs/derivation.md section 19 (the law's degenerate points), in numpy, independent of the C
code (the per-node kernels of tests/loadpath_check.py, sections 1-5 and 10).

  tests/kinks_check.py

The model: the stiff block of issue 34 as P1 tetrahedra (1 x 1 x 0.5, 4 x 4 x 2 cubes of 6 tetrahedra, E = 2e8,
nu = 0.3), held sideways by a spring of k per unit area on its top, its bottom's 25 nodes in contact with the plane
z = 0 (phi = 0.5), reduced to them (P, f of (0.2)); pressed by 1, sheared to 0.8 (it slides until the spring holds
0.3), released, sheared back: in 20 steps the step t = 3.25 lands exactly on the onset of sliding back (the shear -0.2
plus the spring's 0.3 is phi P = 0.5). The iteration is the plain one of section 7 with the offsets of section 10.

Checks (exit status 1 if one fails):
  1. (19.1)-(19.3), the creep: at t = 3.25 the block slides back by delta* = (A/k)^(1/3), A = phi/2 sum_i r_n,i a_i^2
     (a_i the transverse slips of the nodes), to 5 % for k = 10, 40, 160 per unit area (delta* ~ k^(-1/3)); from the
     step before (stuck) the iteration takes at least 5 Newton steps that are parallel (cos >= 0.999) and 3/2 times as
     long as the one before (to 0.1), then converges quadratically; every other step of the path in at most 8
  2. the levers that do not remove it: with gamma 10 and 100 times (6.1)'s the creep stays (>= 5 such steps); along a
     creeping Newton step du the merits ||z||, ||M^-1 (S + T) z|| (the natural level function) and rho (12.3) are all
     larger at u + alpha du for alpha = 2 .. 64 than at alpha = 1, while the error to the solution is smaller at some
     alpha >= 16: no line search on them takes the longer step
  3. (19.4), the floor test of the polishing steps: on the creep the rule "rho not halved and the step not longer
     than the one before" counts at most one (where the steps turn) where "rho not halved" alone counts more than 3
     (LAW_STALLED, issue 34); at
     the round-off floor (steps from the solution) it counts more than 3 within 12 steps
  4. (19c.1)-(19c.2), the two-cycle of a slow mode at touching: the block (k = 20, E/k = 1e7) touching the plane without load,
     the plane raised by 1e-4: with exact steps from the step's start it converges, the rim sliding by a ~ 1e-13; from
     the elastic trial with its slide off by delta = 1e-12 .. 1e-6 (more than a) the plain iteration cycles between
     slides of +-phi N/k (to 1e-3); with the stuck element at twice-reversed slips (||z|| back to within 10 %) it
     converges from every delta, and on check 1's 20-step path (k = 10) it never acts (the same iterations)
"""
import sys

import numpy as np

import loadpath_check as lc
import stopping_check as sc

PHI = 0.5
KNOTS = [(0, (0, 0, 0)), (1, (0, 0, -1)), (2, (0.8, 0, -1)), (3, (0, 0, -1)), (4, (-0.8, 0, -1)), (5, (0, 0, -1))]
RESULTS = []


def report(name, ok, figures):
    RESULTS.append(ok)
    print("%-58s %s (%s)" % (name, "ok" if ok else "FAILED", figures))


def block(E=2e8, nu=0.3, k=10.0, n=4, m=2):
    """P and the reduced load of a unit top traction (a function of it) of the block on its spring; p contact nodes"""
    xs, zs = np.linspace(0, 1, n + 1), np.linspace(0, 0.5, m + 1)
    X = np.array([[x, y, z] for z in zs for y in xs for x in xs])
    vid = lambda i, j, l: i + (n + 1) * (j + (n + 1) * l)  # noqa: E731
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    D[range(6), range(6)] += [2 * mu] * 3 + [mu] * 3
    K = np.zeros((3 * len(X), 3 * len(X)))
    for l in range(m):
        for j in range(n):
            for i in range(n):
                c = [vid(i + a, j + b, l + d) for d in (0, 1) for b in (0, 1) for a in (0, 1)]
                for q in ((1, 3), (3, 2), (2, 6), (6, 4), (4, 5), (5, 1)):  # 6 tetrahedra around the diagonal 0-7
                    t = [c[0], c[q[0]], c[q[1]], c[7]]
                    A = np.c_[np.ones(4), X[t]]
                    G = np.linalg.inv(A)[1:]
                    B = np.zeros((6, 12))
                    for a in range(4):
                        gx, gy, gz = G[:, a]
                        B[:, 3 * a:3 * a + 3] = [[gx, 0, 0], [0, gy, 0], [0, 0, gz], [0, gz, gy], [gz, 0, gx], [gy, gx, 0]]
                    dofs = np.array([[3 * v, 3 * v + 1, 3 * v + 2] for v in t]).ravel()
                    K[np.ix_(dofs, dofs)] += abs(np.linalg.det(A)) / 6 * B.T @ D @ B

    def areas(z):  # the lumped areas of the face z = const
        edge = lambda x: 0.5 if np.isclose(x, 0) or np.isclose(x, 1) else 1.0  # noqa: E731
        return np.array([edge(x[0]) * edge(x[1]) / n ** 2 if np.isclose(x[2], z) else 0.0 for x in X])

    top = areas(0.5)
    for v in np.nonzero(top)[0]:
        K[3 * v:3 * v + 3, 3 * v:3 * v + 3] += k * top[v] * np.eye(3)
    C = np.array([[3 * v, 3 * v + 1, 3 * v + 2] for v in np.nonzero(areas(0.0))[0]]).ravel()
    I = np.setdiff1d(np.arange(3 * len(X)), C)
    KIIinv_KIC = np.linalg.solve(K[np.ix_(I, I)], K[np.ix_(I, C)])
    P = K[np.ix_(C, C)] - K[np.ix_(C, I)] @ KIIinv_KIC

    def f_of(traction):
        b = (top[:, None] * np.asarray(traction, float)[None, :]).ravel()
        return b[C] - KIIinv_KIC.T @ b[I]
    return P, f_of, len(C) // 3


class Step:
    """one step of the path: 0 in P u - f + Q(u + o), o_t = -u_t of the step before (section 10, frames = I)"""

    def __init__(self, P, f, u_before, gamma=None, path=(0.0, 0.0)):
        self.P, self.f, self.p, self.path = P, f, len(f) // 3, path
        self.gamma = 1 / np.mean(np.diag(P)) if gamma is None else gamma
        self.off = np.zeros((self.p, 3))
        self.off[:, :2] = -u_before.reshape(self.p, 3)[:, :2]
        self.u0 = u_before.copy()
        self.r0 = P @ u_before - f

    def work(self, u):
        """v, z, d, b and the states at u"""
        p, g = self.p, self.gamma
        v, z, d, b = lc.node_work([("coulomb", PHI)] * p, np.array([np.eye(3)] * p), self.off, u.reshape(p, 3), (g * (self.P @ u - self.f)).reshape(p, 3), g)
        return v, z, d, b, lc.node_states([("coulomb", PHI)] * p, v, d, b, g, g * np.abs(self.f).max())

    def newton(self, u):
        """the Newton step du at u (5.1), ||z||, and the Newton matrix M and S + T of it"""
        v, z, d, b, states = self.work(u)
        S, T = np.zeros((3 * self.p,) * 2), np.zeros((3 * self.p,) * 2)
        for i in range(self.p):
            k3 = slice(3 * i, 3 * i + 3)
            S[k3, k3], T[k3, k3] = lc.reduced_blocks(("coulomb", PHI), states[i], d[i], b[i])
        M = S @ (self.gamma * self.P) + T
        return np.linalg.solve(M, (S + T) @ z.ravel()), np.linalg.norm(z), M, S + T

    def rho(self, u):
        """the law residual (12.3) of u as the file writes it, with the scales of (12.2) and their floors (the path's
        largest displacement and force so far: path)"""
        w = (u.reshape(self.p, 3) + self.off).ravel()
        r = self.P @ u - self.f
        U = max(np.abs(w).max(), np.abs(u - self.u0).max(), 1e-6 * np.abs(u).max(), 1e-6 * self.path[0])
        F = max(np.abs(r).max(), np.abs(r - self.r0).max(), 2e-7 * (np.abs(self.P).sum(1).max() * np.abs(u).max() + np.abs(self.f).max()), 1e-6 * self.path[1])
        return sc.law_residual(w, r, PHI, U, F)

    def iterate(self, u, its=80, rtol=1e-14, more=0):
        """the plain iteration: its iterates, steps, ||z||; more: steps taken on after ||z|| met rtol (the floor)"""
        us, steps, zs = [u.copy()], [], []
        for _ in range(its):
            du, zn, _, _ = self.newton(u)
            zs.append(zn)
            if zn <= rtol * max(np.linalg.norm(u), self.gamma * np.linalg.norm(self.f)):
                if more == 0:
                    break
                more -= 1
            steps.append(du)
            u = u + du
            us.append(u.copy())
        return us, steps, zs


def path(k=10.0, E=2e8, until=3.25, steps=20):
    """the path's steps up to t = until: the iteration counts, and the Step of the last with its start"""
    P, f_of, p = block(E=E, k=k)
    u, counts, largest = np.zeros(3 * p), [], (0.0, 0.0)
    for t in np.linspace(0, 5, steps + 1):
        if t > until + 1e-12:
            break
        st = Step(P, f_of(lc.piecewise(KNOTS, t)), u, path=largest)
        us, _, _ = st.iterate(u)
        counts.append(len(us) - 1)
        start, u = u, us[-1]
        largest = (max(largest[0], np.abs(u).max()), max(largest[1], np.abs(P @ u - st.f).max()))
    return st, start, u, counts


def creep_run(steps):
    """the longest run of consecutive Newton steps parallel to the one before and 3/2 times as long (to 0.1)"""
    best = run = 0
    for a, b in zip(steps, steps[1:]):
        cos = a @ b / np.linalg.norm(a) / np.linalg.norm(b)
        ratio = np.linalg.norm(b) / np.linalg.norm(a)
        run = run + 1 if cos >= 0.999 and abs(ratio - 1.5) <= 0.1 else 0
        best = max(best, run)
    return best


def slide(st, u):
    """delta* (the mean slide of the nodes in contact, against x) and (A/k)^(1/3) without k: A = phi/2 sum r_n a^2"""
    v = u.reshape(st.p, 3) + st.off
    r = (st.P @ u - st.f).reshape(st.p, 3)
    touching = r[:, 2] > 0
    return -v[touching, 0].mean(), PHI / 2 * np.sum(r[touching, 2] * v[touching, 1] ** 2)


def check_creep():
    figures, ok, deltas = [], True, {}
    for k in (10.0, 40.0, 160.0):
        st, start, u, counts = path(k=k)
        delta, A = slide(st, u)
        deltas[k] = delta
        predicted = (A / k) ** (1 / 3)
        ok &= abs(delta / predicted - 1) <= 0.05
        figures.append("k %g: delta* %.3e, (A/k)^1/3 %.3e" % (k, delta, predicted))
        if k == 10.0:
            kept = st, start
            us, steps, zs = st.iterate(start)
            run = creep_run(steps)
            quadratic = zs[-1] <= 0.1 * zs[-2] and zs[-2] <= 0.2 * zs[-3]
            ok &= run >= 5 and quadratic and max(counts[:-1]) <= 10
            figures.append("from the stuck start %d iterations, %d steps parallel and 3/2 as long, then ||z|| %s; the path's other steps at most %d" % (
                len(us) - 1, run, " ".join("%.0e" % z for z in zs[-4:]), max(counts[:-1])))
    ratio = deltas[10.0] / deltas[160.0]
    ok &= abs(ratio / 16 ** (1 / 3) - 1) <= 0.05
    figures.append("delta*(10)/delta*(160) %.3f against 16^(1/3) = %.3f" % (ratio, 16 ** (1 / 3)))
    report("(19.1)-(19.3): the creep at the onset of sliding back", ok, "; ".join(figures))
    return kept


def check_levers(st, start):
    ok, figures = True, []
    us, steps, _ = st.iterate(start)
    solution = us[-1]
    delta = slide(st, solution)[0]
    for times in (1, 10, 100, 1000):
        other = Step(st.P, st.f, start, gamma=times * st.gamma)
        other.off, other.u0, other.r0 = st.off, st.u0, st.r0
        others, _, _ = other.iterate(start)
        near = next((j for j, x in enumerate(others) if np.abs(x - solution).max() <= 1e-2 * delta), len(others))
        ok &= near >= 12
        figures.append("gamma x %d: %d iterations to 1e-2 of delta*%s" % (times, near, "" if len(others) < 81 else ", never to round-off"))
    errors = lambda j, a: np.abs(us[j] + a * steps[j] - solution).max()  # noqa: E731
    j = next(j for j in range(3, len(steps)) if min(errors(j, a) for a in (16, 32, 64)) < 0.5 * errors(j, 1))
    u, du = us[j], steps[j]
    _, _, M, ST = st.newton(u)
    merits = lambda x: (np.linalg.norm(st.work(x)[1]), st.rho(x), np.linalg.norm(np.linalg.solve(M, ST @ st.work(x)[1].ravel())))  # noqa: E731
    at = {a: merits(u + a * du) for a in (1, 2, 4, 8, 16, 32, 64)}
    grow = all(at[a][0] > at[1][0] and at[a][1] > at[1][1] for a in (2, 4, 8, 16, 32, 64)) and all(at[a][2] > at[1][2] for a in (16, 32, 64))
    best = min((16, 32, 64), key=lambda a: errors(j, a))
    ok &= grow
    figures.append("along the creeping step of iteration %d: ||z||, rho at alpha = 1 %.1e, %.1e, larger at every alpha = 2..64, the natural level "
                   "function %.1e larger at 16..64: %s; the error %.1e at alpha = 1, %.1e at %d" % (j, at[1][0], at[1][1], at[1][2], grow, errors(j, 1), errors(j, best), best))
    report("the levers: gamma, the merit functions", ok, "; ".join(figures))


def stalls(rhos, lengths, growing):
    """SNESSolve_SSStar's polishing rule on a sequence of iterates' rho and the lengths of the steps to them: a stall
    where rho does not halve the best so far, unless (growing) the step is longer than the one before and rho smaller
    than the best"""
    best, count = np.inf, 0
    for j, rho in enumerate(rhos):
        creeping = growing and j >= 1 and lengths[j] > lengths[j - 1] and rho < best
        if rho > 0.5 * best and not creeping:
            count += 1
        best = min(best, rho)
    return count


def check_floor_rule(st, start):
    us, steps, _ = st.iterate(start)
    rhos, lengths = [st.rho(x) for x in us[1:]], [np.linalg.norm(d) for d in steps]
    creep = [j for j in range(1, len(steps)) if lengths[j] > lengths[j - 1] and rhos[j] > 1e-8]
    run = (creep[0] - 1, creep[-1] + 1)
    old, new = stalls(rhos[run[0]:run[1]], lengths[run[0]:run[1]], False), stalls(rhos[run[0]:run[1]], lengths[run[0]:run[1]], True)
    floor_us, floor_steps, _ = st.iterate(us[-1], more=12)
    frhos, flengths = [st.rho(x) for x in floor_us[1:]], [np.linalg.norm(d) for d in floor_steps]
    at_floor = stalls(frhos, flengths, True)
    ok = len(creep) >= 5 and old > 3 and new <= 1 and at_floor > 3
    report("(19.4): the floor test of the polishing steps", ok, "%d creeping iterations (rho %.1e .. %.1e, %.2f per step): %d stalls by 'rho not halved', %d by (19.4); at the "
           "floor (rho %.1e .. %.1e, steps %.0e .. %.0e) %d stalls in 12 steps" % (
               len(creep), max(rhos[run[0]:run[1]]), min(rhos[run[0]:run[1]]), (min(rhos[run[0]:run[1]]) / max(rhos[run[0]:run[1]])) ** (1 / (run[1] - run[0] - 1)),
               old, new, min(frhos), max(frhos), min(flengths), max(flengths), at_floor))


def pressed(k=20.0, press=1e-4):
    """the block (E/k = 1e7) touching the plane with no load, the plane raised by press: the step's Step"""
    P, f_of, p = block(k=k)
    st = Step(P, f_of((0, 0, 0)), np.zeros(3 * p))
    st.off[:, 2] = -press
    return st


def newton_19c(st, u, rule, its=60, rtol=1e-8):
    """section 7's iteration with exact steps (no globalization) to ||z|| <= rtol max(||u||, ||gamma f||) and rho <= 1e-8;
    rule: (19c.2), a sliding node whose slip reversed at two iterates in a row while ||z|| came back to within 10 % of
    its value two iterations ago gets the stuck element at d = 0. Its iterations, whether it converged, the mean slide
    of the nodes along x at each iterate, the nodes stuck"""
    p, slip, twice, zs, slides, stuck = st.p, np.zeros((st.p, 2)), np.zeros(st.p, bool), [], [], 0
    for it in range(its):
        v, z, d, b, states = st.work(u)
        zs.append(np.linalg.norm(z))
        if zs[-1] <= rtol * max(np.linalg.norm(u), st.gamma * np.linalg.norm(st.f)) and st.rho(u) <= 1e-8:
            return it, True, slides, stuck
        cycling = len(zs) >= 3 and zs[-1] > 0.9 * zs[-3]
        for i in range(p):
            reverse = states[i] == "M1" and slip[i] @ d[i, :2] < 0
            if rule and reverse and twice[i] and cycling:
                states[i], z[i], d[i], slip[i], twice[i] = "M3+", -v[i], 0.0, 0.0, False
                stuck += 1
            else:
                slip[i], twice[i] = (d[i, :2] if states[i] == "M1" else 0.0), reverse
        S, T = np.zeros((3 * p,) * 2), np.zeros((3 * p,) * 2)
        for i in range(p):
            k3 = slice(3 * i, 3 * i + 3)
            S[k3, k3], T[k3, k3] = lc.reduced_blocks(("coulomb", PHI), states[i], d[i], b[i])
        u = u + np.linalg.solve(S @ (st.gamma * st.P) + T, (S + T) @ z.ravel())
        slides.append(u.reshape(p, 3)[:, 0].mean())
    return its, False, slides, stuck


def check_reversal():
    st = pressed()
    its, ok, _, _ = newton_19c(st, np.zeros(3 * st.p), False)
    solution = np.zeros(3 * st.p)
    for _ in range(its):
        solution = solution + st.newton(solution)[0]
    _, _, d, b, states = st.work(solution)
    a = np.abs(d[:, :2]).max()  # the elastic slips, the basin's size
    amplitude = PHI * np.sum((st.P @ solution - st.f).reshape(st.p, 3)[:, 2]) / 20.0  # phi N / k (k per unit area, unit top)
    figures = ["exact steps from the step's start: %d iterations, %d of %d nodes sliding by at most a = %.1e" % (its, states.count("M1"), st.p, a)]
    first = st.newton(np.zeros(3 * st.p))[0]  # the elastic trial: every node stuck
    plain, ruled = {}, {}
    for delta in (1e-14, 1e-12, 1e-9, 1e-6):
        u = first.copy()
        u[0::3] += delta  # the first step's error along the slow mode: the block slid by delta
        plain[delta], ruled[delta] = newton_19c(st, u, False), newton_19c(st, u, True)
    cycle = plain[1e-6][2][-4:]
    ok &= plain[1e-14][1] and all(not plain[x][1] for x in (1e-12, 1e-9, 1e-6)) and all(ruled[x][1] for x in ruled)
    ok &= all(abs(abs(x) / amplitude - 1) <= 1e-3 for x in cycle) and cycle[0] * cycle[1] < 0 and ruled[1e-14][0] == plain[1e-14][0]
    figures.append("from the trial with the slide off by delta: plain %s; the cycle's slides %s against phi N/k = %.2e; with (19c.2) %s" % (
        ", ".join("%.0e: %s" % (x, "%d its" % plain[x][0] if plain[x][1] else "no convergence") for x in plain), " ".join("%.2e" % x for x in cycle), amplitude,
        ", ".join("%.0e: %d its (%d nodes stuck)" % (x, ruled[x][0], ruled[x][3]) for x in ruled)))
    P, f_of, p = block(k=10.0)  # the rule on check 1's path (its creep, its slides back and forth): never acts
    u, fired, counts = np.zeros(3 * p), 0, []
    for t in np.linspace(0, 5, 21):
        step = Step(P, f_of(lc.piecewise(KNOTS, t)), u)
        its_plain, _, _, _ = newton_19c(step, u, False)
        its_rule, conv, _, n = newton_19c(step, u, True)
        fired, counts = fired + n, counts + [(its_plain, its_rule)]
        for _ in range(its_rule):
            u = u + step.newton(u)[0]
    ok &= fired == 0 and all(a == b for a, b in counts)
    figures.append("on the 20-step path of check 1 (k = 10): %d nodes stuck, the same iterations at every step (%d in all)" % (fired, sum(b for _, b in counts)))
    report("(19c.1)-(19c.2): the two-cycle of a slow mode", ok, "; ".join(figures))


def main():
    st, start = check_creep()
    check_levers(st, start)
    check_floor_rule(st, start)
    check_reversal()
    sys.exit(0 if all(RESULTS) else 1)


if __name__ == "__main__":
    main()
